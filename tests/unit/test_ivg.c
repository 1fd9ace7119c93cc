/* test_ivg.c — IVG grid creation, memory accounting, bundle decoding in both
 * wire forms against double references, and rejection of every malformed
 * bundle with the grid left byte-for-byte unchanged; runs of records without
 * the header (lumo_ivg_apply_records) against the same records in a bundle. */
#include "test_ivg_util.h"
#include "test_ivg_entry.h"

/* ---- creation and memory ----------------------------------------------- */

static void test_memory_and_create(void **state)
{
    lumo_ivg_desc d = {{5, 4, 3}, {0, 0, 0}, {LUMO_Q16_ONE, LUMO_Q16_ONE, LUMO_Q16_ONE}};
    lumo_ivg_desc bad = d;
    size_t need = lumo_ivg_memory_size(&d), n;
    uint64_t *mem = malloc(need + 64);   /* 8-aligned */
    lumo_arena a;
    lumo_ivg *g = NULL;
    (void)state;
    assert_true(need >= 60u * 6u * LUMO_IVG_QUANT_ENTRY);   /* packed: 42 bytes a vertex */
    assert_int_equal(lumo_ivg_memory_size(NULL), 0);
    bad.dims[1] = 1;
    assert_int_equal(lumo_ivg_memory_size(&bad), 0);
    bad = d; bad.dims[2] = 257;
    assert_int_equal(lumo_ivg_memory_size(&bad), 0);
    bad = d; bad.bmax[0] = bad.bmin[0];
    assert_int_equal(lumo_ivg_memory_size(&bad), 0);
    lumo_arena_init(&a, mem, need + 64);
    assert_int_equal(lumo_ivg_create(&g, &a, &bad), LUMO_ERR_ARG);
    assert_int_equal(a.used, 0);
    /* arena sizes below the need: LUMO_ERR_NOMEM and the arena untouched */
    for (n = 0; n < need; n += 1 + n / 7) {
        lumo_arena_init(&a, mem, n);
        assert_int_equal(lumo_ivg_create(&g, &a, &d), LUMO_ERR_NOMEM);
        assert_int_equal(a.used, 0);
        assert_int_equal(a.peak, 0);
    }
    lumo_arena_init(&a, mem, need - 1);
    assert_int_equal(lumo_ivg_create(&g, &a, &d), LUMO_ERR_NOMEM);
    /* exactly the need is enough, and all of it is used */
    lumo_arena_init(&a, mem, need);
    assert_int_equal(lumo_ivg_create(&g, &a, &d), LUMO_OK);
    assert_int_equal(a.used, need);
    assert_int_equal(lumo_ivg_vertex_count(g), 60);
    assert_int_equal(lumo_ivg_received_count(g), 0);
    assert_memory_equal(lumo_ivg_get_desc(g), &d, sizeof d);
    assert_null(IVG_ENTRY(g, 60, LUMO_IVG_PX));
    assert_null(IVG_ENTRY(g, 0, LUMO_IVG_AXES));
    assert_non_null(IVG_ENTRY(g, 59, LUMO_IVG_NZ));
    assert_int_equal(lumo_ivg_is_received(g, 1000), 0);
    free(mem);
}

static void test_memory_large(void **state)
{
    lumo_ivg_desc d = {{256, 256, 256}, {0, 0, 0}, {1, 1, 1}};
    size_t n = lumo_ivg_memory_size(&d);
    (void)state;
    /* 2^24 vertices x 42 bytes plus the pyramid (< 2/7 more with its bits) */
    assert_true(n > (size_t)704643072u);
    assert_true(n < (size_t)704643072u / 7u * 9u);
}

/* Level 1 kept as two rings of three planes (docs/ivg-format.md §6): a 32^3
 * grid at most 48 bytes a vertex, pyramid included; a grid with level 1 in
 * rings is created in exactly its need, and one byte less fails. */
static void test_memory_rings(void **state)
{
    lumo_ivg_desc d = {{32, 32, 32}, {0, 0, 0}, {LUMO_Q16_ONE, LUMO_Q16_ONE, LUMO_Q16_ONE}};
    lumo_ivg_desc r = {{7, 5, 23}, {0, 0, 0}, {LUMO_Q16_ONE, LUMO_Q16_ONE, LUMO_Q16_ONE}};
    size_t need = lumo_ivg_memory_size(&r);
    uint64_t *mem = malloc(need + 64);
    lumo_arena a;
    lumo_ivg *g = NULL;
    (void)state;
    assert_true(lumo_ivg_memory_size(&d) <= (size_t)48u * 32u * 32u * 32u);
    lumo_arena_init(&a, mem, need - 1);
    assert_int_equal(lumo_ivg_create(&g, &a, &r), LUMO_ERR_NOMEM);
    assert_int_equal(a.used, 0);
    lumo_arena_init(&a, mem, need);
    assert_int_equal(lumo_ivg_create(&g, &a, &r), LUMO_OK);
    assert_int_equal(a.used, need);
    free(mem);
}

