/*
 * gen_formats.c — the hostile corpus of the model formats beyond OBJ, PLY
 * and OFF (issue 24, round three), made at test time: binary and ASCII
 * STL, glTF 2.0 (.gltf, .glb) whose declared counts outrun their bytes,
 * the formats lumo refuses by name, and scene files whose lights are wrong
 * field by field. Appends to the corpus gen_hostile writes:
 *
 *   gen_formats OUTDIR
 *
 * one line per case to OUTDIR/manifest ("KIND<TAB>FILE<TAB>EXPECTED", as
 * gen_hostile; tests/hostile/hostile.sh runs each under its memory and time
 * limits).
 */
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <zlib.h>
#include "lumo/wire.h"
#include "corpus.h"


/* ---- STL ------------------------------------------------------------------------ */

/* A binary STL of one triangle declaring `declared` triangles; corner
 * value `bad` (when not 0) replaces corner 1's y. */
static size_t binary_stl(uint8_t *buf, const char *head, uint32_t declared, float bad)
{
    static const float corners[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    memset(buf, 0, 134);
    memcpy(buf, head, strlen(head));
    lumo_wire_put_le32(buf + 80, declared);
    corpus_put_f32(buf + 84 + 8, 1.0f);   /* the normal, (0, 0, 1) */
    for (int k = 0; k < 9; k++)
        corpus_put_f32(buf + 96 + 4 * k, k == 4 && bad != 0.0f ? bad : corners[k]);
    return 134;
}

static void stl_cases(void)
{
    uint8_t b[134];
    const char *facet = "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n";
    corpus_put("model", "good_b.stl", b, binary_stl(b, "lumo", 1, 0), "OK");
    /* Exporters often begin a binary header with "solid": the size decides. */
    corpus_put("model", "good_solid_b.stl", b, binary_stl(b, "solid by an exporter", 1, 0), "OK");
    corpus_put("model", "huge_b.stl", b, binary_stl(b, "lumo", 1000000000u, 0),
             "the binary STL header declares 1000000000 triangles: 84 + 50 x 1000000000 = 50000000084 bytes, the "
             "file holds 134");
    corpus_put("model", "max_b.stl", b, binary_stl(b, "lumo", 0xffffffffu, 0), "declares 4294967295 triangles");
    corpus_put("model", "zero_b.stl", b, binary_stl(b, "lumo", 0, 0), "declares 0 triangles: 84 + 50 x 0 = 84 bytes, "
             "the file holds 134");
    corpus_put("model", "short_b.stl", b, 60, "60 bytes: too short for a binary STL (84-byte header)");
    binary_stl(b, "lumo", 1, 0);
    corpus_put("model", "cut_b.stl", b, 120, "declares 1 triangles: 84 + 50 x 1 = 134 bytes, the file holds 120");
    corpus_put("model", "nan_b.stl", b, binary_stl(b, "lumo", 1, NAN), "triangle 0, corner 1: y = nan is not "
             "finite");
    corpus_put("model", "far_b.stl", b, binary_stl(b, "lumo", 1, 1e7f), "triangle 0, corner 1: y = 10000000 is beyond "
             "the 1e6 m coordinate bound");
    corpus_text("model", "good_a.stl", "OK", "solid t\n%sendsolid t\n", facet);
    corpus_text("model", "four_a.stl", "line 7: a facet with more than 3 vertices", "solid t\nfacet normal 0 0 1\n"
              "outer loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nvertex 1 1 0\nendloop\nendfacet\n");
    corpus_text("model", "two_a.stl", "line 7: facet 0 has 2 vertices, a facet has 3", "solid t\nfacet normal 0 0 1\n"
              "outer loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\n");
    corpus_text("model", "cut_a.stl", "the file ends inside facet 1", "solid t\n%sfacet normal 0 0 1\nouter loop\n"
              "vertex 0 0 0\n", facet);
    corpus_text("model", "cut_word_a.stl", "line 11: facet 1, vertex 0: z is missing", "solid t\n%sfacet normal 0 0 1\n"
              "outer loop\nvertex 0 0", facet);
    corpus_text("model", "word_a.stl", "line 4: facet 0, vertex 0: y 'one' is not a number", "solid t\nfacet normal "
              "0 0 1\nouter loop\nvertex 0 one 0\n");
    corpus_text("model", "inf_a.stl", "facet 0, vertex 2: z = inf is not finite", "solid t\nfacet normal 0 0 1\n"
              "outer loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 inf\n");
    corpus_text("model", "empty_a.stl", "an ASCII STL without a facet", "solid t\nendsolid t\n");
    corpus_text("model", "bytes_a.stl", "not an ASCII one", "solid\x01\x02");
}

/* ---- glTF ------------------------------------------------------------------------- */

/* (0,0,0) (1,0,0) (0,1,0) as 36 bytes of little-endian floats, base64. */
#define TRI_B64 "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"

/* A one-triangle glTF with its fields given: the buffer (byteLength, uri),
 * the view's byteLength, the accessor's count and extra accessor members,
 * and the members after "meshes". */
static void gltf_case(const char *name, const char *expect, const char *blen, const char *uri, const char *vlen,
                      const char *count, const char *acc_extra, const char *tail)
{
    corpus_text("model", name, expect,
              "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":%s,\"uri\":\"%s\"}],"
              "\"bufferViews\":[{\"buffer\":0,\"byteLength\":%s}],\"accessors\":[{\"bufferView\":0,"
              "\"componentType\":5126,\"count\":%s,\"type\":\"VEC3\",\"min\":[0,0,0],\"max\":[1,1,0]%s}],"
              "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}]%s}",
              blen, uri, vlen, count, acc_extra, tail);
}

#define DATA_URI "data:application/octet-stream;base64," TRI_B64
#define ONE_NODE ",\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}]"

static void gltf_cases(void)
{
    static char roots[64];
    gltf_case("good.gltf", "OK", "36", DATA_URI, "36", "3", "", ONE_NODE);
    gltf_case("acc_past.gltf", "accessor 0: 1000000000 items of 12 bytes from offset 0 need 12000000000 bytes, "
              "bufferView 0 holds 36", "36", DATA_URI, "36", "1000000000", "", ONE_NODE);
    gltf_case("acc_offset.gltf", "accessor 0: 3 items of 12 bytes from offset 4 need 40 bytes", "36", DATA_URI, "36",
              "3", ",\"byteOffset\":4", ONE_NODE);
    gltf_case("acc_count.gltf", "accessor 0: count must be an integer in [1, 1073741824]", "36", DATA_URI, "36",
              "1e300", "", ONE_NODE);
    gltf_case("acc_sparse.gltf", "accessor 0 is sparse: not read", "36", DATA_URI, "36", "3",
              ",\"sparse\":{\"count\":1000000000}", ONE_NODE);
    gltf_case("view_past.gltf", "bufferView 0: bytes 0..4000000 lie past buffer 0's 36", "36", DATA_URI, "4000000",
              "3", "", ONE_NODE);
    gltf_case("buffer_big.gltf", "buffer 0 declares 1000000000 bytes, its uri holds 36", "1000000000", DATA_URI,
              "36", "3", "", ONE_NODE);
    gltf_case("buffer_none.gltf", "buffer 0: 'lumo-none.bin': No such file or directory", "36", "lumo-none.bin",
              "36", "3", "", ONE_NODE);
    corpus_put(NULL, "short.bin", "0123456789", 10, NULL);
    gltf_case("buffer_short.gltf", "buffer 0 declares 36 bytes, its uri holds 10", "36", "short.bin", "36", "3", "",
              ONE_NODE);
    gltf_case("buffer_dir.gltf", "buffer 0: '.' is not a regular file", "36", ".", "36", "3", "", ONE_NODE);
    gltf_case("node_cycle.gltf", "is its own ancestor: the hierarchy must be trees", "36", DATA_URI, "36", "3", "",
              ",\"nodes\":[{\"mesh\":0,\"children\":[1]},{\"children\":[0]}]");
    gltf_case("node_two_parents.gltf", "node 0 is the child of nodes 1 and 2", "36", DATA_URI, "36", "3", "",
              ",\"nodes\":[{\"mesh\":0},{\"children\":[0]},{\"children\":[0]}],\"scenes\":[{\"nodes\":[1,2]}]");
    gltf_case("node_mesh.gltf", "node 0: mesh must be an integer in [0, 0]", "36", DATA_URI, "36", "3", "",
              ",\"nodes\":[{\"mesh\":5}]");
    snprintf(roots, sizeof roots, ",\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0,0,0]}]");
    /* 96 MB of positions (a sparse file: no disk) drawn three times. */
    corpus_text("model", "instances.gltf", "mesh 0: the geometry assimp would expand passes 256 MiB",
              "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":96000000,\"uri\":\"big.bin\"}],"
              "\"bufferViews\":[{\"buffer\":0,\"byteLength\":96000000}],\"accessors\":[{\"bufferView\":0,"
              "\"componentType\":5126,\"count\":8000000,\"type\":\"VEC3\"}],\"meshes\":[{\"primitives\":"
              "[{\"attributes\":{\"POSITION\":0}}]}]%s}", roots);
    corpus_text("model", "no_view.gltf", "accessor 0 has no bufferView (zeros or Draco-compressed data): not read",
              "{\"asset\":{\"version\":\"2.0\"},\"accessors\":[{\"componentType\":5126,\"count\":1000000000,"
              "\"type\":\"VEC3\"}],\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}]" ONE_NODE "}");
    corpus_text("model", "v1.gltf", "glTF version '1.0': only glTF 2.0 is read", "{\"asset\":{\"version\":\"1.0\"}}");
    corpus_text("model", "noversion.gltf", "no asset.version: not a glTF file", "{\"meshes\":[]}");
    corpus_text("model", "json.gltf", "JSON line 1", "{\"asset\":{\"version\":\"2.0\"},");
    corpus_text("model", "dup.gltf", "JSON line 1", "{\"asset\":{\"version\":\"2.0\"},\"asset\":{}}");
}

/* JSON nested 100,000 deep, and JSON past SRV_GLTF_MAX_JSON. */
static void gltf_size_cases(void)
{
    size_t n = 100000, big = (17u << 20);
    char *s = malloc(2 * n + 1 > big ? 2 * n + 1 : big);
    if (!s)
        exit(1);
    memset(s, '[', n);
    memset(s + n, ']', n);
    corpus_put("model", "deep.gltf", s, 2 * n, "JSON line 1");
    memset(s, ' ', big);
    memcpy(s, "{\"asset\":{\"version\":\"2.0\"}}", 27);
    corpus_put("model", "big_json.gltf", s, big, "17825792 bytes of JSON, at most 16 MiB are read");
    free(s);
}

/* A GLB of the one triangle: JSON chunk, BIN chunk; n the whole size. */
static size_t glb(uint8_t *out, uint32_t version, uint32_t bin_declared, const char *count)
{
    char json[512];
    int jl = snprintf(json, sizeof json,
                      "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":36}],\"bufferViews\":[{\"buffer\":0,"
                      "\"byteLength\":36}],\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":%s,"
                      "\"type\":\"VEC3\",\"min\":[0,0,0],\"max\":[1,1,0]}],\"meshes\":[{\"primitives\":[{"
                      "\"attributes\":{\"POSITION\":0}}]}]" ONE_NODE "}", count);
    size_t jp = ((size_t)jl + 3) / 4 * 4, n = 20 + jp + 8 + 36;
    static const float tri[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    memset(out, ' ', n);
    memcpy(out, "glTF", 4);
    lumo_wire_put_le32(out + 4, version);
    lumo_wire_put_le32(out + 8, (uint32_t)n);
    lumo_wire_put_le32(out + 12, (uint32_t)jp);
    memcpy(out + 16, "JSON", 4);
    memcpy(out + 20, json, (size_t)jl);
    lumo_wire_put_le32(out + 20 + jp, bin_declared);
    memcpy(out + 24 + jp, "BIN", 4);
    out[27 + jp] = 0;
    for (int k = 0; k < 9; k++)
        corpus_put_f32(out + 28 + jp + 4 * k, tri[k]);
    return n;
}

