/* bench/pm_quality.c — `make bench-pm-quality`: lumo's progressive-mesh
 * levels against meshoptimizer's meshopt_simplify (the benchmark-only peer,
 * Debian libmeshoptimizer-dev) on the same cleaned mesh, at the same
 * triangle count, measured against the original surface: symmetric RMS and
 * sampled Hausdorff distance in units of the bounding-box diagonal; and how
 * far each simplifies (the base mesh, the first picture's cost).
 *
 *   pm-quality --out FILE.md --cmd "COMMAND" KIND:MODEL...
 */
#include <float.h>
#include <math.h>
#include <meshoptimizer.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "pm/pm_load.h"
#include "pm/pm.h"
#include "pm_surface.h"

#define SAMPLES 100000u  /* area samples per direction, plus every corner */

static const double LEVELS[] = {0.02, 0.05, 0.10, 0.20, 0.35, 0.50};
#define NLEVELS (sizeof LEVELS / sizeof LEVELS[0])

typedef struct { double rms, hausdorff; uint32_t tris, verts; } measure;

typedef struct {
    const char *kind, *name;
    srv_pm      pm;
    uint32_t   *full, nf;      /* the cleaned input, resolved at level n */
    float      *peer_xyz;      /* the same mesh in an order of its own for meshoptimizer */
    uint32_t   *peer_tris, *peer_to_pm; /* (whose result depends on the order), not lumo's */
    pm_surface *orig;
    double      diag, build_s;
} model;

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + t.tv_nsec * 1e-9;
}

static double bbox_diagonal(const float *xyz, uint32_t n)
{
    double lo[3] = {DBL_MAX, DBL_MAX, DBL_MAX}, hi[3] = {-DBL_MAX, -DBL_MAX, -DBL_MAX}, d = 0;
    for (uint32_t v = 0; v < n; v++)
        for (int a = 0; a < 3; a++)
            lo[a] = fmin(lo[a], xyz[3 * (size_t)v + a]), hi[a] = fmax(hi[a], xyz[3 * (size_t)v + a]);
    for (int a = 0; a < 3; a++)
        d += (hi[a] - lo[a]) * (hi[a] - lo[a]);
    return sqrt(d);
}

static uint32_t used_vertices(const uint32_t *tris, uint32_t nf, uint32_t nv)
{
    uint8_t *seen = calloc(nv ? nv : 1, 1);
    uint32_t n = 0;
    for (size_t i = 0; seen && i < 3 * (size_t)nf; i++)
        n += !seen[tris[i]], seen[tris[i]] = 1;
    free(seen);
    return n;
}

/* Symmetric distance between the simplified faces and the original. */
static measure measure_faces(const model *m, const uint32_t *tris, uint32_t nf)
{
    measure r = {0, 0, nf, used_vertices(tris, nf, m->pm.vertices)};
    pm_surface *s = pm_surface_open(m->pm.xyz, tris, nf);
    double ms_a, mx_a, ms_b, mx_b;
    if (!s)
        return r;
    pm_surface_one_sided(m->pm.xyz, tris, nf, m->orig, SAMPLES, 0x9e3779b97f4a7c15ull, &ms_a, &mx_a);
    pm_surface_one_sided(m->pm.xyz, m->full, m->nf, s, SAMPLES, 0xd1b54a32d192ed03ull, &ms_b, &mx_b);
    pm_surface_close(s);
    r.rms = sqrt(0.5 * (ms_a + ms_b)) / m->diag;
    r.hausdorff = fmax(mx_a, mx_b) / m->diag;
    return r;
}

static measure measure_lumo(const model *m, uint32_t k, uint32_t *buf)
{
    return measure_faces(m, buf, srv_pm_level(&m->pm, k, buf));
}

/* meshoptimizer asked for at most `tris` triangles, into buf in lumo's
 * vertex numbering; the triangle count. */
static uint32_t run_meshopt(const model *m, uint32_t tris, uint32_t *buf)
{
    float err = 0;
    size_t n = meshopt_simplify(buf, m->peer_tris, 3 * (size_t)m->nf, m->peer_xyz, m->pm.vertices,
                                3 * sizeof(float), 3 * (size_t)tris, FLT_MAX, 0, &err);
    for (size_t i = 0; i < n; i++)
        buf[i] = m->peer_to_pm[buf[i]];
    return (uint32_t)(n / 3);
}

static measure measure_meshopt(const model *m, uint32_t tris, uint32_t *buf)
{
    return measure_faces(m, buf, run_meshopt(m, tris, buf));
}

/* The peer's input: vertices in the cleaned input's order (by the input
 * vertex each stands for), faces sorted by their corners in that order,
 * each turned to start at its smallest corner. Nothing of lumo's
 * simplification shows in it: lumo's progressive order fed to meshoptimizer
 * moved its errors by up to 16% from one lumo version to the next (bunny
 * 2%: RMS 158.9 in one, 184.9 in the next). */
static const uint32_t *g_src, *g_tri;  /* qsort contexts */

static int cmp_source(const void *a, const void *b)
{
    uint32_t x = g_src[*(const uint32_t *)a], y = g_src[*(const uint32_t *)b];
    return (x > y) - (x < y);
}

