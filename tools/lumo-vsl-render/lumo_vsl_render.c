/*
 * lumo_vsl_render.c — seed 004's renderer driven by the dynamic engine
 * (docs/dynamic.md §8): the scene's motion run step by step, the engine
 * settled at each time asked, then the frame drawn on a desktop GL backend
 * by lumo/raster_gl_vsl.h — shadow-mapped direct light plus the VSLs in
 * deferred shading (§0.6, §0.7.3) — and written as PNG; with --reference,
 * compared with the path tracer of the same moment and with the IVG the
 * clients render from. --bench measures Tables 2-3 (ms per frame against
 * the VSL count, deferred against the whole scene per VSL).
 *
 *   lumo-vsl-render SCENE|--default DRAGON [--out DIR] [--times T,..]
 *       [--size WxH] [--vsl N] [--pool N] [--batch N] [--eps E]
 *       [--camera C] [--exposure X] [--backend osmesa|egl]
 *       [--reference SPP] [--bench] [--counts N,..] [--frames N]
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <EGL/egl.h>
#include <GL/osmesa.h>
#include "bake/reference.h"
#include "bake/rt.h"
#include "lumo/raster_gl_vsl.h"
#include "lumo_host/image_diff.h"
#include "lumo_host/png_io.h"
#include "lumo_host/tonemap.h"
#include "scene/import.h"
#include "scene/shapes.h"
#include "vsl/vsl_engine.h"

typedef struct options {
    const char *scene, *dragon, *out, *camera, *backend;
    int w, h, ref_spp, bench, frames, ntimes, ncounts;
    double times[16];
    size_t counts[8];
    float eps, exposure;
    srv_vsl_engine_opts eng;
} options;

typedef struct view {
    lumo_osmesa *osm;
    lumo_egl *egl;
    lumo_gl_vsl *r;
} view;

/* Geometry of the posed scene: positions, smooth normals, albedo. */
typedef struct geometry {
    float *pos, *nrm, *alb;
    uint32_t *tris;
    uint32_t nverts, ntris;
} geometry;

static const char *const pic_names[3] = {"vsl", "vsl-whole", "vsl-onepass"};

static int fail(const char *m)
{
    fprintf(stderr, "lumo-vsl-render: error: %s\n", m);
    return 1;
}

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

/* ---- options ------------------------------------------------------------------- */

static int parse_list(const char *t, double *out, int max)
{
    int n = 0;
    char buf[512], *save = NULL;
    snprintf(buf, sizeof buf, "%s", t);
    for (char *w = strtok_r(buf, ",", &save); w && n < max; w = strtok_r(NULL, ",", &save)) {
        char *end;
        out[n++] = strtod(w, &end);
        if (*end || !isfinite(out[n - 1]) || out[n - 1] < 0)
            return -1;
    }
    return n;
}

static int parse_option(options *o, const char *k, const char *v)
{
    double l[8];
    int n;
    if (!strcmp(k, "--out")) o->out = v;
    else if (!strcmp(k, "--default")) o->dragon = v;
    else if (!strcmp(k, "--camera")) o->camera = v;
    else if (!strcmp(k, "--backend")) o->backend = v;
    else if (!strcmp(k, "--times")) return (o->ntimes = parse_list(v, o->times, 16)) > 0 ? 0 : -1;
    else if (!strcmp(k, "--size")) return sscanf(v, "%dx%d", &o->w, &o->h) == 2 && o->w > 0 && o->h > 0 &&
                                               o->w <= 4096 && o->h <= 4096 ? 0 : -1;
    else if (!strcmp(k, "--vsl")) o->eng.nv = (size_t)atol(v);
    else if (!strcmp(k, "--pool")) o->eng.pool = (size_t)atol(v);
    else if (!strcmp(k, "--batch")) o->eng.batch = (uint64_t)atol(v);
    else if (!strcmp(k, "--eps")) o->eps = (float)atof(v);
    else if (!strcmp(k, "--exposure")) o->exposure = (float)atof(v);
    else if (!strcmp(k, "--reference")) o->ref_spp = atoi(v);
    else if (!strcmp(k, "--frames")) o->frames = atoi(v);
    else if (!strcmp(k, "--counts")) {
        if ((n = parse_list(v, l, 8)) <= 0)
            return -1;
        for (o->ncounts = 0; o->ncounts < n; o->ncounts++)
            o->counts[o->ncounts] = (size_t)l[o->ncounts];
    } else
        return -1;
    return 0;
}

