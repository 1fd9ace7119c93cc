/*
 * pm/pm_stream.h — writing the progressive-mesh stream of
 * docs/progressive-mesh.md from a srv_pm (server/pm/pm_build.c). The client
 * reads it with lumo/pmesh.h.
 */
#ifndef SRV_PM_STREAM_H
#define SRV_PM_STREAM_H

#include <stddef.h>
#include <stdint.h>
#include "pm/draco_shim.h"
#include "pm/pm.h"
#include "lumo/pmesh.h"

/* Where the bits go (split records only), filled when options->stats is
 * set: bits of each split-block field summed over the split vertices, and
 * the bytes of their Draco payloads and record framing. */
typedef struct srv_pm_stream_stats {
    uint64_t splits;                    /* split vertices */
    /* bits of the range code (-log2 of each coded bit's probability) */
    double   parent_bits, kind_bits;    /* lookup-table parents, kind codes */
    double   fan_bits;                  /* fan splits: the fan's rank, or first wing + fan length */
    uint64_t arc_ranked, fans;          /* fan splits coded by rank; all fan splits */
    double   mask_bits;                 /* mask splits: masks, flips, third vertices */
    double   pos_bits;                  /* CODED positions: the residuals in the range code */
    double   albedo_bits;               /* CODED albedo: "the parent's" or residuals */
    double   other_bits;                /* the code's flush and rounding */
    uint64_t draco_bytes, frame_bytes;  /* payloads; record heads (varints + CRC) */
    uint64_t ctx_bits[LUMO_PMESH_CONTEXTS][2];  /* adaptive bits coded per context:
                                                   zeros, ones (tools/pm_priors.py) */
} srv_pm_stream_stats;

typedef struct srv_pm_stream_options {
    uint32_t            batch_vertices;  /* vertices per batch; 0 (default): per mesh,
                                            srv_pm_stream_auto_batch */
    int                 quant_bits;      /* position grid bits; 0 (default): per mesh,
                                            srv_pm_stream_auto_bits */
    srv_draco_settings  draco;           /* the payload encoder choice */
    int                 position_coding; /* LUMO_PMESH_POS_CODED (default), _PREDICTED or
                                            _ABSOLUTE */
    srv_pm_stream_stats *stats;          /* NULL (default), or filled by the build */
    int                 fan_rank_escape; /* 1: every fan takes the rank's escape and is
                                            coded explicitly (tests the decoder's escape
                                            path; larger streams), 0 (default) */
    int                 lattice;         /* LUMO_PMESH_LATTICE (CODED only): 1 on, 0 off,
                                            -1 (default): per mesh, whichever stream is
                                            smaller (built both ways) */
} srv_pm_stream_options;

void srv_pm_stream_default_options(srv_pm_stream_options *o);

/* Position precision from the mesh's error budget: the fewest grid bits
 * (MIN_AUTO_BITS ... MAX_AUTO_BITS) whose step is at most 1/EDGE_STEPS of
 * the full mesh's median edge, so rounding moves a vertex by at most
 * 1/(2 EDGE_STEPS) of an edge per axis: detail finer than the mesh's own
 * sampling is not kept, detail at its scale is. */
#define SRV_PM_EDGE_STEPS    16.0
#define SRV_PM_MIN_AUTO_BITS 8
#define SRV_PM_MAX_AUTO_BITS 16
int srv_pm_stream_auto_bits(const srv_pm *pm);
/* Median edge length of the full mesh's faces (each face's three edges),
 * 0 when it has none or memory runs out. */
double srv_pm_median_edge(const srv_pm *pm);

/* Vertices per batch: BATCH (the paper's 250), doubled while the mesh
 * has more than BATCHES_MAX batches, at most MAX_BATCH: a large mesh
 * still arrives in a few hundred levels while each Draco payload's header
 * and tables (about 1.2 bits per vertex at 250) are shared by more
 * vertices; the client's work and memory per batch stay bounded by
 * MAX_BATCH vertices, whatever the mesh's size. */
#define SRV_PM_BATCH         250u
#define SRV_PM_MAX_BATCH     2000u
#define SRV_PM_BATCHES_MAX   256u
uint32_t srv_pm_stream_auto_batch(const srv_pm *pm);

/* One record's place in the stream, for listings and benchmarks. */
typedef struct srv_pm_batch_info {
    uint32_t first_vertex, vertex_count, face_count, move_count;
    size_t   offset, bytes, side_bytes, draco_bytes;
} srv_pm_batch_info;

/* Build the whole stream (header + every batch record) into one malloc'ed
 * buffer. If `batches` is not NULL it receives a malloc'ed array of
 * *nbatches entries. LUMO_OK; LUMO_ERR_ARG for an empty mesh or bad
 * options; else, with a message on stderr, LUMO_ERR_NOMEM, a Draco
 * encoder status (draco_shim.h) or LUMO_ERR_CORRUPT (a level the split
 * records cannot express: pm was not made by srv_pm_build). */
lumo_status srv_pm_stream_build(const srv_pm *pm, const srv_pm_stream_options *o, uint8_t **out,
                                size_t *len, srv_pm_batch_info **batches, uint32_t *nbatches);


#endif

/* For lumo-bake (server/pm/pm_pack.c): simplify one mesh, build its stream and
 * append it to a package as a PMSH chunk (one chunk per mesh, in mesh
 * order, replacing the raw MESH chunk). albedo: 3 bytes per vertex (0..255)
 * or NULL. o may be NULL for the defaults.
 * LUMO_OK, or the failing step's status (srv_pm_build_albedo,
 * srv_pm_stream_build, srv_pkgw_add) with a one-line reason in err. */
struct srv_pkg_writer;
lumo_status srv_pm_pack(struct srv_pkg_writer *w, const float *xyz, const uint8_t *albedo,
                        uint32_t nv, const uint32_t *tris, uint32_t nf,
                        const srv_pm_stream_options *o, char *err, size_t errlen);
