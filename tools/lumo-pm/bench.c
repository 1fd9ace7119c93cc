/* tools/lumo-pm/bench.c — `lumo-pm bench`: the progressive-mesh numbers of issue 5 as
 * a markdown section (bench/pm.mk writes build/bench/sections/60-pm.md).
 *
 *   lumo-pm bench --out FILE.md --cmd "COMMAND" [--fig5 MODEL] MODEL...
 *
 * 1. stream size against single-shot draco_encoder -cl 7 / -cl 10 at the
 *    same 12-bit quantization, on the same cleaned mesh;
 * 2. seed 000 §5.2 Fig. 5: receive + apply time against batch size, and
 *    the overhead against one raw transfer, on a stated link model;
 * 3. client time and memory per batch against mesh size;
 * 4. the quality cost of independent-set rounds against one collapse at a
 *    time (RMS plane distance of intermediate levels). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#include "pm/pm_client.h"
#include "pm/pm_load.h"
#include "pm/pm_internal.h"
#include "pm/pm_stream.h"

int bench_main(int argc, char **argv);

/* Link model for Fig. 5: 802.11g-like 20 Mbit/s effective, one request
 * round trip of 2 ms per batch (the client asks for each batch). */
#define LINK_BYTES_PER_S 2.5e6
#define LINK_RTT_S       0.002

typedef struct {
    const char *path, *name;
    float *xyz;
    uint32_t *tris, nv, nf;
    srv_pm pm;
    double build_s;
} model;

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + t.tv_nsec * 1e-9;
}

static const char *base_name(const char *p)
{
    const char *s = strrchr(p, '/');
    return s ? s + 1 : p;
}

static int load_model(const char *path, model *m)
{
    char err[256];
    memset(m, 0, sizeof *m);
    m->path = path, m->name = base_name(path);
    if (srv_pm_load(path, &m->xyz, NULL, &m->nv, &m->tris, &m->nf, err, sizeof err)) {
        fprintf(stderr, "lumo-pm bench: %s\n", err);
        return -1;
    }
    double t0 = now();
    if (srv_pm_build(m->xyz, m->nv, m->tris, m->nf, NULL, &m->pm))
        return -1;
    m->build_s = now() - t0;
    return 0;
}

static void free_model(model *m)
{
    srv_pm_free(&m->pm);
    free(m->xyz);
    free(m->tris);
}

/* The default stream of pm with its bit statistics; 0 on success. */
static int stream_stats(const srv_pm *pm, srv_pm_stream_stats *st, uint8_t **s, size_t *len)
{
    srv_pm_stream_options o;
    srv_pm_stream_default_options(&o);
    o.stats = st;
    return srv_pm_stream_build(pm, &o, s, len, NULL, NULL);
}

/* A stream of m: batch 0 and bits 0 are the per-mesh choices. */
static int stream_bits(const model *m, uint32_t batch, int bits, int coding, uint8_t **s, size_t *len)
{
    srv_pm_stream_options o;
    srv_pm_stream_default_options(&o);
    o.batch_vertices = batch;
    o.quant_bits = bits;
    o.position_coding = coding;
    return srv_pm_stream_build(&m->pm, &o, s, len, NULL, NULL);
}

static int stream(const model *m, uint32_t batch, int coding, uint8_t **s, size_t *len)
{
    return stream_bits(m, batch, 0, coding, s, len);
}

/* Size of `draco_encoder -qp BITS -cl CL` on the cleaned mesh, or 0. The
 * mesh goes in the cleaner's order (the input's, welded), not the
 * progressive mesh's: Edgebreaker's bytes depend a little on the order
 * given, and the reference must not move with the simplifier's choices. */
static long draco_cli_size(const model *m, int bits, int cl)
{
    char ply[64], drc[64], cmd[256];
    srv_pm_clean_mesh c;
    snprintf(ply, sizeof ply, "/tmp/lumo-pm-bench-%d.ply", (int)getpid());
    snprintf(drc, sizeof drc, "/tmp/lumo-pm-bench-%d.drc", (int)getpid());
    if (srv_pm_clean(m->xyz, NULL, m->nv, m->tris, m->nf, &c))
        return 0;
    int bad = srv_pm_write_ply(ply, c.xyz, c.nv, c.tris, c.nf);
    srv_pm_clean_free(&c);
    if (bad)
        return 0;
    snprintf(cmd, sizeof cmd, "draco_encoder -i %s -o %s -qp %d -cl %d >/dev/null 2>&1", ply, drc, bits, cl);
    long size = 0;
    if (system(cmd) == 0) {
        FILE *f = fopen(drc, "rb");
        if (f && !fseek(f, 0, SEEK_END))
            size = ftell(f);
        if (f)
            fclose(f);
    }
    remove(ply), remove(drc);
    return size;
}

