/*
 * test_server_order.c — the IVG's stratified streaming order (seed 000 §4.1;
 * docs/protocol.md §4; package chunk IVGS, docs/package-format.md):
 *
 *  - the server's order (server/package/ivg_order.c) equals a second
 *    implementation written here from the text of docs/package-format.md;
 *  - corners first; every round r >= 1 has at most one record per slice and
 *    exactly one per slice that still had vertices; no vertex twice; every
 *    vertex covered; the round count of the rule;
 *  - same seed -> same order and the same package bytes, another seed -> another
 *    order (the same records);
 *  - in a package: IVGS offsets fall on the bundles' record boundaries
 *    (walked here independently), the records are the order's vertices,
 *    solid ones as solid records;
 *  - the first k rounds applied through lumo_ivg_apply_records, whole or
 *    round by round, give the grid the same records give as a bundle;
 *  - the SDK's IVGS decoder refuses every damaged field;
 *  - lumo-bake's default ORDR: every base mesh and the corners first, then a
 *    batch of every mesh with a lighting step that ends with the geometry.
 */
#include "test_common.h"
#include <stdlib.h>
#include "lumo/package.h"
#include "lumo/pmesh.h"
#include "lumo/wire.h"
#include "package/ivg_encode.h"
#include "package/ivg_order.h"
#include "package/package_write.h"
#include "pm/pm_stream.h"
#include "scene/shapes.h"
#include "test_ivg_entry.h"

static void wr32(uint8_t *p, uint32_t v)
{
    lumo_wire_put_le32(p, v);
}

/* ---- the draw, from docs/package-format.md "IVGS" alone ------------------ */