static void glb_cases(void)
{
    uint8_t b[1024];
    size_t n = glb(b, 2, 36, "3");
    corpus_put("model", "good.glb", b, n, "OK");
    corpus_put("model", "cut.glb", b, n - 20, "the GLB header declares");
    corpus_put("model", "head.glb", b, 12, "no GLB header");
    corpus_put("model", "bin_huge.glb", b, glb(b, 2, 4000000000u, "3"), "the BIN chunk declares 4000000000 bytes, 36 "
             "follow it");
    corpus_put("model", "bin_short.glb", b, glb(b, 2, 12, "3"), "buffer 0 declares 36 bytes, the BIN chunk holds 12");
    corpus_put("model", "acc_past.glb", b, glb(b, 2, 36, "1000000000"), "accessor 0: 1000000000 items");
    corpus_put("model", "v1.glb", b, glb(b, 1, 36, "3"), "GLB version 1: only version 2 (glTF 2.0) is read");
    n = glb(b, 2, 36, "3");
    lumo_wire_put_le32(b + 12, 4000000000u);
    corpus_put("model", "json_huge.glb", b, n, "the first GLB chunk is not JSON of 4000000000 bytes");
}

/* ---- PNG pictures (lumo-compare, --env, --prt-env) -------------------------------------- */

