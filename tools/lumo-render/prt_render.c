/* prt_render.c — see prt_render.h. Desktop side: the lighting vector is
 * built here from doubles (the environment's projection is the server's,
 * server/prt/prt_pack.c); everything per frame goes through the client's
 * fixed-point lumo/prt.h, as on a device. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "lumo/package.h"
#include "lumo/wire.h"
#include "lumo_host/file_io.h"
#include "lumo_host/png_io.h"
#include "prt/prt_pack.h"
#include "prt_render.h"

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

/* The scene's lights through the client's own conversion
 * (lumo_prt_light_add_pkg): distant lights as seen from the scene's centre. */
static int lights_vector(host_prt *p, const host_scene *s)
{
    lumo_q16_16 c[3];
    for (int a = 0; a < 3; a++)
        c[a] = (lumo_q16_16)(((int64_t)s->bmin[a] + s->bmax[a]) / 2);
    for (uint32_t i = 0; i < s->light_count; i++) {
        const lumo_raster_light *rl = &s->lights[i];
        lumo_pkg_light pl;
        memset(&pl, 0, sizeof pl);
        pl.kind = rl->kind, pl.cos_half = rl->cos_cutoff;
        memcpy(pl.pos, rl->pos, sizeof pl.pos);
        memcpy(pl.dir, rl->dir, sizeof pl.dir);
        memcpy(pl.power, rl->value, sizeof pl.power);
        lumo_status st = lumo_prt_light_add_pkg(&p->base, &pl, c);
        if (st && st != LUMO_ERR_RANGE)   /* a light at the centre itself lights nothing here */
            return -1;
    }
    return 0;
}

static int env_vector(host_prt *p, const char *env, char *err, size_t errlen)
{
    uint8_t *rgb;
    int w, h;
    double c[3 * LUMO_PRT_MAX_COEFFS];
    if (host_png_read_rgb8(env, &rgb, &w, &h)) {
        snprintf(err, errlen, "%s: cannot read the environment map (an 8-bit PNG of at most 2^26 pixels)", env);
        return -1;
    }
    float *f = malloc(3u * (size_t)w * (size_t)h * sizeof *f);
    for (size_t i = 0; f && i < 3u * (size_t)w * (size_t)h; i++)
        f[i] = rgb[i] / 255.0f;
    free(rgb);
    if (!f)
        return -1;
    srv_prt_env_project(f, w, h, p->base.order, c);
    free(f);
    for (int ch = 0; ch < 3; ch++)
        for (int i = 0; i < p->base.order * p->base.order; i++)
            p->base.c[ch][i] = host_q16(c[ch * p->base.order * p->base.order + i]);
    return 0;
}

/* The package's PRTL (lumo_prt_light_decode), when its order is the
 * transfer's. 1 when used. */
static int prtl_vector(host_prt *p, const lumo_package *pkg)
{
    const uint8_t *d;
    uint32_t n;
    lumo_prt_light l;
    if (lumo_package_find(pkg, SRV_PRT_PKG_PRTL, 0, &d, &n) || lumo_prt_light_decode(d, n, &l) ||
        l.order != p->base.order)
        return 0;
    p->base = l;
    return 1;
}

static int find_meshes(host_prt *p, const lumo_package *pkg, uint32_t host_vertices, char *err, size_t errlen)
{
    const uint8_t *d;
    uint32_t n, total = 0;
    lumo_status st;
    for (p->meshes = 0; p->meshes < LUMO_MAX_MESHES && !lumo_package_find(pkg, SRV_PRT_PKG_PRTV, p->meshes, &d, &n);
         p->meshes++) {
        if ((st = lumo_prt_parse(&p->mesh[p->meshes], d, n))) {
            snprintf(err, errlen, "PRTV chunk %u: %s", p->meshes, lumo_strerror(st));
            return -1;
        }
        total += p->mesh[p->meshes].vertices_held;
        if (!(p->frame[p->meshes] = malloc(lumo_prt_frame_entries(&p->mesh[p->meshes]) * sizeof(lumo_q16_16))))
            return -1;
    }
    if (!p->meshes) {
        snprintf(err, errlen, "no PRTV chunk (bake with lumo-bake --prt)");
        return -1;
    }
    if (p->meshes == 1 ? host_vertices > total : host_vertices != total) {
        snprintf(err, errlen, "the PRT covers %u vertices, the scene holds %u (several meshes: --lod all only)", total,
                 host_vertices);
        return -1;
    }
    for (uint32_t i = 1; i < p->meshes; i++)
        if (p->mesh[i].order != p->mesh[0].order) {
            snprintf(err, errlen, "PRTV chunks of different SH orders");
            return -1;
        }
    return 0;
}

