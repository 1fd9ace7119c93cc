/*
 * prt/transfer.h — per-vertex diffuse transfer vectors (seed 003 §3.1.1,
 * Eq. 1-3, for a diffuse BRDF; Sloan, Kautz & Snyder 2002 §4):
 *
 *   T_p = 1/pi int V_p(s) max(n_p . s, 0) y(s) ds                (bounce 0)
 *   T_p += 1/pi int (1 - V_p(s)) max(n_p . s, 0) rho_q T_q^{b-1} ds  (b >= 1)
 *
 * so that a vertex of albedo rho under distant lighting L (SH radiance
 * coefficients) leaves with radiance rho (T_p . L). T is scalar: the
 * colour is the vertex albedo's and the lighting's; rho_q, the albedo of
 * the surface a bounce ray hits, is the mean of its channels.
 *
 * Visibility V_p is traced with Embree (bake/rt.h) against the mesh itself
 * (self-shadowing, self-interreflection; seed 003 §3.1.1's shadow and
 * light-transport passes). Every vertex uses the same stratified set of
 * directions (seeded), so the result depends only on the seed.
 * Glossy transfer matrices (the thesis's Phong and Cook-Torrance BRDFs)
 * are not done: lumo's surfaces are diffuse (docs/prt.md).
 */
#ifndef SRV_PRT_TRANSFER_H
#define SRV_PRT_TRANSFER_H

#include <stdint.h>
#include <stddef.h>
#include "lumo/status.h"

typedef struct srv_prt_mesh {
    uint32_t nverts, ntris;
    const float    *xyz;      /* 3 * nverts */
    const uint32_t *tris;     /* 3 * ntris */
    const uint8_t  *albedo;   /* 3 * nverts, 0..255 linear, or NULL (0.8) */
} srv_prt_mesh;

typedef struct srv_prt_transfer_opts {
    int      order;       /* SH order N, 1..6 (N*N coefficients; seed 003 uses 6) */
    int      strata;      /* directions: strata x strata jittered over the sphere */
    int      shadowed;    /* 0: unshadowed transfer (V = 1) */
    int      bounces;     /* interreflection bounces (0: shadowed only) */
    uint64_t seed;
    int      threads;
    int      progress;
} srv_prt_transfer_opts;

void srv_prt_transfer_default_opts(srv_prt_transfer_opts *o);

/* Area-weighted vertex normals (unit; a vertex of no area gets +z). */
void srv_prt_vertex_normals(const srv_prt_mesh *m, float *n);

/* out: nverts * order^2 doubles, vertex-major. LUMO_OK, LUMO_ERR_ARG (bad
 * options, an index out of range, an empty mesh), LUMO_ERR_NOMEM, with a
 * one-line reason in err. */
lumo_status srv_prt_transfer(const srv_prt_mesh *m, const srv_prt_transfer_opts *o, double *out,
                             char *err, size_t errlen);

#endif
