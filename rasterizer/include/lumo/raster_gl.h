/*
 * lumo/raster_gl.h — the GL backends of the rasterizer (desktop: floats, heap).
 *
 * The same frame description as lumo/raster.h (camera, scene, mesh) drawn
 * with OpenGL 3.3 core or OpenGL ES 3.0 shaders — the paper's GPU path
 * (seed 000, §3.3): the IVG uploaded as twelve 3D textures (colour as
 * GL_RGB9_E5, direction as RGB8, one pair per hemisphere), hardware
 * trilinear filtering, the directional interpolation and the direct lights
 * in GLSL, the shading model of docs/rasterizer.md.
 *
 * Two ways to a context: OSMesa (off-screen Mesa) and EGL (surfaceless or
 * pbuffer). Both hand GL entry points to the shared renderer through a
 * get-proc-address function, so one program can hold both backends.
 */
#ifndef LUMO_RASTER_GL_H
#define LUMO_RASTER_GL_H

#include <stddef.h>
#include <stdint.h>
#include "lumo/ivg.h"
#include "lumo/raster.h"

typedef void (*lumo_gl_proc)(void);
typedef lumo_gl_proc (*lumo_gl_getproc_fn)(const char *name);

typedef struct lumo_gl lumo_gl;

/* The shared renderer, in the context current on this thread. gles: the
 * context is OpenGL ES 3 (else desktop 3.3 core or compatibility). NULL on
 * failure with a message in err. */
lumo_gl *lumo_gl_create(lumo_gl_getproc_fn getproc, int gles, int width, int height,
                        char *err, size_t errlen);
/* Upload the mesh (replaces the previous one). 0 on success. */
int lumo_gl_set_mesh(lumo_gl *g, const lumo_raster_mesh *m);
/* Upload the IVG as 3D textures (NULL removes it). 0 on success. */
int lumo_gl_set_ivg(lumo_gl *g, const lumo_ivg *ivg);
/* Draw one frame and read it back: rgb gets width*height*3 bytes, top row
 * first. The scene's indirect term is used when s->indirect is set and an
 * IVG was uploaded. A light whose `shadow` is set (its views:
 * lumo_raster_shadow_views or _init; the depth pointer is not read) is
 * shadowed by the backend's own depth maps, drawn from those views again
 * only when they change or a new mesh is uploaded (docs/rasterizer.md,
 * "GL shadow maps"; faces * size^2 * 4 bytes of texture). 0 on success. */
int lumo_gl_draw(lumo_gl *g, const lumo_raster_camera *cam, const lumo_raster_scene *s,
                 uint8_t *rgb);
/* Renderer name reported by the driver (e.g. "llvmpipe ..."). */
const char *lumo_gl_renderer(const lumo_gl *g);
void lumo_gl_destroy(lumo_gl *g);

/* ---- OSMesa ---- */
typedef struct lumo_osmesa lumo_osmesa;
/* A 3.3 core context (falls back to the default one) rendering width x
 * height; the driver follows GALLIUM_DRIVER (llvmpipe, softpipe). */
lumo_osmesa *lumo_osmesa_open(int width, int height, char *err, size_t errlen);
lumo_gl *lumo_osmesa_gl(lumo_osmesa *o);
void lumo_osmesa_close(lumo_osmesa *o);

/* ---- EGL ---- */
typedef struct lumo_egl lumo_egl;
/* Surfaceless EGL (EGL_MESA_platform_surfaceless), else the default display
 * with a pbuffer; desktop GL when available, else GLES 3. */
lumo_egl *lumo_egl_open(int width, int height, char *err, size_t errlen);
lumo_gl *lumo_egl_gl(lumo_egl *e);
/* How the context was made, e.g. "surfaceless, OpenGL core 3.3". */
const char *lumo_egl_describe(const lumo_egl *e);
void lumo_egl_close(lumo_egl *e);

#endif
