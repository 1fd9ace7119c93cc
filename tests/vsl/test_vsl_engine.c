/*
 * test_vsl_engine.c — the live engine (vsl_engine.h) and motion scripts
 * (vsl_motion.h):
 *  - a moved light's old lighting fades within the pool's turnover: the
 *    red wall's VSL flux, high with the light by it, falls after the move
 *    to what a fresh engine with the light at its new place gives, and
 *    the change is settled after one turnover;
 *  - a moved object's VSLs move with it;
 *  - the engine's own thread: a live move settles while it runs, the IVG
 *    version advances and changed vertices are reported;
 *  - motion lines: parsed, interpolated, looped; malformed ones refused.
 */
#include "test_common.h"
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include <unistd.h>
#include "scene/shapes.h"
#include "vsl/vsl_engine.h"

static void room(srv_scene *s, float light_x)
{
    vec3 white = v3(0.75f, 0.75f, 0.75f), red = v3(0.63f, 0.065f, 0.05f), green = v3(0.14f, 0.45f, 0.091f);
    srv_scene_init(s);
    assert_int_equal(srv_add_quad(s, "floor", v3(-1, 0, -1), v3(0, 0, 2), v3(2, 0, 0), white), 0);
    assert_int_equal(srv_add_quad(s, "ceiling", v3(-1, 2, -1), v3(2, 0, 0), v3(0, 0, 2), white), 0);
    assert_int_equal(srv_add_quad(s, "back", v3(-1, 0, -1), v3(2, 0, 0), v3(0, 2, 0), white), 0);
    assert_int_equal(srv_add_quad(s, "left-red", v3(-1, 0, -1), v3(0, 2, 0), v3(0, 0, 2), red), 0);
    assert_int_equal(srv_add_quad(s, "right-green", v3(1, 0, -1), v3(0, 0, 2), v3(0, 2, 0), green), 0);
    assert_int_equal(srv_add_sphere(s, "ball", v3(0, 0.3f, 0), 0.3f, 24, white, 0), 0);
    srv_light l = {.kind = LUMO_LIGHT_POINT, .pos = {light_x, 1.0f, 0}, .power = {40, 40, 40}};
    assert_int_equal(srv_scene_add_light(s, &l), 0);
}

static srv_vsl_engine_opts small_opts(void)
{
    srv_vsl_engine_opts o = srv_vsl_engine_defaults();
    o.nv = 300, o.pool = 60000, o.batch = 10000;
    o.dims[0] = o.dims[1] = o.dims[2] = 8;
    return o;
}

/* Red-channel flux of the red wall's VSLs (object 3), W. */
static double red_wall_flux(const srv_vsl_engine *e)
{
    size_t n;
    const srv_vsl_lit *lit = srv_vsl_engine_lit(e, &n);
    double sum = 0;
    for (size_t i = 0; i < n; i++)
        if (lit[i].pos.x < -0.999f)
            sum += lit[i].flux.x;
    return sum;
}

static void fill_pool(srv_vsl_engine *e, double t, int steps)
{
    for (int k = 0; k < steps; k++)
        srv_vsl_engine_step(e, t);
}

static void test_old_light_fades(void **state)
{
    (void)state;
    srv_scene s, s2;
    char err[160];
    room(&s, -0.8f);
    room(&s2, 0.8f);
    srv_vsl_engine_opts o = small_opts();
    srv_vsl_engine *e = srv_vsl_engine_create(&s, NULL, &o, err, sizeof err);
    srv_vsl_engine *fresh = srv_vsl_engine_create(&s2, NULL, &o, err, sizeof err);
    assert_non_null(e);
    assert_non_null(fresh);
    fill_pool(e, 0, 6);
    fill_pool(fresh, 0, 6);
    double near = red_wall_flux(e), want = red_wall_flux(fresh);
    assert_true(near > 2.0 * want);
    assert_int_equal(srv_vsl_engine_move_light(e, 0, v3(0.8f, 1.0f, 0)), LUMO_OK);
    int steps = 0;
    while (srv_vsl_engine_latency(e).settled < 1 && steps < 50)
        srv_vsl_engine_step(e, 0), steps++;
    srv_vsl_latency lat = srv_vsl_engine_latency(e);
    double after = red_wall_flux(e);
    printf("# red wall flux: light by it %.4f W, moved away and settled after %d steps (%llu paths, %.3f s) "
           "%.4f W, fresh engine %.4f W\n",
           near, steps, (unsigned long long)lat.last_paths, lat.last_s, after, want);
    assert_int_equal(lat.changes, 1);
    assert_int_equal(lat.settled, 1);
    /* A pool of 60 000 impacts at ~2.6 impacts a path: ~23 000 paths, the
     * step that moved and 2-3 more of 10 000. */
    assert_true(steps >= 2 && steps <= 5);
    assert_close(after, want, 0.1 * want);
    srv_vsl_engine_free(e);
    srv_vsl_engine_free(fresh);
    srv_scene_free(&s);
    srv_scene_free(&s2);
}

