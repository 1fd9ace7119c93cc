/*
 * test_vsl_ivg.c — the IVG re-evaluated from the VSLs (vsl_ivg.h):
 *  - with tau = 0, after any sequence of flux changes and moves, the
 *    localized updates hold exactly the full evaluation (to 1e-9: doubles),
 *    with the paper's cut-off and with a cut-off that bites;
 *  - with tau > 0 the grid's hemisphere-normal components stay within tau
 *    of the full evaluation's bound (each VSL's held flux is within tau);
 *  - one VSL's change touches the vertices inside its cut-off spheres and
 *    no other (the dirty list is that set).
 */
#include "test_common.h"
#include <stdio.h>
#include <stdlib.h>
#include "vsl/vsl_ivg.h"

enum { NV = 60, NX = 9, NY = 7, NZ = 8, NVERT = NX * NY * NZ };

static srv_grid grid(void)
{
    srv_grid g = {{NX, NY, NZ}, {-1, 0, -1}, {1, 2, 1}};
    return g;
}

static vec3 rnd_unit(test_rng *r)
{
    vec3 d;
    do
        d = v3((float)test_rng_uniform(r, -1, 1), (float)test_rng_uniform(r, -1, 1), (float)test_rng_uniform(r, -1, 1));
    while (v3_dot(d, d) > 1.0f || v3_dot(d, d) < 0.01f);
    return v3_norm(d);
}

static void rnd_vsl(test_rng *r, srv_vsl_lit *v)
{
    v->pos = v3((float)test_rng_uniform(r, -1.2, 1.2), (float)test_rng_uniform(r, -0.2, 2.2),
                (float)test_rng_uniform(r, -1.2, 1.2));
    v->normal = rnd_unit(r);
    v->flux = v3((float)test_rng_uniform(r, 0, 0.05), (float)test_rng_uniform(r, 0, 0.05),
                 (float)test_rng_uniform(r, 0, 0.05));
    v->area = (float)test_rng_uniform(r, 0.001, 0.02);
}

static double max_rel_diff(const double *a, const double *b, size_t n)
{
    double worst = 0.0, scale = 1e-12;
    for (size_t i = 0; i < n; i++)
        scale = fmax(scale, fabs(b[i]));
    for (size_t i = 0; i < n; i++)
        worst = fmax(worst, fabs(a[i] - b[i]) / scale);
    return worst;
}

/* A step: some VSLs change flux (up, down, to zero), a few move. */
static void perturb(test_rng *r, srv_vsl_lit *lit)
{
    for (int s = 0; s < NV; s++) {
        uint64_t u = test_rng_next(r) % 10;
        if (u < 3)
            lit[s].flux = v3_scale(lit[s].flux, (float)test_rng_uniform(r, 0.0, 2.0));
        else if (u == 3)
            lit[s].pos = v3_add(lit[s].pos, v3(0.1f, 0, -0.05f)), lit[s].normal = rnd_unit(r);
        else if (u == 4)
            lit[s].flux = v3(0, 0, 0);
    }
}

static void exact_case(float eps)
{
    test_rng r = {31};
    srv_grid g = grid();
    srv_vsl_ivg v;
    static srv_vsl_lit lit[NV];
    static double full[NVERT * SRV_VSL_IVG_VALUES];
    for (int s = 0; s < NV; s++)
        rnd_vsl(&r, &lit[s]);
    assert_int_equal(srv_vsl_ivg_init(&v, &g, NV, eps, 0.0f), LUMO_OK);
    for (int step = 0; step < 40; step++) {
        srv_vsl_ivg_update(&v, lit);
        srv_vsl_ivg_full(&g, lit, NV, eps, full);
        assert_true(max_rel_diff(v.I, full, NVERT * SRV_VSL_IVG_VALUES) < 1e-9);
        perturb(&r, lit);
    }
    printf("# eps %g: 40 steps equal the full evaluation; %llu vertex terms for %llu republished VSLs\n",
           (double)eps, (unsigned long long)v.touched, (unsigned long long)v.republished);
    srv_vsl_ivg_free(&v);
}

static void test_exact_paper_cutoff(void **state) { (void)state; exact_case(1e-6f); }
static void test_exact_biting_cutoff(void **state) { (void)state; exact_case(0.01f); }

/* Normal component of hemisphere h, channel ch, at vertex idx. */
static double normal_part(const double *I, size_t idx, int h, int ch)
{
    double x = I[idx * SRV_VSL_IVG_VALUES + (size_t)((h * 3 + ch) * 3 + h / 2)];
    return h & 1 ? -x : x;
}