static int parse_args(options *o, int argc, char **argv)
{
    *o = (options){.out = ".", .backend = "osmesa", .w = 800, .h = 600, .frames = 10, .ntimes = 1,
                   .ncounts = 4, .counts = {10, 50, 100, 200}, .eps = SRV_VSL_EPSILON, .exposure = 1.0f};
    o->eng = srv_vsl_engine_defaults();
    o->eng.dims[0] = o->eng.dims[1] = o->eng.dims[2] = 12;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--bench"))
            o->bench = 1;
        else if (argv[i][0] != '-' && !o->scene)
            o->scene = argv[i];
        else if (i + 1 >= argc || parse_option(o, argv[i], argv[i + 1]))
            return -1;
        else
            i++;
    }
    return (o->scene != NULL) != (o->dragon != NULL) && o->frames > 0 && o->eng.nv > 0 ? 0 : -1;
}

/* ---- the GL view --------------------------------------------------------------- */

static lumo_gl_proc osmesa_proc(const char *name)
{
    return (lumo_gl_proc)OSMesaGetProcAddress(name);
}

static lumo_gl_proc egl_proc(const char *name)
{
    return (lumo_gl_proc)eglGetProcAddress(name);
}

/* The backend's context made current (its own renderer is not used), then
 * seed 004's renderer in it. */
static int view_open(view *v, const options *o, char *err, size_t errlen)
{
    memset(v, 0, sizeof *v);
    if (!strcmp(o->backend, "osmesa")) {
        if (!(v->osm = lumo_osmesa_open(o->w, o->h, err, errlen)))
            return -1;
        v->r = lumo_gl_vsl_create(osmesa_proc, o->w, o->h, err, errlen);
    } else if (!strcmp(o->backend, "egl")) {
        if (!(v->egl = lumo_egl_open(o->w, o->h, err, errlen)))
            return -1;
        if (strstr(lumo_egl_describe(v->egl), "OpenGL ES")) {
            snprintf(err, errlen, "EGL gave %s: the VSL renderer needs desktop OpenGL 3.3", lumo_egl_describe(v->egl));
            return -1;
        }
        v->r = lumo_gl_vsl_create(egl_proc, o->w, o->h, err, errlen);
    } else {
        snprintf(err, errlen, "unknown backend '%s' (osmesa, egl)", o->backend);
        return -1;
    }
    return v->r ? 0 : -1;
}

static void view_close(view *v)
{
    lumo_gl_vsl_destroy(v->r);
    lumo_osmesa_close(v->osm);
    lumo_egl_close(v->egl);
}

/* ---- the scene as the renderer takes it ------------------------------------------ */

static void geometry_free(geometry *g)
{
    free(g->pos), free(g->nrm), free(g->alb), free(g->tris);
    memset(g, 0, sizeof *g);
}

/* Area-weighted vertex normals of one mesh, appended at base. */
static void mesh_normals(const srv_mesh *m, float *nrm, uint32_t base)
{
    for (uint32_t t = 0; t < m->ntris; t++) {
        const uint32_t *f = &m->tris[3 * (size_t)t];
        vec3 n = v3_cross(v3_sub(m->pos[f[1]], m->pos[f[0]]), v3_sub(m->pos[f[2]], m->pos[f[0]]));
        for (int c = 0; c < 3; c++) {
            float *o = nrm + 3 * (size_t)(base + f[c]);
            o[0] += n.x, o[1] += n.y, o[2] += n.z;
        }
    }
    for (uint32_t v = 0; v < m->nverts; v++) {
        float *o = nrm + 3 * (size_t)(base + v), l = sqrtf(o[0] * o[0] + o[1] * o[1] + o[2] * o[2]);
        if (l > 0)
            o[0] /= l, o[1] /= l, o[2] /= l;
    }
}