static void test_object_vsls_move(void **state)
{
    (void)state;
    srv_scene s;
    char err[160];
    room(&s, 0.0f);
    srv_vsl_engine_opts o = small_opts();
    srv_vsl_engine *e = srv_vsl_engine_create(&s, NULL, &o, err, sizeof err);
    assert_non_null(e);
    srv_vsl_engine_step(e, 0);
    size_t n;
    const srv_vsl_lit *lit = srv_vsl_engine_lit(e, &n);
    double before = 0;
    int on_ball = 0;
    for (size_t i = 0; i < n; i++)
        if (lit[i].pos.y > 0.005f && v3_len(v3_sub(lit[i].pos, v3(0, 0.3f, 0))) < 0.31f)
            before += lit[i].pos.x, on_ball++;
    assert_true(on_ball >= 1);
    srv_pose p = srv_pose_make(v3(0.5f, 0, 0), 0);
    assert_int_equal(srv_vsl_engine_move_object(e, 5, &p), LUMO_OK);
    assert_int_equal(srv_vsl_engine_move_object(e, 6, &p), LUMO_ERR_ARG);
    srv_vsl_engine_step(e, 0);
    double after = 0;
    int moved = 0;
    for (size_t i = 0; i < n; i++)
        if (lit[i].pos.y > 0.005f && v3_len(v3_sub(lit[i].pos, v3(0.5f, 0.3f, 0))) < 0.31f)
            after += lit[i].pos.x, moved++;
    assert_int_equal(moved, on_ball);
    assert_close(after - before, 0.5 * on_ball, 1e-4 * on_ball);
    srv_vsl_engine_free(e);
    srv_scene_free(&s);
}

static void test_thread_settles_live_move(void **state)
{
    (void)state;
    srv_scene s;
    char err[160];
    room(&s, -0.8f);
    srv_vsl_engine_opts o = small_opts();
    srv_vsl_engine *e = srv_vsl_engine_create(&s, NULL, &o, err, sizeof err);
    assert_non_null(e);
    assert_int_equal(srv_vsl_engine_start(e), LUMO_OK);
    uint64_t v0 = 0, v1 = 0;
    struct timespec ts = {0, 20000000};
    while (v0 < 8)
        srv_vsl_engine_snapshot(e, NULL, NULL, 0, &v0), nanosleep(&ts, NULL);
    assert_int_equal(srv_vsl_engine_move_light(e, 0, v3(0.8f, 1.0f, 0)), LUMO_OK);
    for (int k = 0; k < 1500 && srv_vsl_engine_latency(e).settled < 1; k++)
        nanosleep(&ts, NULL);
    static uint32_t dirty[512];
    size_t nd = srv_vsl_engine_snapshot(e, NULL, dirty, 512, &v1);
    srv_vsl_engine_stop(e);
    srv_vsl_latency lat = srv_vsl_engine_latency(e);
    printf("# threaded: live move settled in %.3f s (%llu paths); %zu vertices changed, version %llu\n",
           lat.last_s, (unsigned long long)lat.last_paths, nd, (unsigned long long)v1);
    assert_int_equal(lat.settled, 1);
    assert_true(v1 > v0);
    assert_true(nd > 0);
    assert_int_equal(srv_vsl_engine_move_light(e, 1, v3(0, 0, 0)), LUMO_ERR_ARG);
    srv_vsl_engine_free(e);
    srv_scene_free(&s);
}

