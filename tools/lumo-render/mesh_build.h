/*
 * mesh_build.h — lumo-render's scene container (floats allowed here): the
 * mesh every backend draws (fixed-point lumo_raster_* structures), with its
 * lights and camera, and the generated quads and spheres the rasterizer's
 * unit tests draw. Scenes themselves come from the server's scene room
 * (default scene, assimp import, camera and light strings) through
 * scene_convert.h, or from packages (package_load.h).
 */
#ifndef LUMO_HOST_MESH_BUILD_H
#define LUMO_HOST_MESH_BUILD_H

#include <stdint.h>
#include "lumo/raster.h"

typedef struct host_mesh {
    lumo_q16_16 *pos;       /* 3 per vertex */
    lumo_q1_14  *normal;    /* 3 per vertex */
    lumo_q1_14  *albedo;    /* 3 per vertex */
    uint32_t    *tris;      /* 3 per triangle */
    uint32_t vertex_count, tri_count;
    uint32_t vertex_cap, tri_cap;
} host_mesh;

typedef struct host_scene {
    host_mesh mesh;
    lumo_raster_light lights[LUMO_MAX_LIGHTS];
    uint32_t light_count;
    lumo_raster_camera camera;
    lumo_q16_16 bmin[3], bmax[3];   /* the scene's bounds (metres): camera fits, near planes */
} host_scene;

/* Q16.16 and Q1.14 of v, rounded to nearest, saturated to the type. */
lumo_q16_16 host_q16(double v);
lumo_q1_14  host_q14(double v);

void host_mesh_free(host_mesh *m);
/* A parallelogram corner + s u + t v, tessellated nu x nv quads, normal
 * u x v, counter-clockwise seen from the side the normal points to. */
int host_mesh_add_quad(host_mesh *m, const double c[3], const double u[3], const double v[3],
                       int nu, int nv, const double albedo[3]);
/* A UV sphere of `seg` segments around and seg/2 up. */
int host_mesh_add_sphere(host_mesh *m, const double c[3], double r, int seg, int inward,
                         const double albedo[3]);
/* Append nv vertices (pos, normal: 3 per vertex; albedo 3 per vertex, or
 * NULL for HOST_DEFAULT_ALBEDO) and nt triangles whose indices are local
 * to the part (0..nv-1). 0 on success; -1 when out of memory or past
 * UINT32_MAX / 3 vertices or triangles. */
#define HOST_DEFAULT_ALBEDO ((lumo_q1_14)(3 * LUMO_Q14_ONE / 4))   /* 0.75 */
int host_mesh_append(host_mesh *m, const lumo_q16_16 *pos, const lumo_q1_14 *normal,
                     const lumo_q1_14 *albedo, uint32_t nv, const uint32_t *tris, uint32_t nt);

/* The rasterizer view of a host mesh. */
lumo_raster_mesh host_mesh_raster(const host_mesh *m);

/* Frees the mesh; lights and camera need nothing. */
void host_scene_free(host_scene *s);

#endif
