/*
 * test_raster_camera.c — the fitted camera (lumo_scene_camera_fit) sees the
 * whole box for random boxes and frame shapes, and the near plane
 * (lumo_raster_znear_for_box) clips none of it; the server's fit is the
 * client's (docs/scene-format.md, "Fitted camera").
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include "lumo/raster.h"
#include "lumo/scene.h"
#include "scene/camera.h"

static uint64_t rng_state = 0x9e3779b97f4a7c15ull;

static double uniform(void)   /* [0, 1) */
{
    rng_state = rng_state * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(rng_state >> 11) / 9007199254740992.0;
}

static double q16(lumo_q16_16 v) { return v / 65536.0; }

/* A random box: centre within +-c, each extent log-uniform in [1e-3, e]
 * metres, one axis flat now and then (a floor, a wall). */
static void random_box(lumo_pkg_info *info, double c, double e)
{
    int k, flat = uniform() < 0.2 ? (int)(uniform() * 3) : -1;

    memset(info, 0, sizeof *info);
    for (k = 0; k < 3; k++) {
        double mid = (2 * uniform() - 1) * c;
        double half = k == flat ? 0 : 0.5e-3 * pow(e / 1e-3, uniform());
        info->bmin[k] = (lumo_q16_16)floor((mid - half) * 65536);
        info->bmax[k] = (lumo_q16_16)ceil((mid + half) * 65536);
    }
}

/* Corner (c) of the box in the camera's image: |s|, |t| <= 1 is inside a
 * w x h frame (docs/scene-format.md, "Camera"); *depth is the view depth. */
static void project(const lumo_pkg_info *info, int c, double aspect, double *s, double *t, double *depth)
{
    double e[3], f[3], u[3], r[3], p[3], lf = 0, lr = 0, th = tan(q16(info->fovy_deg) * M_PI / 360);
    int k;

    for (k = 0; k < 3; k++) {
        e[k] = q16(info->eye[k]);
        f[k] = q16(info->target[k]) - e[k];
        u[k] = q16(info->up[k]);
        p[k] = q16((c >> k) & 1 ? info->bmax[k] : info->bmin[k]) - e[k];
        lf += f[k] * f[k];
    }
    for (k = 0; k < 3; k++)
        f[k] /= sqrt(lf);
    r[0] = f[1] * u[2] - f[2] * u[1], r[1] = f[2] * u[0] - f[0] * u[2], r[2] = f[0] * u[1] - f[1] * u[0];
    for (k = 0; k < 3; k++)
        lr += r[k] * r[k];
    for (k = 0; k < 3; k++)
        r[k] /= sqrt(lr);
    u[0] = r[1] * f[2] - r[2] * f[1], u[1] = r[2] * f[0] - r[0] * f[2], u[2] = r[0] * f[1] - r[1] * f[0];
    *depth = p[0] * f[0] + p[1] * f[1] + p[2] * f[2];
    *s = (p[0] * r[0] + p[1] * r[1] + p[2] * r[2]) / (*depth * th * aspect);
    *t = (p[0] * u[0] + p[1] * u[1] + p[2] * u[2]) / (*depth * th);
}

static void check_fit(lumo_pkg_info *info, uint32_t w, uint32_t h, int framed)
{
    lumo_raster_camera cam;
    double aspect = (double)w / h, widest = 0, s, t, d, nearest = 1e300;
    int c;

    assert_int_equal(lumo_scene_camera_fit(info, w, h), LUMO_OK);
    lumo_raster_camera_from_info(info, &cam);
    for (c = 0; c < 8; c++) {
        project(info, c, aspect, &s, &t, &d);
        assert_true(d > 0);
        assert_true(fabs(s) <= 1.0 && fabs(t) <= 1.0);
        if (fabs(s) > widest) widest = fabs(s);
        if (fabs(t) > widest) widest = fabs(t);
        if (d < nearest) nearest = d;
    }
    /* Framed tightly, not lost in the distance: the nearest distance with
     * every corner in view, plus 1/64, puts some corner near an edge. */
    if (framed && !(widest > 0.95))
        print_message("box %g,%g,%g .. %g,%g,%g in %ux%u: widest %g\n", q16(info->bmin[0]), q16(info->bmin[1]),
                      q16(info->bmin[2]), q16(info->bmax[0]), q16(info->bmax[1]), q16(info->bmax[2]), w, h, widest);
    assert_true(!framed || widest > 0.95);
    /* The near plane: in front of every corner, at half the nearest. */
    assert_true(q16(cam.znear) <= nearest);
    assert_true(cam.znear == LUMO_RASTER_ZNEAR || fabs(q16(cam.znear) - nearest / 2) <= 1e-3 * nearest + 1e-4);
}

static void test_fit_random_boxes(void **state)
{
    static const uint32_t sizes[][2] = {{320, 240}, {160, 128}, {128, 64}, {240, 320}, {64, 256}, {100, 100}};
    lumo_pkg_info info;
    int i;
    (void)state;

    for (i = 0; i < 3000; i++) {
        const uint32_t *sz = sizes[i % 6];
        random_box(&info, i % 3 == 0 ? 1 : 500, i % 5 == 0 ? 1000 : 20);
        check_fit(&info, sz[0], sz[1], 1);
    }
}

