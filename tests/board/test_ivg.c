/*
 * test_ivg.c — the IVG client core on the board (seed 000 §3-4.1): memory
 * sizing, bundle decoding in both wire forms with exact known answers,
 * every rejection leaving the grid unchanged, push-pull on constant and
 * linear fields, and sampling with answers known in closed form.
 */
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include "lumo/ivg.h"
#include "board.h"
#include "harness.h"
#include "ivg_wire.h"

static uint8_t g_mem[1u << 20];
static uint8_t g_buf[WIRE_HEADER + 64u * WIRE_FLOAT_RECORD];

/* A 5 x 4 x 3 grid over [0, 4] x [0, 3] x [0, 2]: one unit per cell. */
static const lumo_ivg_desc k_desc = {
    {5, 4, 3}, {0, 0, 0}, {4 * LUMO_Q16_ONE, 3 * LUMO_Q16_ONE, 2 * LUMO_Q16_ONE}
};

static lumo_ivg *make_grid(lumo_arena *a, const lumo_ivg_desc *d)
{
    lumo_ivg *g = NULL;

    lumo_arena_init(a, g_mem, sizeof g_mem);
    if (lumo_ivg_create(&g, a, d) != LUMO_OK)
        return NULL;
    return g;
}

/* Entry of axis a with d = +-delta_a (q = 127) and colour mantissa m,
 * exponent 15: c = m * 2^-9 W/m^2 = m * 128 in UQ16.16. */
static void axis_entries(wire_qentry e[6], uint16_t m)
{
    int a, k;

    memset(e, 0, 6 * sizeof e[0]);
    for (a = 0; a < 6; a++) {
        e[a].d[a / 2] = (int8_t)(a % 2 ? -127 : 127);
        for (k = 0; k < 3; k++)
            e[a].m[k] = (uint16_t)(m + (unsigned)k);
        e[a].e = 15;
    }
}

static void test_memory_size(void)
{
    lumo_ivg_desc bad = k_desc;
    lumo_arena a;
    lumo_ivg *g = NULL;
    size_t need = lumo_ivg_memory_size(&k_desc);

    BT_CHECK(need > 60u * 6u * LUMO_IVG_QUANT_ENTRY);   /* packed: 42 bytes a vertex */
    bad.dims[1] = 1;
    BT_EQ(lumo_ivg_memory_size(&bad), 0);
    bad = k_desc;
    bad.dims[2] = LUMO_IVG_MAX_DIM + 1;
    BT_EQ(lumo_ivg_memory_size(&bad), 0);
    bad = k_desc;
    bad.bmax[0] = bad.bmin[0];
    BT_EQ(lumo_ivg_memory_size(&bad), 0);
    /* exactly `need` bytes suffice, one less fails with the arena unchanged */
    lumo_arena_init(&a, g_mem, need + LUMO_ARENA_SLACK);
    BT_EQ(lumo_ivg_create(&g, &a, &k_desc), LUMO_OK);
    lumo_arena_init(&a, g_mem, need - 1);
    BT_EQ(lumo_ivg_create(&g, &a, &k_desc), LUMO_ERR_NOMEM);
    BT_EQ(a.used, 0);
}

static size_t two_records(uint8_t *p, uint32_t v0, uint32_t v1)
{
    wire_qentry e[6];
    size_t n = wire_header(p, LUMO_IVG_FORM_QUANTIZED, k_desc.dims, 2);

    axis_entries(e, 256);
    n += wire_quant_record(p + n, v0, e);
    e[0].d[0] = 64;        /* q = 64: 64/127 in Q1.14 = 8257 (8256.5 rounded) */
    e[0].d[1] = 110;       /* |d|^2 = 64^2 + 110^2 = 16196: within 1/16 of 127^2 */
    e[0].e = 20;           /* m * 2^-4 */
    n += wire_quant_record(p + n, v1, e);
    return n;
}

/* The entry (v, a) unpacked into room (lumo_ivg_entry_get), or NULL. */
static const lumo_ivg_entry *entry_of(const lumo_ivg *g, uint32_t v, int a, lumo_ivg_entry *room)
{
    return lumo_ivg_entry_get(g, v, (lumo_ivg_axis)a, room) == LUMO_OK ? room : NULL;
}

