/*
 * lumo/ivg.h — the client half of the Irradiance Vector Grid (seed 000, §3-4.1).
 *
 * An IVG is an axis-aligned uniform grid of dims[0] x dims[1] x dims[2]
 * vertices over the box [bmin, bmax]. Vertex (i, j, k) has the linear index
 * i + dims[0] * (j + dims[1] * k). Each vertex stores six entries, one per
 * hemisphere delta in the order +x, -x, +y, -y, +z, -z (lumo_ivg_axis). An
 * entry is the paper's compressed 3x3 matrix M = (I^R | I^G | I^B): a unit
 * direction d and a colour c with M n = c (d . n) for n = delta (§3.3).
 *
 * The grid holds what was received plus what push-pull filled in, every
 * entry packed as 7 bytes in the quantized wire form (3 x int8 direction,
 * RGB9E5 colour): received quantized entries exactly as they came, binary32
 * ones and push-pull's results rounded to that form. A bitmap says which
 * vertices were received. Received values are never changed by
 * push-pull. A vertex may also be marked "solid" (inside geometry: the
 * server has no irradiance for it); it counts as not received and push-pull
 * fills it like any hole. docs/ivg-format.md gives the wire forms byte by byte.
 *
 * Bundle wire format (all multi-byte fields little-endian):
 *
 *   offset size  field
 *   0      4     magic 'I' 'V' 'G' 'B' (0x49 0x56 0x47 0x42)
 *   4      1     version, LUMO_IVG_BUNDLE_VERSION (1)
 *   5      1     form: 0 = LUMO_IVG_FORM_FLOAT, 1 = LUMO_IVG_FORM_QUANTIZED
 *   6      6     dims[0], dims[1], dims[2] as u16: must equal the grid's
 *   12     4     record count, u32
 *   16     ...   records, back to back; the bundle ends after the last one
 *
 *   record: u32 word: bits 0-30 vertex index i + dims[0] * (j + dims[1] * k),
 *           bit 31 LUMO_IVG_SOLID_BIT. A solid record ends there; any other
 *           record carries 6 entries in the order +x, -x, +y, -y, +z, -z.
 *   quantized entry (7 bytes): d as 3 x int8 (value q / 127, q = -128 is
 *           corrupt), then c as u32 RGB9E5 (R bits 0-8, G 9-17, B 18-26,
 *           exponent 27-31; GL_EXT_texture_shared_exponent).
 *   binary32 entry (24 bytes): d x, y, z then c r, g, b as IEEE-754 binary32.
 *
 * Rules (each breach rejects the whole bundle, the grid stays as it was):
 *   fewer than 16 bytes, or records running past the end -> LUMO_ERR_TRUNCATED
 *   wrong magic, bytes after the last record, a vertex twice in one bundle,
 *   more records than the grid has vertices, q = -128     -> LUMO_ERR_CORRUPT
 *   version other than 1                                  -> LUMO_ERR_VERSION
 *   form other than 0 or 1                                -> LUMO_ERR_UNSUPPORTED
 *   dims differ from the grid's, vertex index >= vertex count, colour < 0 or
 *   > 65535, d neither zero nor of length within 1/16 of 1 -> LUMO_ERR_RANGE
 *   NaN or infinity anywhere in a binary32 entry          -> LUMO_ERR_NONFINITE
 * A record for a vertex received earlier replaces it (lighting updates);
 * a solid record clears the vertex's data and its received flag.
 *
 * Memory: everything lives in the caller's arena; lumo_ivg_memory_size()
 * tells how many bytes before anything is allocated. No float, no heap.
 */
#ifndef LUMO_IVG_H
#define LUMO_IVG_H

#include <stddef.h>
#include <stdint.h>
#include "lumo/arena.h"
#include "lumo/fixed.h"
#include "lumo/status.h"

/* The six hemispheres of a grid vertex: +x, -x, +y, -y, +z, -z. */
typedef enum lumo_ivg_axis {
    LUMO_IVG_PX = 0, LUMO_IVG_NX, LUMO_IVG_PY, LUMO_IVG_NY, LUMO_IVG_PZ, LUMO_IVG_NZ,
    LUMO_IVG_AXES
} lumo_ivg_axis;

/* Limits that bound every computation on hostile descriptors. */
#define LUMO_IVG_MIN_DIM 2
#define LUMO_IVG_MAX_DIM 256   /* vertices per axis, at most */

