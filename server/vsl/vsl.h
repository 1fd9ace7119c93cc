/*
 * vsl.h — virtual surface-element lights (seed 004 §0.4): points placed on
 * the scene's surfaces a priori, independently of the lighting, that collect
 * the energy of photon impacts (vsl_pool.h) and light the scene as small
 * diffuse emitters (vsl_light.h).
 *
 * A VSL belongs to one object (a mesh of the srv_scene, by index) and is
 * stored in that object's frame, so that it moves with the object (§0.4.2
 * note (i)); every non-emitting object keeps at least one (note (ii)).
 * Emitter meshes (area-light rectangles) are black and get none.
 */
#ifndef SRV_VSL_H
#define SRV_VSL_H

#include <stddef.h>
#include <stdint.h>
#include "scene/scene.h"

typedef struct srv_vsl {
    vec3     pos;       /* object frame, scene units (m) */
    vec3     normal;    /* object frame, unit, the triangle's front side */
    vec3     albedo;    /* the surface's, linear */
    float    area;      /* dS' (m^2): the object's area over its VSL count */
    uint32_t object;    /* mesh index in the srv_scene */
} srv_vsl;

/* VSLs sorted by object: object o owns v[first[o] .. first[o] + count[o]). */
typedef struct srv_vsl_set {
    srv_vsl  *v;
    size_t    n;
    size_t    nobjects;  /* == the scene's nmeshes */
    uint32_t *first, *count;
} srv_vsl_set;

typedef struct srv_vsl_place_opts {
    size_t   nv;          /* N_v, the number wanted (>= number of non-emitting objects) */
    float    oversample;  /* extra density before removal: 0.10 in §0.4.2 */
    float    shrink;      /* triangles scaled about their centroid by this (Figure 4.a) */
    uint64_t seed;
} srv_vsl_place_opts;

/* §0.4.2 defaults: 10% more, triangles scaled by 0.95 ("a small scale":
 * 0.8 moved the Cornell walls' energy 20% of a 2 m triangle inwards and
 * over-lit the room by 4%, 0.95 by under 1% — docs/dynamic.md). */
srv_vsl_place_opts srv_vsl_place_defaults(size_t nv, uint64_t seed);

/* Place N_v VSLs on s: candidates drawn by area (1 + oversample) N_v,
 * at least one per object, then thinned by Algorithm 1 (srv_vsl_thin).
 * The set owns its arrays (free with srv_vsl_set_free). LUMO_OK, or with
 * a reason in err LUMO_ERR_ARG (nv below the number of non-emitting
 * objects, or no surface) or LUMO_ERR_NOMEM. */
lumo_status srv_vsl_place(const srv_scene *s, const srv_vsl_place_opts *o, srv_vsl_set *out,
                          char *err, size_t errlen);
void srv_vsl_set_free(srv_vsl_set *set);

/* Algorithm 1 (§0.4.2, Figure 5): remove points until keep remain. Each
 * point holds its two nearest living neighbours (d_min1, d_min2); the one
 * removed is the point with the smallest (d_min1, d_min2), ties to the
 * lower index — of the closest pair, the one in the denser place. Only the
 * points whose V1 or V2 was removed look for new neighbours (O(n) each),
 * so a removal costs O(n) scans plus O(n) per such point, not O(n^2).
 * group[i] (may be NULL) names point i's object: the last living point of
 * a group is never removed. alive[i] is set to 1 for survivors, 0 for the
 * removed. Returns the number alive (> keep only when every group is down
 * to one). LUMO_ERR_NOMEM is reported as (size_t)-1. */
size_t srv_vsl_thin(const vec3 *p, const uint32_t *group, size_t n, size_t keep, uint8_t *alive);

/* The same removal done naively (every distance recomputed for every
 * removal, O(n^3) in all): the same survivors as srv_vsl_thin, for tests
 * and the benchmark only. */
size_t srv_vsl_thin_naive(const vec3 *p, const uint32_t *group, size_t n, size_t keep, uint8_t *alive);

#endif
