/* pack.c — the scene and IVG chunks of a package (layouts byte by byte in
 * docs/package-format.md). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "lumo/package.h"
#include "package/ivg_encode.h"
#include "package/package_write.h"

static void put_light(lumo_buf *b, const lumo_light *l)
{
    lumo_buf_u32(b, (uint32_t)l->kind);
    lumo_buf_vec3(b, l->pos);
    lumo_buf_vec3(b, l->dir);
    lumo_buf_vec3(b, l->u);
    lumo_buf_vec3(b, l->v);
    lumo_buf_f32(b, l->half_angle_deg);
    lumo_buf_f32(b, l->kind == LUMO_LIGHT_SPOT ? l->cos_half : -1.0f);
    lumo_buf_vec3(b, l->power);
}

static int pack_info(lumo_pkg_writer *w, const lumo_scene *s)
{
    lumo_buf b = {0};
    vec3 lo = v3(0, 0, 0), hi = v3(0, 0, 0);
    lumo_scene_bounds(s, &lo, &hi);
    lumo_buf_u32(&b, (uint32_t)s->nmeshes);
    lumo_buf_u32(&b, (uint32_t)s->nlights);
    lumo_buf_u32(&b, (uint32_t)lumo_scene_triangle_count(s));
    lumo_buf_u32(&b, 0);
    lumo_buf_vec3(&b, lo);
    lumo_buf_vec3(&b, hi);
    lumo_buf_vec3(&b, s->camera.eye);
    lumo_buf_vec3(&b, s->camera.target);
    lumo_buf_vec3(&b, s->camera.up);
    lumo_buf_f32(&b, s->camera.fovy_deg);
    for (size_t i = 0; i < s->nlights; i++)
        put_light(&b, &s->lights[i]);
    int rc = b.failed || s->nlights > LUMO_PKG_MAX_LIGHTS ? -1 : lumo_pkgw_add(w, LUMO_PKG_INFO, b.p, b.len);
    lumo_buf_free(&b);
    return rc;
}

/* Area-weighted vertex normals of the wound faces: what a client shades
 * with (the path tracer itself uses face normals). */
static vec3 *vertex_normals(const lumo_mesh *m)
{
    vec3 *n = calloc(m->nverts ? m->nverts : 1, sizeof *n);
    if (!n)
        return NULL;
    for (uint32_t t = 0; t < m->ntris; t++) {
        const uint32_t *ix = &m->tris[3 * t];
        vec3 a = m->pos[ix[0]];
        vec3 fn = v3_cross(v3_sub(m->pos[ix[1]], a), v3_sub(m->pos[ix[2]], a));
        for (int k = 0; k < 3; k++)
            n[ix[k]] = v3_add(n[ix[k]], fn);
    }
    for (uint32_t v = 0; v < m->nverts; v++)
        n[v] = v3_norm(n[v]);
    return n;
}

static int pack_mesh(lumo_pkg_writer *w, const lumo_mesh *m)
{
    lumo_buf b = {0};
    vec3 *n = vertex_normals(m);
    if (!n)
        return -1;
    lumo_buf_u32(&b, m->emitter ? LUMO_PKG_MESH_EMITTER : 0);
    lumo_buf_u32(&b, m->nverts);
    lumo_buf_u32(&b, m->ntris);
    lumo_buf_u32(&b, 0);
    for (uint32_t v = 0; v < m->nverts; v++) {
        lumo_buf_vec3(&b, m->pos[v]);
        lumo_buf_vec3(&b, n[v]);
        lumo_buf_vec3(&b, m->albedo[v]);
    }
    for (uint32_t i = 0; i < 3u * m->ntris; i++)
        lumo_buf_u32(&b, m->tris[i]);
    free(n);
    int rc = b.failed ? -1 : lumo_pkgw_add(w, LUMO_PKG_MESH, b.p, b.len);
    lumo_buf_free(&b);
    return rc;
}

int lumo_pack_scene(lumo_pkg_writer *w, const lumo_scene *s, int raw_meshes)
{
    if (pack_info(w, s))
        return -1;
    for (size_t i = 0; raw_meshes && i < s->nmeshes; i++)
        if (pack_mesh(w, &s->meshes[i]))
            return -1;
    return 0;
}

int lumo_pack_ivg_desc(lumo_pkg_writer *w, const lumo_bake_result *r, uint32_t spp, uint64_t seed);
int lumo_pack_ivg_desc(lumo_pkg_writer *w, const lumo_bake_result *r, uint32_t spp, uint64_t seed)
{
    lumo_buf b = {0};
    uint32_t valid = 0;
    for (size_t v = 0; v < r->nverts; v++)
        valid += r->valid[v];
    for (int a = 0; a < 3; a++)
        lumo_buf_u16(&b, (uint32_t)r->grid.dims[a]);
    lumo_buf_u16(&b, 0);
    lumo_buf_vec3(&b, r->grid.bmin);
    lumo_buf_vec3(&b, r->grid.bmax);
    lumo_buf_u32(&b, spp);
    lumo_buf_u32(&b, (uint32_t)seed);
    lumo_buf_u32(&b, (uint32_t)(seed >> 32));
    lumo_buf_u32(&b, valid);
    int rc = b.failed ? -1 : lumo_pkgw_add(w, LUMO_PKG_IVGD, b.p, b.len);
    lumo_buf_free(&b);
    return rc;
}

/* One bundle of every grid vertex in the given wire form (solid vertices as
 * solid records), through the IVG encoder (seed 000 §3.3). */
static int pack_bundle(lumo_pkg_writer *w, const lumo_bake_result *r, lumo_ivg_form form, uint32_t type)
{
    uint32_t solid = 0;
    for (size_t v = 0; v < r->nverts; v++)
        solid += !r->valid[v];
    size_t cap = lumo_ivg_bundle_bytes(form, (uint32_t)r->nverts - solid, solid);
    uint8_t *buf = malloc(cap);
    uint16_t dims[3] = {(uint16_t)r->grid.dims[0], (uint16_t)r->grid.dims[1], (uint16_t)r->grid.dims[2]};
    lumo_ivg_writer iw;
    if (!buf || lumo_ivg_writer_begin(&iw, buf, cap, form, dims)) {
        free(buf);
        return -1;
    }
    for (size_t v = 0; v < r->nverts; v++) {
        lumo_ivg_fentry e[LUMO_IVG_AXES];
        if (!r->valid[v]) {
            lumo_ivg_writer_add_solid(&iw, (uint32_t)v);
            continue;
        }
        for (int h = 0; h < LUMO_IVG_AXES; h++)
            lumo_ivg_compress((const float(*)[3]) & r->I[LUMO_BAKE_I(v, h, 0)], (lumo_ivg_axis)h, &e[h]);
        lumo_ivg_writer_add(&iw, (uint32_t)v, e);
    }
    size_t len = lumo_ivg_writer_finish(&iw);
    int rc = len ? lumo_pkgw_add(w, type, buf, len) : -1;
    free(buf);
    return rc;
}

int lumo_pack_ivg(lumo_pkg_writer *w, const lumo_bake_result *r, uint32_t spp, uint64_t seed,
                  char *err, size_t errlen)
{
    if (lumo_pack_ivg_desc(w, r, spp, seed) ||
        pack_bundle(w, r, LUMO_IVG_FORM_QUANTIZED, LUMO_PKG_IVGQ) ||
        pack_bundle(w, r, LUMO_IVG_FORM_FLOAT, LUMO_PKG_IVGF)) {
        snprintf(err, errlen, "cannot encode the IVG (out of memory)");
        return -1;
    }
    return 0;
}