static double bits_per_tri(size_t bytes, uint32_t faces)
{
    return faces ? 8.0 * (double)bytes / faces : 0;
}

static void section_sizes(FILE *o, model *ms, int n)
{
    fprintf(o, "### Stream size against single-shot Draco\n\n"
               "Same cleaned mesh (welded, degenerate/duplicate faces dropped) for every column, Draco's in "
               "the input's order; "
               "pm = the progressive stream (version %u, header and record framing included; "
               "positions coded in the split records, docs/progressive-mesh.md §2.3 step 5, with lattice "
               "copies where the build found them smaller (lattice column); "
               "v4 payload = the same stream with its residuals in Draco payloads, as version 4 had them (`position_coding` 1)), "
               "Draco = stock `draco_encoder -cl 7` at the same quantization (`-qp`). Left: 12-bit "
               "positions and batches of 250 for every mesh (pm absolute: stock-readable positions); "
               "right: the stream's own per-mesh choices (`lumo-pm build`'s default: position bits "
               "from the median edge, batch size from the vertex count, docs/progressive-mesh.md "
               "§2.1).\n\n"
               "| model | triangles | vertices | base | pm 12 bits, 250 | bits/tri | v4 payload | pm absolute | "
               "draco -qp 12 -cl 7 | bits/tri | pm / draco | bits | batch | pm per mesh | bits/tri "
               "| draco same -qp | pm / draco | lattice | build s |\n"
               "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
               LUMO_PMESH_VERSION);
    for (int i = 0; i < n; i++) {
        model *m = &ms[i];
        uint8_t *s1 = NULL, *s0 = NULL, *sa = NULL, *sp = NULL;
        size_t l1 = 0, l0 = 0, la = 0, lp = 0;
        lumo_pmesh_header h = {0};
        stream_bits(m, 250, 12, LUMO_PMESH_POS_CODED, &s1, &l1);
        stream_bits(m, 250, 12, LUMO_PMESH_POS_PREDICTED, &sp, &lp);
        stream_bits(m, 250, 12, LUMO_PMESH_POS_ABSOLUTE, &s0, &l0);
        if (!stream_bits(m, 0, 0, LUMO_PMESH_POS_CODED, &sa, &la))
            (void)lumo_pmesh_read_header(sa, la, &h);
        long c7 = draco_cli_size(m, 12, 7), ca = draco_cli_size(m, (int)h.quant_bits, 7);
        uint32_t F = m->pm.faces;
        fprintf(o, "| %s | %u | %u | %u | %zu | %.2f | %zu | %zu | %ld | %.2f | %.3f | %u | %u | %zu | %.2f "
                   "| %ld | %.3f | %s | %.1f |\n",
                m->name, F, m->pm.vertices, m->pm.base_vertices, l1, bits_per_tri(l1, F), lp, l0, c7,
                bits_per_tri((size_t)c7, F), c7 ? (double)l1 / c7 : 0, h.quant_bits, h.batch_vertices,
                la, bits_per_tri(la, F), ca, ca ? (double)la / ca : 0,
                h.flags & LUMO_PMESH_LATTICE ? "yes" : "no", m->build_s);
        free(s1), free(s0), free(sa), free(sp);
    }
    fprintf(o, "\n");
}

/* Apply a whole stream with the client; per-batch times into t (seconds). */
static int run_client(const uint8_t *s, size_t len, double *t, uint32_t *nb, size_t *arena)
{
    srv_pm_client c;
    if (srv_pm_client_open(&c, s, len))
        return -1;
    *nb = 0;
    while (!lumo_pmesh_complete(&c.pm)) {
        double t0 = now();
        if (srv_pm_client_step(&c)) {
            srv_pm_client_close(&c);
            return -1;
        }
        t[(*nb)++] = now() - t0;
    }
    *arena = c.arena_bytes;
    srv_pm_client_close(&c);
    return 0;
}

