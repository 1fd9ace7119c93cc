/*
 * raster_gl_vsl.c — seed 004's renderer on the desktop GL backends
 * (lumo/raster_gl_vsl.h): G-buffer, shadow-mapped direct light, VSLs in
 * deferred shading (§0.6, §0.7.3). Desktop code: floats and heap.
 *
 * Its shadow maps are its own (a depth-texture array, one layer per spot
 * light, six per point light) so that it does not wait on raster_gl.c's;
 * the GL entry points come through the backend's get-proc-address into the
 * backends' one table (raster_gl_api.h), so no libGL is linked.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <GL/glcorearb.h>
#include "lumo/raster_gl_vsl.h"
#include "raster_gl_api.h"
#include "raster_gl_vsl_shaders.h"

enum { ATTR_POS = 0, ATTR_NRM = 1, ATTR_ALB = 2 };
enum { P_DEPTH, P_GBUFFER, P_DIRECT, P_DEFERRED, P_WHOLE, P_ONEPASS, P_COUNT };
enum { T_GPOS, T_GNRM, T_GALB, T_SHADOW, T_VSLS, T_ACC, T_COUNT };
#define MAX_LAYERS (6 * LUMO_GL_VSL_MAX_LIGHTS)
#define SPHERE_SEG 16   /* proxy sphere: longitudes; half as many latitudes */
#define ZNEAR 0.05f

struct lumo_gl_vsl {
    lumo_gl_api gl;
    int width, height;
    GLuint prog[P_COUNT];
    GLuint tex[T_COUNT];
    GLuint fbo_gbuf, fbo_acc, fbo_shadow, rb_depth;
    GLuint vao_scene, vbo_scene, ebo_scene, vao_sphere, vbo_sphere, ebo_sphere, vao_empty;
    GLsizei scene_indices, sphere_indices;
    int shadow_layers;   /* allocated layers of T_SHADOW */
    int vsl_rows;        /* allocated rows of T_VSLS */
    float scene_center[3], scene_radius;
    float *vsl_texels;
    char describe[256];
};

/* ---- shaders ---------------------------------------------------------------- */

static GLuint compile(lumo_gl_vsl *r, GLenum stage, const char *body, char *err, size_t errlen)
{
    const char *src[2] = {vsl_common_glsl, body};
    GLuint s = r->gl.CreateShader(stage);
    GLint ok = 0;

    r->gl.ShaderSource(s, 2, src, NULL);
    r->gl.CompileShader(s);
    r->gl.GetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (ok)
        return s;
    char log[1024] = "";
    r->gl.GetShaderInfoLog(s, sizeof log, NULL, log);
    snprintf(err, errlen, "VSL shader compile failed: %s", log);
    r->gl.DeleteShader(s);
    return 0;
}

/* Texture units are fixed per sampler name (T_*), set once at link. */
static void bind_samplers(lumo_gl_vsl *r, GLuint p)
{
    static const char *const names[] = {"u_gpos", "u_gnrm", "u_galb", "u_shadow", "u_vsls"};
    r->gl.UseProgram(p);
    for (int i = 0; i < 5; i++)
        r->gl.Uniform1i(r->gl.GetUniformLocation(p, names[i]), i);
}

static GLuint link(lumo_gl_vsl *r, const char *vs_src, const char *fs_src, char *err, size_t errlen)
{
    GLuint vs = compile(r, GL_VERTEX_SHADER, vs_src, err, errlen);
    GLuint fs = vs ? compile(r, GL_FRAGMENT_SHADER, fs_src, err, errlen) : 0;
    GLint ok = 0;

    if (!fs) {
        if (vs)
            r->gl.DeleteShader(vs);
        return 0;
    }
    GLuint p = r->gl.CreateProgram();
    r->gl.AttachShader(p, vs);
    r->gl.AttachShader(p, fs);
    r->gl.BindAttribLocation(p, ATTR_POS, "a_pos");
    r->gl.BindAttribLocation(p, ATTR_NRM, "a_nrm");
    r->gl.BindAttribLocation(p, ATTR_ALB, "a_alb");
    r->gl.LinkProgram(p);
    r->gl.DeleteShader(vs);
    r->gl.DeleteShader(fs);
    r->gl.GetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[1024] = "";
        r->gl.GetProgramInfoLog(p, sizeof log, NULL, log);
        snprintf(err, errlen, "VSL program link failed: %s", log);
        r->gl.DeleteProgram(p);
        return 0;
    }
    bind_samplers(r, p);
    return p;
}

