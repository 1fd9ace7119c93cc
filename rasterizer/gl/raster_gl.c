/*
 * raster_gl.c — the shared GL renderer of the OSMesa and EGL backends
 * (lumo/raster_gl.h). Desktop code: floats and heap are fine here.
 *
 * GL entry points come from the backend's get-proc-address function into
 * the backends' one table (raster_gl_api.h), so the renderer never links a
 * GL library itself: OSMesa and EGL (libglvnd) can live in one program. Frames go to an off-screen
 * framebuffer object (RGBA8 + 24-bit depth) and are read back.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <GL/glcorearb.h>
#include "lumo/raster_gl.h"
#include "raster_gl_api.h"
#include "raster_gl_shaders.h"
#include "raster_gl_shadow.h"

enum { ATTR_POS = 0, ATTR_NRM = 1, ATTR_ALB = 2 };
#define IVG_TEXTURES 12
#define SHADOW_UNIT IVG_TEXTURES    /* the shadow maps' texture unit */

struct lumo_gl {
    lumo_gl_api gl;
    lumo_gl_getproc_fn getproc;     /* kept for the add-ons in their own files (lumo_gl_getproc) */
    int gles, width, height;
    GLuint prog[2];                 /* per vertex, per pixel */
    lumo_gl_shadow *shadow;         /* the lights' shadow maps (raster_gl_shadow.c) */
    unsigned mesh_gen;              /* counts lumo_gl_set_mesh: the maps follow the mesh */
    GLuint fbo, rb_color, rb_depth;
    GLuint vao, vbo, ebo;
    GLsizei index_count;
    GLuint tex[IVG_TEXTURES];       /* c+x c-x c+y c-y c+z c-z, then d */
    int have_ivg;
    float gmin[3], gext[3], tscale[3], toff[3];
    float scene_radius;
    char renderer[128];
    uint8_t *rgba;
};

static const char *const tex_names[IVG_TEXTURES] = {
    "u_cpx", "u_cnx", "u_cpy", "u_cny", "u_cpz", "u_cnz",
    "u_dpx", "u_dnx", "u_dpy", "u_dny", "u_dpz", "u_dnz"
};

/* Report a failed compile or link with the driver's log, delete the
 * object, return 0 (no object). */
static GLuint gl_fail(char *err, size_t errlen, const char *what, const char *log,
                      void (*del)(GLuint), GLuint obj)
{
    snprintf(err, errlen, "%s failed: %s", what, log);
    del(obj);
    return 0;
}

static GLuint compile(lumo_gl *g, GLenum stage, int per_pixel, const char *body, char *err, size_t errlen)
{
    const char *head = g->gles ? "#version 300 es\nprecision highp float;\nprecision highp int;\n"
                               : "#version 330 core\n";
    const char *src[4] = {head, per_pixel ? "#define PER_PIXEL 1\n" : "", lumo_gl_common_glsl, body};
    GLuint s = g->gl.CreateShader(stage);
    GLint ok = 0;

    g->gl.ShaderSource(s, 4, src, NULL);
    g->gl.CompileShader(s);
    g->gl.GetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[1024] = "";
        g->gl.GetShaderInfoLog(s, sizeof log, NULL, log);
        return gl_fail(err, errlen, "shader compile", log, g->gl.DeleteShader, s);
    }
    return s;
}

/* Compile and link a vertex and fragment body (after the version line and
 * lumo_gl_common_glsl) with attribs[i] bound to location i. */
