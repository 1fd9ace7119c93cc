/* test_ivg_pushpull.c — 3D push-pull (seed 000 §4.1) against a
 * double-precision implementation of the same algorithm written here, and
 * hand-made cases with known answers. */
#include "test_ivg_util.h"
#include "test_ivg_entry.h"

/* ---- double reference ----------------------------------------------------- */

/* One vertex: 6 hemispheres x (c r, g, b, d x, y, z). */
typedef struct rvert { double v[LUMO_IVG_AXES][6]; } rvert;

typedef struct rlevel {
    unsigned dims[3], count;
    rvert   *e;
    int     *valid;
} rlevel;

static unsigned ref_coarse(unsigned f) { return f >= 3 ? f / 2 + 1 : 1; }

/* Push weight of fine index f for coarse index i (tent around 2i). */
static double ref_push_w(int f, int i, unsigned fine, unsigned coarse)
{
    if (fine == coarse) return f == i;
    if (coarse == 1) return 1;
    return abs(f - 2 * i) == 0 ? 2 : abs(f - 2 * i) == 1 ? 1 : 0;
}

/* Pull weight: fine f sits at coarse coordinate f/2; linear hat. */
static double ref_pull_w(int f, int i, unsigned fine, unsigned coarse)
{
    double x;
    if (fine == coarse) return f == i;
    if (coarse == 1) return 1;
    x = f / 2.0 - i;
    return fabs(x) >= 1 ? 0 : 1 - fabs(x);
}

static void accumulate(rvert *acc, const rvert *e, double w)
{
    int a, k;
    for (a = 0; a < LUMO_IVG_AXES; a++)
        for (k = 0; k < 6; k++)
            acc->v[a][k] += w * e->v[a][k];
}

static void scale(rvert *e, double s)
{
    int a, k;
    for (a = 0; a < LUMO_IVG_AXES; a++)
        for (k = 0; k < 6; k++)
            e->v[a][k] *= s;
}

static unsigned lidx(const rlevel *l, int i, int j, int k)
{
    return (unsigned)i + l->dims[0] * ((unsigned)j + l->dims[1] * (unsigned)k);
}

/* Weighted average over a window of `src` around (ci, cj, ck): kind 0 push
 * (src finer), 1 pull (src coarser), 2 smoothing (same level). */
static int window(const rlevel *src, const rlevel *dst, int i, int j, int k, int kind, int valid_only, rvert *out)
{
    int x, y, z, lo[3], hi[3], at[3] = {i, j, k}, a;
    double wsum = 0;
    memset(out, 0, sizeof *out);
    for (a = 0; a < 3; a++) {
        lo[a] = kind == 0 ? 2 * at[a] - 1 : kind == 1 ? at[a] / 2 - 1 : at[a] - 1;
        hi[a] = kind == 0 ? 2 * at[a] + 1 : kind == 1 ? at[a] / 2 + 1 : at[a] + 1;
        if (lo[a] < 0) lo[a] = 0;
        if (hi[a] > (int)src->dims[a] - 1) hi[a] = (int)src->dims[a] - 1;
    }
    for (z = lo[2]; z <= hi[2]; z++)
        for (y = lo[1]; y <= hi[1]; y++)
            for (x = lo[0]; x <= hi[0]; x++) {
                int s[3] = {x, y, z};
                double w = 1;
                unsigned v = lidx(src, x, y, z);
                for (a = 0; a < 3; a++) {
                    if (kind == 0)
                        w *= ref_push_w(s[a], at[a], src->dims[a], dst->dims[a]);
                    else if (kind == 1)
                        w *= ref_pull_w(at[a], s[a], dst->dims[a], src->dims[a]);
                    else
                        w *= s[a] == at[a] ? 2 : 1;
                }
                if (w == 0 || (valid_only && !src->valid[v]))
                    continue;
                accumulate(out, &src->e[v], w);
                wsum += w;
            }
    if (wsum > 0)
        scale(out, 1 / wsum);
    return wsum > 0;
}