static void test_decode_quantized_known(void)
{
    lumo_arena a;
    lumo_ivg *g = make_grid(&a, &k_desc);
    const lumo_ivg_entry *e;
    lumo_ivg_entry room;
    uint32_t applied = 0;
    size_t n = two_records(g_buf, 7, 59);

    BT_CHECK(g != NULL);
    if (g == NULL)
        return;
    BT_EQ(lumo_ivg_apply_bundle(g, g_buf, n, &applied), LUMO_OK);
    BT_EQ(applied, 2);
    BT_EQ(lumo_ivg_received_count(g), 2);
    BT_CHECK(lumo_ivg_is_received(g, 7) && lumo_ivg_is_received(g, 59) && !lumo_ivg_is_received(g, 8));
    e = entry_of(g, 7, LUMO_IVG_NY, &room);
    BT_CHECK(e != NULL);
    if (e == NULL)
        return;
    BT_EQ(e->d[0], 0);
    BT_EQ(e->d[1], -16384);
    BT_EQ(e->c[0], 256u * 128u);   /* 256 * 2^(15-24) W/m^2 in UQ16.16 */
    BT_EQ(e->c[2], 258u * 128u);
    e = entry_of(g, 59, LUMO_IVG_PX, &room);
    BT_EQ(e->d[0], 8257);
    BT_EQ(e->d[1], 14191);         /* 110/127 * 2^14 = 14190.9 */
    BT_EQ(e->c[1], 257u * 4096u);  /* 257 * 2^(20-24) */
    BT_CHECK(entry_of(g, 60, LUMO_IVG_PX, &room) == NULL);   /* out of range */
}

static void test_decode_float_known(void)
{
    lumo_arena a;
    lumo_ivg *g = make_grid(&a, &k_desc);
    wire_fentry e[6];
    const lumo_ivg_entry *got;
    lumo_ivg_entry room;
    size_t n;
    int k;

    if (g == NULL) {
        BT_CHECK(g != NULL);
        return;
    }
    memset(e, 0, sizeof e);
    for (k = 0; k < 6; k++) {
        e[k].dnum[0] = 48;             /* (0.75, 0.625, -0.25): |d| = 1.0078 */
        e[k].dnum[1] = 40;
        e[k].dnum[2] = -16;
        e[k].cnum[0] = 3u * 256u + 128u;  /* 3.5 */
        e[k].cnum[1] = 1;                 /* 1/256 */
        e[k].cnum[2] = 40000u * 256u;     /* 40000: above 2^15 */
    }
    n = wire_header(g_buf, LUMO_IVG_FORM_FLOAT, k_desc.dims, 1);
    n += wire_float_record(g_buf + n, 33, e);
    BT_EQ(lumo_ivg_apply_bundle(g, g_buf, n, NULL), LUMO_OK);
    /* Stored in the packed (quantized) form: d to the nearest q/127 (95,
     * 79, -32), c to RGB9E5 with 40000's exponent (31: steps of 128 W/m^2),
     * so 3.5 and 1/256 round to 0 and 40000 to 313 * 128 (312.5 half up). */
    got = entry_of(g, 33, LUMO_IVG_PZ, &room);
    BT_EQ(got->d[0], 12256);
    BT_EQ(got->d[1], 10192);
    BT_EQ(got->d[2], -4128);
    BT_EQ(got->c[0], 0u);
    BT_EQ(got->c[1], 0u);
    BT_EQ(got->c[2], 40064u * 65536u);
    /* a NaN colour anywhere rejects the bundle */
    wire_u32(g_buf + WIRE_HEADER + 4u + 5u * 24u + 16u, 0x7FC00000u);
    BT_EQ(lumo_ivg_apply_bundle(g, g_buf, n, NULL), LUMO_ERR_NONFINITE);
    BT_EQ(entry_of(g, 33, LUMO_IVG_PZ, &room)->c[2], 40064u * 65536u);
}

/* Every hostile variant of a good two-record bundle fails with its code and
 * leaves the grid byte for byte as it was. */