static int build_programs(lumo_gl_vsl *r, char *err, size_t errlen)
{
    static const char *const stages[P_COUNT][2] = {
        [P_DEPTH] = {vsl_geometry_vs, vsl_depth_fs},     [P_GBUFFER] = {vsl_geometry_vs, vsl_gbuffer_fs},
        [P_DIRECT] = {vsl_screen_vs, vsl_direct_fs},     [P_DEFERRED] = {vsl_sphere_vs, vsl_deferred_fs},
        [P_WHOLE] = {vsl_geometry_vs, vsl_whole_fs},     [P_ONEPASS] = {vsl_screen_vs, vsl_onepass_fs},
    };
    for (int i = 0; i < P_COUNT; i++)
        if (!(r->prog[i] = link(r, stages[i][0], stages[i][1], err, errlen)))
            return -1;
    return 0;
}

/* ---- targets ------------------------------------------------------------------ */

static void texture_2d(lumo_gl_vsl *r, GLuint t, GLenum internal, int w, int h, GLenum format, GLenum type)
{
    r->gl.BindTexture(GL_TEXTURE_2D, t);
    r->gl.TexImage2D(GL_TEXTURE_2D, 0, (GLint)internal, w, h, 0, format, type, NULL);
    r->gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    r->gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    r->gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    r->gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

static int complete(lumo_gl_vsl *r, const char *which, char *err, size_t errlen)
{
    GLenum st = r->gl.CheckFramebufferStatus(GL_FRAMEBUFFER);
    if (st == GL_FRAMEBUFFER_COMPLETE)
        return 0;
    snprintf(err, errlen, "the %s framebuffer is incomplete (0x%x): no float render target?", which, st);
    return -1;
}

/* G-buffer: world position, normal, albedo as RGBA32F (the positions need
 * the precision), one depth buffer shared with the accumulation target so
 * the whole-scene passes can test against the G-buffer's depth. */
static int make_targets(lumo_gl_vsl *r, char *err, size_t errlen)
{
    static const GLenum bufs[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
    r->gl.GenTextures(T_COUNT, r->tex);
    for (int i = T_GPOS; i <= T_GALB; i++)
        texture_2d(r, r->tex[i], GL_RGBA32F, r->width, r->height, GL_RGBA, GL_FLOAT);
    texture_2d(r, r->tex[T_ACC], GL_RGBA32F, r->width, r->height, GL_RGBA, GL_FLOAT);
    r->gl.GenRenderbuffers(1, &r->rb_depth);
    r->gl.BindRenderbuffer(GL_RENDERBUFFER, r->rb_depth);
    r->gl.RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, r->width, r->height);

    r->gl.GenFramebuffers(1, &r->fbo_gbuf);
    r->gl.BindFramebuffer(GL_FRAMEBUFFER, r->fbo_gbuf);
    for (int i = 0; i < 3; i++)
        r->gl.FramebufferTexture2D(GL_FRAMEBUFFER, bufs[i], GL_TEXTURE_2D, r->tex[T_GPOS + i], 0);
    r->gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, r->rb_depth);
    r->gl.DrawBuffers(3, bufs);
    if (complete(r, "G-buffer", err, errlen))
        return -1;

    r->gl.GenFramebuffers(1, &r->fbo_acc);
    r->gl.BindFramebuffer(GL_FRAMEBUFFER, r->fbo_acc);
    r->gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, r->tex[T_ACC], 0);
    r->gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, r->rb_depth);
    if (complete(r, "accumulation", err, errlen))
        return -1;
    r->gl.GenFramebuffers(1, &r->fbo_shadow);
    return 0;
}

/* (Re)allocate the shadow-map array to hold n layers. */
static void shadow_layers(lumo_gl_vsl *r, int n)
{
    if (n <= r->shadow_layers)
        return;
    r->gl.ActiveTexture(GL_TEXTURE0 + T_SHADOW);
    r->gl.BindTexture(GL_TEXTURE_2D_ARRAY, r->tex[T_SHADOW]);
    r->gl.TexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_DEPTH_COMPONENT24, LUMO_GL_VSL_SHADOW_SIZE,
                     LUMO_GL_VSL_SHADOW_SIZE, n, 0, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, NULL);
    r->gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    r->gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    r->gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    r->gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    r->gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    r->gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    r->shadow_layers = n;
}