/* ---- decoding ------------------------------------------------------------ */

/* Every stored entry against the float the server meant. Quantized: q/127
 * and the RGB9E5 value within the Q1.14 / UQ16.16 rounding (1/2 ulp).
 * Binary32: the grid stores it packed, so within half a step of q/127 and
 * of the shared-exponent mantissa (1/512 of the entry's largest channel). */
static void check_entries(const lumo_ivg *g, uint32_t v, const srv_ivg_fentry *want, lumo_ivg_form form)
{
    int a, k;
    for (a = 0; a < LUMO_IVG_AXES; a++) {
        const lumo_ivg_entry *e = IVG_ENTRY(g, v, (lumo_ivg_axis)a);
        srv_ivg_fentry ref = want[a];
        if (form == LUMO_IVG_FORM_QUANTIZED)
            srv_ivg_dequantize(&want[a], &ref);
        double cmax = fmax(ref.c[0], fmax(ref.c[1], ref.c[2]));
        int packed = form == LUMO_IVG_FORM_FLOAT;
        for (k = 0; k < 3; k++) {
            assert_close(e->d[k] / Q14, (double)ref.d[k], 0.5 / Q14 + (packed ? 0.5 / 127 : 1e-9));
            assert_close(e->c[k] / Q16, (double)ref.c[k], 0.5 / Q16 + (packed ? cmax / 512 : 1e-9));
        }
        assert_int_equal(e->reserved, 0);
    }
}

static void decode_random(lumo_ivg_form form)
{
    test_rng r = {0xC0FFEEu + form};
    tgrid t;
    lumo_ivg *g = tgrid_make(&t, 7, 5, 6, 4);
    uint32_t count = lumo_ivg_vertex_count(g), *verts = malloc(count * sizeof *verts), n, i, v;
    srv_ivg_fentry (*f)[LUMO_IVG_AXES] = random_field(&r, count, 300.0);

    /* a wide range of magnitudes, including the RGB9E5 extremes */
    f[0][0].c[0] = 65408.0f; f[0][0].c[1] = 1e-7f; f[0][0].c[2] = 0;
    f[0][1].c[0] = 65000.0f; f[0][1].c[1] = 40000.25f; f[0][1].c[2] = 3e-3f;
    f[1][0].d[0] = f[1][0].d[1] = f[1][0].d[2] = 0;   /* zero direction */
    n = random_subset(&r, count, 40, verts);
    verts[0] = 0;
    verts[1] = 1;
    send(g, form, verts, n, f);
    assert_int_equal(lumo_ivg_received_count(g), n);
    for (i = 0, v = 0; v < count; v++) {
        int got = lumo_ivg_is_received(g, v);
        if (i < n && verts[i] == v) {
            assert_true(got);
            check_entries(g, v, f[v], form);
            i++;
        } else {
            assert_false(got);
            assert_int_equal(IVG_ENTRY(g, v, LUMO_IVG_PY)->c[1], 0);
        }
    }
    free(verts);
    free(f);
    tgrid_free(&t);
}

static void test_decode_quantized(void **state) { (void)state; decode_random(LUMO_IVG_FORM_QUANTIZED); }
static void test_decode_float(void **state) { (void)state; decode_random(LUMO_IVG_FORM_FLOAT); }

/* Exact known values: q/127 in Q1.14 and RGB9E5 words. */
static void test_decode_known_values(void **state)
{
    tgrid t;
    lumo_ivg *g = tgrid_make(&t, 2, 2, 2, 1);
    uint8_t b[LUMO_IVG_BUNDLE_HEADER + LUMO_IVG_QUANT_RECORD] = {
        0x49, 0x56, 0x47, 0x42, 1, 1, 2, 0, 2, 0, 2, 0, 1, 0, 0, 0, 7, 0, 0, 0};
    const lumo_ivg_entry *e;
    int a;
    (void)state;
    for (a = 0; a < 6; a++) {
        uint8_t *p = b + 20 + 7 * a;
        /* d = (127, 0, 0)/127 except axis 1: (-90, 90, 0)/127 */
        p[0] = a == 1 ? (uint8_t)(256 - 90) : 127;
        p[1] = a == 1 ? 90 : 0;
        p[2] = 0;
        /* c: R = 1.0 (m 256, E 16), G = 0.5, B = 2^-9 (m 1, E 6) */
        p[3] = 0x00; p[4] = 0x03; p[5] = 0x02; p[6] = 0x80;
    }
    /* R=256 at bits 0-8, G=128 at 9-17, B=0, E=16 -> 0x80000000 | 128<<9 | 256 */
    b[20 + 3] = 0x00; b[20 + 4] = 0x01 | (128 << 1 & 0xFF); b[20 + 5] = 128 >> 7; b[20 + 6] = 0x80;
    assert_int_equal(lumo_ivg_apply_bundle(g, b, sizeof b, NULL), LUMO_OK);
    e = IVG_ENTRY(g, 7, LUMO_IVG_PX);
    assert_int_equal(e->d[0], LUMO_Q14_ONE);
    assert_int_equal(e->c[0], LUMO_Q16_ONE);
    assert_int_equal(e->c[1], LUMO_Q16_HALF);
    assert_int_equal(e->c[2], 0);
    e = IVG_ENTRY(g, 7, LUMO_IVG_NX);
    assert_int_equal(e->d[0], -11611);   /* round(90 * 16384 / 127) = 11610.7 */
    assert_int_equal(e->d[1], 11611);
    tgrid_free(&t);
}