/* One hemisphere's compressed irradiance: colour c (UQ16.16, W/m^2 per
 * channel) and direction d (Q1.14, unit length or zero). */
typedef struct lumo_ivg_entry {
    lumo_uq16_16 c[3];       /* colour, W/m^2 per channel */
    lumo_q1_14   d[3];       /* direction, unit or zero */
    int16_t      reserved;   /* keeps the entry at 20 bytes, always 0 */
} lumo_ivg_entry;

/* Grid shape and placement; bounds in scene units as Q16.16. */
typedef struct lumo_ivg_desc {
    uint16_t    dims[3];     /* vertices per axis, each in [2, 256] */
    lumo_q16_16 bmin[3];     /* lower corner */
    lumo_q16_16 bmax[3];     /* bmax > bmin on every axis */
} lumo_ivg_desc;

typedef struct lumo_ivg lumo_ivg;   /* opaque; lives in the arena */

/* Wire forms of a sample bundle (docs/ivg-format.md). */
typedef enum lumo_ivg_form {
    LUMO_IVG_FORM_FLOAT = 0,       /* d: 3 x binary32, c: 3 x binary32 */
    LUMO_IVG_FORM_QUANTIZED = 1    /* d: 3 x int8 (q/127), c: RGB9E5 */
} lumo_ivg_form;

#define LUMO_IVG_BUNDLE_VERSION  1u   /* the bundle version read */
#define LUMO_IVG_BUNDLE_HEADER    16u   /* bytes before the first record */
#define LUMO_IVG_SOLID_BIT        0x80000000u   /* index word: the vertex is solid */
#define LUMO_IVG_QUANT_ENTRY      7u    /* bytes per quantized entry */
#define LUMO_IVG_FLOAT_ENTRY      24u   /* bytes per binary32 entry */
/* Bytes of one record with data: index word + 6 entries. */
#define LUMO_IVG_QUANT_RECORD     (4u + LUMO_IVG_AXES * LUMO_IVG_QUANT_ENTRY)
#define LUMO_IVG_FLOAT_RECORD     (4u + LUMO_IVG_AXES * LUMO_IVG_FLOAT_ENTRY)   /* binary32 form */

/* Push-pull options (seed 000, §4.1). */
#define LUMO_IVG_SMOOTH 1u   /* pyramidal filter after each push step */

/* Arena bytes lumo_ivg_create() needs for this descriptor (including the
 * push-pull pyramid and its smoothing scratch), or 0 when the descriptor is
 * invalid; SIZE_MAX when the size does not fit a size_t (no arena can hold
 * it). The caller adds LUMO_ARENA_SLACK if its buffer may be unaligned. */
size_t lumo_ivg_memory_size(const lumo_ivg_desc *desc);

/* Create an empty grid (nothing received) in the arena. On error the arena
 * is left as it was. */
lumo_status lumo_ivg_create(lumo_ivg **out, lumo_arena *arena, const lumo_ivg_desc *desc);

/* The grid's descriptor, its vertex count, how many vertices were
 * received, and whether `vertex` was (1) or not (0). */
const lumo_ivg_desc *lumo_ivg_get_desc(const lumo_ivg *g);
uint32_t lumo_ivg_vertex_count(const lumo_ivg *g);
uint32_t lumo_ivg_received_count(const lumo_ivg *g);
int lumo_ivg_is_received(const lumo_ivg *g, uint32_t vertex);
/* Solid vertices (inside geometry, marked by the server): not received. */
uint32_t lumo_ivg_solid_count(const lumo_ivg *g);
int lumo_ivg_is_solid(const lumo_ivg *g, uint32_t vertex);

/* The entry stored for (vertex, axis) — received, filled by push-pull, or
 * zero — unpacked into *out (the grid keeps entries packed in the quantized
 * wire form, docs/ivg-format.md §2.5 and §6). LUMO_ERR_ARG when out of range
 * or a pointer is NULL (*out untouched). */
lumo_status lumo_ivg_entry_get(const lumo_ivg *g, uint32_t vertex, lumo_ivg_axis axis, lumo_ivg_entry *out);

/* Decode one bundle of samples (header + records, docs/ivg-format.md) and
 * store them as received. The whole bundle is validated before anything is
 * stored: on any error the grid is unchanged. *applied (may be NULL) gets
 * the number of records stored. */