static void test_decode_rejects_unchanged(void)
{
    static uint8_t before[1u << 16];
    lumo_arena a;
    lumo_ivg *g = make_grid(&a, &k_desc);
    size_t n, used;
    uint32_t applied;
    int i;
    static const struct { size_t off; uint8_t val; lumo_status want; } bad[] = {
        {0, 'X', LUMO_ERR_CORRUPT},           /* magic */
        {4, 2, LUMO_ERR_VERSION},
        {5, 7, LUMO_ERR_UNSUPPORTED},         /* form */
        {6, 6, LUMO_ERR_RANGE},               /* dims differ */
        {12, 3, LUMO_ERR_TRUNCATED},          /* 3 records announced, 2 there */
        {16, 60, LUMO_ERR_RANGE},             /* vertex index 60 of 60 */
        {16 + WIRE_QUANT_RECORD, 3, LUMO_ERR_CORRUPT},   /* same vertex twice */
        {20, 0x80, LUMO_ERR_CORRUPT},         /* q = -128 */
        {20, 20, LUMO_ERR_RANGE},             /* |d| = 20/127: not unit */
    };

    if (g == NULL) {
        BT_CHECK(g != NULL);
        return;
    }
    /* something received already, so "unchanged" is not just "empty" */
    n = two_records(g_buf, 3, 11);
    BT_EQ(lumo_ivg_apply_bundle(g, g_buf, n, NULL), LUMO_OK);
    used = a.used;
    BT_CHECK(used <= sizeof before);
    memcpy(before, g_mem, used);
    for (i = 0; i < (int)(sizeof bad / sizeof bad[0]); i++) {
        n = two_records(g_buf, 3, 12);
        g_buf[bad[i].off] = bad[i].val;
        applied = 99;
        BT_EQ(lumo_ivg_apply_bundle(g, g_buf, n, &applied), bad[i].want);
        BT_EQ(memcmp(before, g_mem, used), 0);
    }
    n = two_records(g_buf, 3, 12);
    BT_EQ(lumo_ivg_apply_bundle(g, g_buf, n - 1, NULL), LUMO_ERR_TRUNCATED);
    BT_EQ(lumo_ivg_apply_bundle(g, g_buf, 15, NULL), LUMO_ERR_TRUNCATED);
    g_buf[n] = 0;
    BT_EQ(lumo_ivg_apply_bundle(g, g_buf, n + 1, NULL), LUMO_ERR_CORRUPT);   /* trailing byte */
    BT_EQ(memcmp(before, g_mem, used), 0);
    BT_EQ(lumo_ivg_received_count(g), 2);
}

/* Receive every vertex whose index is a multiple of `step` with the same
 * entries; returns the number received. */
static uint32_t receive_every(lumo_ivg *g, uint32_t step, uint16_t m)
{
    wire_qentry e[6];
    uint32_t v, count = lumo_ivg_vertex_count(g), r = 0;
    size_t n = WIRE_HEADER;

    axis_entries(e, m);
    for (v = 0; v < count; v += step, r++)
        n += wire_quant_record(g_buf + n, v, e);
    wire_header(g_buf, LUMO_IVG_FORM_QUANTIZED, lumo_ivg_get_desc(g)->dims, r);
    return lumo_ivg_apply_bundle(g, g_buf, n, NULL) == LUMO_OK ? r : 0;
}

static int entries_equal(const lumo_ivg_entry *x, const lumo_ivg_entry *y)
{
    return memcmp(x, y, sizeof *x) == 0;
}

/* A constant field stays exactly constant through push-pull, with and
 * without smoothing, and received vertices are untouched. */
static void test_pushpull_constant(void)
{
    unsigned flags;

    for (flags = 0; flags <= LUMO_IVG_SMOOTH; flags++) {
        lumo_arena a;
        lumo_ivg *g = make_grid(&a, &k_desc);
        uint32_t v, bad = 0;
        int ax;
        lumo_ivg_entry x, y;

        if (g == NULL || receive_every(g, 7, 300) != 9) {
            BT_CHECK(0);
            return;
        }
        BT_EQ(lumo_ivg_pushpull(g, flags), LUMO_OK);
        for (v = 0; v < 60; v++)
            for (ax = 0; ax < LUMO_IVG_AXES; ax++)
                bad += !entries_equal(entry_of(g, v, ax, &x), entry_of(g, 0, ax, &y));
        BT_EQ(bad, 0);
        BT_EQ(lumo_ivg_received_count(g), 9);
    }
    {
        lumo_arena a;
        lumo_ivg *g = make_grid(&a, &k_desc);
        BT_EQ(lumo_ivg_pushpull(g, 2u), LUMO_ERR_ARG);   /* unknown flag */
        BT_EQ(lumo_ivg_pushpull(NULL, 0), LUMO_ERR_ARG);
    }
}

/* Push-pull fills with averages: on a field whose colour grows with x, every
 * filled value lies within the received range, received ones are exact. */
static void test_pushpull_bounded(void)
{
    lumo_arena a;
    lumo_ivg *g = make_grid(&a, &k_desc);
    wire_qentry e[6];
    uint32_t v, r = 0, out_of_range = 0, changed = 0;
    lumo_ivg_entry room;
    size_t n = WIRE_HEADER;

    if (g == NULL) {
        BT_CHECK(0);
        return;
    }
    for (v = 0; v < 60; v += 3, r++) {
        axis_entries(e, (uint16_t)(100 + 50 * (v % 5)));
        n += wire_quant_record(g_buf + n, v, e);
    }
    wire_header(g_buf, LUMO_IVG_FORM_QUANTIZED, k_desc.dims, r);
    BT_EQ(lumo_ivg_apply_bundle(g, g_buf, n, NULL), LUMO_OK);
    BT_EQ(lumo_ivg_pushpull(g, LUMO_IVG_SMOOTH), LUMO_OK);
    for (v = 0; v < 60; v++) {
        uint32_t c = entry_of(g, v, LUMO_IVG_PX, &room)->c[0];
        out_of_range += c < 100u * 128u || c > 300u * 128u;
        if (v % 3 == 0)
            changed += c != (100u + 50u * (v % 5)) * 128u;
    }
    BT_EQ(out_of_range, 0);
    BT_EQ(changed, 0);
}

