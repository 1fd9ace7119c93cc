/*
 * import.h — meshes and lights from files through assimp (OBJ, PLY, OFF,
 * glTF, ...), and the scene description format (docs/scene-format.md).
 */
#ifndef SRV_IMPORT_H
#define SRV_IMPORT_H

#include <stddef.h>
#include <stdint.h>
#include "lumo/status.h"
#include "scene/scene.h"

/* Scale, then rotate about an axis, then translate. */
typedef struct srv_xform {
    vec3  scale;
    vec3  axis;
    float angle_deg;
    vec3  translate;
} srv_xform;

srv_xform srv_xform_identity(void);
vec3 srv_xform_apply(const srv_xform *x, vec3 p);

/* Load every mesh (and light) of a file into the scene, transformed.
 * albedo: NULL to use the file's materials / vertex colours. The file goes
 * through lumo's own checks first (scene/model_check.h: declared counts
 * against the file's size, face lists, indices, coordinates), then assimp
 * with aiProcess_ValidateDataStructure, then every mesh it returns is
 * checked again. LUMO_OK, or with a one-line reason naming the file, the
 * element and why in err: srv_model_check_file's statuses (IO, CORRUPT,
 * TRUNCATED, RANGE, NONFINITE, LIMIT, UNSUPPORTED), LUMO_ERR_UNSUPPORTED
 * (a format assimp does not read), LUMO_ERR_CORRUPT (assimp cannot read
 * it, or it holds no triangle), LUMO_ERR_NOMEM. */
lumo_status srv_import_file(srv_scene *s, const char *path, const srv_xform *x, const vec3 *albedo,
                            char *err, size_t errlen);

/* Sphere segments at most, and the triangles every sphere of one
 * description may generate together (2^22: twice the largest stock model;
 * a line of text cannot justify gigabytes of mesh). */
#define SRV_SCENE_MAX_SEGMENTS   1024
#define SRV_SCENE_MAX_SHAPE_TRIS ((uint64_t)1 << 22)

/* Longest line and largest file of a scene description. */
#define SRV_SCENE_MAX_LINE  2046
#define SRV_SCENE_MAX_BYTES ((uint64_t)1 << 20)

/* Read a scene description file. LUMO_OK, or with "FILE:LINE: reason" in
 * err: LUMO_ERR_IO (cannot open, not a regular file), LUMO_ERR_LIMIT (a
 * line too long, more than 16 words, a file over 1 MiB), LUMO_ERR_CORRUPT
 * (a malformed statement, a NUL byte), LUMO_ERR_RANGE (sphere segments
 * outside [8, 1024]), LUMO_ERR_LIMIT (spheres past SRV_SCENE_MAX_SHAPE_TRIS),
 * or the status of a mesh's srv_import_file / of memory. */
lumo_status srv_scene_load(srv_scene *s, const char *path, char *err, size_t errlen);

/* The same from len bytes of text (not NUL-terminated; name for messages,
 * dir for the relative paths of mesh statements). */
lumo_status srv_scene_parse(srv_scene *s, const char *name, const char *dir, const char *text, size_t len,
                            char *err, size_t errlen);

#endif
