/*
 * lumo/pmesh.h — progressive meshes on the client (seed 000 §4.2; the
 * stream is specified byte by byte in docs/progressive-mesh.md).
 *
 * A stream is a header followed by batches. The first batch is the base
 * mesh; each later batch adds the next `vertex_count` vertices, in the
 * server's significance order, by vertex splits (the inverse of the
 * server's half-edge collapses). The lookup table, the connectivity and
 * (by default) the positions are range coded in each record's block; older
 * position codings carry positions in a Draco point cloud decoded with
 * lumo's own decoder (lumo/draco.h).
 *
 * Usage:
 *   lumo_pmesh_header h;  lumo_pmesh_read_header(stream, size, &h);
 *   arena of lumo_pmesh_arena_bytes(&h) bytes;  lumo_pmesh_init(&pm, &h, &arena);
 *   for each batch record B:  lumo_pmesh_apply(&pm, B, lumo_pmesh_record_size(B...));
 *   lumo_pmesh_get_view(&pm, &view);  -> hand to the rasterizer
 *
 * Memory: everything lives in the arena given to init, sized up front from
 * the header's counts; applying a batch allocates nothing. Work per batch
 * grows with the batch (its vertices, the faces they touch and the
 * valences of their parents), never with the mesh.
 *
 * Hostile input: every batch is checked (CRC-32, counts, indices, bits);
 * a batch that fails is rejected whole with an error and the mesh stays at
 * its last good level, so a retransmitted good batch and the ones after it
 * still apply. No level ever holds a degenerate triangle.
 */
#ifndef LUMO_PMESH_H
#define LUMO_PMESH_H

#include <stddef.h>
#include <stdint.h>
#include "lumo/arena.h"
#include "lumo/fixed.h"
#include "lumo/status.h"

/* The stream header (docs/progressive-mesh.md §2.1): 7 fixed bytes (its
 * length in byte 6), eight LEB128 counts, 23 fixed bytes: 38 to 70 bytes. */
#define LUMO_PMESH_HEADER_MIN 38u
#define LUMO_PMESH_HEADER_MAX 70u
/* A batch record's head (docs/progressive-mesh.md §2.2): one or two LEB128
 * varints (the block's size and a payload flag, the payload's size) and a
 * CRC-32: 5 to 14 bytes. */
#define LUMO_PMESH_BATCH_HEAD_MIN 5u
#define LUMO_PMESH_BATCH_HEAD_MAX 14u   /* bytes of a record head, at most */
#define LUMO_PMESH_VERSION     8u    /* the stream version read (docs/progressive-mesh.md) */
#define LUMO_PMESH_MAX_QBITS   20u   /* position quantization bits, at most */
/* How a batch's Draco payload carries positions (docs/progressive-mesh.md):
 * ABSOLUTE: a quantized POSITION attribute on the stream's grid (stock
 * Draco tools show the points); PREDICTED: a GENERIC int32 x3 attribute
 * of grid residuals from a prediction (for a split vertex the mean of its
 * neighbours right after the split, in the base mesh the previous vertex),
 * about half the bytes. */
#define LUMO_PMESH_POS_ABSOLUTE 0u
#define LUMO_PMESH_POS_PREDICTED 1u   /* residuals from the prediction (above) */
/* CODED (the default): no Draco payloads; the base record's block holds
 * its positions as plain grid integers, a split vertex's residuals from
 * the same prediction are coded in its split record's range code, by
 * classes conditioned on the spread of its ring (docs/progressive-mesh.md
 * §2.3 step 5). Not with albedo (which rides in the payloads). */
#define LUMO_PMESH_POS_CODED     2u
/* Header flag: every payload also carries a COLOR uint8 x3 attribute, the
 * per-vertex albedo (0..255 -> 0..1). */
#define LUMO_PMESH_HAS_ALBEDO 1u
/* Header flag (CODED only): a split vertex's coordinate on an axis may be
 * copied from one of its ring's (docs/progressive-mesh.md §2.3 step 5):
 * meshes extracted from a voxel grid put their vertices on its lines, so
 * a coordinate often repeats a neighbour's. The writer sets it when it
 * makes the stream smaller. */
#define LUMO_PMESH_LATTICE    2u
/* "LPM1", first character in the lowest byte. */
#define LUMO_PMESH_MAGIC       0x314d504cu
/* Adaptive contexts of the split records' range code (a probability and
 * a count each, one uint32), kept from record to record (layout:
 * lumo_shared/pmesh_shared.h); in the arena. */
#define LUMO_PMESH_CONTEXTS    346u

