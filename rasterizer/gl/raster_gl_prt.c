/*
 * raster_gl_prt.c — PRT drawn by the GL backends as the thesis draws it
 * (lumo/raster_gl_prt.h; seed 003 Ch. 4-5, Eq. 7-8; docs/prt.md "GL
 * multipass"). Desktop code: floats and heap are fine here.
 *
 * Upload: one vertex buffer (position, normal, albedo, the vertex's pass
 * and its cluster's slot in that pass, the P weights), one index buffer
 * holding the mesh's triangles (the depth pre-pass) and then, per pass,
 * every triangle with a corner in the pass (§4.3: a triangle straddling k
 * passes is drawn k times, Eq. 8). Per frame: the depth pre-pass, then per
 * pass the pass's clusters' dot products into the constant registers and
 * its triangles with additive blending into a float target, then the sum
 * tone-mapped into the lumo_gl frame.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <GL/glcorearb.h>
#include "lumo/raster_gl_prt.h"
#include "lumo/wire.h"
#include "raster_gl_api.h"
#include "raster_gl_prt_shaders.h"

/* Query objects: GL 3.3 has GL_PRIMITIVES_GENERATED, GLES 3.0 does not. */
enum { ATTR_POS, ATTR_NRM, ATTR_ALB, ATTR_PS, ATTR_W0 };
#define MAX_WVEC ((LUMO_PRT_MAX_COMPONENTS + 3) / 4)

/* One cluster as a pass holds it: which mesh's table, which cluster. */
typedef struct prt_slot {
    uint32_t mesh, cluster;
} prt_slot;

typedef struct prt_pass {
    uint32_t first_slot, slots;   /* into lumo_gl_prt.slot */
    size_t   first_index;         /* into the index buffer */
    uint32_t indices;
} prt_pass;

struct lumo_gl_prt {
    lumo_gl_api gl;
    lumo_gl *g;
    int width, height, has_query;
    unsigned np;                  /* registers per cluster: P + 1 */
    GLuint prog, resolve, vao, vbo, ebo, fbo, tex, rb_depth, query;
    uint32_t tris, passes;
    prt_pass *pass;
    prt_slot *slot;
    float *reg;                   /* 4 * LUMO_GL_PRT_REGISTERS */
    uint64_t drawn, generated;
};

/* The table, and whether the context counts primitives (query objects). */
static int load_api(lumo_gl_api *gl, lumo_gl_getproc_fn getproc, int *has_query, char *err, size_t errlen)
{
    if (lumo_gl_api_load(gl, getproc, err, errlen))
        return -1;
    *has_query = gl->GenQueries && gl->BeginQuery && gl->EndQuery && gl->GetQueryObjectuiv && gl->DeleteQueries;
    return 0;
}

/* The vertex shader for P components: NP, the weight inputs, the sum of
 * Eq. 7's per-vertex part t = M.L + sum_j w_j (B_j.L). */
static char *vertex_source(unsigned components)
{
    static const char xyzw[] = "xyzw";
    size_t cap = 1024 + sizeof lumo_gl_prt_vertex_head_glsl + sizeof lumo_gl_prt_vertex_mid_glsl
               + sizeof lumo_gl_prt_vertex_tail_glsl + 64u * components;
    char *s = malloc(cap);
    size_t n;
    unsigned j;

    if (!s)
        return NULL;
    n = (size_t)snprintf(s, cap, "#define NP %u\n%s", components + 1u, lumo_gl_prt_vertex_head_glsl);
    for (j = 0; j < (components + 3u) / 4u; j++)
        n += (size_t)snprintf(s + n, cap - n, "in vec4 a_w%u;\n", j);
    n += (size_t)snprintf(s + n, cap - n, "%s", lumo_gl_prt_vertex_mid_glsl);
    for (j = 0; j < components; j++)
        n += (size_t)snprintf(s + n, cap - n, "    t += a_w%u.%c * u_reg[b + %u].rgb;\n", j / 4u, xyzw[j % 4u],
                              j + 1u);
    snprintf(s + n, cap - n, "%s", lumo_gl_prt_vertex_tail_glsl);
    return s;
}

