/*
 * raster_gl_shadow.c — shadow maps of the GL backends (raster_gl_shadow.h).
 * Desktop code: floats and heap are fine here.
 *
 * Every face of every shadowed light is one layer of a depth array texture,
 * drawn from the soft rasterizer's own view of that face (lumo_raster_view:
 * eye, basis, cot(fov/2), near plane), both sides of every triangle, depth
 * = w / far written by the fragment shader (linear, so the lookup compares
 * view depths as the soft path does, without its 16-bit step). The GL
 * entry points are the backends' one table (raster_gl_api.h).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "raster_gl_api.h"
#include "raster_gl_shadow.h"

/* What a light's maps were drawn from: its views, compared whole. */
typedef struct drawn_key {
    lumo_raster_view face[LUMO_RASTER_SHADOW_MAX_FACES];
    uint16_t size;
    uint8_t faces;
} drawn_key;

struct lumo_gl_shadow {
    lumo_gl_api gl;
    GLuint prog, tex, fbo;
    GLsizei tex_size, tex_layers;          /* the texture's allocation */
    uint32_t count;                        /* lights of the drawn scene */
    drawn_key key[LUMO_MAX_LIGHTS];        /* faces == 0: no map */
    GLint first[LUMO_MAX_LIGHTS];          /* each light's first layer */
    float far[LUMO_MAX_LIGHTS];
    unsigned mesh_gen;
    int drawn;
    size_t bytes;
};

void lumo_gl_frustum(const double rows[3][3], const double eye[3], double cot_half, double aspect,
                     double znear, double zfar, float out[16])
{
    double view[16], proj[16];
    int i, j, k;

    memset(view, 0, sizeof view);
    for (k = 0; k < 3; k++) {
        view[4 * k + 0] = rows[0][k];
        view[4 * k + 1] = rows[1][k];
        view[4 * k + 2] = -rows[2][k];           /* GL looks down -z */
    }
    for (k = 0; k < 3; k++) {
        view[12] -= rows[0][k] * eye[k];
        view[13] -= rows[1][k] * eye[k];
        view[14] += rows[2][k] * eye[k];
    }
    view[15] = 1;
    memset(proj, 0, sizeof proj);
    proj[0] = cot_half / aspect;
    proj[5] = cot_half;
    proj[10] = (zfar + znear) / (znear - zfar);
    proj[11] = -1;
    proj[14] = 2 * zfar * znear / (znear - zfar);
    for (i = 0; i < 4; i++)
        for (j = 0; j < 4; j++) {
            double s = 0;
            for (k = 0; k < 4; k++)
                s += proj[4 * k + j] * view[4 * i + k];
            out[4 * i + j] = (float)s;
        }
}

lumo_gl_shadow *lumo_gl_shadow_create(lumo_gl_getproc_fn getproc, GLuint depth_prog, char *err,
                                      size_t errlen)
{
    lumo_gl_shadow *sh = calloc(1, sizeof *sh);

    if (!sh) {
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    if (lumo_gl_api_load(&sh->gl, getproc, err, errlen)) {
        free(sh);
        return NULL;
    }
    sh->prog = depth_prog;
    sh->gl.GenFramebuffers(1, &sh->fbo);
    return sh;
}

/* The light's key: its views, or faces 0 when it has no map. */
static void key_of(const lumo_raster_light *L, drawn_key *k)
{
    memset(k, 0, sizeof *k);
    if (!L->shadow || L->shadow->faces == 0)
        return;
    memcpy(k->face, L->shadow->face, sizeof k->face);
    k->size = L->shadow->size;
    k->faces = L->shadow->faces;
}

static int unchanged(const lumo_gl_shadow *sh, const lumo_raster_scene *s, unsigned mesh_gen)
{
    uint32_t i;

    if (!sh->drawn || sh->mesh_gen != mesh_gen || sh->count != s->light_count)
        return 0;
    for (i = 0; i < s->light_count; i++) {
        drawn_key k;
        key_of(&s->lights[i], &k);
        if (memcmp(&k, &sh->key[i], sizeof k))
            return 0;
    }
    return 1;
}

/* One layer per face, all of the largest face size (smaller maps use a
 * corner of theirs). */
static int allocate(lumo_gl_shadow *sh, GLsizei size, GLsizei layers)
{
    if (sh->tex && size == sh->tex_size && layers <= sh->tex_layers)
        return 0;
    if (!sh->tex)
        sh->gl.GenTextures(1, &sh->tex);
    sh->gl.BindTexture(GL_TEXTURE_2D_ARRAY, sh->tex);
    sh->gl.TexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_DEPTH_COMPONENT32F, size, size, layers, 0,
                      GL_DEPTH_COMPONENT, GL_FLOAT, NULL);
    /* read with texelFetch: nearest, no comparison (the PCF is the shader's) */
    sh->gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    sh->gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    sh->gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_COMPARE_MODE, GL_NONE);
    sh->tex_size = size;
    sh->tex_layers = layers;
    return sh->gl.GetError() == GL_NO_ERROR ? 0 : -1;
}