/* The reference: fills the invalid vertices of level 0 in place. */
static void ref_pushpull(rlevel *l0, int smooth)
{
    rlevel lv[16];
    unsigned n = 0, l, i, j, k;
    lv[0] = *l0;
    while (lv[n].count > 1) {
        rlevel *f = &lv[n], *c = &lv[n + 1];
        for (i = 0; i < 3; i++)
            c->dims[i] = ref_coarse(f->dims[i]);
        c->count = c->dims[0] * c->dims[1] * c->dims[2];
        c->e = calloc(c->count, sizeof *c->e);
        c->valid = calloc(c->count, sizeof *c->valid);
        for (k = 0; k < c->dims[2]; k++)
            for (j = 0; j < c->dims[1]; j++)
                for (i = 0; i < c->dims[0]; i++) {
                    unsigned v = lidx(c, (int)i, (int)j, (int)k);
                    c->valid[v] = window(f, c, (int)i, (int)j, (int)k, 0, 1, &c->e[v]);
                }
        if (smooth) {
            rvert *tmp = calloc(c->count, sizeof *tmp);
            for (k = 0; k < c->dims[2]; k++)
                for (j = 0; j < c->dims[1]; j++)
                    for (i = 0; i < c->dims[0]; i++) {
                        unsigned v = lidx(c, (int)i, (int)j, (int)k);
                        if (c->valid[v])
                            window(c, c, (int)i, (int)j, (int)k, 2, 1, &tmp[v]);
                    }
            memcpy(c->e, tmp, c->count * sizeof *tmp);
            free(tmp);
        }
        n++;
    }
    for (l = n; l-- > 0;) {
        rlevel *f = &lv[l], *c = &lv[l + 1];
        for (k = 0; k < f->dims[2]; k++)
            for (j = 0; j < f->dims[1]; j++)
                for (i = 0; i < f->dims[0]; i++) {
                    unsigned v = lidx(f, (int)i, (int)j, (int)k);
                    if (!f->valid[v])
                        window(c, f, (int)i, (int)j, (int)k, 1, 0, &f->e[v]);
                }
    }
    for (l = 1; l <= n; l++) {
        free(lv[l].e);
        free(lv[l].valid);
    }
}

static unsigned level_count(const unsigned dims[3])
{
    unsigned d[3] = {dims[0], dims[1], dims[2]}, n = 1, a;
    while (d[0] * d[1] * d[2] > 1) {
        for (a = 0; a < 3; a++) d[a] = ref_coarse(d[a]);
        n++;
    }
    return n;
}

/* Run the fixed-point push-pull on g and the reference on its received
 * data; compare every vertex. Each push, smoothing and pull rounds once to
 * fixed point (<= 1/2 ulp; the earlier unpacked grid held that to 1 +
 * levels/2 ulp) and then packs the result (docs/ivg-format.md §3.3): d to
 * the nearest q/127 (<= 1/254), c to RGB9E5 (<= 2^-9 of the entry's largest
 * channel, so of the grid's largest colour cmax). Weighted averages do not
 * amplify earlier errors; a filled vertex of level 0 depends on at most
 * 2 (levels - 1) roundings up (push, smooth) and levels - 1 down (pull):
 * the bound is 1 + levels/2 ulp plus 3 (levels - 1) packings. Returns the
 * largest error seen as a fraction of that bound. */
static double compare_with_reference(lumo_ivg *g, unsigned flags)
{
    const lumo_ivg_desc *d = lumo_ivg_get_desc(g);
    rlevel l0;
    uint32_t v, count = lumo_ivg_vertex_count(g);
    unsigned dims[3] = {d->dims[0], d->dims[1], d->dims[2]};
    double ulps = 1.0 + 0.5 * level_count(dims), packs = 3.0 * (level_count(dims) - 1), cmax = 0, worst = 0;
    int a, k;

    l0.dims[0] = dims[0]; l0.dims[1] = dims[1]; l0.dims[2] = dims[2];
    l0.count = count;
    l0.e = calloc(count, sizeof *l0.e);
    l0.valid = calloc(count, sizeof *l0.valid);
    for (v = 0; v < count; v++) {
        l0.valid[v] = lumo_ivg_is_received(g, v);
        for (a = 0; a < LUMO_IVG_AXES && l0.valid[v]; a++)
            for (k = 0; k < 3; k++) {
                const lumo_ivg_entry *e = IVG_ENTRY(g, v, (lumo_ivg_axis)a);
                l0.e[v].v[a][k] = e->c[k] / Q16;
                l0.e[v].v[a][3 + k] = e->d[k] / Q14;
                cmax = fmax(cmax, e->c[k] / Q16);
            }
    }
    assert_int_equal(lumo_ivg_pushpull(g, flags), LUMO_OK);
    ref_pushpull(&l0, (flags & LUMO_IVG_SMOOTH) != 0);
    for (v = 0; v < count; v++)
        for (a = 0; a < LUMO_IVG_AXES; a++)
            for (k = 0; k < 3; k++) {
                const lumo_ivg_entry *e = IVG_ENTRY(g, v, (lumo_ivg_axis)a);
                double tc = ulps / Q16 + packs * cmax / 512, td = ulps / Q14 + packs / 254;
                double ec = fabs(e->c[k] / Q16 - l0.e[v].v[a][k]) / tc;
                double ed = fabs(e->d[k] / Q14 - l0.e[v].v[a][3 + k]) / td;
                if (ec > worst) worst = ec;
                if (ed > worst) worst = ed;
                if (ec > 1 || ed > 1)
                    fail_msg("dims %ux%ux%u vertex %u (%s) axis %d comp %d: c %.6f want %.6f, d %.6f want %.6f (tol %g, %g)",
                             dims[0], dims[1], dims[2], v, lumo_ivg_is_received(g, v) ? "received" : "filled",
                             a, k, e->c[k] / Q16, l0.e[v].v[a][k], e->d[k] / Q14, l0.e[v].v[a][3 + k], tc, td);
            }
    free(l0.e);
    free(l0.valid);
    return worst;
}

