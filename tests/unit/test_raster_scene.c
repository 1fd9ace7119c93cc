/*
 * test_raster_scene.c — lumo-render's scene conversion (tools/lumo-render/
 * scene_convert.h): camera and light strings through the server's parsers
 * into the rasterizer's fixed point, package and area lights, and whole
 * server scenes (the default scene, an assimp-imported model, welding and
 * normals, bad meshes, too many lights).
 */
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>
#include "test_common.h"
#include "lumo/raster.h"
#include "scene/import.h"
#include "scene/shapes.h"
#include "../../tools/lumo-render/mesh_build.h"
#include "../../tools/lumo-render/scene_convert.h"

static void assert_q16_3(const lumo_q16_16 got[3], double x, double y, double z)
{
    assert_int_equal(got[0], host_q16(x));
    assert_int_equal(got[1], host_q16(y));
    assert_int_equal(got[2], host_q16(z));
}

/* |n| of a Q1.14 normal, in units of 1. */
static double q14_len(const lumo_q1_14 *n)
{
    return sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]) / 16384.0;
}

static void test_camera_strings(void **state)
{
    static const char *bad[] = {"1,2,3", "0,0,0:0,0,0:0,1,0:40", "0,1,3:0,1,0:0,0,1:40", "0,1,3:0,1,0:0,1,0:0",
                                "0,1,3:0,1,0:0,1,0:180", "0,1,3:0,1,0:0,1,0:40 ", "inf,1,3:0,1,0:0,1,0:40",
                                "0,1,3:0,1,0:0,1,0:40:5", "x,1,3:0,1,0:0,1,0:40"};
    lumo_raster_camera cam, keep;
    size_t i;
    (void)state;

    assert_int_equal(host_camera_from_string("0,1,3.4:0,1,0:0,1,0:40", &cam), LUMO_OK);
    assert_q16_3(cam.eye, 0, 1, 3.4);
    assert_q16_3(cam.target, 0, 1, 0);
    assert_q16_3(cam.up, 0, 1, 0);
    assert_int_equal(cam.fovy_deg, 40 << 16);
    assert_int_equal(cam.znear, host_q16(0.01));
    /* the rasterizer's limits of the field of view: [1, 179] */
    assert_int_equal(host_camera_from_string("0,1,3:0,1,0:0,1,0:1", &cam), LUMO_OK);
    assert_int_equal(host_camera_from_string("0,1,3:0,1,0:0,1,0:179", &cam), LUMO_OK);
    assert_int_equal(host_camera_from_string("0,1,3:0,1,0:0,1,0:0.5", &cam), LUMO_ERR_RANGE);
    assert_int_equal(host_camera_from_string("0,1,3:0,1,0:0,1,0:179.5", &cam), LUMO_ERR_RANGE);
    /* malformed or degenerate: refused, the output untouched */
    memset(&keep, 0x5A, sizeof keep);
    for (i = 0; i < sizeof bad / sizeof *bad; i++) {
        cam = keep;
        if (host_camera_from_string(bad[i], &cam) == LUMO_OK)
            fail_msg("camera '%s' accepted", bad[i]);
        assert_memory_equal(&cam, &keep, sizeof cam);
    }
}

