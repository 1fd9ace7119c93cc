/* tools/lumo-inspect/pm.c — lumo-inspect subcommands for the progressive-mesh stream
 * (docs/progressive-mesh.md), decoded by the real client (lumo/pmesh.h):
 *
 *   lumo-inspect --stream FILE           the header and every batch record: its
 *                                        index, first vertex, vertices added, faces
 *                                        after it, head / side / Draco / record bytes
 *                                        and offset in the stream; the base record
 *                                        of a CODED stream also its seed mesh
 *                                        (vertices / faces) and splits
 *   lumo-inspect --lod N --ply OUT FILE  the level with N vertices (N = all)
 *   --mesh I                             the I-th mesh's stream (default 0)
 *
 * FILE is a .lumo package with a PMSH chunk or a raw stream (lumo-pm --raw). */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "lumo_host/file_io.h"
#include "lumo_host/options.h"
#include "lumo_host/package_msg.h"
#include "inspect.h"
#include "lumo/wire.h"
#include "pm/pm_client.h"

static int load(const char *path, uint8_t **data, size_t *len)
{
    char err[600] = "";
    if (!path || host_opt_file(NULL, path, "package or stream", err, sizeof err) ||
        !(*data = host_read_file(path, len))) {
        if (path && !err[0])
            snprintf(err, sizeof err, "%s: cannot read", path);
        fprintf(stderr, "lumo-inspect: error: %s\n", path ? err : "no package file given (try --help)");
        return -1;
    }
    return 0;
}

/* --mesh I: which PMSH chunk (one per mesh of the scene); 0 when absent.
 * -1 after printing the refusal. */
static int mesh_arg(int argc, char **argv, uint32_t *mesh)
{
    char err[320];
    *mesh = 0;
    for (int i = 1; i < argc; i++)
        if (!strcmp(argv[i], "--mesh")) {
            if (i + 1 < argc && !host_opt_u32("--mesh", argv[i + 1], 0, UINT32_MAX, mesh, err, sizeof err))
                return 0;
            if (i + 1 == argc)
                snprintf(err, sizeof err, "--mesh needs a value (try --help)");
            fprintf(stderr, "lumo-inspect: error: %s\n", err);
            return -1;
        }
    return 0;
}

static int open_stream(const char *path, uint32_t mesh, uint8_t **file, srv_pm_client *c)
{
    size_t len, slen;
    const uint8_t *s;
    if (load(path, file, &len))
        return -1;
    lumo_status st = srv_pm_find_stream(*file, len, mesh, &s, &slen);
    if (!st)
        st = srv_pm_client_open(c, s, slen);
    if (st == LUMO_ERR_VERSION) {
        char why[160];
        fprintf(stderr, "lumo-inspect: error: %s: %s\n", path, host_package_strerror(*file, len, st, why, sizeof why));
        free(*file);
        return -1;
    }
    if (st) {
        fprintf(stderr, "lumo-inspect: error: %s: no progressive mesh stream %u: %s\n", path, mesh,
                lumo_strerror(st));
        free(*file);
        return -1;
    }
    return 0;
}

/* Elias gamma code (docs/progressive-mesh.md §2.3): z zeros, a one, z bits. */
static int gamma_read(lumo_wire_bits *b, uint32_t *v)
{
    uint32_t z = 0, bit = 0, low = 0;
    while (!bit)
        if (lumo_wire_bits_read(b, 1, &bit) || (!bit && ++z > 31))
            return -1;
    if (lumo_wire_bits_read(b, z, &low))
        return -1;
    *v = (uint32_t)1 << z | low;
    return 0;
}

/* A CODED base record's seed size, its block's first two fields (§2.3
 * "Base record"; the client has applied the record, so they are valid). */
static int seed_size(const uint8_t *block, uint32_t bytes, uint32_t *nv, uint32_t *nf)
{
    lumo_wire_bits b;
    lumo_wire_bits_init(&b, block, bytes);
    if (gamma_read(&b, nv) || gamma_read(&b, nf))
        return -1;
    *nf -= 1;
    return 0;
}

static int run_stream(int argc, char **argv)
{
    uint8_t *file;
    srv_pm_client c;
    uint32_t mesh;
    if (mesh_arg(argc, argv, &mesh) || open_stream(inspect_file_arg(argc, argv), mesh, &file, &c))
        return 1;
    const lumo_pmesh_header *h = &c.h;
    static const char *const coding[] = {"absolute, in Draco payloads", "predicted, residuals in Draco payloads",
                                         "coded"};
    printf("progressive mesh: %u vertices, %u faces; base %u vertices, %u faces; %u batches of %u "
           "vertices; positions %u bits (%s%s)%s; stream %zu bytes (%.2f bits/triangle; header %u); client arena "
           "%zu bytes\n",
           h->vertices, h->faces, h->base_vertices, h->base_faces, h->batch_count, h->batch_vertices,
           h->quant_bits, coding[h->position_coding], h->flags & LUMO_PMESH_LATTICE ? ", lattice copies" : "",
           h->flags & LUMO_PMESH_HAS_ALBEDO ? "; albedo" : "", c.len, h->faces ? 8.0 * c.len / h->faces : 0.0,
           h->header_bytes, c.arena_bytes);
    printf("%6s %9s %8s %8s %6s %8s %8s %9s %10s\n", "batch", "first", "verts", "faces", "head B",
           "side B", "draco B", "record B", "offset");
    int rc = 0;
    while (!lumo_pmesh_complete(&c.pm)) {
        const uint8_t *r;
        size_t n, at = c.at;
        lumo_pmesh_record_head rh;
        lumo_pmesh_view before, after;
        lumo_status st = srv_pm_client_next(&c, &r, &n);
        /* The head as the SDK reads it (docs/progressive-mesh.md §2.2); the
         * counts from the level before and after the batch. */
        if (!st)
            st = lumo_pmesh_read_record_head(r, n, &rh);
        lumo_pmesh_get_view(&c.pm, &before);
        if (!st)
            st = srv_pm_client_step(&c);
        if (st) {
            fprintf(stderr, "lumo-inspect: error: batch %u: %s\n", lumo_pmesh_batches(&c.pm), lumo_strerror(st));
            rc = 1;
            break;
        }
        lumo_pmesh_get_view(&c.pm, &after);
        uint32_t sv, sf;
        printf("%6u %9u %8u %8u %6u %8u %8u %9zu %10zu", lumo_pmesh_batches(&c.pm) - 1, before.vertex_count,
               after.vertex_count - before.vertex_count, after.face_count, rh.head_bytes, rh.side_bytes,
               rh.draco_bytes, n, at);
        if (lumo_pmesh_batches(&c.pm) == 1 && h->position_coding == LUMO_PMESH_POS_CODED &&
            !seed_size(r + rh.head_bytes, rh.side_bytes, &sv, &sf))
            printf("  seed %u vertices, %u faces, %u splits", sv, sf, after.vertex_count - sv);
        printf("\n");
    }
    srv_pm_client_close(&c);
    free(file);
    return rc;
}