static GLuint link_program(lumo_gl *g, int per_pixel, const char *vbody, const char *fbody,
                           const char *const *attribs, unsigned nattribs, char *err, size_t errlen)
{
    GLuint vs = compile(g, GL_VERTEX_SHADER, per_pixel, vbody, err, errlen);
    GLuint fs = vs ? compile(g, GL_FRAGMENT_SHADER, per_pixel, fbody, err, errlen) : 0;
    GLuint p;
    GLint ok = 0;
    unsigned i;

    if (!fs) {
        if (vs) g->gl.DeleteShader(vs);
        return 0;
    }
    p = g->gl.CreateProgram();
    g->gl.AttachShader(p, vs);
    g->gl.AttachShader(p, fs);
    for (i = 0; i < nattribs; i++)
        g->gl.BindAttribLocation(p, i, attribs[i]);
    g->gl.LinkProgram(p);
    g->gl.DeleteShader(vs);
    g->gl.DeleteShader(fs);
    g->gl.GetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[1024] = "";
        g->gl.GetProgramInfoLog(p, sizeof log, NULL, log);
        return gl_fail(err, errlen, "program link", log, g->gl.DeleteProgram, p);
    }
    return p;
}

unsigned lumo_gl_program(lumo_gl *g, const char *vertex, const char *fragment, const char *const *attribs,
                         unsigned nattribs, char *err, size_t errlen)
{
    return link_program(g, 0, vertex, fragment, attribs, nattribs, err, errlen);
}

/* A program of lumo's own stages' bodies (after the common GLSL): the mesh's
 * attributes bound, the IVG textures and the shadow maps on their units. */
static GLuint build_program(lumo_gl *g, int per_pixel, const char *vbody, const char *fbody, char *err,
                            size_t errlen)
{
    static const char *const attribs[] = {"a_pos", "a_nrm", "a_alb"};   /* ATTR_POS, _NRM, _ALB */
    GLuint p = link_program(g, per_pixel, vbody, fbody, attribs, 3, err, errlen);
    int i;

    if (!p)
        return 0;
    g->gl.UseProgram(p);
    for (i = 0; i < IVG_TEXTURES; i++)
        g->gl.Uniform1i(g->gl.GetUniformLocation(p, tex_names[i]), i);
    g->gl.Uniform1i(g->gl.GetUniformLocation(p, "u_smap"), SHADOW_UNIT);
    return p;
}

static int make_framebuffer(lumo_gl *g, char *err, size_t errlen)
{
    g->gl.GenFramebuffers(1, &g->fbo);
    g->gl.BindFramebuffer(GL_FRAMEBUFFER, g->fbo);
    g->gl.GenRenderbuffers(1, &g->rb_color);
    g->gl.BindRenderbuffer(GL_RENDERBUFFER, g->rb_color);
    g->gl.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, g->width, g->height);
    g->gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, g->rb_color);
    g->gl.GenRenderbuffers(1, &g->rb_depth);
    g->gl.BindRenderbuffer(GL_RENDERBUFFER, g->rb_depth);
    g->gl.RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, g->width, g->height);
    g->gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, g->rb_depth);
    if (g->gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        snprintf(err, errlen, "framebuffer incomplete");
        return -1;
    }
    return 0;
}