/* ---- solid vertices and updates ------------------------------------------ */

static void test_solid_and_update(void **state)
{
    test_rng r = {77};
    tgrid t;
    lumo_ivg *g = tgrid_make(&t, 3, 3, 3, 2);
    srv_ivg_fentry (*f)[LUMO_IVG_AXES] = random_field(&r, 27, 10.0);
    srv_ivg_fentry (*f2)[LUMO_IVG_AXES] = random_field(&r, 27, 10.0);
    uint8_t buf[512];
    srv_ivg_writer w;
    uint32_t verts[3] = {4, 5, 6};
    size_t len;
    (void)state;
    send(g, LUMO_IVG_FORM_QUANTIZED, verts, 3, f);
    /* vertex 5 becomes solid, 9 is solid from the start */
    srv_ivg_writer_begin(&w, buf, sizeof buf, LUMO_IVG_FORM_QUANTIZED, t.desc.dims);
    srv_ivg_writer_add_solid(&w, 5);
    srv_ivg_writer_add_solid(&w, 9);
    srv_ivg_writer_add(&w, 4, f2[4]);           /* a lighting update */
    len = srv_ivg_writer_finish(&w);
    assert_int_equal(len, 16 + 4 + 4 + LUMO_IVG_QUANT_RECORD);
    assert_int_equal(lumo_ivg_apply_bundle(g, buf, len, NULL), LUMO_OK);
    assert_int_equal(lumo_ivg_received_count(g), 2);
    assert_int_equal(lumo_ivg_solid_count(g), 2);
    assert_true(lumo_ivg_is_solid(g, 5));
    assert_false(lumo_ivg_is_received(g, 5));
    assert_true(lumo_ivg_is_solid(g, 9));
    assert_int_equal(IVG_ENTRY(g, 5, LUMO_IVG_PX)->c[0], 0);
    check_entries(g, 4, f2[4], LUMO_IVG_FORM_QUANTIZED);
    check_entries(g, 6, f[6], LUMO_IVG_FORM_QUANTIZED);
    /* push-pull fills solid vertices like holes */
    assert_int_equal(lumo_ivg_pushpull(g, 0), LUMO_OK);
    assert_true(IVG_ENTRY(g, 5, LUMO_IVG_PX)->c[0] != 0
                || IVG_ENTRY(g, 5, LUMO_IVG_PX)->c[1] != 0);
    /* data again: no longer solid */
    send(g, LUMO_IVG_FORM_FLOAT, verts + 1, 1, f);
    assert_false(lumo_ivg_is_solid(g, 5));
    assert_true(lumo_ivg_is_received(g, 5));
    assert_int_equal(lumo_ivg_solid_count(g), 1);
    assert_int_equal(lumo_ivg_received_count(g), 3);
    free(f);
    free(f2);
    tgrid_free(&t);
}

/* ---- rejection ----------------------------------------------------------- */

typedef struct reject_fixture {
    tgrid            t;
    lumo_ivg        *g;
    uint8_t         *before;
    srv_ivg_fentry (*f)[LUMO_IVG_AXES];
} reject_fixture;

/* A grid with some data already (so "unchanged" is not just "all zero"). */
static void fixture_init(reject_fixture *x)
{
    test_rng r = {2024};
    uint32_t verts[4] = {0, 10, 33, 59};
    x->g = tgrid_make(&x->t, 5, 4, 3, 1);
    x->f = random_field(&r, 60, 50.0);
    send(x->g, LUMO_IVG_FORM_QUANTIZED, verts, 4, x->f);
    x->before = malloc(x->t.size);
    memcpy(x->before, x->t.mem, x->t.size);
}

static void fixture_free(reject_fixture *x)
{
    free(x->before);
    free(x->f);
    tgrid_free(&x->t);
}

