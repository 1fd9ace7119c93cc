/*
 * pm/pm.h — progressive meshes on the server (seed 000 §4.2).
 *
 * srv_pm_build() simplifies a triangle mesh by half-edge collapses (an edge
 * collapses onto one of its end vertices; no new vertex) ordered by the
 * quadric error metric of Garland & Heckbert, then renumbers the vertices by
 * significance: the base mesh first, then the collapsed vertices with the
 * last collapsed first. The result is the indexed face set of the full mesh
 * plus the vertex lookup table (parent[v] < v: the vertex v collapsed onto),
 * with faces ordered by the level at which they appear. Every vertex count
 * k in [seed_vertices, vertices] is a level: the faces with level <= k,
 * each corner v resolved by following parent[] until it is below k; the
 * levels from base_vertices on keep every input vertex within max_error.
 *
 * Units: positions in the input's units (metres in lumo). Memory: every
 * array is malloc'ed; srv_pm_free() releases them.
 */
#ifndef SRV_PM_H
#define SRV_PM_H

#include <stddef.h>
#include <stdint.h>
#include "lumo/status.h"

typedef struct srv_pm_options {
    uint32_t min_vertices;     /* stop collapsing at this many (default 3) */
    double   boundary_weight;  /* penalty quadric weight of boundary edges (100) */
    double   flip_cos;         /* reject a collapse turning a face normal by
                                  more than acos(flip_cos) (0.2) */
    double   round_fraction;   /* independent-set rounds: each round considers
                                  the cheapest fraction of the candidates
                                  (0.1); 0 = one collapse at a time */
    double   max_error;        /* refuse a collapse whose worst-case error (the
                                  distance of an input vertex from the new faces,
                                  or of the new faces from the input surface)
                                  exceeds this fraction of the bounding-box
                                  diagonal (0.05): it would change the shape,
                                  not its detail; every input vertex then stays
                                  that near every level; 0 = no limit */
    int      seed;             /* 1 (default): after the collapses within
                                  max_error, go on without the limit to a seed
                                  mesh of a few vertices (seed_vertices); the
                                  levels from base_vertices on are the same
                                  either way; 0: stop at the base mesh */
} srv_pm_options;

typedef struct srv_pm {
    uint32_t  vertices;        /* n, after welding duplicates */
    uint32_t  faces;           /* after dropping degenerate/duplicate faces */
    uint32_t  base_vertices;   /* vertices of the coarsest level shown (the
                                  last within max_error) */
    uint32_t  base_faces;      /* faces of that level */
    uint32_t  seed_vertices;   /* vertices of the seed mesh (<= base_vertices):
                                  levels seed_vertices .. base_vertices - 1 go
                                  past max_error and are never shown; the
                                  stream's base record builds the base mesh
                                  from the seed by splits */
    uint32_t  seed_faces;      /* faces of the seed mesh (level seed_vertices) */
    float    *xyz;             /* 3 * vertices, progressive order */
    uint8_t  *albedo;          /* 3 * vertices (sRGB-agnostic 0..255), or NULL */
    uint32_t *parent;          /* vertices: parent[v] < v (base: parent[v] = v) */
    uint32_t *tris;            /* 3 * faces: full-resolution corners, faces in
                                  appearance order, input winding kept */
    uint32_t *level;           /* faces: vertex count at which the face appears */
    uint32_t *source;          /* vertices: an input vertex welded into it */
    uint32_t  welded;          /* input vertices merged into another */
    uint32_t  dropped_faces;   /* degenerate or duplicate input faces */
} srv_pm;

void srv_pm_default_options(srv_pm_options *o);

/* Build from nv positions (xyz) and nf triangles. LUMO_OK, LUMO_ERR_NOMEM,
 * or LUMO_ERR_RANGE for an index out of range. */
lumo_status srv_pm_build(const float *xyz, uint32_t nv, const uint32_t *tris, uint32_t nf,
                         const srv_pm_options *opt, srv_pm *out);

/* The same with a per-vertex albedo (3 bytes per vertex, linear 0..255,
 * may be NULL). Vertices weld only when position and albedo agree, so a
 * colour seam stays a seam: the simplifier sees it as a boundary, which it
 * penalises and only slides along. */
lumo_status srv_pm_build_albedo(const float *xyz, const uint8_t *albedo, uint32_t nv,
                                const uint32_t *tris, uint32_t nf, const srv_pm_options *opt,
                                srv_pm *out);
void srv_pm_free(srv_pm *pm);

/* Vertex v resolved at level k (k > 0): follows parent[] while v >= k. */
uint32_t srv_pm_resolve(const srv_pm *pm, uint32_t v, uint32_t k);

/* Number of faces at level k (the prefix of faces with level <= k). */
uint32_t srv_pm_level_faces(const srv_pm *pm, uint32_t k);

/* Write the faces of level k (3 per face, resolved) into out, which holds
 * 3 * srv_pm_level_faces(pm, k) entries. Returns that face count. */
uint32_t srv_pm_level(const srv_pm *pm, uint32_t k, uint32_t *out);

#endif