lumo_gl *lumo_gl_create(lumo_gl_getproc_fn getproc, int gles, int width, int height,
                        char *err, size_t errlen)
{
    lumo_gl *g = calloc(1, sizeof *g);
    const GLubyte *name;
    GLuint depth;

    if (!g) {
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    g->gles = gles;
    g->getproc = getproc;
    g->width = width;
    g->height = height;
    g->rgba = malloc((size_t)width * height * 4);
    if (!g->rgba || lumo_gl_api_load(&g->gl, getproc, err, errlen))
        goto fail;
    name = g->gl.GetString(GL_RENDERER);
    snprintf(g->renderer, sizeof g->renderer, "%s", name ? (const char *)name : "?");
    if (!(g->prog[0] = build_program(g, 0, lumo_gl_vertex_glsl, lumo_gl_fragment_glsl, err, errlen))
        || !(g->prog[1] = build_program(g, 1, lumo_gl_vertex_glsl, lumo_gl_fragment_glsl, err, errlen)))
        goto fail;
    if (!(depth = build_program(g, 0, lumo_gl_depth_vertex_glsl, lumo_gl_depth_fragment_glsl, err, errlen)))
        goto fail;
    if (!(g->shadow = lumo_gl_shadow_create(getproc, depth, err, errlen))) {
        g->gl.DeleteProgram(depth);
        goto fail;
    }
    if (make_framebuffer(g, err, errlen))
        goto fail;
    g->gl.GenVertexArrays(1, &g->vao);
    g->gl.GenBuffers(1, &g->vbo);
    g->gl.GenBuffers(1, &g->ebo);
    return g;
fail:
    lumo_gl_destroy(g);
    return NULL;
}

const char *lumo_gl_renderer(const lumo_gl *g)
{
    return g->renderer;
}

int lumo_gl_set_mesh(lumo_gl *g, const lumo_raster_mesh *m)
{
    float *v = malloc((size_t)m->vertex_count * 9 * sizeof *v + 1);
    float r2 = 0;
    uint32_t i;
    int k;

    if (!v)
        return -1;
    for (i = 0; i < m->vertex_count; i++) {
        const lumo_q1_14 *a = m->albedo ? &m->albedo[3 * (size_t)i] : m->mesh_albedo;
        float d2 = 0;
        for (k = 0; k < 3; k++) {
            v[9 * (size_t)i + k] = (float)(m->pos[3 * (size_t)i + k] / 65536.0);
            v[9 * (size_t)i + 3 + k] = (float)(m->normal[3 * (size_t)i + k] / 16384.0);
            v[9 * (size_t)i + 6 + k] = (float)(a[k] < 0 ? 0 : a[k] / 16384.0);
            d2 += v[9 * (size_t)i + k] * v[9 * (size_t)i + k];
        }
        if (d2 > r2) r2 = d2;
    }
    g->scene_radius = sqrtf(r2);
    g->mesh_gen++;
    g->gl.BindVertexArray(g->vao);
    g->gl.BindBuffer(GL_ARRAY_BUFFER, g->vbo);
    g->gl.BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)m->vertex_count * 9 * sizeof *v, v, GL_STATIC_DRAW);
    free(v);
    g->gl.VertexAttribPointer(ATTR_POS, 3, GL_FLOAT, GL_FALSE, 36, (const void *)0);
    g->gl.VertexAttribPointer(ATTR_NRM, 3, GL_FLOAT, GL_FALSE, 36, (const void *)12);
    g->gl.VertexAttribPointer(ATTR_ALB, 3, GL_FLOAT, GL_FALSE, 36, (const void *)24);
    g->gl.EnableVertexAttribArray(ATTR_POS);
    g->gl.EnableVertexAttribArray(ATTR_NRM);
    g->gl.EnableVertexAttribArray(ATTR_ALB);
    g->gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, g->ebo);
    g->gl.BufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)m->tri_count * 3 * sizeof(uint32_t), m->tris,
                     GL_STATIC_DRAW);
    g->index_count = (GLsizei)(m->tri_count * 3);
    return g->gl.GetError() == GL_NO_ERROR ? 0 : -1;
}

/* One hemisphere's colour (RGB9E5 from floats: the driver packs) and
 * direction (RGB8, d * 0.5 + 0.5) as 3D textures with trilinear filtering. */