/* A unit sphere circumscribed by its facets' planes' sphere: vertices at
 * radius 1 / (cos(pi/SEG) cos(pi/SEG)), so every facet lies outside the
 * unit sphere and the proxy covers all of the cut-off sphere. */
static int make_sphere(lumo_gl_vsl *r)
{
    enum { LON = SPHERE_SEG, LAT = SPHERE_SEG / 2 };
    float v[(LAT + 1) * (LON + 1) * 3];
    GLuint idx[LAT * LON * 6];
    double k = 1.0 / (cos(M_PI / LON) * cos(M_PI / LAT));
    int n = 0, m = 0;

    for (int i = 0; i <= LAT; i++)
        for (int j = 0; j <= LON; j++) {
            double th = M_PI * i / LAT, ph = 2 * M_PI * j / LON;
            v[n++] = (float)(k * sin(th) * cos(ph));
            v[n++] = (float)(k * cos(th));
            v[n++] = (float)(k * sin(th) * sin(ph));
        }
    for (int i = 0; i < LAT; i++)
        for (int j = 0; j < LON; j++) {
            GLuint a = (GLuint)(i * (LON + 1) + j), b = a + LON + 1;
            idx[m++] = a, idx[m++] = b, idx[m++] = a + 1;
            idx[m++] = a + 1, idx[m++] = b, idx[m++] = b + 1;
        }
    r->gl.GenVertexArrays(1, &r->vao_sphere);
    r->gl.BindVertexArray(r->vao_sphere);
    r->gl.GenBuffers(1, &r->vbo_sphere);
    r->gl.BindBuffer(GL_ARRAY_BUFFER, r->vbo_sphere);
    r->gl.BufferData(GL_ARRAY_BUFFER, sizeof v, v, GL_STATIC_DRAW);
    r->gl.VertexAttribPointer(ATTR_POS, 3, GL_FLOAT, GL_FALSE, 12, (const void *)0);
    r->gl.EnableVertexAttribArray(ATTR_POS);
    r->gl.GenBuffers(1, &r->ebo_sphere);
    r->gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, r->ebo_sphere);
    r->gl.BufferData(GL_ELEMENT_ARRAY_BUFFER, sizeof idx, idx, GL_STATIC_DRAW);
    r->sphere_indices = m;
    r->gl.GenVertexArrays(1, &r->vao_empty);
    return 0;
}

lumo_gl_vsl *lumo_gl_vsl_create(lumo_gl_getproc_fn getproc, int width, int height, char *err, size_t errlen)
{
    lumo_gl_vsl *r = calloc(1, sizeof *r);
    if (!r) {
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    r->width = width, r->height = height;
    if (lumo_gl_api_load(&r->gl, getproc, err, errlen))
        goto fail;
    const GLubyte *name = r->gl.GetString(GL_RENDERER), *ver = r->gl.GetString(GL_VERSION);
    snprintf(r->describe, sizeof r->describe, "%s; OpenGL %s; G-buffer RGBA32F x3, accumulation RGBA32F",
             name ? (const char *)name : "?", ver ? (const char *)ver : "?");
    if (build_programs(r, err, errlen) || make_targets(r, err, errlen) || make_sphere(r))
        goto fail;
    r->gl.GenVertexArrays(1, &r->vao_scene);
    r->gl.GenBuffers(1, &r->vbo_scene);
    r->gl.GenBuffers(1, &r->ebo_scene);
    if (r->gl.GetError() != GL_NO_ERROR) {
        snprintf(err, errlen, "GL error while setting up the VSL renderer");
        goto fail;
    }
    return r;
fail:
    lumo_gl_vsl_destroy(r);
    return NULL;
}

const char *lumo_gl_vsl_describe(const lumo_gl_vsl *r)
{
    return r->describe;
}

/* ---- geometry ------------------------------------------------------------------ */

static void bounds_sphere(lumo_gl_vsl *r, const float *pos, uint32_t n)
{
    float lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0}, r2 = 0;
    for (uint32_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            float x = pos[3 * (size_t)i + k];
            if (i == 0 || x < lo[k]) lo[k] = x;
            if (i == 0 || x > hi[k]) hi[k] = x;
        }
    for (int k = 0; k < 3; k++) {
        r->scene_center[k] = 0.5f * (lo[k] + hi[k]);
        r2 += 0.25f * (hi[k] - lo[k]) * (hi[k] - lo[k]);
    }
    r->scene_radius = sqrtf(r2);
}