/* Emitter meshes are black, as the path tracer sees their faces lit by
 * nothing but their own emission (not drawn here). */
static int geometry_build(const srv_scene *s, geometry *g)
{
    size_t nv = 0, nt = 0;
    for (size_t i = 0; i < s->nmeshes; i++)
        nv += s->meshes[i].nverts, nt += s->meshes[i].ntris;
    memset(g, 0, sizeof *g);
    g->pos = malloc(nv * 12 + 1), g->nrm = calloc(nv * 3 + 1, 4), g->alb = malloc(nv * 12 + 1);
    g->tris = malloc(nt * 12 + 1);
    if (!g->pos || !g->nrm || !g->alb || !g->tris || nv > UINT32_MAX)
        return -1;
    for (size_t i = 0; i < s->nmeshes; i++) {
        const srv_mesh *m = &s->meshes[i];
        for (uint32_t v = 0; v < m->nverts; v++) {
            float *p = g->pos + 3 * (size_t)(g->nverts + v), *a = g->alb + 3 * (size_t)(g->nverts + v);
            p[0] = m->pos[v].x, p[1] = m->pos[v].y, p[2] = m->pos[v].z;
            a[0] = m->emitter ? 0 : m->albedo[v].x, a[1] = m->emitter ? 0 : m->albedo[v].y;
            a[2] = m->emitter ? 0 : m->albedo[v].z;
        }
        mesh_normals(m, g->nrm, g->nverts);
        for (size_t t = 0; t < 3 * (size_t)m->ntris; t++)
            g->tris[3 * (size_t)g->ntris + t] = g->nverts + m->tris[t];
        g->nverts += m->nverts, g->ntris += m->ntris;
    }
    return 0;
}

/* Point and spot lights, intensity = power / 4 pi (the path tracer's). */
static int lights_build(const srv_scene *posed, lumo_gl_vsl_light *out, uint32_t *n, char *err, size_t errlen)
{
    if (posed->nlights > LUMO_GL_VSL_MAX_LIGHTS) {
        snprintf(err, errlen, "%zu lights: the VSL renderer draws at most %d", posed->nlights, LUMO_GL_VSL_MAX_LIGHTS);
        return -1;
    }
    for (size_t i = 0; i < posed->nlights; i++) {
        const srv_light *l = &posed->lights[i];
        if (l->kind != LUMO_LIGHT_POINT && l->kind != LUMO_LIGHT_SPOT) {
            snprintf(err, errlen, "light %zu is neither a point nor a spot light: the VSL renderer's shadow maps "
                     "are for those (seed 004 §0.7.3)", i);
            return -1;
        }
        lumo_gl_vsl_light *o = &out[i];
        memcpy(o->pos, &l->pos, 12), memcpy(o->dir, &l->dir, 12);
        o->cos_half = l->kind == LUMO_LIGHT_SPOT ? l->cos_half : -1.0f;
        o->spot = l->kind == LUMO_LIGHT_SPOT;
        o->intensity[0] = l->power.x / (4 * (float)M_PI), o->intensity[1] = l->power.y / (4 * (float)M_PI);
        o->intensity[2] = l->power.z / (4 * (float)M_PI);
    }
    *n = (uint32_t)posed->nlights;
    return 0;
}

static lumo_gl_vsl_point *vsls_build(const srv_vsl_engine *e, uint32_t *n)
{
    size_t count;
    const srv_vsl_lit *lit = srv_vsl_engine_lit(e, &count);
    lumo_gl_vsl_point *v = malloc(count * sizeof *v + 1);
    if (!v)
        return NULL;
    for (size_t i = 0; i < count; i++) {
        memcpy(v[i].pos, &lit[i].pos, 12), memcpy(v[i].normal, &lit[i].normal, 12);
        memcpy(v[i].flux, &lit[i].flux, 12), v[i].area = lit[i].area;
    }
    *n = (uint32_t)count;
    return v;
}