static void png_chunk(FILE *f, const char *type, const uint8_t *data, uint32_t n)
{
    uint8_t be[4] = {(uint8_t)(n >> 24), (uint8_t)(n >> 16), (uint8_t)(n >> 8), (uint8_t)n};
    uLong crc = crc32(crc32(0, (const Bytef *)type, 4), data, n);
    uint8_t c[4] = {(uint8_t)(crc >> 24), (uint8_t)(crc >> 16), (uint8_t)(crc >> 8), (uint8_t)crc};
    fwrite(be, 1, 4, f), fwrite(type, 1, 4, f), fwrite(data, 1, n, f), fwrite(c, 1, 4, f);
}

/* A whole, valid RGB8 PNG of side x side black pixels: 243 MB of pixels
 * in a quarter of a megabyte of deflate. */
static void black_png(const char *name, uint32_t side, const char *expect)
{
    static uint8_t row[3 * 9000 + 1], out[1 << 20];
    uint8_t ihdr[13] = {(uint8_t)(side >> 24), (uint8_t)(side >> 16), (uint8_t)(side >> 8), (uint8_t)side, 0, 0, 0, 0,
                        8, 2, 0, 0, 0};
    z_stream z;
    FILE *f;
    memcpy(ihdr + 4, ihdr, 4);
    memset(&z, 0, sizeof z);
    if (side > 9000 || !(f = fopen(corpus_path(name), "wb")) || deflateInit(&z, 1) != Z_OK)
        exit(1);
    fwrite("\x89PNG\r\n\x1a\n", 1, 8, f);
    png_chunk(f, "IHDR", ihdr, 13);
    for (uint32_t y = 0; y <= side; y++) {
        z.next_in = row, z.avail_in = y < side ? 3 * side + 1 : 0;
        do {
            z.next_out = out, z.avail_out = sizeof out;
            deflate(&z, y < side ? Z_NO_FLUSH : Z_FINISH);
            if (sizeof out - z.avail_out)
                png_chunk(f, "IDAT", out, (uint32_t)(sizeof out - z.avail_out));
        } while (z.avail_out == 0);
    }
    deflateEnd(&z);
    png_chunk(f, "IEND", out, 0);
    if (fclose(f))
        exit(1);
    corpus_note("png", name, expect);
}

