/*
 * gen_hostile.c — the hostile corpus of tests/hostile/hostile.sh, made at
 * test time (no stored binaries): bad models (OFF, ASCII and binary PLY,
 * OBJ), scene files, and checksum-valid packages rewritten from a real
 * bake with hostile lights, IVG descriptors and doubled chunks.
 *
 *   gen_hostile OUTDIR LIGHTS.lumo
 *
 * writes the files into OUTDIR and one line per case into
 * OUTDIR/manifest: "KIND<TAB>FILE<TAB>EXPECTED", KIND being model, scene
 * or package (hostile.sh knows which tools read each), EXPECTED the text
 * the refusal must contain.
 */
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "lumo/package.h"
#include "lumo/wire.h"
#include "corpus.h"


/* ---- models ------------------------------------------------------------------ */

static const char *const k_bad_values[] = {"nan", "inf", "-inf", "1e38", "-3e7", "1.5e6"};
static const char *const k_bad_why[] = {"not finite", "not finite", "not finite", "beyond", "beyond", "beyond"};

/* A valid three-vertex OFF with vertex v's axis a replaced by val. */
static void off_coords(void)
{
    char name[64], expect[96];
    for (unsigned b = 0; b < sizeof k_bad_values / sizeof *k_bad_values; b++)
        for (int v = 0; v < 3; v++)
            for (int a = 0; a < 3; a++) {
                const char *c[9] = {"0", "0", "0", "1", "0", "0", "0", "1", "0"};
                c[3 * v + a] = k_bad_values[b];
                snprintf(name, sizeof name, "coord_%u_%d_%d.off", b, v, a);
                snprintf(expect, sizeof expect, "vertex %d: %c = ", v, "xyz"[a]);
                corpus_text("model", name, expect, "OFF\n3 1 0\n%s %s %s\n%s %s %s\n%s %s %s\n3 0 1 2\n", c[0], c[1],
                          c[2], c[3], c[4], c[5], c[6], c[7], c[8]);
                (void)k_bad_why;
            }
}