static double sum(const double *t, uint32_t n)
{
    double s = 0;
    for (uint32_t i = 0; i < n; i++)
        s += t[i];
    return s;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static void section_fig5(FILE *o, const model *m)
{
    static const uint32_t sizes[] = {10, 25, 50, 100, 250, 500, 1000, 2500, 5000};
    size_t raw = 12 * (size_t)m->pm.vertices + 12 * (size_t)m->pm.faces;
    double raw_s = raw / LINK_BYTES_PER_S + LINK_RTT_S;
    fprintf(o, "### Receive + apply time against batch size (seed 000 §5.2, Fig. 5)\n\n"
               "%s (%u triangles). Link model: %.0f Mbit/s effective (802.11g-like) and one %.0f ms "
               "request round trip per batch; apply = measured client time (host, `-O2` liblumo, best "
               "of 3 runs) for the range decode (or a Draco payload) + vertex splits + normals. Raw transfer = one request for "
               "the uncompressed mesh (float xyz + uint32 triangles, %zu bytes): %.3f s. Overhead = "
               "total / raw − 1.\n\n"
               "| batch vertices | batches | stream bytes | transfer s | apply s | total s | overhead vs raw |\n"
               "|---|---|---|---|---|---|---|\n",
            m->name, m->pm.faces, LINK_BYTES_PER_S * 8 / 1e6, LINK_RTT_S * 1e3, raw, raw_s);
    for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; i++) {
        uint8_t *s = NULL;
        size_t len = 0, arena;
        if (stream(m, sizes[i], LUMO_PMESH_POS_PREDICTED, &s, &len))
            continue;
        double *t = malloc(sizeof *t * (m->pm.vertices + 2)), best = 1e30;
        uint32_t nb = 0;
        for (int rep = 0; rep < 3; rep++)
            if (!run_client(s, len, t, &nb, &arena) && sum(t, nb) < best)
                best = sum(t, nb);
        double xfer = len / LINK_BYTES_PER_S + nb * LINK_RTT_S, total = xfer + best;
        fprintf(o, "| %u | %u | %zu | %.3f | %.3f | %.3f | %+.0f%% |\n", sizes[i], nb, len, xfer, best,
                total, 100 * (total / raw_s - 1));
        free(t);
        free(s);
    }
    fprintf(o, "\n");
}

/* callgrind instructions inside lumo_pmesh_apply over the first `records`
 * records of the stream at `path`. */
static double callgrind_ir(const char *self, const char *path, int records)
{
    char out[64], cmd[4400], line[256];
    snprintf(out, sizeof out, "/tmp/lumo-pm-bench-%d.cg", (int)getpid());
    snprintf(cmd, sizeof cmd, "valgrind --tool=callgrind --callgrind-out-file=%s "
             "--toggle-collect=lumo_pmesh_apply %s apply %s %d >/dev/null 2>&1", out, self, path, records);
    double ir = -1;
    FILE *f;
    if (system(cmd) == 0 && (f = fopen(out, "r"))) {
        while (fgets(line, sizeof line, f))
            if (!strncmp(line, "summary:", 8))
                ir = strtod(line + 8, NULL);
        fclose(f);
    }
    remove(out);
    return ir;
}

/* Instructions per split batch (records 1 .. k, the base mesh excluded):
 * cache-independent work per batch. */
static double callgrind_per_batch(const char *self, const uint8_t *s, size_t len, uint32_t batches)
{
    char path[64];
    int k = batches - 1 < 40 ? (int)batches - 1 : 40;
    snprintf(path, sizeof path, "/tmp/lumo-pm-bench-%d.lpm", (int)getpid());
    FILE *f = fopen(path, "wb");
    if (k < 1 || !f || fwrite(s, 1, len, f) != len || fclose(f))
        return 0;
    double all = callgrind_ir(self, path, k + 1), base = callgrind_ir(self, path, 1);
    remove(path);
    return all < 0 || base < 0 ? 0 : (all - base) / k;
}

