/* tools/lumo-server/dynamic.c — lumo-server --dynamic (docs/dynamic.md):
 * the photon-streaming lighting engine (server/vsl/) beside serving, its
 * IVG on the grid of the first package (the clients' grid), its changes
 * published into the update log the updates channel serves
 * (docs/protocol.md §9), and live move commands read from a file or FIFO. */
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "lumo/fixed.h"
#include "lumo_host/options.h"
#include "scene/import.h"
#include "serve/index.h"
#include "vsl/vsl_engine.h"
#include "dynamic.h"

struct dynamic {
    srv_scene       scene;
    srv_motion      motion;
    srv_vsl_engine *engine;
    srv_vsl_updates updates;
    int             have_updates;
    int             cmd_fd;
    pthread_t       cmd_thread;
    int             cmd_running, stop;
};

/* "key=value" settings after the scene file's name, each value through
 * the strict option parser: the refusal names the setting and the value
 * ("--dynamic vsl 1.5: not an integer"). */
static int setting(srv_vsl_engine_opts *o, const char **commands, char *kv, char *err, size_t errlen)
{
    char *eq = strchr(kv, '=');
    int64_t n;
    double v;
    if (!eq) {
        snprintf(err, errlen, "--dynamic: setting '%.64s' has no '=' (vsl=N, pool=N, batch=N, photon-rate=R, tau=T, "
                 "seed=S, commands=FILE)", kv);
        return -1;
    }
    *eq++ = 0;
    if (!strcmp(kv, "commands"))
        return *commands = eq, 0;
    if (!strcmp(kv, "vsl") || !strcmp(kv, "pool") || !strcmp(kv, "batch")) {
        char opt[32];
        snprintf(opt, sizeof opt, "--dynamic %s", kv);
        if (host_opt_i64(opt, eq, 1, (int64_t)1e12, &n, err, errlen))
            return -1;
        if (kv[0] == 'v')
            o->nv = (size_t)n;
        else if (kv[0] == 'p')
            o->pool = (size_t)n;
        else
            o->batch = (uint64_t)n;
        return 0;
    }
    if (!strcmp(kv, "photon-rate"))
        return host_opt_double("--dynamic photon-rate", eq, 0, 1e12, &o->rate, err, errlen);
    if (!strcmp(kv, "tau")) {
        if (host_opt_double("--dynamic tau", eq, 0, 1, &v, err, errlen))
            return -1;
        o->tau = (float)v;
        return 0;
    }
    if (!strcmp(kv, "seed"))
        return host_opt_u64("--dynamic seed", eq, &o->seed, err, errlen);
    snprintf(err, errlen, "--dynamic: unknown setting '%.64s' (vsl=N, pool=N, batch=N, photon-rate=R, tau=T, "
             "seed=S, commands=FILE)", kv);
    return -1;
}

/* The engine works on the first package's IVG grid (Q16.16 bounds). */
static int package_grid(const srv_pkg *p, srv_grid *g, char *err, size_t errlen)
{
    lumo_ivg_desc d;
    if (lumo_package_ivg_desc(&p->pkg, &d)) {
        snprintf(err, errlen, "--dynamic: %s has no IVG to update", p->name);
        return -1;
    }
    for (int a = 0; a < 3; a++)
        g->dims[a] = d.dims[a];
    g->bmin = v3((float)d.bmin[0] / 65536.0f, (float)d.bmin[1] / 65536.0f, (float)d.bmin[2] / 65536.0f);
    g->bmax = v3((float)d.bmax[0] / 65536.0f, (float)d.bmax[1] / 65536.0f, (float)d.bmax[2] / 65536.0f);
    return 0;
}

/* "move object NAME|INDEX X,Y,Z[:YAW]" or "move light INDEX X,Y,Z". */
static void command(struct dynamic *d, char *line)
{
    char *w[4], *save = NULL, err[160];
    int n = 0;
    for (char *t = strtok_r(line, " \t\r\n", &save); t && n < 4; t = strtok_r(NULL, " \t\r\n", &save))
        w[n++] = t;
    if (n == 0 || w[0][0] == '#')
        return;
    srv_motion one = {0};
    char key[96];
    if (n == 4 && !strcmp(w[0], "move") && snprintf(key, sizeof key, "0:%s", w[3]) < (int)sizeof key) {
        char *words[3] = {w[1], w[2], key};
        if (srv_motion_parse_words(&one, &d->scene, words, 3, err, sizeof err) != LUMO_OK) {
            fprintf(stderr, "lumo-server: dynamic: refused 'move %.32s %.32s %.64s': %s\n", w[1], w[2], w[3], err);
            return;
        }
        const srv_motion_track *tr = &one.tracks[0];
        srv_pose p = srv_pose_make(tr->keys[0].p, tr->keys[0].yaw_deg);
        lumo_status st = tr->light ? srv_vsl_engine_move_light(d->engine, tr->target, tr->keys[0].p)
                                   : srv_vsl_engine_move_object(d->engine, tr->target, &p);
        fprintf(stderr, "lumo-server: dynamic: %s %s %s: %s\n", w[1], w[2], w[3], st ? lumo_strerror(st) : "moved");
        return;
    }
    fprintf(stderr, "lumo-server: dynamic: ignored '%s ...': want 'move object NAME|INDEX X,Y,Z[:YAW]' or "
            "'move light INDEX X,Y,Z'\n", w[0]);
}