static void test_light_strings(void **state)
{
    static const char *bad[] = {"point:1,2,3", "point:0,1,0:-1,1,1", "directional:0,0,0:1,1,1",
                                "spot:0,1,0:0,0,0:30:1,1,1", "spot:0,1,0:0,-1,0:0:1,1,1", "lamp:0,1,0:1,1,1",
                                "point:0,1,0:1,1,1,1", "area:0,0,0:1,0,0:2,0,0:1,1,1"};
    lumo_raster_light l, keep;
    double a = sqrt(1 + 1 + 0.09);
    size_t i;
    (void)state;

    assert_int_equal(host_light_from_string("point:1,2,1.5:30,25,20", &l), LUMO_OK);
    assert_int_equal(l.kind, LUMO_LIGHT_POINT);
    assert_q16_3(l.pos, 1, 2, 1.5);
    assert_int_equal(l.value[0], 30u << 16);
    assert_int_equal(l.value[1], 25u << 16);
    assert_int_equal(l.value[2], 20u << 16);

    assert_int_equal(host_light_from_string("spot:-1,1.5,0.5:1,-1,-0.3:25:40,40,60", &l), LUMO_OK);
    assert_int_equal(l.kind, LUMO_LIGHT_SPOT);
    assert_q16_3(l.pos, -1, 1.5, 0.5);
    assert_true(abs(l.dir[0] - host_q14(1 / a)) <= 1);
    assert_true(abs(l.dir[1] - host_q14(-1 / a)) <= 1);
    assert_true(abs(l.dir[2] - host_q14(-0.3 / a)) <= 1);
    assert_true(abs(l.cos_cutoff - host_q14(cos(25 * M_PI / 180))) <= 1);
    assert_int_equal(l.value[2], 60u << 16);

    assert_int_equal(host_light_from_string("directional:0,-2,0:0.3,0.3,0.35", &l), LUMO_OK);
    assert_int_equal(l.kind, LUMO_LIGHT_DIRECTIONAL);
    assert_int_equal(l.dir[0], 0);
    assert_int_equal(l.dir[1], -16384);
    assert_int_equal(l.dir[2], 0);
    assert_int_equal(l.value[0], host_q16(0.3));
    assert_int_equal(l.value[2], host_q16(0.35));

    /* an area light is drawn as the client draws a package's: a spot at
     * the centre facing u x v, 90 degrees, point-equivalent power 2 Phi */
    assert_int_equal(host_light_from_string("area:-0.25,1.98,-0.25:0.5,0,0:0,0,0.5:20,20,20", &l), LUMO_OK);
    assert_int_equal(l.kind, LUMO_LIGHT_SPOT);
    assert_q16_3(l.pos, 0, 1.98, 0);
    assert_int_equal(l.dir[1], -16384);
    assert_int_equal(l.cos_cutoff, 0);
    assert_int_equal(l.value[0], 40u << 16);

    /* the server's limits: a 180-degree spot lights every direction */
    assert_int_equal(host_light_from_string("spot:0,1,0:0,-1,0:180:1,1,1", &l), LUMO_OK);
    assert_int_equal(l.cos_cutoff, -16384);
    /* powers saturate at the top of UQ16.16 */
    assert_int_equal(host_light_from_string("point:0,1,0:70000,1,1", &l), LUMO_OK);
    assert_int_equal(l.value[0], UINT32_MAX);

    memset(&keep, 0x5A, sizeof keep);
    for (i = 0; i < sizeof bad / sizeof *bad; i++) {
        l = keep;
        if (host_light_from_string(bad[i], &l) == LUMO_OK)
            fail_msg("light '%s' accepted", bad[i]);
        assert_memory_equal(&l, &keep, sizeof l);
    }
    assert_int_not_equal(host_light_from_string(NULL, &l), LUMO_OK);
}

/* The package rule (area light with a power past half the range). */
static void test_light_from_pkg(void **state)
{
    lumo_pkg_light p;
    lumo_raster_light l;
    int k;
    (void)state;

    memset(&p, 0, sizeof p);
    p.kind = LUMO_LIGHT_AREA;
    for (k = 0; k < 3; k++) {
        p.pos[k] = LUMO_Q16_ONE;
        p.u[k] = k == 0 ? 2 * LUMO_Q16_ONE : 0;
        p.v[k] = k == 2 ? 4 * LUMO_Q16_ONE : 0;
        p.power[k] = k == 0 ? 0x90000000u : 3 * LUMO_Q16_ONE;
    }
    p.dir[1] = -16384;
    p.cos_half = -16384;
    lumo_raster_light_from_pkg(&p, &l);
    assert_int_equal(l.kind, LUMO_LIGHT_SPOT);
    assert_q16_3(l.pos, 2, 1, 3);
    assert_int_equal(l.dir[1], -16384);
    assert_int_equal(l.cos_cutoff, 0);
    assert_int_equal(l.value[0], UINT32_MAX);
    assert_int_equal(l.value[1], 6 * LUMO_Q16_ONE);
    p.kind = LUMO_LIGHT_POINT;
    lumo_raster_light_from_pkg(&p, &l);
    assert_int_equal(l.kind, LUMO_LIGHT_POINT);
    assert_q16_3(l.pos, 1, 1, 1);
    assert_int_equal(l.value[1], 3 * LUMO_Q16_ONE);
}

/* A package's camera: the info's fields, the clients' near plane (the one
 * host_camera_from_srv gives a server camera). */