static void upload_hemisphere(lumo_gl *g, const lumo_ivg *ivg, int axis, float *cbuf, uint8_t *dbuf)
{
    const lumo_ivg_desc *d = lumo_ivg_get_desc(ivg);
    uint32_t n = (uint32_t)d->dims[0] * d->dims[1] * d->dims[2], i;
    int t, k;

    for (i = 0; i < n; i++) {
        lumo_ivg_entry e;
        (void)lumo_ivg_entry_get(ivg, i, (lumo_ivg_axis)axis, &e);   /* i, axis in range */
        for (k = 0; k < 3; k++) {
            double dv = e.d[k] / 16384.0;
            cbuf[3 * (size_t)i + k] = (float)(e.c[k] / 65536.0);
            dv = dv < -1 ? -1 : dv > 1 ? 1 : dv;
            dbuf[3 * (size_t)i + k] = (uint8_t)floor((dv * 0.5 + 0.5) * 255.0 + 0.5);
        }
    }
    for (t = 0; t < 2; t++) {
        GLuint tex = g->tex[axis + 6 * t];
        g->gl.ActiveTexture(GL_TEXTURE0 + (GLenum)(axis + 6 * t));
        g->gl.BindTexture(GL_TEXTURE_3D, tex);
        g->gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
        if (t == 0)
            g->gl.TexImage3D(GL_TEXTURE_3D, 0, GL_RGB9_E5, d->dims[0], d->dims[1], d->dims[2], 0,
                             GL_RGB, GL_FLOAT, cbuf);
        else
            g->gl.TexImage3D(GL_TEXTURE_3D, 0, GL_RGB8, d->dims[0], d->dims[1], d->dims[2], 0,
                             GL_RGB, GL_UNSIGNED_BYTE, dbuf);
        g->gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        g->gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        g->gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        g->gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        g->gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    }
}

int lumo_gl_set_ivg(lumo_gl *g, const lumo_ivg *ivg)
{
    const lumo_ivg_desc *d;
    size_t n;
    float *cbuf;
    uint8_t *dbuf;
    int a, k;

    if (g->have_ivg)
        g->gl.DeleteTextures(IVG_TEXTURES, g->tex);
    g->have_ivg = 0;
    if (!ivg)
        return 0;
    d = lumo_ivg_get_desc(ivg);
    n = (size_t)d->dims[0] * d->dims[1] * d->dims[2];
    cbuf = malloc(n * 3 * sizeof *cbuf);
    dbuf = malloc(n * 3);
    if (!cbuf || !dbuf) {
        free(cbuf);
        free(dbuf);
        return -1;
    }
    g->gl.GenTextures(IVG_TEXTURES, g->tex);
    for (a = 0; a < 6; a++)
        upload_hemisphere(g, ivg, a, cbuf, dbuf);
    free(cbuf);
    free(dbuf);
    /* Grid vertex i sits at the centre of texel i: t = (i + 0.5) / dims. */
    for (k = 0; k < 3; k++) {
        g->gmin[k] = (float)(d->bmin[k] / 65536.0);
        g->gext[k] = (float)((d->bmax[k] - (double)d->bmin[k]) / 65536.0);
        g->tscale[k] = (float)((d->dims[k] - 1.0) / d->dims[k]);
        g->toff[k] = (float)(0.5 / d->dims[k]);
    }
    g->have_ivg = 1;
    return g->gl.GetError() == GL_NO_ERROR ? 0 : -1;
}

/* gluLookAt x gluPerspective (docs/scene-format.md), column-major. */
static void camera_matrix(const lumo_gl *g, const lumo_raster_camera *cam, float out[16], float eye[3])
{
    double e[3], rows[3][3], up[3], l, zf;
    double *f = rows[2], *r = rows[0], *u = rows[1];
    int k;

    for (k = 0; k < 3; k++) {
        e[k] = cam->eye[k] / 65536.0;
        f[k] = cam->target[k] / 65536.0 - e[k];
        up[k] = cam->up[k] / 65536.0;
        eye[k] = (float)e[k];
    }
    l = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    for (k = 0; k < 3; k++) f[k] /= l;
    r[0] = f[1] * up[2] - f[2] * up[1];
    r[1] = f[2] * up[0] - f[0] * up[2];
    r[2] = f[0] * up[1] - f[1] * up[0];
    l = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
    for (k = 0; k < 3; k++) r[k] /= l;
    u[0] = r[1] * f[2] - r[2] * f[1];
    u[1] = r[2] * f[0] - r[0] * f[2];
    u[2] = r[0] * f[1] - r[1] * f[0];
    /* Far plane beyond everything: the soft rasterizer has none. */
    zf = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]) + 2.0 * g->scene_radius + 1.0;
    lumo_gl_frustum(rows, e, 1.0 / tan(cam->fovy_deg / 65536.0 * M_PI / 360.0), (double)g->width / g->height,
                    cam->znear / 65536.0, zf, out);
}

