/* vsl_motion.c — motion scripts (vsl_motion.h, docs/dynamic.md). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "vsl/vsl_motion.h"

/* A mesh by name, else by index. */
static int find_mesh(const srv_scene *s, const char *name, uint32_t *out)
{
    char *end;
    for (size_t i = 0; i < s->nmeshes; i++)
        if (!strcmp(s->meshes[i].name, name)) {
            *out = (uint32_t)i;
            return 0;
        }
    unsigned long i = strtoul(name, &end, 10);
    if (end == name || *end || i >= s->nmeshes)
        return -1;
    *out = (uint32_t)i;
    return 0;
}

static int parse_target(srv_motion_track *tr, const srv_scene *s, char **w)
{
    char *end;
    if (!strcmp(w[0], "object")) {
        tr->light = 0;
        return find_mesh(s, w[1], &tr->target);
    }
    if (strcmp(w[0], "light"))
        return -1;
    unsigned long i = strtoul(w[1], &end, 10);
    if (end == w[1] || *end || i >= s->nlights)
        return -1;
    tr->light = 1;
    tr->target = (uint32_t)i;
    return 0;
}

/* Bounds of a key: scene time in seconds, a position within the scene's
 * coordinate bound (an object's offset or a light's position: beyond it
 * the engine's photon tracing overflows), a yaw in degrees. */
#define MOTION_MAX_TIME 1.0e9f
#define MOTION_MAX_YAW  1.0e6f

/* "T:X,Y,Z[:YAW]": LUMO_OK, or why the key is refused in why (the part
 * that is wrong and its value). */
static lumo_status parse_key(const char *text, int light, srv_motion_key *k, char *why, size_t whylen)
{
    char buf[128], *a, *b;
    float f[3];
    if (strlen(text) >= sizeof buf)
        return snprintf(why, whylen, "longer than %zu characters", sizeof buf - 1), LUMO_ERR_LIMIT;
    strcpy(buf, text);
    if (!(a = strchr(buf, ':')))
        return snprintf(why, whylen, "no ':' after the time (T:X,Y,Z[:YAW])"), LUMO_ERR_ARG;
    *a++ = 0;
    if ((b = strchr(a, ':')))
        *b++ = 0;
    if (srv_parse_floats(buf, &k->t, 1) || !(k->t >= 0.0f && k->t <= MOTION_MAX_TIME))
        return snprintf(why, whylen, "time '%.32s' is not a number of seconds in [0, 1e9]", buf), LUMO_ERR_ARG;
    if (srv_parse_floats(a, f, 3))
        return snprintf(why, whylen, "position '%.48s' is not 3 finite numbers X,Y,Z", a), LUMO_ERR_ARG;
    for (int i = 0; i < 3; i++)
        if (!(fabsf(f[i]) <= SRV_SCENE_MAX_COORD))
            return snprintf(why, whylen, "position %c = %g is beyond ±%g m (SRV_SCENE_MAX_COORD)", "XYZ"[i], f[i],
                            SRV_SCENE_MAX_COORD), LUMO_ERR_RANGE;
    k->p = v3(f[0], f[1], f[2]);
    k->yaw_deg = 0.0f;
    if (b && light)
        return snprintf(why, whylen, "a light has no yaw ('%.32s')", b), LUMO_ERR_ARG;
    if (b && (srv_parse_floats(b, &k->yaw_deg, 1) || !(fabsf(k->yaw_deg) <= MOTION_MAX_YAW)))
        return snprintf(why, whylen, "yaw '%.32s' is not a number of degrees in [-1e6, 1e6]", b), LUMO_ERR_ARG;
    return LUMO_OK;
}

lumo_status srv_motion_parse_words(srv_motion *m, const srv_scene *s, char **w, int n, char *err,
                                   size_t errlen)
{
    if (m->ntracks == SRV_MOTION_MAX_TRACKS) {
        snprintf(err, errlen, "more than %d motion tracks", SRV_MOTION_MAX_TRACKS);
        return LUMO_ERR_LIMIT;
    }
    srv_motion_track *tr = &m->tracks[m->ntracks];
    memset(tr, 0, sizeof *tr);
    if (n < 3 || parse_target(tr, s, w)) {
        snprintf(err, errlen, "motion: want 'object NAME|INDEX' or 'light INDEX' naming one of the scene's");
        return LUMO_ERR_ARG;
    }
    int i = 2;
    if (!strcmp(w[i], "loop"))
        tr->loop = 1, i++;
    for (; i < n; i++) {
        if (tr->nkeys == SRV_MOTION_MAX_KEYS) {
            snprintf(err, errlen, "motion: more than %d keys", SRV_MOTION_MAX_KEYS);
            return LUMO_ERR_LIMIT;
        }
        srv_motion_key *k = &tr->keys[tr->nkeys];
        char why[160];
        lumo_status st = parse_key(w[i], tr->light, k, why, sizeof why);
        if (!st && tr->nkeys && !(k->t > tr->keys[tr->nkeys - 1].t)) {
            snprintf(why, sizeof why, "time %g does not follow %g (times increase)", k->t, tr->keys[tr->nkeys - 1].t);
            st = LUMO_ERR_ARG;
        }
        if (st) {
            snprintf(err, errlen, "motion: key %zu '%.64s': %s", tr->nkeys + 1, w[i], why);
            return st;
        }
        tr->nkeys++;
    }
    if (!tr->nkeys) {
        snprintf(err, errlen, "motion: no key");
        return LUMO_ERR_ARG;
    }
    m->ntracks++;
    return LUMO_OK;
}

lumo_status srv_motion_load(srv_motion *m, const srv_scene *s, const char *path, char *err, size_t errlen)
{
    char line[2048], msg[200], *w[SRV_MOTION_MAX_KEYS + 8];
    FILE *f = fopen(path, "r");
    if (!f) {
        snprintf(err, errlen, "%s: cannot open", path);
        return LUMO_ERR_IO;
    }
    for (int lineno = 1; fgets(line, sizeof line, f); lineno++) {
        char *hash = strchr(line, '#'), *save = NULL;
        int n = 0;
        if (hash)
            *hash = 0;
        for (char *t = strtok_r(line, " \t\r\n", &save); t && n < (int)(sizeof w / sizeof *w);
             t = strtok_r(NULL, " \t\r\n", &save))
            w[n++] = t;
        if (n == 0 || strcmp(w[0], "motion"))
            continue;
        lumo_status st = srv_motion_parse_words(m, s, w + 1, n - 1, msg, sizeof msg);
        if (st) {
            snprintf(err, errlen, "%s:%d: %s", path, lineno, msg);
            fclose(f);
            return st;
        }
    }
    fclose(f);
    return LUMO_OK;
}

srv_motion_key srv_motion_at(const srv_motion_track *tr, double t)
{
    const srv_motion_key *k = tr->keys;
    size_t n = tr->nkeys;
    double end = k[n - 1].t;
    if (tr->loop && end > 0.0 && t > end)
        t = fmod(t, end);
    if (t <= k[0].t)
        return k[0];
    if (t >= end)
        return k[n - 1];
    size_t i = 1;
    while (k[i].t < t)
        i++;
    float a = (float)((t - k[i - 1].t) / (k[i].t - k[i - 1].t));
    srv_motion_key r = {(float)t, v3_add(v3_scale(k[i - 1].p, 1.0f - a), v3_scale(k[i].p, a)),
                        k[i - 1].yaw_deg * (1.0f - a) + k[i].yaw_deg * a};
    return r;
}
