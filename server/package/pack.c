/* pack.c — the scene and IVG chunks of a package (layouts byte by byte in
 * docs/package-format.md). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "lumo/package.h"
#include "lumo/pmesh.h"
#include "package/ivg_encode.h"
#include "package/ivg_order.h"
#include "package/package_write.h"

static void put_light(srv_buf *b, const srv_light *l)
{
    srv_buf_u32(b, (uint32_t)l->kind);
    srv_buf_vec3(b, l->pos);
    srv_buf_vec3(b, l->dir);
    srv_buf_vec3(b, l->u);
    srv_buf_vec3(b, l->v);
    srv_buf_f32(b, l->half_angle_deg);
    srv_buf_f32(b, l->kind == LUMO_LIGHT_SPOT ? l->cos_half : -1.0f);
    srv_buf_vec3(b, l->power);
}

static lumo_status pack_info(srv_pkg_writer *w, const srv_scene *s)
{
    srv_buf b = {0};
    vec3 lo = v3(0, 0, 0), hi = v3(0, 0, 0);
    srv_scene_bounds(s, &lo, &hi);
    srv_buf_u32(&b, (uint32_t)s->nmeshes);
    srv_buf_u32(&b, (uint32_t)s->nlights);
    srv_buf_u32(&b, (uint32_t)srv_scene_triangle_count(s));
    srv_buf_u32(&b, 0);
    srv_buf_vec3(&b, lo);
    srv_buf_vec3(&b, hi);
    srv_buf_vec3(&b, s->camera.eye);
    srv_buf_vec3(&b, s->camera.target);
    srv_buf_vec3(&b, s->camera.up);
    srv_buf_f32(&b, s->camera.fovy_deg);
    for (size_t i = 0; i < s->nlights; i++)
        put_light(&b, &s->lights[i]);
    lumo_status rc = b.failed ? LUMO_ERR_NOMEM
                     : s->nlights > LUMO_MAX_LIGHTS ? LUMO_ERR_LIMIT
                     : srv_pkgw_add(w, LUMO_PKG_INFO, b.p, b.len);
    srv_buf_free(&b);
    return rc;
}

/* Area-weighted vertex normals of the wound faces: what a client shades
 * with (the path tracer itself uses face normals). */
static vec3 *vertex_normals(const srv_mesh *m)
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

static lumo_status pack_mesh(srv_pkg_writer *w, const srv_mesh *m)
{
    srv_buf b = {0};
    vec3 *n = vertex_normals(m);
    if (!n)
        return LUMO_ERR_NOMEM;
    srv_buf_u32(&b, m->emitter ? LUMO_PKG_MESH_EMITTER : 0);
    srv_buf_u32(&b, m->nverts);
    srv_buf_u32(&b, m->ntris);
    srv_buf_u32(&b, 0);
    for (uint32_t v = 0; v < m->nverts; v++) {
        srv_buf_vec3(&b, m->pos[v]);
        srv_buf_vec3(&b, n[v]);
        srv_buf_vec3(&b, m->albedo[v]);
    }
    for (uint32_t i = 0; i < 3u * m->ntris; i++)
        srv_buf_u32(&b, m->tris[i]);
    free(n);
    lumo_status rc = b.failed ? LUMO_ERR_NOMEM : srv_pkgw_add(w, LUMO_PKG_MESH, b.p, b.len);
    srv_buf_free(&b);
    return rc;
}

lumo_status srv_pack_scene(srv_pkg_writer *w, const srv_scene *s, int raw_meshes)
{
    lumo_status st = pack_info(w, s);
    for (size_t i = 0; !st && raw_meshes && i < s->nmeshes; i++)
        st = pack_mesh(w, &s->meshes[i]);
    return st;
}

lumo_status srv_pack_ivg_desc(srv_pkg_writer *w, const srv_bake_result *r, uint32_t spp,
                              uint64_t seed);
lumo_status srv_pack_ivg_desc(srv_pkg_writer *w, const srv_bake_result *r, uint32_t spp,
                              uint64_t seed)
{
    srv_buf b = {0};
    uint32_t valid = 0;
    for (size_t v = 0; v < r->nverts; v++)
        valid += r->valid[v];
    for (int a = 0; a < 3; a++)
        srv_buf_u16(&b, (uint32_t)r->grid.dims[a]);
    srv_buf_u16(&b, 0);
    srv_buf_vec3(&b, r->grid.bmin);
    srv_buf_vec3(&b, r->grid.bmax);
    srv_buf_u32(&b, spp);
    srv_buf_u32(&b, (uint32_t)seed);
    srv_buf_u32(&b, (uint32_t)(seed >> 32));
    srv_buf_u32(&b, valid);
    lumo_status rc = b.failed ? LUMO_ERR_NOMEM : srv_pkgw_add(w, LUMO_PKG_IVGD, b.p, b.len);
    srv_buf_free(&b);
    return rc;
}

