/*
 * lumo/prt.h — precomputed radiance transfer on the client (seed 003 §3.2,
 * Eq. 7; docs/prt.md): relighting each vertex of a mesh under distant
 * lighting given as spherical-harmonic coefficients, from the clustered-PCA
 * transfer the server wrote into a PRTV chunk (docs/package-format.md).
 *
 * Per frame: the lighting vector L (lumo_prt_light_*), then per cluster the
 * dot products M_k . L and B_j . L once (lumo_prt_frame), then per vertex
 * albedo * (M_k . L + sum_j w_j (B_j . L)) (lumo_prt_shade): 3 * P
 * multiply-adds per vertex for P components, whatever the SH order.
 *
 * SH convention: order N holds bands l = 0..N-1, index l*(l+1)+m, real SH
 * without the Condon-Shortley phase (server/prt/sh.h states the formulas).
 * The polar axis is +z of the mesh's space.
 *
 * Formats: lighting coefficients Q16.16 radiance (W/m^2/sr per basis
 * function), per channel; transfer means, components and weights Q1.14
 * (the chunk); per-cluster frame values Q16.16; radiance out UQ16.16.
 * Nothing is allocated: a lumo_prt is a view of the caller's chunk bytes,
 * which must outlive it; every other array is the caller's.
 */
#ifndef LUMO_PRT_H
#define LUMO_PRT_H

#include <stddef.h>
#include <stdint.h>
#include "lumo/config.h"
#include "lumo/fixed.h"
#include "lumo/scene.h"
#include "lumo/status.h"

#define LUMO_PRT_VERSION    1u    /* the PRTV chunk version this reader takes */
#define LUMO_PRT_MAX_ORDER  6     /* SH orders 1..6 (bands 0..5) */
#define LUMO_PRT_MAX_COEFFS (LUMO_PRT_MAX_ORDER * LUMO_PRT_MAX_ORDER)   /* 36 */
#define LUMO_PRT_HEADER_SIZE 12u  /* bytes of a PRTV chunk's header */

/* A parsed PRTV chunk (or a prefix of it holding every cluster). */
typedef struct lumo_prt {
    uint8_t  order;            /* N, 1..LUMO_PRT_MAX_ORDER */
    uint8_t  components;       /* P, 0..LUMO_PRT_MAX_COMPONENTS */
    uint32_t clusters;         /* K, 1..LUMO_PRT_MAX_CLUSTERS */
    uint32_t vertices;         /* V announced (the full mesh's vertex count) */
    uint32_t vertices_held;    /* complete vertex records in the bytes given */
    const uint8_t *cluster_data;  /* K records of (P + 1) * N^2 int16 */
    const uint8_t *pass_data;     /* K uint16: the draw pass (super-cluster) of each cluster */
    const uint8_t *vertex_data;   /* vertices_held records of 2 + 2P bytes */
} lumo_prt;

/* Bytes of one cluster record and one vertex record. */
size_t lumo_prt_cluster_bytes(unsigned order, unsigned components);
size_t lumo_prt_vertex_bytes(unsigned components);

/* The chunk's sizes from its header (the first LUMO_PRT_HEADER_SIZE bytes
 * of data, len >= that): *total, the whole chunk (header, clusters, pass
 * table, every vertex record); *fixed, the part before the vertex records.
 * For a client that holds a streamed chunk (lumo/session.h's PRTV and PRTS
 * messages) before its bytes arrive. Errors as lumo_prt_parse's header
 * checks (TRUNCATED, VERSION, RANGE, LIMIT, CORRUPT); LUMO_ERR_OVERFLOW when
 * the size does not fit a size_t. */
lumo_status lumo_prt_chunk_size(const uint8_t *data, size_t len, size_t *total, size_t *fixed);

/* Check the units of a chunk whose bytes [0, end) are at data and of which
 * [0, from) were checked before: every pass entry and vertex record that
 * ends in (from, end] must name a cluster < K (the header's). LUMO_OK or
 * LUMO_ERR_RANGE; LUMO_ERR_ARG when the header is not in [0, end). */
lumo_status lumo_prt_check_span(const uint8_t *data, size_t from, size_t end);

/* Parse data[0..len): the header, every cluster record, the pass table,
 * then as many whole vertex records as len holds (a streamed prefix is
 * fine; bytes past the V-th record are LUMO_ERR_CORRUPT). Every pass and
 * every held vertex's cluster index is checked (< K). LUMO_OK; LUMO_ERR_ARG (NULL), LUMO_ERR_TRUNCATED (header or
 * clusters incomplete), LUMO_ERR_VERSION, LUMO_ERR_RANGE (order, a cluster
 * index), LUMO_ERR_LIMIT (K or P above lumo/config.h's limits),
 * LUMO_ERR_CORRUPT (non-zero flags, trailing bytes). All-or-nothing: *out
 * is written only on success. */
lumo_status lumo_prt_parse(lumo_prt *out, const uint8_t *data, size_t len);