static int cmp_face(const void *a, const void *b)
{
    const uint32_t *x = g_tri + 3 * (size_t)*(const uint32_t *)a, *y = g_tri + 3 * (size_t)*(const uint32_t *)b;
    for (int k = 0; k < 3; k++)
        if (x[k] != y[k])
            return x[k] < y[k] ? -1 : 1;
    return 0;
}

static int peer_input(model *m)
{
    uint32_t n = m->pm.vertices, *to_peer = malloc(sizeof *to_peer * (n ? n : 1));
    uint32_t *tris = malloc(sizeof *tris * 3 * (size_t)m->nf), *order = malloc(sizeof *order * (m->nf ? m->nf : 1));
    m->peer_to_pm = malloc(sizeof *m->peer_to_pm * (n ? n : 1));
    m->peer_xyz = malloc(sizeof *m->peer_xyz * 3 * (size_t)(n ? n : 1));
    m->peer_tris = malloc(sizeof *m->peer_tris * 3 * (size_t)m->nf);
    if (!to_peer || !tris || !order || !m->peer_to_pm || !m->peer_xyz || !m->peer_tris)
        return free(to_peer), free(tris), free(order), -1;
    for (uint32_t v = 0; v < n; v++)
        m->peer_to_pm[v] = v;
    g_src = m->pm.source;
    qsort(m->peer_to_pm, n, sizeof *m->peer_to_pm, cmp_source);
    for (uint32_t i = 0; i < n; i++) {
        to_peer[m->peer_to_pm[i]] = i;
        memcpy(m->peer_xyz + 3 * (size_t)i, m->pm.xyz + 3 * (size_t)m->peer_to_pm[i], 3 * sizeof(float));
    }
    for (uint32_t f = 0; f < m->nf; f++) {
        const uint32_t *t = m->full + 3 * (size_t)f;
        uint32_t a = to_peer[t[0]], b = to_peer[t[1]], c = to_peer[t[2]];
        uint32_t *o = tris + 3 * (size_t)f;
        if (a < b && a < c)
            o[0] = a, o[1] = b, o[2] = c;
        else if (b < c)
            o[0] = b, o[1] = c, o[2] = a;
        else
            o[0] = c, o[1] = a, o[2] = b;
        order[f] = f;
    }
    g_tri = tris;
    qsort(order, m->nf, sizeof *order, cmp_face);
    for (uint32_t f = 0; f < m->nf; f++)
        memcpy(m->peer_tris + 3 * (size_t)f, tris + 3 * (size_t)order[f], 3 * sizeof *tris);
    free(to_peer), free(tris), free(order);
    return 0;
}

static int load(const char *arg, model *m)
{
    char err[256];
    float *xyz;
    uint32_t *tris, nv, nf;
    const char *colon = strchr(arg, ':');
    memset(m, 0, sizeof *m);
    if (!colon)
        return fprintf(stderr, "pm-quality: %s is not KIND:MODEL\n", arg), -1;
    m->kind = strndup(arg, (size_t)(colon - arg));
    m->name = strrchr(arg, '/') ? strrchr(arg, '/') + 1 : colon + 1;
    if (srv_pm_load(colon + 1, &xyz, NULL, &nv, &tris, &nf, err, sizeof err))
        return fprintf(stderr, "pm-quality: %s\n", err), -1;
    double t0 = now();
    lumo_status rc = srv_pm_build(xyz, nv, tris, nf, NULL, &m->pm);
    m->build_s = now() - t0;
    free(xyz);
    free(tris);
    if (rc)
        return fprintf(stderr, "pm-quality: %s: build failed (%d)\n", arg, rc), -1;
    m->nf = m->pm.faces;
    m->full = malloc(sizeof *m->full * 3 * (size_t)m->nf);
    if (!m->full)
        return -1;
    srv_pm_level(&m->pm, m->pm.vertices, m->full);
    m->diag = bbox_diagonal(m->pm.xyz, m->pm.vertices);
    m->orig = pm_surface_open(m->pm.xyz, m->full, m->nf);
    return m->orig && !peer_input(m) ? 0 : -1;
}

static void unload(model *m)
{
    pm_surface_close(m->orig);
    free(m->full);
    free(m->peer_xyz);
    free(m->peer_tris);
    free(m->peer_to_pm);
    free((char *)m->kind);
    srv_pm_free(&m->pm);
}

static const char *ratio_mark(double lumo, double peer)
{
    return lumo <= peer * 1.0005 + 1e-12 ? "" : " ✗";
}

/* The coarsest level with at least nf faces (lumo's level at
 * meshoptimizer's count, where meshoptimizer cannot go as far as lumo). */
static uint32_t level_with_faces(const model *m, uint32_t nf)
{
    uint32_t k = m->pm.base_vertices;
    while (k < m->pm.vertices && srv_pm_level_faces(&m->pm, k) < nf)
        k++;
    return k;
}

