/*
 * mesh_build.h — desktop-side construction of rasterizer meshes and scenes
 * (floats allowed here): quads, boxes, spheres, ASCII PLY / OBJ models, the
 * built-in Cornell scene of docs/scene-format.md, camera strings. Produces
 * the fixed-point lumo_raster_* structures every backend draws.
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
} host_scene;

lumo_q16_16 host_q16(double v);
lumo_q1_14  host_q14(double v);

void host_mesh_free(host_mesh *m);
/* A parallelogram corner + s u + t v, tessellated nu x nv quads, normal
 * u x v, counter-clockwise seen from the side the normal points to. */
int host_mesh_add_quad(host_mesh *m, const double c[3], const double u[3], const double v[3],
                       int nu, int nv, const double albedo[3]);
/* An axis-aligned box (normals out, or in for a room). */
int host_mesh_add_box(host_mesh *m, const double lo[3], const double hi[3], int inward,
                      const double albedo[3]);
/* A UV sphere of `seg` segments around and seg/2 up. */
int host_mesh_add_sphere(host_mesh *m, const double c[3], double r, int seg, int inward,
                         const double albedo[3]);
/* Load an ASCII PLY (positions; faces as polygons) or OBJ (v / f lines),
 * scaled so that its longest extent is `size`, then centred on x/z and its
 * lowest point at y = y0; smooth area-weighted normals. Returns 0 on success. */
int host_mesh_load_model(host_mesh *m, const char *path, double size, double y0,
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

/* Parse "EYE:TARGET:UP:FOVY" (docs/scene-format.md). 0 on success. */
int host_camera_parse(const char *s, lumo_raster_camera *cam);
/* Parse a light "point:X,Y,Z:R,G,B" | "spot:..." | "directional:..." */
int host_light_parse(const char *s, lumo_raster_light *l);

/* The default Cornell scene: box, spot light, dragon (model path, may be
 * NULL or missing: then the sphere). 0 on success. */
int host_scene_default(host_scene *s, const char *model_path);
void host_scene_free(host_scene *s);

#endif
