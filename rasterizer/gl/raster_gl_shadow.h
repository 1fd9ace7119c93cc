/*
 * raster_gl_shadow.h — the GL backends' shadow maps (private to
 * rasterizer/gl; docs/rasterizer.md "Shadows", "GL backends").
 *
 * The maps are drawn from the very views the soft rasterizer draws its own
 * from (lumo_raster_light.shadow: lumo_raster_shadow_init or
 * lumo_raster_shadow_views, so the faces, fields of view, near planes and
 * the directional light's eye are the soft path's), into one
 * GL_DEPTH_COMPONENT32F 2D array texture, one layer per face, holding the
 * view depth w / far (linear). The lookup in GLSL (raster_gl_shaders.h,
 * shadow_visibility) makes the soft path's choices: normal offset 1.5 texel
 * footprints, depth bias one footprint, 2x2 PCF with 1/16-texel weights.
 * Memory (driver's): faces * size^2 * 4 bytes.
 */
#ifndef LUMO_RASTER_GL_SHADOW_H
#define LUMO_RASTER_GL_SHADOW_H

#include <stddef.h>
#include <GL/glcorearb.h>
#include "lumo/raster_gl.h"

typedef struct lumo_gl_shadow lumo_gl_shadow;

/* The shadow maps of a context; depth_prog draws depth only (attribute 0:
 * positions; uniforms u_smvp, u_sinvfar) and becomes the module's. NULL with
 * a message in err on failure. */
lumo_gl_shadow *lumo_gl_shadow_create(lumo_gl_getproc_fn getproc, GLuint depth_prog, char *err,
                                      size_t errlen);
/* Draw the maps of the scene's lights that carry one when their views
 * differ from those drawn, or mesh_gen changed (a new mesh): the maps
 * depend on the light and the geometry only. vao holds the mesh (attribute
 * 0, index_count uint32 indices); scene_radius bounds |p| (the far plane).
 * Leaves the framebuffer binding and the viewport changed. 0 on success. */
int lumo_gl_shadow_update(lumo_gl_shadow *sh, const lumo_raster_scene *s, GLuint vao,
                          GLsizei index_count, float scene_radius, unsigned mesh_gen);
/* Set program p's shadow uniforms for the scene's lights and bind the maps
 * to texture unit `unit` (p's u_smap must name that unit). */
void lumo_gl_shadow_bind(lumo_gl_shadow *sh, GLuint p, const lumo_raster_scene *s, int unit);
/* Bytes of the maps drawn last (faces * size^2 * 4). */
size_t lumo_gl_shadow_bytes(const lumo_gl_shadow *sh);
void lumo_gl_shadow_destroy(lumo_gl_shadow *sh);

/* Column-major clip matrix of a view: rows right, up, forward (unit), eye,
 * cot(fovy/2), aspect width/height, near and far planes (gluLookAt x
 * gluPerspective; raster_gl.c's cameras and the light's faces). */
void lumo_gl_frustum(const double rows[3][3], const double eye[3], double cot_half, double aspect,
                     double znear, double zfar, float out[16]);

#endif