/* The bundle must fail with `want` and leave every arena byte as it was. */
static void expect_reject(reject_fixture *x, const uint8_t *b, size_t len, lumo_status want, const char *what)
{
    uint32_t applied = 12345;
    lumo_status st = lumo_ivg_apply_bundle(x->g, b, len, &applied);
    if (st != want)
        fail_msg("%s: got %s, want %s", what, lumo_strerror(st), lumo_strerror(want));
    assert_int_equal(applied, 12345);
    assert_memory_equal(x->t.mem, x->before, x->t.size);
}

static uint8_t *bundle_of(reject_fixture *x, lumo_ivg_form form, const uint32_t *v, uint32_t n, size_t *len)
{
    return make_bundle(&x->t.desc, form, v, n, x->f, len);
}

static void put32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)v; p[1] = (uint8_t)(v >> 8); p[2] = (uint8_t)(v >> 16); p[3] = (uint8_t)(v >> 24);
}

static void put_f32(uint8_t *p, float f) { put32(p, test_f32_bits(f)); }

static void test_reject_header(void **state)
{
    reject_fixture x;
    uint32_t v[3] = {1, 2, 3};
    size_t len, i;
    uint8_t *b, *c;
    (void)state;
    fixture_init(&x);
    b = bundle_of(&x, LUMO_IVG_FORM_QUANTIZED, v, 3, &len);
    c = malloc(len + 8);
    for (i = 0; i < len; i++)           /* every truncation of a good bundle */
        expect_reject(&x, b, i, i < 16 ? LUMO_ERR_TRUNCATED : LUMO_ERR_TRUNCATED, "truncated");
    memcpy(c, b, len); c[0] = 'X';
    expect_reject(&x, c, len, LUMO_ERR_CORRUPT, "magic");
    memcpy(c, b, len); c[4] = 2;
    expect_reject(&x, c, len, LUMO_ERR_VERSION, "version");
    memcpy(c, b, len); c[5] = 2;
    expect_reject(&x, c, len, LUMO_ERR_UNSUPPORTED, "form");
    memcpy(c, b, len); c[6] = 6;
    expect_reject(&x, c, len, LUMO_ERR_RANGE, "dims x");
    memcpy(c, b, len); c[11] = 1;
    expect_reject(&x, c, len, LUMO_ERR_RANGE, "dims z");
    memcpy(c, b, len); put32(c + 12, 61);
    expect_reject(&x, c, len, LUMO_ERR_CORRUPT, "more records than vertices");
    memcpy(c, b, len); put32(c + 12, 0xFFFFFFFFu);
    expect_reject(&x, c, len, LUMO_ERR_CORRUPT, "huge count");
    memcpy(c, b, len); put32(c + 12, 4);
    expect_reject(&x, c, len, LUMO_ERR_TRUNCATED, "count one too many");
    memcpy(c, b, len); put32(c + 12, 2);
    expect_reject(&x, c, len, LUMO_ERR_CORRUPT, "count one too few (trailing record)");
    memcpy(c, b, len); c[len] = 0;
    expect_reject(&x, c, len + 1, LUMO_ERR_CORRUPT, "trailing byte");
    /* the float form's form byte on quantized records */
    memcpy(c, b, len); c[5] = 0;
    expect_reject(&x, c, len, LUMO_ERR_TRUNCATED, "form swapped");
    assert_int_equal(lumo_ivg_apply_bundle(x.g, NULL, 0, NULL), LUMO_ERR_TRUNCATED);
    assert_int_equal(lumo_ivg_apply_bundle(x.g, NULL, 5, NULL), LUMO_ERR_ARG);
    assert_int_equal(lumo_ivg_apply_bundle(NULL, b, len, NULL), LUMO_ERR_ARG);
    free(b);
    free(c);
    fixture_free(&x);
}