/* The stream header (all counts validated by lumo_pmesh_read_header). */
typedef struct lumo_pmesh_header {
    uint32_t header_bytes;      /* the header's own length; records follow */
    uint32_t vertices;          /* n: vertices of the full mesh */
    uint32_t faces;             /* triangles of the full mesh */
    uint32_t base_vertices;     /* vertices of the base mesh (first batch) */
    uint32_t base_faces;        /* triangles of the base mesh */
    uint32_t batch_vertices;    /* nominal vertices per batch (the last may be short) */
    uint32_t batch_count;       /* batch records following the header (derived) */
    uint32_t max_batch_faces;   /* largest face count of one batch */
    uint32_t max_batch_moves;   /* largest corner-move count of one batch */
    uint32_t max_batch_bytes;   /* largest batch record, header included */
    uint32_t quant_bits;        /* position quantization (1..LUMO_PMESH_MAX_QBITS) */
    uint32_t position_coding;   /* LUMO_PMESH_POS_ABSOLUTE, _PREDICTED or _CODED */
    uint32_t flags;             /* LUMO_PMESH_HAS_ALBEDO */
    uint32_t origin_bits[3];    /* grid origin, IEEE-754 binary32 bits, metres */
    uint32_t range_bits;        /* grid edge length, binary32 bits, metres */
} lumo_pmesh_header;

/* The current level, as the rasterizer wants it. Arrays belong to the
 * pmesh (its arena) and change with every applied batch. */
typedef struct lumo_pmesh_view {
    uint32_t           vertex_count;   /* vertices of the current level */
    uint32_t           face_count;     /* triangles of the current level */
    const lumo_q16_16 *positions;  /* 3 per vertex, metres */
    const lumo_q1_14  *normals;    /* 3 per vertex, unit (area-weighted face
                                      normals of the current level); 0,0,0
                                      for a vertex with no face */
    const uint32_t    *triangles;  /* 3 per face, counter-clockwise front,
                                      every index < vertex_count, never
                                      two equal indices in one triangle */
    const lumo_q1_14  *albedo;     /* 3 per vertex in [0, 1], or NULL when the
                                      stream carries none (use the mesh's) */
} lumo_pmesh_view;

/* The object. Fields are private; read the level through lumo_pmesh_view. */
typedef struct lumo_pmesh {
    lumo_pmesh_header h;
    uint32_t     vertex_count, face_count, batches_applied;
    lumo_q16_16  origin[3], range;    /* dequantization, metres */
    lumo_q16_16 *pos;                 /* 3 * vertices */
    int32_t     *qpos;                /* 3 * vertices: quantized grid integers */
    lumo_q1_14  *nrm;                 /* 3 * vertices */
    lumo_q1_14  *albedo;              /* 3 * vertices, or NULL */
    uint32_t    *tris;                /* 3 * faces: the index buffer */
    uint32_t    *next;                /* 3 * faces: corner lists per vertex */
    uint32_t    *head;                /* vertices: first corner showing it */
    uint32_t    *mark;                /* vertices: last batch that touched it */
    uint32_t    *journal;             /* undo log of one batch */
    uint32_t    *dirty;               /* vertices whose normal to refresh */
    uint32_t    *batch_parent;        /* parent of each vertex of the batch */
    uint32_t    *split_log;           /* journal length before each split of
                                         the last batch (batch_vertices + 1) */
    uint32_t    *round_parent;        /* vertices: the round start of the last
                                         round the vertex was a parent in, or 0 */
    uint32_t    *stamp_log;           /* round_parent of each split's parent
                                         before the split (undo) */
    uint32_t     log_n;               /* journal entries of the last batch */
    uint32_t     last_parent;         /* parent of the last split applied, or
                                         0xffffffff before the first */
    uint32_t     last_first;          /* first vertex of the last batch */
    uint32_t     round_first;         /* first split vertex of the current
                                         collapse round (parent scan) */
    uint32_t     last_fan;            /* the last split was a fan split */
    uint32_t     last_same;           /* the last split's albedo was its parent's */
    uint32_t    *ctx;                 /* LUMO_PMESH_CONTEXTS range-code contexts */
    uint32_t    *ctx_undo;            /* their copy from before the batch */
    int          rewound;             /* lumo_pmesh_rewind was used */
    int64_t     *arc_key;             /* fan-rank candidates of one split
                                         (ARC_MAX_CORNERS^2 keys) */
    uint8_t     *scratch;             /* Draco decoder work memory */
    size_t       scratch_bytes;
} lumo_pmesh;