/* Sampling a constant field whose hemisphere directions are the axes:
 * I_n . n = sum_a n_a^2 (d_a . n) c = c (|n_x|^3 + |n_y|^3 + |n_z|^3). */
static void test_sampling_known(void)
{
    lumo_arena a;
    lumo_ivg *g = make_grid(&a, &k_desc);
    lumo_q16_16 p[3] = {LUMO_Q16_FRAC(13, 10), LUMO_Q16_FRAC(27, 10), LUMO_Q16_FRAC(1, 3)};
    lumo_q16_16 far[3] = {-5 * LUMO_Q16_ONE, 9 * LUMO_Q16_ONE, LUMO_Q16_ONE};
    lumo_q1_14 nx[3] = {LUMO_Q14_ONE, 0, 0}, nny[3] = {0, -LUMO_Q14_ONE, 0};
    lumo_q1_14 diag[3] = {11585, 0, -11585};   /* (1, 0, -1)/sqrt 2 */
    lumo_q1_14 albedo[3] = {LUMO_Q14_ONE, LUMO_Q14_ONE / 2, 0};
    lumo_uq16_16 out[3];

    if (g == NULL || receive_every(g, 1, 256) != 60) {
        BT_CHECK(0);
        return;
    }
    lumo_ivg_irradiance(g, p, nx, out);
    BT_EQ(out[0], 32768u);             /* c = 256 * 2^-9 = 0.5 exactly */
    BT_EQ(out[1], 257u * 128u);
    lumo_ivg_irradiance(g, far, nny, out);   /* outside the box: clamped */
    BT_EQ(out[2], 258u * 128u);
    /* 2 * (1/sqrt 2)^3 = 1/sqrt 2: 0.5 * 0.70711 = 0.35355 -> 23170.5 */
    lumo_ivg_irradiance(g, p, diag, out);
    BT_NEAR(out[0], 23170, 2);
    lumo_ivg_radiance(g, p, nx, albedo, out);
    BT_NEAR(out[0], 10430, 1);         /* 0.5 / pi = 0.159155 -> 10430.2 */
    BT_NEAR(out[1], 5236, 1);          /* 0.5 * 257/256 * 0.5 / pi = 0.079893 */
    BT_EQ(out[2], 0);
}

/* A colour linear in x, received everywhere: trilinear sampling between
 * vertices returns the linear value (exact at the vertices). */
static void test_sampling_linear(void)
{
    lumo_arena a;
    lumo_ivg *g = make_grid(&a, &k_desc);
    wire_qentry e[6];
    lumo_q1_14 nx[3] = {LUMO_Q14_ONE, 0, 0};
    lumo_uq16_16 out[3];
    uint32_t v;
    size_t n = WIRE_HEADER;
    int i;

    if (g == NULL) {
        BT_CHECK(0);
        return;
    }
    for (v = 0; v < 60; v++) {
        axis_entries(e, (uint16_t)(100 + 64 * (v % 5)));   /* c = (100 + 64 x) / 512 */
        n += wire_quant_record(g_buf + n, v, e);
    }
    wire_header(g_buf, LUMO_IVG_FORM_QUANTIZED, k_desc.dims, 60);
    BT_EQ(lumo_ivg_apply_bundle(g, g_buf, n, NULL), LUMO_OK);
    for (i = 0; i <= 16; i++) {
        /* x = i/4 in [0, 4]; c(x) = (100 + 64 x) * 128 in UQ16.16 */
        lumo_q16_16 p[3] = {LUMO_Q16_FRAC(i, 4), LUMO_Q16_HALF, LUMO_Q16_ONE};
        lumo_ivg_irradiance(g, p, nx, out);
        BT_NEAR(out[0], 12800 + 2048 * i, 1);
    }
}

int main(void)
{
    BT_RUN(test_memory_size);
    BT_RUN(test_decode_quantized_known);
    BT_RUN(test_decode_float_known);
    BT_RUN(test_decode_rejects_unchanged);
    BT_RUN(test_pushpull_constant);
    BT_RUN(test_pushpull_bounded);
    BT_RUN(test_sampling_known);
    BT_RUN(test_sampling_linear);
    return bt_finish();
}