static int build_programs(lumo_gl_prt *p, unsigned components, char *err, size_t errlen)
{
    static const char *const attribs[4 + MAX_WVEC] = {"a_pos", "a_nrm", "a_alb", "a_ps", "a_w0", "a_w1", "a_w2",
                                                      "a_w3", "a_w4", "a_w5", "a_w6", "a_w7", "a_w8"};
    char *vs = vertex_source(components);

    if (!vs) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    p->prog = lumo_gl_program(p->g, vs, lumo_gl_prt_fragment_glsl, attribs, 4u + (components + 3u) / 4u, err,
                              errlen);
    free(vs);
    if (!p->prog)
        return -1;
    p->resolve = lumo_gl_program(p->g, lumo_gl_prt_resolve_vertex_glsl, lumo_gl_prt_resolve_fragment_glsl, NULL,
                                 0, err, errlen);
    return p->resolve ? 0 : -1;
}

/* The float target the passes add into, with its own depth buffer. */
static int make_target(lumo_gl_prt *p, char *err, size_t errlen)
{
    lumo_gl_api *gl = &p->gl;

    gl->GenFramebuffers(1, &p->fbo);
    gl->BindFramebuffer(GL_FRAMEBUFFER, p->fbo);
    gl->GenTextures(1, &p->tex);
    gl->ActiveTexture(GL_TEXTURE0);
    gl->BindTexture(GL_TEXTURE_2D, p->tex);
    gl->TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, p->width, p->height, 0, GL_RGBA, GL_FLOAT, NULL);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl->FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, p->tex, 0);
    gl->GenRenderbuffers(1, &p->rb_depth);
    gl->BindRenderbuffer(GL_RENDERBUFFER, p->rb_depth);
    gl->RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, p->width, p->height);
    gl->FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, p->rb_depth);
    if (gl->CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        snprintf(err, errlen, "a float (RGBA32F) target is not renderable here");
        return -1;
    }
    return 0;
}

/* Passes of one mesh: its highest pass number + 1. */
static uint32_t mesh_passes(const lumo_prt *prt)
{
    uint32_t k, top = 0;

    for (k = 0; k < prt->clusters; k++)
        if (lumo_prt_pass(prt, k) + 1u > top)
            top = lumo_prt_pass(prt, k) + 1u;
    return top;
}

/* Each cluster's pass and slot, the passes numbered across meshes (mesh
 * i's passes after mesh i-1's). ps: 2 per cluster of every mesh. */
static int plan_passes(lumo_gl_prt *p, const lumo_prt *prt, uint32_t meshes, uint32_t *ps, char *err,
                       size_t errlen)
{
    uint32_t i, k, s, c, base;

    for (i = 0, p->passes = 0; i < meshes; i++)
        p->passes += mesh_passes(&prt[i]);
    if (!(p->pass = calloc(p->passes + 1u, sizeof *p->pass)))
        return -1;
    for (i = 0, c = 0, base = 0; i < meshes; base += mesh_passes(&prt[i]), i++)
        for (k = 0; k < prt[i].clusters; k++, c++) {
            uint32_t q = base + lumo_prt_pass(&prt[i], k);
            ps[2 * c] = q;
            ps[2 * c + 1] = p->pass[q].slots++;
        }
    for (i = 0, s = 0; i < p->passes; s += p->pass[i].slots, i++) {
        p->pass[i].first_slot = s;
        if ((size_t)p->pass[i].slots * p->np > LUMO_GL_PRT_REGISTERS) {
            snprintf(err, errlen, "pass %u holds %u clusters: %u float4 registers, the shader has %d", i,
                     p->pass[i].slots, p->pass[i].slots * p->np, LUMO_GL_PRT_REGISTERS);
            return -1;
        }
    }
    if (!(p->slot = calloc(c + 1u, sizeof *p->slot)))
        return -1;
    for (i = 0, c = 0; i < meshes; i++)
        for (k = 0; k < prt[i].clusters; k++, c++)
            p->slot[p->pass[ps[2 * c]].first_slot + ps[2 * c + 1]] = (prt_slot){i, k};
    return 0;
}