static void *read_commands(void *arg)
{
    struct dynamic *d = arg;
    sigset_t all;
    sigfillset(&all);   /* SIGINT / SIGTERM are the serving loop's (signalfd) */
    pthread_sigmask(SIG_BLOCK, &all, NULL);
    char buf[1024];
    size_t len = 0;
    while (!__atomic_load_n(&d->stop, __ATOMIC_ACQUIRE)) {
        struct pollfd pf = {d->cmd_fd, POLLIN, 0};
        if (poll(&pf, 1, 200) <= 0)
            continue;
        ssize_t got = read(d->cmd_fd, buf + len, sizeof buf - 1 - len);
        if (got <= 0) {
            struct timespec ts = {0, 100000000};
            nanosleep(&ts, NULL);   /* a FIFO with no writer: wait for one */
            continue;
        }
        len += (size_t)got;
        buf[len] = 0;
        char *nl;
        /* memchr, not strchr: a NUL byte in a line must not hide the lines
         * after it (the line itself ends at the NUL for command()). */
        while ((nl = memchr(buf, '\n', len))) {
            *nl = 0;
            command(d, buf);
            len -= (size_t)(nl + 1 - buf);
            memmove(buf, nl + 1, len + 1);
        }
        if (len == sizeof buf - 1)
            len = 0;   /* a line too long: dropped */
    }
    return NULL;
}

static int start_commands(struct dynamic *d, const char *path, char *err, size_t errlen)
{
    /* O_RDWR: a FIFO opens without waiting for a writer and never reads EOF */
    d->cmd_fd = open(path, O_RDWR | O_NONBLOCK);
    if (d->cmd_fd < 0) {
        snprintf(err, errlen, "--dynamic: commands=%s: %s", path, strerror(errno));
        return -1;
    }
    if (pthread_create(&d->cmd_thread, NULL, read_commands, d)) {
        snprintf(err, errlen, "--dynamic: cannot start the command thread");
        return -1;
    }
    d->cmd_running = 1;
    return 0;
}

static int start(struct dynamic *d, char *spec, const srv_pkg *pkg, char *err, size_t errlen)
{
    srv_vsl_engine_opts o = srv_vsl_engine_defaults();
    const char *commands = NULL;
    char *save = NULL, *file = strtok_r(spec, ",", &save);
    for (char *kv = strtok_r(NULL, ",", &save); kv; kv = strtok_r(NULL, ",", &save))
        if (setting(&o, &commands, kv, err, errlen))
            return -1;
    if (!file || srv_scene_load(&d->scene, file, err, errlen) ||
        srv_motion_load(&d->motion, &d->scene, file, err, errlen) || package_grid(pkg, &o.grid, err, errlen))
        return -1;
    o.use_grid = 1;
    if (!(d->engine = srv_vsl_engine_create(&d->scene, &d->motion, &o, err, errlen)))
        return -1;
    if (srv_vsl_updates_init(&d->updates, o.grid.dims)) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    d->have_updates = 1;
    srv_vsl_engine_attach_updates(d->engine, &d->updates);
    if (commands && start_commands(d, commands, err, errlen))
        return -1;
    if (srv_vsl_engine_start(d->engine)) {
        snprintf(err, errlen, "--dynamic: cannot start the engine's thread");
        return -1;
    }
    fprintf(stderr, "lumo-server: dynamic: %s: %zu VSLs, pool %zu, %d motion tracks, grid %dx%dx%d\n", file, o.nv,
            o.pool, (int)d->motion.ntracks, o.grid.dims[0], o.grid.dims[1], o.grid.dims[2]);
    return 0;
}

struct dynamic *dynamic_start(const char *spec, const srv_pkg *pkg, srv_serve_options *opt, char *err,
                              size_t errlen)
{
    struct dynamic *d = calloc(1, sizeof *d);
    char *copy = strdup(spec);
    sigset_t stop;
    /* Blocked before any thread starts (the engine's, Embree's workers):
     * the serving loop takes SIGINT / SIGTERM through its signalfd, and a
     * thread that did not block them would be killed by them instead. */
    sigemptyset(&stop);
    sigaddset(&stop, SIGINT);
    sigaddset(&stop, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &stop, NULL);
    if (!d || !copy) {
        free(d), free(copy);
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    d->cmd_fd = -1;
    srv_scene_init(&d->scene);
    int bad = start(d, copy, pkg, err, errlen);
    free(copy);
    if (bad) {
        dynamic_stop(d);
        return NULL;
    }
    opt->updates = &d->updates;
    return d;
}

void dynamic_stop(struct dynamic *d)
{
    if (!d)
        return;
    __atomic_store_n(&d->stop, 1, __ATOMIC_RELEASE);
    if (d->cmd_running)
        pthread_join(d->cmd_thread, NULL);
    if (d->cmd_fd >= 0)
        close(d->cmd_fd);
    if (d->engine) {
        srv_vsl_engine_stop(d->engine);
        srv_vsl_latency l = srv_vsl_engine_latency(d->engine);
        if (l.settled)
            fprintf(stderr, "lumo-server: dynamic: %llu changes, %llu settled; latency change -> settled lighting "
                    "mean %.3f s, max %.3f s\n", (unsigned long long)l.changes, (unsigned long long)l.settled,
                    l.mean_s, l.max_s);
        else   /* stopped before a change settled (a short run, a loaded machine) */
            fprintf(stderr, "lumo-server: dynamic: %llu changes, none settled yet: no latency to say\n",
                    (unsigned long long)l.changes);
        srv_vsl_engine_free(d->engine);
    }
    if (d->have_updates)
        srv_vsl_updates_free(&d->updates);
    srv_scene_free(&d->scene);
    free(d);
}