int host_prt_open(host_prt *p, const char *path, const char *env, const host_scene *s, char *err, size_t errlen)
{
    size_t size = 0;
    lumo_package pkg;
    memset(p, 0, sizeof *p);
    p->file = host_read_file(path, &size);
    if (!p->file || lumo_package_open(&pkg, p->file, size)) {
        snprintf(err, errlen, "%s: cannot read the package", path);
        return -1;
    }
    if (find_meshes(p, &pkg, s->mesh.vertex_count, err, errlen))
        return -1;
    for (uint32_t m = 0; m < p->meshes; m++)   /* one mesh: any level of detail; several: all vertices */
        p->count[m] = p->meshes == 1 ? s->mesh.vertex_count : p->mesh[m].vertices_held, p->has[m] = 1;
    lumo_prt_light_clear(&p->base, p->mesh[0].order);
    if (!(p->lit = calloc(6u * (s->mesh.vertex_count ? s->mesh.vertex_count : 1), sizeof *p->lit)))
        return -1;
    if (env)
        return env_vector(p, env, err, errlen);
    if (prtl_vector(p, &pkg))
        return 0;
    return lights_vector(p, s);
}

int host_prt_open_session(host_prt *p, const lumo_session *ses, const host_scene *s, char *err, size_t errlen)
{
    const lumo_pkg_info *info = lumo_session_info(ses);
    uint32_t total = 0;
    memset(p, 0, sizeof *p);
    for (p->meshes = 0; info && p->meshes < info->mesh_count; p->meshes++) {
        uint32_t m = p->meshes;
        lumo_pmesh_view v;
        lumo_status st = lumo_session_prt(ses, m, &p->mesh[m]);
        p->count[m] = lumo_session_mesh(ses, m, &v) == LUMO_OK ? v.vertex_count : 0;
        total += p->count[m];
        if (st == LUMO_ERR_RANGE) {
            snprintf(err, errlen, "mesh %u has no PRT (a package baked with lumo-bake --prt, streamed with --prt)", m);
            return -1;
        }
        p->has[m] = st == LUMO_OK;
        if (p->has[m] && !(p->frame[m] = malloc(lumo_prt_frame_entries(&p->mesh[m]) * sizeof(lumo_q16_16))))
            return -1;
    }
    if (!p->meshes || total != s->mesh.vertex_count) {
        snprintf(err, errlen, "the session's meshes hold %u vertices, the scene %u", total, s->mesh.vertex_count);
        return -1;
    }
    if (!(p->lit = calloc(6u * (total ? total : 1), sizeof *p->lit)))
        return -1;
    lumo_prt_light l;
    if (lumo_session_prt_light(ses, &l) == LUMO_OK) {
        p->base = l;
        return 0;
    }
    for (uint32_t m = 0; m < p->meshes; m++)
        if (p->has[m])
            return lumo_prt_light_clear(&p->base, p->mesh[m].order) ? -1 : lights_vector(p, s);
    return 0;   /* no cluster has arrived anywhere: every vertex black */
}

/* Host vertices mesh m's PRT relights; the first `held` of them have
 * their vertex records (the rest stay black). */
static uint32_t mesh_count(const host_prt *p, const host_scene *s, uint32_t m)
{
    (void)s;
    return p->count[m];
}