static void test_camera_from_info(void **state)
{
    lumo_pkg_info info;
    lumo_raster_camera c;
    srv_camera sc;
    lumo_raster_camera h;
    int k;
    (void)state;

    memset(&info, 0, sizeof info);
    for (k = 0; k < 3; k++) {
        info.eye[k] = (k + 1) * LUMO_Q16_ONE;
        info.target[k] = -k * LUMO_Q16_ONE / 2;
        info.up[k] = k == 1 ? LUMO_Q16_ONE : 0;
    }
    info.fovy_deg = 40 * LUMO_Q16_ONE;
    lumo_raster_camera_from_info(&info, &c);
    assert_q16_3(c.eye, 1, 2, 3);
    assert_int_equal(c.target[1], -LUMO_Q16_ONE / 2);
    assert_int_equal(c.up[1], LUMO_Q16_ONE);
    assert_int_equal(c.fovy_deg, 40 * LUMO_Q16_ONE);
    /* The near plane from the bounds (a point at the origin here): half
     * its view depth, (0,0,0)-(1,2,3) along the unit view direction. */
    {
        double f[3] = {-1, -2.5, -4}, lf = sqrt(1 + 6.25 + 16), w = (-1 * f[0] - 2 * f[1] - 3 * f[2]) / lf;
        assert_true(fabs(c.znear / 65536.0 - w / 2) < 1e-3);
    }
    assert_int_equal(srv_camera_parse("0,1,3:0,1,0:0,1,0:40", &sc), LUMO_OK);
    assert_int_equal(host_camera_from_srv(&sc, &h), LUMO_OK);
    assert_int_equal(h.znear, LUMO_RASTER_ZNEAR);
}

/* The server's default scene without its dragon: the walls, the sphere, the
 * documented spot light and camera, unit normals facing into the room and
 * out of the sphere. */
static void test_default_scene(void **state)
{
    srv_scene s;
    host_scene h;
    lumo_raster_light spot;
    lumo_raster_camera cam;
    char err[256];
    uint32_t v;
    (void)state;

    srv_scene_init(&s);
    assert_int_equal(srv_default_scene(&s, "/nonexistent/dragon.ply", err, sizeof err), LUMO_OK);
    assert_int_equal(host_scene_from_srv(&h, &s, err, sizeof err), LUMO_OK);
    assert_int_equal(h.mesh.tri_count, srv_scene_triangle_count(&s));
    assert_int_equal(h.mesh.vertex_count, 5 * 4 + s.meshes[5].nverts);
    assert_int_equal(h.light_count, 1);
    assert_int_equal(host_light_from_string("spot:0,1.95,0:0,-1,0:60:40,40,40", &spot), LUMO_OK);
    assert_memory_equal(&h.lights[0], &spot, sizeof spot);
    assert_int_equal(host_camera_from_string("0,1,3.4:0,1,0:0,1,0:40", &cam), LUMO_OK);
    cam.znear = lumo_raster_znear_for_box(&cam, h.bmin, h.bmax);   /* from the room's bounds */
    assert_true(cam.znear > LUMO_RASTER_ZNEAR);
    assert_memory_equal(&h.camera, &cam, sizeof cam);
    for (v = 0; v < h.mesh.vertex_count; v++) {
        const lumo_q16_16 *p = &h.mesh.pos[3 * v];
        const lumo_q1_14 *n = &h.mesh.normal[3 * v];
        assert_close(q14_len(n), 1.0, 3.0 / 16384);
        if (v < 4) {                                  /* the floor looks up */
            assert_int_equal(n[1], 16384);
            assert_int_equal(h.mesh.albedo[3 * v], host_q14(0.75));
        } else if (v >= 20) {                         /* the sphere looks out */
            double d[3] = {p[0] / 65536.0, p[1] / 65536.0 - 0.45, p[2] / 65536.0}, dot = 0;
            int k;
            for (k = 0; k < 3; k++)
                dot += d[k] / 0.45 * n[k] / 16384.0;
            assert_true(dot > 0.99);
            assert_int_equal(h.mesh.albedo[3 * v + 2], host_q14(0.45));
        }
    }
    host_scene_free(&h);
    srv_scene_free(&s);
}

/* An OBJ octahedron through the server's assimp import: assimp gives a
 * vertex per corner (24); the conversion welds them back to 6 with the
 * area-weighted normal of their 4 faces, pointing out along the axis. */
