/*
 * test_server_reference.c — the reference renderer and the light models
 * against closed forms (docs/scene-format.md): a floor seen straight down
 * through a 1-degree camera, so every pixel sees nearly the same point.
 *   point:       L = rho/pi * Phi/(4 pi) / h^2
 *   spot:        the same inside the cone, 0 outside (hard cut-off)
 *   directional: L = rho/pi * E * cos
 *   area:        L = rho/pi * E, E a numeric integral over the rectangle;
 *                NEE picks one random light point per path, so the
 *                tolerance is K_SIGMA standard errors over the pixels
 *   indirect-only of an open floor: 0 (one surface, nothing to bounce).
 */
#include "test_common.h"
#include <stdio.h>
#include <stdlib.h>
#include "bake/bake.h"
#include "bake/reference.h"
#include "scene/shapes.h"

#define K_SIGMA 5.0
#define RHO 0.6
#define N 8

typedef struct { double mean, se; } stat;

/* Render an N x N image of the floor around (x, 0, 0) from 0.5 m above it
 * (below every light of these tests). */
static stat render_floor(srv_scene *s, float x, int spp, int indirect)
{
    char err[256];
    srv_camera cam;
    char cs[128];
    snprintf(cs, sizeof cs, "%g,0.5,0:%g,0,0:0,0,-1:1", x, x);
    assert_int_equal(srv_camera_parse(cs, &cam), 0);
    assert_int_equal(srv_scene_validate(s, err, sizeof err), 0);
    srv_rt *rt = srv_rt_create(s, 2, err, sizeof err);
    assert_non_null(rt);
    srv_tracer t;
    srv_tracer_init(&t, s, rt);
    srv_render_opts o = {spp, 5, 2, indirect, 0};
    srv_image img;
    assert_int_equal(srv_render_reference(&t, &cam, N, N, &o, &img, NULL), 0);
    double sum = 0, sq = 0;
    for (int i = 0; i < N * N; i++) {
        double v = img.rgb[3 * i + 1];
        sum += v;
        sq += v * v;
    }
    stat st = {sum / (N * N), 0};
    st.se = sqrt(fmax(sq / (N * N) - st.mean * st.mean, 0) / (N * N));
    srv_image_free(&img);
    srv_rt_free(rt);
    return st;
}

static void floor_scene(srv_scene *s)
{
    srv_scene_init(s);
    assert_int_equal(srv_add_quad(s, "floor", v3(-3, 0, -3), v3(0, 0, 6), v3(6, 0, 0),
                                  v3(RHO, RHO, RHO)), 0);
}

/* A 1-degree view 0.5 m away covers a 9 mm disc: E varies by < 0.1% there. */
#define FOOTPRINT 2e-3

static void test_point_light(void **state)
{
    (void)state;
    srv_scene s;
    floor_scene(&s);
    srv_light l = {.kind = LUMO_LIGHT_POINT, .pos = {0, 1.5f, 0}, .power = {20, 20, 20}};
    srv_scene_add_light(&s, &l);
    stat st = render_floor(&s, 0.0f, 4, 0);
    assert_close(st.mean, RHO / M_PI * 20.0 / (4 * M_PI) / (1.5 * 1.5), FOOTPRINT * st.mean);
    st = render_floor(&s, 0.0f, 4, 1);
    assert_close(st.mean, 0.0, 0.0);
    srv_scene_free(&s);
}

static void test_spot_cutoff(void **state)
{
    (void)state;
    srv_scene s;
    char err[256];
    floor_scene(&s);
    srv_light l;
    /* 30-degree cone from 1 m: radius tan(30) = 0.577 m on the floor. */
    assert_int_equal(srv_light_parse("spot:0,1,0:0,-1,0:30:10,10,10", &l, err, sizeof err), 0);
    srv_scene_add_light(&s, &l);
    double want = RHO / M_PI * 10.0 / (4 * M_PI) / pow(1.0 + 0.5 * 0.5, 1.5);   /* at x = 0.5 */
    stat in = render_floor(&s, 0.5f, 4, 0), out = render_floor(&s, 0.65f, 4, 0);
    assert_close(in.mean, want, FOOTPRINT * 2 * want);
    assert_close(out.mean, 0.0, 0.0);
    srv_scene_free(&s);
}

static void test_directional(void **state)
{
    (void)state;
    srv_scene s;
    char err[256];
    floor_scene(&s);
    srv_light l;
    assert_int_equal(srv_light_parse("directional:1,-1,0:3,3,3", &l, err, sizeof err), 0);
    srv_scene_add_light(&s, &l);
    stat st = render_floor(&s, 0.0f, 4, 0);
    assert_close(st.mean, RHO / M_PI * 3.0 * cos(M_PI / 4), 1e-5);
    srv_scene_free(&s);
}