/* The vertex buffer: 11 floats (position, normal, albedo, pass, slot) and
 * 4 * ceil(P / 4) weights per vertex; vpass gets each vertex's pass. */
static float *vertex_data(const lumo_raster_mesh *m, const lumo_prt *prt,
                          const uint32_t *counts, uint32_t meshes, const uint32_t *ps, uint32_t *vpass,
                          size_t *stride)
{
    unsigned P = prt[0].components, nw = 4u * ((P + 3u) / 4u);
    size_t st = 11u + nw, vb = lumo_prt_vertex_bytes(P);
    float *v = calloc((size_t)m->vertex_count * st + 1, sizeof *v);
    uint32_t i, j, c0 = 0, v0 = 0;

    for (i = 0; v && i < meshes; c0 += prt[i].clusters, v0 += counts[i], i++)
        for (j = 0; j < counts[i]; j++) {
            const uint8_t *r = prt[i].vertex_data + (size_t)j * vb;
            float *o = v + (size_t)(v0 + j) * st;
            const lumo_q1_14 *a = m->albedo ? &m->albedo[3 * (size_t)(v0 + j)] : m->mesh_albedo;
            uint32_t k = c0 + lumo_wire_le16(r), w;   /* < clusters: lumo_prt_parse checked */
            for (w = 0; w < 3; w++) {
                o[w] = (float)(m->pos[3 * (size_t)(v0 + j) + w] / 65536.0);
                o[3 + w] = (float)(m->normal[3 * (size_t)(v0 + j) + w] / 16384.0);
                o[6 + w] = (float)(a[w] < 0 ? 0 : a[w] / 16384.0);
            }
            o[9] = (float)ps[2 * k];
            o[10] = (float)ps[2 * k + 1];
            vpass[v0 + j] = ps[2 * k];
            for (w = 0; w < P; w++) {
                uint32_t u = lumo_wire_le16(r + 2 + 2 * w);
                o[11 + w] = (float)((int32_t)u - (int32_t)((u & 0x8000u) << 1)) / 16384.0f;
            }
        }
    *stride = st;
    return v;
}

/* The index buffer: the mesh's triangles, then per pass the triangles
 * with a corner in it (each triangle once per distinct pass among its
 * corners: Eq. 8). */
static uint32_t *index_data(lumo_gl_prt *p, const lumo_raster_mesh *m, const uint32_t *vpass, size_t *count)
{
    size_t n = 3u * (size_t)m->tri_count, at;
    uint32_t t, q, *idx, *fill = calloc(p->passes + 1u, sizeof *fill);

    for (t = 0; fill && t < m->tri_count; t++) {
        const uint32_t *c = &m->tris[3 * (size_t)t];
        uint32_t a = vpass[c[0]], b = vpass[c[1]], d = vpass[c[2]];
        fill[a]++;
        if (b != a) fill[b]++;
        if (d != a && d != b) fill[d]++;
    }
    if (!fill)
        return NULL;
    for (q = 0, at = n; q < p->passes; q++) {
        p->pass[q].first_index = at;
        p->pass[q].indices = 3u * fill[q];
        p->drawn += fill[q];
        at += 3u * (size_t)fill[q];
        fill[q] = 0;
    }
    *count = at;
    if (!(idx = malloc(at * sizeof *idx + 1))) {
        free(fill);
        return NULL;
    }
    memcpy(idx, m->tris, n * sizeof *idx);
    for (t = 0; t < m->tri_count; t++) {
        const uint32_t *c = &m->tris[3 * (size_t)t];
        uint32_t s[3] = {vpass[c[0]], vpass[c[1]], vpass[c[2]]}, k;
        for (k = 0; k < 3; k++) {
            if ((k > 0 && s[k] == s[0]) || (k > 1 && s[k] == s[1]))
                continue;
            memcpy(idx + p->pass[s[k]].first_index + 3u * fill[s[k]]++, c, 3 * sizeof *idx);
        }
    }
    free(fill);
    return idx;
}

