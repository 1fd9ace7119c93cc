/*
 * test_server_scene.c — the bake's sense and bookkeeping (issue 3):
 * Cornell red/green sense, solid-vertex detection, same seed -> identical
 * results for 1 and 2 threads, quantized vs float IVG within the format's
 * error, package round trip through the client reader, and the importer's
 * and validator's errors.
 */
#include "test_common.h"
#include <stdlib.h>
#include "bake_fixture.h"
#include "lumo/package.h"
#include "scene/import.h"
#include "package/ivg_encode.h"
#include "package/package_write.h"
#include "test_ivg_entry.h"

static void cornell(bake_fixture *f, int n, int spp, uint64_t seed, int threads)
{
    char err[256];
    memset(f, 0, sizeof *f);
    srv_scene_init(&f->scene);
    assert_int_equal(srv_default_scene(&f->scene, NULL, err, sizeof err), 0);    /* sphere inside */
    int dims[3] = {n, n, n};
    srv_grid g = srv_grid_over(&f->scene, dims);
    fixture_bake(f, &g, spp, seed, threads);
}

/* Vertices one cell from the red wall (x = -1) get more red than green in
 * the hemisphere facing it (-x); mirrored for the green wall (+x). Only up
 * to y = 1.2: above y = 1.37 the spot (half angle 60 deg at y = 1.95) does
 * not light the walls and the white ceiling dominates both hemispheres. */
static void test_cornell_sense(void **state)
{
    (void)state;
    bake_fixture f;
    cornell(&f, 6, 256, 5, 2);
    int checked = 0;
    for (int k = 0; k < 6; k++)
        for (int j = 0; j < 4; j++) {
            size_t left = (size_t)(1 + 6 * (j + 6 * k)), right = (size_t)(4 + 6 * (j + 6 * k));
            if (!f.res.valid[left] || !f.res.valid[right])
                continue;
            assert_true(fixture_normal_component(&f, left, 1, 0) > fixture_normal_component(&f, left, 1, 1));
            assert_true(fixture_normal_component(&f, right, 0, 1) > fixture_normal_component(&f, right, 0, 0));
            checked++;
        }
    assert_true(checked >= 20);
    fixture_free(&f);
}

/* A solid cube inside a room: exactly the vertices inside it are invalid. */
static void test_solid_vertices(void **state)
{
    (void)state;
    bake_fixture f;
    memset(&f, 0, sizeof f);
    srv_scene_init(&f.scene);
    vec3 w = v3(0.7f, 0.7f, 0.7f);
    assert_int_equal(srv_add_box(&f.scene, "room", v3(-1, -1, -1), v3(1, 1, 1), w, 1), 0);
    assert_int_equal(srv_add_box(&f.scene, "cube", v3(-0.45f, -0.45f, -0.45f), v3(0.45f, 0.45f, 0.45f), w, 0), 0);
    srv_light l = {.kind = LUMO_LIGHT_POINT, .pos = {0, 0.8f, 0}, .power = v3(10, 10, 10)};
    assert_int_equal(srv_scene_add_light(&f.scene, &l), 0);
    int dims[3] = {9, 9, 9};   /* spacing 0.25: 3^3 vertices inside the cube */
    srv_grid g = srv_grid_over(&f.scene, dims);
    fixture_bake(&f, &g, 64, 1, 2);
    int invalid = 0;
    for (size_t v = 0; v < f.res.nverts; v++) {
        vec3 p = srv_grid_vertex(&g, (int)(v % 9), (int)(v / 9 % 9), (int)(v / 81));
        int inside = fabsf(p.x) < 0.45f && fabsf(p.y) < 0.45f && fabsf(p.z) < 0.45f;
        assert_int_equal(f.res.valid[v], !inside);
        invalid += !f.res.valid[v];
    }
    assert_int_equal(invalid, 27);
    fixture_free(&f);
}

/* The default scene with the scanned dragon (when installed): solid
 * vertices exist (the dragon is closed enough) and all lie inside the
 * dragon's bounding box; none on the room's walls. */