/* Everything one frame needs at the engine's current moment. */
typedef struct moment {
    srv_scene posed;
    geometry geo;
    lumo_gl_vsl_light lights[LUMO_GL_VSL_MAX_LIGHTS];
    lumo_gl_vsl_point *vsls;
    lumo_gl_vsl_frame frame;
} moment;

static void moment_free(moment *m)
{
    srv_scene_free(&m->posed);
    geometry_free(&m->geo);
    free(m->vsls);
    m->vsls = NULL;
}

static int moment_take(moment *m, const srv_scene *s, const srv_vsl_engine *e, const srv_camera *cam,
                       const options *o, view *v, char *err, size_t errlen)
{
    memset(m, 0, sizeof *m);
    if (srv_vsl_engine_posed_scene(e, s, &m->posed) || geometry_build(&m->posed, &m->geo) ||
        !(m->vsls = vsls_build(e, &m->frame.nvsls))) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    if (lights_build(&m->posed, m->lights, &m->frame.nlights, err, errlen))
        return -1;
    if (lumo_gl_vsl_set_geometry(v->r, m->geo.pos, m->geo.nrm, m->geo.alb, m->geo.nverts, m->geo.tris,
                                 m->geo.ntris)) {
        snprintf(err, errlen, "the GL refused the geometry (%u triangles)", m->geo.ntris);
        return -1;
    }
    lumo_gl_vsl_frame *f = &m->frame;
    memcpy(f->eye, &cam->eye, 12), memcpy(f->target, &cam->target, 12), memcpy(f->up, &cam->up, 12);
    f->fovy_deg = cam->fovy_deg;
    f->lights = m->lights, f->vsls = m->vsls;
    f->eps = o->eps;
    f->direct = f->indirect = 1;
    return 0;
}

/* ---- the IVG picture: the clients' lighting on the same G-buffer ------------------ */

/* Seed 000 §3.2 on the engine's grid (trilinear, the hemisphere by the
 * sign of each normal component): I_n . n = sum n_a^2 (I_a . n). */
static void ivg_irradiance(const srv_vsl_ivg *ivg, const float p[3], const float n[3], double e[3])
{
    const srv_grid *g = &ivg->grid;
    double t[3];
    int i0[3];
    for (int k = 0; k < 3; k++) {
        double lo = v3_get(g->bmin, k), ext = v3_get(g->bmax, k) - lo;
        double x = (p[k] - lo) / ext * (g->dims[k] - 1);
        x = x < 0 ? 0 : x > g->dims[k] - 1 ? g->dims[k] - 1 : x;
        i0[k] = (int)x < g->dims[k] - 1 ? (int)x : g->dims[k] - 2;
        t[k] = x - i0[k];
    }
    e[0] = e[1] = e[2] = 0;
    for (int c = 0; c < 8; c++) {
        int ix = i0[0] + (c & 1), iy = i0[1] + (c >> 1 & 1), iz = i0[2] + (c >> 2 & 1);
        double w = (c & 1 ? t[0] : 1 - t[0]) * (c & 2 ? t[1] : 1 - t[1]) * (c & 4 ? t[2] : 1 - t[2]);
        const double *I = ivg->I + SRV_VSL_IVG_VALUES * ((size_t)ix + (size_t)g->dims[0] * ((size_t)iy +
                                                         (size_t)g->dims[1] * (size_t)iz));
        for (int a = 0; a < 3; a++) {
            int h = 2 * a + (n[a] < 0);
            for (int ch = 0; ch < 3; ch++) {
                const double *v = I + (h * 3 + ch) * 3;
                e[ch] += w * n[a] * n[a] * (v[0] * n[0] + v[1] * n[1] + v[2] * n[2]);
            }
        }
    }
    for (int ch = 0; ch < 3; ch++)
        e[ch] = e[ch] > 0 ? e[ch] : 0;
}

/* direct (the GL's, shadow-mapped; when asked) + rho/pi E_IVG at every
 * G-buffer pixel. */
