/*
 * test_vsl_place.c — VSL placement (seed 004 §0.4.2):
 *  - Algorithm 1 (d_min1/d_min2 kept per point, only the points that lost
 *    a neighbour rescanned) leaves the same survivors as the naive process
 *    (every distance recomputed for every removal, O(n^2) each) on random
 *    sets: uniform, clustered, with exact duplicates (ties), with groups
 *    (every object keeps one);
 *  - srv_vsl_place on the Cornell room: N_v placed, every object has one,
 *    each VSL on its object's surface, away from the triangles' edges.
 */
#include "test_common.h"
#include <stdio.h>
#include <stdlib.h>
#include "scene/shapes.h"
#include "vsl/vsl.h"

static void random_set(test_rng *r, vec3 *p, uint32_t *g, size_t n, int kind, int ngroups)
{
    for (size_t i = 0; i < n; i++) {
        float x = (float)test_rng_uniform(r, 0, 1), y = (float)test_rng_uniform(r, 0, 1),
              z = (float)test_rng_uniform(r, 0, 1);
        if (kind == 1)   /* clusters: a few centres, small spread */
            x = (float)(test_rng_next(r) % 4) + 0.05f * x, z *= 0.05f;
        if (kind == 2 && i > 0 && test_rng_next(r) % 4 == 0)   /* exact duplicates: ties */
            x = p[i - 1].x, y = p[i - 1].y, z = p[i - 1].z;
        if (kind == 3)   /* on a grid: many equal distances */
            x = (float)(test_rng_next(r) % 8), y = (float)(test_rng_next(r) % 8), z = 0.0f;
        p[i] = v3(x, y, z);
        if (g)
            g[i] = (uint32_t)(test_rng_next(r) % (uint64_t)ngroups);
    }
}

static void test_thin_matches_brute_force(void **state)
{
    (void)state;
    test_rng r = {0x1234567u};
    enum { N = 300 };
    static vec3 p[N];
    static uint32_t g[N];
    static uint8_t a[N], b[N];
    int cases = 0;
    for (int kind = 0; kind < 4; kind++)
        for (int grouped = 0; grouped < 2; grouped++)
            for (int rep = 0; rep < 6; rep++) {
                size_t n = 20 + test_rng_next(&r) % (N - 20);
                size_t keep = 1 + test_rng_next(&r) % n;
                random_set(&r, p, grouped ? g : NULL, n, kind, 1 + rep * 7);
                size_t ca = srv_vsl_thin(p, grouped ? g : NULL, n, keep, a);
                size_t cb = srv_vsl_thin_naive(p, grouped ? g : NULL, n, keep, b);
                assert_int_equal(ca, cb);
                assert_memory_equal(a, b, n);
                assert_true(ca >= keep);
                cases++;
            }
    printf("# %d random sets: same survivors as the O(n^2) removal\n", cases);
}

/* Every group keeps its last point even when keep asks for fewer. */
static void test_thin_keeps_one_per_group(void **state)
{
    (void)state;
    test_rng r = {99};
    enum { N = 200 };
    vec3 p[N];
    uint32_t g[N];
    uint8_t a[N];
    random_set(&r, p, g, N, 0, 17);
    size_t left = srv_vsl_thin(p, g, N, 1, a);
    int seen[17] = {0};
    for (size_t i = 0; i < N; i++)
        seen[g[i]] += a[i];
    for (int k = 0; k < 17; k++)
        assert_int_equal(seen[k], 1);
    assert_int_equal(left, 17);
}

static void cornell_room(srv_scene *s)
{
    vec3 w = v3(0.75f, 0.75f, 0.75f);
    srv_scene_init(s);
    assert_int_equal(srv_add_quad(s, "floor", v3(-1, 0, -1), v3(0, 0, 2), v3(2, 0, 0), w), 0);
    assert_int_equal(srv_add_quad(s, "ceiling", v3(-1, 2, -1), v3(2, 0, 0), v3(0, 0, 2), w), 0);
    assert_int_equal(srv_add_quad(s, "back", v3(-1, 0, -1), v3(2, 0, 0), v3(0, 2, 0), w), 0);
    assert_int_equal(srv_add_sphere(s, "ball", v3(0.4f, 0.3f, 0.2f), 0.1f, 16, w, 0), 0);
}

static void test_place_cornell(void **state)
{
    (void)state;
    srv_scene s;
    srv_vsl_set set;
    char err[128];
    cornell_room(&s);
    srv_vsl_place_opts o = srv_vsl_place_defaults(200, 7);
    assert_int_equal(srv_vsl_place(&s, &o, &set, err, sizeof err), LUMO_OK);
    assert_int_equal(set.n, 200);
    assert_int_equal(set.nobjects, 4);
    /* The ball is 0.126 m^2 of 12.1: about 2 by area; it has at least one. */
    for (size_t k = 0; k < 4; k++)
        assert_true(set.count[k] >= 1);
    double area = 0;
    for (size_t i = 0; i < set.n; i++) {
        const srv_vsl *v = &set.v[i];
        area += v->area;
        assert_true(i < set.first[v->object] + set.count[v->object] && i >= set.first[v->object]);
        if (v->object == 0) {   /* floor: y = 0, normal up, off the quad's edges by the shrink */
            assert_true(fabsf(v->pos.y) < 1e-6f && v->normal.y > 0.999f);
            assert_true(fabsf(v->pos.x) < 1.0f - 1e-3f && fabsf(v->pos.z) < 1.0f - 1e-3f);
        }
        if (v->object == 3)
            assert_close(v3_len(v3_sub(v->pos, v3(0.4f, 0.3f, 0.2f))), 0.1, 0.02);
    }
    assert_close(area, 12.0 + 0.126, 0.01);   /* the dS' tile the surfaces */
    srv_vsl_set_free(&set);
    o.nv = 3;   /* fewer than the objects */
    assert_int_equal(srv_vsl_place(&s, &o, &set, err, sizeof err), LUMO_ERR_ARG);
    srv_scene_free(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_thin_matches_brute_force),
        cmocka_unit_test(test_thin_keeps_one_per_group),
        cmocka_unit_test(test_place_cornell),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