static uint64_t doc_next(uint64_t *state)
{
    uint64_t z;
    *state += 0x9E3779B97F4A7C15ull;
    z = *state;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/* out: the vertices in order; first: rounds + 1 entries; returns R. */
static uint32_t doc_order(const int dims[3], uint64_t seed, uint32_t *out, uint32_t *first)
{
    int axis = dims[0] >= dims[1] && dims[0] >= dims[2] ? 0 : dims[1] >= dims[2] ? 1 : 2;
    uint32_t nx = (uint32_t)dims[0], ny = (uint32_t)dims[1], nz = (uint32_t)dims[2], n = nx * ny * nz;
    uint32_t S = (uint32_t)dims[axis], at = 0, R = 1, longest = 0;
    uint32_t **list = calloc(S, sizeof *list), *len = calloc(S, sizeof *len);
    for (uint32_t s = 0; s < S; s++)
        list[s] = malloc(sizeof **list * n);
    for (uint32_t k = 0; k < nz; k++)   /* rule 2: corners in increasing index */
        for (uint32_t j = 0; j < ny; j++)
            for (uint32_t i = 0; i < nx; i++) {
                uint32_t v = i + nx * (j + ny * k), c[3] = {i, j, k};
                int corner = (i == 0 || i == nx - 1) && (j == 0 || j == ny - 1) && (k == 0 || k == nz - 1);
                if (corner)
                    out[at++] = v;
                else
                    list[c[axis]][len[c[axis]]++] = v;   /* rule 3: increasing index */
            }
    assert_int_equal(at, 8);
    first[0] = 0;
    for (uint32_t s = 0; s < S; s++)
        longest = len[s] > longest ? len[s] : longest;
    uint64_t state = seed;
    for (uint32_t r = 1; r <= longest; r++) {   /* rule 5 */
        first[R++] = at;
        for (uint32_t s = 0; s < S; s++) {
            if (len[s] == 0)
                continue;
            uint32_t j = (uint32_t)(doc_next(&state) % len[s]);
            out[at++] = list[s][j];
            list[s][j] = list[s][len[s] - 1];
            len[s]--;
        }
    }
    first[R] = at;
    for (uint32_t s = 0; s < S; s++)
        free(list[s]);
    free(list);
    free(len);
    return R;
}

static const int k_dims[][3] = {
    {2, 2, 2}, {3, 3, 3}, {2, 2, 5}, {7, 5, 6}, {5, 9, 4}, {4, 4, 9}, {4, 6, 6}, {6, 6, 4},
    {2, 9, 2}, {17, 3, 2}, {16, 16, 16}, {3, 40, 7}, {256, 2, 3}, {12, 12, 13},
};
#define NDIMS (sizeof k_dims / sizeof k_dims[0])

static void make_order(const int dims[3], uint64_t seed, srv_ivg_order *o)
{
    uint16_t d[3] = {(uint16_t)dims[0], (uint16_t)dims[1], (uint16_t)dims[2]};
    assert_int_equal(srv_ivg_order_make(d, seed, o), LUMO_OK);
}

/* The writer and the text agree, vertex for vertex and round for round. */
static void test_order_matches_the_text(void **state)
{
    (void)state;
    static const uint64_t seeds[] = {1, 7, 0, 0xFFFFFFFFFFFFFFFFull, 0x123456789ABCDEFull};
    for (size_t i = 0; i < NDIMS; i++)
        for (size_t k = 0; k < sizeof seeds / sizeof seeds[0]; k++) {
            srv_ivg_order o;
            make_order(k_dims[i], seeds[k], &o);
            uint32_t *v = malloc(sizeof *v * o.count), *first = malloc(sizeof *first * (LUMO_IVG_ORDER_MAX_ROUNDS + 1));
            uint32_t R = doc_order(k_dims[i], seeds[k], v, first);
            assert_int_equal(o.rounds, R);
            assert_memory_equal(o.vertex, v, sizeof *v * o.count);
            assert_memory_equal(o.round_first, first, sizeof *first * (R + 1));
            free(v);
            free(first);
            srv_ivg_order_free(&o);
        }
}

/* The properties seed 000 §4.1 asks for, on every test grid. */
static void test_order_properties(void **state)
{
    (void)state;
    for (size_t i = 0; i < NDIMS; i++) {
        const int *dims = k_dims[i];
        srv_ivg_order o;
        make_order(dims, 42, &o);
        uint32_t nx = (uint32_t)dims[0], ny = (uint32_t)dims[1], n = nx * ny * (uint32_t)dims[2];
        uint32_t axis = lumo_ivg_order_axis((const uint16_t[3]){(uint16_t)dims[0], (uint16_t)dims[1], (uint16_t)dims[2]});
        uint32_t S = (uint32_t)dims[axis], per_slice = n / S;
        uint8_t *seen = calloc(n, 1);
        uint32_t *left = malloc(sizeof *left * S);   /* unsent vertices per slice */
        assert_int_equal(o.count, n);
        assert_int_equal(o.axis, axis);
        assert_int_equal(o.slices, S);
        for (int a = 0; a < 3; a++)   /* the longest axis, x then y on ties */
            assert_true((uint32_t)dims[a] <= S && ((uint32_t)dims[a] < S || (uint32_t)a >= axis));
        /* round 0: the 8 corners, in increasing index */
        assert_int_equal(o.round_first[0], 0);
        assert_int_equal(o.round_first[1], 8);
        for (uint32_t r = 0; r < 8; r++) {
            uint32_t v = o.vertex[r], c[3] = {v % nx, v / nx % ny, v / (nx * ny)};
            for (int a = 0; a < 3; a++)
                assert_true(c[a] == 0 || c[a] == (uint32_t)dims[a] - 1);
            assert_true(r == 0 || o.vertex[r - 1] < v);
        }
        for (uint32_t s = 0; s < S; s++)
            left[s] = per_slice - (s == 0 || s == S - 1 ? 4u : 0u);
        for (uint32_t r = 1; r < o.rounds; r++) {
            uint8_t *had = malloc(S), *hit = calloc(S, 1);
            uint32_t last = 0;
            for (uint32_t s = 0; s < S; s++)
                had[s] = left[s] > 0;
            for (uint32_t p = o.round_first[r]; p < o.round_first[r + 1]; p++) {
                uint32_t v = o.vertex[p], c[3] = {v % nx, v / nx % ny, v / (nx * ny)}, s = c[axis];
                assert_int_equal(hit[s], 0);          /* at most one per slice */
                assert_true(p == o.round_first[r] || s > last);   /* slices in increasing order */
                assert_true(left[s] > 0);
                hit[s] = 1, last = s;
                left[s]--;
            }
            for (uint32_t s = 0; s < S; s++)          /* exactly one per slice that still had some */
                assert_int_equal(hit[s], had[s]);
            free(had);
            free(hit);
        }
        for (uint32_t s = 0; s < S; s++)
            assert_int_equal(left[s], 0);
        for (uint32_t p = 0; p < n; p++) {            /* no vertex twice, all covered */
            assert_true(o.vertex[p] < n);
            assert_int_equal(seen[o.vertex[p]], 0);
            seen[o.vertex[p]] = 1;
        }
        assert_int_equal(o.round_first[o.rounds], n);
        assert_int_equal(o.rounds, 1 + (S > 2 ? per_slice : per_slice - 4));
        free(seen);
        free(left);
        srv_ivg_order_free(&o);
    }
}

/* Same seed: the same order; another seed: another order of the same set. */
static void test_order_seeds(void **state)
{
    (void)state;
    const int dims[3] = {7, 5, 6};
    srv_ivg_order a, b, c;
    make_order(dims, 9, &a);
    make_order(dims, 9, &b);
    make_order(dims, 10, &c);
    assert_memory_equal(a.vertex, b.vertex, sizeof *a.vertex * a.count);
    assert_memory_equal(a.vertex, c.vertex, 8 * sizeof *a.vertex);   /* the corners do not depend on it */
    assert_memory_not_equal(a.vertex + 8, c.vertex + 8, sizeof *a.vertex * (a.count - 8));
    assert_memory_equal(a.round_first, c.round_first, sizeof *a.round_first * (a.rounds + 1));
    srv_ivg_order_free(&a);
    srv_ivg_order_free(&b);
    srv_ivg_order_free(&c);
}

/* ---- in a package -------------------------------------------------------- */

/* A bake result with random irradiance and every 5th vertex solid. */
static void fake_bake(srv_bake_result *r, const int dims[3], uint64_t rng_seed)
{
    test_rng rng = {rng_seed};
    memset(r, 0, sizeof *r);
    for (int a = 0; a < 3; a++)
        r->grid.dims[a] = dims[a];
    r->grid.bmin = v3(-1, 0, -1);
    r->grid.bmax = v3(1, 2, 1);
    r->nverts = (size_t)dims[0] * dims[1] * dims[2];
    r->I = malloc(sizeof *r->I * r->nverts * 54);
    r->se = calloc(r->nverts * 18, sizeof *r->se);
    r->valid = malloc(r->nverts);
    for (size_t i = 0; i < r->nverts * 54; i++)
        r->I[i] = (float)test_rng_uniform(&rng, -0.5, 4.0);
    for (size_t v = 0; v < r->nverts; v++)
        r->valid[v] = v % 5 != 3;
}

static uint8_t *pack(const srv_bake_result *r, uint64_t seed, size_t *len)
{
    srv_pkg_writer w;
    uint8_t *data = NULL;
    char err[256];
    srv_pkgw_init(&w);
    assert_int_equal(srv_pack_ivg(&w, r, 8, seed, err, sizeof err), 0);
    assert_int_equal(srv_pkgw_serialize(&w, &data, len), 0);
    srv_pkgw_free(&w);
    return data;
}

static const uint8_t *chunk(const lumo_package *pkg, uint32_t type, uint32_t *len)
{
    const uint8_t *p;
    assert_int_equal(lumo_package_find(pkg, type, 0, &p, len), LUMO_OK);
    return p;
}

/* Walk a bundle's records: offsets[i] = byte offset of record i (count + 1
 * entries), words[i] its index word. */
static void walk(const uint8_t *b, uint32_t len, lumo_ivg_form form, uint32_t count, uint32_t *offsets, uint32_t *words)
{
    uint32_t pos = 16;
    assert_int_equal(lumo_wire_le32(b + 12), count);
    for (uint32_t i = 0; i < count; i++) {
        offsets[i] = pos;
        words[i] = lumo_wire_le32(b + pos);
        pos += words[i] & LUMO_IVG_SOLID_BIT ? 4u : form == LUMO_IVG_FORM_FLOAT ? 148u : 46u;
    }
    offsets[count] = pos;
    assert_int_equal(pos, len);
}

static void test_package_order(void **state)
{
    (void)state;
    const int dims[3] = {6, 7, 5};
    srv_bake_result r;
    srv_ivg_order o;
    size_t len, len2, len3;
    fake_bake(&r, dims, 99);
    uint8_t *data = pack(&r, 5, &len), *again = pack(&r, 5, &len2), *other = pack(&r, 6, &len3);
    assert_int_equal(len, len2);
    assert_memory_equal(data, again, len);   /* same seed, same bytes */
    assert_int_equal(len, len3);
    assert_memory_not_equal(data, other, len);
    lumo_package pkg;
    lumo_ivg_order io;
    assert_int_equal(lumo_package_open(&pkg, data, len), LUMO_OK);
    assert_int_equal(pkg.version_major, 2);
    assert_int_equal(lumo_package_ivg_order(&pkg, &io), LUMO_OK);
    make_order(dims, 5, &o);
    assert_int_equal(io.seed, 5);
    assert_int_equal(io.axis, o.axis);
    assert_int_equal(io.slices, o.slices);
    assert_int_equal(io.rounds, o.rounds);
    assert_int_equal(io.records, r.nverts);
    for (int f = 0; f < 2; f++) {
        lumo_ivg_form form = f ? LUMO_IVG_FORM_FLOAT : LUMO_IVG_FORM_QUANTIZED;
        uint32_t blen, *off = malloc(sizeof *off * (r.nverts + 1)), *word = malloc(sizeof *word * r.nverts);
        const uint8_t *b = chunk(&pkg, f ? LUMO_PKG_IVGF : LUMO_PKG_IVGQ, &blen);
        walk(b, blen, form, (uint32_t)r.nverts, off, word);
        for (uint32_t i = 0; i < r.nverts; i++) {   /* the order's vertices; solid as solid records */
            uint32_t v = o.vertex[i];
            assert_int_equal(word[i] & ~LUMO_IVG_SOLID_BIT, v);
            assert_int_equal(!(word[i] & LUMO_IVG_SOLID_BIT), r.valid[v]);
        }
        for (uint32_t k = 0; k <= o.rounds; k++) {   /* IVGS on record boundaries */
            assert_int_equal(lumo_ivg_order_first(&io, k), o.round_first[k]);
            assert_int_equal(lumo_ivg_order_offset(&io, form, k), off[o.round_first[k]]);
        }
        assert_int_equal(lumo_ivg_order_offset(&io, form, io.rounds + 5), blen);
        free(off);
        free(word);
    }
    /* rounds_in: whole rounds among a prefix of records */
    assert_int_equal(lumo_ivg_order_rounds_in(&io, 0), 0);
    assert_int_equal(lumo_ivg_order_rounds_in(&io, 7), 0);
    assert_int_equal(lumo_ivg_order_rounds_in(&io, 8), 1);
    assert_int_equal(lumo_ivg_order_rounds_in(&io, o.round_first[3] + 1), 3);
    assert_int_equal(lumo_ivg_order_rounds_in(&io, io.records), io.rounds);
    /* another seed: the same records, in another order */
    lumo_package pkg3;
    lumo_ivg_order io3;
    uint32_t q1, q3;
    assert_int_equal(lumo_package_open(&pkg3, other, len3), LUMO_OK);
    assert_int_equal(lumo_package_ivg_order(&pkg3, &io3), LUMO_OK);
    assert_int_equal(io3.seed, 6);
    const uint8_t *b1 = chunk(&pkg, LUMO_PKG_IVGQ, &q1), *b3 = chunk(&pkg3, LUMO_PKG_IVGQ, &q3);
    assert_int_equal(q1, q3);
    assert_memory_equal(b1, b3, lumo_ivg_order_offset(&io, LUMO_IVG_FORM_QUANTIZED, 1));   /* header and corners */
    assert_memory_not_equal(b1, b3, q1);
    srv_ivg_order_free(&o);
    free(data);
    free(again);
    free(other);
    srv_bake_result_free(&r);
}

/* ---- applying rounds ----------------------------------------------------- */

static lumo_ivg *new_grid(const lumo_package *pkg, void **mem)
{
    lumo_ivg_desc d;
    lumo_arena a;
    lumo_ivg *g;
    assert_int_equal(lumo_package_ivg_desc(pkg, &d), LUMO_OK);
    size_t n = lumo_ivg_memory_size(&d) + LUMO_ARENA_SLACK;
    *mem = malloc(n);
    lumo_arena_init(&a, *mem, n);
    assert_int_equal(lumo_ivg_create(&g, &a, &d), LUMO_OK);
    return g;
}

static void assert_same_grid(const lumo_ivg *a, const lumo_ivg *b)
{
    assert_int_equal(lumo_ivg_received_count(a), lumo_ivg_received_count(b));
    assert_int_equal(lumo_ivg_solid_count(a), lumo_ivg_solid_count(b));
    for (uint32_t v = 0; v < lumo_ivg_vertex_count(a); v++) {
        assert_int_equal(lumo_ivg_is_received(a, v), lumo_ivg_is_received(b, v));
        assert_int_equal(lumo_ivg_is_solid(a, v), lumo_ivg_is_solid(b, v));
        assert_true(test_ivg_vertex_equal(a, v, b, v));
    }
}

/* The first k rounds, as the server streams them (one byte range of the
 * bundle, applied without the header; or round by round), against the same
 * records given as a bundle (the package's header with the count patched). */
static void test_prefix_of_rounds(void **state)
{
    (void)state;
    const int dims[3] = {5, 4, 6};
    srv_bake_result r;
    size_t len;
    fake_bake(&r, dims, 7);
    uint8_t *data = pack(&r, 77, &len);
    lumo_package pkg;
    lumo_ivg_order io;
    assert_int_equal(lumo_package_open(&pkg, data, len), LUMO_OK);
    assert_int_equal(lumo_package_ivg_order(&pkg, &io), LUMO_OK);
    for (int f = 0; f < 2; f++) {
        lumo_ivg_form form = f ? LUMO_IVG_FORM_FLOAT : LUMO_IVG_FORM_QUANTIZED;
        uint32_t blen;
        const uint8_t *b = chunk(&pkg, f ? LUMO_PKG_IVGF : LUMO_PKG_IVGQ, &blen);
        for (uint32_t k = 1; k <= io.rounds; k += 1 + k / 3) {
            uint32_t records = lumo_ivg_order_first(&io, k), end = lumo_ivg_order_offset(&io, form, k), applied;
            uint8_t *bundle = malloc(end);
            void *m1, *m2, *m3;
            lumo_ivg *g1 = new_grid(&pkg, &m1), *g2 = new_grid(&pkg, &m2), *g3 = new_grid(&pkg, &m3);
            memcpy(bundle, b, end);
            wr32(bundle + 12, records);
            assert_int_equal(lumo_ivg_apply_bundle(g1, bundle, end, &applied), LUMO_OK);
            assert_int_equal(applied, records);
            assert_int_equal(lumo_ivg_apply_records(g2, form, records, b + 16, end - 16, &applied), LUMO_OK);
            assert_int_equal(applied, records);
            assert_same_grid(g1, g2);
            for (uint32_t c = 0; c < k; c++) {   /* round by round, as REQUESTs of one round would */
                uint32_t from = lumo_ivg_order_offset(&io, form, c), to = lumo_ivg_order_offset(&io, form, c + 1);
                uint32_t n = lumo_ivg_order_first(&io, c + 1) - lumo_ivg_order_first(&io, c);
                assert_int_equal(lumo_ivg_apply_records(g3, form, n, b + from, to - from, &applied), LUMO_OK);
                assert_int_equal(applied, n);
            }
            assert_same_grid(g1, g3);
            assert_int_equal(lumo_ivg_received_count(g1) + lumo_ivg_solid_count(g1), records);
            free(bundle);
            free(m1), free(m2), free(m3);
        }
    }
    /* the whole bundle equals all rounds */
    void *m1, *m2;
    uint32_t blen;
    const uint8_t *b = chunk(&pkg, LUMO_PKG_IVGQ, &blen);
    lumo_ivg *g1 = new_grid(&pkg, &m1), *g2 = new_grid(&pkg, &m2);
    assert_int_equal(lumo_package_load_ivg(&pkg, g1, LUMO_IVG_FORM_QUANTIZED, NULL), LUMO_OK);
    assert_int_equal(lumo_ivg_apply_records(g2, LUMO_IVG_FORM_QUANTIZED, io.records, b + 16, blen - 16, NULL), LUMO_OK);
    assert_same_grid(g1, g2);
    free(m1), free(m2);
    free(data);
    srv_bake_result_free(&r);
}

/* ---- the decoder against damage ------------------------------------------ */

static void expect_decode(const uint8_t *p, size_t len, const lumo_ivg_desc *d, lumo_status want, const char *what)
{
    lumo_ivg_order o;
    memset(&o, 0xA5, sizeof o);
    lumo_status st = lumo_ivg_order_decode(p, len, d, &o);
    if (st != want)
        fail_msg("%s: got %s, want %s", what, lumo_strerror(st), lumo_strerror(want));
    if (st) {
        uint8_t x[sizeof o];
        memset(x, 0xA5, sizeof x);
        assert_memory_equal(&o, x, sizeof o);   /* untouched on error */
    }
}

static void test_decode_rejects(void **state)
{
    (void)state;
    const int dims[3] = {4, 6, 3};
    srv_bake_result r;
    size_t len;
    fake_bake(&r, dims, 3);
    uint8_t *data = pack(&r, 1, &len);
    lumo_package pkg;
    lumo_ivg_desc d;
    uint32_t n;
    assert_int_equal(lumo_package_open(&pkg, data, len), LUMO_OK);
    assert_int_equal(lumo_package_ivg_desc(&pkg, &d), LUMO_OK);
    const uint8_t *s = chunk(&pkg, LUMO_PKG_IVGS, &n);
    uint8_t *c = malloc(n + 16);
    uint32_t R = lumo_wire_le32(s + 16);
    const uint32_t first = 20, qoff = 20 + 4 * (R + 1), foff = 20 + 8 * (R + 1);
    assert_int_equal(lumo_wire_le32(s + 12), 6);   /* y is the longest */
    assert_int_equal(s[8], 1);
    expect_decode(s, n, &d, LUMO_OK, "good");
    expect_decode(s, n, NULL, LUMO_OK, "good, no descriptor");
    for (size_t k = 0; k < n; k++)
        expect_decode(s, k, NULL, LUMO_ERR_TRUNCATED, "truncated");
    memcpy(c, s, n); c[n] = 0;
    expect_decode(c, n + 1, NULL, LUMO_ERR_CORRUPT, "trailing byte");
#define CASE(off, val, desc, want, what) \
    memcpy(c, s, n); wr32(c + (off), (val)); expect_decode(c, n, (desc), (want), (what))
    memcpy(c, s, n); c[8] = 3;
    expect_decode(c, n, NULL, LUMO_ERR_CORRUPT, "axis 3");
    memcpy(c, s, n); c[8] = 0;
    expect_decode(c, n, NULL, LUMO_OK, "axis x, no descriptor");
    expect_decode(c, n, &d, LUMO_ERR_RANGE, "axis x on a y-longest grid");
    CASE(12, 1, NULL, LUMO_ERR_RANGE, "1 slice");
    CASE(12, 257, NULL, LUMO_ERR_RANGE, "257 slices");
    CASE(12, 7, &d, LUMO_ERR_RANGE, "slices differ from the grid");
    CASE(16, 0, NULL, LUMO_ERR_RANGE, "0 rounds");
    CASE(16, LUMO_IVG_ORDER_MAX_ROUNDS + 1, NULL, LUMO_ERR_RANGE, "too many rounds");
    CASE(16, R - 1, NULL, LUMO_ERR_CORRUPT, "rounds disagree with the length");
    CASE(first, 1, NULL, LUMO_ERR_CORRUPT, "first record of round 0");
    CASE(first + 4, 9, NULL, LUMO_ERR_CORRUPT, "round 0 of 9 records");
    CASE(first + 8, lumo_wire_le32(s + first + 12), NULL, LUMO_ERR_CORRUPT, "an empty round");
    CASE(first + 8, lumo_wire_le32(s + first + 4) + 7, NULL, LUMO_ERR_CORRUPT, "a round of 7 on 6 slices");
    CASE(first + 4 * R, lumo_wire_le32(s + first + 4 * R) + 1, &d, LUMO_ERR_RANGE, "record count differs from the grid");
    CASE(qoff, 17, NULL, LUMO_ERR_CORRUPT, "IVGQ starts past the header");
    CASE(foff, 0, NULL, LUMO_ERR_CORRUPT, "IVGF starts at 0");
    CASE(qoff + 8, lumo_wire_le32(s + qoff + 8) + 1, NULL, LUMO_ERR_CORRUPT, "IVGQ round 1 one byte longer");
    CASE(qoff + 8, lumo_wire_le32(s + qoff + 8) + 42, NULL, LUMO_ERR_CORRUPT, "IVGQ one more data record than IVGF");
    CASE(foff + 4 * R, lumo_wire_le32(s + foff + 4 * R) - 4, NULL, LUMO_ERR_CORRUPT, "IVGF end short");
    CASE(qoff + 4, 0xFFFFFFF0u, NULL, LUMO_ERR_CORRUPT, "offset backwards after a huge one");
    /* the bundle check: the other form's bytes, a bundle cut short, a bad count */
    lumo_ivg_order o;
    uint32_t blen;
    const uint8_t *b = chunk(&pkg, LUMO_PKG_IVGQ, &blen);
    assert_int_equal(lumo_ivg_order_decode(s, n, &d, &o), LUMO_OK);
    assert_int_equal(lumo_ivg_order_check_bundle(&o, LUMO_IVG_FORM_QUANTIZED, b, blen), LUMO_OK);
    assert_int_equal(lumo_ivg_order_check_bundle(&o, LUMO_IVG_FORM_FLOAT, b, blen), LUMO_ERR_CORRUPT);
    assert_int_equal(lumo_ivg_order_check_bundle(&o, LUMO_IVG_FORM_QUANTIZED, b, blen - 1), LUMO_ERR_CORRUPT);
    uint8_t *bb = malloc(blen);
    uint32_t *offs = malloc(sizeof *offs * (r.nverts + 1)), *words = malloc(sizeof *words * r.nverts);
    walk(b, blen, LUMO_IVG_FORM_QUANTIZED, (uint32_t)r.nverts, offs, words);
    memcpy(bb, b, blen);
    wr32(bb + 12, (uint32_t)r.nverts - 1);
    assert_int_equal(lumo_ivg_order_check_bundle(&o, LUMO_IVG_FORM_QUANTIZED, bb, blen), LUMO_ERR_CORRUPT);
    /* the last record's solid flag flipped: it ends short of the bundle, or
     * runs past it (a flip further up may happen to land on a boundary
     * again: the walk checks boundaries, the entries are apply's job) */
    memcpy(bb, b, blen);
    bb[offs[r.nverts - 1] + 3] ^= 0x80;
    assert_int_equal(lumo_ivg_order_check_bundle(&o, LUMO_IVG_FORM_QUANTIZED, bb, blen),
                     words[r.nverts - 1] & LUMO_IVG_SOLID_BIT ? LUMO_ERR_TRUNCATED : LUMO_ERR_CORRUPT);
    free(offs);
    free(words);
    free(bb);
    free(c);
    free(data);
    srv_bake_result_free(&r);
#undef CASE
}

/* ---- the default interleaving (ORDR) --------------------------------------- */

static void test_default_interleaving(void **state)
{
    (void)state;
    srv_scene sc;
    srv_pkg_writer w;
    srv_bake_result r;
    char err[256];
    const int dims[3] = {9, 5, 5};
    srv_scene_init(&sc);
    assert_int_equal(srv_add_box(&sc, "room", v3(-1, 0, -1), v3(1, 2, 1), v3(0.7f, 0.7f, 0.7f), 1), 0);
    /* 48 segments: enough vertices above its base (max_error keeps a sphere's shape) for 2 batches */
    assert_int_equal(srv_add_sphere(&sc, "ball", v3(0, 0.5f, 0), 0.4f, 48, v3(0.5f, 0.5f, 0.5f), 0), 0);
    srv_pkgw_init(&w);
    assert_int_equal(srv_pack_scene(&w, &sc, 0), 0);
    for (size_t m = 0; m < sc.nmeshes; m++)
        assert_int_equal(srv_pm_pack(&w, &sc.meshes[m].pos[0].x, NULL, sc.meshes[m].nverts, sc.meshes[m].tris,
                                     sc.meshes[m].ntris, NULL, err, sizeof err), 0);
    fake_bake(&r, dims, 1);
    assert_int_equal(srv_pack_ivg(&w, &r, 8, 3, err, sizeof err), 0);
    assert_int_equal(srv_pack_order(&w), 0);
    uint8_t *data;
    size_t len;
    assert_int_equal(srv_pkgw_serialize(&w, &data, &len), 0);
    lumo_package pkg;
    lumo_scene_order o;
    lumo_ivg_order io;
    lumo_scene_step st;
    assert_int_equal(lumo_package_open(&pkg, data, len), LUMO_OK);
    assert_int_equal(lumo_package_order(&pkg, &o), LUMO_OK);
    assert_int_equal(lumo_package_ivg_order(&pkg, &io), LUMO_OK);
    uint32_t meshes = (uint32_t)sc.nmeshes, remaining[64] = {0}, longest = 0, streamed = 0;
    assert_true(meshes < 64);
    /* the prefix: every base mesh in mesh order, then round 0 */
    assert_int_equal(o.prefix, meshes + 1);
    for (uint32_t m = 0; m < meshes; m++) {
        const uint8_t *p;
        uint32_t n;
        lumo_pmesh_header h;
        assert_int_equal(lumo_package_find(&pkg, LUMO_PKG_PMSH, m, &p, &n), LUMO_OK);
        assert_int_equal(lumo_pmesh_read_header(p, n, &h), LUMO_OK);
        assert_int_equal(lumo_scene_order_step(&o, m, &st), LUMO_OK);
        assert_int_equal(st.channel, LUMO_CHANNEL_GEOMETRY);
        assert_int_equal(st.mesh, m);
        assert_int_equal(st.amount, h.base_vertices);
        remaining[m] = h.batch_count - 1;
        longest = remaining[m] > longest ? remaining[m] : longest;
        streamed += remaining[m] > 0;
    }
    assert_true(longest >= 2);
    assert_int_equal(lumo_scene_order_step(&o, meshes, &st), LUMO_OK);
    assert_int_equal(st.channel, LUMO_CHANNEL_LIGHTING);
    assert_int_equal(st.amount, 1);
    /* the cycle: a batch of every mesh that has more, then the lighting */
    assert_int_equal(o.cycle, streamed + 1);
    assert_int_equal(lumo_scene_order_step(&o, o.prefix + o.cycle - 1, &st), LUMO_OK);
    assert_int_equal(st.channel, LUMO_CHANNEL_LIGHTING);
    assert_int_equal(st.amount, (io.rounds - 1 + longest - 1) / longest);
    assert_int_equal(lumo_scene_order_step(&o, o.prefix + o.cycle, &st), LUMO_ERR_RANGE);
    /* played out: the geometry ends in pass B - 1 (B: the longest stream's
     * batches after its base), the lighting in pass ceil((R - 1) / k) - 1,
     * never later */
    uint32_t rounds = 1, pass = 0, geometry_end = 0, lighting_end = 0;
    for (int busy = 1; busy; pass++) {
        busy = 0;
        for (uint32_t i = o.prefix; i < o.prefix + o.cycle; i++) {
            lumo_scene_order_step(&o, i, &st);
            if (st.channel == LUMO_CHANNEL_GEOMETRY && remaining[st.mesh]) {
                remaining[st.mesh]--;
                busy = 1;
                geometry_end = pass;
            } else if (st.channel == LUMO_CHANNEL_LIGHTING && rounds < io.rounds) {
                rounds = rounds + st.amount < io.rounds ? rounds + st.amount : io.rounds;
                busy = 1;
                lighting_end = pass;
            }
        }
    }
    uint32_t k = (io.rounds - 1 + longest - 1) / longest;
    assert_int_equal(geometry_end, longest - 1);
    assert_int_equal(lighting_end, (io.rounds - 1 + k - 1) / k - 1);
    assert_true(lighting_end <= geometry_end);
    assert_true(io.rounds - 1 < longest || 2 * (lighting_end + 1) >= longest);   /* not far ahead either */
    free(data);
    srv_pkgw_free(&w);
    srv_bake_result_free(&r);
    srv_scene_free(&sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_order_matches_the_text), cmocka_unit_test(test_order_properties),
        cmocka_unit_test(test_order_seeds),            cmocka_unit_test(test_package_order),
        cmocka_unit_test(test_prefix_of_rounds),       cmocka_unit_test(test_decode_rejects),
        cmocka_unit_test(test_default_interleaving),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