/* E at the origin from a Lambertian rectangle [x0,x1] x [z0,z1] at height h
 * facing down, radiance Le: midpoint rule. */
static double rect_irradiance(double le, double h, double half)
{
    const int n = 400;
    double d = 2 * half / n, e = 0;
    for (int i = 0; i < n; i++)
        for (int k = 0; k < n; k++) {
            double x = -half + (i + 0.5) * d, z = -half + (k + 0.5) * d, r2 = x * x + h * h + z * z;
            e += le * (h * h / r2) / r2 * d * d;   /* cos at both ends = h / r */
        }
    return e;
}

static void test_area_light(void **state)
{
    (void)state;
    srv_scene s;
    char err[256];
    floor_scene(&s);
    srv_light l;
    /* 0.5 m square at 1 m, facing down (u x v = -y), Phi = 30 W. */
    assert_int_equal(srv_light_parse("area:-0.25,1,-0.25:0.5,0,0:0,0,0.5:30,30,30", &l, err, sizeof err), 0);
    assert_int_equal(srv_add_area_light(&s, &l), 0);
    double le = 30.0 / (M_PI * 0.25);
    double want = RHO / M_PI * rect_irradiance(le, 1.0, 0.25);
    stat st = render_floor(&s, 0.0f, 256, 0);
    assert_close(st.mean, want, K_SIGMA * st.se + FOOTPRINT * want);
    srv_scene_free(&s);
}

/* The bake and the indirect-only reference estimate the same quantity on
 * a floor point of the Cornell box: E_ind = I_{+y} . y from the bake and
 * pi L / rho from the renderer. Independent estimators, so the tolerance is
 * K_SIGMA times their combined standard error (+ the view's footprint). */
static void test_bake_matches_reference(void **state)
{
    (void)state;
    srv_scene s;
    char err[256];
    srv_scene_init(&s);
    assert_int_equal(srv_default_scene(&s, NULL, err, sizeof err), 0);
    srv_rt *rt = srv_rt_create(&s, 2, err, sizeof err);
    srv_tracer t;
    srv_tracer_init(&t, &s, rt);
    /* Vertex (1, 0, 0) of this grid is the floor point (0, 0, -0.5). */
    srv_grid g = {{3, 3, 3}, {-0.5f, 0, -0.5f}, {0.5f, 1, 0.5f}};
    srv_bake_opts bo = {32768, 3, 2, 0, 0.25f};
    srv_bake_result r;
    assert_int_equal(srv_bake(&t, &g, &bo, &r, err, sizeof err), 0);
    double e_bake = r.I[SRV_BAKE_I(1, 2, 1) + 1], se_bake = r.se[(1 * 6 + 2) * 3 + 1];
    srv_bake_result_free(&r);
    srv_rt_free(rt);
    /* Looking straight down at it from 0.3 m with a 1-degree view. */
    srv_camera cam;
    assert_int_equal(srv_camera_parse("0,0.3,-0.5:0,0,-0.5:0,0,-1:1", &cam), 0);
    s.camera = cam;
    rt = srv_rt_create(&s, 2, err, sizeof err);
    srv_tracer_init(&t, &s, rt);
    srv_render_opts o = {512, 5, 2, 1, 0};
    srv_image img;
    assert_int_equal(srv_render_reference(&t, &s.camera, N, N, &o, &img, NULL), 0);
    double sum = 0, sq = 0, k = M_PI / 0.75;   /* white floor, rho = 0.75 */
    for (int i = 0; i < N * N; i++) {
        double e = k * img.rgb[3 * i + 1];
        sum += e, sq += e * e;
    }
    double e_ref = sum / (N * N), se_ref = sqrt(fmax(sq / (N * N) - e_ref * e_ref, 0) / (N * N));
    print_message("E_ind bake %.5f +- %.5f, reference %.5f +- %.5f\n", e_bake, se_bake, e_ref, se_ref);
    assert_true(e_bake > 0.05);
    assert_close(e_bake, e_ref, K_SIGMA * sqrt(se_bake * se_bake + se_ref * se_ref) + FOOTPRINT * e_ref);
    srv_image_free(&img);
    srv_rt_free(rt);
    srv_scene_free(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_point_light), cmocka_unit_test(test_spot_cutoff),
        cmocka_unit_test(test_directional), cmocka_unit_test(test_area_light),
        cmocka_unit_test(test_bake_matches_reference),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
