/*
 * test_model_check.c — lumo's front end of the model importer (issue 24):
 * declared counts against the file size, face lists, indices refused not
 * remapped, coordinates bounded, the file itself; and through
 * srv_import_file, that what passes imports as it should and what is
 * refused leaves the scene untouched. tests/hostile/ runs the same classes
 * through the tools.
 */
#include "test_common.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>
#include "scene/import.h"
#include "scene/model_check.h"

static char g_err[256];

static lumo_status check(const char *name, const char *text)
{
    const uint8_t *d = (const uint8_t *)text;
    size_t n = strlen(text);
    g_err[0] = 0;
    return srv_model_check_bytes(name, d, n, srv_model_format_of(name, d, n), g_err, sizeof g_err);
}

static void assert_says(const char *what)
{
    if (!strstr(g_err, what))
        fail_msg("'%s' does not say '%s'", g_err, what);
}

static void test_declared_counts(void **state)
{
    (void)state;
    assert_int_equal(check("a.off", "OFF\n3 1000000000 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"), LUMO_ERR_TRUNCATED);
    assert_says("a.off: the header declares 3 vertices and 1000000000 faces: at least 8000000018 bytes");
    assert_int_equal(check("a.ply", "ply\nformat ascii 1.0\nelement vertex 1000000000\nproperty float x\n"
                                    "end_header\n0\n"), LUMO_ERR_TRUNCATED);
    assert_says("element 'vertex' declares 1000000000 items");
    assert_int_equal(check("a.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
                                    "property float y\nproperty float z\nelement face 2\n"
                                    "property list uchar int vertex_indices\nend_header\n"), LUMO_ERR_TRUNCATED);
    assert_says("'vertex' declares 3 items: with those before it at least 36 bytes, the file holds 0");
}

static void test_faces_and_indices(void **state)
{
    (void)state;
    const char *head = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n";
    char buf[256];
    snprintf(buf, sizeof buf, "%s3 0 1 3\n", head);
    assert_int_equal(check("i.off", buf), LUMO_ERR_RANGE);   /* assimp would remap it to vertex 2 */
    assert_says("i.off: line 6: face 0: vertex index 3 is outside [0, 3)");
    snprintf(buf, sizeof buf, "%s10 0 1 2 0 1 2 0 1 2 0\n", head);
    assert_int_equal(check("i.off", buf), LUMO_ERR_CORRUPT);   /* assimp would drop it */
    assert_says("face 0 has 10 vertices (3 to 9 are read)");
    assert_int_equal(check("i.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n"), LUMO_ERR_RANGE);
    assert_says("line 4: vertex index -4: only 3 vertexs so far");
    assert_int_equal(check("i.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -3\n"), LUMO_OK);
}

static void test_coordinates(void **state)
{
    (void)state;
    assert_int_equal(check("c.obj", "v 1e38 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\n"), LUMO_ERR_RANGE);
    assert_says("c.obj: line 1: vertex 1: x = 1e+38 is beyond the 1e6 m coordinate bound");
    assert_int_equal(check("c.off", "OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n"), LUMO_ERR_NONFINITE);
    assert_says("vertex 1: y = nan is not finite");
    float xyz[6] = {0, 0, 0, 1, 2, INFINITY};
    assert_int_equal(srv_model_check_positions("m.gltf", 2, xyz, 2, g_err, sizeof g_err), LUMO_ERR_NONFINITE);
    assert_says("m.gltf: mesh 2, vertex 1: z = inf is not finite");
    xyz[5] = 3;
    assert_int_equal(srv_model_check_positions("m.gltf", 2, xyz, 2, g_err, sizeof g_err), LUMO_OK);
}

static void test_binary_ply_face_list(void **state)
{
    (void)state;
    static const char head[] = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
                               "property float y\nproperty float z\nelement face 1\n"
                               "property list uchar int vertex_indices\nend_header\n";
    uint8_t buf[512];
    size_t n = sizeof head - 1;
    memcpy(buf, head, n);
    memset(buf + n, 0, 36), n += 36;
    buf[n++] = 255;                      /* the count byte of the segfault */
    for (int i = 0; i < 3; i++)
        buf[n++] = (uint8_t)i, buf[n++] = 0, buf[n++] = 0, buf[n++] = 0;
    assert_int_equal(srv_model_check_bytes("f.ply", buf, n, SRV_MODEL_PLY, g_err, sizeof g_err), LUMO_ERR_TRUNCATED);
    assert_says("face 0: the data ends inside its list of 255 items");
    buf[n - 13] = 3;
    assert_int_equal(srv_model_check_bytes("f.ply", buf, n, SRV_MODEL_PLY, g_err, sizeof g_err), LUMO_OK);
}

static void test_formats(void **state)
{
    (void)state;
    assert_int_equal(srv_model_format_of("X.OBJ", NULL, 0), SRV_MODEL_OBJ);
    assert_int_equal(srv_model_format_of("x", (const uint8_t *)"ply\nformat", 10), SRV_MODEL_PLY);
    assert_int_equal(srv_model_format_of("x", (const uint8_t *)"OFF\n", 4), SRV_MODEL_OFF);
    assert_int_equal(srv_model_format_of("x.glb", (const uint8_t *)"glTF", 4), SRV_MODEL_GLB);
    assert_int_equal(srv_model_format_of("x", (const uint8_t *)"glTF", 4), SRV_MODEL_GLB);
    assert_int_equal(srv_model_format_of("x.dae", (const uint8_t *)"<?xml", 5), SRV_MODEL_OTHER);
    assert_int_equal(check("e.obj", ""), LUMO_ERR_CORRUPT);
    assert_says("e.obj: empty file");
    assert_int_equal(check("t.obj", "v 0 0 0\n\x1a\n"), LUMO_ERR_CORRUPT);
    assert_says("byte 8 is 0x1a: not a text file");
}

static const char *write_tmp(const char *name, const char *text)
{
    static char path[256];
    snprintf(path, sizeof path, "%s/lumo-test-%d-%s", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp", (int)getpid(),
             name);
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
    return path;
}

/* Through the importer: a quad imports as two triangles; a refused file
 * leaves the scene as it was. */
static void test_import_front_end(void **state)
{
    (void)state;
    srv_scene s;
    srv_xform x = srv_xform_identity();
    srv_scene_init(&s);
    const char *p = write_tmp("q.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n");
    assert_int_equal(srv_import_file(&s, p, &x, NULL, g_err, sizeof g_err), LUMO_OK);
    remove(p);
    assert_int_equal(srv_scene_triangle_count(&s), 2);
    p = write_tmp("bad.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n");
    assert_int_equal(srv_import_file(&s, p, &x, NULL, g_err, sizeof g_err), LUMO_ERR_RANGE);
    remove(p);
    assert_says("vertex index 5 is outside [0, 3)");
    assert_int_equal(s.nmeshes, 1);
    p = write_tmp("bad.xyz", "1 2 3\n");
    assert_int_equal(srv_import_file(&s, p, &x, NULL, g_err, sizeof g_err), LUMO_ERR_UNSUPPORTED);
    remove(p);
    assert_says("unknown model format");
    assert_int_equal(srv_import_file(&s, "/", &x, NULL, g_err, sizeof g_err), LUMO_ERR_IO);
    assert_says("/: a directory, not a model file");
    srv_scene_free(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_declared_counts), cmocka_unit_test(test_faces_and_indices),
        cmocka_unit_test(test_coordinates), cmocka_unit_test(test_binary_ply_face_list),
        cmocka_unit_test(test_formats), cmocka_unit_test(test_import_front_end),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
