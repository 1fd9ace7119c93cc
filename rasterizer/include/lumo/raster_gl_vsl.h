/*
 * lumo/raster_gl_vsl.h — seed 004's renderer (§0.6, §0.7.3) on the desktop
 * GL backends (OSMesa, EGL; desktop code: floats and heap). For each frame:
 * (i) the geometry into a G-buffer (world position, normal, albedo as
 * float render targets), (ii) a shadow map per light and the direct light
 * of point and spot lights from it, (iii) the indirect light of every VSL
 * accumulated with additive blending. No VSL visibility (§0.6: "we have
 * decided not to take VSLs shadows into account").
 *
 * A VSL of reflected flux Phi_s (W per channel) lights a point x of albedo
 * rho and normal n with
 *   L = rho/pi * Phi_s cos(theta) cos(theta') / (pi r^2 + dS')
 * — the paper's L = Phi_s rho/pi cos cos' / (pi r^2) with the disc term dS'
 * the engine uses (server/vsl/vsl_light.h), which keeps the element finite
 * as r -> 0; beyond the cut-off radius r_c = sqrt(max Phi_s / (pi eps))
 * (§0.7.3, eps = 1e-6) a VSL adds nothing.
 *
 * Three ways to the indirect term (lumo_gl_vsl_mode), the same light:
 *  - DEFERRED (§0.7.3): each VSL drawn as a sphere of radius r_c (its back
 *    faces, depth-clamped), shading only the G-buffer pixels it covers;
 *  - WHOLE_SCENE (Tables 2-3, the second value): the whole geometry drawn
 *    again for each VSL, shaded from its own attributes where the depth
 *    equals the G-buffer's;
 *  - ONE_PASS: one full-screen pass evaluating every VSL at every pixel
 *    (the VSLs in a float texture).
 *
 * Units: positions in metres, light intensity W/sr, VSL flux W, output
 * linear radiance W/(m^2 sr) per channel.
 */
#ifndef LUMO_RASTER_GL_VSL_H
#define LUMO_RASTER_GL_VSL_H

#include <stddef.h>
#include <stdint.h>
#include "lumo/raster_gl.h"

/* Lights with shadow maps in one frame: a spot takes one layer, a point
 * light six (a cube of 90-degree frusta). */
#define LUMO_GL_VSL_MAX_LIGHTS 4
#define LUMO_GL_VSL_SHADOW_SIZE 1024

typedef struct lumo_gl_vsl lumo_gl_vsl;

typedef struct lumo_gl_vsl_light {
    float pos[3];
    float dir[3];        /* spot axis, unit */
    float cos_half;      /* spot: cos(half angle), a hard cone as the path tracer's */
    float intensity[3];  /* W/sr per channel (power / 4 pi) */
    int   spot;          /* 0: point light */
} lumo_gl_vsl_light;

typedef struct lumo_gl_vsl_point {
    float pos[3], normal[3];   /* world; the normal is the lit side's */
    float flux[3];             /* reflected flux Phi_s, W per channel */
    float area;                /* dS', m^2 */
} lumo_gl_vsl_point;

typedef enum lumo_gl_vsl_mode {
    LUMO_GL_VSL_DEFERRED = 0,
    LUMO_GL_VSL_WHOLE_SCENE = 1,
    LUMO_GL_VSL_ONE_PASS = 2
} lumo_gl_vsl_mode;

typedef struct lumo_gl_vsl_frame {
    float eye[3], target[3], up[3], fovy_deg;   /* docs/scene-format.md "Camera" */
    const lumo_gl_vsl_light *lights;            /* borrowed for the call */
    uint32_t nlights;                           /* <= LUMO_GL_VSL_MAX_LIGHTS */
    const lumo_gl_vsl_point *vsls;              /* borrowed for the call */
    uint32_t nvsls;
    float eps;                                  /* cut-off, 1e-6 (§0.7.3); <= 0: none */
    lumo_gl_vsl_mode mode;
    int direct, indirect;                       /* which terms to draw */
} lumo_gl_vsl_frame;

/* A renderer of width x height in the desktop GL 3.3 core context current
 * on this thread (entry points through getproc). NULL with a reason in err
 * (no float render target, a shader that does not compile, ...). */
lumo_gl_vsl *lumo_gl_vsl_create(lumo_gl_getproc_fn getproc, int width, int height, char *err, size_t errlen);

/* The geometry (copied to the GL): nverts positions, unit normals and
 * linear albedos (3 floats each), ntris triangles of vertex indices.
 * 0, or -1 on a GL error or an index past nverts. */
int lumo_gl_vsl_set_geometry(lumo_gl_vsl *r, const float *pos, const float *normal, const float *albedo,
                             uint32_t nverts, const uint32_t *tris, uint32_t ntris);

/* Draw one frame and wait for the GL to finish it. 0, or -1 (too many
 * lights, a GL error). */
int lumo_gl_vsl_draw(lumo_gl_vsl *r, const lumo_gl_vsl_frame *f);

/* The last frame's linear radiance, width*height*3 floats, top row first. */
int lumo_gl_vsl_read(lumo_gl_vsl *r, float *rgb);

/* The last frame's G-buffer: world positions (w = 1 where a surface is,
 * 0 elsewhere), normals (facing the eye) and albedos, width*height*4
 * floats each, top row first (any may be NULL). */
int lumo_gl_vsl_read_surface(lumo_gl_vsl *r, float *pos4, float *nrm4, float *alb4);

/* "renderer; GL version; G-buffer format". */
const char *lumo_gl_vsl_describe(const lumo_gl_vsl *r);

void lumo_gl_vsl_destroy(lumo_gl_vsl *r);

#endif