static void view_rows(const lumo_raster_view *v, double rows[3][3], double eye[3])
{
    int i, k;

    for (i = 0; i < 3; i++) {
        eye[i] = v->eye[i] / 65536.0;
        for (k = 0; k < 3; k++)
            rows[i][k] = v->rot[i][k] / 16384.0;
    }
}

static int draw_face(lumo_gl_shadow *sh, const lumo_raster_view *v, GLint layer, GLsizei size, float far,
                     GLsizei index_count)
{
    double rows[3][3], eye[3];
    float mvp[16];

    sh->gl.FramebufferTextureLayer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, sh->tex, 0, layer);
    if (sh->gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return -1;
    sh->gl.Viewport(0, 0, size, size);
    sh->gl.Clear(GL_DEPTH_BUFFER_BIT);                    /* 1: nothing, lit */
    view_rows(v, rows, eye);
    lumo_gl_frustum(rows, eye, v->cot_half / 65536.0, 1.0, v->znear / 65536.0, far, mvp);
    sh->gl.UniformMatrix4fv(sh->gl.GetUniformLocation(sh->prog, "u_smvp"), 1, GL_FALSE, mvp);
    sh->gl.Uniform1f(sh->gl.GetUniformLocation(sh->prog, "u_sinvfar"), 1.0f / far);
    sh->gl.DrawElements(GL_TRIANGLES, index_count, GL_UNSIGNED_INT, (const void *)0);
    return 0;
}

int lumo_gl_shadow_update(lumo_gl_shadow *sh, const lumo_raster_scene *s, GLuint vao,
                          GLsizei index_count, float scene_radius, unsigned mesh_gen)
{
    static const GLenum none = GL_NONE;
    GLsizei size = 0, layers = 0;
    uint32_t i, n = s->light_count > LUMO_MAX_LIGHTS ? LUMO_MAX_LIGHTS : s->light_count;
    unsigned f;

    if (unchanged(sh, s, mesh_gen))
        return 0;
    for (i = 0; i < n; i++) {
        key_of(&s->lights[i], &sh->key[i]);
        sh->first[i] = layers;
        layers += sh->key[i].faces;
        if (sh->key[i].size > size)
            size = sh->key[i].size;
    }
    sh->count = n;
    sh->mesh_gen = mesh_gen;
    sh->drawn = 1;
    sh->bytes = (size_t)layers * size * size * 4;
    if (layers == 0)
        return 0;
    if (allocate(sh, size, layers))
        return -1;
    sh->gl.BindFramebuffer(GL_FRAMEBUFFER, sh->fbo);
    sh->gl.DrawBuffers(1, &none);
    sh->gl.ReadBuffer(GL_NONE);
    sh->gl.Enable(GL_DEPTH_TEST);
    sh->gl.DepthFunc(GL_LESS);
    sh->gl.Disable(GL_CULL_FACE);                          /* both sides cast, as in soft */
    sh->gl.UseProgram(sh->prog);
    sh->gl.BindVertexArray(vao);
    for (i = 0; i < n; i++) {
        const drawn_key *k = &sh->key[i];
        double e = 0;
        int c;
        if (!k->faces)
            continue;
        for (c = 0; c < 3; c++)
            e += (k->face[0].eye[c] / 65536.0) * (k->face[0].eye[c] / 65536.0);
        /* beyond every point of the mesh: |p - eye| <= |eye| + |p| */
        sh->far[i] = (float)(sqrt(e) + scene_radius + 1.0);
        for (f = 0; f < k->faces; f++)
            if (draw_face(sh, &k->face[f], sh->first[i] + (GLint)f, k->size, sh->far[i], index_count))
                return -1;
    }
    return sh->gl.GetError() == GL_NO_ERROR ? 0 : -1;
}

