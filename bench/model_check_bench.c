/*
 * model_check_bench.c — what lumo's model checks (server/scene/model_check.h:
 * OBJ, PLY, OFF, STL, glTF before assimp; issue 24) cost, against the peer
 * they guard: assimp's own import of the same file with the flags lumo uses
 * (server/scene/import.c). Each model is also written by assimp's exporter
 * as binary STL, glTF (.gltf + .bin) and GLB, so every checked format is
 * timed on the same geometry. Median of REPS runs of each; a Markdown
 * table on stdout.
 *
 *   lumo-bench-model-check REPS TMPDIR MODEL...
 */
#include <assimp/cexport.h>
#include <assimp/cimport.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include "lumo_host/options.h"
#include "scene/import_io.h"
#include "scene/model_check.h"

#define MAX_REPS   99
#define IMPORT_FLAGS (aiProcess_Triangulate | aiProcess_PreTransformVertices | aiProcess_SortByPType | \
                      aiProcess_ValidateDataStructure)

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return v[n / 2];
}

/* Median seconds of lumo's check of path; -1 when it refuses the file. */
static double time_check(const char *path, int reps)
{
    double t[MAX_REPS];
    char err[256];
    for (int r = 0; r < reps; r++) {
        srv_model_format fmt;
        double t0 = now_s();
        if (srv_model_check_file(path, &fmt, err, sizeof err)) {
            fprintf(stderr, "lumo-bench-model-check: %s\n", err);
            return -1;
        }
        t[r] = now_s() - t0;
    }
    return median(t, reps);
}

/* Median seconds of assimp's import of path (lumo's flags and file system). */
static double time_import(const char *path, int reps, unsigned *tris)
{
    double t[MAX_REPS];
    for (int r = 0; r < reps; r++) {
        double t0 = now_s();
        const struct aiScene *sc = aiImportFileEx(path, IMPORT_FLAGS, srv_import_io());
        t[r] = now_s() - t0;
        if (!sc)
            return -1;
        *tris = 0;
        for (unsigned m = 0; m < sc->mNumMeshes; m++)
            *tris += sc->mMeshes[m]->mNumFaces;
        aiReleaseImport(sc);
    }
    return median(t, reps);
}

static long long file_bytes(const char *path)
{
    struct stat st;
    return stat(path, &st) ? -1 : (long long)st.st_size;
}

static void row(const char *label, const char *path, int reps)
{
    unsigned tris = 0;
    double c = time_check(path, reps), i = time_import(path, reps, &tris);
    if (c < 0 || i < 0) {
        printf("| %s | refused or unreadable | | | | |\n", label);
        return;
    }
    printf("| %s | %lld | %u | %.2f | %.2f | %.3f |\n", label, file_bytes(path), tris, c * 1e3, i * 1e3, c / i);
}

/* The model, then assimp's export of it in each checked format. */
static void model_rows(const char *model, const char *tmp, int reps)
{
    static const struct { const char *id, *ext, *label; } k_exports[] = {
        {"stlb", "stl", "binary STL"}, {"gltf2", "gltf", "glTF (.gltf + .bin)"}, {"glb2", "glb", "GLB"},
    };
    const char *base = strrchr(model, '/');
    char label[256], out[1024];
    base = base ? base + 1 : model;
    snprintf(label, sizeof label, "%s", base);
    row(label, model, reps);
    const struct aiScene *sc = aiImportFileEx(model, IMPORT_FLAGS, srv_import_io());
    if (!sc)
        return;
    for (size_t e = 0; e < sizeof k_exports / sizeof k_exports[0]; e++) {
        snprintf(out, sizeof out, "%s/%.*s.%s", tmp, (int)(strcspn(base, ".")), base, k_exports[e].ext);
        if (aiExportScene(sc, k_exports[e].id, out, 0) != aiReturn_SUCCESS) {
            printf("| %s as %s | assimp cannot export it | | | | |\n", base, k_exports[e].label);
            continue;
        }
        snprintf(label, sizeof label, "%s as %s", base, k_exports[e].label);
        row(label, out, reps);
    }
    aiReleaseImport(sc);
}

int main(int argc, char **argv)
{
    char why[160];
    int reps;
    if (argc < 4) {
        fprintf(stderr, "usage: lumo-bench-model-check REPS TMPDIR MODEL...\n");
        return 2;
    }
    if (host_opt_int("REPS", argv[1], 1, MAX_REPS, &reps, why, sizeof why)) {
        fprintf(stderr, "lumo-bench-model-check: error: %s\n", why);
        return 2;
    }
    printf("| file | bytes | triangles | lumo's checks ms | assimp import ms | checks / import |\n");
    printf("|---|---|---|---|---|---|\n");
    for (int m = 3; m < argc; m++)
        model_rows(argv[m], argv[2], reps);
    return 0;
}
