/*
 * prt/prt_pack.h — PRT into a .lumo package (docs/package-format.md
 * "PRTV", "PRTL"; docs/prt.md): the transfer of a mesh's progressive
 * vertices (server/pm), compressed by CPCA (prt/cpca.h), quantized to
 * Q1.14, and the SH lighting of an environment map.
 */
#ifndef SRV_PRT_PACK_H
#define SRV_PRT_PACK_H

#include <stddef.h>
#include <stdint.h>
#include "lumo/status.h"
#include "prt/cpca.h"
#include "prt/transfer.h"

#define SRV_PRT_PKG_PRTV 0x56545250u   /* 'P','R','T','V' as LUMO_PKG_FOURCC */
#define SRV_PRT_PKG_PRTL 0x4C545250u   /* 'P','R','T','L' */

/* The PRTV chunk of a compressed transfer: header, clusters (mean then
 * components, Q1.14), the pass of each cluster (pass: k entries from
 * srv_cpca_superclusters, or NULL: one pass per cluster), vertices
 * (cluster, weights Q1.14) in vertex order.
 * Malloc'ed into *out. LUMO_OK, LUMO_ERR_LIMIT (clusters or components
 * beyond lumo/config.h), LUMO_ERR_RANGE (a value outside [-2, 2): it would
 * not fit Q1.14: nothing is saturated silently), LUMO_ERR_NOMEM. */
lumo_status srv_prt_encode(const srv_cpca *c, int order, const uint32_t *pass, uint8_t **out, size_t *len);

/* The uncompressed-vs-quantized error: average over vertices of the
 * squared difference between the CPCA reconstruction in double and the
 * one from the Q1.14 chunk. */
double srv_prt_quant_sq_error(const srv_cpca *c, const uint8_t *chunk, size_t len);

typedef struct srv_prt_options {
    srv_prt_transfer_opts transfer;
    srv_cpca_opts         cpca;
    int                   registers;   /* super-clusters under this many float4
                                          registers a pass (seed 003 §4.1: 256);
                                          0: one pass per cluster */
} srv_prt_options;

void srv_prt_default_options(srv_prt_options *o);

/* What srv_prt_pack measured: seed 003 Chapter 5's metrics for the mesh. */
typedef struct srv_prt_stats {
    uint32_t vertices, triangles, clusters, passes;
    int      iterations;                 /* LBG passes */
    double   transfer_seconds, cluster_seconds;
    double   overdraw, overdraw_passes;  /* Eq. 8: one pass per cluster; the written passes */
    double   sq_error, quant_sq_error;   /* CPCA against the transfer; Q1.14 against CPCA */
    size_t   bytes;                      /* the PRTV chunk */
} srv_prt_stats;

/* For lumo-bake --prt: the same progressive mesh srv_pm_pack builds (the
 * vertex order of its PMSH chunk), its transfer, CPCA, one PRTV chunk;
 * stats (may be NULL) gets the metrics. LUMO_OK or the failing step's
 * status with a reason in err. */
struct srv_pkg_writer;
lumo_status srv_prt_pack(struct srv_pkg_writer *w, const float *xyz, const uint8_t *albedo, uint32_t nv,
                         const uint32_t *tris, uint32_t nf, const srv_prt_options *o, srv_prt_stats *stats,
                         char *err, size_t errlen);

/* An equirectangular image (linear RGB radiance, w x h, row-major from the
 * top; docs/prt.md) projected on SH of order N. lumo's scenes are y-up, so
 * row y looks at polar angle theta = pi (y + 0.5) / h from +y and column x
 * at phi = 2 pi (x + 0.5) / w: d = (sin theta cos phi, cos theta,
 * sin theta sin phi). out[c * N^2 + i]: radiance per basis function. */
void srv_prt_env_project(const float *rgb, int w, int h, int order, double *out);

/* The PRTL chunk: u8 order, 3 zero bytes, then 3 x N^2 int32 Q16.16
 * (channel-major). LUMO_ERR_RANGE when a coefficient is beyond Q16.16. */
lumo_status srv_prt_encode_light(const double *coeffs, int order, uint8_t **out, size_t *len);

#endif