int lumo_gl_vsl_set_geometry(lumo_gl_vsl *r, const float *pos, const float *normal, const float *albedo,
                             uint32_t nverts, const uint32_t *tris, uint32_t ntris)
{
    for (size_t i = 0; i < 3 * (size_t)ntris; i++)
        if (tris[i] >= nverts)
            return -1;
    float *v = malloc((size_t)nverts * 9 * sizeof *v + 1);
    if (!v)
        return -1;
    for (size_t i = 0; i < nverts; i++) {
        memcpy(v + 9 * i, pos + 3 * i, 12);
        memcpy(v + 9 * i + 3, normal + 3 * i, 12);
        memcpy(v + 9 * i + 6, albedo + 3 * i, 12);
    }
    bounds_sphere(r, pos, nverts);
    r->gl.BindVertexArray(r->vao_scene);
    r->gl.BindBuffer(GL_ARRAY_BUFFER, r->vbo_scene);
    r->gl.BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)nverts * 36, v, GL_STATIC_DRAW);
    free(v);
    r->gl.VertexAttribPointer(ATTR_POS, 3, GL_FLOAT, GL_FALSE, 36, (const void *)0);
    r->gl.VertexAttribPointer(ATTR_NRM, 3, GL_FLOAT, GL_FALSE, 36, (const void *)12);
    r->gl.VertexAttribPointer(ATTR_ALB, 3, GL_FLOAT, GL_FALSE, 36, (const void *)24);
    for (int a = ATTR_POS; a <= ATTR_ALB; a++)
        r->gl.EnableVertexAttribArray((GLuint)a);
    r->gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, r->ebo_scene);
    r->gl.BufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)ntris * 12, tris, GL_STATIC_DRAW);
    r->scene_indices = (GLsizei)(3 * ntris);
    return r->gl.GetError() == GL_NO_ERROR ? 0 : -1;
}

/* ---- matrices (column-major, as GL) ------------------------------------------- */

static void mat_mul(const double a[16], const double b[16], float out[16])
{
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) {
            double s = 0;
            for (int k = 0; k < 4; k++)
                s += a[4 * k + j] * b[4 * i + k];
            out[4 * i + j] = (float)s;
        }
}

static void normalize3(double v[3])
{
    double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int k = 0; k < 3; k++)
        v[k] /= l;
}

/* gluLookAt x gluPerspective. */
static void view_proj(const float eye[3], const float dir_in[3], const float up_in[3], double fovy_deg,
                      double aspect, double zn, double zf, float out[16])
{
    double f[3] = {dir_in[0], dir_in[1], dir_in[2]}, up[3] = {up_in[0], up_in[1], up_in[2]}, s[3], u[3];
    double view[16] = {0}, proj[16] = {0};
    normalize3(f);
    s[0] = f[1] * up[2] - f[2] * up[1], s[1] = f[2] * up[0] - f[0] * up[2], s[2] = f[0] * up[1] - f[1] * up[0];
    normalize3(s);
    u[0] = s[1] * f[2] - s[2] * f[1], u[1] = s[2] * f[0] - s[0] * f[2], u[2] = s[0] * f[1] - s[1] * f[0];
    for (int k = 0; k < 3; k++) {
        view[4 * k + 0] = s[k], view[4 * k + 1] = u[k], view[4 * k + 2] = -f[k];
        view[12] -= s[k] * eye[k], view[13] -= u[k] * eye[k], view[14] += f[k] * eye[k];
    }
    view[15] = 1;
    double ct = 1.0 / tan(fovy_deg * M_PI / 360.0);
    proj[0] = ct / aspect, proj[5] = ct;
    proj[10] = (zf + zn) / (zn - zf), proj[11] = -1, proj[14] = 2 * zf * zn / (zn - zf);
    mat_mul(proj, view, out);
}

/* Far enough for everything seen from p. */
static double far_from(const lumo_gl_vsl *r, const float p[3])
{
    double d = 0;
    for (int k = 0; k < 3; k++)
        d += (p[k] - r->scene_center[k]) * (double)(p[k] - r->scene_center[k]);
    return sqrt(d) + r->scene_radius + 1.0;
}

/* ---- passes -------------------------------------------------------------------- */

static void draw_scene(lumo_gl_vsl *r)
{
    r->gl.BindVertexArray(r->vao_scene);
    r->gl.DrawElements(GL_TRIANGLES, r->scene_indices, GL_UNSIGNED_INT, (const void *)0);
}