static int ivg_picture(view *v, const moment *m, const srv_vsl_ivg *ivg, const options *o, int direct, float *out)
{
    size_t n = (size_t)o->w * o->h;
    float *pos = malloc(n * 16), *nrm = malloc(n * 16), *alb = malloc(n * 16);
    lumo_gl_vsl_frame f = m->frame;
    int rc = -1;
    f.indirect = 0;
    f.direct = direct;
    if (pos && nrm && alb && !lumo_gl_vsl_draw(v->r, &f) && !lumo_gl_vsl_read(v->r, out) &&
        !lumo_gl_vsl_read_surface(v->r, pos, nrm, alb)) {
        for (size_t i = 0; i < n; i++) {
            double e[3];
            if (pos[4 * i + 3] == 0)
                continue;
            ivg_irradiance(ivg, pos + 4 * i, nrm + 4 * i, e);
            for (int ch = 0; ch < 3; ch++)
                out[3 * i + ch] += (float)(alb[4 * i + ch] / M_PI * e[ch]);
        }
        rc = 0;
    }
    free(pos), free(nrm), free(alb);
    return rc;
}

/* ---- the GL against the engine's own VSL light ------------------------------------ */

/* The deferred indirect term at every 61st covered pixel against
 * rho/pi srv_vsl_irradiance (server/vsl/vsl_light.c, doubles of the same
 * formula) at the G-buffer's point and normal: the largest difference
 * relative to the pixel's value (floor: 1% of the mean). */
static int check_against_engine(view *v, moment *m, const srv_vsl_engine *e, const options *o, double *worst)
{
    size_t n = (size_t)o->w * o->h, lit_n, checked = 0;
    const srv_vsl_lit *lit = srv_vsl_engine_lit(e, &lit_n);
    float *gl = malloc(n * 12), *pos = malloc(n * 16), *nrm = malloc(n * 16), *alb = malloc(n * 16);
    lumo_gl_vsl_frame f = m->frame;
    double mean = 0;
    int rc = -1;
    f.direct = 0, f.mode = LUMO_GL_VSL_DEFERRED;
    *worst = 0;
    if (gl && pos && nrm && alb && !lumo_gl_vsl_draw(v->r, &f) && !lumo_gl_vsl_read(v->r, gl) &&
        !lumo_gl_vsl_read_surface(v->r, pos, nrm, alb)) {
        for (size_t i = 0; i < 3 * n; i++)
            mean += gl[i] / (3.0 * n);
        for (size_t i = 0; i < n; i += 61) {
            if (pos[4 * i + 3] == 0)
                continue;
            vec3 E = srv_vsl_irradiance(lit, lit_n, v3(pos[4 * i], pos[4 * i + 1], pos[4 * i + 2]),
                                        v3(nrm[4 * i], nrm[4 * i + 1], nrm[4 * i + 2]), o->eps);
            for (int ch = 0; ch < 3; ch++) {
                double want = alb[4 * i + ch] / M_PI * v3_get(E, ch);
                double d = fabs(gl[3 * i + ch] - want) / fmax(fabs(want), 0.01 * mean);
                *worst = fmax(*worst, d);
            }
            checked++;
        }
        rc = checked > 0 ? 0 : -1;
    }
    free(gl), free(pos), free(nrm), free(alb);
    return rc;
}

/* ---- pictures and their errors ---------------------------------------------------- */

/* sum |a - b| / sum |b| over the pixels and channels (linear radiance). */
static double rel_l1(const float *a, const float *b, size_t n)
{
    double d = 0, s = 0;
    for (size_t i = 0; i < n; i++)
        d += fabs((double)a[i] - b[i]), s += fabs((double)b[i]);
    return s > 0 ? d / s : 0;
}

static void diff_line(const char *what, const float *a, const float *b, const options *o)
{
    size_t n = (size_t)o->w * o->h;
    uint8_t *x = host_tonemap_rgb8(a, 3 * n, o->exposure), *y = host_tonemap_rgb8(b, 3 * n, o->exposure);
    host_image_diff d = {0};
    if (x && y)
        host_image_diff_rgb8(x, y, n, &d);
    printf("  %-40s relative L1 %6.1f%%  mean dE %5.2f  PSNR %5.1f dB\n", what, 100 * rel_l1(a, b, 3 * n),
           d.mean_de, d.psnr_db);
    free(x), free(y);
}