/* One bundle of every grid vertex in the given wire form (solid vertices as
 * solid records), through the IVG encoder (seed 000 §3.3), its records in
 * the streaming order; offsets[r] gets the byte offset of round r in the
 * payload (rounds + 1 entries, the last = the length). */
static lumo_status pack_bundle(srv_pkg_writer *w, const srv_bake_result *r, const srv_ivg_order *ord,
                               lumo_ivg_form form, uint32_t type, uint32_t *offsets)
{
    uint32_t solid = 0;
    for (size_t v = 0; v < r->nverts; v++)
        solid += !r->valid[v];
    size_t cap = srv_ivg_bundle_bytes(form, (uint32_t)r->nverts - solid, solid);
    uint8_t *buf = cap <= UINT32_MAX ? malloc(cap) : NULL;
    uint16_t dims[3] = {(uint16_t)r->grid.dims[0], (uint16_t)r->grid.dims[1], (uint16_t)r->grid.dims[2]};
    srv_ivg_writer iw;
    lumo_status st = buf ? srv_ivg_writer_begin(&iw, buf, cap, form, dims) : LUMO_ERR_NOMEM;
    if (st) {
        free(buf);
        return st;
    }
    uint32_t round = 0;
    for (uint32_t i = 0; i < ord->count; i++) {
        uint32_t v = ord->vertex[i];
        srv_ivg_fentry e[LUMO_IVG_AXES];
        while (round <= ord->rounds && ord->round_first[round] == i)
            offsets[round++] = (uint32_t)iw.len;
        if (!r->valid[v]) {
            srv_ivg_writer_add_solid(&iw, v);
            continue;
        }
        for (int h = 0; h < LUMO_IVG_AXES; h++)
            srv_ivg_compress((const float(*)[3]) & r->I[SRV_BAKE_I(v, h, 0)], (lumo_ivg_axis)h, &e[h]);
        srv_ivg_writer_add(&iw, v, e);
    }
    offsets[ord->rounds] = (uint32_t)iw.len;
    size_t len = srv_ivg_writer_finish(&iw);
    lumo_status rc = len ? srv_pkgw_add(w, type, buf, len) : iw.error;
    free(buf);
    return rc;
}

/* IVGS: the order's seed, axis, slices, rounds, then per round its first
 * record and its offsets in the IVGQ and IVGF payloads. */
static lumo_status pack_order(srv_pkg_writer *w, const srv_ivg_order *ord, uint64_t seed, const uint32_t *qoff,
                              const uint32_t *foff)
{
    srv_buf b = {0};
    uint8_t axis[4] = {(uint8_t)ord->axis, 0, 0, 0};
    srv_buf_u32(&b, (uint32_t)seed);
    srv_buf_u32(&b, (uint32_t)(seed >> 32));
    srv_buf_put(&b, axis, 4);
    srv_buf_u32(&b, ord->slices);
    srv_buf_u32(&b, ord->rounds);
    for (uint32_t r = 0; r <= ord->rounds; r++)
        srv_buf_u32(&b, ord->round_first[r]);
    for (uint32_t r = 0; r <= ord->rounds; r++)
        srv_buf_u32(&b, qoff[r]);
    for (uint32_t r = 0; r <= ord->rounds; r++)
        srv_buf_u32(&b, foff[r]);
    lumo_status rc = b.failed ? LUMO_ERR_NOMEM : srv_pkgw_add(w, LUMO_PKG_IVGS, b.p, b.len);
    srv_buf_free(&b);
    return rc;
}