static void quality_rows(FILE *o, const model *m)
{
    uint32_t *buf = malloc(sizeof *buf * 3 * (size_t)m->nf);
    if (!buf)
        return;
    for (size_t l = 0; l < NLEVELS; l++) {
        uint32_t k = (uint32_t)lround(LEVELS[l] * m->pm.vertices);
        if (k < m->pm.base_vertices) {
            fprintf(o, "| %s | %s | %.0f%% | base is %u vertices | | | | | | |\n", m->name, m->kind,
                    100 * LEVELS[l], m->pm.base_vertices);
            continue;
        }
        measure a = measure_lumo(m, k, buf), b = measure_meshopt(m, a.tris, buf);
        int stuck = b.tris > a.tris + a.tris / 100;  /* meshopt stopped short of lumo's count */
        if (stuck)
            a = measure_lumo(m, level_with_faces(m, b.tris), buf);
        fprintf(o, "| %s | %s | %.0f%%%s | %u / %u | %u / %u | %.2f | %.2f | %.2f%s | %.1f | %.1f | %.2f%s |\n",
                m->name, m->kind, 100 * LEVELS[l], stuck ? " †" : "", a.tris, a.verts, b.tris, b.verts, 1e4 * a.rms,
                1e4 * b.rms, a.rms / b.rms, ratio_mark(a.rms, b.rms), 1e4 * a.hausdorff,
                1e4 * b.hausdorff, a.hausdorff / b.hausdorff, ratio_mark(a.hausdorff, b.hausdorff));
        fflush(o);
    }
    free(buf);
}

/* How far each goes: lumo's base, meshoptimizer asked for no triangle at
 * all (it stops where its own guards stop it). */
static void base_row(FILE *o, const model *m)
{
    uint32_t *buf = malloc(sizeof *buf * 3 * (size_t)m->nf);
    if (!buf)
        return;
    uint32_t n = 3 * run_meshopt(m, 0, buf);
    uint32_t goal = m->pm.vertices / 50 > 100 ? m->pm.vertices / 50 : 100;
    fprintf(o, "| %s | %s | %u / %u | %u / %u (%.1f%%) | %u | %u / %u | %.2f s |\n", m->name, m->kind,
            m->pm.vertices, m->pm.faces, m->pm.base_vertices, m->pm.base_faces,
            100.0 * m->pm.base_vertices / m->pm.vertices, goal,
            used_vertices(buf, (uint32_t)(n / 3), m->pm.vertices), (uint32_t)(n / 3), m->build_s);
    free(buf);
}

int main(int argc, char **argv)
{
    const char *out = NULL, *cmd = "";
    int first = 1;
    for (; first + 1 < argc && argv[first][0] == '-'; first += 2) {
        if (!strcmp(argv[first], "--out"))
            out = argv[first + 1];
        else if (!strcmp(argv[first], "--cmd"))
            cmd = argv[first + 1];
    }
    int nm = argc - first;
    model *ms = calloc(nm > 0 ? (size_t)nm : 1, sizeof *ms);
    FILE *o = out ? fopen(out, "w") : stdout;
    if (!ms || !o || nm <= 0)
        return fprintf(stderr, "usage: pm-quality [--out FILE.md] [--cmd TEXT] KIND:MODEL...\n"), 2;
    for (int i = 0; i < nm; i++)
        if (load(argv[first + i], &ms[i]))
            return 1;
    fprintf(o, "## Progressive meshes: simplification quality against meshoptimizer\n\n"
               "Made by `%s`. Peer: meshoptimizer %d.%d `meshopt_simplify` (no error limit, "
               "borders free) on the same cleaned mesh, asked for lumo's triangle count at "
               "each level. Errors against the original surface in 10⁻⁴ of the bounding-box "
               "diagonal: symmetric RMS over %u area samples each way, Hausdorff as the largest "
               "distance of those samples and every corner, both ways. Ratio lumo / meshoptimizer; "
               "✗ marks a level where lumo is worse. † marks a level meshoptimizer cannot reach "
               "(its guards stop it above lumo's triangle count): there lumo is measured at "
               "meshoptimizer's count instead (its level with at least that many triangles).\n\n",
            cmd, MESHOPTIMIZER_VERSION / 1000, MESHOPTIMIZER_VERSION % 1000 / 10, SAMPLES);
    fprintf(o, "| mesh | kind | level | lumo tris / verts | meshopt tris / verts | lumo RMS | meshopt RMS "
               "| ratio | lumo Hausdorff | meshopt Hausdorff | ratio |\n"
               "|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (int i = 0; i < nm; i++)
        quality_rows(o, &ms[i]);
    fprintf(o, "\nHow far each simplifies (lumo's base mesh is the first picture; the goal is "
               "at most 2%% of the vertices or 100, whichever is larger):\n\n"
               "| mesh | kind | vertices / faces | lumo base vertices / faces | goal | meshopt minimum "
               "vertices / faces | lumo build |\n|---|---|---|---|---|---|---|\n");
    for (int i = 0; i < nm; i++)
        base_row(o, &ms[i]);
    for (int i = 0; i < nm; i++)
        unload(&ms[i]);
    free(ms);
    if (out)
        fclose(o);
    return 0;
}