/* ---- tests ----------------------------------------------------------------- */

static lumo_ivg *random_grid(tgrid *t, test_rng *r, unsigned nx, unsigned ny, unsigned nz, unsigned percent)
{
    lumo_ivg *g = tgrid_make(t, nx, ny, nz, 3);
    uint32_t count = lumo_ivg_vertex_count(g), *verts = malloc(count * sizeof *verts), n;
    srv_ivg_fentry (*f)[LUMO_IVG_AXES] = random_field(r, count, 200.0);
    n = random_subset(r, count, percent, verts);
    send(g, LUMO_IVG_FORM_QUANTIZED, verts, n, f);
    free(verts);
    free(f);
    return g;
}

static void test_against_double(void **state)
{
    static const unsigned cases[][4] = {
        {16, 16, 16, 10}, {16, 16, 16, 50}, {17, 9, 5, 25}, {20, 3, 11, 10}, {32, 32, 32, 25}, {2, 2, 2, 50},
        {33, 2, 6, 30}, {256, 2, 2, 5}, {3, 256, 4, 20}, {2, 3, 256, 1},
    };
    test_rng r = {4242};
    unsigned i, flags;
    (void)state;
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++)
        for (flags = 0; flags <= LUMO_IVG_SMOOTH; flags++) {
            tgrid t;
            lumo_ivg *g = random_grid(&t, &r, cases[i][0], cases[i][1], cases[i][2], cases[i][3]);
            double worst = compare_with_reference(g, flags);
            print_message("push-pull %ux%ux%u %u%% %s: worst error %.3f of the bound\n", cases[i][0], cases[i][1],
                          cases[i][2], cases[i][3], flags ? "smooth" : "plain", worst);
            tgrid_free(&t);
        }
}

/* Every dims from 2 to 9 on each axis, odd and even, both modes. */
static void test_dims_sweep(void **state)
{
    test_rng r = {99};
    unsigned x, y, z;
    (void)state;
    for (x = 2; x <= 9; x++)
        for (y = 2; y <= 9; y++)
            for (z = 2; z <= 9; z++) {
                tgrid t;
                lumo_ivg *g = random_grid(&t, &r, x, y, z, 5 + (unsigned)(test_rng_next(&r) % 40));
                compare_with_reference(g, (x + y + z) & 1 ? LUMO_IVG_SMOOTH : 0);
                tgrid_free(&t);
            }
}

/* Received entries come out bit-identical; every other vertex is filled. */
static void test_received_untouched(void **state)
{
    test_rng r = {7};
    unsigned flags;
    (void)state;
    for (flags = 0; flags <= LUMO_IVG_SMOOTH; flags++) {
        tgrid t;
        lumo_ivg *g = random_grid(&t, &r, 13, 11, 9, 25);
        uint32_t v, count = lumo_ivg_vertex_count(g), filled = 0;
        lumo_ivg_entry *before = malloc(count * 6 * sizeof *before);
        int a;
        for (v = 0; v < count; v++)
            for (a = 0; a < 6; a++)
                assert_int_equal(lumo_ivg_entry_get(g, v, (lumo_ivg_axis)a, &before[v * 6 + a]), LUMO_OK);
        assert_int_equal(lumo_ivg_pushpull(g, flags), LUMO_OK);
        assert_int_equal(lumo_ivg_pushpull(g, flags), LUMO_OK);   /* twice: same */
        for (v = 0; v < count; v++) {
            lumo_ivg_entry e[6];
            for (a = 0; a < 6; a++)
                assert_int_equal(lumo_ivg_entry_get(g, v, (lumo_ivg_axis)a, &e[a]), LUMO_OK);
            if (lumo_ivg_is_received(g, v))
                assert_memory_equal(e, &before[v * 6], 6 * sizeof *e);
            else
                filled += e[0].c[0] != 0 || e[3].c[2] != 0;
        }
        assert_int_equal(filled, count - lumo_ivg_received_count(g));
        free(before);
        tgrid_free(&t);
    }
}

