/*
 * vsl_motion.h — scripted motion of objects and lights (docs/dynamic.md
 * "Motion"): piecewise-linear paths over scene time, read from `motion`
 * lines of a scene file (the static bake skips them) or given one by one.
 *
 *   motion object NAME|INDEX [loop] T:X,Y,Z[:YAW] T:X,Y,Z[:YAW] ...
 *   motion light INDEX [loop] T:X,Y,Z T:X,Y,Z ...
 *
 * NAME is a mesh's name (the first of that name), else INDEX its index.
 * Times in seconds, increasing; an object's keys are its pose (offset from
 * where the scene put it, yaw in degrees about +y), a light's are its
 * position. Before the first key the first holds, after the last the last
 * (or, with loop, time wraps at the last key).
 */
#ifndef SRV_VSL_MOTION_H
#define SRV_VSL_MOTION_H

#include <stddef.h>
#include "scene/scene.h"
#include "vsl/vsl_pose.h"

#define SRV_MOTION_MAX_KEYS   32
#define SRV_MOTION_MAX_TRACKS 16

typedef struct srv_motion_key {
    float t;
    vec3  p;
    float yaw_deg;
} srv_motion_key;

typedef struct srv_motion_track {
    int      light;          /* 1: a light's position; 0: an object's pose */
    uint32_t target;         /* mesh or light index */
    int      loop;
    size_t   nkeys;
    srv_motion_key keys[SRV_MOTION_MAX_KEYS];
} srv_motion_track;

typedef struct srv_motion {
    size_t           ntracks;
    srv_motion_track tracks[SRV_MOTION_MAX_TRACKS];
} srv_motion;

/* Parse one motion line's words after "motion" (words[0] is "object" or
 * "light") against scene s (names, index ranges). LUMO_OK, or with a
 * reason LUMO_ERR_ARG (malformed, unknown target, times not increasing;
 * the key, its number and the part that is wrong named: "motion: key 2
 * '1:0,x,0': position '0,x,0' is not 3 finite numbers X,Y,Z"),
 * LUMO_ERR_RANGE (a position beyond ±SRV_SCENE_MAX_COORD) or
 * LUMO_ERR_LIMIT (too many keys or tracks, a key over 127 characters).
 * Times lie in [0, 1e9] s, yaws in [-1e6, 1e6] degrees. */
lumo_status srv_motion_parse_words(srv_motion *m, const srv_scene *s, char **words, int n,
                                   char *err, size_t errlen);

/* Every `motion` line of the scene file at path ('#' comments). LUMO_OK
 * (none is fine), LUMO_ERR_IO, or a parse error with path:line. */
lumo_status srv_motion_load(srv_motion *m, const srv_scene *s, const char *path, char *err, size_t errlen);

/* Track k's key at time t (interpolated). */
srv_motion_key srv_motion_at(const srv_motion_track *tr, double t);

#endif