static uint32_t mesh_held(const host_prt *p, uint32_t m)
{
    if (!p->has[m])
        return 0;
    return p->count[m] < p->mesh[m].vertices_held ? p->count[m] : p->mesh[m].vertices_held;
}

/* A false colour for id, bright enough to tell neighbours apart. */
static void id_colour(uint32_t id, lumo_uq16_16 *rgb)
{
    uint32_t h = id * 2654435761u;
    for (int c = 0; c < 3; c++)
        rgb[c] = (lumo_uq16_16)(((h >> (8 * c)) & 0xFFu) * 96u + 2048u);
}

static void false_colour(host_prt *p, const host_scene *s)
{
    uint32_t first = 0;
    for (uint32_t m = 0; m < p->meshes; m++) {
        const lumo_prt *c = &p->mesh[m];
        uint32_t n = mesh_count(p, s, m);
        for (uint32_t v = 0; v < mesh_held(p, m); v++) {
            uint32_t k = lumo_wire_le16(c->vertex_data + (size_t)v * lumo_prt_vertex_bytes(c->components));
            id_colour(p->view == HOST_PRT_PASSES ? lumo_prt_pass(c, k) + (m << 16) : k + (m << 16),
                      p->lit + 6u * (first + v));
        }
        first += n;
    }
}

int host_prt_gl_open(host_prt *p, lumo_gl *g, const host_scene *s, const lumo_raster_mesh *m, char *err,
                     size_t errlen)
{
    uint32_t counts[LUMO_MAX_MESHES];
    if (p->view != HOST_PRT_LIGHT) {
        snprintf(err, errlen, "--prt-view draws with the soft backend only");
        return -1;
    }
    for (uint32_t i = 0; i < p->meshes; i++) {
        counts[i] = mesh_count(p, s, i);
        if (mesh_held(p, i) < counts[i]) {
            snprintf(err, errlen, "mesh %u: the GL multipass needs every vertex's PRT record", i);
            return -1;
        }
    }
    p->gl = lumo_gl_prt_create(g, m, p->mesh, counts, p->meshes, err, errlen);
    return p->gl ? 0 : -1;
}

int host_prt_gl_draw(host_prt *p, const lumo_raster_camera *cam, const lumo_raster_scene *rs, uint8_t *rgb)
{
    return lumo_gl_prt_draw(p->gl, cam, rs, (const lumo_q16_16 *const *)p->frame, rgb);
}

int host_prt_relight(host_prt *p, const host_scene *s, int i, double deg)
{
    if (p->view != HOST_PRT_LIGHT) {
        false_colour(p, s);
        return 0;
    }
    double a = i * deg * M_PI / 180.0, t0 = now_ms();
    lumo_q1_14 one[2] = {LUMO_Q14_ONE, 0}, b[2] = {host_q14(cos(a)), host_q14(sin(a))};
    lumo_prt_light l;
    uint32_t first = 0;
    if (!p->base.order)   /* nothing has arrived to relight with */
        return 0;
    if (lumo_prt_light_rotate(&p->base, one, b, one, &l))
        return -1;
    for (uint32_t m = 0; m < p->meshes; m++) {
        uint32_t n = mesh_count(p, s, m), held = mesh_held(p, m);
        if (p->has[m] && lumo_prt_frame(&p->mesh[m], &l, p->frame[m]))
            return -1;
        if (!p->gl && held &&
            lumo_prt_shade(&p->mesh[m], p->frame[m], s->mesh.albedo + 3u * first, 0, held, p->lit + 6u * first))
            return -1;
        if (!p->gl)   /* vertices whose records have not arrived: black */
            memset(p->lit + 6u * ((size_t)first + held), 0, 6u * (size_t)(n - held) * sizeof *p->lit);
        first += n;
    }
    p->relight_ms += now_ms() - t0;
    return 0;
}

void host_prt_close(host_prt *p)
{
    lumo_gl_prt_destroy(p->gl);
    for (uint32_t m = 0; m < p->meshes; m++)
        free(p->frame[m]);
    free(p->lit);
    free(p->file);
    memset(p, 0, sizeof *p);
}