static void test_imported_model_welded(void **state)
{
    char path[] = "/tmp/lumo-test-octa-XXXXXX.obj", err[256];
    srv_xform x = srv_xform_identity();
    vec3 gold = v3(0.72f, 0.62f, 0.45f);
    srv_scene s;
    host_scene h;
    uint32_t v;
    FILE *f;
    int fd = mkstemps(path, 4), k;
    (void)state;

    assert_true(fd >= 0);
    f = fdopen(fd, "w");
    assert_non_null(f);
    fputs("v 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\n"
          "f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\nf 3 1 6\nf 2 3 6\nf 4 2 6\nf 1 4 6\n", f);
    fclose(f);
    srv_scene_init(&s);
    assert_int_equal(srv_import_file(&s, path, &x, &gold, err, sizeof err), LUMO_OK);
    unlink(path);
    assert_int_equal(s.nmeshes, 1);
    assert_int_equal(s.meshes[0].ntris, 8);
    assert_int_equal(host_scene_from_srv(&h, &s, err, sizeof err), LUMO_OK);
    assert_int_equal(h.mesh.vertex_count, 6);
    assert_int_equal(h.mesh.tri_count, 8);
    for (v = 0; v < 6; v++)
        for (k = 0; k < 3; k++) {
            assert_int_equal(h.mesh.normal[3 * v + k], h.mesh.pos[3 * v + k] / 4);   /* 65536 -> 16384 */
            assert_int_equal(h.mesh.albedo[3 * v + k], host_q14(k == 0 ? 0.72f : k == 1 ? 0.62f : 0.45f));
        }
    host_scene_free(&h);
    srv_scene_free(&s);
}

/* A ridge of two triangles with a vertex each per corner: with one albedo
 * the shared edge welds (4 vertices); with a colour seam it stays 6 vertices
 * but the edge's normals are still shared (smooth shading over the seam). */
static void test_weld_and_seam(void **state)
{
    static const float pos[6][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 1}, {1, 0, 0}, {0, 0, 0}, {0, -1, 1}};
    char err[256];
    int seam;
    (void)state;

    for (seam = 0; seam < 2; seam++) {
        srv_scene s;
        host_scene h;
        srv_mesh *m;
        uint32_t v, i;
        srv_scene_init(&s);
        m = srv_scene_add_mesh(&s, "ridge", 6, 2);
        assert_non_null(m);
        for (v = 0; v < 6; v++) {
            m->pos[v] = v3(pos[v][0], pos[v][1], pos[v][2]);
            m->albedo[v] = seam && v >= 3 ? v3(0.9f, 0.1f, 0.1f) : v3(0.5f, 0.5f, 0.5f);
            m->tris[v] = v;
        }
        assert_int_equal(host_scene_from_srv(&h, &s, err, sizeof err), LUMO_OK);
        assert_int_equal(h.mesh.vertex_count, seam ? 6 : 4);
        assert_int_equal(h.mesh.tri_count, 2);
        /* vertices on the edge (y = 0, z = 0) share the mean normal (0, 0, 1) */
        for (i = 0; i < 3 * h.mesh.tri_count; i++) {
            uint32_t w = h.mesh.tris[i];
            const lumo_q16_16 *p = &h.mesh.pos[3 * w];
            const lumo_q1_14 *n = &h.mesh.normal[3 * w];
            if (p[1] == 0 && p[2] == 0) {
                assert_int_equal(n[0], 0);
                assert_int_equal(n[1], 0);
                assert_int_equal(n[2], 16384);
            }
        }
        host_scene_free(&h);
        srv_scene_free(&s);
    }
}

static void test_bad_scenes(void **state)
{
    srv_light pl = {.kind = LUMO_LIGHT_POINT, .pos = {0, 1, 0}, .power = {1, 1, 1}};
    char err[256];
    srv_scene s;
    host_scene h;
    srv_mesh *m;
    int i;
    (void)state;

    srv_scene_init(&s);
    for (i = 0; i <= LUMO_MAX_LIGHTS; i++)
        assert_int_equal(srv_scene_add_light(&s, &pl), LUMO_OK);
    assert_int_equal(host_scene_from_srv(&h, &s, err, sizeof err), LUMO_ERR_LIMIT);
    assert_non_null(strstr(err, "lights"));
    srv_scene_free(&s);

    srv_scene_init(&s);
    m = srv_scene_add_mesh(&s, "broken", 3, 1);
    assert_non_null(m);
    m->tris[0] = 0; m->tris[1] = 1; m->tris[2] = 3;
    assert_int_equal(host_scene_from_srv(&h, &s, err, sizeof err), LUMO_ERR_RANGE);
    assert_non_null(strstr(err, "broken"));
    assert_null(h.mesh.pos);
    srv_scene_free(&s);

    srv_scene_init(&s);
    s.camera.fovy_deg = 0.5f;
    assert_int_equal(host_scene_from_srv(&h, &s, err, sizeof err), LUMO_ERR_RANGE);
    srv_scene_free(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_camera_strings),
        cmocka_unit_test(test_light_strings),
        cmocka_unit_test(test_light_from_pkg),
        cmocka_unit_test(test_camera_from_info),
        cmocka_unit_test(test_default_scene),
        cmocka_unit_test(test_imported_model_welded),
        cmocka_unit_test(test_weld_and_seam),
        cmocka_unit_test(test_bad_scenes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