static void set_lights(lumo_gl *g, GLuint p, const lumo_raster_scene *s)
{
    GLint kind[LUMO_MAX_LIGHTS];
    float pos[3 * LUMO_MAX_LIGHTS], dir[3 * LUMO_MAX_LIGHTS], cosv[LUMO_MAX_LIGHTS], val[3 * LUMO_MAX_LIGHTS];
    uint32_t i, n = s->light_count > LUMO_MAX_LIGHTS ? LUMO_MAX_LIGHTS : s->light_count;
    int k;

    for (i = 0; i < n; i++) {
        const lumo_raster_light *L = &s->lights[i];
        kind[i] = L->kind == LUMO_LIGHT_DIRECTIONAL ? 2 : L->kind == LUMO_LIGHT_SPOT ? 1 : 0;
        cosv[i] = (float)(L->cos_cutoff / 16384.0);
        for (k = 0; k < 3; k++) {
            pos[3 * i + k] = (float)(L->pos[k] / 65536.0);
            dir[3 * i + k] = (float)(L->dir[k] / 16384.0);
            /* point and spot carry power: intensity = Phi / (4 pi) */
            val[3 * i + k] = (float)(L->value[k] / 65536.0 / (kind[i] == 2 ? 1.0 : 4.0 * M_PI));
        }
    }
    g->gl.Uniform1i(g->gl.GetUniformLocation(p, "u_nlights"), (GLint)n);
    if (!n)
        return;
    g->gl.Uniform1iv(g->gl.GetUniformLocation(p, "u_kind"), (GLsizei)n, kind);
    g->gl.Uniform3fv(g->gl.GetUniformLocation(p, "u_lpos"), (GLsizei)n, pos);
    g->gl.Uniform3fv(g->gl.GetUniformLocation(p, "u_ldir"), (GLsizei)n, dir);
    g->gl.Uniform1fv(g->gl.GetUniformLocation(p, "u_lcos"), (GLsizei)n, cosv);
    g->gl.Uniform3fv(g->gl.GetUniformLocation(p, "u_lval"), (GLsizei)n, val);
}

int lumo_gl_draw(lumo_gl *g, const lumo_raster_camera *cam, const lumo_raster_scene *s,
                 uint8_t *rgb)
{
    GLuint p = g->prog[(s->flags & LUMO_RASTER_PER_PIXEL) ? 1 : 0];
    float mvp[16], eye[3];
    int x, ind = s->indirect != NULL && g->have_ivg;

    camera_matrix(g, cam, mvp, eye);
    if (lumo_gl_shadow_update(g->shadow, s, g->vao, g->index_count, g->scene_radius, g->mesh_gen))
        return -1;
    g->gl.BindFramebuffer(GL_FRAMEBUFFER, g->fbo);
    g->gl.Viewport(0, 0, g->width, g->height);
    g->gl.ClearColor(0, 0, 0, 1);
    g->gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    g->gl.Enable(GL_DEPTH_TEST);
    g->gl.DepthFunc(GL_LESS);
    if (s->flags & LUMO_RASTER_CULL_BACK) {
        g->gl.Enable(GL_CULL_FACE);
        g->gl.FrontFace(GL_CCW);
        g->gl.CullFace(GL_BACK);
    } else {
        g->gl.Disable(GL_CULL_FACE);
    }
    g->gl.UseProgram(p);
    g->gl.UniformMatrix4fv(g->gl.GetUniformLocation(p, "u_mvp"), 1, GL_FALSE, mvp);
    g->gl.Uniform3fv(g->gl.GetUniformLocation(p, "u_eye"), 1, eye);
    g->gl.Uniform1f(g->gl.GetUniformLocation(p, "u_exposure"), (float)(s->exposure / 65536.0));
    g->gl.Uniform1i(g->gl.GetUniformLocation(p, "u_indirect"), ind);
    g->gl.Uniform3fv(g->gl.GetUniformLocation(p, "u_gmin"), 1, g->gmin);
    g->gl.Uniform3fv(g->gl.GetUniformLocation(p, "u_gext"), 1, g->gext);
    g->gl.Uniform3fv(g->gl.GetUniformLocation(p, "u_tscale"), 1, g->tscale);
    g->gl.Uniform3fv(g->gl.GetUniformLocation(p, "u_toff"), 1, g->toff);
    set_lights(g, p, s);
    lumo_gl_shadow_bind(g->shadow, p, s, SHADOW_UNIT);
    if (g->have_ivg)
        for (x = 0; x < IVG_TEXTURES; x++) {
            g->gl.ActiveTexture(GL_TEXTURE0 + (GLenum)x);
            g->gl.BindTexture(GL_TEXTURE_3D, g->tex[x]);
        }
    g->gl.BindVertexArray(g->vao);
    g->gl.DrawElements(GL_TRIANGLES, g->index_count, GL_UNSIGNED_INT, (const void *)0);
    return lumo_gl_read_rgb(g, rgb);
}