static int write_png(const options *o, const char *kind, double t, const float *rgb)
{
    char path[1024], err[256];
    snprintf(path, sizeof path, "%s/%s-t%05.2f.png", o->out, kind, t);
    if (host_png_write_radiance(path, rgb, o->w, o->h, o->exposure, err, sizeof err))
        return fail(err);
    printf("  wrote %s\n", path);
    return 0;
}

/* The path tracer's picture of the posed scene from the same camera. */
static int reference_picture(const moment *m, const srv_camera *cam, const options *o, uint64_t seed,
                             int indirect_only, srv_image *img)
{
    char err[256];
    srv_rt *rt = srv_rt_create(&m->posed, 2, err, sizeof err);
    srv_tracer tr;
    srv_render_opts ro = {o->ref_spp, seed, 2, indirect_only, 0};
    if (!rt)
        return fail(err);
    srv_tracer_init(&tr, &m->posed, rt);
    lumo_status st = srv_render_reference(&tr, cam, o->w, o->h, &ro, img, NULL);
    srv_rt_free(rt);
    return st ? fail("the reference render failed") : 0;
}

/* The whole picture and the indirect part alone (the VSLs' against the
 * path tracer's indirect_only), each beside a second reference of another
 * seed: the references' own noise (their difference is about sqrt(2)
 * times each one's). */
static int compare_reference(view *v, moment *m, const srv_vsl_engine *e, const srv_camera *cam,
                             const options *o, double t, const float *vsl, const float *ivg)
{
    size_t n = (size_t)o->w * o->h * 3;
    srv_image ref[4] = {{0}};
    float *vind = malloc(n * 4), *iind = malloc(n * 4);
    lumo_gl_vsl_frame f = m->frame;
    int rc = 0;
    f.direct = 0, f.mode = LUMO_GL_VSL_DEFERRED;
    for (int k = 0; k < 4 && !rc; k++)
        rc = reference_picture(m, cam, o, 7 + (k & 1), k >= 2, &ref[k]);
    if (!rc && (!vind || !iind || lumo_gl_vsl_draw(v->r, &f) || lumo_gl_vsl_read(v->r, vind) ||
                ivg_picture(v, m, srv_vsl_engine_ivg(e), o, 0, iind)))
        rc = fail("drawing the indirect part failed");
    if (rc)
        goto out;
    rc = write_png(o, "reference", t, ref[0].rgb);
    diff_line("VSL picture vs path traced", vsl, ref[0].rgb, o);
    diff_line("IVG picture vs path traced", ivg, ref[0].rgb, o);
    diff_line("path traced vs path traced (seed 8)", ref[1].rgb, ref[0].rgb, o);
    diff_line("indirect: VSLs vs path traced", vind, ref[2].rgb, o);
    diff_line("indirect: IVG vs path traced", iind, ref[2].rgb, o);
    diff_line("indirect: path traced vs seed 8", ref[3].rgb, ref[2].rgb, o);
out:
    for (int k = 0; k < 4; k++)
        srv_image_free(&ref[k]);
    free(vind), free(iind);
    return rc;
}

/* The VSLs' cut-off radii (§0.7.3) at this moment. */
static void radius_line(const moment *m, const options *o)
{
    double rmin = 1e30, rmax = 0;
    for (uint32_t i = 0; i < m->frame.nvsls; i++) {
        const float *f = m->vsls[i].flux;
        double r = sqrt(fmax(f[0], fmax(f[1], f[2])) / (M_PI * o->eps));
        rmin = fmin(rmin, r), rmax = fmax(rmax, r);
    }
    printf("  %u VSLs, cut-off radius %.3g to %.3g m (eps %g)\n", m->frame.nvsls, rmin, rmax, (double)o->eps);
}