/* A spot light's one frustum (its cone), or a point light's six. */
static int light_frusta(const lumo_gl_vsl *r, const lumo_gl_vsl_light *l, float mats[6][16])
{
    static const float dirs[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    static const float ups[6][3] = {{0, 1, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, 1}, {0, 1, 0}, {0, 1, 0}};
    double zf = far_from(r, l->pos);
    if (l->spot) {
        float up[3] = {0, 1, 0};
        if (fabsf(l->dir[1]) > 0.9f)
            up[1] = 0, up[2] = 1;
        double half = acos(fmax(-1.0, fmin(1.0, l->cos_half))) * 180.0 / M_PI;
        view_proj(l->pos, l->dir, up, fmin(2.0 * half + 4.0, 170.0), 1.0, 0.01, zf, mats[0]);
        return 1;
    }
    for (int f = 0; f < 6; f++)
        view_proj(l->pos, dirs[f], ups[f], 90.5, 1.0, 0.01, zf, mats[f]);
    return 6;
}

/* Shadow maps of every light into the layers of T_SHADOW; the matrices
 * and each light's first layer and count into the programs' uniforms. */
static void shadow_pass(lumo_gl_vsl *r, const lumo_gl_vsl_frame *f, float mats[MAX_LAYERS][16], GLint first[4],
                        GLint count[4])
{
    int layers = 0;
    for (uint32_t i = 0; i < f->nlights; i++) {
        first[i] = layers;
        count[i] = light_frusta(r, &f->lights[i], &mats[layers]);
        layers += count[i];
    }
    shadow_layers(r, layers > 0 ? layers : 1);
    r->gl.BindFramebuffer(GL_FRAMEBUFFER, r->fbo_shadow);
    r->gl.DrawBuffer(GL_NONE);
    r->gl.ReadBuffer(GL_NONE);
    r->gl.Viewport(0, 0, LUMO_GL_VSL_SHADOW_SIZE, LUMO_GL_VSL_SHADOW_SIZE);
    r->gl.UseProgram(r->prog[P_DEPTH]);
    r->gl.Enable(GL_DEPTH_TEST);
    r->gl.DepthFunc(GL_LESS);
    r->gl.DepthMask(GL_TRUE);
    r->gl.Enable(GL_POLYGON_OFFSET_FILL);
    r->gl.PolygonOffset(1.5f, 4.0f);
    GLint mvp = r->gl.GetUniformLocation(r->prog[P_DEPTH], "u_mvp");
    for (int k = 0; k < layers; k++) {
        r->gl.FramebufferTextureLayer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, r->tex[T_SHADOW], 0, k);
        r->gl.Clear(GL_DEPTH_BUFFER_BIT);
        r->gl.UniformMatrix4fv(mvp, 1, GL_FALSE, mats[k]);
        draw_scene(r);
    }
    r->gl.Disable(GL_POLYGON_OFFSET_FILL);
}

static void set_lights(lumo_gl_vsl *r, GLuint p, const lumo_gl_vsl_frame *f, float mats[MAX_LAYERS][16],
                       const GLint first[4], const GLint count[4])
{
    float pos[12], dir[12], in[12], cs[4];
    GLint spot[4];
    int layers = 0;
    for (uint32_t i = 0; i < f->nlights; i++) {
        const lumo_gl_vsl_light *l = &f->lights[i];
        memcpy(pos + 3 * i, l->pos, 12), memcpy(dir + 3 * i, l->dir, 12), memcpy(in + 3 * i, l->intensity, 12);
        cs[i] = l->cos_half, spot[i] = l->spot;
        layers += count[i];
    }
    r->gl.UseProgram(p);
    r->gl.Uniform1i(r->gl.GetUniformLocation(p, "u_nlights"), (GLint)f->nlights);
    if (!f->nlights)
        return;
    GLsizei n = (GLsizei)f->nlights;
    r->gl.Uniform3fv(r->gl.GetUniformLocation(p, "u_lpos"), n, pos);
    r->gl.Uniform3fv(r->gl.GetUniformLocation(p, "u_ldir"), n, dir);
    r->gl.Uniform3fv(r->gl.GetUniformLocation(p, "u_lint"), n, in);
    r->gl.Uniform1fv(r->gl.GetUniformLocation(p, "u_lcos"), n, cs);
    r->gl.Uniform1iv(r->gl.GetUniformLocation(p, "u_lspot"), n, spot);
    r->gl.Uniform1iv(r->gl.GetUniformLocation(p, "u_lfirst"), n, first);
    r->gl.Uniform1iv(r->gl.GetUniformLocation(p, "u_lcount"), n, count);
    r->gl.UniformMatrix4fv(r->gl.GetUniformLocation(p, "u_lmat"), layers, GL_FALSE, &mats[0][0]);
}

