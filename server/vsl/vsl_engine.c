/* vsl_engine.c — the photon-streaming lighting engine and its thread
 * (seed 004 §0.3, §0.7.2; vsl_engine.h). */
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "vsl/vsl_engine.h"

#define CHANGE_RING 256

typedef struct { uint64_t serial; double wall; } change;

struct srv_vsl_engine {
    const srv_scene    *s;
    const srv_motion   *motion;
    srv_vsl_engine_opts o;
    srv_vsl_set         set;
    srv_vsl_index       ix;
    srv_vsl_rt         *rt;
    srv_vsl_pool        pool;
    srv_photon_tracer   pt;
    srv_vsl_ivg         ivg;
    srv_vsl_lit        *lit;
    /* live commands (under mu) */
    srv_pose           *want_pose;
    uint8_t            *want_obj;
    vec3                want_light[LUMO_MAX_LIGHTS];
    uint8_t             want_lt[LUMO_MAX_LIGHTS];
    uint8_t            *live_obj;                 /* moved live: its motion track no longer applies */
    uint8_t             live_lt[LUMO_MAX_LIGHTS];
    /* latency */
    change              ring[CHANGE_RING];
    size_t              rhead, rlen;
    srv_vsl_latency     lat;
    double              lat_sum;
    uint64_t            version;
    srv_vsl_updates    *updates;     /* NULL: dirty vertices kept for snapshots */
    uint32_t           *dirty;       /* scratch: one grid of vertex indices */
    pthread_mutex_t     mu;
    pthread_t           th;
    int                 running, stop;
};

static double wall_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

srv_vsl_engine_opts srv_vsl_engine_defaults(void)
{
    srv_vsl_engine_opts o = {400, 200000, 20000, 0.0, 0.05f, 1e-6f, {16, 16, 16}, 0, {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}, 1};
    return o;
}

/* Motion moves point and spot lights (a light is a position); an area
 * light's rectangle is a mesh of its own, a directional light has none. */
static lumo_status check_motion(const srv_vsl_engine *e, char *err, size_t errlen)
{
    for (size_t k = 0; e->motion && k < e->motion->ntracks; k++) {
        const srv_motion_track *tr = &e->motion->tracks[k];
        if (!tr->light)
            continue;
        if (tr->target >= e->pt.nlights || e->pt.lights[tr->target].kind == LUMO_LIGHT_AREA ||
            e->pt.lights[tr->target].kind == LUMO_LIGHT_DIRECTIONAL) {
            snprintf(err, errlen, "motion: light %u is not a point or spot light", tr->target);
            return LUMO_ERR_ARG;
        }
    }
    return LUMO_OK;
}

static lumo_status build(srv_vsl_engine *e, char *err, size_t errlen)
{
    srv_vsl_place_opts po = srv_vsl_place_defaults(e->o.nv, e->o.seed);
    lumo_status st = srv_vsl_place(e->s, &po, &e->set, err, errlen);
    if (st)
        return st;
    if (srv_vsl_index_build(&e->ix, &e->set) || srv_vsl_pool_init(&e->pool, e->o.pool, e->set.n)) {
        snprintf(err, errlen, "out of memory (pool of %zu photons)", e->o.pool);
        return e->o.pool ? LUMO_ERR_NOMEM : LUMO_ERR_ARG;
    }
    e->rt = srv_vsl_rt_create(e->s, err, errlen);
    if (!e->rt)
        return LUMO_ERR_NOMEM;
    st = srv_photon_tracer_init(&e->pt, e->s, e->rt, &e->ix, &e->pool, e->o.seed, err, errlen);
    if (st || (st = check_motion(e, err, errlen)))
        return st;
    srv_grid g = e->o.use_grid ? e->o.grid : srv_grid_over(e->s, e->o.dims);
    e->lit = calloc(e->set.n ? e->set.n : 1, sizeof *e->lit);
    e->want_pose = calloc(e->s->nmeshes ? e->s->nmeshes : 1, sizeof *e->want_pose);
    e->want_obj = calloc(e->s->nmeshes ? e->s->nmeshes : 1, 1);
    e->live_obj = calloc(e->s->nmeshes ? e->s->nmeshes : 1, 1);
    e->dirty = calloc((size_t)g.dims[0] * (size_t)g.dims[1] * (size_t)g.dims[2], sizeof *e->dirty);
    if (!e->lit || !e->want_pose || !e->want_obj || !e->live_obj || !e->dirty || srv_vsl_ivg_init(&e->ivg, &g, e->set.n, e->o.eps, e->o.tau)) {
        snprintf(err, errlen, "out of memory (IVG grid, VSL states)");
        return LUMO_ERR_NOMEM;
    }
    return LUMO_OK;
}