/* A constant field stays exactly constant everywhere, on any dims. */
static void test_constant_field(void **state)
{
    static const unsigned dims[][3] = {{16, 16, 16}, {7, 5, 9}, {2, 2, 2}, {3, 17, 2}, {64, 4, 5}};
    test_rng r = {1};
    unsigned i, flags;
    (void)state;
    for (i = 0; i < sizeof dims / sizeof dims[0]; i++)
        for (flags = 0; flags <= LUMO_IVG_SMOOTH; flags++) {
            tgrid t;
            lumo_ivg *g = tgrid_make(&t, dims[i][0], dims[i][1], dims[i][2], 2);
            uint32_t count = lumo_ivg_vertex_count(g), *verts = malloc(count * sizeof *verts), n, v;
            srv_ivg_fentry (*f)[LUMO_IVG_AXES] = random_field(&r, count, 100.0);
            for (v = 1; v < count; v++)
                memcpy(f[v], f[0], sizeof f[0]);
            n = random_subset(&r, count, 10, verts);
            send(g, LUMO_IVG_FORM_QUANTIZED, verts, n, f);
            assert_int_equal(lumo_ivg_pushpull(g, flags), LUMO_OK);
            for (v = 0; v < count; v++)
                assert_true(test_ivg_vertex_equal(g, v, g, verts[0]));
            free(verts);
            free(f);
            tgrid_free(&t);
        }
}

/* Known answer: on 3x2x2 with the planes x=0 (value A) and x=2 (value B)
 * received, the middle plane is exactly (A+B)/2 without smoothing. */
static void test_midpoint(void **state)
{
    tgrid t;
    lumo_ivg *g = tgrid_make(&t, 3, 2, 2, 1);
    srv_ivg_fentry f[12][LUMO_IVG_AXES];
    uint32_t verts[8], n = 0, v;
    int a;
    (void)state;
    memset(f, 0, sizeof f);
    for (v = 0; v < 12; v++)
        for (a = 0; a < 6; a++) {
            f[v][a].d[a / 2] = 1.0f;
            f[v][a].c[0] = v % 3 == 0 ? 2.0f : 4.0f;
            f[v][a].c[1] = v % 3 == 0 ? 0.25f : 0.75f;
        }
    for (v = 0; v < 12; v++)
        if (v % 3 != 1)
            verts[n++] = v;
    send(g, LUMO_IVG_FORM_FLOAT, verts, n, (const srv_ivg_fentry (*)[LUMO_IVG_AXES])f);
    assert_int_equal(lumo_ivg_pushpull(g, 0), LUMO_OK);
    for (v = 1; v < 12; v += 3) {
        const lumo_ivg_entry *e = IVG_ENTRY(g, v, LUMO_IVG_PY);
        assert_int_equal(e->c[0], 3u << 16);
        assert_int_equal(e->c[1], 1u << 15);
        assert_int_equal(e->d[1], LUMO_Q14_ONE);
    }
    tgrid_free(&t);
}

/* One received vertex: push-pull spreads it everywhere unchanged. */
static void test_single_sample(void **state)
{
    test_rng r = {3};
    tgrid t;
    lumo_ivg *g = tgrid_make(&t, 9, 4, 6, 1);
    srv_ivg_fentry (*f)[LUMO_IVG_AXES] = random_field(&r, 216, 30.0);
    uint32_t one = 77, v;
    (void)state;
    send(g, LUMO_IVG_FORM_QUANTIZED, &one, 1, f);
    assert_int_equal(lumo_ivg_pushpull(g, LUMO_IVG_SMOOTH), LUMO_OK);
    for (v = 0; v < 216; v++)
        assert_true(test_ivg_vertex_equal(g, v, g, one));
    free(f);
    tgrid_free(&t);
}