static void test_dragon_solid_only_inside(void **state)
{
    (void)state;
    bake_fixture f;
    char err[256];
    const char *path = "build/data/models/dragon_48k.ply";
    memset(&f, 0, sizeof f);
    srv_scene_init(&f.scene);
    assert_int_equal(srv_default_scene(&f.scene, path, err, sizeof err), 0);
    const srv_mesh *d = &f.scene.meshes[f.scene.nmeshes - 1];
    if (strcmp(d->name, "dragon")) {
        print_message("%s not present (run tools/setup.sh): skipped\n", path);
        srv_scene_free(&f.scene);
        skip();
    }
    vec3 lo = d->pos[0], hi = d->pos[0];
    for (uint32_t v = 1; v < d->nverts; v++)
        lo = v3_min(lo, d->pos[v]), hi = v3_max(hi, d->pos[v]);
    int dims[3] = {21, 21, 21};
    srv_grid g = srv_grid_over(&f.scene, dims);
    fixture_bake(&f, &g, 32, 1, 2);
    int solid = 0;
    for (size_t v = 0; v < f.res.nverts; v++) {
        if (f.res.valid[v])
            continue;
        vec3 p = srv_grid_vertex(&g, (int)(v % 21), (int)(v / 21 % 21), (int)(v / 441));
        assert_true(p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y && p.z >= lo.z && p.z <= hi.z);
        solid++;
    }
    assert_true(solid > 0);
    fixture_free(&f);
}

/* Same seed: identical floats for 1 and 2 threads; another seed differs. */
static void test_same_seed_same_bytes(void **state)
{
    (void)state;
    bake_fixture a, b, c;
    cornell(&a, 5, 32, 42, 1);
    cornell(&b, 5, 32, 42, 2);
    cornell(&c, 5, 32, 43, 2);
    size_t n = a.res.nverts * 6 * 9 * sizeof(float);
    assert_memory_equal(a.res.I, b.res.I, n);
    assert_memory_equal(a.res.valid, b.res.valid, a.res.nverts);
    assert_memory_not_equal(a.res.I, c.res.I, n);
    fixture_free(&a);
    fixture_free(&b);
    fixture_free(&c);
}

/* ---- package round trip and quantization -------------------------------- */

static uint8_t *bake_package(bake_fixture *f, size_t *len)
{
    srv_pkg_writer w;
    uint8_t *data = NULL;
    char err[256];
    srv_pkgw_init(&w);
    assert_int_equal(srv_pack_scene(&w, &f->scene, 1), 0);
    assert_int_equal(srv_pack_ivg(&w, &f->res, 32, 9, err, sizeof err), 0);
    assert_int_equal(srv_pkgw_serialize(&w, &data, len), 0);
    srv_pkgw_free(&w);
    return data;
}

static lumo_ivg *load_ivg(const lumo_package *pkg, lumo_ivg_form form, void **mem)
{
    lumo_ivg_desc d;
    lumo_arena arena;
    lumo_ivg *g;
    assert_int_equal(lumo_package_ivg_desc(pkg, &d), LUMO_OK);
    size_t bytes = lumo_ivg_memory_size(&d) + LUMO_ARENA_SLACK;
    *mem = malloc(bytes);
    lumo_arena_init(&arena, *mem, bytes);
    assert_int_equal(lumo_ivg_create(&g, &arena, &d), LUMO_OK);
    assert_int_equal(lumo_package_load_ivg(pkg, g, form, NULL), LUMO_OK);
    return g;
}

/* Decoded entries against the float compression of the bake: the float
 * form within the client's fixed-point steps, the quantized form within
 * 8-bit direction steps (0.5/127 per component) and RGB9E5's shared
 * exponent (half a mantissa step of the largest channel: max * 2^-9). */