static void gbuffer_pass(lumo_gl_vsl *r, const float mvp[16], const float eye[3])
{
    r->gl.BindFramebuffer(GL_FRAMEBUFFER, r->fbo_gbuf);
    r->gl.Viewport(0, 0, r->width, r->height);
    r->gl.ClearColor(0, 0, 0, 0);
    r->gl.Enable(GL_DEPTH_TEST);
    r->gl.DepthFunc(GL_LESS);
    r->gl.DepthMask(GL_TRUE);
    r->gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    r->gl.UseProgram(r->prog[P_GBUFFER]);
    r->gl.UniformMatrix4fv(r->gl.GetUniformLocation(r->prog[P_GBUFFER], "u_mvp"), 1, GL_FALSE, mvp);
    r->gl.Uniform3fv(r->gl.GetUniformLocation(r->prog[P_GBUFFER], "u_eye"), 1, eye);
    draw_scene(r);
}

static float cutoff2(const lumo_gl_vsl_point *v, float eps)
{
    float m = fmaxf(fabsf(v->flux[0]), fmaxf(fabsf(v->flux[1]), fabsf(v->flux[2])));
    return eps > 0 ? m / ((float)M_PI * eps) : 1e30f;
}

static void set_vsl(lumo_gl_vsl *r, GLuint p, const lumo_gl_vsl_point *v, float cut2)
{
    r->gl.Uniform3fv(r->gl.GetUniformLocation(p, "u_vpos"), 1, v->pos);
    r->gl.Uniform3fv(r->gl.GetUniformLocation(p, "u_vnrm"), 1, v->normal);
    r->gl.Uniform3fv(r->gl.GetUniformLocation(p, "u_vflux"), 1, v->flux);
    r->gl.Uniform1f(r->gl.GetUniformLocation(p, "u_varea"), v->area);
    r->gl.Uniform1f(r->gl.GetUniformLocation(p, "u_vcut2"), cut2);
}

/* §0.7.3: each VSL as a sphere of its cut-off radius, its back faces
 * (depth-clamped: the radius at eps = 1e-6 is metres to hundreds of
 * metres) so that it covers its pixels whether the eye is in it or not;
 * a full-screen triangle when the eye is inside (no facet crosses the
 * eye). */
static void deferred_pass(lumo_gl_vsl *r, const lumo_gl_vsl_frame *f, const float mvp[16], const float eye[3])
{
    GLuint p = r->prog[P_DEFERRED];
    GLint full = r->gl.GetUniformLocation(p, "u_fullscreen"), rad = r->gl.GetUniformLocation(p, "u_vrad");
    r->gl.UseProgram(p);
    r->gl.UniformMatrix4fv(r->gl.GetUniformLocation(p, "u_mvp"), 1, GL_FALSE, mvp);
    r->gl.CullFace(GL_FRONT);
    r->gl.Enable(GL_DEPTH_CLAMP);
    for (uint32_t i = 0; i < f->nvsls; i++) {
        const lumo_gl_vsl_point *v = &f->vsls[i];
        float c2 = cutoff2(v, f->eps), rc = c2 >= 1e29f ? 1e6f : sqrtf(c2);
        double d2 = 0;
        for (int k = 0; k < 3; k++)
            d2 += (eye[k] - v->pos[k]) * (double)(eye[k] - v->pos[k]);
        int inside = sqrt(d2) < 1.2 * rc + 2 * ZNEAR;
        set_vsl(r, p, v, c2);
        r->gl.Uniform1i(full, inside);
        r->gl.Uniform1f(rad, rc);
        if (inside) {   /* the full-screen triangle faces the eye: not culled */
            r->gl.Disable(GL_CULL_FACE);
            r->gl.BindVertexArray(r->vao_empty);
            r->gl.DrawArrays(GL_TRIANGLES, 0, 3);
        } else {
            r->gl.Enable(GL_CULL_FACE);
            r->gl.BindVertexArray(r->vao_sphere);
            r->gl.DrawElements(GL_TRIANGLES, r->sphere_indices, GL_UNSIGNED_INT, (const void *)0);
        }
    }
    r->gl.Disable(GL_DEPTH_CLAMP);
    r->gl.Disable(GL_CULL_FACE);
}

