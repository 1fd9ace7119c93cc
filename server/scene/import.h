/*
 * import.h — meshes and lights from files through assimp (OBJ, PLY, OFF,
 * glTF, ...), and the scene description format (docs/scene-format.md).
 */
#ifndef LUMO_SERVER_IMPORT_H
#define LUMO_SERVER_IMPORT_H

#include <stddef.h>
#include "scene/scene.h"

/* Scale, then rotate about an axis, then translate. */
typedef struct lumo_xform {
    vec3  scale;
    vec3  axis;
    float angle_deg;
    vec3  translate;
} lumo_xform;

lumo_xform lumo_xform_identity(void);
vec3 lumo_xform_apply(const lumo_xform *x, vec3 p);

/* Load every mesh (and light) of a file into the scene, transformed.
 * albedo: NULL to use the file's materials / vertex colours. Returns 0, or
 * -1 with a one-line reason in err. */
int lumo_import_file(lumo_scene *s, const char *path, const lumo_xform *x, const vec3 *albedo,
                     char *err, size_t errlen);

/* Read a scene description file. Returns 0, or -1 with "FILE:LINE: reason". */
int lumo_scene_load(lumo_scene *s, const char *path, char *err, size_t errlen);

#endif
