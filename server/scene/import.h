/*
 * import.h — meshes and lights from files through assimp (OBJ, PLY, OFF,
 * glTF, ...), and the scene description format (docs/scene-format.md).
 */
#ifndef SRV_IMPORT_H
#define SRV_IMPORT_H

#include <stddef.h>
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
 * albedo: NULL to use the file's materials / vertex colours. Returns 0, or
 * -1 with a one-line reason in err. */
int srv_import_file(srv_scene *s, const char *path, const srv_xform *x, const vec3 *albedo,
                    char *err, size_t errlen);

/* Read a scene description file. Returns 0, or -1 with "FILE:LINE: reason". */
int srv_scene_load(srv_scene *s, const char *path, char *err, size_t errlen);

#endif
