/*
 * lumo/draco.h — allocation-free, float-free decoder of Draco bitstreams
 * (meshes v2.2, point clouds v2.3, as written by libdraco 1.5.5).
 *
 * The decoder produces the *portable* attribute values: the quantized
 * integers libdraco holds before its final dequantization, in libdraco's
 * point order and face order, byte for byte. Dequantization parameters are
 * given both as the raw IEEE-754 bit patterns from the stream and in fixed
 * point; lumo_draco_dequantize() turns a portable integer into fixed point.
 *
 * Usage:
 *   lumo_draco_need need;
 *   lumo_draco_arena_need(data, size, &need);  // scan: the arena, before decoding
 *   arena with need.bytes free bytes (+ LUMO_ARENA_SLACK if the buffer may
 *   be unaligned); need.exact: exactly what the decode takes, else a bound
 *   lumo_draco_decode(data, size, &arena, &mesh);
 * (lumo_draco_peek + lumo_draco_arena_bound: a cruder bound from the header
 * counts alone.)
 *
 * Memory: every output array is carved from the caller's arena; temporary
 * work memory is taken from the top of the arena's free space and given back
 * before returning, so after a successful decode the arena holds only the
 * outputs (mesh.arena_bytes of them). On error the arena is unchanged.
 * The input buffer is only read; it need not outlive the decode.
 */
#ifndef LUMO_DRACO_H
#define LUMO_DRACO_H

#include <stddef.h>
#include <stdint.h>
#include "lumo/arena.h"
#include "lumo/status.h"

/* Geometry kinds (Draco header byte). */
#define LUMO_DRACO_POINT_CLOUD 0u
#define LUMO_DRACO_MESH        1u

/* Encoder methods: point clouds 0 sequential / 1 KD-tree; meshes 0
 * sequential / 1 EdgeBreaker. */
#define LUMO_DRACO_METHOD_SEQUENTIAL 0u
#define LUMO_DRACO_METHOD_KD_TREE    1u
#define LUMO_DRACO_METHOD_EDGEBREAKER 1u

/* Attribute semantics (Draco GeometryAttribute::Type). */
#define LUMO_DRACO_POSITION  0u
#define LUMO_DRACO_NORMAL    1u
#define LUMO_DRACO_COLOR     2u
#define LUMO_DRACO_TEX_COORD 3u
#define LUMO_DRACO_GENERIC   4u

/* Original data types (Draco DataType). */
#define LUMO_DRACO_DT_INT8    1u
#define LUMO_DRACO_DT_UINT8   2u
#define LUMO_DRACO_DT_INT16   3u
#define LUMO_DRACO_DT_UINT16  4u
#define LUMO_DRACO_DT_INT32   5u
#define LUMO_DRACO_DT_UINT32  6u
#define LUMO_DRACO_DT_FLOAT32 9u

/* How the portable integers relate to the original values. */
#define LUMO_DRACO_XFORM_NONE        0u  /* integers are the values */
#define LUMO_DRACO_XFORM_QUANTIZED   1u  /* min + q * range / (2^bits - 1) */
#define LUMO_DRACO_XFORM_OCTAHEDRAL  2u  /* 2 components, octahedral normal */

/* Largest component count lumo decodes per attribute. */
#define LUMO_DRACO_MAX_COMPONENTS 16u
/* Largest number of attributes per geometry. */
#define LUMO_DRACO_MAX_ATTRIBUTES 32u

/* Decoding modes found, for diagnostics (`lumo-draco-decode --info`). */
typedef struct lumo_draco_attr_modes {
    uint8_t decoder_id;       /* attributes decoder the attribute belongs to */
    uint8_t traversal;        /* 0 depth-first, 1 prediction degree */
    uint8_t vertex_attribute; /* 1 per-vertex, 0 per-corner (seams) */
    uint8_t seq_type;         /* 0 generic 1 integer 2 quantization 3 normals */
    int8_t  prediction;       /* -2 none, 0 delta, 1 parallelogram, 2 multi,
                                 4 constrained multi, 5 tex-coords portable,
                                 6 geometric normal */
    int8_t  transform;        /* -1 none, 1 wrap, 3 octahedron canonicalized */
    uint8_t compressed;       /* 1 entropy coded, 0 raw bytes */
    uint8_t symbol_coding;    /* 0 tagged, 1 raw rANS (when compressed) */
} lumo_draco_attr_modes;