lumo_status lumo_ivg_apply_bundle(lumo_ivg *g, const uint8_t *buf, size_t len, uint32_t *applied);

/* Decode a run of `count` records without the bundle header — the records
 * of some rounds of a package's bundle, as the server streams them
 * (docs/protocol.md, DATA lighting) — in the given form and store them as
 * received. Same rules and the same loop as lumo_ivg_apply_bundle: the
 * whole run is validated first (UNSUPPORTED for an unknown form, CORRUPT
 * for more records than grid vertices or bytes after the last record,
 * TRUNCATED, RANGE, NONFINITE as for a bundle), and on any error the grid
 * is unchanged. `records` may be NULL when len is 0. *applied (may be NULL)
 * gets the number of records stored. */
lumo_status lumo_ivg_apply_records(lumo_ivg *g, lumo_ivg_form form, uint32_t count, const uint8_t *records,
                                   size_t len, uint32_t *applied);

/* ---- the stratified streaming order (package chunk IVGS) -----------------
 * A package's bundles hold their records in the order of seed 000 §4.1
 * (docs/protocol.md §4, exact draw in docs/package-format.md "IVGS"): round
 * 0 the eight corners, then rounds of at most one vertex per slice along
 * the grid's longest axis. The IVGS payload says where each round starts:
 *
 *   offset size  field
 *   0      8     seed of the draw, u64 (two u32, low first)
 *   8      1     axis of the slices: 0 x, 1 y, 2 z (the longest; x, then y on ties)
 *   9      3     reserved, 0
 *   12     4     slices S = dims[axis]
 *   16     4     rounds R >= 1
 *   20     4(R+1)  first record of round r (entry R: the record count)
 *   ...    4(R+1)  byte offset of round r in the IVGQ payload (entry 0: 16,
 *                  after the bundle header; entry R: the payload's length)
 *   ...    4(R+1)  the same in the IVGF payload
 *
 * Rounds r .. r+k-1 of a form are payload bytes [offset(r), offset(r+k)): a
 * run of whole records for lumo_ivg_apply_records. */
typedef struct lumo_ivg_order {
    uint64_t       seed;      /* the order's random seed */
    uint32_t       axis;      /* 0 x, 1 y, 2 z */
    uint32_t       slices;    /* slices along axis */
    uint32_t       rounds;    /* R: round 0 is the corners */
    uint32_t       records;   /* records of the whole order (grid vertices) */
    const uint8_t *table;     /* the payload's three arrays (not owned) */
} lumo_ivg_order;

#define LUMO_IVG_ORDER_HEADER 20u   /* bytes of an IVGS payload's head */
/* Most rounds a grid can have: the corners, then one per vertex of an
 * interior slice of 256 x 256. */
#define LUMO_IVG_ORDER_MAX_ROUNDS (1u + LUMO_IVG_MAX_DIM * LUMO_IVG_MAX_DIM)

/* The axis the order slices along: the one with the most vertices, x on a
 * tie with y or z, then y. */
uint32_t lumo_ivg_order_axis(const uint16_t dims[3]);

/* Decode and check an IVGS payload; *out keeps a pointer into p (which must
 * outlive it) and is written only on success. Checks: the length is that of
 * R rounds (TRUNCATED / CORRUPT); axis < 3 (CORRUPT), S in [2, 256] and R in
 * [1, LUMO_IVG_ORDER_MAX_ROUNDS] (RANGE); round 0 holds 8 records and every
 * later round 1 .. S; both offset arrays start at 16 and each round's bytes
 * are those of its records (4 per solid record, 46 or 148 per data record,
 * the same data records in both forms) (CORRUPT). With a descriptor (may
 * be NULL) also: axis, S and every round's record count are those of its
 * grid (RANGE). Work is linear in R. */
lumo_status lumo_ivg_order_decode(const uint8_t *p, size_t len, const lumo_ivg_desc *desc, lumo_ivg_order *out);

/* Where round r starts: its first record, and its byte offset in the form's
 * bundle payload. r = rounds (or more) gives the end: the record count, the
 * payload length. */
uint32_t lumo_ivg_order_first(const lumo_ivg_order *o, uint32_t r);
uint32_t lumo_ivg_order_offset(const lumo_ivg_order *o, lumo_ivg_form form, uint32_t r);

