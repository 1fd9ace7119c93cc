/* bake_fixture.h — shared by the server tests: build a scene, bake a grid,
 * free everything (one bake = one fixture). */
#ifndef LUMO_TEST_BAKE_FIXTURE_H
#define LUMO_TEST_BAKE_FIXTURE_H

#include <stdio.h>
#include <string.h>
#include "bake/bake.h"
#include "scene/shapes.h"

typedef struct {
    srv_scene        scene;
    srv_rt          *rt;
    srv_tracer       tracer;
    srv_bake_result  res;
} bake_fixture;

/* Bake the (already built) scene on grid g; fails the test on error. */
static inline void fixture_bake(bake_fixture *f, const srv_grid *g, int spp, uint64_t seed, int threads)
{
    char err[256];
    srv_bake_opts o = {spp, seed, threads, 0, 0.25f};
    assert_int_equal(srv_scene_validate(&f->scene, err, sizeof err), 0);
    f->rt = srv_rt_create(&f->scene, threads, err, sizeof err);
    assert_non_null(f->rt);
    srv_tracer_init(&f->tracer, &f->scene, f->rt);
    if (srv_bake(&f->tracer, g, &o, &f->res, err, sizeof err))
        fail_msg("bake: %s", err);
}

static inline void fixture_free(bake_fixture *f)
{
    srv_bake_result_free(&f->res);
    srv_rt_free(f->rt);
    srv_scene_free(&f->scene);
}

/* I_delta . delta of vertex v, hemisphere h, channel ch. */
static inline double fixture_normal_component(const bake_fixture *f, size_t v, int h, int ch)
{
    double x = f->res.I[SRV_BAKE_I(v, h, ch) + (size_t)(h / 2)];
    return h & 1 ? -x : x;
}

static inline double fixture_se(const bake_fixture *f, size_t v, int h, int ch)
{
    return f->res.se[(v * 6 + (size_t)h) * 3 + (size_t)ch];
}

static inline srv_grid fixture_grid(vec3 lo, vec3 hi, int n)
{
    srv_grid g = {{n, n, n}, lo, hi};
    return g;
}

#endif