static void off_headers(void)
{
    static const struct { const char *name, *text, *expect; } k[] = {
        {"huge_faces.off", "OFF\n3 1000000000 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "1000000000 faces: at least"},
        {"huge_verts.off", "OFF\n1000000000 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "1000000000 vertices"},
        {"max_counts.off", "OFF\n4294967295 4294967295 0\n0 0 0\n", "4294967295 vertices"},
        {"over_counts.off", "OFF\n4294967296 1 0\n0 0 0\n", "not a count"},
        {"neg_counts.off", "OFF\n-3 1 0\n0 0 0\n", "not a count"},
        {"no_faces.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n", "nothing to draw"},
        {"no_header.off", "3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "no OFF header"},
        {"binary.off", "OFF BINARY\n3 1 0\n", "binary OFF"},
        {"four.off", "4OFF\n3 1 0\n0 0 0 1\n1 0 0 1\n0 1 0 1\n3 0 1 2\n", "homogeneous"},
        {"idx_past.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "vertex index 3 is outside [0, 3)"},
        {"idx_far.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 4000000000\n", "vertex index 4000000000"},
        {"idx_neg.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", "vertex index -1"},
        {"idx_word.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 one 2\n", "not an integer"},
        {"face_2.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n# padding: the header's byte bound holds, the line checks speak\n", "has 2 vertices"},
        {"face_0.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n0\n# padding: the header's byte bound holds, the line checks speak\n", "has 0 vertices"},
        {"face_10.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n10 0 1 2 0 1 2 0 1 2 0\n", "has 10 vertices"},
        {"face_255.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n255 0 1 2\n", "has 255 vertices"},
        {"face_short.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n", "index 3 is missing"},
        {"vert_short.off", "OFF\n3 1 0\n0 0 0\n1 0\n0 1 0\n3 0 1 2\n# padding: the header's byte bound holds, the line checks speak\n", "z is missing"},
        {"few_lines.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "at least 34 bytes, the file holds 26"},
        {"few_lines_pad.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n\n\n\n\n\n\n\n\n\n\n",
         "the file ends after 3 of 3 vertices and 1 of 2 faces"},
    };
    for (size_t i = 0; i < sizeof k / sizeof *k; i++)
        corpus_text("model", k[i].name, k[i].expect, "%s", k[i].text);
}

/* Every prefix of a valid OFF that cuts into its data is refused. */
static void off_truncated(void)
{
    static const char full[] = "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n";
    char name[64];
    size_t n = sizeof full - 1;
    for (size_t cut = 1; cut + 2 < n; cut += 2) {
        snprintf(name, sizeof name, "cut_%02zu.off", cut);
        corpus_put("model", name, full, cut, "cut_");
    }
}

static const char k_ply_head[] =
    "ply\nformat %s 1.0\nelement vertex %s\nproperty float x\nproperty float y\nproperty float z\n"
    "element face %s\nproperty list %s int vertex_indices\nend_header\n";

static void ply_ascii(void)
{
    static const struct { const char *name, *nv, *nf, *body, *expect; } k[] = {
        {"huge_verts_a.ply", "1000000000", "1", "0 0 0\n", "'vertex' declares 1000000000 items"},
        {"huge_faces_a.ply", "3", "1000000000", "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "'face' declares 1000000000"},
        {"idx_past_a.ply", "3", "1", "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "vertex index 3 is outside [0, 3)"},
        {"idx_neg_a.ply", "3", "1", "0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", "vertex index -1"},
        {"idx_frac_a.ply", "3", "1", "0 0 0\n1 0 0\n0 1 0\n3 0 1.5 2\n", "vertex index"},
        {"list_255_a.ply", "3", "1", "0 0 0\n1 0 0\n0 1 0\n255 0 1 2\n", "its list of 255 items"},
        {"list_2_a.ply", "3", "1", "0 0 0\n1 0 0\n0 1 0\n2 0 1\n", "a list of 2 items"},
        {"nan_a.ply", "3", "1", "0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n", "vertex 1: x = nan is not finite"},
        {"big_a.ply", "3", "1", "0 0 0\n1 1e38 0\n0 1 0\n3 0 1 2\n", "vertex 1: y = 1e+38 is beyond"},
        {"word_a.ply", "3", "1", "0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n", "vertex 1: 'zero' is not a number"},
    };
    char head[512];
    for (size_t i = 0; i < sizeof k / sizeof *k; i++) {
        snprintf(head, sizeof head, k_ply_head, "ascii", k[i].nv, k[i].nf, "uchar");
        corpus_text("model", k[i].name, k[i].expect, "%s%s", head, k[i].body);
    }
    corpus_text("model", "no_end_a.ply", "no end_header", "ply\nformat ascii 1.0\nelement vertex 3\n");
    corpus_text("model", "no_format_a.ply", "no format line", "ply\nelement vertex 0\nend_header\n");
    corpus_text("model", "bad_type_a.ply", "a known type", "ply\nformat ascii 1.0\nelement vertex 1\n"
              "property quad x\nend_header\n0\n");
    corpus_text("model", "no_magic_a.ply", "no 'ply' magic", "plx\nformat ascii 1.0\nend_header\n");
}

/* Binary PLY: three float vertices, one face whose list count byte is
 * `count` but which holds `held` int indices (the crash: 255 over 3). */
static void ply_binary_face(const char *name, const char *fmt, unsigned count, unsigned held, const int32_t *idx,
                            const float *xyz, const char *expect)
{
    uint8_t buf[1024];
    int h = snprintf((char *)buf, sizeof buf, k_ply_head, fmt, "3", "1", "uchar");
    size_t n = (size_t)h;
    int be = !strcmp(fmt, "binary_big_endian");
    for (int i = 0; i < 9; i++) {
        uint32_t w;
        memcpy(&w, &xyz[i], 4);
        for (int b = 0; b < 4; b++)
            buf[n++] = (uint8_t)(w >> (be ? 24 - 8 * b : 8 * b));
    }
    buf[n++] = (uint8_t)count;
    for (unsigned k = 0; k < held; k++)
        for (int b = 0; b < 4; b++)
            buf[n++] = (uint8_t)((uint32_t)idx[k] >> (be ? 24 - 8 * b : 8 * b));
    corpus_put("model", name, buf, n, expect);
}

static void ply_binary(void)
{
    static const float good[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    static const int32_t tri[3] = {0, 1, 2}, past[3] = {0, 1, 3}, neg[3] = {0, -7, 2}, big[3] = {0, 1, 0x7fffffff};
    static const char *const fmts[2] = {"binary_little_endian", "binary_big_endian"};
    char name[64];
    for (int e = 0; e < 2; e++) {
        const char *f = fmts[e];
        snprintf(name, sizeof name, "list_255_%d.ply", e);
        ply_binary_face(name, f, 255, 3, tri, good, "its list of 255 items");
        snprintf(name, sizeof name, "list_4_%d.ply", e);
        ply_binary_face(name, f, 4, 3, tri, good, "its list of 4 items");
        snprintf(name, sizeof name, "list_0_%d.ply", e);
        ply_binary_face(name, f, 0, 0, tri, good, "a list of 0 items");
        snprintf(name, sizeof name, "idx_past_%d.ply", e);
        ply_binary_face(name, f, 3, 3, past, good, "vertex index 3 is outside [0, 3)");
        snprintf(name, sizeof name, "idx_neg_%d.ply", e);
        ply_binary_face(name, f, 3, 3, neg, good, "vertex index -7");
        snprintf(name, sizeof name, "idx_big_%d.ply", e);
        ply_binary_face(name, f, 3, 3, big, good, "vertex index 2147483647");
        for (int v = 0; v < 9; v++) {
            float bad[9];
            static const float vals[3] = {NAN, INFINITY, 1e38f};
            for (int k = 0; k < 3; k++) {
                memcpy(bad, good, sizeof bad);
                bad[v] = vals[k];
                snprintf(name, sizeof name, "coord_%d_%d_%d.ply", e, v, k);
                char expect[64];
                snprintf(expect, sizeof expect, "vertex %d: %c = ", v / 3, "xyz"[v % 3]);
                ply_binary_face(name, f, 3, 3, tri, bad, expect);
            }
        }
    }
    char head[512];
    snprintf(head, sizeof head, k_ply_head, "binary_little_endian", "1000000000", "1000000000", "uchar");
    corpus_text("model", "huge_b.ply", "'vertex' declares 1000000000 items", "%s%s", head, "\1\2\3\4\5\6\7\10");
    snprintf(head, sizeof head, k_ply_head, "binary_little_endian", "3", "4000000000", "uint");
    corpus_text("model", "huge_faces_b.ply", "'face' declares 4000000000", "%s%036d", head, 0);
}

static void obj_cases(void)
{
    static const struct { const char *name, *text, *expect; } k[] = {
        {"big.obj", "v 1e38 0 0\nv 0 1e38 0\nv 0 0 1\nf 1 2 3\n", "vertex 1: x = 1e+38 is beyond"},
        {"nan.obj", "v 0 0 0\nv nan 1 0\nv 0 0 1\nf 1 2 3\n", "vertex 2: x = nan is not finite"},
        {"inf.obj", "v 0 0 0\nv 1 0 0\nv 0 0 -inf\nf 1 2 3\n", "vertex 3: z = -inf is not finite"},
        {"idx_past.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "vertex index 4: only 3 vertexs"},
        {"idx_zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "vertex index 0"},
        {"idx_neg.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n", "vertex index -4"},
        {"idx_ahead.obj", "v 0 0 0\nf 1 2 3\nv 1 0 0\nv 0 1 0\n", "vertex index 2: only 1"},
        {"vt_past.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/1\n", "texture coordinate index 2"},
        {"vn_past.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//1 2//1 3//1\n", "normal index 1"},
        {"slots.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nf 1/1/1/1 2 3\n", "more than three slots"},
        {"word.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 two 3\n", "'two' is not a vertex index"},
        {"short_v.obj", "v 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "z is missing"},
        {"face_2.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", "a face needs 3"},
        {"no_v.obj", "# nothing\nf 1 2 3\n", "vertex index 1: only 0"},
        {"empty_v.obj", "# only a comment\n", "no vertex"},
        {"mtl_dev.obj", "mtllib /dev/zero\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
         "line 1: mtllib '/dev/zero' is not a regular file"},
        {"mtl_dir.obj", "mtllib .\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "mtllib '.' is not a regular file"},
    };
    static const char nul[] = "v 0 0 0\nv 1 0\0 0\n", png[] = "\x89PNG\r\n\x1a\n\0\0\0\rIHDR";
    for (size_t i = 0; i < sizeof k / sizeof *k; i++)
        corpus_put("model", k[i].name, k[i].text, strlen(k[i].text), k[i].expect);
    corpus_put("model", "nul.obj", nul, sizeof nul - 1, "byte 13 is 0x00: not a text file");
    corpus_put("model", "png.obj", png, sizeof png - 1, "byte 6 is 0x1a: not a text file");
    char big[8192];
    size_t n = (size_t)snprintf(big, sizeof big, "v 0 0 0\nf");
    for (int i = 0; i < 1100 && n + 4 < sizeof big; i++)
        n += (size_t)snprintf(big + n, sizeof big - n, " 1");
    big[n++] = '\n';
    corpus_put("model", "corners.obj", big, n, "more than 1024 corners");
}

/* Sound models of every reader: each tool must still take them. */
static void good_cases(void)
{
    static const float xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    static const int32_t tri[3] = {0, 1, 2};
    char head[512];
    corpus_text("model", "good.off", "OK", "OFF\n# a quad\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n"
              "4 0 1 2 3\n");
    corpus_text("model", "good_c.off", "OK", "COFF 3 1 0\n0 0 0 1 1 1 1\n1 0 0 1 1 1 1\n0 1 0 1 1 1 1\n3 0 1 2\n");
    corpus_text("model", "good.obj", "OK", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n"
              "f 1/1/1 2/1/1 3/1/1\nf -4//-1 -2//-1 -1//-1\n");
    /* 1255 m: past 16 m, steps of 1e-6 vanish in single precision (the
     * Draco grid of lumo-pm build stepped forever); 40000 m: past Q16.16. */
    corpus_text("model", "far_ok.off", "OK", "OFF\n3 1 0\n0 0 0\n1255 0 0\n0 1 -900\n3 0 1 2\n");
    corpus_text("model", "far_q16.off", "x = 40000 m is beyond the client's", "OFF\n3 1 0\n0 0 0\n40000 0 0\n"
              "0 1 0\n3 0 1 2\n");
    snprintf(head, sizeof head, k_ply_head, "ascii", "3", "1", "uchar");
    corpus_text("model", "good_a.ply", "OK", "%s0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", head);
    ply_binary_face("good_le.ply", "binary_little_endian", 3, 3, tri, xyz, "OK");
    ply_binary_face("good_be.ply", "binary_big_endian", 3, 3, tri, xyz, "OK");
}

static void file_cases(void)
{
    corpus_put("model", "empty.obj", "", 0, "empty file");
    corpus_put("model", "empty.ply", "", 0, "empty file");
    corpus_put("model", "model.xyz", "1 2 3\n", 6, "unknown model format");
    corpus_put("model", "noext", "1 2 3\n", 6, "unknown model format");
    corpus_put("model", "image.png", "\x89PNG\r\n\x1a\n", 8, "unknown model format");
}

/* ---- scene files ------------------------------------------------------------ */

static void scene_cases(void)
{
    static const struct { const char *name, *text, *expect; } k[] = {
        {"s_mesh_off.txt", "mesh huge_faces.off\nlight point:0,1,0:1,1,1\n", "huge_faces.off: the header declares"},
        {"s_mesh_big.txt", "mesh big.obj\nlight point:0,1,0:1,1,1\n", "big.obj: line 1: vertex 1: x = 1e+38"},
        {"s_mesh_dir.txt", "mesh .\nlight point:0,1,0:1,1,1\n", "a directory"},
        {"s_mesh_none.txt", "mesh none.obj\n", "none.obj: no such file"},
        {"s_words.txt", "quad 0,0,0 1,0,0 0,0,1 albedo 1,1,1 albedo 1,1,1 albedo 1,1,1 albedo 1,1,1 albedo "
                        "1,1,1 albedo 1,1,1 albedo 1,1,1\n", "more than 16 words"},
        {"s_seg.txt", "sphere 0,0,0 1 segments 100000\n", "sphere: segments '100000' must be in [8, 1024]"},
        {"s_seg_big.txt", "sphere 0,0,0 1 segments 99999999999999999999\n", "segments '99999999999999999999' must be in [8, 1024]"},
        {"s_seg_word.txt", "sphere 0,0,0 1 segments many\n", "segments 'many' must be in [8, 1024]"},
        {"s_spheres.txt", "sphere 0,0,0 1 segments 1024\nsphere 0,0,0 2 segments 1024\nsphere 0,0,0 3 segments "
                          "1024\nsphere 0,0,0 4 segments 1024\nsphere 0,0,0 5 segments 1024\n",
         ":5: the description's spheres would hold 5232640 triangles, more than 4194304"},
        {"s_nan.txt", "quad nan,0,0 1,0,0 0,0,1\n", "quad: corner 'nan,0,0' is not 3 finite numbers X,Y,Z"},
        {"s_quad_v.txt", "quad 0,0,0 1,0,0 0,0\n", "quad: edge V '0,0' is not 3 finite numbers VX,VY,VZ"},
        {"s_quad_short.txt", "quad 0,0,0 1,0,0\n", "quad: edge V is missing (VX,VY,VZ)"},
        {"s_box.txt", "box 0,0,0 1,-1,1\n", "box: corner 0 0,0,0 must lie below corner 1 1,-1,1 on every axis"},
        {"s_sphere_r.txt", "sphere 0,0,0 -2\n", "sphere: radius '-2' is not a finite number above 0"},
        {"s_albedo.txt", "quad 0,0,0 1,0,0 0,0,1 albedo 1,x,1\n", "quad: albedo '1,x,1' is not 3 finite numbers R,G,B"},
        {"s_albedo_end.txt", "quad 0,0,0 1,0,0 0,0,1 albedo\n", "quad: albedo is missing (R,G,B)"},
        {"s_inward.txt", "quad 0,0,0 1,0,0 0,0,1 inward\n", "quad: unexpected 'inward'"},
        {"s_mesh_opt.txt", "mesh m.obj spin 3\n", "mesh: unknown option 'spin' (translate, scale, rotate, albedo)"},
        {"s_mesh_rot.txt", "mesh m.obj rotate 0,1,0\n", "mesh: rotate '0,1,0' is not 4 finite numbers AX,AY,AZ,DEG"},
        {"s_mesh_tr.txt", "mesh m.obj translate\n", "mesh: translate is missing (X,Y,Z)"},
        {"s_camera.txt", "quad 0,0,0 1,0,0 0,0,1\ncamera 0,1,0:0,1,0:0,1,0:40\n", ":2: camera '0,1,0:0,1,0:0,1,0:40': "},
        {"s_light_words.txt", "light point:0,1,0:1,1,1 extra\n", "light takes one word, got 2"},
        {"s_light.txt", "light point:0,nan,0:1,1,1\n", ":1:"},
        {"s_unknown.txt", "teapot 1\n", "unknown or malformed statement 'teapot'"},
    };
    static const char nul[] = "quad 0,0,0 1,0,0 0,0,1\nbox\0 0,0,0 1,1,1\n";
    for (size_t i = 0; i < sizeof k / sizeof *k; i++)
        corpus_put("scene", k[i].name, k[i].text, strlen(k[i].text), k[i].expect);
    corpus_put("scene", "s_nul.txt", nul, sizeof nul - 1, ":2: a NUL byte");
    static char longline[4096];
    memset(longline, 'x', sizeof longline - 2);
    longline[sizeof longline - 2] = '\n';
    corpus_put("scene", "s_long.txt", longline, sizeof longline - 1, "line longer than 2046");
}

/* ---- packages ---------------------------------------------------------------- */

typedef struct chunk {
    uint32_t type, len;
    uint8_t *p;
} chunk;

typedef struct pkg {
    uint8_t head[8];
    chunk   c[64];
    unsigned n;
} pkg;

static void pkg_read(pkg *k, const char *path)
{
    size_t size;
    FILE *f = fopen(path, "rb");
    static uint8_t data[1 << 22];
    lumo_package lp;
    size = f ? fread(data, 1, sizeof data, f) : 0;
    if (f)
        fclose(f);
    if (lumo_package_open(&lp, data, size) || lp.chunk_count > 64) {
        fprintf(stderr, "gen_hostile: %s: not a package to start from\n", path);
        exit(1);
    }
    memcpy(k->head, data, 8);
    k->n = lp.chunk_count;
    for (unsigned i = 0; i < k->n; i++) {
        lumo_pkg_chunk e;
        lumo_package_chunk(&lp, i, &e);
        k->c[i] = (chunk){e.type, e.length, malloc(e.length ? e.length : 1)};
        memcpy(k->c[i].p, data + e.offset, e.length);
    }
}

static void pkg_copy(pkg *dst, const pkg *src)
{
    *dst = *src;
    for (unsigned i = 0; i < src->n; i++) {
        dst->c[i].p = malloc(src->c[i].len ? src->c[i].len : 1);
        memcpy(dst->c[i].p, src->c[i].p, src->c[i].len);
    }
}

static void pkg_free(pkg *k)
{
    for (unsigned i = 0; i < k->n; i++)
        free(k->c[i].p);
}

static chunk *pkg_find(pkg *k, uint32_t type)
{
    for (unsigned i = 0; i < k->n; i++)
        if (k->c[i].type == type)
            return &k->c[i];
    return NULL;
}

/* The package with every CRC and offset right: only the content is hostile. */
static void pkg_write(const pkg *k, const char *name, const char *expect)
{
    static uint8_t out[1 << 22];
    size_t pos = LUMO_PKG_HEADER_SIZE + (size_t)k->n * LUMO_PKG_ENTRY_SIZE;
    memset(out, 0, pos);
    memcpy(out, k->head, 8);
    lumo_wire_put_le32(out + 8, k->n);
    for (unsigned i = 0; i < k->n; i++) {
        uint8_t *e = out + LUMO_PKG_HEADER_SIZE + (size_t)i * LUMO_PKG_ENTRY_SIZE;
        while (pos & 3)
            out[pos++] = 0;
        lumo_wire_put_le32(e, k->c[i].type);
        lumo_wire_put_le32(e + 4, (uint32_t)pos);
        lumo_wire_put_le32(e + 8, k->c[i].len);
        lumo_wire_put_le32(e + 12, lumo_wire_crc32(0, k->c[i].p, k->c[i].len));
        memcpy(out + pos, k->c[i].p, k->c[i].len);
        pos += k->c[i].len;
    }
    lumo_wire_put_le32(out + 16, lumo_wire_crc32(0, out + LUMO_PKG_HEADER_SIZE, (size_t)k->n * LUMO_PKG_ENTRY_SIZE));
    lumo_wire_put_le32(out + 20, lumo_wire_crc32(0, out, 20));
    corpus_put("package", name, out, pos, expect);
}

/* Light l's field at byte `off` of its record set to f (or, off 0, the kind to u). */
static void light_case(const pkg *base, uint32_t l, unsigned off, float f, uint32_t u, const char *tag)
{
    pkg k;
    char name[64], expect[64];
    pkg_copy(&k, base);
    uint8_t *rec = pkg_find(&k, LUMO_PKG_INFO)->p + 80 + 72 * (size_t)l;
    if (off == 0)
        lumo_wire_put_le32(rec, u);
    else
        corpus_put_f32(rec + off, f);
    snprintf(name, sizeof name, "light_%u_%02u_%s.lumo", l, off, tag);
    snprintf(expect, sizeof expect, off == 0 ? "INFO light %u of 3: unknown kind" : "INFO light %u of 3 (", l);
    pkg_write(&k, name, expect);
    pkg_free(&k);
}

static void light_cases(const pkg *base)
{
    static const float bad[3] = {NAN, INFINITY, -INFINITY};
    static const char *const tag[3] = {"nan", "inf", "ninf"};
    for (uint32_t l = 0; l < 3; l++) {
        for (unsigned off = 4; off < 72; off += 4)   /* every field NaN; light 0 also +-inf */
            for (int b = 0; b < (l == 0 ? 3 : 1); b++)
                light_case(base, l, off, bad[b], 0, tag[b]);
        light_case(base, l, 0, 0, 4, "kind4");
        light_case(base, l, 0, 0, 0xffffffffu, "kindmax");
        light_case(base, l, 56, 1.5f, 0, "cos");     /* cosine above 1 */
        light_case(base, l, 56, -1.01f, 0, "cosneg");
        light_case(base, l, 16, 2.0f, 0, "dir");     /* a direction component above 1 */
        light_case(base, l, 60, -1.0f, 0, "power");  /* negative power */
        light_case(base, l, 4, 1e9f, 0, "far");      /* beyond Q16.16 */
    }
}

static void ivgd_case(const pkg *base, unsigned off, int is_dim, uint32_t u, float f, const char *name)
{
    pkg k;
    pkg_copy(&k, base);
    uint8_t *d = pkg_find(&k, LUMO_PKG_IVGD)->p;
    if (is_dim)
        lumo_wire_put_le16(d + off, (uint16_t)u);
    else
        corpus_put_f32(d + off, f);
    pkg_write(&k, name, "IVGD: grid ");
    pkg_free(&k);
}

static void ivgd_cases(const pkg *base)
{
    static const uint32_t dims[4] = {0, 1, 257, 65535};
    static const float vals[3] = {NAN, INFINITY, -INFINITY};
    char name[64];
    for (unsigned a = 0; a < 3; a++)
        for (int i = 0; i < 4; i++) {
            snprintf(name, sizeof name, "ivgd_dim%u_%u.lumo", a, dims[i]);
            ivgd_case(base, 2 * a, 1, dims[i], 0, name);
        }
    for (unsigned f = 0; f < 6; f++)
        for (int i = 0; i < 3; i++) {
            snprintf(name, sizeof name, "ivgd_box%u_%d.lumo", f, i);
            ivgd_case(base, 8 + 4 * f, 0, 0, vals[i], name);
        }
    for (unsigned a = 0; a < 3; a++) {
        snprintf(name, sizeof name, "ivgd_minmax%u.lumo", a);
        ivgd_case(base, 8 + 4 * a, 0, 0, 100.0f, name);          /* min above max */
        snprintf(name, sizeof name, "ivgd_flat%u.lumo", a);
        pkg k;
        pkg_copy(&k, base);
        uint8_t *d = pkg_find(&k, LUMO_PKG_IVGD)->p;
        memcpy(d + 8 + 4 * a, d + 20 + 4 * a, 4);               /* min == max */
        pkg_write(&k, name, "IVGD: grid ");
        pkg_free(&k);
    }
}

/* A second copy of chunk `type` right after the first. */
static void twice_case(const pkg *base, uint32_t type, const char *name, const char *expect)
{
    pkg k;
    pkg_copy(&k, base);
    for (unsigned i = 0; i < k.n; i++)
        if (k.c[i].type == type) {
            memmove(&k.c[i + 1], &k.c[i], (k.n - i) * sizeof k.c[0]);
            k.c[i + 1].p = malloc(k.c[i].len ? k.c[i].len : 1);
            memcpy(k.c[i + 1].p, k.c[i].p, k.c[i].len);
            k.n++;
            break;
        }
    pkg_write(&k, name, expect);
    pkg_free(&k);
}

static void info_cases(const pkg *base)
{
    static const struct { unsigned off; float f; const char *name; } k[] = {
        {76, 0.0f, "info_fov0.lumo"}, {76, 180.0f, "info_fov180.lumo"}, {76, NAN, "info_fovnan.lumo"},
        {16, NAN, "info_boundsnan.lumo"}, {40, INFINITY, "info_eyeinf.lumo"},
    };
    for (size_t i = 0; i < sizeof k / sizeof *k; i++) {
        pkg p;
        pkg_copy(&p, base);
        corpus_put_f32(pkg_find(&p, LUMO_PKG_INFO)->p + k[i].off, k[i].f);
        pkg_write(&p, k[i].name, "INFO (");
        pkg_free(&p);
    }
    pkg p;
    for (int c = 0; c < 3; c++) {   /* cameras that cannot be placed */
        static const char *const names[3] = {"info_up0.lumo", "info_eye_on_target.lumo", "info_up_along.lumo"};
        pkg_copy(&p, base);
        uint8_t *in = pkg_find(&p, LUMO_PKG_INFO)->p;
        for (int a = 0; a < 3; a++) {
            float eye, target;
            uint32_t w = lumo_wire_le32(in + 40 + 4 * a), t = lumo_wire_le32(in + 52 + 4 * a);
            memcpy(&eye, &w, 4);
            memcpy(&target, &t, 4);
            if (c == 0)
                corpus_put_f32(in + 64 + 4 * a, 0.0f);
            else if (c == 1)
                lumo_wire_put_le32(in + 40 + 4 * a, t);
            else
                corpus_put_f32(in + 64 + 4 * a, 2.0f * (target - eye));
        }
        pkg_write(&p, names[c], "eye off the target");
        pkg_free(&p);
    }
    pkg_copy(&p, base);
    lumo_wire_put_le32(pkg_find(&p, LUMO_PKG_INFO)->p + 4, 17);
    pkg_write(&p, "info_lights17.lumo", "INFO (");
    pkg_free(&p);
    pkg_copy(&p, base);
    pkg_find(&p, LUMO_PKG_INFO)->type = LUMO_PKG_FOURCC('I', 'N', 'F', 'X');
    pkg_write(&p, "info_none.lumo", "no INFO chunk");   /* hostile.sh: lumo-inspect lists such a package */
    pkg_free(&p);
}

static void package_cases(const char *src)
{
    pkg base;
    pkg_read(&base, src);
    if (!pkg_find(&base, LUMO_PKG_INFO) || !pkg_find(&base, LUMO_PKG_IVGD) ||
        lumo_wire_le32(pkg_find(&base, LUMO_PKG_INFO)->p + 4) != 3) {
        fprintf(stderr, "gen_hostile: %s: needs INFO with 3 lights and IVGD\n", src);
        exit(1);
    }
    light_cases(&base);
    ivgd_cases(&base);
    info_cases(&base);
    twice_case(&base, LUMO_PKG_INFO, "twice_info.lumo", "two INFO chunks");
    twice_case(&base, LUMO_PKG_IVGD, "twice_ivgd.lumo", "two IVGD chunks");
    twice_case(&base, LUMO_PKG_IVGS, "twice_ivgs.lumo", "two IVGS chunks");
    twice_case(&base, LUMO_PKG_ORDR, "twice_ordr.lumo", "two ORDR chunks");
    twice_case(&base, LUMO_PKG_IVGQ, "twice_ivgq.lumo", "two IVGQ chunks");
    pkg_write(&base, "control.lumo", "OK");   /* the rewrite itself is sound */
    pkg_free(&base);
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: gen_hostile OUTDIR LIGHTS.lumo\n");
        return 2;
    }
    if (corpus_open(argv[1], "w", "gen_hostile"))
        return 1;
    off_coords();
    off_headers();
    off_truncated();
    ply_ascii();
    ply_binary();
    obj_cases();
    file_cases();
    good_cases();
    scene_cases();
    package_cases(argv[2]);
    corpus_close();
    return 0;
}