srv_vsl_engine *srv_vsl_engine_create(const srv_scene *s, const srv_motion *m,
                                      const srv_vsl_engine_opts *o, char *err, size_t errlen)
{
    srv_vsl_engine *e = calloc(1, sizeof *e);
    if (!e) {
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    e->s = s, e->motion = m, e->o = *o;
    pthread_mutex_init(&e->mu, NULL);
    if (!o->batch || build(e, err, errlen)) {
        if (!o->batch)
            snprintf(err, errlen, "a step must shoot at least one photon");
        srv_vsl_engine_free(e);
        return NULL;
    }
    return e;
}

void srv_vsl_engine_free(srv_vsl_engine *e)
{
    if (!e)
        return;
    srv_vsl_engine_stop(e);
    srv_vsl_ivg_free(&e->ivg);
    srv_vsl_rt_free(e->rt);
    srv_vsl_pool_free(&e->pool);
    srv_vsl_index_free(&e->ix);
    srv_vsl_set_free(&e->set);
    free(e->lit), free(e->want_pose), free(e->want_obj), free(e->live_obj), free(e->dirty);
    pthread_mutex_destroy(&e->mu);
    free(e);
}

/* ---- changes ------------------------------------------------------------- */

static int set_pose(srv_vsl_engine *e, uint32_t o, const srv_pose *p)
{
    if (srv_pose_equal(srv_vsl_rt_pose(e->rt, o), p))
        return 0;
    srv_vsl_rt_set_pose(e->rt, o, p);
    return 1;
}

static int set_light(srv_vsl_engine *e, uint32_t i, vec3 pos)
{
    srv_light l = e->pt.lights[i];
    if (l.pos.x == pos.x && l.pos.y == pos.y && l.pos.z == pos.z)
        return 0;
    l.pos = pos;
    return srv_photon_tracer_set_light(&e->pt, i, &l) == LUMO_OK;
}

static int apply_motion(srv_vsl_engine *e, double t)
{
    int moved = 0;
    for (size_t k = 0; e->motion && k < e->motion->ntracks; k++) {
        const srv_motion_track *tr = &e->motion->tracks[k];
        srv_motion_key key = srv_motion_at(tr, t);
        if (tr->light ? e->live_lt[tr->target] : e->live_obj[tr->target])
            continue;
        if (tr->light) {
            moved |= set_light(e, tr->target, key.p) ? 2 : 0;
        } else {
            srv_pose p = srv_pose_make(key.p, key.yaw_deg);
            moved |= set_pose(e, tr->target, &p);
        }
    }
    return moved;
}

static int apply_commands(srv_vsl_engine *e)
{
    int moved = 0;
    pthread_mutex_lock(&e->mu);
    for (uint32_t o = 0; o < e->s->nmeshes; o++)
        if (e->want_obj[o])
            moved |= set_pose(e, o, &e->want_pose[o]), e->want_obj[o] = 0, e->live_obj[o] = 1;
    for (uint32_t i = 0; i < e->pt.nlights; i++)
        if (e->want_lt[i])
            moved |= set_light(e, i, e->want_light[i]) ? 2 : 0, e->want_lt[i] = 0, e->live_lt[i] = 1;
    pthread_mutex_unlock(&e->mu);
    return moved;
}

static void note_change(srv_vsl_engine *e, double wall)
{
    if (e->rlen == CHANGE_RING)   /* the oldest unsettled change is forgotten */
        e->rhead = (e->rhead + 1) % CHANGE_RING, e->rlen--;
    change c = {e->pt.emitted, wall};
    e->ring[(e->rhead + e->rlen++) % CHANGE_RING] = c;
    e->lat.changes++;
}

/* Changes whose photons have all left the pool are settled now. */
static void settle(srv_vsl_engine *e, double wall)
{
    const srv_photon *old = srv_vsl_pool_oldest(&e->pool);
    while (e->rlen && old && old->emitted >= e->ring[e->rhead].serial) {
        const change *c = &e->ring[e->rhead];
        double dt = wall - c->wall;
        e->lat.last_s = dt;
        e->lat.last_paths = e->pt.emitted - c->serial;
        e->lat.max_s = dt > e->lat.max_s ? dt : e->lat.max_s;
        e->lat_sum += dt;
        e->lat.settled++;
        e->lat.mean_s = e->lat_sum / (double)e->lat.settled;
        e->rhead = (e->rhead + 1) % CHANGE_RING, e->rlen--;
    }
}

/* ---- poses for the clients ----------------------------------------------- */

static lumo_q16_16 q16(float x)
{
    double v = (double)x * 65536.0;
    return (lumo_q16_16)(v > 2147483647.0 ? 2147483647.0 : v < -2147483648.0 ? -2147483648.0 : v);
}

/* Lights where they are now, meshes moved from where the scene put them. */
static void publish_poses(srv_vsl_engine *e)
{
    lumo_net_pose p[LUMO_NET_MAX_POSES];
    uint32_t n = 0;
    for (uint32_t i = 0; i < e->pt.nlights && n < LUMO_NET_MAX_POSES; i++) {
        vec3 x = e->pt.lights[i].pos;
        lumo_net_pose one = {LUMO_NET_POSE_LIGHT, i, {q16(x.x), q16(x.y), q16(x.z)}, 0};
        p[n++] = one;
    }
    for (uint32_t o = 0; o < e->s->nmeshes && o < LUMO_MAX_MESHES && n < LUMO_NET_MAX_POSES; o++) {
        const srv_pose *q = srv_vsl_rt_pose(e->rt, o);
        lumo_net_pose one = {LUMO_NET_POSE_MESH, o, {q16(q->t.x), q16(q->t.y), q16(q->t.z)}, q16(q->yaw_deg)};
        if (q->t.x != 0.0f || q->t.y != 0.0f || q->t.z != 0.0f || q->yaw_deg != 0.0f)
            p[n++] = one;
    }
    srv_vsl_updates_set_poses(e->updates, p, n);
}

/* ---- steps ---------------------------------------------------------------- */

size_t srv_vsl_engine_step(srv_vsl_engine *e, double t)
{
    int moved = apply_motion(e, t) | apply_commands(e);
    if (moved & 1)
        srv_vsl_rt_commit(e->rt);
    if (moved)
        note_change(e, wall_now());
    srv_photon_shoot(&e->pt, e->o.batch);
    srv_vsl_lit_fill(&e->set, e->rt, &e->pt, e->lit);
    pthread_mutex_lock(&e->mu);
    size_t n = srv_vsl_ivg_update(&e->ivg, e->lit);
    if (e->updates)
        publish_poses(e);
    if (e->updates)
        srv_vsl_updates_publish(e->updates, e->ivg.I, e->dirty,
                                srv_vsl_ivg_take_dirty(&e->ivg, e->dirty, e->ivg.nverts));
    e->version++;
    pthread_mutex_unlock(&e->mu);
    settle(e, wall_now());
    return n;
}

static void *run(void *arg)
{
    srv_vsl_engine *e = arg;
    sigset_t all;
    sigfillset(&all);   /* process signals are the serving thread's (signalfd) */
    pthread_sigmask(SIG_BLOCK, &all, NULL);
    double start = wall_now();
    uint64_t first = e->pt.emitted;
    while (!__atomic_load_n(&e->stop, __ATOMIC_ACQUIRE)) {
        double t = wall_now() - start;
        if (e->o.rate > 0.0 && (double)(e->pt.emitted - first) > e->o.rate * t) {
            struct timespec ts = {0, 2000000};   /* photon rate cap: wait 2 ms */
            nanosleep(&ts, NULL);
            continue;
        }
        srv_vsl_engine_step(e, t);
    }
    return NULL;
}

lumo_status srv_vsl_engine_start(srv_vsl_engine *e)
{
    if (e->running)
        return LUMO_OK;
    e->stop = 0;
    if (pthread_create(&e->th, NULL, run, e))
        return LUMO_ERR_NOMEM;
    e->running = 1;
    return LUMO_OK;
}

void srv_vsl_engine_stop(srv_vsl_engine *e)
{
    if (!e->running)
        return;
    __atomic_store_n(&e->stop, 1, __ATOMIC_RELEASE);
    pthread_join(e->th, NULL);
    e->running = 0;
}

lumo_status srv_vsl_engine_move_object(srv_vsl_engine *e, uint32_t o, const srv_pose *p)
{
    if (o >= e->s->nmeshes)
        return LUMO_ERR_ARG;
    pthread_mutex_lock(&e->mu);
    e->want_pose[o] = *p, e->want_obj[o] = 1;
    pthread_mutex_unlock(&e->mu);
    return LUMO_OK;
}

lumo_status srv_vsl_engine_move_light(srv_vsl_engine *e, uint32_t i, vec3 pos)
{
    if (i >= e->pt.nlights || e->pt.lights[i].kind == LUMO_LIGHT_AREA ||
        e->pt.lights[i].kind == LUMO_LIGHT_DIRECTIONAL)
        return LUMO_ERR_ARG;
    pthread_mutex_lock(&e->mu);
    e->want_light[i] = pos, e->want_lt[i] = 1;
    pthread_mutex_unlock(&e->mu);
    return LUMO_OK;
}

size_t srv_vsl_engine_snapshot(srv_vsl_engine *e, double *I, uint32_t *dirty, size_t cap,
                               uint64_t *version)
{
    pthread_mutex_lock(&e->mu);
    if (I)
        memcpy(I, e->ivg.I, e->ivg.nverts * SRV_VSL_IVG_VALUES * sizeof *I);
    size_t n = dirty ? srv_vsl_ivg_take_dirty(&e->ivg, dirty, cap) : 0;
    if (version)
        *version = e->version;
    pthread_mutex_unlock(&e->mu);
    return n;
}

void srv_vsl_engine_attach_updates(srv_vsl_engine *e, srv_vsl_updates *u)
{
    pthread_mutex_lock(&e->mu);
    e->updates = u;
    pthread_mutex_unlock(&e->mu);
}

const srv_vsl_ivg *srv_vsl_engine_ivg(const srv_vsl_engine *e) { return &e->ivg; }
const srv_photon_tracer *srv_vsl_engine_tracer(const srv_vsl_engine *e) { return &e->pt; }
const srv_pose *srv_vsl_engine_pose(const srv_vsl_engine *e, uint32_t o) { return srv_vsl_rt_pose(e->rt, o); }
srv_vsl_latency srv_vsl_engine_latency(const srv_vsl_engine *e) { return e->lat; }

const srv_vsl_lit *srv_vsl_engine_lit(const srv_vsl_engine *e, size_t *n)
{
    *n = e->set.n;
    return e->lit;
}

int srv_vsl_engine_settle(srv_vsl_engine *e, double t, int max_steps)
{
    int steps = 1;
    srv_vsl_engine_step(e, t);
    while (srv_vsl_engine_latency(e).settled < srv_vsl_engine_latency(e).changes && steps < max_steps)
        srv_vsl_engine_step(e, t), steps++;
    srv_vsl_engine_step(e, t);
    return steps + 1;
}

lumo_status srv_vsl_engine_posed_scene(const srv_vsl_engine *e, const srv_scene *s, srv_scene *out)
{
    const srv_photon_tracer *pt = srv_vsl_engine_tracer(e);
    srv_scene_init(out);
    for (size_t i = 0; i < s->nmeshes; i++) {
        const srv_mesh *m = &s->meshes[i];
        const srv_pose *p = srv_vsl_engine_pose(e, (uint32_t)i);
        srv_mesh *d = srv_scene_add_mesh(out, m->name, m->nverts, m->ntris);
        if (!d)
            return LUMO_ERR_NOMEM;
        for (uint32_t v = 0; v < m->nverts; v++)
            d->pos[v] = srv_pose_point(p, m->pos[v]), d->albedo[v] = m->albedo[v];
        memcpy(d->tris, m->tris, 3u * m->ntris * sizeof *m->tris);
        d->emitter = m->emitter;
    }
    for (size_t i = 0; i < s->nlights; i++) {
        srv_light l = s->lights[i];
        if (i < pt->nlights)
            l.pos = pt->lights[i].pos;
        if (srv_scene_add_light(out, &l))
            return LUMO_ERR_NOMEM;
    }
    out->camera = s->camera, out->has_camera = s->has_camera;
    return LUMO_OK;
}