static void test_reject_records(void **state)
{
    reject_fixture x;
    uint32_t v[3] = {1, 2, 3}, dup[3] = {7, 8, 7};
    size_t len, qrec = LUMO_IVG_QUANT_RECORD;
    uint8_t *b, *c;
    (void)state;
    fixture_init(&x);
    b = bundle_of(&x, LUMO_IVG_FORM_QUANTIZED, v, 3, &len);
    c = malloc(len);
    memcpy(c, b, len); put32(c + 16 + 2 * qrec, 60);
    expect_reject(&x, c, len, LUMO_ERR_RANGE, "index = vertex count (last record)");
    memcpy(c, b, len); put32(c + 16 + qrec, 0x01000002u);
    expect_reject(&x, c, len, LUMO_ERR_RANGE, "index high bits");
    memcpy(c, b, len); put32(c + 16, 0x7FFFFFFFu);
    expect_reject(&x, c, len, LUMO_ERR_RANGE, "index 2^31-1");
    memcpy(c, b, len); c[16 + 2 * qrec + 4 + 5 * 7 + 1] = 0x80;
    expect_reject(&x, c, len, LUMO_ERR_CORRUPT, "q = -128 in the last entry");
    memcpy(c, b, len); c[16 + 4] = 40; c[16 + 5] = 40; c[16 + 6] = 40;
    expect_reject(&x, c, len, LUMO_ERR_RANGE, "|d| = 0.55");
    memcpy(c, b, len); c[16 + 4] = 127; c[16 + 5] = 127; c[16 + 6] = 0;
    expect_reject(&x, c, len, LUMO_ERR_RANGE, "|d| = 1.41");
    memcpy(c, b, len); c[16 + 4] = 1; c[16 + 5] = 0; c[16 + 6] = 0;
    expect_reject(&x, c, len, LUMO_ERR_RANGE, "|d| = 1/127");
    /* a solid flag where data follow: the record then ends early and the
     * next "index" is entry bytes */
    memcpy(c, b, len); put32(c + 16 + 2 * qrec, 3u | LUMO_IVG_SOLID_BIT);
    expect_reject(&x, c, len, LUMO_ERR_CORRUPT, "solid with data (trailing)");
    free(b);
    b = bundle_of(&x, LUMO_IVG_FORM_QUANTIZED, dup, 3, &len);
    expect_reject(&x, b, len, LUMO_ERR_CORRUPT, "duplicate vertex");
    free(b);
    free(c);
    /* after all those failures the seen-marks are clear: the vertices of
     * the rejected bundles are accepted now */
    b = bundle_of(&x, LUMO_IVG_FORM_QUANTIZED, v, 3, &len);
    assert_int_equal(lumo_ivg_apply_bundle(x.g, b, len, NULL), LUMO_OK);
    free(b);
    b = bundle_of(&x, LUMO_IVG_FORM_QUANTIZED, dup, 2, &len);
    assert_int_equal(lumo_ivg_apply_bundle(x.g, b, len, NULL), LUMO_OK);
    free(b);
    fixture_free(&x);
}

/* One float in the last entry of the last record replaced by `value`. */
static void float_case(reject_fixture *x, const uint8_t *b, size_t len, int component, float value,
                       lumo_status want, const char *what)
{
    uint8_t *c = malloc(len);
    memcpy(c, b, len);
    put_f32(c + len - LUMO_IVG_FLOAT_ENTRY + 4 * component, value);
    if (want == LUMO_OK) {
        assert_int_equal(lumo_ivg_apply_bundle(x->g, c, len, NULL), LUMO_OK);
        memcpy(x->before, x->t.mem, x->t.size);
    } else {
        expect_reject(x, c, len, want, what);
    }
    free(c);
}

static void test_reject_float(void **state)
{
    reject_fixture x;
    uint32_t v[2] = {11, 12};
    size_t len;
    uint8_t *b, *c;
    (void)state;
    fixture_init(&x);
    b = bundle_of(&x, LUMO_IVG_FORM_FLOAT, v, 2, &len);
    float_case(&x, b, len, 0, NAN, LUMO_ERR_NONFINITE, "NaN in d");
    float_case(&x, b, len, 4, INFINITY, LUMO_ERR_NONFINITE, "inf in c");
    float_case(&x, b, len, 5, -INFINITY, LUMO_ERR_NONFINITE, "-inf in c");
    float_case(&x, b, len, 3, -1.0f, LUMO_ERR_RANGE, "negative colour");
    float_case(&x, b, len, 3, -1e-30f, LUMO_ERR_RANGE, "tiny negative colour");
    float_case(&x, b, len, 4, 65536.0f, LUMO_ERR_RANGE, "colour 65536");
    float_case(&x, b, len, 4, 65535.5f, LUMO_ERR_RANGE, "colour 65535.5");
    float_case(&x, b, len, 1, 1e10f, LUMO_ERR_RANGE, "huge d");
    float_case(&x, b, len, 2, 3.0f, LUMO_ERR_RANGE, "long d");
    /* fits int32 as Q1.14 but its square times 256 would not (fuzz find) */
    float_case(&x, b, len, 0, 100000.0f, LUMO_ERR_RANGE, "d = 1e5");
    float_case(&x, b, len, 1, -131071.0f, LUMO_ERR_RANGE, "d = -131071");
    /* accepted edge values */
    float_case(&x, b, len, 3, -0.0f, LUMO_OK, "-0 colour");
    float_case(&x, b, len, 4, 65535.0f, LUMO_OK, "colour 65535");
    assert_int_equal(IVG_ENTRY(x.g, 12, LUMO_IVG_NZ)->c[1], 65408u << 16);   /* packed: RGB9E5's largest */
    float_case(&x, b, len, 5, 40000.00390625f, LUMO_OK, "colour above 2^15 with 8 fraction bits");
    assert_int_equal(IVG_ENTRY(x.g, 12, LUMO_IVG_NZ)->c[2], 40064u << 16);   /* to 128 W/m^2 steps */
    c = malloc(len);
    memcpy(c, b, len);   /* zero direction */
    put_f32(c + len - 24, 0.0f); put_f32(c + len - 20, -0.0f); put_f32(c + len - 16, 0.0f);
    assert_int_equal(lumo_ivg_apply_bundle(x.g, c, len, NULL), LUMO_OK);
    free(c);
    free(b);
    fixture_free(&x);
}

