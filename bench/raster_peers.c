/*
 * bench/raster_peers.c — lumo's side of the per-vertex comparison with tgx
 * and small3dlib (docs/benchmarks.md, "Round five"; the peers' sides are
 * built outside the repository from their own sources, same scene from
 * raster_peers_mesh.h). Per frame (the function `frame`, which callgrind
 * collects with --toggle-collect=frame): clear, transform (lumo_raster_prepare),
 * draw, 640x480 XRGB8888, 32-bit depth, Gouraud from vertex radiance lit
 * once (`lit`). Host-only: floats only to load the mesh.
 *
 *   raster_peers DRAGON.ply [OUT.raw]   OUT: the three frames' colour bytes
 *   make bench-raster-peers              (bench/raster.mk) builds and counts it
 */
#include <stdint.h>

#include "lumo/raster.h"
#include "raster_peers_mesh.h"

static uint32_t color[H_W * H_H], depth[H_W * H_H];

static int32_t q(double v, double one)
{
    return (int32_t)lrint(v * one);
}

static void scene_of(const hmesh *h, lumo_q16_16 *pos, lumo_q1_14 *nrm, uint32_t *tris, lumo_raster_mesh *m,
                     lumo_raster_light *light, lumo_raster_scene *s)
{
    double ll = sqrt(h_light[0] * h_light[0] + h_light[1] * h_light[1] + h_light[2] * h_light[2]);
    int i;

    for (i = 0; i < 3 * h->nv; i++) {
        pos[i] = q(h->p[i], 65536.0);
        nrm[i] = (lumo_q1_14)q(h->n[i], 16384.0);
    }
    for (i = 0; i < 3 * h->nt; i++)
        tris[i] = h->tri[i];
    memset(m, 0, sizeof *m);
    m->pos = pos;
    m->normal = nrm;
    for (i = 0; i < 3; i++)
        m->mesh_albedo[i] = (lumo_q1_14)q(H_ALBEDO, 16384.0);
    m->tris = tris;
    m->vertex_count = (uint32_t)h->nv;
    m->tri_count = (uint32_t)h->nt;
    memset(light, 0, sizeof *light);
    light->kind = LUMO_LIGHT_DIRECTIONAL;
    for (i = 0; i < 3; i++) {
        light->dir[i] = (lumo_q1_14)q(h_light[i] / ll, 16384.0);
        light->value[i] = (lumo_uq16_16)q(M_PI, 65536.0);     /* radiance rho/pi E = rho cos */
    }
    memset(s, 0, sizeof *s);
    s->lights = light;
    s->light_count = 1;
    s->exposure = LUMO_Q16_ONE;
}

int frame(int k, const lumo_raster_scene *s, const lumo_raster_mesh *m, lumo_raster_vertex *cache,
          lumo_raster_target *t);

/* One frame: clear, transform, draw (what callgrind collects). */
__attribute__((noinline)) int frame(int k, const lumo_raster_scene *s, const lumo_raster_mesh *m,
                                    lumo_raster_vertex *cache, lumo_raster_target *t)
{
    lumo_raster_camera cam;
    lumo_raster_view v;
    double e[3];
    int i;

    h_eye(k, e);
    memset(&cam, 0, sizeof cam);
    for (i = 0; i < 3; i++)
        cam.eye[i] = q(e[i], 65536.0);
    cam.up[1] = LUMO_Q16_ONE;
    cam.fovy_deg = q(H_FOVY, 65536.0);
    cam.znear = q(0.1, 65536.0);
    if (lumo_raster_view_init(&v, &cam, H_W, H_H) || lumo_raster_clear(t, 0))
        return 1;
    if (lumo_raster_prepare(&v, s, m, cache))
        return 1;
    return lumo_raster_draw(&v, s, m, cache, t) != LUMO_OK;
}

int main(int argc, char **argv)
{
    static lumo_raster_vertex cache[1 << 17];
    hmesh h;
    lumo_raster_mesh m;
    lumo_raster_light light;
    lumo_raster_scene s;
    lumo_raster_target t;
    lumo_q16_16 *pos;
    lumo_q1_14 *nrm;
    uint32_t *tris;
    lumo_uq16_16 *lit;
    FILE *out = NULL;
    int k;
    long covered = 0, i;

    if (argc < 2)
        return fprintf(stderr, "usage: raster_peers DRAGON.ply [OUT.raw]\n"), 2;
    h_load(argv[1], &h);
    if (h.nv > (1 << 17))
        return 2;
    pos = malloc(3 * sizeof *pos * (size_t)h.nv);
    nrm = malloc(3 * sizeof *nrm * (size_t)h.nv);
    tris = malloc(3 * sizeof *tris * (size_t)h.nt);
    lit = malloc(lumo_raster_lit_bytes((uint32_t)h.nv));
    scene_of(&h, pos, nrm, tris, &m, &light, &s);
    if (lumo_raster_light_vertices(&s, &m, lit))
        return 1;
    m.lit = lit;
    if (lumo_raster_target_init(&t, H_W, H_H, 0, H_H, LUMO_PIXEL_XRGB8888, color, depth, 32))
        return 1;
    if (argc > 2 && !(out = fopen(argv[2], "wb")))
        return perror(argv[2]), 1;
    for (k = 0; k < H_FRAMES; k++) {
        if (frame(k, &s, &m, cache, &t))
            return fprintf(stderr, "frame %d failed\n", k), 1;
        for (i = 0; i < H_W * H_H; i++)
            covered += depth[i] != 0;
        if (out)
            fwrite(color, sizeof color, 1, out);
    }
    printf("lumo: %d vertices, %d triangles, %.0f covered pixels a frame\n", h.nv, h.nt,
           (double)covered / H_FRAMES);
    if (out)
        fclose(out);
    return 0;
}
