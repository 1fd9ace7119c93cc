/* fuzz_motion.c — hostile text into the motion parser (server/vsl/vsl_motion.c):
 * `motion` lines of scene files and the live `move` commands lumo-server
 * --dynamic reads from its commands file or FIFO. The input is split into
 * words as those readers split it, against a scene of two meshes ("ball",
 * "wall") and two lights. Nothing may read out of bounds; a refusal is one
 * terminated line starting "motion"; an accepted track names an existing
 * target and holds 1..SRV_MOTION_MAX_KEYS keys, times increasing within
 * [0, 1e9], positions within SRV_SCENE_MAX_COORD. Host code: built by
 * tests/hostile/hostile.mk. Seeds in tests/fuzz/seeds/fuzz_motion/. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include "vsl/vsl_motion.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static srv_scene *scene(void)
{
    static srv_scene s;
    static int made;
    if (made)
        return &s;
    srv_scene_init(&s);
    srv_scene_add_mesh(&s, "ball", 3, 1);
    srv_scene_add_mesh(&s, "wall", 3, 1);
    srv_light l;
    memset(&l, 0, sizeof l);
    l.kind = LUMO_LIGHT_POINT;
    srv_scene_add_light(&s, &l);
    srv_scene_add_light(&s, &l);
    made = 1;
    return &s;
}

static int bad_track(const srv_scene *s, const srv_motion_track *tr)
{
    if (tr->nkeys < 1 || tr->nkeys > SRV_MOTION_MAX_KEYS || tr->target >= (tr->light ? s->nlights : s->nmeshes))
        return 1;
    for (size_t k = 0; k < tr->nkeys; k++) {
        const srv_motion_key *key = &tr->keys[k];
        if (!(key->t >= 0.0f && key->t <= 1e9f) || (k && !(key->t > tr->keys[k - 1].t)) ||
            !(fabsf(key->p.x) <= SRV_SCENE_MAX_COORD && fabsf(key->p.y) <= SRV_SCENE_MAX_COORD &&
              fabsf(key->p.z) <= SRV_SCENE_MAX_COORD) || !isfinite(key->yaw_deg))
            return 1;
    }
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char err[256], *w[SRV_MOTION_MAX_KEYS + 8], *save = NULL;
    srv_motion m;
    int n = 0;
    char *text = malloc(size + 1);
    if (!text)
        return 0;
    memcpy(text, data, size);
    text[size] = 0;
    for (char *t = strtok_r(text, " \t\r\n", &save); t && n < (int)(sizeof w / sizeof *w);
         t = strtok_r(NULL, " \t\r\n", &save))
        w[n++] = t;
    memset(&m, 0, sizeof m);
    memset(err, 'x', sizeof err);
    err[sizeof err - 1] = 0;
    if (n > 0) {
        lumo_status st = srv_motion_parse_words(&m, scene(), w, n, err, sizeof err);
        if (st && (strncmp(err, "motion", 6) || strchr(err, '\n')))
            abort();
        if (!st && (m.ntracks != 1 || bad_track(scene(), &m.tracks[0])))
            abort();
    }
    free(text);
    return 0;
}