static int check_meshes(const lumo_raster_mesh *m, const lumo_prt *prt, const uint32_t *counts, uint32_t meshes,
                        char *err, size_t errlen)
{
    uint64_t total = 0;
    uint32_t i;

    if (!meshes) {
        snprintf(err, errlen, "no PRT mesh");
        return -1;
    }
    for (i = 0; i < meshes; i++) {
        if (counts[i] > prt[i].vertices_held || prt[i].components != prt[0].components) {
            snprintf(err, errlen, "PRT mesh %u: %u vertices of %u held, %u components (mesh 0: %u)", i, counts[i],
                     prt[i].vertices_held, prt[i].components, prt[0].components);
            return -1;
        }
        total += counts[i];
    }
    if (total != m->vertex_count) {
        snprintf(err, errlen, "the PRT covers %llu vertices, the mesh has %u", (unsigned long long)total,
                 m->vertex_count);
        return -1;
    }
    return 0;
}

static int upload(lumo_gl_prt *p, const lumo_raster_mesh *m, const lumo_prt *prt, const uint32_t *counts,
                  uint32_t meshes, const uint32_t *ps)
{
    lumo_gl_api *gl = &p->gl;
    uint32_t *vpass = malloc((size_t)m->vertex_count * sizeof *vpass + 1), *idx = NULL, a;
    size_t stride = 0, nidx = 0;
    float *v = vpass ? vertex_data(m, prt, counts, meshes, ps, vpass, &stride) : NULL;

    if (v)
        idx = index_data(p, m, vpass, &nidx);
    free(vpass);
    if (!idx) {
        free(v);
        return -1;
    }
    gl->GenVertexArrays(1, &p->vao);
    gl->BindVertexArray(p->vao);
    gl->GenBuffers(1, &p->vbo);
    gl->BindBuffer(GL_ARRAY_BUFFER, p->vbo);
    gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(m->vertex_count * stride * sizeof *v), v, GL_STATIC_DRAW);
    gl->VertexAttribPointer(ATTR_POS, 3, GL_FLOAT, GL_FALSE, (GLsizei)(stride * 4), (const void *)0);
    gl->VertexAttribPointer(ATTR_NRM, 3, GL_FLOAT, GL_FALSE, (GLsizei)(stride * 4), (const void *)12);
    gl->VertexAttribPointer(ATTR_ALB, 3, GL_FLOAT, GL_FALSE, (GLsizei)(stride * 4), (const void *)24);
    gl->VertexAttribPointer(ATTR_PS, 2, GL_FLOAT, GL_FALSE, (GLsizei)(stride * 4), (const void *)36);
    for (a = 0; a < ATTR_W0 + (stride - 11u) / 4u; a++) {
        if (a >= ATTR_W0)
            gl->VertexAttribPointer(a, 4, GL_FLOAT, GL_FALSE, (GLsizei)(stride * 4),
                                    (const void *)(size_t)(44u + 16u * (a - ATTR_W0)));
        gl->EnableVertexAttribArray(a);
    }
    gl->GenBuffers(1, &p->ebo);
    gl->BindBuffer(GL_ELEMENT_ARRAY_BUFFER, p->ebo);
    gl->BufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(nidx * sizeof *idx), idx, GL_STATIC_DRAW);
    free(v);
    free(idx);
    return gl->GetError() == GL_NO_ERROR ? 0 : -1;
}