static void test_quantized_vs_float(void **state)
{
    (void)state;
    bake_fixture f;
    cornell(&f, 5, 32, 9, 2);
    size_t len;
    uint8_t *data = bake_package(&f, &len);
    lumo_package pkg;
    void *mf, *mq;
    assert_int_equal(lumo_package_open(&pkg, data, len), LUMO_OK);
    lumo_ivg *gf = load_ivg(&pkg, LUMO_IVG_FORM_FLOAT, &mf), *gq = load_ivg(&pkg, LUMO_IVG_FORM_QUANTIZED, &mq);
    for (uint32_t v = 0; v < f.res.nverts; v++) {
        assert_int_equal(lumo_ivg_is_received(gf, v), f.res.valid[v]);
        assert_int_equal(lumo_ivg_is_received(gq, v), f.res.valid[v]);
        if (!f.res.valid[v])
            continue;
        for (int h = 0; h < 6; h++) {
            srv_ivg_fentry e;
            srv_ivg_compress((const float(*)[3]) & f.res.I[SRV_BAKE_I(v, h, 0)], (lumo_ivg_axis)h, &e);
            const lumo_ivg_entry *ef = IVG_ENTRY(gf, v, (lumo_ivg_axis)h);
            const lumo_ivg_entry *eq = IVG_ENTRY(gq, v, (lumo_ivg_axis)h);
            double cmax = fmax(e.c[0], fmax(e.c[1], e.c[2]));
            for (int k = 0; k < 3; k++) {
                /* the client stores binary32 records packed too (docs/ivg-format.md §2.5) */
                assert_close(ef->d[k] / 16384.0, e.d[k], 0.5 / 127 + 1.0 / 16384);
                assert_close(ef->c[k] / 65536.0, e.c[k], cmax / 512 + 1.0 / 65536);
                assert_close(eq->d[k] / 16384.0, e.d[k], 0.5 / 127 + 1.0 / 16384);
                assert_close(eq->c[k] / 65536.0, e.c[k], cmax / 512 + 1.0 / 65536);
            }
        }
    }
    free(mf);
    free(mq);
    free(data);
    fixture_free(&f);
}

static void test_package_round_trip(void **state)
{
    (void)state;
    bake_fixture f;
    cornell(&f, 4, 8, 1, 2);
    size_t len;
    uint8_t *data = bake_package(&f, &len);
    lumo_package pkg;
    lumo_pkg_info in;
    lumo_pkg_light l;
    assert_int_equal(lumo_package_open(&pkg, data, len), LUMO_OK);
    assert_int_equal(lumo_package_info(&pkg, &in), LUMO_OK);
    assert_int_equal(in.mesh_count, f.scene.nmeshes);
    assert_int_equal(in.light_count, 1);
    assert_int_equal(in.triangle_count, srv_scene_triangle_count(&f.scene));
    assert_int_equal(in.bmax[1], 2 * 65536);
    assert_int_equal(lumo_package_light(&pkg, 0, &l), LUMO_OK);
    assert_int_equal(l.kind, LUMO_LIGHT_SPOT);
    assert_int_equal(l.dir[1], -16384);
    assert_int_equal(l.cos_half, 8192);
    assert_int_equal(l.power[0], 40u * 65536u);
    for (uint32_t m = 0; m < in.mesh_count; m++) {
        lumo_pkg_mesh_info mi;
        const srv_mesh *sm = &f.scene.meshes[m];
        assert_int_equal(lumo_package_mesh_info(&pkg, m, &mi), LUMO_OK);
        assert_int_equal(mi.nverts, sm->nverts);
        lumo_q16_16 *pos = calloc(3 * mi.nverts, sizeof *pos);
        lumo_q1_14 *nrm = calloc(3 * mi.nverts, sizeof *nrm), *alb = calloc(3 * mi.nverts, sizeof *alb);
        uint32_t *tris = calloc(3 * mi.ntris, sizeof *tris);
        assert_int_equal(lumo_package_mesh_read(&pkg, m, pos, nrm, alb, tris), LUMO_OK);
        for (uint32_t v = 0; v < mi.nverts; v++) {
            assert_close(pos[3 * v] / 65536.0, sm->pos[v].x, 1.0 / 65536);
            assert_close(alb[3 * v + 1] / 16384.0, sm->albedo[v].y, 1.0 / 16384);
            double nl = sqrt((double)nrm[3 * v] * nrm[3 * v] + (double)nrm[3 * v + 1] * nrm[3 * v + 1] +
                             (double)nrm[3 * v + 2] * nrm[3 * v + 2]) / 16384.0;
            assert_close(nl, 1.0, 1e-3);
        }
        assert_memory_equal(tris, sm->tris, 3 * mi.ntris * sizeof *tris);
        free(pos), free(nrm), free(alb), free(tris);
    }
    /* One flipped byte anywhere: the package is refused. */
    for (size_t i = 0; i < len; i += 97) {
        data[i] ^= 0x10;
        assert_int_not_equal(lumo_package_open(&pkg, data, len), LUMO_OK);
        data[i] ^= 0x10;
    }
    free(data);
    fixture_free(&f);
}