static int check_line(view *v, moment *m, const srv_vsl_engine *e, const options *o)
{
    double worst;
    if (check_against_engine(v, m, e, o, &worst))
        return fail("the check against the engine's VSL light drew nothing");
    printf("  %-40s largest relative difference %.2e\n", "GL deferred vs srv_vsl_irradiance", worst);
    return worst > 1e-3 ? fail("the GL's VSL light differs from the engine's") : 0;
}

/* Every mode's picture (they must agree: one light, three ways), the IVG
 * picture, the check against the engine and, with --reference, the path
 * tracer's pictures, with the errors between them. */
static int render_moment(view *v, moment *m, const srv_vsl_engine *e, const srv_camera *cam, const options *o,
                         double t)
{
    size_t n = (size_t)o->w * o->h * 3;
    float *pic[3] = {malloc(n * 4), malloc(n * 4), malloc(n * 4)}, *ivg = malloc(n * 4);
    int rc = !pic[0] || !pic[1] || !pic[2] || !ivg ? fail("out of memory") : 0;
    for (int k = 0; k < 3 && !rc; k++) {
        m->frame.mode = (lumo_gl_vsl_mode)k;
        rc = lumo_gl_vsl_draw(v->r, &m->frame) || lumo_gl_vsl_read(v->r, pic[k]) ? fail("drawing failed")
                                                                                  : write_png(o, pic_names[k], t, pic[k]);
    }
    if (!rc)
        rc = ivg_picture(v, m, srv_vsl_engine_ivg(e), o, 1, ivg) ? fail("drawing the IVG picture failed")
                                                                 : write_png(o, "ivg", t, ivg);
    if (!rc) {
        radius_line(m, o);
        rc = check_line(v, m, e, o);
    }
    if (!rc) {
        diff_line("whole-scene vs deferred", pic[1], pic[0], o);
        diff_line("one-pass vs deferred", pic[2], pic[0], o);
        diff_line("IVG picture vs VSL picture", ivg, pic[0], o);
        rc = o->ref_spp > 0 ? compare_reference(v, m, e, cam, o, t, pic[0], ivg) : 0;
    }
    for (int k = 0; k < 3; k++)
        free(pic[k]);
    free(ivg);
    return rc;
}

/* ---- Tables 2-3 -------------------------------------------------------------------- */

static double frame_ms(view *v, moment *m, lumo_gl_vsl_mode mode, int frames)
{
    m->frame.mode = mode;
    for (int i = 0; i < 2; i++)   /* warm: shaders specialised, targets touched */
        if (lumo_gl_vsl_draw(v->r, &m->frame))
            return -1;
    double t0 = now_ms();
    for (int i = 0; i < frames; i++)
        if (lumo_gl_vsl_draw(v->r, &m->frame))
            return -1;
    return (now_ms() - t0) / frames;
}

static void bench_header(const view *v, const srv_scene *s, const options *o)
{
    const char *lp = getenv("LP_NUM_THREADS");
    double load = 0;
    FILE *f = fopen("/proc/loadavg", "r");
    if (f) {
        if (fscanf(f, "%lf", &load) != 1)
            load = -1;
        fclose(f);
    }
    printf("lumo-vsl-render --bench: %s, %zu triangles, %dx%d, %s, LP_NUM_THREADS=%s, load %.2f (1 min), "
           "%d frames a cell, eps %g\n", o->dragon ? "Cornell box + dragon" : o->scene, srv_scene_triangle_count(s),
           o->w, o->h, lumo_gl_vsl_describe(v->r), lp ? lp : "(unset)", load, o->frames, (double)o->eps);
    printf("| VSLs | deferred ms | whole-scene ms | one-pass ms | deferred fps / whole-scene fps |\n");
    printf("|---:|---:|---:|---:|---|\n");
}