/* Flipping any single byte of a valid bundle either applies or fails
 * cleanly; failures leave the grid unchanged. */
static void test_byte_flips(void **state)
{
    test_rng r = {31337};
    reject_fixture x;
    uint32_t v[3] = {5, 6, 40};
    size_t len, i;
    int form;
    (void)state;
    fixture_init(&x);
    for (form = 0; form < 2; form++) {
        uint8_t *b = bundle_of(&x, (lumo_ivg_form)form, v, 3, &len);
        for (i = 0; i < len; i++) {
            uint8_t keep = b[i];
            lumo_status st;
            b[i] = (uint8_t)(b[i] ^ (1u << (test_rng_next(&r) % 8)));
            st = lumo_ivg_apply_bundle(x.g, b, len, NULL);
            if (st == LUMO_OK)
                memcpy(x.before, x.t.mem, x.t.size);
            else
                assert_memory_equal(x.t.mem, x.before, x.t.size);
            b[i] = keep;
        }
        free(b);
    }
    fixture_free(&x);
}

/* ---- runs of records without the header ----------------------------------- */

/* Same received/solid state and the same stored entries, vertex by vertex. */
static void assert_grids_equal(const lumo_ivg *a, const lumo_ivg *b)
{
    uint32_t v;
    int h;
    assert_int_equal(lumo_ivg_received_count(a), lumo_ivg_received_count(b));
    assert_int_equal(lumo_ivg_solid_count(a), lumo_ivg_solid_count(b));
    for (v = 0; v < lumo_ivg_vertex_count(a); v++) {
        assert_int_equal(lumo_ivg_is_received(a, v), lumo_ivg_is_received(b, v));
        assert_int_equal(lumo_ivg_is_solid(a, v), lumo_ivg_is_solid(b, v));
        for (h = 0; h < LUMO_IVG_AXES; h++)
            assert_memory_equal(IVG_ENTRY(a, v, (lumo_ivg_axis)h), IVG_ENTRY(b, v, (lumo_ivg_axis)h),
                                sizeof(lumo_ivg_entry));
    }
}

