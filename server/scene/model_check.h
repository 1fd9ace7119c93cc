/*
 * model_check.h — lumo's own checks of a model file, before and after
 * assimp reads it (server/scene/import.c; lumo-bake, lumo-pm, lumo-render).
 *
 * Every byte of a model is hostile. assimp trusts a file's declared counts
 * (an OFF or PLY header declaring 10^9 faces allocates for them before it
 * reads one), remaps an OFF face index past the vertex count to the last
 * vertex, and crashes in post-processing on a binary PLY face list whose
 * count runs past its data. So before assimp sees a file:
 *
 *   - it exists, is a regular file, is not empty and not larger than
 *     SRV_MODEL_MAX_BYTES;
 *   - OBJ, PLY (ASCII and binary) and OFF are read through once by lumo:
 *     every element a header declares must be backed by at least its
 *     smallest encoding in the file (so assimp's allocations stay
 *     proportional to the file's size, whatever the header says), every
 *     face has 3..SRV_MODEL_MAX_FACE_VERTS vertices and every index names
 *     a vertex that exists;
 *   - STL (stl_check.c): a binary STL's size is exactly 84 + 50 x its
 *     declared triangle count; an ASCII one is text of 3-vertex facets;
 *   - glTF 2.0, .gltf and .glb (gltf_check.c): the container, every buffer
 *     backed by bytes, every bufferView and accessor inside what holds it,
 *     the node hierarchy trees, and what assimp expands (accessors once
 *     per primitive and node instance) at most SRV_GLTF_MAX_EXPANDED;
 *   - every other format (Collada, 3DS, FBX, X, Blender, ... which assimp
 *     also reads, trusting the counts they declare) is refused, the
 *     message listing what lumo reads. docs/scene-format.md states the
 *     memory bound of each.
 * What assimp makes of an accepted file is validated again
 * (aiProcess_ValidateDataStructure, srv_model_check_positions).
 *
 * After import every position is finite and within SRV_MODEL_MAX_COORD.
 * Messages name the file, the element (line, face, vertex, header field)
 * and why.
 */
#ifndef SRV_MODEL_CHECK_H
#define SRV_MODEL_CHECK_H

#include <stddef.h>
#include <stdint.h>
#include "lumo/status.h"

/* Largest model file read: 1 GiB. */
#define SRV_MODEL_MAX_BYTES ((uint64_t)1 << 30)
/* Largest |coordinate| of a vertex, metres: beyond it single precision
 * keeps under 0.06 m of resolution and the client's Q16.16 cannot hold it
 * (lumo/fixed.h: ±32768 m) once a scene is scaled. */
#define SRV_MODEL_MAX_COORD 1.0e6f
/* Most vertices of one polygon in OBJ, PLY or OFF. */
#define SRV_MODEL_MAX_FACE_VERTS 1024u
/* Largest glTF JSON (a .gltf file, a .glb's JSON chunk): jansson holds
 * about 25 bytes per byte of a JSON of small numbers, so 16 MiB parse in
 * ~400 MB; a real scene's JSON is kilobytes, its data in buffers. */
#define SRV_GLTF_MAX_JSON ((uint64_t)16 << 20)
/* Most bytes of accessor data assimp expands from one glTF: each accessor
 * once per primitive and node instance using it, plus animation, skin and
 * image data (256 MiB: about 10 M triangles with normals). */
#define SRV_GLTF_MAX_EXPANDED ((uint64_t)256 << 20)

/* The formats lumo reads; SRV_MODEL_OTHER is refused. */
typedef enum srv_model_format {
    SRV_MODEL_OTHER = 0, SRV_MODEL_OBJ, SRV_MODEL_PLY, SRV_MODEL_OFF, SRV_MODEL_STL, SRV_MODEL_GLTF, SRV_MODEL_GLB
} srv_model_format;

/* What the message of a refused format lists. */
#define SRV_MODEL_FORMATS "OBJ, PLY, OFF, STL and glTF 2.0 (.gltf, .glb)"

/* The format a file name says (extension, case-insensitive), else what the
 * first bytes say ("ply\n", "OFF", "glTF"), else SRV_MODEL_OTHER. */
srv_model_format srv_model_format_of(const char *name, const uint8_t *data, size_t size);

/* Check a model's bytes as the file `name` (used for its extension and in
 * messages). LUMO_OK, or with "NAME: where: why" in err: LUMO_ERR_CORRUPT
 * (malformed header or statement, not text, a face with too few or too
 * many vertices), LUMO_ERR_TRUNCATED (data ends before what the header
 * declares), LUMO_ERR_RANGE (an index past the vertex count, a glTF
 * accessor past its bufferView), LUMO_ERR_LIMIT (past SRV_GLTF_MAX_*),
 * LUMO_ERR_IO (a glTF buffer file missing or not regular, resolved beside
 * `name`), LUMO_ERR_UNSUPPORTED (binary OFF, a PLY property type assimp
 * does not read, glTF 1, sparse accessors, SRV_MODEL_OTHER). OBJ, PLY,
 * OFF and STL: reads each byte once, allocates nothing; glTF: parses the
 * JSON (at most SRV_GLTF_MAX_JSON) into memory. */
lumo_status srv_model_check_bytes(const char *name, const uint8_t *data, size_t size, srv_model_format fmt,
                                  char *err, size_t errlen);

/* The file at path: LUMO_ERR_IO (no such file, not a regular file, cannot
 * read), LUMO_ERR_CORRUPT (empty), LUMO_ERR_LIMIT (larger than
 * SRV_MODEL_MAX_BYTES), then srv_model_check_bytes.
 * *fmt gets the format. Holds the file in memory while it checks it. */
lumo_status srv_model_check_file(const char *path, srv_model_format *fmt, char *err, size_t errlen);

/* Positions of mesh `mesh` after import (3 floats per vertex): LUMO_OK, or
 * LUMO_ERR_NONFINITE (NaN, infinity) / LUMO_ERR_RANGE (|c| >
 * SRV_MODEL_MAX_COORD) naming the vertex and the value. */
lumo_status srv_model_check_positions(const char *name, unsigned mesh, const float *xyz, uint32_t nverts,
                                      char *err, size_t errlen);

#endif