/* ---- import and validation ----------------------------------------------- */

static void test_validate_errors(void **state)
{
    (void)state;
    srv_scene s;
    char err[256];
    srv_light l = {.kind = LUMO_LIGHT_POINT, .power = {1, 1, 1}};
    srv_scene_init(&s);
    assert_int_equal(srv_scene_validate(&s, err, sizeof err), LUMO_ERR_ARG);
    assert_non_null(strstr(err, "no geometry"));
    assert_int_equal(srv_add_quad(&s, "q", v3(0, 0, 0), v3(1, 0, 0), v3(0, 0, 1), v3(0.5f, 0.5f, 0.5f)), 0);
    assert_int_equal(srv_scene_validate(&s, err, sizeof err), LUMO_ERR_ARG);
    assert_non_null(strstr(err, "no light"));
    srv_scene_add_light(&s, &l);
    assert_int_equal(srv_scene_validate(&s, err, sizeof err), 0);
    s.meshes[0].pos[2] = s.meshes[0].pos[1];          /* zero-area face */
    assert_int_equal(srv_scene_validate(&s, err, sizeof err), LUMO_ERR_CORRUPT);
    assert_non_null(strstr(err, "zero area"));
    s.meshes[0].pos[2] = v3(NAN, 0, 0);
    assert_int_equal(srv_scene_validate(&s, err, sizeof err), LUMO_ERR_NONFINITE);
    assert_non_null(strstr(err, "non-finite"));
    srv_scene_free(&s);
}

static void test_parsers(void **state)
{
    (void)state;
    srv_light l;
    srv_camera c;
    char err[256];
    assert_int_equal(srv_light_parse("spot:0,2,0:0,-2,0:30:5,6,7", &l, err, sizeof err), 0);
    assert_int_equal(l.kind, LUMO_LIGHT_SPOT);
    assert_close(l.dir.y, -1.0, 1e-6);
    assert_close(l.cos_half, cos(M_PI / 6), 1e-6);
    assert_close(l.power.z, 7.0, 0.0);
    assert_int_equal(srv_light_parse("directional:0,-1,0:3,3,3", &l, err, sizeof err), 0);
    assert_int_equal(srv_light_parse("area:0,2,0:1,0,0:0,0,1:9,9,9", &l, err, sizeof err), 0);
    assert_close(l.dir.y, -1.0, 1e-6);   /* u x v: shines down */
    const char *bad[] = {"point:0,0,0", "point:0,0:1,1,1", "spot:0,0,0:0,0,0:30:1,1,1", "laser:0,0,0:1,1,1",
                         "point:0,0,0:1,1,-1", "point:nan,0,0:1,1,1", "point:0,0,0:1,1,1:4", ""};
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++)
        assert_int_equal(srv_light_parse(bad[i], &l, err, sizeof err), LUMO_ERR_ARG);
    assert_int_equal(srv_camera_parse("0,1,3.4:0,1,0:0,1,0:40", &c), 0);
    assert_int_equal(srv_camera_parse("0,1,0:0,1,0:0,1,0:40", &c), LUMO_ERR_ARG); /* eye == target */
    assert_int_equal(srv_camera_parse("0,0,0:0,1,0:0,1,0:40", &c), LUMO_ERR_ARG); /* up parallel */
    assert_int_equal(srv_camera_parse("0,1,3:0,1,0:0,1,0:180", &c), LUMO_ERR_ARG);
    /* The centre pixel looks at the target; the top row looks up. */
    assert_int_equal(srv_camera_parse("0,0,5:0,0,0:0,1,0:90", &c), 0);
    vec3 d = srv_camera_ray(&c, 100, 100, 50.0f, 50.0f);
    assert_close(d.z, -1.0, 1e-6);
    d = srv_camera_ray(&c, 100, 100, 50.0f, 0.0f);
    assert_close(d.y, sqrt(0.5), 1e-6);
    d = srv_camera_ray(&c, 200, 100, 200.0f, 50.0f);    /* right edge at aspect 2 */
    assert_close(d.x / -d.z, 2.0, 1e-5);
}