/* Distant lighting as SH radiance coefficients, one vector per channel. */
typedef struct lumo_prt_light {
    uint8_t     order;                      /* N: coefficients 0..N*N-1 are used */
    lumo_q16_16 c[3][LUMO_PRT_MAX_COEFFS];  /* per channel (r, g, b), W/m^2/sr per basis function */
} lumo_prt_light;

/* The PRTL payload (an environment's lighting, docs/package-format.md): u8
 * order N, 3 zero bytes, 3 x N^2 int32 Q16.16, channel-major, into *out.
 * LUMO_ERR_TRUNCATED, LUMO_ERR_CORRUPT (length or reserved bytes),
 * LUMO_ERR_RANGE (order), LUMO_ERR_ARG. */
lumo_status lumo_prt_light_decode(const uint8_t *p, size_t len, lumo_prt_light *out);

/* The draw pass of cluster k (< clusters): the super-cluster a multipass
 * GPU client uploads it with (seed 003 §4.3); passes are numbered from 0. */
uint32_t lumo_prt_pass(const lumo_prt *p, uint32_t k);

/* All coefficients zero, order N (1..6): LUMO_OK or LUMO_ERR_RANGE. */
lumo_status lumo_prt_light_clear(lumo_prt_light *l, unsigned order);

/* y_i(d) in Q2.30 for i < order^2, d a unit vector (Q1.14; any length
 * within 2 ulp of 1, as lumo_normalize3_q14 makes). Error against the
 * double formula at the normalised direction <= 1e-3, most of it the
 * direction's own Q1.14 rounding raised to the 5th power of band 5
 * (tests/prt/test_prt_client.c). */
void lumo_prt_sh_eval(unsigned order, const lumo_q1_14 d[3], int32_t *y);

/* Add a distant light of irradiance e (W/m^2 per channel, on a surface
 * facing it) arriving from unit direction `towards` (surface to light):
 * L_i += e y_i(towards), the delta function's projection, so that an
 * unshadowed vertex of normal n gets e max(n . towards, 0) / pi up to the
 * band limit. Saturates. LUMO_OK or LUMO_ERR_ARG. */
lumo_status lumo_prt_light_add_directional(lumo_prt_light *l, const lumo_q1_14 towards[3],
                                           const lumo_uq16_16 e[3]);

/* Add one of the scene's lights (the package's INFO, lumo/scene.h) as a
 * distant light seen from `centre` (metres, Q16.16; PRT's lighting is
 * distant, so a local light is taken where the object is): directional as
 * it is; point, spot and area (at its rectangle's centre) from their
 * direction to it with irradiance power / (4 pi r^2); a spot whose cone
 * misses the centre adds nothing. LUMO_OK, LUMO_ERR_ARG (NULL, bad order),
 * LUMO_ERR_RANGE (a local light at the centre itself). Error against the
 * double formula: docs/prt.md. */
lumo_status lumo_prt_light_add_pkg(lumo_prt_light *l, const lumo_pkg_light *light, const lumo_q16_16 centre[3]);

/* Rotate the lighting: out = the lighting turned by R = Rz(gamma) Ry(beta)
 * Rz(alpha) (alpha first), each angle given by its cosine and sine (Q1.14,
 * a unit pair). Zonal method: Rz per band by cos/sin(m angle), Ry(beta) as
 * Rx(-90) Rz(beta) Rx(+90) with Rx(90)'s constant per-band tables. in and
 * out may not overlap. Error against the double rotation: docs/prt.md. */
lumo_status lumo_prt_light_rotate(const lumo_prt_light *in, const lumo_q1_14 alpha[2],
                                  const lumo_q1_14 beta[2], const lumo_q1_14 gamma[2],
                                  lumo_prt_light *out);

/* int32 entries of the per-frame table: 3 * K * (P + 1). */
size_t lumo_prt_frame_entries(const lumo_prt *p);

/* The per-frame table (Eq. 7's CPU part): for cluster k and channel c,
 * M_k . L_c then B_kj . L_c for each component j, Q16.16, saturated.
 * frame: lumo_prt_frame_entries(p). LUMO_OK, LUMO_ERR_ARG (NULL) or
 * LUMO_ERR_RANGE (the light's order differs from the chunk's). */
lumo_status lumo_prt_frame(const lumo_prt *p, const lumo_prt_light *l, lumo_q16_16 *frame);

/* Radiance of vertices [first, first + count) (count <= vertices_held -
 * first): albedo * (M.L + sum_j w_j (B_j.L)), clamped at 0, written as
 * the rasterizer's per-vertex `lit` entries (lumo_raster_mesh.lit: 6 per
 * vertex of the whole mesh, front then back; back = 0, transfer holds the
 * front hemisphere only); only the entries of those vertices are written.
 * albedo: 3 per vertex of the whole mesh in [0, 1] (Q1.14), or NULL for 1.
 * LUMO_OK, LUMO_ERR_ARG or LUMO_ERR_RANGE. Cost: 3 (P + 1) multiply-adds
 * and 3 albedo products per vertex. */
lumo_status lumo_prt_shade(const lumo_prt *p, const lumo_q16_16 *frame, const lumo_q1_14 *albedo,
                           uint32_t first, uint32_t count, lumo_uq16_16 *lit);

#endif