int lumo_gl_read_rgb(lumo_gl *g, uint8_t *rgb)
{
    int y, x;

    g->gl.BindFramebuffer(GL_FRAMEBUFFER, g->fbo);
    g->gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
    g->gl.ReadPixels(0, 0, g->width, g->height, GL_RGBA, GL_UNSIGNED_BYTE, g->rgba);
    /* GL's rows go bottom-up; PNG's top-down. */
    for (y = 0; y < g->height; y++) {
        const uint8_t *src = g->rgba + (size_t)(g->height - 1 - y) * g->width * 4;
        uint8_t *dst = rgb + (size_t)y * g->width * 3;
        for (x = 0; x < g->width; x++) {
            dst[3 * x] = src[4 * x];
            dst[3 * x + 1] = src[4 * x + 1];
            dst[3 * x + 2] = src[4 * x + 2];
        }
    }
    return g->gl.GetError() == GL_NO_ERROR ? 0 : -1;
}

void lumo_gl_bind_target(lumo_gl *g)
{
    g->gl.BindFramebuffer(GL_FRAMEBUFFER, g->fbo);
    g->gl.Viewport(0, 0, g->width, g->height);
}

void lumo_gl_mvp(const lumo_gl *g, const lumo_raster_camera *cam, float mvp[16])
{
    float eye[3];
    camera_matrix(g, cam, mvp, eye);
}

lumo_gl_getproc_fn lumo_gl_getproc(const lumo_gl *g)
{
    return g->getproc;
}

int lumo_gl_gles(const lumo_gl *g)
{
    return g->gles;
}

void lumo_gl_size(const lumo_gl *g, int *width, int *height)
{
    *width = g->width;
    *height = g->height;
}

void lumo_gl_destroy(lumo_gl *g)
{
    if (!g)
        return;
    if (g->gl.DeleteProgram) {
        if (g->prog[0]) g->gl.DeleteProgram(g->prog[0]);
        if (g->prog[1]) g->gl.DeleteProgram(g->prog[1]);
        lumo_gl_shadow_destroy(g->shadow);
        if (g->have_ivg) g->gl.DeleteTextures(IVG_TEXTURES, g->tex);
        if (g->vbo) g->gl.DeleteBuffers(1, &g->vbo);
        if (g->ebo) g->gl.DeleteBuffers(1, &g->ebo);
        if (g->vao) g->gl.DeleteVertexArrays(1, &g->vao);
        if (g->fbo) g->gl.DeleteFramebuffers(1, &g->fbo);
        if (g->rb_color) g->gl.DeleteRenderbuffers(1, &g->rb_color);
        if (g->rb_depth) g->gl.DeleteRenderbuffers(1, &g->rb_depth);
    }
    free(g->rgba);
    free(g);
}