static void test_import_models(void **state)
{
    (void)state;
    srv_scene s;
    char err[512];
    srv_xform x = srv_xform_identity();
    srv_scene_init(&s);
    if (srv_import_file(&s, "build/data/models/bunny.obj", &x, NULL, err, sizeof err) == 0) {
        assert_true(srv_scene_triangle_count(&s) > 1000);
        assert_close(s.meshes[0].albedo[0].x, 0.8, 1e-6);   /* no material: lumo's default */
    } else {
        print_message("bunny.obj not present (run tools/setup.sh): %s\n", err);
    }
    /* glTF: base colour as albedo, a KHR_lights_punctual point light of
     * intensity 2 W/sr (Phi = 8 pi), placed by its node. */
    srv_scene_free(&s);
    assert_int_equal(srv_import_file(&s, "tests/server/data/tri_light.gltf", &x, NULL, err, sizeof err), 0);
    assert_int_equal(srv_scene_triangle_count(&s), 1);
    assert_close(s.meshes[0].albedo[0].y, 0.4, 1e-6);
    assert_close(s.meshes[0].albedo[2].z, 0.6, 1e-6);
    assert_int_equal(s.nlights, 1);
    assert_int_equal(s.lights[0].kind, LUMO_LIGHT_POINT);
    assert_close(s.lights[0].power.x, 8 * M_PI, 1e-4);
    assert_close(s.lights[0].pos.y, 1.0, 1e-6);
    assert_close(s.lights[0].pos.x, 0.3, 1e-6);
    /* PLY vertex colours become per-vertex albedo (clamped to 0.98). */
    srv_scene_free(&s);
    assert_int_equal(srv_import_file(&s, "tests/server/data/colours.ply", &x, NULL, err, sizeof err), 0);
    assert_close(s.meshes[0].albedo[0].x, 0.98, 1e-6);
    assert_close(s.meshes[0].albedo[0].z, 0.0, 1e-6);
    assert_close(s.meshes[0].albedo[2].z, 0.98, 1e-6);
    assert_int_equal(srv_import_file(&s, "build/nonexistent.obj", &x, NULL, err, sizeof err),
                     LUMO_ERR_IO);
    assert_non_null(strstr(err, "no such file"));
    srv_scene_free(&s);
}

static void test_scene_file(void **state)
{
    (void)state;
    srv_scene s;
    char err[512];
    srv_scene_init(&s);
    assert_int_equal(srv_scene_load(&s, "tests/server/data/scene.txt", err, sizeof err), 0);
    /* 2 meshes + quad + 6 box faces + sphere + the area light's emitter */
    assert_int_equal(s.nmeshes, 11);
    assert_int_equal(s.nlights, 2);
    assert_true(s.has_camera);
    assert_close(s.camera.fovy_deg, 45.0, 0.0);
    /* scale 2, rotate 90 deg about y, translate: (0,0,1) -> (0,0,2) -> (2,0,0) -> (3,0,0) */
    assert_close(s.meshes[0].pos[1].x, 3.0, 1e-5);
    assert_close(s.meshes[0].pos[1].z, 0.0, 1e-5);
    assert_close(s.meshes[0].albedo[0].x, 0.98, 1e-6);      /* vertex colour */
    assert_close(s.meshes[1].pos[1].y, 5.0, 1e-6);
    assert_close(s.meshes[1].albedo[0].z, 0.3, 1e-6);       /* line override */
    assert_int_equal(s.meshes[10].emitter, 1);
    assert_int_equal(srv_scene_validate(&s, err, sizeof err), 0);
    srv_scene_free(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cornell_sense),      cmocka_unit_test(test_solid_vertices),
        cmocka_unit_test(test_dragon_solid_only_inside), cmocka_unit_test(test_same_seed_same_bytes),
        cmocka_unit_test(test_quantized_vs_float),
        cmocka_unit_test(test_package_round_trip), cmocka_unit_test(test_validate_errors),
        cmocka_unit_test(test_parsers),            cmocka_unit_test(test_import_models),
        cmocka_unit_test(test_scene_file),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