static lumo_status parse_line(srv_motion *m, const srv_scene *s, const char *text)
{
    char buf[512], *w[48], *save = NULL, err[200];
    int n = 0;
    snprintf(buf, sizeof buf, "%s", text);
    for (char *t = strtok_r(buf, " ", &save); t && n < 48; t = strtok_r(NULL, " ", &save))
        w[n++] = t;
    return srv_motion_parse_words(m, s, w, n, err, sizeof err);
}

static void test_motion_lines(void **state)
{
    (void)state;
    srv_scene s;
    srv_motion m = {0};
    room(&s, 0.0f);
    assert_int_equal(parse_line(&m, &s, "object ball 0:0,0,0 2:1,0,0:90 4:1,1,0"), LUMO_OK);
    assert_int_equal(parse_line(&m, &s, "light 0 loop 0:-0.8,1.9,0 3:0.8,1.9,0 6:-0.8,1.9,0"), LUMO_OK);
    assert_int_equal(parse_line(&m, &s, "object 3 1:0,0,0"), LUMO_OK);
    assert_int_equal(m.ntracks, 3);
    assert_int_equal(m.tracks[0].target, 5);
    assert_int_equal(m.tracks[2].target, 3);
    srv_motion_key k = srv_motion_at(&m.tracks[0], 1.0);
    assert_close(k.p.x, 0.5, 1e-6);
    assert_close(k.yaw_deg, 45.0, 1e-4);
    k = srv_motion_at(&m.tracks[0], 9.0);   /* after the last key: the last */
    assert_close(k.p.y, 1.0, 1e-6);
    k = srv_motion_at(&m.tracks[1], 7.5);   /* loop: 1.5 s into the path */
    assert_close(k.p.x, 0.0, 1e-6);
    static const char *bad[] = {
        "object nothing 0:0,0,0", "object 6 0:0,0,0", "light 1 0:0,0,0", "light 0 0:0,0,0:30",
        "object ball 1:0,0,0 1:1,1,1", "object ball 0:0,0", "object ball", "object ball -1:0,0,0",
        "object ball 0:0,0,nan", "spin ball 0:0,0,0", "object ball loop",
    };
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++)
        assert_int_equal(parse_line(&m, &s, bad[i]), LUMO_ERR_ARG);
    char many[1024] = "object ball";
    for (int i = 0; i < SRV_MOTION_MAX_KEYS + 1; i++)
        snprintf(many + strlen(many), sizeof many - strlen(many), " %d:0,0,0", i);
    assert_int_equal(parse_line(&m, &s, many), LUMO_ERR_LIMIT);
    srv_scene_free(&s);
}

static void test_motion_file(void **state)
{
    (void)state;
    srv_scene s;
    srv_motion m = {0};
    char err[200], path[] = "/tmp/lumo_motion_XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    FILE *f = fdopen(fd, "w");
    fputs("# a scene file\nquad -1,0,-1 0,0,2 2,0,0\nmotion light 0 0:0,1,0 1:0.5,1,0  # comment\n\n"
          "motion object ball loop 0:0,0,0 2:0.3,0,0\n", f);
    fclose(f);
    room(&s, 0.0f);
    assert_int_equal(srv_motion_load(&m, &s, path, err, sizeof err), LUMO_OK);
    assert_int_equal(m.ntracks, 2);
    f = fopen(path, "w");
    fputs("motion light 0 0:0,1,0\nmotion light 0 2:0,1,0 1:0,1,0\n", f);
    fclose(f);
    memset(&m, 0, sizeof m);
    assert_int_equal(srv_motion_load(&m, &s, path, err, sizeof err), LUMO_ERR_ARG);
    assert_non_null(strstr(err, ":2: "));
    unlink(path);
    assert_int_equal(srv_motion_load(&m, &s, path, err, sizeof err), LUMO_ERR_IO);
    srv_scene_free(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_old_light_fades),
        cmocka_unit_test(test_object_vsls_move),
        cmocka_unit_test(test_thread_settles_live_move),
        cmocka_unit_test(test_motion_lines),
        cmocka_unit_test(test_motion_file),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