/* Whole rounds among the first `records` records of the order. */
uint32_t lumo_ivg_order_rounds_in(const lumo_ivg_order *o, uint32_t records);

/* Check that a bundle is the one the order describes: its form, its record
 * count, its length, and a record boundary at every round's offset (the
 * index words are walked; the entries are left to lumo_ivg_apply_*).
 * CORRUPT or TRUNCATED otherwise. Linear in the record count. */
lumo_status lumo_ivg_order_check_bundle(const lumo_ivg_order *o, lumo_ivg_form form, const uint8_t *bundle,
                                        size_t len);

/* Fill every not-received vertex from the received ones by 3D push-pull;
 * received vertices keep their exact values. flags: LUMO_IVG_SMOOTH.
 * Only received values are inputs, so a re-run after more bundles arrived
 * recomputes every filled vertex; with nothing received all stay zero.
 * Work is bounded by a constant times the vertex count; stack use about
 * 620 bytes on the Cortex-M3.
 * LUMO_ERR_ARG for a NULL grid or unknown flags. */
lumo_status lumo_ivg_pushpull(lumo_ivg *g, unsigned flags);

/* Irradiance towards normal n at point p (§3.2): trilinear interpolation of
 * the three hemispheres picked by the signs of n (n_a >= 0 picks +a), with
 * d and c interpolated separately (as two hardware-filtered 3D textures
 * would be), I_n = sum I_a n_a^2, and out[k] = max(0, I_n^k . n) in W/m^2
 * (UQ16.16, saturated). p in scene units (Q16.16, clamped to the grid box),
 * n unit length in Q1.14 (a longer n gives clamped but defined results). */
void lumo_ivg_irradiance(const lumo_ivg *g, const lumo_q16_16 p[3], const lumo_q1_14 n[3],
                         lumo_uq16_16 out[3]);

/* A sampler: lumo_ivg_irradiance with a memo of the last cell it opened.
 * Neighbouring samples of a surface (the pixels of a span) mostly fall in
 * one cell; the memo keeps that cell's eight corners of every hemisphere
 * used so far unpacked (colour UQ16.16, direction in q units), so such a
 * sample skips finding and opening the corners' packed entries and only
 * weighs them. Results are bit-identical to lumo_ivg_irradiance.
 * Caller-owned (908 bytes on a Cortex-M3, 912 on x86-64), one per thread;
 * the grid is borrowed.
 * The memo is of the grid's values when they were opened: call
 * lumo_ivg_sampler_init again after any lumo_ivg_apply_* or
 * lumo_ivg_pushpull on the grid. g may be NULL (all samples are zero). */
typedef struct lumo_ivg_sampler {
    const lumo_ivg *grid;      /* sampled grid, borrowed; NULL: every sample is zero */
    uint32_t cell;             /* first vertex of the opened cell; UINT32_MAX: none */
    uint32_t opened;           /* bit h set: hemisphere h (lumo_ivg_axis) opened */
    uint32_t corner_off[8];    /* byte offsets of a cell's corners (x + 2y + 4z) */
    uint32_t c[6][3][8];       /* colour, UQ16.16: hemisphere, channel, corner */
    int16_t  q[6][3][8];       /* direction in q units (value q / 127) */
} lumo_ivg_sampler;

/* Set s up for grid g (may be NULL) with an empty memo: before the first
 * sample, and again after g changed. Never fails; touches only *s. */
void lumo_ivg_sampler_init(lumo_ivg_sampler *s, const lumo_ivg *g);

/* lumo_ivg_irradiance(s->grid, p, n, out), through the memo. */
void lumo_ivg_sampler_irradiance(lumo_ivg_sampler *s, const lumo_q16_16 p[3], const lumo_q1_14 n[3],
                                 lumo_uq16_16 out[3]);

/* Reflected indirect radiance L_r = rho/pi (I_n . n) per channel (eq. 2):
 * albedo in Q1.14 ([0, 1]), result in UQ16.16 (W/m^2/sr). */
void lumo_ivg_radiance(const lumo_ivg *g, const lumo_q16_16 p[3], const lumo_q1_14 n[3],
                       const lumo_q1_14 albedo[3], lumo_uq16_16 out[3]);

#endif /* LUMO_IVG_H */
