/*
 * lumo/package.h — reading a .lumo package (docs/package-format.md): a
 * versioned container of checksummed chunks (scene info, meshes, IVG). The
 * payloads' decoders are in lumo/scene.h, lumo/pmesh.h and lumo/ivg.h; the
 * getters here find a chunk and hand it to them.
 *
 * The package is read in place: lumo_package_open() validates the header,
 * the chunk table and every chunk's CRC-32 over the caller's buffer, which
 * must then stay alive and unchanged while the lumo_package is used. No
 * memory is allocated; getters convert the file's binary32 fields to lumo
 * fixed point with integer code only (lumo_f32bits_to_fixed).
 *
 * Every byte is hostile: each function bounds-checks what it reads, returns
 * a lumo_status, and writes its outputs only on success.
 */
#ifndef LUMO_PACKAGE_H
#define LUMO_PACKAGE_H

#include <stddef.h>
#include <stdint.h>
#include "lumo/config.h"
#include "lumo/fixed.h"
#include "lumo/ivg.h"
#include "lumo/scene.h"
#include "lumo/status.h"

/* Version 2: the IVG bundles hold their records in the stratified streaming
 * order, described by an IVGS chunk; an ORDR chunk recommends how to
 * interleave geometry and lighting. Version-1 packages are refused
 * (LUMO_ERR_VERSION): re-bake them. */
#define LUMO_PKG_VERSION_MAJOR 2u
#define LUMO_PKG_VERSION_MINOR 0u   /* additions a version-2 reader may ignore */
#define LUMO_PKG_HEADER_SIZE   24u  /* bytes of the file header */
#define LUMO_PKG_ENTRY_SIZE    16u  /* bytes of one chunk-table entry */
#define LUMO_PKG_MAX_CHUNKS    ((uint32_t)LUMO_MAX_CHUNKS)   /* chunks a package may have (lumo/config.h) */

/* Chunk types: four ASCII characters, first character in the lowest byte. */
#define LUMO_PKG_FOURCC(a, b, c, d) \
    ((uint32_t)(a) | ((uint32_t)(b) << 8) | ((uint32_t)(c) << 16) | ((uint32_t)(d) << 24))
#define LUMO_PKG_INFO LUMO_PKG_FOURCC('I', 'N', 'F', 'O')  /* scene info, exactly one */
#define LUMO_PKG_MESH LUMO_PKG_FOURCC('M', 'E', 'S', 'H')  /* raw mesh, one per mesh */
#define LUMO_PKG_PMSH LUMO_PKG_FOURCC('P', 'M', 'S', 'H')  /* progressive mesh stream, one per mesh */
#define LUMO_PKG_IVGD LUMO_PKG_FOURCC('I', 'V', 'G', 'D')  /* IVG grid descriptor */
#define LUMO_PKG_IVGQ LUMO_PKG_FOURCC('I', 'V', 'G', 'Q')  /* IVG bundle, quantized form */
#define LUMO_PKG_IVGF LUMO_PKG_FOURCC('I', 'V', 'G', 'F')  /* IVG bundle, binary32 form */
#define LUMO_PKG_IVGS LUMO_PKG_FOURCC('I', 'V', 'G', 'S')  /* IVG streaming order (lumo_ivg_order) */
#define LUMO_PKG_ORDR LUMO_PKG_FOURCC('O', 'R', 'D', 'R')  /* geometry/lighting interleaving (lumo_scene_order) */

/* One entry of the chunk table. */
typedef struct lumo_pkg_chunk {
    uint32_t type, offset, length, crc;   /* fourcc; payload's byte offset and length in the file; its CRC-32 */
} lumo_pkg_chunk;

/* An opened package: a view of the caller's buffer. */
typedef struct lumo_package {
    const uint8_t *data;     /* the caller's buffer (not owned) */
    size_t         size;     /* its bytes */
    uint16_t       version_major, version_minor;   /* the file's format version */
    uint32_t       chunk_count;   /* entries in the chunk table */
} lumo_package;

