/*
 * dyn_error.c — the dynamic engine against the path tracer at the same
 * moment (docs/dynamic.md "Error"): the scene file's motion is run step by
 * step (scripted time, deterministic); at each time asked the engine is
 * left to settle (every change's photons out of the pool, then the IVG
 * updated), and its IVG from the VSLs is compared with a path-traced bake
 * of the scene posed at that moment on the same grid. Also reports the
 * latency from a change to its settling (photon paths, wall seconds).
 *
 *   dyn-error SCENE [--times T,T,...] [--vsl N] [--pool N] [--batch N]
 *             [--grid N] [--spp N]
 *
 * Error: over the grid vertices the bake finds valid, the hemispheres'
 * normal components (I_delta . delta) of the three channels,
 * sum |VSL - traced| / sum |traced|; the bake's own noise (its standard
 * errors over the same sum) is printed beside it.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "bake/bake.h"
#include "scene/import.h"
#include "vsl/vsl_engine.h"
#include "lumo_host/options.h"

static int fail(const char *m)
{
    fprintf(stderr, "dyn-error: error: %s\n", m);
    return 1;
}

static double normal_part(const float *I, const double *J, size_t v, int h, int ch)
{
    size_t at = I ? SRV_BAKE_I(v, h, ch) + (size_t)(h / 2) : v * SRV_VSL_IVG_VALUES + (size_t)((h * 3 + ch) * 3 + h / 2);
    double x = I ? I[at] : J[at];
    return h & 1 ? -x : x;
}

static void compare(const srv_bake_result *ref, const srv_vsl_ivg *ivg, double *err, double *noise)
{
    double diff = 0, sum = 0, se = 0;
    for (size_t v = 0; v < ref->nverts; v++) {
        if (!ref->valid[v])
            continue;
        for (int h = 0; h < 6; h++)
            for (int ch = 0; ch < 3; ch++) {
                double r = normal_part(ref->I, NULL, v, h, ch), g = normal_part(NULL, ivg->I, v, h, ch);
                diff += fabs(g - r);
                sum += fabs(r);
                se += ref->se[(v * 6 + (size_t)h) * 3 + (size_t)ch];
            }
    }
    *err = sum > 0 ? diff / sum : 0;
    *noise = sum > 0 ? se / sum : 0;
}

/* One option and its value, strictly (lumo_host/options.h): 0, or -1 with
 * the refusal naming both in err. */
static int take(const char *a, const char *v, srv_vsl_engine_opts *o, double *times, int *ntimes, int *grid,
                int *spp, char *err, size_t errlen)
{
    int64_t n;
    if (!strcmp(a, "--times"))
        return host_opt_list(a, v, 0, 1e6, 1, times, 16, ntimes, err, errlen);
    if (!strcmp(a, "--grid"))
        return host_opt_int(a, v, 2, 256, grid, err, errlen);
    if (!strcmp(a, "--spp"))
        return host_opt_int(a, v, 1, 1 << 20, spp, err, errlen);
    if (strcmp(a, "--vsl") && strcmp(a, "--pool") && strcmp(a, "--batch"))
        return snprintf(err, errlen, "%s: unknown option", a), -1;
    if (host_opt_i64(a, v, 1, (int64_t)1e12, &n, err, errlen))
        return -1;
    if (a[2] == 'v')
        o->nv = (size_t)n;
    else if (a[2] == 'p')
        o->pool = (size_t)n;
    else
        o->batch = (uint64_t)n;
    return 0;
}

int main(int argc, char **argv)
{
    double times[16] = {0, 3, 6, 9};
    int ntimes = 4, grid = 12, spp = 256;
    srv_vsl_engine_opts o = srv_vsl_engine_defaults();
    char err[400];
    if (argc < 2)
        return fail("usage: dyn-error SCENE [--times T,..] [--vsl N] [--pool N] [--batch N] [--grid N] [--spp N]");
    for (int i = 2; i < argc; i += 2) {
        if (i + 1 == argc)
            return fail("an option without its value (try: dyn-error SCENE --times 0,3,6)");
        if (take(argv[i], argv[i + 1], &o, times, &ntimes, &grid, &spp, err, sizeof err))
            return fail(err);
    }
    srv_scene s;
    srv_motion m = {0};
    srv_scene_init(&s);
    if (srv_scene_load(&s, argv[1], err, sizeof err) || srv_motion_load(&m, &s, argv[1], err, sizeof err))
        return fail(err);
    o.dims[0] = o.dims[1] = o.dims[2] = grid;
    srv_vsl_engine *e = srv_vsl_engine_create(&s, &m, &o, err, sizeof err);
    if (!e)
        return fail(err);
    const srv_vsl_ivg *ivg = srv_vsl_engine_ivg(e);
    printf("dyn-error: %s: %zu VSLs, pool %zu, %llu paths a step, grid %d^3, reference %d spp\n", argv[1], o.nv,
           o.pool, (unsigned long long)o.batch, grid, spp);
    printf("  time s | steps to settle | latency paths | latency s | IVG error vs path traced | reference noise\n");
    for (int k = 0; k < ntimes; k++) {
        int steps = srv_vsl_engine_settle(e, times[k], 10000);
        srv_vsl_latency lat = srv_vsl_engine_latency(e);
        srv_scene posed;
        srv_bake_result ref;
        srv_bake_opts bo = {spp, 1, 2, 0, 0.25f};
        srv_tracer tr;
        double er, noise;
        if (srv_vsl_engine_posed_scene(e, &s, &posed))
            return fail("out of memory");
        srv_rt *rt = srv_rt_create(&posed, 2, err, sizeof err);
        if (!rt)
            return fail(err);
        srv_tracer_init(&tr, &posed, rt);
        if (srv_bake(&tr, &ivg->grid, &bo, &ref, err, sizeof err))
            return fail(err);
        compare(&ref, ivg, &er, &noise);
        printf("  %6.2f | %15d | %13llu | %9.3f | %23.1f%% | %14.1f%%\n", times[k], steps,
               (unsigned long long)lat.last_paths, lat.last_s, 100 * er, 100 * noise);
        srv_bake_result_free(&ref);
        srv_rt_free(rt);
        srv_scene_free(&posed);
    }
    srv_vsl_latency lat = srv_vsl_engine_latency(e);
    printf("dyn-error: %llu changes settled, latency mean %.3f s, max %.3f s (change -> pool turned over -> IVG "
           "updated)\n", (unsigned long long)lat.settled, lat.mean_s, lat.max_s);
    srv_vsl_engine_free(e);
    srv_scene_free(&s);
    return 0;
}