/* One decoded attribute. Values are `num_values` entries of
 * `num_portable` int32 components each; point p uses entry
 * point_to_value[p] (or entry p when point_to_value is NULL). */
typedef struct lumo_draco_attribute {
    uint8_t  type;            /* LUMO_DRACO_POSITION ... GENERIC */
    uint8_t  data_type;       /* original data type (LUMO_DRACO_DT_*) */
    uint8_t  num_components;  /* components of the original attribute */
    uint8_t  num_portable;    /* components of the portable values */
    uint8_t  normalized;      /* Draco's normalized flag */
    uint8_t  xform;           /* LUMO_DRACO_XFORM_* */
    uint8_t  quant_bits;      /* quantization / octahedral bits, else 0 */
    uint8_t  frac_bits;       /* fractional bits of min_fixed/range_fixed */
    uint32_t unique_id;       /* Draco's attribute id */
    uint32_t num_values;      /* distinct values decoded */
    int32_t  *values;         /* num_values * num_portable portable ints */
    uint32_t *point_to_value; /* num_points entries, or NULL (identity) */
    /* Quantization (xform == QUANTIZED): float32 bit patterns as stored,
     * and the same in fixed point with frac_bits fractional bits. */
    uint32_t *min_bits;       /* num_components */
    uint32_t range_bits;      /* the quantization range, float32 bits */
    int32_t  *min_fixed;      /* num_components */
    int32_t  range_fixed;     /* the range in fixed point (frac_bits) */
    lumo_draco_attr_modes modes;   /* how the values were coded */
} lumo_draco_attribute;

/* What lumo_draco_peek reads from a stream's header, without decoding. */
typedef struct lumo_draco_info {
    uint8_t  version_major, version_minor;   /* the stream's Draco version */
    uint8_t  geometry;        /* LUMO_DRACO_POINT_CLOUD or LUMO_DRACO_MESH */
    uint8_t  method;          /* LUMO_DRACO_METHOD_* */
    uint16_t flags;           /* bit 15: metadata present */
    uint8_t  connectivity;    /* meshes: sequential 0 compressed / 1 raw;
                                 EdgeBreaker 0 standard / 2 valence */
    uint32_t num_faces;       /* exact */
    uint32_t num_points_max;  /* upper bound on decoded points */
    size_t   input_bytes;     /* size of the stream peeked at */
} lumo_draco_info;

/* A decoded stream: its faces and attributes, arrays in the arena. */
typedef struct lumo_draco_mesh {
    uint8_t  geometry, method, connectivity;   /* as in lumo_draco_info */
    uint32_t num_points;      /* points (vertices) decoded */
    uint32_t num_faces;       /* triangles; 0 for a point cloud */
    uint32_t *faces;          /* 3 * num_faces point indices, libdraco order */
    uint32_t num_attributes;  /* entries at attributes */
    lumo_draco_attribute *attributes;  /* in libdraco attribute-id order */
    size_t   arena_bytes;     /* arena bytes the outputs occupy */
    size_t   work_bytes;      /* arena_bytes + work_bytes is the exact arena
                                 size this decode needs (peak use) */
} lumo_draco_mesh;

/* Parse the header, skip metadata, read the geometry counts; nothing is
 * decoded. On error *info is unchanged. */
lumo_status lumo_draco_peek(const uint8_t *data, size_t size, lumo_draco_info *info);

/* Upper bound of the free arena bytes (lumo_arena_remaining) a decode
 * needs, from the counts of lumo_draco_peek, for a geometry whose
 * attributes hold at most `max_components` portable components per point
 * in total (e.g. 3 position + 2 normal + 2 uv + 4 colour = 11). Includes
 * LUMO_ARENA_SLACK. SIZE_MAX on overflow. Loose for EdgeBreaker meshes
 * with attribute seams (points may reach 3 per face); the exact need of a
 * decode is reported in lumo_draco_mesh. Formula: docs/draco-decoder.md. */
size_t lumo_draco_arena_bound(const lumo_draco_info *info, unsigned max_components);