static void section_scaling(FILE *o, model *ms, int n, const char *self)
{
    fprintf(o, "### Client time and memory per batch against mesh size (batches of 250)\n\n"
               "Apply time per batch (host, `-O2`), over all batches after the base mesh. Arena = "
               "everything the client holds, sized from the stream header; per-batch working memory = "
               "arena minus the mesh arrays (42 B/vertex + 24 B/triangle): undo log, dirty list and "
               "the Draco decoder's scratch. Flat columns are the goal.\n\n"
               "Instructions: callgrind over `lumo_pmesh_apply` for split batches 1 … 40 (the base "
               "mesh excluded), which does not depend on caches: the host times grow with the mesh "
               "mostly because a bigger mesh's arrays miss the caches. p95/max include scheduling noise "
               "of a shared 2-core machine (single batches of a few ms that move between runs).\n\n"
               "| model | triangles | batches | median µs/batch | p95 µs | max µs | µs per split vertex "
               "| instructions per batch (1 … 40) | arena bytes | per-batch working bytes |\n"
               "|---|---|---|---|---|---|---|---|---|---|\n");
    for (int i = 0; i < n; i++) {
        model *m = &ms[i];
        uint8_t *s = NULL;
        size_t len = 0, arena = 0;
        if (stream(m, 250, LUMO_PMESH_POS_PREDICTED, &s, &len))
            continue;
        double *t = malloc(sizeof *t * (m->pm.vertices + 2));
        uint32_t nb = 0;
        if (!run_client(s, len, t, &nb, &arena) && nb > 1) {
            double *split = t + 1;  /* the base mesh is not a batch of splits */
            uint32_t k = nb - 1;
            double total = sum(split, k);
            qsort(split, k, sizeof *split, cmp_double);
            size_t mesh = 42 * (size_t)m->pm.vertices + 24 * (size_t)m->pm.faces;
            fprintf(o, "| %s | %u | %u | %.0f | %.0f | %.0f | %.2f | %.0f | %zu | %zu |\n", m->name,
                    m->pm.faces, nb, split[k / 2] * 1e6, split[(k * 95) / 100] * 1e6, split[k - 1] * 1e6,
                    total * 1e6 / (m->pm.vertices - m->pm.base_vertices),
                    callgrind_per_batch(self, s, len, nb), arena, arena - mesh);
        }
        free(t);
        free(s);
    }
    fprintf(o, "\n");
}

/* RMS distance of level k from the full mesh, in the quadric sense: every
 * full-resolution face's plane, area weighted, against the level's
 * positions of its three corners (each resolved at level k). */
static double level_rms(const srv_pm *pm, uint32_t k)
{
    double err = 0, area = 0;
    for (uint32_t f = 0; f < pm->faces; f++) {
        const uint32_t *t = pm->tris + 3 * (size_t)f;
        const float *a = pm->xyz + 3 * (size_t)t[0], *b = pm->xyz + 3 * (size_t)t[1],
                    *c = pm->xyz + 3 * (size_t)t[2];
        double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (len <= 0)
            continue;
        for (int i = 0; i < 3; i++) {
            const float *p = pm->xyz + 3 * (size_t)srv_pm_resolve(pm, t[i], k);
            double d = ((p[0] - a[0]) * n[0] + (p[1] - a[1]) * n[1] + (p[2] - a[2]) * n[2]) / len;
            err += 0.5 * len * d * d;
        }
        area += 1.5 * len;
    }
    return area > 0 ? sqrt(err / area) : 0;
}

static double bbox_diagonal(const srv_pm *pm)
{
    float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
    for (size_t i = 0; i < 3 * (size_t)pm->vertices; i++) {
        lo[i % 3] = pm->xyz[i] < lo[i % 3] ? pm->xyz[i] : lo[i % 3];
        hi[i % 3] = pm->xyz[i] > hi[i % 3] ? pm->xyz[i] : hi[i % 3];
    }
    double d[3] = {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]};
    return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

static void section_rounds(FILE *o, model *ms, int n)
{
    static const double at[] = {0.01, 0.05, 0.25};
    fprintf(o, "### Quality cost of independent-set rounds\n\n"
               "Same cleaned mesh simplified one collapse at a time (`round_fraction` 0, the QEM "
               "order) and in independent-set rounds (the default `round_fraction` 0.1: each round takes "
               "the valid, mutually independent collapses among the cheapest tenth of the candidates; "
               "1 = all of them). Error of a "
               "level = RMS distance of the level's corner positions from the planes of the full "
               "mesh's faces (area weighted, the quadric error), in units of 10⁻⁴ of the bounding-box "
               "diagonal; and the stream's lookup-table parent bits per split vertex.\n\n"
               "| model | order | base vertices | 1%% level | 5%% level | 25%% level | parent bits/vertex "
               "| stream bytes |\n|---|---|---|---|---|---|---|---|\n");
    for (int i = 0; i < n; i++) {
        static const double fraction[] = {0, -1, 1};  /* -1: the default */
        for (int j = 0; j < 3; j++) {
            srv_pm_options po;
            srv_pm pm;
            srv_pm_default_options(&po);
            if (fraction[j] >= 0)
                po.round_fraction = fraction[j];
            if (srv_pm_build(ms[i].xyz, ms[i].nv, ms[i].tris, ms[i].nf, &po, &pm))
                continue;
            double diag = bbox_diagonal(&pm), e[3];
            for (int l = 0; l < 3; l++) {
                uint32_t k = (uint32_t)(at[l] * pm.vertices);
                e[l] = 1e4 * level_rms(&pm, k > pm.base_vertices ? k : pm.base_vertices) / diag;
            }
            char order[32];
            if (po.round_fraction > 0)
                snprintf(order, sizeof order, "rounds %g", po.round_fraction);
            else
                snprintf(order, sizeof order, "one at a time");
            srv_pm_stream_stats st;
            uint8_t *s = NULL;
            size_t len = 0;
            if (!stream_stats(&pm, &st, &s, &len))
                fprintf(o, "| %s | %s | %u | %.2f | %.2f | %.2f | %.2f | %zu |\n", ms[i].name,
                        order, pm.base_vertices, e[0], e[1], e[2],
                        st.splits ? (double)st.parent_bits / st.splits : 0, len);
            free(s);
            srv_pm_free(&pm);
        }
    }
    fprintf(o, "\n");
}