static int bench(view *v, const srv_scene *s, const srv_motion *mo, const srv_camera *cam, const options *o)
{
    char err[400];
    bench_header(v, s, o);
    for (int c = 0; c < o->ncounts; c++) {
        srv_vsl_engine_opts eo = o->eng;
        eo.nv = o->counts[c];
        srv_vsl_engine *e = srv_vsl_engine_create(s, mo, &eo, err, sizeof err);
        moment m;
        double ms[3];
        if (!e)
            return fail(err);
        srv_vsl_engine_settle(e, 0.0, 100);
        if (moment_take(&m, s, e, cam, o, v, err, sizeof err))
            return fail(err);
        for (int k = 0; k < 3; k++)
            if ((ms[k] = frame_ms(v, &m, (lumo_gl_vsl_mode)k, o->frames)) < 0)
                return fail("drawing failed");
        printf("| %zu | %.1f | %.1f | %.1f | %.1f / %.1f |\n", eo.nv, ms[0], ms[1], ms[2], 1000 / ms[0],
               1000 / ms[1]);
        fflush(stdout);
        moment_free(&m);
        srv_vsl_engine_free(e);
    }
    return 0;
}

/* ---- main ------------------------------------------------------------------------ */

/* mkdir -p */
static int make_dirs(const char *path)
{
    char buf[1024];
    if (snprintf(buf, sizeof buf, "%s", path) >= (int)sizeof buf)
        return -1;
    for (char *p = buf + 1; *p; p++)
        if (*p == '/') {
            *p = '\0';
            if (mkdir(buf, 0777) && errno != EEXIST)
                return -1;
            *p = '/';
        }
    return mkdir(buf, 0777) && errno != EEXIST ? -1 : 0;
}

static int load_scene(const options *o, srv_scene *s, srv_motion *m, char *err, size_t errlen)
{
    srv_scene_init(s);
    memset(m, 0, sizeof *m);
    if (o->dragon)
        return srv_default_scene(s, o->dragon, err, errlen) ? -1 : 0;
    return srv_scene_load(s, o->scene, err, errlen) || srv_motion_load(m, s, o->scene, err, errlen) ? -1 : 0;
}

static int render(view *v, const srv_scene *s, const srv_motion *mo, const srv_camera *cam, const options *o)
{
    char err[400];
    srv_vsl_engine *e = srv_vsl_engine_create(s, mo, &o->eng, err, sizeof err);
    if (!e)
        return fail(err);
    printf("lumo-vsl-render: %s, %zu VSLs, pool %zu, %dx%d, %s\n", o->dragon ? "Cornell box + dragon" : o->scene,
           o->eng.nv, o->eng.pool, o->w, o->h, lumo_gl_vsl_describe(v->r));
    int rc = 0;
    for (int k = 0; k < o->ntimes && !rc; k++) {
        moment m;
        int steps = srv_vsl_engine_settle(e, o->times[k], 10000);
        printf(" time %.2f s: settled in %d steps\n", o->times[k], steps);
        if (moment_take(&m, s, e, cam, o, v, err, sizeof err))
            rc = fail(err);
        else
            rc = render_moment(v, &m, e, cam, o, o->times[k]);
        moment_free(&m);
    }
    srv_vsl_engine_free(e);
    return rc;
}

int main(int argc, char **argv)
{
    options o;
    char err[400];
    srv_scene s;
    srv_motion mo;
    srv_camera cam;
    view v;
    if (parse_args(&o, argc, argv))
        return fail("usage: lumo-vsl-render SCENE|--default DRAGON [--out DIR] [--times T,..] [--size WxH] "
                    "[--vsl N] [--pool N] [--batch N] [--eps E] [--camera C] [--exposure X] [--backend osmesa|egl] "
                    "[--reference SPP] [--bench] [--counts N,..] [--frames N]");
    if (load_scene(&o, &s, &mo, err, sizeof err))
        return fail(err);
    cam = s.has_camera ? s.camera : srv_camera_default();
    if (o.camera && srv_camera_parse_why(o.camera, &cam, err, sizeof err))
        return fail(err);
    if (view_open(&v, &o, err, sizeof err))
        return fail(err);
    if (!o.bench && make_dirs(o.out))
        return fail("cannot create the output folder");
    int rc = o.bench ? bench(&v, &s, &mo, &cam, &o) : render(&v, &s, &mo, &cam, &o);
    view_close(&v);
    srv_scene_free(&s);
    return rc;
}