/* Byte length of the record at p (the run is valid). */
static size_t record_bytes(const uint8_t *p, lumo_ivg_form form)
{
    uint32_t word = (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
    if (word & LUMO_IVG_SOLID_BIT)
        return 4;
    return form == LUMO_IVG_FORM_FLOAT ? LUMO_IVG_FLOAT_RECORD : LUMO_IVG_QUANT_RECORD;
}

/* A bundle with data and solid records, applied whole to one grid and as
 * runs of 1, 2, 3, ... records (cut at record boundaries) to another: the
 * grids agree, in both forms. */
static void test_apply_records_equals_bundle(void **state)
{
    test_rng r = {4242};
    int form;
    (void)state;
    for (form = 0; form < 2; form++) {
        tgrid ta, tb;
        lumo_ivg *ga = tgrid_make(&ta, 6, 5, 4, 3), *gb = tgrid_make(&tb, 6, 5, 4, 3);
        uint32_t count = lumo_ivg_vertex_count(ga), *verts = malloc(count * sizeof *verts), n, i, applied;
        srv_ivg_fentry (*f)[LUMO_IVG_AXES] = random_field(&r, count, 200.0);
        size_t cap, len, at, run_len;
        uint8_t *buf;
        srv_ivg_writer w;
        n = random_subset(&r, count, 60, verts);
        cap = srv_ivg_bundle_bytes((lumo_ivg_form)form, n, 0);
        buf = malloc(cap);
        assert_int_equal(srv_ivg_writer_begin(&w, buf, cap, (lumo_ivg_form)form, ta.desc.dims), LUMO_OK);
        for (i = 0; i < n; i++)   /* every third vertex solid */
            assert_int_equal(i % 3 == 1 ? srv_ivg_writer_add_solid(&w, verts[i]) : srv_ivg_writer_add(&w, verts[i], f[verts[i]]),
                             LUMO_OK);
        len = srv_ivg_writer_finish(&w);
        assert_int_equal(lumo_ivg_apply_bundle(ga, buf, len, &applied), LUMO_OK);
        assert_int_equal(applied, n);
        /* the whole run at once */
        assert_int_equal(lumo_ivg_apply_records(gb, (lumo_ivg_form)form, n, buf + 16, len - 16, &applied), LUMO_OK);
        assert_int_equal(applied, n);
        assert_grids_equal(ga, gb);
        tgrid_free(&tb);
        gb = tgrid_make(&tb, 6, 5, 4, 3);
        /* runs of growing length */
        for (at = 16, i = 0; i < n;) {
            uint32_t k = 0, want = 1 + i % 4;
            run_len = 0;
            while (k < want && i + k < n) {
                run_len += record_bytes(buf + at + run_len, (lumo_ivg_form)form);
                k++;
            }
            assert_int_equal(lumo_ivg_apply_records(gb, (lumo_ivg_form)form, k, buf + at, run_len, &applied), LUMO_OK);
            assert_int_equal(applied, k);
            at += run_len;
            i += k;
        }
        assert_int_equal(at, len);
        assert_grids_equal(ga, gb);
        /* an empty run changes nothing */
        assert_int_equal(lumo_ivg_apply_records(gb, (lumo_ivg_form)form, 0, NULL, 0, &applied), LUMO_OK);
        assert_int_equal(applied, 0);
        assert_grids_equal(ga, gb);
        free(buf);
        free(verts);
        free(f);
        tgrid_free(&ta);
        tgrid_free(&tb);
    }
}

/* The run must fail with `want` and leave every arena byte as it was. */
static void expect_reject_run(reject_fixture *x, lumo_ivg_form form, uint32_t count, const uint8_t *p, size_t len,
                              lumo_status want, const char *what)
{
    uint32_t applied = 12345;
    lumo_status st = lumo_ivg_apply_records(x->g, form, count, p, len, &applied);
    if (st != want)
        fail_msg("%s: got %s, want %s", what, lumo_strerror(st), lumo_strerror(want));
    assert_int_equal(applied, 12345);
    assert_memory_equal(x->t.mem, x->before, x->t.size);
}

static void test_apply_records_reject(void **state)
{
    reject_fixture x;
    uint32_t v[3] = {1, 2, 3}, dup[3] = {7, 8, 7};
    size_t len, i;
    uint8_t *b, *c;
    const uint8_t *rec;
    (void)state;
    fixture_init(&x);
    b = bundle_of(&x, LUMO_IVG_FORM_QUANTIZED, v, 3, &len);
    rec = b + 16;
    len -= 16;
    for (i = 0; i < len; i++)           /* every truncation */
        expect_reject_run(&x, LUMO_IVG_FORM_QUANTIZED, 3, rec, i, LUMO_ERR_TRUNCATED, "truncated run");
    expect_reject_run(&x, (lumo_ivg_form)2, 3, rec, len, LUMO_ERR_UNSUPPORTED, "form 2");
    expect_reject_run(&x, (lumo_ivg_form)255, 3, rec, len, LUMO_ERR_UNSUPPORTED, "form 255");
    expect_reject_run(&x, LUMO_IVG_FORM_QUANTIZED, 61, rec, len, LUMO_ERR_CORRUPT, "more records than vertices");
    expect_reject_run(&x, LUMO_IVG_FORM_QUANTIZED, 0xFFFFFFFFu, rec, len, LUMO_ERR_CORRUPT, "huge count");
    expect_reject_run(&x, LUMO_IVG_FORM_QUANTIZED, 4, rec, len, LUMO_ERR_TRUNCATED, "count one too many");
    expect_reject_run(&x, LUMO_IVG_FORM_QUANTIZED, 2, rec, len, LUMO_ERR_CORRUPT, "count one too few");
    expect_reject_run(&x, LUMO_IVG_FORM_QUANTIZED, 0, rec, len, LUMO_ERR_CORRUPT, "count 0 with bytes");
    expect_reject_run(&x, LUMO_IVG_FORM_FLOAT, 3, rec, len, LUMO_ERR_TRUNCATED, "quantized records as float");
    c = malloc(len);
    memcpy(c, rec, len); put32(c + 2 * LUMO_IVG_QUANT_RECORD, 60);
    expect_reject_run(&x, LUMO_IVG_FORM_QUANTIZED, 3, c, len, LUMO_ERR_RANGE, "index = vertex count");
    memcpy(c, rec, len); c[4 + 5 * 7 + 1] = 0x80;
    expect_reject_run(&x, LUMO_IVG_FORM_QUANTIZED, 3, c, len, LUMO_ERR_CORRUPT, "q = -128");
    free(c);
    free(b);
    b = bundle_of(&x, LUMO_IVG_FORM_QUANTIZED, dup, 3, &len);
    expect_reject_run(&x, LUMO_IVG_FORM_QUANTIZED, 3, b + 16, len - 16, LUMO_ERR_CORRUPT, "duplicate vertex");
    assert_int_equal(lumo_ivg_apply_records(x.g, LUMO_IVG_FORM_QUANTIZED, 1, NULL, 4, NULL), LUMO_ERR_ARG);
    assert_int_equal(lumo_ivg_apply_records(NULL, LUMO_IVG_FORM_QUANTIZED, 3, b + 16, len - 16, NULL), LUMO_ERR_ARG);
    assert_int_equal(lumo_ivg_apply_records(x.g, LUMO_IVG_FORM_QUANTIZED, 1, NULL, 0, NULL), LUMO_ERR_TRUNCATED);
    /* the same vertex in two runs is an update, not a duplicate */
    assert_int_equal(lumo_ivg_apply_records(x.g, LUMO_IVG_FORM_QUANTIZED, 2, b + 16, 2 * LUMO_IVG_QUANT_RECORD, NULL),
                     LUMO_OK);
    assert_int_equal(lumo_ivg_apply_records(x.g, LUMO_IVG_FORM_QUANTIZED, 1, b + 16 + 2 * LUMO_IVG_QUANT_RECORD,
                                            LUMO_IVG_QUANT_RECORD, NULL), LUMO_OK);
    free(b);
    fixture_free(&x);
}

/* ---- the server's encoder ------------------------------------------------- */

static void test_encoder(void **state)
{
    test_rng r = {555};
    int i, a, k;
    (void)state;
    for (i = 0; i < 20000; i++) {
        float I[3][3];
        srv_ivg_fentry e;
        a = (int)(test_rng_next(&r) % 6);
        /* irradiance vectors of a hemisphere point into it */
        for (k = 0; k < 9; k++)
            I[k / 3][k % 3] = (float)test_rng_uniform(&r, -5, 5);
        for (k = 0; k < 3; k++)
            I[k][a / 2] = (float)(fabs(I[k][a / 2]) + 0.1) * (a & 1 ? -1.0f : 1.0f);
        srv_ivg_compress((const float (*)[3])I, (lumo_ivg_axis)a, &e);
        /* M delta = c (d . delta) per channel (§3.3) */
        for (k = 0; k < 3; k++) {
            double md = I[k][a / 2] * (a & 1 ? -1.0 : 1.0);
            double dd = e.d[a / 2] * (a & 1 ? -1.0 : 1.0);
            assert_close(e.c[k] * dd, md, 1e-5 * (1 + fabs(md)));
        }
        assert_close(sqrt(e.d[0] * e.d[0] + e.d[1] * e.d[1] + e.d[2] * e.d[2]), 1.0, 1e-6);
    }
    /* RGB9E5: pack/unpack within half a step of the shared exponent */
    for (i = 0; i < 100000; i++) {
        float c[3], u[3];
        uint32_t p;
        double mx = 0, step;
        for (k = 0; k < 3; k++) {
            c[k] = (float)ldexp(test_rng_uniform(&r, 0, 1), (int)(test_rng_next(&r) % 40) - 24);
            if (c[k] > mx) mx = c[k];
        }
        if (mx > 65408) continue;
        p = srv_ivg_rgb9e5_pack(c);
        srv_ivg_rgb9e5_unpack(p, u);
        step = ldexp(1.0, (int)(p >> 27) - 24);
        for (k = 0; k < 3; k++)
            assert_close(u[k], c[k], step * 0.5 + 1e-30);
    }
    {
        float one[3] = {1.0f, 0.5f, 0.0f}, big[3] = {1e9f, -3.0f, NAN};
        uint32_t p = srv_ivg_rgb9e5_pack(one);
        assert_int_equal(p, (16u << 27) | (128u << 9) | 256u);
        p = srv_ivg_rgb9e5_pack(big);
        assert_int_equal(p, 0xF80001FFu);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_memory_and_create),
        cmocka_unit_test(test_memory_large),
        cmocka_unit_test(test_memory_rings),
        cmocka_unit_test(test_decode_quantized),
        cmocka_unit_test(test_decode_float),
        cmocka_unit_test(test_decode_known_values),
        cmocka_unit_test(test_solid_and_update),
        cmocka_unit_test(test_reject_header),
        cmocka_unit_test(test_reject_records),
        cmocka_unit_test(test_reject_float),
        cmocka_unit_test(test_byte_flips),
        cmocka_unit_test(test_encoder),
        cmocka_unit_test(test_apply_records_equals_bundle),
        cmocka_unit_test(test_apply_records_reject),
    };
    return cmocka_run_group_tests_name("ivg", tests, NULL, NULL);
}
