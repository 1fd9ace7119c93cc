/*
 * test_vsl_pool.c — photon streaming (seed 004 §0.5, Algorithm 2):
 *  - flux conserved: after millions of impacts through a small pool, every
 *    VSL's flux equals the sum over the pool's photons linked to it, and
 *    the VSLs' total equals the pool's, exactly (integer books);
 *  - turnover: once a pool's worth of new impacts has arrived, nothing of
 *    the old lighting is left;
 *  - the k-d tree's nearest VSL is the linear scan's;
 *  - the instanced ray scene: a moved object is hit where it now is;
 *  - a static scene's VSL lighting converges to the path tracer's as the
 *    pool grows (the empty Cornell room: convex, so the VSLs' missing
 *    visibility costs nothing and the error left is the VSLs' spacing).
 */
#include "test_common.h"
#include <stdio.h>
#include <stdlib.h>
#include "bake/trace.h"
#include "common/sample.h"
#include "scene/shapes.h"
#include "vsl/vsl_light.h"

static void check_books(const srv_vsl_pool *p)
{
    int64_t *want = calloc(3 * p->nvsl, sizeof *want), tot_pool = 0, tot_vsl = 0;
    assert_non_null(want);
    for (size_t i = 0; i < p->len; i++)
        for (int c = 0; c < 3; c++) {
            want[3 * p->ring[i].vsl + (size_t)c] += p->ring[i].flux[c];
            tot_pool += p->ring[i].flux[c];
        }
    for (size_t v = 0; v < 3 * p->nvsl; v++) {
        assert_true(p->acc[v] >= 0);
        assert_true(p->acc[v] == want[v]);
        tot_vsl += p->acc[v];
    }
    assert_true(tot_vsl == tot_pool);
    free(want);
}

static void test_flux_conserved(void **state)
{
    (void)state;
    srv_vsl_pool p;
    test_rng r = {77};
    assert_int_equal(srv_vsl_pool_init(&p, 100003, 997), LUMO_OK);
    for (uint64_t k = 0; k < 3000000; k++) {
        uint32_t f[3] = {(uint32_t)(test_rng_next(&r) >> 40), (uint32_t)(test_rng_next(&r) >> 41),
                         (uint32_t)(test_rng_next(&r) % 3 ? test_rng_next(&r) >> 33 : 0)};
        srv_vsl_pool_push(&p, (uint32_t)(test_rng_next(&r) % 997), f, k / 3);
        if (k == 50000 || k == 100002 || k == 100003 || k % 1000000 == 999999)
            check_books(&p);
    }
    assert_int_equal(p.len, 100003);
    assert_true(p.impacts == 3000000);
    /* 100003 impacts, three per emission: the pool spans ~33335 emissions. */
    uint64_t e = srv_vsl_pool_emissions(&p);
    assert_true(e >= 33334 && e <= 33336);
    printf("# 3 000 000 impacts through a pool of 100 003: books balance to the unit\n");
    srv_vsl_pool_free(&p);
}

static void test_turnover(void **state)
{
    (void)state;
    srv_vsl_pool p;
    uint32_t f[3] = {5, 6, 7};
    assert_int_equal(srv_vsl_pool_init(&p, 1000, 10), LUMO_OK);
    for (uint32_t k = 0; k < 2500; k++)
        srv_vsl_pool_push(&p, k % 10, f, k);
    for (uint32_t k = 0; k < 999; k++)
        srv_vsl_pool_push(&p, 3, f, 2500 + k);
    assert_true(p.acc[3 * 9] == 5);   /* one old photon left, the oldest: push 2499 to VSL 9 */
    srv_vsl_pool_push(&p, 3, f, 3499);
    for (size_t v = 0; v < 10; v++)
        assert_true(p.acc[3 * v] == (v == 3 ? 5000 : 0));
    assert_true(srv_vsl_pool_oldest(&p)->emitted == 2500);
    check_books(&p);
    srv_vsl_pool_free(&p);
    assert_int_equal(srv_vsl_pool_init(&p, 0, 10), LUMO_ERR_ARG);
}