/* ---- formats lumo refuses, and the lights of scene files ----------------------------- */

static void other_cases(void)
{
    static const char *const ext[] = {"dae", "3ds", "fbx", "x", "blend", "ase", "lwo", "md2", "ms3d", "x3d"};
    char name[32], expect[128];
    for (size_t i = 0; i < sizeof ext / sizeof *ext; i++) {
        snprintf(name, sizeof name, "model.%s", ext[i]);
        snprintf(expect, sizeof expect, "unknown model format (extension '.%s'): lumo reads OBJ, PLY, OFF, STL and "
                 "glTF 2.0", ext[i]);
        corpus_put("model", name, "\x4d\x4d\x10\x00\x00\x00", 6, expect);
    }
}

static void light_scene_cases(void)
{
    static const struct { const char *name, *light, *expect; } k[] = {
        {"l_pos.txt", "point:0,1:1,1,1", "light 'point:0,1:1,1,1': position needs 3 numbers, got 2"},
        {"l_kind.txt", "laser:0,1,0:1,1,1", "kind 'laser' is not point, spot, directional or area"},
        {"l_fields.txt", "point:0,1,0:1,1,1:9", "a point light is point:X,Y,Z:R,G,B (3 fields), got 4"},
        {"l_power.txt", "point:0,1,0:1,-1,1", "power value 2 = -1 is outside [0, 1e+09] W"},
        {"l_nan.txt", "point:0,nan,0:1,1,1", "position value 2 'nan' is not a finite number"},
        {"l_far.txt", "point:0,1e30,0:1,1,1", "position value 2 = 1e+30 is outside [-32000, 32000] m"},
        {"l_dir.txt", "directional:0,0,0:1,1,1", "direction 0,0,0 has no length"},
        {"l_irr.txt", "directional:0,-1,0:1,1", "irradiance needs 3 numbers, got 2"},
        {"l_cone.txt", "spot:0,1,0:0,-1,0:200:1,1,1", "cone half-angle = 200 is outside [0, 180] degrees"},
        {"l_cone0.txt", "spot:0,1,0:0,-1,0:0:1,1,1", "cone half-angle 0 must be above 0 degrees"},
        {"l_area.txt", "area:0,1,0:1,0,0:2,0,0:1,1,1", "edges U 1,0,0 and V 2,0,0 are parallel or zero"},
    };
    static char text[4096];
    size_t o = 0;
    for (size_t i = 0; i < sizeof k / sizeof *k; i++)
        corpus_text("scene", k[i].name, k[i].expect, "quad 0,0,0 1,0,0 0,0,1\nlight %s\n", k[i].light);
    o += (size_t)snprintf(text + o, sizeof text - o, "quad 0,0,0 1,0,0 0,0,1\n");
    for (int i = 0; i < 17; i++)
        o += (size_t)snprintf(text + o, sizeof text - o, "light point:0,%d,0:1,1,1\n", i + 1);
    corpus_put("scene", "l_count.txt", text, o, ":18: light 'point:0,17,0:1,1,1': more than 16 lights; a scene holds "
             "at most 16 (LUMO_MAX_LIGHTS");
    corpus_text("scene", "l_dae.txt", "model.dae: unknown model format", "mesh model.dae\nlight point:0,1,0:1,1,1\n");
    corpus_text("scene", "l_stl.txt", "huge_b.stl: the binary STL header declares 1000000000 triangles",
              "mesh huge_b.stl\nlight point:0,1,0:1,1,1\n");
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: gen_formats OUTDIR\n");
        return 2;
    }
    if (corpus_open(argv[1], "a", "gen_formats"))
        return 1;
    /* The 96 MB buffer of instances.gltf: a sparse file, no disk. */
    FILE *big = fopen(corpus_path("big.bin"), "wb");
    if (!big || ftruncate(fileno(big), 96000000) || fclose(big)) {
        fprintf(stderr, "gen_formats: cannot write %s\n", corpus_path("big.bin"));
        return 1;
    }
    stl_cases();
    gltf_cases();
    gltf_size_cases();
    glb_cases();
    other_cases();
    light_scene_cases();
    black_png("black_9000.png", 9000, "cannot read as an 8-bit PNG picture (of at most 2^26 pixels)");
    black_png("black_8192.png", 8192, "OK");
    corpus_close();
    return 0;
}
