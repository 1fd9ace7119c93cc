/*
 * test_server_physics.c — the bake against known answers (issue 3):
 *  - closed diffuse sphere (albedo rho, radius R) with a point light of
 *    power Phi at its centre: indirect radiance inside is uniform, so every
 *    interior vertex has I_delta = rho/(1-rho) * Phi/(4 pi R^2) * delta;
 *  - an open lit floor (one bounce) against a numeric integral;
 *  - tangential components of I_delta vanish by symmetry in the sphere.
 * Tolerances: K_SIGMA standard errors of the Monte Carlo estimate (the bake
 * reports the sample standard error per vertex, hemisphere and channel) plus
 * a stated geometric bias (the sphere is a polygon).
 */
#include "test_common.h"
#include <stdlib.h>
#include "bake_fixture.h"

#define K_SIGMA 5.0
/* A UV sphere of 96 segments is inscribed: facet distances lie in
 * [R cos(pi/96), R], irradiance within 0.2% of the sphere's; 0.5% covers it
 * and the non-uniformity of the polygon's interreflection. */
#define SPHERE_BIAS 0.005

static void sphere_case(double rho, double power)
{
    bake_fixture f;
    memset(&f, 0, sizeof f);
    srv_scene_init(&f.scene);
    vec3 a = v3((float)rho, (float)rho, (float)rho);
    assert_int_equal(srv_add_sphere(&f.scene, "room", v3(0, 0, 0), 1.0f, 96, a, 1), 0);
    srv_light l = {.kind = LUMO_LIGHT_POINT, .power = v3((float)power, (float)power, (float)power)};
    assert_int_equal(srv_scene_add_light(&f.scene, &l), 0);
    /* 3^3 vertices over [-0.5, 0.5]^3: all inside the sphere (corners at 0.87 R). */
    srv_grid g = fixture_grid(v3(-0.5f, -0.5f, -0.5f), v3(0.5f, 0.5f, 0.5f), 3);
    fixture_bake(&f, &g, 4096, 7, 2);
    double want = rho / (1.0 - rho) * power / (4.0 * M_PI);
    double sum = 0.0, sum_var = 0.0;
    int n = 0;
    for (size_t v = 0; v < f.res.nverts; v++) {
        assert_true(f.res.valid[v]);
        for (int h = 0; h < 6; h++)
            for (int ch = 0; ch < 3; ch++) {
                double got = fixture_normal_component(&f, v, h, ch), se = fixture_se(&f, v, h, ch);
                assert_close(got, want, K_SIGMA * se + SPHERE_BIAS * want);
                sum += got;
                sum_var += se * se;
                n++;
            }
    }
    /* The mean over all estimates is much tighter: check it too. */
    printf("# rho %.1f: mean %.6f want %.6f se(mean) %.2g\n", rho, sum / n, want, sqrt(sum_var) / n);
    assert_close(sum / n, want, K_SIGMA * sqrt(sum_var) / n + SPHERE_BIAS * want);
    fixture_free(&f);
}

static void test_sphere_rho_03(void **state) { (void)state; sphere_case(0.3, 10.0); }
static void test_sphere_rho_05(void **state) { (void)state; sphere_case(0.5, 10.0); }
static void test_sphere_rho_08(void **state) { (void)state; sphere_case(0.8, 4.0); }

/* Tangential components: by symmetry the centre vertex's I_delta is along
 * delta; the others' tangential parts are small against the normal one. */
static void test_sphere_tangential(void **state)
{
    (void)state;
    bake_fixture f;
    memset(&f, 0, sizeof f);
    srv_scene_init(&f.scene);
    assert_int_equal(srv_add_sphere(&f.scene, "room", v3(0, 0, 0), 1.0f, 96, v3(0.5f, 0.5f, 0.5f), 1), 0);
    srv_light l = {.kind = LUMO_LIGHT_POINT, .power = v3(10, 10, 10)};
    assert_int_equal(srv_scene_add_light(&f.scene, &l), 0);
    srv_grid g = fixture_grid(v3(-0.5f, -0.5f, -0.5f), v3(0.5f, 0.5f, 0.5f), 3);
    fixture_bake(&f, &g, 1024, 3, 2);
    size_t centre = 13;
    for (int h = 0; h < 6; h++) {
        double nrm = fixture_normal_component(&f, centre, h, 0), se = fixture_se(&f, centre, h, 0);
        for (int c = 0; c < 3; c++)
            if (c != h / 2)   /* tangential: zero mean, spread comparable to the normal part's */
                assert_close(f.res.I[SRV_BAKE_I(centre, h, 0) + (size_t)c], 0.0,
                             K_SIGMA * 1.5 * se + 0.01 * nrm);
    }
    fixture_free(&f);
}