lumo_status srv_pack_ivg(srv_pkg_writer *w, const srv_bake_result *r, uint32_t spp, uint64_t seed,
                         char *err, size_t errlen)
{
    uint16_t dims[3] = {(uint16_t)r->grid.dims[0], (uint16_t)r->grid.dims[1], (uint16_t)r->grid.dims[2]};
    srv_ivg_order ord;
    lumo_status st = srv_pack_ivg_desc(w, r, spp, seed);
    if (!st)
        st = srv_ivg_order_make(dims, seed, &ord);
    if (st) {
        snprintf(err, errlen, "cannot encode the IVG (out of memory)");
        return st;
    }
    uint32_t *qoff = malloc(sizeof *qoff * (ord.rounds + 1u)), *foff = malloc(sizeof *foff * (ord.rounds + 1u));
    st = qoff && foff ? LUMO_OK : LUMO_ERR_NOMEM;
    if (!st)
        st = pack_bundle(w, r, &ord, LUMO_IVG_FORM_QUANTIZED, LUMO_PKG_IVGQ, qoff);
    if (!st)
        st = pack_bundle(w, r, &ord, LUMO_IVG_FORM_FLOAT, LUMO_PKG_IVGF, foff);
    if (!st)
        st = pack_order(w, &ord, seed, qoff, foff);
    if (st)
        snprintf(err, errlen, "cannot encode the IVG (%s)", st == LUMO_ERR_NOMEM ? "out of memory" : lumo_strerror(st));
    free(qoff);
    free(foff);
    srv_ivg_order_free(&ord);
    return st;
}

/* ---- ORDR: the recommended interleaving ------------------------------------ */

typedef struct order_list {
    lumo_scene_step step[LUMO_MAX_MESHES + 1];
    uint32_t        n;
} order_list;

static void add_step(order_list *l, uint32_t channel, uint32_t mesh, uint32_t amount)
{
    l->step[l->n++] = (lumo_scene_step){channel, mesh, amount};
}

/* lumo-bake's default order (docs/package-format.md "ORDR"): the prefix is
 * every base mesh, then the corners (lighting round 0); the cycle is one
 * batch of every mesh that has more, then ceil((R - 1) / B) lighting rounds
 * (at least 1; B the most batches after a base mesh), so that the lighting
 * ends no later than the longest stream. */
static void default_order(const lumo_pmesh_header *h, uint32_t meshes, uint32_t rounds, order_list *prefix,
                          order_list *cycle)
{
    uint32_t most = 0;
    prefix->n = cycle->n = 0;
    for (uint32_t m = 0; m < meshes; m++) {
        add_step(prefix, LUMO_CHANNEL_GEOMETRY, m, h[m].base_vertices);
        if (h[m].batch_count > 1u) {
            add_step(cycle, LUMO_CHANNEL_GEOMETRY, m, h[m].batch_vertices);
            most = h[m].batch_count - 1u > most ? h[m].batch_count - 1u : most;
        }
    }
    if (rounds >= 1u)
        add_step(prefix, LUMO_CHANNEL_LIGHTING, 0, 1);
    if (rounds > 1u)
        add_step(cycle, LUMO_CHANNEL_LIGHTING, 0, most ? (rounds - 1u + most - 1u) / most : 1u);
}

static void put_steps(srv_buf *b, const order_list *l)
{
    for (uint32_t i = 0; i < l->n; i++) {
        uint8_t head[4] = {(uint8_t)l->step[i].channel, 0, 0, 0};
        srv_buf_put(b, head, 4);
        srv_buf_u32(b, l->step[i].mesh);
        srv_buf_u32(b, l->step[i].amount);
    }
}

lumo_status srv_pack_order(srv_pkg_writer *w)
{
    lumo_pmesh_header h[LUMO_MAX_MESHES];
    uint32_t meshes = 0, rounds = 0;
    for (size_t i = 0; i < w->n; i++) {
        const srv_buf *c = &w->chunks[i].data;
        if (w->chunks[i].type == LUMO_PKG_PMSH) {
            if (meshes == LUMO_MAX_MESHES)
                return LUMO_ERR_LIMIT;
            lumo_status st = lumo_pmesh_read_header(c->p, c->len, &h[meshes++]);
            if (st)
                return st;
        } else if (w->chunks[i].type == LUMO_PKG_IVGS && c->len >= LUMO_IVG_ORDER_HEADER) {
            rounds = c->p[16] | c->p[17] << 8 | c->p[18] << 16 | (uint32_t)c->p[19] << 24;
        }
    }
    order_list prefix, cycle;
    srv_buf b = {0};
    default_order(h, meshes, rounds, &prefix, &cycle);
    srv_buf_u32(&b, prefix.n);
    srv_buf_u32(&b, cycle.n);
    put_steps(&b, &prefix);
    put_steps(&b, &cycle);
    lumo_status rc = b.failed ? LUMO_ERR_NOMEM : srv_pkgw_add(w, LUMO_PKG_ORDR, b.p, b.len);
    srv_buf_free(&b);
    return rc;
}
