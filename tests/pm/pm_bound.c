/* pm_bound.c — the simplifier's error bound (issue 23): with max_error e,
 * every input vertex lies within e times the bounding-box diagonal of the
 * surface of every level. The worst-case term guards the input vertices
 * attached to the faces a collapse changes, and a collapse over the limit
 * is refused, so the bound holds at every level, not only for the vertices
 * that collapsed into the one that moved. Checked by brute force (every
 * input vertex against every face) at the base and at 2, 10 and 50% of
 * the vertices, and with --first N at each of the N levels from the base
 * on (the seed renumbers the base's vertices, which may reorder the
 * commuting splits inside a round: each of those levels too).
 *
 *   pm_bound (--gen NAME | MODEL) [--max-error E] [--first N]
 *
 * Prints one line per level and "RESULT: N passed, M failed". */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "common/closest.h"
#include "pm/pm.h"
#include "pm/pm_load.h"
#include "pm_meshes.h"

static double diagonal(const srv_pm *pm)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY}, d = 0;
    for (uint32_t v = 0; v < pm->vertices; v++)
        for (int a = 0; a < 3; a++)
            lo[a] = fmin(lo[a], pm->xyz[3 * (size_t)v + a]), hi[a] = fmax(hi[a], pm->xyz[3 * (size_t)v + a]);
    for (int a = 0; a < 3; a++)
        d += (hi[a] - lo[a]) * (hi[a] - lo[a]);
    return sqrt(d);
}

static void corner(const srv_pm *pm, uint32_t v, double out[3])
{
    for (int a = 0; a < 3; a++)
        out[a] = pm->xyz[3 * (size_t)v + a];
}

/* The largest distance of an input vertex from the faces of level k. */
static double worst_distance(const srv_pm *pm, uint32_t k, uint32_t *tris)
{
    uint32_t nf = srv_pm_level(pm, k, tris);
    double worst = 0;
    for (uint32_t v = 0; v < pm->vertices; v++) {
        double p[3], best = INFINITY;
        corner(pm, v, p);
        for (uint32_t f = 0; f < nf && best > 0; f++) {
            double c[3][3];
            for (int i = 0; i < 3; i++)
                corner(pm, tris[3 * (size_t)f + i], c[i]);
            best = fmin(best, srv_triangle_dist2(p, c[0], c[1], c[2]));
        }
        worst = fmax(worst, best);
    }
    return sqrt(worst);
}

int main(int argc, char **argv)
{
    const char *gen = NULL, *file = NULL;
    uint32_t first = 0;
    srv_pm_options po;
    srv_pm_default_options(&po);
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--gen") && i + 1 < argc)
            gen = argv[++i];
        else if (!strcmp(argv[i], "--max-error") && i + 1 < argc)
            po.max_error = atof(argv[++i]);
        else if (!strcmp(argv[i], "--first") && i + 1 < argc)
            first = (uint32_t)atol(argv[++i]);
        else
            file = argv[i];
    }
    pm_test_mesh in = {0};
    char err[256];
    srv_pm pm;
    if ((gen ? pm_test_mesh_make(gen, &in) : !file || srv_pm_load(file, &in.xyz, NULL, &in.nv, &in.tris, &in.nf, err, sizeof err)) ||
        srv_pm_build(in.xyz, in.nv, in.tris, in.nf, &po, &pm)) {
        printf("FAIL %s: cannot load or build\nRESULT: 0 passed, 1 failed\n", gen ? gen : file ? file : "(nothing)");
        return 1;
    }
    uint32_t *tris = malloc(sizeof *tris * 3 * (size_t)(pm.faces ? pm.faces : 1));
    double limit = po.max_error * diagonal(&pm);
    const double at[] = {0, 0.02, 0.10, 0.50};
    int passed = 0, failed = 0;
    for (int i = 0; tris && i < 4; i++) {
        uint32_t k = (uint32_t)lround(at[i] * pm.vertices);
        k = k < pm.base_vertices ? pm.base_vertices : k;
        double d = worst_distance(&pm, k, tris);
        int ok = d <= limit * (1 + 1e-9);
        printf("%s %s: level %u of %u: every input vertex within %.3g of the surface, limit %.3g (max_error %g)\n",
               ok ? "ok  " : "FAIL", gen ? gen : file, k, pm.vertices, d, limit, po.max_error);
        passed += ok, failed += !ok;
    }
    if (first) {
        uint32_t end = pm.base_vertices + first, bad = 0, k;
        double worst = 0;
        end = end > pm.vertices + 1 ? pm.vertices + 1 : end;
        for (k = pm.base_vertices; tris && k < end; k++) {
            double d = worst_distance(&pm, k, tris);
            worst = fmax(worst, d);
            bad += d > limit * (1 + 1e-9);
        }
        int ok = tris && !bad;
        printf("%s %s: levels %u..%u: every input vertex within %.3g of the surface, limit %.3g, %u levels over\n",
               ok ? "ok  " : "FAIL", gen ? gen : file, pm.base_vertices, end - 1, worst, limit, bad);
        passed += ok, failed += !ok;
    }
    printf("RESULT: %d passed, %d failed\n", passed, failed);
    free(tris);
    srv_pm_free(&pm);
    pm_test_mesh_free(&in);
    return failed || !passed;
}