static void test_tau_bound(void **state)
{
    (void)state;
    const float tau = 0.1f;
    test_rng r = {8};
    srv_grid g = grid();
    srv_vsl_ivg v;
    static srv_vsl_lit lit[NV], bound[NV];
    static double full[NVERT * SRV_VSL_IVG_VALUES], worst[NVERT * SRV_VSL_IVG_VALUES];
    for (int s = 0; s < NV; s++)
        rnd_vsl(&r, &lit[s]);
    assert_int_equal(srv_vsl_ivg_init(&v, &g, NV, 0.0f, tau), LUMO_OK);
    size_t skipped = 0;
    for (int step = 0; step < 60; step++) {
        for (int s = 0; s < NV; s++)   /* small drifts: most stay held */
            lit[s].flux = v3_scale(lit[s].flux, (float)test_rng_uniform(&r, 0.96, 1.045));
        skipped += NV - srv_vsl_ivg_update(&v, lit);
        srv_vsl_ivg_full(&g, lit, NV, 0.0f, full);
        double mean = 0;
        for (int s = 0; s < NV; s++)
            mean += v3_maxc(lit[s].flux) / NV;
        for (int s = 0; s < NV; s++) {
            float k = fmaxf((float)mean, fmaxf(v3_maxc(lit[s].flux), v3_maxc(v.pub[s].flux)));
            bound[s] = lit[s], bound[s].flux = v3(k, k, k);
        }
        srv_vsl_ivg_full(&g, bound, NV, 0.0f, worst);
        for (size_t idx = 0; idx < NVERT; idx++)
            for (int h = 0; h < 6; h++)
                for (int ch = 0; ch < 3; ch++)
                    assert_true(fabs(normal_part(v.I, idx, h, ch) - normal_part(full, idx, h, ch)) <=
                                tau * normal_part(worst, idx, h, ch) * (1 + 1e-6) + 1e-12);
    }
    printf("# tau %.2f: %zu of %d VSL states held back, grid within tau\n", (double)tau, skipped, 60 * NV);
    assert_true(skipped > 0);
    srv_vsl_ivg_free(&v);
}

static void test_one_change_is_local(void **state)
{
    (void)state;
    const float eps = 0.02f;
    test_rng r = {4};
    srv_grid g = grid();
    srv_vsl_ivg v;
    static srv_vsl_lit lit[NV];
    static uint32_t idx[NVERT];
    for (int s = 0; s < NV; s++)
        rnd_vsl(&r, &lit[s]);
    assert_int_equal(srv_vsl_ivg_init(&v, &g, NV, eps, 0.0f), LUMO_OK);
    srv_vsl_ivg_update(&v, lit);
    srv_vsl_ivg_take_dirty(&v, idx, NVERT);
    srv_vsl_lit old = lit[17];
    lit[17].flux = v3_scale(lit[17].flux, 1.5f);
    uint64_t before = v.touched;
    assert_int_equal(srv_vsl_ivg_update(&v, lit), 1);
    size_t n = srv_vsl_ivg_take_dirty(&v, idx, NVERT), want = 0, at = 0;
    for (int k = 0; k < NZ; k++)
        for (int j = 0; j < NY; j++)
            for (int i = 0; i < NX; i++, at++) {
                vec3 p = srv_grid_vertex(&g, i, j, k);
                int in = srv_vsl_reaches(&old, p, eps) || srv_vsl_reaches(&lit[17], p, eps);
                if (in) {
                    assert_true(want < n);
                    assert_int_equal(idx[want], at);
                    want++;
                }
            }
    assert_int_equal(n, want);
    assert_true(n > 0 && n < NVERT / 2);
    assert_true(v.touched - before >= n);
    printf("# one VSL changed: %zu of %d vertices touched\n", n, NVERT);
    assert_int_equal(srv_vsl_ivg_update(&v, lit), 0);   /* nothing changed: nothing done */
    assert_int_equal(srv_vsl_ivg_take_dirty(&v, idx, NVERT), 0);
    srv_vsl_ivg_free(&v);
    assert_int_equal(srv_vsl_ivg_init(&v, &g, NV, eps, -1.0f), LUMO_ERR_ARG);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_exact_paper_cutoff),
        cmocka_unit_test(test_exact_biting_cutoff),
        cmocka_unit_test(test_tau_bound),
        cmocka_unit_test(test_one_change_is_local),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