lumo_gl_prt *lumo_gl_prt_create(lumo_gl *g, const lumo_raster_mesh *m, const lumo_prt *prt,
                                const uint32_t *counts, uint32_t meshes, char *err, size_t errlen)
{
    lumo_gl_prt *p = calloc(1, sizeof *p);
    uint32_t i, clusters = 0, *ps = NULL;

    if (!p || check_meshes(m, prt, counts, meshes, err, errlen))
        goto fail;
    p->g = g;
    p->tris = m->tri_count;
    p->np = prt[0].components + 1u;
    lumo_gl_size(g, &p->width, &p->height);
    if (load_api(&p->gl, lumo_gl_getproc(g), &p->has_query, err, errlen))
        goto fail;
    p->has_query = p->has_query && !lumo_gl_gles(g);
    for (i = 0; i < meshes; i++)
        clusters += prt[i].clusters;
    p->reg = calloc(4u * LUMO_GL_PRT_REGISTERS, sizeof *p->reg);
    ps = malloc(2u * (size_t)clusters * sizeof *ps);
    if (!p->reg || !ps) {
        snprintf(err, errlen, "out of memory");
        goto fail;
    }
    if (plan_passes(p, prt, meshes, ps, err, errlen) || build_programs(p, prt[0].components, err, errlen)
        || make_target(p, err, errlen))
        goto fail;
    if (upload(p, m, prt, counts, meshes, ps)) {
        snprintf(err, errlen, "uploading the PRT mesh failed");
        goto fail;
    }
    if (p->has_query)
        p->gl.GenQueries(1, &p->query);
    free(ps);
    return p;
fail:
    free(ps);
    lumo_gl_prt_destroy(p);
    return NULL;
}

/* Pass q's clusters' dot products into the registers (Q16.16 to float):
 * u_reg[s * NP + j] = (f_r, f_g, f_b) of component j (0: the mean). */
static void upload_pass(lumo_gl_prt *p, GLint loc, uint32_t q, const lumo_q16_16 *const *frame)
{
    const prt_pass *ps = &p->pass[q];
    uint32_t s, j, c;

    for (s = 0; s < ps->slots; s++) {
        const prt_slot *sl = &p->slot[ps->first_slot + s];
        const lumo_q16_16 *f = frame[sl->mesh] + (size_t)sl->cluster * 3u * p->np;
        for (j = 0; j < p->np; j++)
            for (c = 0; c < 4; c++)
                p->reg[4u * (s * p->np + j) + c] = c < 3 ? (float)(f[c * p->np + j] / 65536.0) : 0.0f;
    }
    p->gl.Uniform4fv(loc, (GLsizei)(ps->slots * p->np), p->reg);
}

static void draw_passes(lumo_gl_prt *p, const lumo_q16_16 *const *frame)
{
    lumo_gl_api *gl = &p->gl;
    GLint pass = gl->GetUniformLocation(p->prog, "u_pass"), reg = gl->GetUniformLocation(p->prog, "u_reg");
    GLuint generated = 0;
    uint32_t q;

    gl->Uniform1f(pass, -1.0f);              /* depth pre-pass: every triangle once, no colour */
    gl->ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    gl->DrawElements(GL_TRIANGLES, (GLsizei)(3u * p->tris), GL_UNSIGNED_INT, (const void *)0);
    gl->ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl->DepthMask(GL_FALSE);
    gl->DepthFunc(GL_LEQUAL);
    gl->Enable(GL_BLEND);
    gl->BlendFunc(GL_ONE, GL_ONE);
    if (p->has_query)
        gl->BeginQuery(GL_PRIMITIVES_GENERATED, p->query);
    for (q = 0; q < p->passes; q++) {
        if (!p->pass[q].indices)
            continue;
        gl->Uniform1f(pass, (float)q);
        upload_pass(p, reg, q, frame);
        gl->DrawElements(GL_TRIANGLES, (GLsizei)p->pass[q].indices, GL_UNSIGNED_INT,
                         (const void *)(p->pass[q].first_index * sizeof(uint32_t)));
    }
    if (p->has_query) {
        gl->EndQuery(GL_PRIMITIVES_GENERATED);
        gl->GetQueryObjectuiv(p->query, GL_QUERY_RESULT, &generated);
    }
    p->generated = generated;
    gl->Disable(GL_BLEND);
    gl->DepthMask(GL_TRUE);
}