/* Rows of a view as a GLSL mat3 whose columns are the rows (d * m gives
 * the view coordinates). */
static void rows_mat3(const lumo_raster_view *v, float *m)
{
    int i, k;

    for (i = 0; i < 3; i++)
        for (k = 0; k < 3; k++)
            m[3 * i + k] = (float)(v->rot[i][k] / 16384.0);
}

void lumo_gl_shadow_bind(lumo_gl_shadow *sh, GLuint p, const lumo_raster_scene *s, int unit)
{
    float info[4 * LUMO_MAX_LIGHTS], eye[4 * LUMO_MAX_LIGHTS], cot[LUMO_MAX_LIGHTS];
    float rot[9 * LUMO_MAX_LIGHTS], cube[9 * LUMO_RASTER_SHADOW_MAX_FACES];
    uint32_t i, n = sh->count;
    int c, have_cube = 0;

    memset(info, 0, sizeof info);
    memset(eye, 0, sizeof eye);
    memset(cot, 0, sizeof cot);
    memset(rot, 0, sizeof rot);
    memset(cube, 0, sizeof cube);
    for (i = 0; i < n && i < s->light_count; i++) {
        const drawn_key *k = &sh->key[i];
        if (!k->faces)
            continue;
        info[4 * i] = (float)sh->first[i];
        info[4 * i + 1] = (float)k->faces;
        info[4 * i + 2] = (float)k->size;
        info[4 * i + 3] = sh->far[i];
        for (c = 0; c < 3; c++)
            eye[4 * i + c] = (float)(k->face[0].eye[c] / 65536.0);
        eye[4 * i + 3] = (float)(k->face[0].znear / 65536.0);
        cot[i] = (float)(k->face[0].cot_half / 65536.0);
        rows_mat3(&k->face[0], &rot[9 * i]);
        if (k->faces == LUMO_RASTER_SHADOW_MAX_FACES && !have_cube) {
            /* every cube has the same six bases (+x -x +y -y +z -z) */
            for (c = 0; c < LUMO_RASTER_SHADOW_MAX_FACES; c++)
                rows_mat3(&k->face[c], &cube[9 * c]);
            have_cube = 1;
        }
    }
    sh->gl.UseProgram(p);
    sh->gl.Uniform4fv(sh->gl.GetUniformLocation(p, "u_sinfo"), LUMO_MAX_LIGHTS, info);
    sh->gl.Uniform4fv(sh->gl.GetUniformLocation(p, "u_seye"), LUMO_MAX_LIGHTS, eye);
    sh->gl.Uniform1fv(sh->gl.GetUniformLocation(p, "u_scot"), LUMO_MAX_LIGHTS, cot);
    sh->gl.UniformMatrix3fv(sh->gl.GetUniformLocation(p, "u_srot"), LUMO_MAX_LIGHTS, GL_FALSE, rot);
    sh->gl.UniformMatrix3fv(sh->gl.GetUniformLocation(p, "u_scube"), LUMO_RASTER_SHADOW_MAX_FACES, GL_FALSE,
                            cube);
    sh->gl.ActiveTexture(GL_TEXTURE0 + (GLenum)unit);
    sh->gl.BindTexture(GL_TEXTURE_2D_ARRAY, sh->tex);
}

size_t lumo_gl_shadow_bytes(const lumo_gl_shadow *sh)
{
    return sh ? sh->bytes : 0;
}

void lumo_gl_shadow_destroy(lumo_gl_shadow *sh)
{
    if (!sh)
        return;
    if (sh->tex)
        sh->gl.DeleteTextures(1, &sh->tex);
    if (sh->fbo)
        sh->gl.DeleteFramebuffers(1, &sh->fbo);
    if (sh->prog)
        sh->gl.DeleteProgram(sh->prog);
    free(sh);
}