/* Tables 2-3's second value: the geometry again per VSL, where its depth
 * equals the G-buffer's (same vertex shader and matrix: invariant). */
static void whole_scene_pass(lumo_gl_vsl *r, const lumo_gl_vsl_frame *f, const float mvp[16])
{
    GLuint p = r->prog[P_WHOLE];
    r->gl.UseProgram(p);
    r->gl.UniformMatrix4fv(r->gl.GetUniformLocation(p, "u_mvp"), 1, GL_FALSE, mvp);
    r->gl.Enable(GL_DEPTH_TEST);
    r->gl.DepthFunc(GL_LEQUAL);
    for (uint32_t i = 0; i < f->nvsls; i++) {
        set_vsl(r, p, &f->vsls[i], cutoff2(&f->vsls[i], f->eps));
        draw_scene(r);
    }
    r->gl.Disable(GL_DEPTH_TEST);
}

/* Every VSL at every pixel in one pass: the VSLs as a 3 x n float texture. */
static int one_pass(lumo_gl_vsl *r, const lumo_gl_vsl_frame *f)
{
    GLuint p = r->prog[P_ONEPASS];
    if ((int)f->nvsls > r->vsl_rows) {
        float *t = realloc(r->vsl_texels, (size_t)f->nvsls * 12 * sizeof *t);
        if (!t)
            return -1;
        r->vsl_texels = t;
        r->vsl_rows = (int)f->nvsls;
    }
    for (uint32_t i = 0; i < f->nvsls; i++) {
        const lumo_gl_vsl_point *v = &f->vsls[i];
        float *t = r->vsl_texels + 12 * (size_t)i;
        memcpy(t, v->pos, 12), t[3] = v->area;
        memcpy(t + 4, v->normal, 12), t[7] = cutoff2(v, f->eps);
        memcpy(t + 8, v->flux, 12), t[11] = 0;
    }
    r->gl.ActiveTexture(GL_TEXTURE0 + T_VSLS);
    texture_2d(r, r->tex[T_VSLS], GL_RGBA32F, 3, f->nvsls > 0 ? (int)f->nvsls : 1, GL_RGBA, GL_FLOAT);
    if (f->nvsls)
        r->gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, 3, (GLsizei)f->nvsls, 0, GL_RGBA, GL_FLOAT, r->vsl_texels);
    r->gl.UseProgram(p);
    r->gl.Uniform1i(r->gl.GetUniformLocation(p, "u_nvsls"), (GLint)f->nvsls);
    r->gl.BindVertexArray(r->vao_empty);
    r->gl.DrawArrays(GL_TRIANGLES, 0, 3);
    return 0;
}

static void bind_gbuffer(lumo_gl_vsl *r)
{
    for (int i = T_GPOS; i <= T_GALB; i++) {
        r->gl.ActiveTexture(GL_TEXTURE0 + (GLenum)i);
        r->gl.BindTexture(GL_TEXTURE_2D, r->tex[i]);
    }
    r->gl.ActiveTexture(GL_TEXTURE0 + T_SHADOW);
    r->gl.BindTexture(GL_TEXTURE_2D_ARRAY, r->tex[T_SHADOW]);
}

static void set_eye(lumo_gl_vsl *r, const float eye[3])
{
    for (int i = 0; i < P_COUNT; i++) {
        r->gl.UseProgram(r->prog[i]);
        r->gl.Uniform3fv(r->gl.GetUniformLocation(r->prog[i], "u_eye"), 1, eye);
    }
}