/* Parse and validate the stream header (its first h->header_bytes bytes,
 * LUMO_PMESH_HEADER_MIN ... _MAX; the first 7 say how many). Errors:
 * TRUNCATED, CORRUPT (magic, counts), VERSION, CHECKSUM, LIMIT (counts
 * above 2^28), UNSUPPORTED (quantization bits), NONFINITE (grid). */
lumo_status lumo_pmesh_read_header(const uint8_t *data, size_t size, lumo_pmesh_header *h);

/* Arena bytes lumo_pmesh_init needs for this header (LUMO_ARENA_SLACK
 * included); SIZE_MAX on overflow. */
size_t lumo_pmesh_arena_bytes(const lumo_pmesh_header *h);

/* Carve the mesh from the arena: level "nothing received" (0 vertices).
 * NOMEM when the arena is too small (arena and *pm then unchanged). */
lumo_status lumo_pmesh_init(lumo_pmesh *pm, const lumo_pmesh_header *h, lumo_arena *arena);

/* The head of the batch record starting at data (docs/progressive-mesh.md
 * §2.2): TRUNCATED when the head is cut, CORRUPT for an over-long varint
 * or an impossible size. The record itself may still be shorter than
 * head_bytes + side_bytes + draco_bytes. */
typedef struct lumo_pmesh_record_head {
    uint32_t side_bytes;   /* the split block */
    uint32_t draco_bytes;  /* the Draco point cloud */
    uint32_t crc;          /* CRC-32 of the record's index (not sent) and
                              the record without these 4 bytes */
    uint32_t head_bytes;   /* LUMO_PMESH_BATCH_HEAD_MIN ... _MAX */
} lumo_pmesh_record_head;
/* The head of the batch record at data: TRUNCATED, CORRUPT (varints,
 * sizes past the data). The CRC is read, not checked. */
lumo_status lumo_pmesh_read_record_head(const uint8_t *data, size_t size, lumo_pmesh_record_head *out);

/* Size of the batch record starting at data (head + payloads), for
 * splitting a stream; errors as lumo_pmesh_read_record_head. */
lumo_status lumo_pmesh_record_size(const uint8_t *data, size_t size, size_t *record_bytes);

/* Whether the `size` bytes at data are exactly batch record number `index`
 * of its stream (0 = the base mesh): its head, its length and its CRC,
 * which covers the index the record does not carry. For a transport that
 * checks records before handing them on. CHECKSUM when the bytes are
 * damaged or another record's; CORRUPT, TRUNCATED for a length that is
 * not the head's; errors of lumo_pmesh_read_record_head. */
lumo_status lumo_pmesh_record_check(const uint8_t *data, size_t size, uint32_t index);

/* The next batch record of a stream: the record at data[*at] (the
 * header's header_bytes in at the start), its bytes in *record and
 * *record_bytes, *at advanced past it. LUMO_ERR_RANGE at the end of the data
 * (*at == size), TRUNCATED when the record is cut, errors of
 * lumo_pmesh_read_record_head for a bad head; *at unchanged on error. This
 * is the one walk over a stream's records. */
lumo_status lumo_pmesh_next_record(const uint8_t *data, size_t size, size_t *at,
                                   const uint8_t **record, size_t *record_bytes);

/* Apply one batch record (exactly one record: `size` is its length).
 * CHECKSUM when it is damaged or not the next batch (out of order,
 * repeated: its CRC covers the index it should have); STATE when the mesh
 * is already complete; TRUNCATED, CORRUPT, RANGE, LIMIT, UNSUPPORTED,
 * NOMEM for bad records or Draco payloads. On any error the mesh is
 * unchanged. */
lumo_status lumo_pmesh_apply(lumo_pmesh *pm, const uint8_t *record, size_t size);

/* The current level. */
void lumo_pmesh_get_view(const lumo_pmesh *pm, lumo_pmesh_view *out);

/* Step back to the level with `vertices` vertices inside the last applied
 * batch (first vertex of that batch <= vertices <= vertex_count), undoing
 * its last splits from the batch's log: any level of the stream can be
 * shown, not only batch boundaries (lumo-inspect --lod N). Work is that of
 * the undone splits. Afterwards the mesh is final: lumo_pmesh_apply returns
 * STATE. RANGE when `vertices` is outside the last batch. */
lumo_status lumo_pmesh_rewind(lumo_pmesh *pm, uint32_t vertices);

/* 1 when every vertex of the stream has arrived. */
int lumo_pmesh_complete(const lumo_pmesh *pm);

/* Batch records applied so far (the next one expected has this index). */
uint32_t lumo_pmesh_batches(const lumo_pmesh *pm);

#endif /* LUMO_PMESH_H */