int lumo_gl_prt_draw(lumo_gl_prt *p, const lumo_raster_camera *cam, const lumo_raster_scene *s,
                     const lumo_q16_16 *const *frame, uint8_t *rgb)
{
    lumo_gl_api *gl = &p->gl;
    float mvp[16], eye[3] = {(float)(cam->eye[0] / 65536.0), (float)(cam->eye[1] / 65536.0),
                             (float)(cam->eye[2] / 65536.0)};

    lumo_gl_mvp(p->g, cam, mvp);
    gl->BindFramebuffer(GL_FRAMEBUFFER, p->fbo);
    gl->Viewport(0, 0, p->width, p->height);
    gl->ClearColor(0, 0, 0, 0);
    gl->Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    gl->Enable(GL_DEPTH_TEST);
    gl->DepthFunc(GL_LESS);
    if (s->flags & LUMO_RASTER_CULL_BACK) {
        gl->Enable(GL_CULL_FACE);
        gl->FrontFace(GL_CCW);
        gl->CullFace(GL_BACK);
    } else {
        gl->Disable(GL_CULL_FACE);
    }
    gl->UseProgram(p->prog);
    gl->UniformMatrix4fv(gl->GetUniformLocation(p->prog, "u_mvp"), 1, GL_FALSE, mvp);
    gl->Uniform3fv(gl->GetUniformLocation(p->prog, "u_eye"), 1, eye);
    gl->BindVertexArray(p->vao);
    draw_passes(p, frame);
    /* the sum, exposed and tone-mapped into the renderer's frame */
    lumo_gl_bind_target(p->g);
    gl->Disable(GL_DEPTH_TEST);
    gl->Disable(GL_CULL_FACE);
    gl->UseProgram(p->resolve);
    gl->Uniform1f(gl->GetUniformLocation(p->resolve, "u_exposure"), (float)(s->exposure / 65536.0));
    gl->Uniform1i(gl->GetUniformLocation(p->resolve, "u_acc"), 0);
    gl->ActiveTexture(GL_TEXTURE0);
    gl->BindTexture(GL_TEXTURE_2D, p->tex);
    gl->DrawArrays(GL_TRIANGLES, 0, 3);
    if (gl->GetError() != GL_NO_ERROR)
        return -1;
    return lumo_gl_read_rgb(p->g, rgb);
}

void lumo_gl_prt_get_stats(const lumo_gl_prt *p, lumo_gl_prt_stats *st)
{
    uint32_t q;

    memset(st, 0, sizeof *st);
    for (q = 0; q < p->passes; q++)
        st->passes += p->pass[q].indices != 0;
    st->triangles = p->tris;
    st->drawn = p->drawn;
    st->generated = p->generated;
}

void lumo_gl_prt_destroy(lumo_gl_prt *p)
{
    lumo_gl_api *gl;

    if (!p)
        return;
    gl = &p->gl;
    if (gl->DeleteProgram) {
        if (p->prog) gl->DeleteProgram(p->prog);
        if (p->resolve) gl->DeleteProgram(p->resolve);
        if (p->vbo) gl->DeleteBuffers(1, &p->vbo);
        if (p->ebo) gl->DeleteBuffers(1, &p->ebo);
        if (p->vao) gl->DeleteVertexArrays(1, &p->vao);
        if (p->fbo) gl->DeleteFramebuffers(1, &p->fbo);
        if (p->tex) gl->DeleteTextures(1, &p->tex);
        if (p->rb_depth) gl->DeleteRenderbuffers(1, &p->rb_depth);
        if (p->query) gl->DeleteQueries(1, &p->query);
    }
    free(p->pass);
    free(p->slot);
    free(p->reg);
    free(p);
}