static void empty_room(srv_scene *s, int with_ball)
{
    vec3 white = v3(0.75f, 0.75f, 0.75f), red = v3(0.63f, 0.065f, 0.05f), green = v3(0.14f, 0.45f, 0.091f);
    srv_scene_init(s);
    assert_int_equal(srv_add_quad(s, "floor", v3(-1, 0, -1), v3(0, 0, 2), v3(2, 0, 0), white), 0);
    assert_int_equal(srv_add_quad(s, "ceiling", v3(-1, 2, -1), v3(2, 0, 0), v3(0, 0, 2), white), 0);
    assert_int_equal(srv_add_quad(s, "back", v3(-1, 0, -1), v3(2, 0, 0), v3(0, 2, 0), white), 0);
    assert_int_equal(srv_add_quad(s, "left-red", v3(-1, 0, -1), v3(0, 2, 0), v3(0, 0, 2), red), 0);
    assert_int_equal(srv_add_quad(s, "right-green", v3(1, 0, -1), v3(0, 0, 2), v3(0, 2, 0), green), 0);
    if (with_ball)
        assert_int_equal(srv_add_sphere(s, "ball", v3(0, 0.45f, 0), 0.45f, 32, white, 0), 0);
    srv_light spot = {.kind = LUMO_LIGHT_SPOT, .pos = {0, 1.95f, 0}, .dir = {0, -1, 0},
                      .half_angle_deg = 60.0f, .cos_half = 0.5f, .power = {40, 40, 40}};
    assert_int_equal(srv_scene_add_light(s, &spot), 0);
}

/* The nearest VSL against a linear scan, on both sides of vsl_index.c's
 * threshold: 500 VSLs (every object under 256: scanned) and 4 000 (every
 * object over it: the k-d tree). */
static void nearest_case(size_t nv, int tree)
{
    srv_scene s;
    srv_vsl_set set;
    srv_vsl_index ix;
    char err[128];
    test_rng r = {5};
    empty_room(&s, 1);
    srv_vsl_place_opts o = srv_vsl_place_defaults(nv, 3);
    assert_int_equal(srv_vsl_place(&s, &o, &set, err, sizeof err), LUMO_OK);
    assert_int_equal(srv_vsl_index_build(&ix, &set), LUMO_OK);
    for (size_t k = 0; k < set.nobjects; k++)
        assert_true(tree ? set.count[k] >= 256 : set.count[k] < 256);
    for (int k = 0; k < 20000; k++) {
        uint32_t ob = (uint32_t)(test_rng_next(&r) % set.nobjects);
        vec3 p = v3((float)test_rng_uniform(&r, -1.2, 1.2), (float)test_rng_uniform(&r, -0.2, 2.2),
                    (float)test_rng_uniform(&r, -1.2, 1.2));
        uint32_t best = UINT32_MAX;
        float bd = INFINITY;
        for (uint32_t i = set.first[ob]; i < set.first[ob] + set.count[ob]; i++) {
            vec3 d = v3_sub(p, set.v[i].pos);
            if (v3_dot(d, d) < bd)
                bd = v3_dot(d, d), best = i;
        }
        assert_int_equal(srv_vsl_index_nearest(&ix, ob, p), best);
    }
    assert_int_equal(srv_vsl_index_nearest(&ix, 99, v3(0, 0, 0)), UINT32_MAX);
    srv_vsl_index_free(&ix);
    srv_vsl_set_free(&set);
    srv_scene_free(&s);
}

static void test_nearest_matches_scan(void **state)
{
    (void)state;
    nearest_case(500, 0);
    nearest_case(4000, 1);
}

static void test_instance_moves(void **state)
{
    (void)state;
    srv_scene s;
    char err[128];
    srv_vsl_hit h;
    empty_room(&s, 1);
    srv_vsl_rt *rt = srv_vsl_rt_create(&s, err, sizeof err);
    assert_non_null(rt);
    /* Straight down at x = 0: the ball's top at y = 0.9. */
    assert_true(srv_vsl_rt_intersect(rt, v3(0, 1.5f, 0), v3(0, -1, 0), 0, INFINITY, &h));
    assert_int_equal(h.object, 5);
    assert_close(h.t, 0.6, 1e-3);
    /* Moved 0.5 m along +x and turned: down at x = 0 now meets its side. */
    srv_pose p = srv_pose_make(v3(0.5f, 0, 0), 30.0f);
    srv_vsl_rt_set_pose(rt, 5, &p);
    srv_vsl_rt_commit(rt);
    assert_true(srv_vsl_rt_intersect(rt, v3(0.5f, 1.5f, 0), v3(0, -1, 0), 0, INFINITY, &h));
    assert_int_equal(h.object, 5);
    assert_close(h.t, 0.6, 1e-3);
    assert_close(h.n.y, 1.0, 2e-2);
    vec3 back = srv_pose_point(&p, h.local);   /* local point maps back to the hit */
    assert_close(back.x, 0.5, 1e-4);
    assert_close(back.y, 0.9, 1e-3);
    assert_true(srv_vsl_rt_intersect(rt, v3(-0.3f, 1.5f, 0), v3(0, -1, 0), 0, INFINITY, &h));
    assert_int_equal(h.object, 0);   /* where the ball was: the floor */
    srv_vsl_rt_free(rt);
    srv_scene_free(&s);
}

/* Path-traced indirect irradiance at (x, n): pi times the mean indirect
 * radiance over cosine-distributed directions. */