/* ---- lit floor ------------------------------------------------------------
 * A floor quad [-2,2]x[-2,2] at y = 0 (albedo rho) under a point light at
 * height H: radiance leaving floor point x is rho/pi * Phi/(4 pi) * H/d^3.
 * With nothing else to bounce off, the indirect light at p is that radiance:
 * I_delta(p) = sum over the floor of L(x) w (w . delta > 0) cos_x / r^2 dA,
 * integrated here with a 600x600 midpoint rule. */
#define FLOOR_HALF 2.0
#define LIGHT_H 1.0
#define FLOOR_RHO 0.5
#define FLOOR_PHI 20.0

static void floor_integral(vec3 p, double out[6])
{
    const int n = 600;
    double h = 2.0 * FLOOR_HALF / n;
    memset(out, 0, 6 * sizeof *out);
    for (int i = 0; i < n; i++)
        for (int k = 0; k < n; k++) {
            double x = -FLOOR_HALF + (i + 0.5) * h, z = -FLOOR_HALF + (k + 0.5) * h;
            double dl = sqrt(x * x + LIGHT_H * LIGHT_H + z * z);
            double L = FLOOR_RHO / M_PI * FLOOR_PHI / (4.0 * M_PI) * LIGHT_H / (dl * dl * dl);
            double w[3] = {x - p.x, -p.y, z - p.z};
            double r = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
            double dw = (p.y / r) * h * h / (r * r);   /* solid angle of the cell */
            for (int a = 0; a < 3; a++) {
                double c = w[a] / r;
                out[2 * a + (c < 0)] += L * fabs(c) * dw;
            }
        }
}

static void test_lit_floor(void **state)
{
    (void)state;
    bake_fixture f;
    memset(&f, 0, sizeof f);
    srv_scene_init(&f.scene);
    vec3 a = v3(FLOOR_RHO, FLOOR_RHO, FLOOR_RHO);
    assert_int_equal(srv_add_quad(&f.scene, "floor", v3(-FLOOR_HALF, 0, -FLOOR_HALF), v3(0, 0, 2 * FLOOR_HALF),
                                  v3(2 * FLOOR_HALF, 0, 0), a), 0);
    srv_light l = {.kind = LUMO_LIGHT_POINT, .pos = {0, LIGHT_H, 0},
                   .power = v3(FLOOR_PHI, FLOOR_PHI, FLOOR_PHI)};
    assert_int_equal(srv_scene_add_light(&f.scene, &l), 0);
    srv_grid g = fixture_grid(v3(-0.8f, 0.2f, -0.8f), v3(0.8f, 0.8f, 0.8f), 3);
    fixture_bake(&f, &g, 4096, 11, 2);
    int checked = 0;
    for (size_t v = 0; v < f.res.nverts; v++) {
        int i = (int)(v % 3), j = (int)(v / 3 % 3), k = (int)(v / 9);
        double want[6];
        floor_integral(srv_grid_vertex(&g, i, j, k), want);
        assert_true(f.res.valid[v]);
        for (int h = 0; h < 6; h++) {
            double got = fixture_normal_component(&f, v, h, 1), se = fixture_se(&f, v, h, 1);
            /* 1e-3 relative: the midpoint rule's error at this resolution. */
            assert_close(got, want[h], K_SIGMA * se + 1e-3 * want[h] + 1e-9);
            checked += want[h] > 0.0;
            if (v == 13) printf("# floor centre h%d: %.6f want %.6f se %.2g\n", h, got, want[h], se);
        }
        assert_close(fixture_normal_component(&f, v, 2, 1), 0.0, 0.0);   /* nothing above */
    }
    assert_true(checked >= 27 * 5);
    fixture_free(&f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sphere_rho_03), cmocka_unit_test(test_sphere_rho_05),
        cmocka_unit_test(test_sphere_rho_08), cmocka_unit_test(test_sphere_tangential),
        cmocka_unit_test(test_lit_floor),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