static int write_ply(const char *path, const lumo_pmesh_view *v)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return -1;
    fprintf(f, "ply\nformat ascii 1.0\ncomment lumo progressive mesh level\nelement vertex %u\n"
               "property float x\nproperty float y\nproperty float z\n"
               "property float nx\nproperty float ny\nproperty float nz\n%s"
               "element face %u\nproperty list uchar int vertex_indices\nend_header\n", v->vertex_count,
            v->albedo ? "property uchar red\nproperty uchar green\nproperty uchar blue\n" : "", v->face_count);
    for (uint32_t i = 0; i < v->vertex_count; i++) {
        const lumo_q16_16 *p = v->positions + 3 * i;
        const lumo_q1_14 *n = v->normals + 3 * i;
        fprintf(f, "%.7g %.7g %.7g %.5f %.5f %.5f", p[0] / 65536.0, p[1] / 65536.0, p[2] / 65536.0,
                n[0] / 16384.0, n[1] / 16384.0, n[2] / 16384.0);
        if (v->albedo)
            fprintf(f, " %d %d %d", (v->albedo[3 * i] * 255 + 8192) / 16384,
                    (v->albedo[3 * i + 1] * 255 + 8192) / 16384, (v->albedo[3 * i + 2] * 255 + 8192) / 16384);
        fputc('\n', f);
    }
    for (uint32_t i = 0; i < v->face_count; i++)
        fprintf(f, "3 %u %u %u\n", v->triangles[3 * i], v->triangles[3 * i + 1], v->triangles[3 * i + 2]);
    return fclose(f) ? -1 : 0;
}

/* --lod N|all: 0 with *n (UINT32_MAX for all), or -1 after the refusal. */
static int lod_arg(const char *lod, uint32_t *n)
{
    char err[320];
    if (!strcmp(lod, "all")) {
        *n = UINT32_MAX;
        return 0;
    }
    if (!host_opt_u32("--lod", lod, 1, UINT32_MAX, n, err, sizeof err))
        return 0;
    fprintf(stderr, "lumo-inspect: error: %s (N vertices or all)\n", err);
    return -1;
}

static int run_lod(int argc, char **argv)
{
    const char *lod = NULL, *out = NULL;
    uint32_t n, mesh;
    for (int i = 1; i + 1 < argc; i++) {
        if (!strcmp(argv[i], "--lod"))
            lod = argv[++i];
        else if (!strcmp(argv[i], "--ply"))
            out = argv[++i];
    }
    if (!lod || !out) {
        fprintf(stderr, "lumo-inspect: error: usage: --lod N|all --ply OUT.ply FILE\n");
        return 1;
    }
    if (lod_arg(lod, &n) || mesh_arg(argc, argv, &mesh))
        return 1;
    uint8_t *file;
    srv_pm_client c;
    if (open_stream(inspect_file_arg(argc, argv), mesh, &file, &c))
        return 1;
    int rc = 1;
    if (n == UINT32_MAX)
        n = c.h.vertices;
    if (n < c.h.base_vertices || n > c.h.vertices) {
        fprintf(stderr, "lumo-inspect: error: --lod %s: levels go from %u to %u vertices\n", lod,
                c.h.base_vertices, c.h.vertices);
        goto done;
    }
    lumo_status st = srv_pm_client_until(&c, n);
    if (!st)
        st = lumo_pmesh_rewind(&c.pm, n);
    if (st) {
        fprintf(stderr, "lumo-inspect: error: batch %u: %s\n", lumo_pmesh_batches(&c.pm), lumo_strerror(st));
        goto done;
    }
    lumo_pmesh_view v;
    lumo_pmesh_get_view(&c.pm, &v);
    errno = 0;
    if (write_ply(out, &v)) {
        fprintf(stderr, "lumo-inspect: error: %s: cannot write: %s\n", out, errno ? strerror(errno) : "short write");
        goto done;
    }
    printf("%s: level %u: %u vertices, %u triangles\n", out, v.vertex_count, v.vertex_count, v.face_count);
    rc = 0;
done:
    srv_pm_client_close(&c);
    free(file);
    return rc;
}

INSPECT_COMMAND(pm_stream_cmd, "--stream",
                "--stream [--mesh I] FILE.lumo      list the progressive-mesh batches", run_stream)
INSPECT_COMMAND(pm_lod_cmd, "--lod",
                "--lod N|all --ply OUT.ply [--mesh I] FILE.lumo  write the level with N vertices",
                run_lod)