/* Where the bits of the default stream go, per split vertex. */
static void section_bits(FILE *o, model *ms, int n)
{
    fprintf(o, "### Where the bits go (default stream, per split vertex)\n\n"
               "Fan = the fan's geometric rank (or the escape and the explicit first wing and length); "
               "record heads = the block's size (and a payload's) as varints plus a CRC-32 "
               "(docs/progressive-mesh.md §2).\n\n"
               "| model | parent | kind | fan | mask splits | positions | code flush "
               "| Draco payload | record heads | total bits/vertex | fan splits by rank |\n"
               "|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (int i = 0; i < n; i++) {
        srv_pm_stream_stats st;
        uint8_t *s = NULL;
        size_t len = 0;
        if (stream_stats(&ms[i].pm, &st, &s, &len) || !st.splits)
            continue;
        double sv = (double)st.splits, fields[8] = {st.parent_bits / sv, st.kind_bits / sv, st.fan_bits / sv,
                                                     st.mask_bits / sv, st.pos_bits / sv, st.other_bits / sv,
                                                     8.0 * st.draco_bytes / sv, 8.0 * st.frame_bytes / sv};
        fprintf(o, "| %s |", ms[i].name);
        double total = 0;
        for (int j = 0; j < 8; j++)
            fprintf(o, " %.2f |", fields[j]), total += fields[j];
        fprintf(o, " %.2f | %.1f%% |\n", total, st.fans ? 100.0 * st.arc_ranked / st.fans : 0.0);
        free(s);
    }
    fprintf(o, "\n");
}

int bench_main(int argc, char **argv)
{
    char self[4096];
    ssize_t sl = readlink("/proc/self/exe", self, sizeof self - 1);
    self[sl > 0 ? sl : 0] = 0;
    const char *out = NULL, *cmd = "lumo-pm bench", *fig5 = NULL;
    model ms[8];
    int n = 0, sizes_only = 0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--out") && i + 1 < argc)
            out = argv[++i];
        else if (!strcmp(argv[i], "--cmd") && i + 1 < argc)
            cmd = argv[++i];
        else if (!strcmp(argv[i], "--fig5") && i + 1 < argc)
            fig5 = argv[++i];
        else if (!strcmp(argv[i], "--sizes-only"))
            sizes_only = 1;  /* stream sizes and where the bits go: minutes, not hours */
        else if (n < 8 && access(argv[i], R_OK) == 0 && !load_model(argv[i], &ms[n]))
            n++;
        else
            fprintf(stderr, "lumo-pm bench: skipping %s\n", argv[i]);
    }
    FILE *o = out ? fopen(out, "w") : stdout;
    if (!o)
        return 1;
    fprintf(o, "## Progressive meshes\n\nMade by `%s`.\n\n", cmd);
    section_sizes(o, ms, n);
    fflush(o);
    section_bits(o, ms, n);
    fflush(o);
    if (!sizes_only) {
        section_rounds(o, ms, n);
        for (int i = 0; fig5 && i < n; i++)
            if (!strcmp(ms[i].path, fig5))
                section_fig5(o, &ms[i]);
        section_scaling(o, ms, n, self);
    }
    for (int i = 0; i < n; i++)
        free_model(&ms[i]);
    return o != stdout && fclose(o) ? 1 : 0;
}
