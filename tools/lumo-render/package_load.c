/*
 * package_load.c — see package_load.h.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "lumo/arena.h"
#include "lumo/package.h"
#include "lumo/session.h"
#include "lumo_host/file_io.h"
#include "lumo_host/options.h"
#include "lumo_host/package_msg.h"
#include "package_load.h"
#include "session_scene.h"

/* Which message of the package failed, in words. */
static void describe_failure(const lumo_session_where *w, lumo_status st, char *err, size_t errlen)
{
    if (w->type == LUMO_PKG_PMSH)
        snprintf(err, errlen, "progressive mesh %u, batch %u: %s", w->index, w->batch, lumo_strerror(st));
    else if (w->type == LUMO_PKG_MESH)
        snprintf(err, errlen, "bad MESH chunk %u: %s", w->index, lumo_strerror(st));
    else if (w->type == LUMO_PKG_INFO)
        snprintf(err, errlen, "%s", lumo_strerror(st));
    else
        snprintf(err, errlen, "bad IVG chunk: %s", lumo_strerror(st));
}

/* A refusal "--lod SHOWN: why" from the parser, with its reason replaced
 * by `why` (the parser saw only the number of "P%"). */
static void lod_refusal(char *err, size_t errlen, const char *shown_in, const char *why)
{
    const char *r = strstr(shown_in, ": ");

    snprintf(err, errlen, "%.*s: %s", (int)(r - shown_in), shown_in, why);
}

int host_lod_parse(const char *s, host_lod *lod, char *err, size_t errlen)
{
    size_t n = strlen(s);
    char num[64], why[320];
    uint32_t v;
    double p;

    memset(lod, 0, sizeof *lod);
    lod->fraction = 1;
    if (!strcmp(s, "all"))
        return 0;
    if (n > 1 && s[n - 1] == '%' && n < sizeof num) {
        memcpy(num, s, n - 1);
        num[n - 1] = 0;
        if (host_opt_double("--lod", num, 0, 100, &p, why, sizeof why)) {
            const char *r = strstr(why, ": ");
            if (errlen)
                snprintf(err, errlen, "%.*s%%: percentage %s", (int)(r - why), why, r + 2);
            return -1;
        }
        lod->fraction = p / 100;
        return 0;
    }
    if (host_opt_u32("--lod", s, 1, UINT32_MAX, &v, why, sizeof why)) {
        if (errlen && strstr(why, ": not an integer"))
            lod_refusal(err, errlen, why, "not all, N (at most N vertices) or P% (percent streamed)");
        else if (errlen)
            snprintf(err, errlen, "%s", why);
        return -1;
    }
    lod->vertices = v;
    return 0;
}

/* The level of detail as the session counts it: a vertex cap, or parts per
 * million of the streamed vertices (7% of 100 is 70000 ppm: 7 vertices). */
static lumo_session_config session_config(const host_lod *lod)
{
    lumo_session_config cfg = {{0, LUMO_SESSION_LOD_ALL}, LUMO_IVG_SMOOTH};

    if (lod && lod->vertices)
        cfg.lod.vertices = lod->vertices;
    else if (lod && lod->fraction < 1)
        cfg.lod.ppm = (uint32_t)llround(lod->fraction * LUMO_SESSION_LOD_ALL);
    return cfg;
}

/* Feed the whole package to a session in a heap arena sized by the SDK (a
 * desktop may use the heap; the session itself never does). */
static int run_session(const lumo_package *pkg, const host_lod *lod, lumo_session *ses, host_ivg *ivg,
                       char *err, size_t errlen)
{
    lumo_session_config cfg = session_config(lod);
    lumo_session_where w = {0, 0, 0};
    lumo_arena arena;
    lumo_status st;
    size_t bytes;

    if ((st = lumo_session_package_need(pkg, &bytes))) {
        snprintf(err, errlen, "%s", lumo_strerror(st));
        return -1;
    }
    if (!(ivg->memory = malloc(bytes))) {
        snprintf(err, errlen, "no memory for a %zu-byte arena", bytes);
        return -1;
    }
    lumo_arena_init(&arena, ivg->memory, bytes);
    if ((st = lumo_session_init(ses, &cfg, &arena)) || (st = lumo_session_feed_package(ses, pkg, &w))) {
        describe_failure(&w, st, err, errlen);
        return -1;
    }
    lumo_session_update(ses);
    ivg->grid = lumo_session_ivg(ses);
    if (ivg->grid)
        ivg->received = lumo_ivg_received_count(ivg->grid);
    return 0;
}

int host_package_load(const char *path, const host_lod *lod, host_scene *s, host_ivg *ivg,
                      host_load_stats *stats, char *err, size_t errlen)
{
    static lumo_session ses;   /* 19 KB: not on the stack */
    host_load_stats local;
    char why[200];
    size_t size = 0;
    uint8_t *data = host_read_file(path, &size);
    lumo_package pkg;
    lumo_status st;

    if (!stats)
        stats = &local;
    memset(stats, 0, sizeof *stats);
    memset(s, 0, sizeof *s);
    memset(ivg, 0, sizeof *ivg);
    if (!data || size == 0) {   /* an empty file is as unreadable as a missing one */
        free(data);
        if (host_opt_file(NULL, path, "package", err, errlen) == 0)
            snprintf(err, errlen, "%s: cannot read", path);
        return -1;
    }
    if ((st = lumo_package_open(&pkg, data, size))) {
        snprintf(err, errlen, "%s: %s", path, host_package_strerror(data, size, st, why, sizeof why));
        free(data);
        return -1;
    }
    if (lumo_package_find(&pkg, LUMO_PKG_INFO, 0, &(const uint8_t *){0}, &(uint32_t){0}) == LUMO_ERR_RANGE) {
        snprintf(err, errlen, "%s: no INFO chunk, so no scene to draw (camera, lights); a package from "
                              "lumo-pm build holds a mesh stream only: see it with lumo-inspect --lod N --ply "
                              "OUT.ply, or bake the model into a scene with lumo-bake", path);
        free(data);
        return -1;
    }
    if (run_session(&pkg, lod, &ses, ivg, why, sizeof why)
        || (host_scene_from_session(&ses, s, stats) && snprintf(why, sizeof why, "out of memory"))) {
        snprintf(err, errlen, "%s: %s", path, why);
        free(data);
        host_scene_free(s);
        host_ivg_free(ivg);
        return -1;
    }
    free(data);
    return 0;
}

void host_ivg_free(host_ivg *ivg)
{
    free(ivg->memory);
    memset(ivg, 0, sizeof *ivg);
}