int lumo_gl_vsl_draw(lumo_gl_vsl *r, const lumo_gl_vsl_frame *f)
{
    float mvp[16], dir[3], mats[MAX_LAYERS][16];
    GLint first[4] = {0}, count[4] = {0};
    if (f->nlights > LUMO_GL_VSL_MAX_LIGHTS || f->mode > LUMO_GL_VSL_ONE_PASS)
        return -1;
    for (int k = 0; k < 3; k++)
        dir[k] = f->target[k] - f->eye[k];
    view_proj(f->eye, dir, f->up, f->fovy_deg, (double)r->width / r->height, ZNEAR, far_from(r, f->eye), mvp);
    set_eye(r, f->eye);
    if (f->direct && f->nlights)
        shadow_pass(r, f, mats, first, count);
    gbuffer_pass(r, mvp, f->eye);

    r->gl.BindFramebuffer(GL_FRAMEBUFFER, r->fbo_acc);
    r->gl.Viewport(0, 0, r->width, r->height);
    r->gl.Clear(GL_COLOR_BUFFER_BIT);
    r->gl.DepthMask(GL_FALSE);
    r->gl.Disable(GL_DEPTH_TEST);
    r->gl.Enable(GL_BLEND);
    r->gl.BlendFunc(GL_ONE, GL_ONE);
    bind_gbuffer(r);
    if (f->direct && f->nlights) {
        set_lights(r, r->prog[P_DIRECT], f, mats, first, count);
        r->gl.BindVertexArray(r->vao_empty);
        r->gl.DrawArrays(GL_TRIANGLES, 0, 3);
    }
    int rc = 0;
    if (f->indirect && f->mode == LUMO_GL_VSL_DEFERRED)
        deferred_pass(r, f, mvp, f->eye);
    else if (f->indirect && f->mode == LUMO_GL_VSL_WHOLE_SCENE)
        whole_scene_pass(r, f, mvp);
    else if (f->indirect)
        rc = one_pass(r, f);
    r->gl.Disable(GL_BLEND);
    r->gl.DepthMask(GL_TRUE);
    r->gl.Finish();
    return rc == 0 && r->gl.GetError() == GL_NO_ERROR ? 0 : -1;
}

/* ---- read back ----------------------------------------------------------------- */

/* One RGBA32F attachment of fbo, rows flipped to top first, into out
 * (channels of each pixel: the first keep of 4). */
static int read_rgba(lumo_gl_vsl *r, GLuint fbo, GLenum att, float *out, int keep)
{
    float *buf = malloc((size_t)r->width * r->height * 4 * sizeof *buf);
    if (!buf)
        return -1;
    r->gl.BindFramebuffer(GL_FRAMEBUFFER, fbo);
    r->gl.ReadBuffer(att);
    r->gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
    r->gl.ReadPixels(0, 0, r->width, r->height, GL_RGBA, GL_FLOAT, buf);
    for (int y = 0; y < r->height; y++) {
        const float *src = buf + (size_t)(r->height - 1 - y) * r->width * 4;
        float *dst = out + (size_t)y * r->width * keep;
        for (int x = 0; x < r->width; x++)
            memcpy(dst + (size_t)x * keep, src + 4 * (size_t)x, (size_t)keep * sizeof *dst);
    }
    free(buf);
    return r->gl.GetError() == GL_NO_ERROR ? 0 : -1;
}

int lumo_gl_vsl_read(lumo_gl_vsl *r, float *rgb)
{
    return read_rgba(r, r->fbo_acc, GL_COLOR_ATTACHMENT0, rgb, 3);
}

int lumo_gl_vsl_read_surface(lumo_gl_vsl *r, float *pos4, float *nrm4, float *alb4)
{
    float *out[3] = {pos4, nrm4, alb4};
    for (int i = 0; i < 3; i++)
        if (out[i] && read_rgba(r, r->fbo_gbuf, GL_COLOR_ATTACHMENT0 + (GLenum)i, out[i], 4))
            return -1;
    return 0;
}

void lumo_gl_vsl_destroy(lumo_gl_vsl *r)
{
    if (!r)
        return;
    if (r->gl.DeleteProgram) {
        for (int i = 0; i < P_COUNT; i++)
            if (r->prog[i])
                r->gl.DeleteProgram(r->prog[i]);
        if (r->tex[0])
            r->gl.DeleteTextures(T_COUNT, r->tex);
        GLuint fbos[3] = {r->fbo_gbuf, r->fbo_acc, r->fbo_shadow};
        GLuint bufs[4] = {r->vbo_scene, r->ebo_scene, r->vbo_sphere, r->ebo_sphere};
        GLuint vaos[3] = {r->vao_scene, r->vao_sphere, r->vao_empty};
        r->gl.DeleteFramebuffers(3, fbos);
        r->gl.DeleteBuffers(4, bufs);
        r->gl.DeleteVertexArrays(3, vaos);
        if (r->rb_depth)
            r->gl.DeleteRenderbuffers(1, &r->rb_depth);
    }
    free(r->vsl_texels);
    free(r);
}
