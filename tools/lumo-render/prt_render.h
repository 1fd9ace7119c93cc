/*
 * prt_render.h — lumo-render --prt (docs/prt.md): the package's PRTV
 * chunks (one per mesh, lumo/prt.h) relight the held vertices every frame
 * into the mesh's per-vertex `lit` array, under distant lighting from the
 * scene's lights, the package's PRTL environment, or an equirectangular
 * PNG projected here (--env), turned about +y by --rotate degrees a frame.
 */
#ifndef LUMO_HOST_PRT_RENDER_H
#define LUMO_HOST_PRT_RENDER_H

#include <stddef.h>
#include <stdint.h>
#include "lumo/prt.h"
#include "lumo/raster_gl_prt.h"
#include "lumo/session.h"
#include "mesh_build.h"

typedef struct host_prt {
    uint8_t       *file;                   /* the package bytes (the views point into it) */
    lumo_prt       mesh[LUMO_MAX_MESHES];
    uint32_t       meshes;
    lumo_prt_light base;                   /* the unrotated lighting */
    lumo_q16_16   *frame[LUMO_MAX_MESHES];
    lumo_uq16_16  *lit;                    /* 6 per host vertex */
    double         relight_ms;             /* summed over frames */
    int            view;                   /* HOST_PRT_LIGHT, _CLUSTERS or _PASSES */
    uint32_t       count[LUMO_MAX_MESHES]; /* host vertices of each mesh, in order */
    uint8_t        has[LUMO_MAX_MESHES];   /* mesh[i] holds every cluster (else its vertices stay black) */
    lumo_gl_prt   *gl;                     /* GL backends: the multipass draws, lit stays unused */
} host_prt;

/* What --prt draws: the relit mesh, or each vertex in a false colour of its
 * cluster or of its cluster's draw pass (super-cluster, seed 003 §4.3). */
enum { HOST_PRT_LIGHT = 0, HOST_PRT_CLUSTERS = 1, HOST_PRT_PASSES = 2 };

/* Open the package's PRT for a host scene of host_vertices vertices (one
 * mesh: any level of detail; several: all vertices). env: PNG or NULL (then
 * the package's PRTL, else the scene's lights). 0, or -1 with err. */
int host_prt_open(host_prt *p, const char *path, const char *env, const host_scene *s, char *err, size_t errlen);

/* The same from a client session (lumo/session.h: lumo-client --prt) whose
 * scene s was built by host_scene_from_session: each mesh's PRT as held
 * (a mesh whose clusters have not all arrived, or vertices past the
 * records held, stay black until they do), the session's PRTL, else the
 * scene's lights. 0, or -1 with err. */
int host_prt_open_session(host_prt *p, const lumo_session *ses, const host_scene *s, char *err, size_t errlen);

/* Relight for frame i: lighting turned by i * deg about +y. 0 or -1. */
int host_prt_relight(host_prt *p, const host_scene *s, int i, double deg);

/* GL backends: draw with the thesis's multipass (lumo/raster_gl_prt.h)
 * in the renderer's context g; host_prt_relight then only fills the
 * per-cluster tables. 0, or -1 with err. */
int host_prt_gl_open(host_prt *p, struct lumo_gl *g, const host_scene *s, const lumo_raster_mesh *m, char *err,
                     size_t errlen);
/* Draw the frame host_prt_relight prepared. 0 or -1. */
int host_prt_gl_draw(host_prt *p, const lumo_raster_camera *cam, const lumo_raster_scene *rs, uint8_t *rgb);

void host_prt_close(host_prt *p);

#endif