static vec3 traced_irradiance(const srv_tracer *t, vec3 x, vec3 n, int paths, srv_rng *r)
{
    srv_trace_stats st = {0};
    vec3 sum = v3(0, 0, 0);
    vec3 o = v3_add(x, v3_scale(n, 1e-4f));
    for (int k = 0; k < paths; k++)
        sum = v3_add(sum, srv_trace_indirect(t, o, srv_cosine_dir(n, r), r, &st, NULL));
    return v3_scale(sum, (float)M_PI / (float)paths);
}

enum { NPROBE = 20 };

static void probes(vec3 *x, vec3 *n)
{
    for (int i = 0; i < NPROBE; i++) {
        float a = -0.6f + 0.4f * (float)(i % 4), b = 0.4f + 0.4f * (float)((i / 4) % 4);
        switch (i % 5) {
        case 0: x[i] = v3(a, 0, b - 1.0f), n[i] = v3(0, 1, 0); break;        /* floor */
        case 1: x[i] = v3(a, b, -1), n[i] = v3(0, 0, 1); break;               /* back */
        case 2: x[i] = v3(-1, b, a), n[i] = v3(1, 0, 0); break;               /* red */
        case 3: x[i] = v3(1, b, a), n[i] = v3(-1, 0, 0); break;               /* green */
        default: x[i] = v3(a, 2, b - 1.0f), n[i] = v3(0, -1, 0); break;       /* ceiling */
        }
    }
}

/* Mean over probes and channels of |VSL - traced| / traced. */
static double vsl_error(const srv_vsl_lit *lit, size_t n, const vec3 *x, const vec3 *nn, const vec3 *ref)
{
    double sum = 0.0;
    for (int i = 0; i < NPROBE; i++) {
        vec3 e = srv_vsl_irradiance(lit, n, x[i], nn[i], SRV_VSL_EPSILON);
        for (int c = 0; c < 3; c++)
            sum += fabs((double)v3_get(e, c) - (double)v3_get(ref[i], c)) / (double)v3_get(ref[i], c);
    }
    return sum / (3.0 * NPROBE);
}

static void test_converges_to_path_tracer(void **state)
{
    (void)state;
    srv_scene s;
    srv_vsl_set set;
    srv_vsl_index ix;
    char err[128];
    vec3 x[NPROBE], n[NPROBE], ref[NPROBE];
    empty_room(&s, 0);
    probes(x, n);
    srv_rt *frt = srv_rt_create(&s, 1, err, sizeof err);
    srv_tracer tr;
    srv_rng r;
    srv_tracer_init(&tr, &s, frt);
    srv_rng_seed(&r, 11, 0);
    for (int i = 0; i < NPROBE; i++)
        ref[i] = traced_irradiance(&tr, x[i], n[i], 20000, &r);
    srv_vsl_place_opts o = srv_vsl_place_defaults(1500, 1);
    assert_int_equal(srv_vsl_place(&s, &o, &set, err, sizeof err), LUMO_OK);
    assert_int_equal(srv_vsl_index_build(&ix, &set), LUMO_OK);
    srv_vsl_rt *rt = srv_vsl_rt_create(&s, err, sizeof err);
    srv_vsl_lit *lit = calloc(set.n, sizeof *lit);
    assert_non_null(lit);
    static const size_t pools[] = {3000, 30000, 300000};
    double errs[3];
    for (int k = 0; k < 3; k++) {
        srv_vsl_pool pool;
        srv_photon_tracer pt;
        assert_int_equal(srv_vsl_pool_init(&pool, pools[k], set.n), LUMO_OK);
        assert_int_equal(srv_photon_tracer_init(&pt, &s, rt, &ix, &pool, 5, err, sizeof err), LUMO_OK);
        while (pool.len < pool.cap)
            srv_photon_shoot(&pt, 1000);
        srv_vsl_lit_fill(&set, rt, &pt, lit);
        errs[k] = vsl_error(lit, set.n, x, n, ref);
        printf("# pool %7zu: mean relative error of the VSL irradiance %.4f\n", pools[k], errs[k]);
        srv_vsl_pool_free(&pool);
    }
    /* The pool's noise falls as it grows, down to what is left at 1500
     * VSLs: the reference's own noise (20 000 paths a probe, ~0.5%) and
     * the VSLs' spacing and edge margin (docs/dynamic.md: 1.0% at 3 M). */
    assert_true(errs[1] < errs[0] && errs[2] < errs[0] * 0.6);
    assert_true(errs[2] < 0.02);
    free(lit);
    srv_vsl_rt_free(rt);
    srv_rt_free(frt);
    srv_vsl_index_free(&ix);
    srv_vsl_set_free(&set);
    srv_scene_free(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_flux_conserved),
        cmocka_unit_test(test_turnover),
        cmocka_unit_test(test_nearest_matches_scan),
        cmocka_unit_test(test_instance_moves),
        cmocka_unit_test(test_converges_to_path_tracer),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