static void test_fit_refusals(void **state)
{
    lumo_pkg_info info, keep;
    (void)state;

    random_box(&info, 1, 1);
    keep = info;
    assert_int_equal(lumo_scene_camera_fit(&info, 0, 240), LUMO_ERR_ARG);
    assert_int_equal(lumo_scene_camera_fit(NULL, 320, 240), LUMO_ERR_ARG);
    info.bmin[1] = info.bmax[1] + 1;
    keep = info;
    assert_int_equal(lumo_scene_camera_fit(&info, 320, 240), LUMO_ERR_RANGE);
    assert_memory_equal(&info, &keep, sizeof info);
    /* A box near the edge of Q16.16: the eye would leave the range. */
    memset(&info, 0, sizeof info);
    info.bmin[0] = info.bmin[1] = info.bmin[2] = 20000 * LUMO_Q16_ONE;
    info.bmax[0] = info.bmax[1] = info.bmax[2] = 30000 * LUMO_Q16_ONE;
    keep = info;
    assert_int_equal(lumo_scene_camera_fit(&info, 320, 240), LUMO_ERR_RANGE);
    assert_memory_equal(&info, &keep, sizeof info);
    /* A point still gets a camera at a distance; a needle-thin portrait
     * frame an eye too far for Q16.16. */
    memset(&info, 0, sizeof info);
    check_fit(&info, 320, 240, 0);
    random_box(&info, 1, 1000);
    info.bmin[0] = -500 * LUMO_Q16_ONE, info.bmax[0] = 500 * LUMO_Q16_ONE;
    assert_int_equal(lumo_scene_camera_fit(&info, 1, 2048), LUMO_ERR_RANGE);
}

/* The near plane: half the nearest corner's view depth; the fixed minimum
 * when the eye is inside the box or eye == target. */
static void test_znear(void **state)
{
    lumo_raster_camera cam;
    lumo_q16_16 lo[3] = {-LUMO_Q16_ONE, 0, -LUMO_Q16_ONE}, hi[3] = {LUMO_Q16_ONE, 2 * LUMO_Q16_ONE, LUMO_Q16_ONE};
    (void)state;

    memset(&cam, 0, sizeof cam);
    cam.eye[1] = LUMO_Q16_ONE, cam.eye[2] = LUMO_Q16_FRAC(34, 10);   /* the Cornell box's camera */
    cam.target[1] = LUMO_Q16_ONE, cam.up[1] = LUMO_Q16_ONE, cam.fovy_deg = 40 * LUMO_Q16_ONE;
    /* nearest corner depth 3.4 - 1 = 2.4 -> 1.2 */
    assert_true(abs(lumo_raster_znear_for_box(&cam, lo, hi) - LUMO_Q16_FRAC(12, 10)) <= 2);
    cam.eye[2] = 0;   /* inside */
    cam.target[2] = -LUMO_Q16_ONE;
    assert_int_equal(lumo_raster_znear_for_box(&cam, lo, hi), LUMO_RASTER_ZNEAR);
    memcpy(cam.target, cam.eye, sizeof cam.eye);
    assert_int_equal(lumo_raster_znear_for_box(&cam, lo, hi), LUMO_RASTER_ZNEAR);
}

/* The server's fit (float scene bounds) is the client's, to float precision. */
static void test_server_fit_is_client_fit(void **state)
{
    lumo_pkg_info info;
    srv_camera sc;
    int i, k;
    (void)state;

    for (i = 0; i < 200; i++) {
        vec3 lo, hi;
        random_box(&info, 50, 50);
        lo = v3(q16(info.bmin[0]), q16(info.bmin[1]), q16(info.bmin[2]));
        hi = v3(q16(info.bmax[0]), q16(info.bmax[1]), q16(info.bmax[2]));
        assert_int_equal(srv_camera_fit(lo, hi, &sc), LUMO_OK);
        assert_int_equal(lumo_scene_camera_fit(&info, 1, 1), LUMO_OK);
        for (k = 0; k < 3; k++) {
            double scale = fabs(q16(info.eye[k])) + 1;
            assert_true(fabs(v3_get(sc.eye, k) - q16(info.eye[k])) <= 1e-6 * scale + 2 / 65536.0);
            assert_true(fabs(v3_get(sc.target, k) - q16(info.target[k])) <= 1e-6 * scale + 2 / 65536.0);
        }
        assert_true(sc.fovy_deg == 40.0f);
    }
    assert_int_equal(srv_camera_fit(v3(0, 0, 0), v3(40000, 1, 1), &sc), LUMO_ERR_RANGE);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fit_random_boxes),
        cmocka_unit_test(test_fit_refusals),
        cmocka_unit_test(test_znear),
        cmocka_unit_test(test_server_fit_is_client_fit),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