/* The arena a decode of one stream needs, from lumo_draco_arena_need. */
typedef struct lumo_draco_need {
    size_t  bytes;      /* free arena bytes (lumo_arena_remaining) that every
                           successful decode of the stream fits in: an arena
                           of exactly this many free bytes decodes it */
    size_t  bytes_min;  /* no successful decode needs fewer */
    uint8_t exact;      /* 1: bytes == bytes_min, the exact need
                           (mesh.arena_bytes + mesh.work_bytes) */
} lumo_draco_need;

/* Scan a stream and compute the arena its decode needs, before decoding:
 * every header that decides memory is read (connectivity, attribute
 * decoders, prediction schemes, symbol-stream tables) and payloads are
 * skipped by their coded sizes; no memory beyond a fixed stack depth
 * (about 3 KB on the Cortex-M3), work linear in the input. Exact for sequential meshes,
 * point clouds and EdgeBreaker meshes whose peak does not depend on the
 * connectivity; otherwise a bound (`exact` = 0). Multiples of 8; add
 * LUMO_ARENA_SLACK when the arena's buffer may be unaligned. On error
 * *need is unchanged (the error a decode would also return, in most
 * cases). Formula: docs/draco-decoder.md, "Memory before decoding". */
lumo_status lumo_draco_arena_need(const uint8_t *data, size_t size, lumo_draco_need *need);

/* Decode a whole stream. On success *out describes arrays in `arena`.
 * On error the arena and *out are unchanged. */
lumo_status lumo_draco_decode(const uint8_t *data, size_t size, lumo_arena *arena,
                              lumo_draco_mesh *out);

/* Decoding modes, for the _ex calls (the plain calls: 0). Same output in
 * every mode; the arena need of a mode comes from lumo_draco_arena_need_ex
 * with the same flags. */
#define LUMO_DRACO_LEAN 1u  /* EdgeBreaker meshes: the opposite corners are
                               24-bit ids, read as decoded for positions
                               predicted by parallelograms (-cl 3..8), else
                               packed into the spare bits of the output face
                               array; arena ~1.2x the output instead of
                               1.4-1.7x, for 1.1x (-cl 7) to 1.25-1.35x
                               (-cl 10) the instructions (docs/draco-
                               decoder.md, "The lean mode"); where it packs,
                               need.bytes assumes the worst packing and
                               bytes_min is close to the exact need.
                               EdgeBreaker meshes up to 2 796 202 faces. */
/* A value of LUMO_DRACO_MODES: both modes compiled in (the default). */
#define LUMO_DRACO_MODES_ALL 0
/* A value of LUMO_DRACO_MODES: only the lean mode's code is compiled in;
 * every decode and arena need is the lean mode's, whatever the flags (the
 * output is the same; the EdgeBreaker face limit is the lean one). For a
 * board whose code space is short: the walks instantiated per opposite
 * store exist once (docs/porting.md §3, docs/draco-decoder.md "Round
 * five"). */
#define LUMO_DRACO_MODES_LEAN 1
#ifndef LUMO_DRACO_MODES
/* Which modes a build of the decoder holds, set on the compiler's command
 * line for the SDK's sources (-DLUMO_DRACO_MODES=LUMO_DRACO_MODES_LEAN);
 * the application needs nothing. */
#define LUMO_DRACO_MODES LUMO_DRACO_MODES_ALL
#endif
/* lumo_draco_decode and lumo_draco_arena_need in the mode `flags` (above). */
lumo_status lumo_draco_decode_ex(const uint8_t *data, size_t size, unsigned flags,
                                 lumo_arena *arena, lumo_draco_mesh *out);
lumo_status lumo_draco_arena_need_ex(const uint8_t *data, size_t size, unsigned flags,
                                     lumo_draco_need *need);

/* Original value of component `comp` of a QUANTIZED portable value `q`, in
 * fixed point with attr->frac_bits fractional bits (saturated to int32).
 * Other transforms return q unchanged. */
int32_t lumo_draco_dequantize(const lumo_draco_attribute *attr, unsigned comp, int32_t q);

/* Portable value of point `point`, component `comp` (bounds unchecked). */
static inline int32_t lumo_draco_value(const lumo_draco_attribute *a, uint32_t point,
                                       unsigned comp)
{
    uint32_t e = a->point_to_value ? a->point_to_value[point] : point;
    return a->values[(size_t)e * a->num_portable + comp];
}

#endif /* LUMO_DRACO_H */