/* Validate and open. Fails with TRUNCATED, CORRUPT (bad magic, layout, a
 * second INFO, IVGD, IVGQ, IVGF, IVGS or ORDR chunk),
 * VERSION (other major), CHECKSUM, LIMIT (too many chunks); *pkg is written
 * only on success. Work is linear in size. */
lumo_status lumo_package_open(lumo_package *pkg, const uint8_t *data, size_t size);

/* The chunk table's entries (count of them, LUMO_PKG_ENTRY_SIZE bytes
 * each) hold INFO, IVGD, IVGQ, IVGF, IVGS and ORDR at most once: LUMO_OK,
 * or LUMO_ERR_CORRUPT with the doubled type in *twice (may be NULL).
 * lumo_package_open makes this check; a reader that fetches the table
 * alone (HTTP ranges) makes it here. */
lumo_status lumo_package_table_once(const uint8_t *table, uint32_t count, uint32_t *twice);

/* The version a file claims (bytes 4..7), without validating anything
 * else: what a tool prints when lumo_package_open says VERSION. TRUNCATED
 * below 8 bytes, CORRUPT without the magic. */
lumo_status lumo_package_peek_version(const uint8_t *data, size_t size, uint16_t *major, uint16_t *minor);

/* Table entry `index` (0-based). */
lumo_status lumo_package_chunk(const lumo_package *pkg, uint32_t index, lumo_pkg_chunk *out);

/* The nth (0-based) chunk of a type: payload pointer into the buffer and its
 * length. LUMO_ERR_RANGE when there is no such chunk. */
lumo_status lumo_package_find(const lumo_package *pkg, uint32_t type, uint32_t nth,
                              const uint8_t **payload, uint32_t *len);

/* The INFO chunk, light `index` of it, the counts of MESH chunk `index`:
 * errors of lumo_package_find and of the payload's decoder (lumo/scene.h). */
lumo_status lumo_package_info(const lumo_package *pkg, lumo_pkg_info *out);
lumo_status lumo_package_light(const lumo_package *pkg, uint32_t index, lumo_pkg_light *out);
lumo_status lumo_package_mesh_info(const lumo_package *pkg, uint32_t index, lumo_pkg_mesh_info *out);

/* Read mesh `index` into caller arrays sized from lumo_package_mesh_info:
 * pos 3*nverts (Q16.16 metres), nrm 3*nverts (Q1.14 unit, may be NULL),
 * albedo 3*nverts (Q1.14 in [0,1], may be NULL), tris 3*ntris (may be
 * NULL). The whole chunk is validated (finite values, ranges, indices <
 * nverts) before any output is written. */
lumo_status lumo_package_mesh_read(const lumo_package *pkg, uint32_t index, lumo_q16_16 *pos,
                                   lumo_q1_14 *nrm, lumo_q1_14 *albedo, uint32_t *tris);

/* The IVG descriptor stored in the package (dims, bounds in Q16.16). */
lumo_status lumo_package_ivg_desc(const lumo_package *pkg, lumo_ivg_desc *out);

/* Apply the package's IVG bundle of the given form to a grid created from
 * lumo_package_ivg_desc (through lumo_ivg_apply_bundle: all or nothing). */
lumo_status lumo_package_load_ivg(const lumo_package *pkg, lumo_ivg *g, lumo_ivg_form form,
                                  uint32_t *applied);

/* The IVG streaming order (IVGS), decoded against the package's IVG
 * descriptor and checked against both bundles present (lumo_ivg_order_decode,
 * lumo_ivg_order_check_bundle): a server can then send any rounds as one
 * byte range of a bundle. RANGE when the package has no IVGS. */
lumo_status lumo_package_ivg_order(const lumo_package *pkg, lumo_ivg_order *out);

/* The recommended interleaving (ORDR), its meshes checked against the INFO
 * mesh count. RANGE when the package has none. */
lumo_status lumo_package_order(const lumo_package *pkg, lumo_scene_order *out);

#endif /* LUMO_PACKAGE_H */