static void test_nothing_received(void **state)
{
    tgrid t;
    lumo_ivg *g = tgrid_make(&t, 6, 7, 8, 1);
    lumo_q16_16 p[3] = {LUMO_Q16_HALF, LUMO_Q16_HALF, 1000};
    lumo_q1_14 n[3] = {0, 0, LUMO_Q14_ONE};
    lumo_uq16_16 out[3] = {1, 1, 1};
    lumo_ivg_entry zero;
    uint32_t v;
    int a;
    (void)state;
    memset(&zero, 0, sizeof zero);
    assert_int_equal(lumo_ivg_pushpull(g, LUMO_IVG_SMOOTH), LUMO_OK);
    for (v = 0; v < 336; v++)
        for (a = 0; a < 6; a++)
            assert_memory_equal(IVG_ENTRY(g, v, a), &zero, sizeof zero);
    lumo_ivg_irradiance(g, p, n, out);
    assert_int_equal(out[0] | out[1] | out[2], 0);
    tgrid_free(&t);
}

/* A re-run after more samples equals push-pull of all samples at once. */
static void test_rerun(void **state)
{
    test_rng r = {12};
    tgrid t1, t2;
    lumo_ivg *g1 = tgrid_make(&t1, 12, 10, 7, 2), *g2 = tgrid_make(&t2, 12, 10, 7, 2);
    uint32_t count = 840, *a = malloc(count * 4), *b = malloc(count * 4), *all = malloc(count * 4);
    uint32_t na = 0, nb = 0, v;
    srv_ivg_fentry (*f)[LUMO_IVG_AXES] = random_field(&r, count, 80.0);
    (void)state;
    for (v = 0; v < count; v++) {
        uint64_t x = test_rng_next(&r) % 10;
        if (x < 1) a[na++] = v;
        else if (x < 3) b[nb++] = v;
    }
    send(g1, LUMO_IVG_FORM_QUANTIZED, a, na, f);
    assert_int_equal(lumo_ivg_pushpull(g1, LUMO_IVG_SMOOTH), LUMO_OK);
    send(g1, LUMO_IVG_FORM_QUANTIZED, b, nb, f);
    assert_int_equal(lumo_ivg_pushpull(g1, LUMO_IVG_SMOOTH), LUMO_OK);
    memcpy(all, a, na * 4);
    memcpy(all + na, b, nb * 4);
    send(g2, LUMO_IVG_FORM_QUANTIZED, all, na + nb, f);
    assert_int_equal(lumo_ivg_pushpull(g2, LUMO_IVG_SMOOTH), LUMO_OK);
    for (v = 0; v < count; v++)
        assert_true(test_ivg_vertex_equal(g1, v, g2, v));
    free(a); free(b); free(all); free(f);
    tgrid_free(&t1);
    tgrid_free(&t2);
}

/* Smoothing changes the fill (it is not a no-op) but keeps it in range. */
static void test_smoothing_differs(void **state)
{
    test_rng r1 = {8}, r2 = {8};
    tgrid t1, t2;
    lumo_ivg *g1 = random_grid(&t1, &r1, 16, 16, 16, 10), *g2 = random_grid(&t2, &r2, 16, 16, 16, 10);
    uint32_t v, diff = 0;
    (void)state;
    assert_int_equal(lumo_ivg_pushpull(g1, 0), LUMO_OK);
    assert_int_equal(lumo_ivg_pushpull(g2, LUMO_IVG_SMOOTH), LUMO_OK);
    for (v = 0; v < 4096; v++) {
        int same = test_ivg_vertex_equal(g1, v, g2, v);
        if (lumo_ivg_is_received(g1, v))
            assert_true(same);
        else
            diff += !same;
    }
    assert_true(diff > 3000);
    tgrid_free(&t1);
    tgrid_free(&t2);
}

static void test_args(void **state)
{
    tgrid t;
    lumo_ivg *g = tgrid_make(&t, 2, 2, 2, 1);
    (void)state;
    assert_int_equal(lumo_ivg_pushpull(NULL, 0), LUMO_ERR_ARG);
    assert_int_equal(lumo_ivg_pushpull(g, 2), LUMO_ERR_ARG);
    tgrid_free(&t);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_against_double),
        cmocka_unit_test(test_dims_sweep),
        cmocka_unit_test(test_received_untouched),
        cmocka_unit_test(test_constant_field),
        cmocka_unit_test(test_midpoint),
        cmocka_unit_test(test_single_sample),
        cmocka_unit_test(test_nothing_received),
        cmocka_unit_test(test_rerun),
        cmocka_unit_test(test_smoothing_differs),
        cmocka_unit_test(test_args),
    };
    return cmocka_run_group_tests_name("ivg_pushpull", tests, NULL, NULL);
}
