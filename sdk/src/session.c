/*
 * session.c — the client session (lumo/session.h): messages in, a drawable
 * scene out, all memory from one arena (seed 000 §4: the client refines
 * geometry and lighting as batches arrive).
 */
#include <string.h>
#include "lumo/session.h"
#include "lumo/wire.h"

enum { SLOT_EMPTY = 0, SLOT_RAW = 1, SLOT_PM = 2 };

static const lumo_session_config k_default = {{0, LUMO_SESSION_LOD_ALL}, LUMO_IVG_SMOOTH};

lumo_status lumo_session_init(lumo_session *s, const lumo_session_config *cfg, lumo_arena *arena)
{
    if (!s || !arena || (cfg && (cfg->lod.ppm > LUMO_SESSION_LOD_ALL || (cfg->ivg_flags & ~LUMO_IVG_SMOOTH))))
        return LUMO_ERR_ARG;
    memset(s, 0, sizeof *s);
    s->cfg = cfg ? *cfg : k_default;
    s->arena = arena;
    return LUMO_OK;
}

/* ---- arena needs ------------------------------------------------------------ */

/* The four arrays of a raw mesh, each rounded as the arena hands it out. */
static size_t raw_mesh_bytes(const lumo_pkg_mesh_info *mi)
{
    size_t v3 = lumo_size_mul(mi->nverts, 3), b;
    b = lumo_arena_round(lumo_size_mul(v3, sizeof(lumo_q16_16)));
    b = lumo_size_add(b, lumo_arena_round(lumo_size_mul(v3, sizeof(lumo_q1_14))));
    b = lumo_size_add(b, lumo_arena_round(lumo_size_mul(v3, sizeof(lumo_q1_14))));
    return lumo_size_add(b, lumo_arena_round(lumo_size_mul(lumo_size_mul(mi->ntris, 3), sizeof(uint32_t))));
}

/* A PRTV message holds the whole chunk: its size from the header, which
 * must fit the 32-bit cursor of the protocol. */
static lumo_status prt_need(const uint8_t *p, size_t len, size_t *bytes)
{
    size_t total, fixed;
    lumo_status st = p ? lumo_prt_chunk_size(p, len, &total, &fixed) : LUMO_ERR_ARG;
    if (st)
        return st;
    if (total > UINT32_MAX || len > total)
        return total > UINT32_MAX ? LUMO_ERR_LIMIT : LUMO_ERR_CORRUPT;
    *bytes = lumo_arena_round(total);
    return LUMO_OK;
}

lumo_status lumo_session_message_need(uint32_t type, const uint8_t *p, size_t len, size_t *bytes)
{
    lumo_pkg_mesh_info mi;
    lumo_pmesh_header h;
    lumo_ivg_desc d;
    lumo_ivg_order io;
    lumo_scene_order so;
    lumo_prt_light pl;
    lumo_status st = LUMO_OK;

    if (!bytes || (!p && len))
        return LUMO_ERR_ARG;
    *bytes = 0;
    if (type == LUMO_MSG_MESH && !(st = lumo_scene_mesh_info_decode(p, len, &mi)))
        *bytes = raw_mesh_bytes(&mi);
    else if (type == LUMO_MSG_PMSH && !(st = lumo_pmesh_read_header(p, len, &h)))
        *bytes = lumo_pmesh_arena_bytes(&h);
    else if (type == LUMO_MSG_IVGD && !(st = lumo_scene_ivg_desc_decode(p, len, &d)))
        *bytes = lumo_ivg_memory_size(&d);
    else if (type == LUMO_MSG_IVGS && !(st = lumo_ivg_order_decode(p, len, NULL, &io)))
        *bytes = lumo_arena_round(len);
    else if (type == LUMO_MSG_ORDR && !(st = lumo_scene_order_decode(p, len, UINT32_MAX, &so)))
        *bytes = lumo_arena_round(len);
    else if (type == LUMO_MSG_PRTV)
        st = prt_need(p, len, bytes);
    else if (type == LUMO_MSG_PRTL && !(st = lumo_prt_light_decode(p, len, &pl)))
        *bytes = lumo_arena_round(len);
    return st;
}

/* Adds the need of the nth chunk of a type; absent chunks add nothing. */
static lumo_status add_chunk_need(const lumo_package *pkg, uint32_t type, uint32_t nth, size_t *sum)
{
    const uint8_t *p;
    uint32_t len;
    size_t b;
    lumo_status st;

    if (lumo_package_find(pkg, type, nth, &p, &len) != LUMO_OK)
        return LUMO_OK;
    if ((st = lumo_session_message_need(type, p, len, &b)))
        return st;
    *sum = lumo_size_add(*sum, b);
    return LUMO_OK;
}

/* Progressive streams in the package; 0 means its meshes are raw. */
static uint32_t stream_count(const lumo_package *pkg)
{
    const uint8_t *p;
    uint32_t len, n = 0;

    while (lumo_package_find(pkg, LUMO_PKG_PMSH, n, &p, &len) == LUMO_OK)
        n++;
    return n;
}

lumo_status lumo_session_package_need(const lumo_package *pkg, size_t *bytes)
{
    lumo_pkg_info info;
    uint32_t i, streams;
    size_t sum = LUMO_ARENA_SLACK;
    lumo_status st;

    if (!pkg || !bytes)
        return LUMO_ERR_ARG;
    if ((st = lumo_package_info(pkg, &info)))
        return st;
    /* A session holds at most LUMO_MAX_MESHES (feed_info refuses more): a
     * hostile count must not make this walk billions of chunk lookups. */
    if (info.mesh_count > LUMO_MAX_MESHES)
        return LUMO_ERR_LIMIT;
    if ((st = add_chunk_need(pkg, LUMO_PKG_IVGD, 0, &sum)) ||
        (st = add_chunk_need(pkg, LUMO_PKG_IVGS, 0, &sum)) || (st = add_chunk_need(pkg, LUMO_PKG_ORDR, 0, &sum)))
        return st;
    streams = stream_count(pkg);
    for (i = 0; i < info.mesh_count; i++)
        if ((st = add_chunk_need(pkg, streams ? LUMO_PKG_PMSH : LUMO_PKG_MESH, i, &sum)) ||
            (st = add_chunk_need(pkg, LUMO_MSG_PRTV, i, &sum)))
            return st;
    if ((st = add_chunk_need(pkg, LUMO_MSG_PRTL, 0, &sum)))
        return st;
    if (sum == SIZE_MAX)
        return LUMO_ERR_OVERFLOW;
    *bytes = sum;
    return LUMO_OK;
}

/* ---- messages ---------------------------------------------------------------- */

static lumo_status feed_info(lumo_session *s, const uint8_t *p, size_t len)
{
    lumo_pkg_info info;
    uint32_t i;
    lumo_status st;

    if (s->have_info)
        return LUMO_ERR_STATE;
    if ((st = lumo_scene_info_decode(p, len, &info)))
        return st;
    if (info.mesh_count > LUMO_MAX_MESHES)
        return LUMO_ERR_LIMIT;
    /* The lights are unused until have_info is set, so decoding in place
     * changes nothing visible on error. */
    for (i = 0; i < info.light_count; i++)
        if ((st = lumo_scene_light_decode(p, len, i, &s->lights[i])))
            return st;
    s->info = info;
    s->have_info = 1;
    return LUMO_OK;
}

/* The empty slot a mesh message fills. */
static lumo_status empty_slot(lumo_session *s, uint32_t index, lumo_session_mesh_slot **out)
{
    if (index >= s->info.mesh_count)
        return LUMO_ERR_RANGE;
    if (s->mesh[index].kind != SLOT_EMPTY)
        return LUMO_ERR_STATE;
    *out = &s->mesh[index];
    return LUMO_OK;
}

static lumo_status feed_raw_mesh(lumo_session *s, uint32_t index, const uint8_t *p, size_t len)
{
    lumo_session_mesh_slot *slot;
    lumo_pkg_mesh_info mi;
    lumo_arena_mark mark = lumo_arena_get_mark(s->arena);
    lumo_q16_16 *pos;
    lumo_q1_14 *nrm, *alb;
    uint32_t *tris;
    lumo_status st;

    if ((st = empty_slot(s, index, &slot)) || (st = lumo_scene_mesh_info_decode(p, len, &mi)))
        return st;
    pos = lumo_arena_alloc_array(s->arena, lumo_size_mul(mi.nverts, 3), sizeof *pos);
    nrm = lumo_arena_alloc_array(s->arena, lumo_size_mul(mi.nverts, 3), sizeof *nrm);
    alb = lumo_arena_alloc_array(s->arena, lumo_size_mul(mi.nverts, 3), sizeof *alb);
    tris = lumo_arena_alloc_array(s->arena, lumo_size_mul(mi.ntris, 3), sizeof *tris);
    st = !pos || !nrm || !alb || !tris ? LUMO_ERR_NOMEM : lumo_scene_mesh_decode(p, len, pos, nrm, alb, tris);
    if (st) {
        lumo_arena_reset(s->arena, mark);
        return st;
    }
    slot->raw.vertex_count = mi.nverts;
    slot->raw.face_count = mi.ntris;
    slot->raw.positions = pos;
    slot->raw.normals = nrm;
    slot->raw.albedo = alb;
    slot->raw.triangles = tris;
    slot->kind = SLOT_RAW;
    return LUMO_OK;
}

/* The vertex count the level of detail asks of a stream with header h. */
static uint32_t lod_target(const lumo_session_lod *lod, const lumo_pmesh_header *h)
{
    uint32_t t = h->vertices;
    uint64_t rest = h->vertices - h->base_vertices;

    if (lod->vertices)
        t = lod->vertices < h->vertices ? lod->vertices : h->vertices;
    else if (lod->ppm < LUMO_SESSION_LOD_ALL)
        t = h->base_vertices + (uint32_t)((lod->ppm * rest + LUMO_SESSION_LOD_ALL - 1) / LUMO_SESSION_LOD_ALL);
    return t < h->base_vertices ? h->base_vertices : t;
}

/* One batch record: ignored past the target; the batch that crosses it is
 * stepped back to exactly the target (seed 000 §4.2: any level can be
 * shown). */
static lumo_status apply_batch(lumo_session_mesh_slot *slot, const uint8_t *rec, size_t n)
{
    lumo_pmesh_view v;
    lumo_status st;

    lumo_pmesh_get_view(&slot->pm, &v);
    if (v.vertex_count >= slot->target || lumo_pmesh_complete(&slot->pm))
        return LUMO_OK;
    if ((st = lumo_pmesh_apply(&slot->pm, rec, n)))
        return st;
    lumo_pmesh_get_view(&slot->pm, &v);
    return v.vertex_count > slot->target ? lumo_pmesh_rewind(&slot->pm, slot->target) : LUMO_OK;
}

/* A stream header, then any batch records that follow it in the message. */
static lumo_status feed_stream(lumo_session *s, uint32_t index, const uint8_t *p, size_t len)
{
    lumo_session_mesh_slot *slot;
    lumo_pmesh_header h;
    size_t at, n;
    const uint8_t *rec;
    lumo_status st;

    if ((st = empty_slot(s, index, &slot)) || (st = lumo_pmesh_read_header(p, len, &h)) ||
        (st = lumo_pmesh_init(&slot->pm, &h, s->arena)))
        return st;
    at = h.header_bytes;
    slot->target = lod_target(&s->cfg.lod, &h);
    slot->kind = SLOT_PM;
    while ((st = lumo_pmesh_next_record(p, len, &at, &rec, &n)) == LUMO_OK) {
        if ((st = apply_batch(slot, rec, n)))
            return st;
    }
    return st == LUMO_ERR_RANGE ? LUMO_OK : st;
}

static lumo_status feed_batch(lumo_session *s, uint32_t index, const uint8_t *p, size_t len)
{
    if (index >= s->info.mesh_count)
        return LUMO_ERR_RANGE;
    if (s->mesh[index].kind != SLOT_PM)
        return LUMO_ERR_STATE;
    return apply_batch(&s->mesh[index], p, len);
}

static lumo_status feed_ivg_desc(lumo_session *s, const uint8_t *p, size_t len)
{
    lumo_ivg_desc d;
    lumo_status st;

    if (s->ivg)
        return LUMO_ERR_STATE;
    if ((st = lumo_scene_ivg_desc_decode(p, len, &d)))
        return st;
    return lumo_ivg_create(&s->ivg, s->arena, &d);
}

static lumo_status feed_ivg_bundle(lumo_session *s, const uint8_t *p, size_t len)
{
    uint32_t applied;
    lumo_status st;

    if (!s->ivg)
        return LUMO_ERR_STATE;
    if ((st = lumo_ivg_apply_bundle(s->ivg, p, len, &applied)))
        return st;
    s->ivg_dirty = 1;
    s->ivg_records += applied;
    return LUMO_OK;
}

/* IVGR (and IVGU): form, 3 reserved bytes, record count, then the records.
 * IVGU runs are lighting updates (docs/dynamic.md): applied the same way,
 * but not counted as records of the streaming order (the lighting
 * channel's cursor stays the package's). */
static lumo_status feed_ivg_records(lumo_session *s, const uint8_t *p, size_t len, int counted)
{
    uint32_t applied;
    lumo_status st;

    if (!s->ivg)
        return LUMO_ERR_STATE;
    if (len < LUMO_MSG_IVGR_HEADER)
        return LUMO_ERR_TRUNCATED;
    st = lumo_ivg_apply_records(s->ivg, (lumo_ivg_form)p[0], lumo_wire_le32(p + 4), p + LUMO_MSG_IVGR_HEADER,
                                len - LUMO_MSG_IVGR_HEADER, &applied);
    if (st)
        return st;
    s->ivg_dirty = 1;
    if (counted)
        s->ivg_records += applied;
    return LUMO_OK;
}

/* A copy of a checked payload in the arena (messages may live in a
 * transport's buffer that is reused); NULL when the arena is full. */
static uint8_t *keep(lumo_session *s, const uint8_t *p, size_t len)
{
    uint8_t *copy = lumo_arena_alloc(s->arena, len ? len : 1);
    if (copy && len)
        memcpy(copy, p, len);
    return copy;
}

static lumo_status feed_ivg_order(lumo_session *s, const uint8_t *p, size_t len)
{
    lumo_ivg_order o;
    uint8_t *copy;
    lumo_status st;

    if (!s->ivg || s->have_ivg_order)
        return LUMO_ERR_STATE;
    if ((st = lumo_ivg_order_decode(p, len, lumo_ivg_get_desc(s->ivg), &o)))
        return st;
    if (!(copy = keep(s, p, len)))
        return LUMO_ERR_NOMEM;
    o.table = copy + (o.table - p);
    s->ivg_order = o;
    s->have_ivg_order = 1;
    return LUMO_OK;
}

static lumo_status feed_order(lumo_session *s, const uint8_t *p, size_t len)
{
    lumo_scene_order o;
    uint8_t *copy;
    lumo_status st;

    if (s->have_order)
        return LUMO_ERR_STATE;
    if ((st = lumo_scene_order_decode(p, len, s->info.mesh_count, &o)))
        return st;
    if (!(copy = keep(s, p, len)))
        return LUMO_ERR_NOMEM;
    o.steps = copy + (o.steps - p);
    s->order = o;
    s->have_order = 1;
    return LUMO_OK;
}

/* ---- PRT (seed 003; docs/client-session.md "PRT") ---------------------------- */

/* The whole size of the chunk whose header the slot holds (checked when
 * its PRTV came: it fits 32 bits). */
static uint32_t prt_size(const lumo_session_mesh_slot *slot)
{
    size_t total = 0, fixed = 0;

    if (slot->prt)
        (void)lumo_prt_chunk_size(slot->prt, LUMO_PRT_HEADER_SIZE, &total, &fixed);
    return (uint32_t)total;
}

/* Bytes [held, held + n) of mesh `index`'s chunk: copied behind what is
 * held (invisible until held moves), then every pass entry and vertex
 * record they complete checked; held moves only when all are good. */
static lumo_status prt_append(lumo_session_mesh_slot *slot, const uint8_t *p, size_t n)
{
    lumo_status st;

    if (n > (size_t)(prt_size(slot) - slot->prt_held))
        return LUMO_ERR_CORRUPT;
    memcpy(slot->prt + slot->prt_held, p, n);
    if ((st = lumo_prt_check_span(slot->prt, slot->prt_held, slot->prt_held + n)))
        return st;
    slot->prt_held += (uint32_t)n;
    return LUMO_OK;
}

static lumo_status feed_prt(lumo_session *s, uint32_t index, const uint8_t *p, size_t len)
{
    lumo_session_mesh_slot *slot;
    lumo_arena_mark mark = lumo_arena_get_mark(s->arena);
    size_t total, fixed;
    lumo_status st;

    if (index >= s->info.mesh_count)
        return LUMO_ERR_RANGE;
    slot = &s->mesh[index];
    if (slot->prt)
        return LUMO_ERR_STATE;
    if ((st = prt_need(p, len, &total)) || (st = lumo_prt_chunk_size(p, len, &total, &fixed)))
        return st;
    /* The transfer is per vertex of the full mesh (docs/prt.md); checked
     * when the mesh came first. */
    if ((slot->kind == SLOT_PM && lumo_wire_le32(p + 8) != slot->pm.h.vertices) ||
        (slot->kind == SLOT_RAW && lumo_wire_le32(p + 8) != slot->raw.vertex_count))
        return LUMO_ERR_CORRUPT;
    if (!(slot->prt = lumo_arena_alloc(s->arena, total)))
        return LUMO_ERR_NOMEM;
    memcpy(slot->prt, p, LUMO_PRT_HEADER_SIZE);
    slot->prt_held = LUMO_PRT_HEADER_SIZE;
    if ((st = prt_append(slot, p + LUMO_PRT_HEADER_SIZE, len - LUMO_PRT_HEADER_SIZE))) {
        slot->prt = NULL, slot->prt_held = 0;
        lumo_arena_reset(s->arena, mark);
    }
    return st;
}

/* PRTS: u32 offset = the bytes held, then the bytes that follow them. */
static lumo_status feed_prt_span(lumo_session *s, uint32_t index, const uint8_t *p, size_t len)
{
    lumo_session_mesh_slot *slot;

    if (index >= s->info.mesh_count)
        return LUMO_ERR_RANGE;
    slot = &s->mesh[index];
    if (len < LUMO_MSG_PRTS_HEADER)
        return LUMO_ERR_TRUNCATED;
    if (!slot->prt || lumo_wire_le32(p) != slot->prt_held)
        return LUMO_ERR_STATE;
    return prt_append(slot, p + LUMO_MSG_PRTS_HEADER, len - LUMO_MSG_PRTS_HEADER);
}

static lumo_status feed_prt_light(lumo_session *s, const uint8_t *p, size_t len)
{
    lumo_prt_light l;
    uint8_t *copy;
    lumo_status st;

    if (s->prtl)
        return LUMO_ERR_STATE;
    if ((st = lumo_prt_light_decode(p, len, &l)))
        return st;
    if (!(copy = keep(s, p, len)))
        return LUMO_ERR_NOMEM;
    s->prtl = copy;
    return LUMO_OK;
}

lumo_status lumo_session_feed(lumo_session *s, uint32_t type, uint32_t index, const uint8_t *p, size_t len)
{
    if (!s || !p)
        return LUMO_ERR_ARG;
    if (type == LUMO_MSG_INFO)
        return feed_info(s, p, len);
    if (!s->have_info)
        return LUMO_ERR_STATE;
    switch (type) {
    case LUMO_MSG_MESH: return feed_raw_mesh(s, index, p, len);
    case LUMO_MSG_PMSH: return feed_stream(s, index, p, len);
    case LUMO_MSG_PMSB: return feed_batch(s, index, p, len);
    case LUMO_MSG_IVGD: return feed_ivg_desc(s, p, len);
    case LUMO_MSG_IVGQ:
    case LUMO_MSG_IVGF: return feed_ivg_bundle(s, p, len);
    case LUMO_MSG_IVGR: return feed_ivg_records(s, p, len, 1);
    case LUMO_MSG_IVGU: return feed_ivg_records(s, p, len, 0);
    case LUMO_MSG_IVGS: return feed_ivg_order(s, p, len);
    case LUMO_MSG_ORDR: return feed_order(s, p, len);
    case LUMO_MSG_PRTV: return feed_prt(s, index, p, len);
    case LUMO_MSG_PRTS: return feed_prt_span(s, index, p, len);
    case LUMO_MSG_PRTL: return feed_prt_light(s, p, len);
    default:            return LUMO_ERR_UNSUPPORTED;
    }
}

/* ---- a whole package ------------------------------------------------------------ */

/* Feed the nth chunk of a type as message `index`; absent chunks are fine
 * unless `required`. */
static lumo_status feed_chunk(lumo_session *s, const lumo_package *pkg, uint32_t type, uint32_t nth,
                              int required, lumo_session_where *w)
{
    const uint8_t *p;
    uint32_t len;

    w->type = type, w->index = nth, w->batch = 0;
    if (lumo_package_find(pkg, type, nth, &p, &len) != LUMO_OK)
        return required ? LUMO_ERR_CORRUPT : LUMO_OK;
    return lumo_session_feed(s, type, nth, p, len);
}

static int has_chunk(const lumo_package *pkg, uint32_t type)
{
    const uint8_t *p;
    uint32_t len;

    return lumo_package_find(pkg, type, 0, &p, &len) == LUMO_OK;
}

lumo_status lumo_session_feed_package(lumo_session *s, const lumo_package *pkg, lumo_session_where *where)
{
    lumo_session_where local;
    lumo_session_where *w = where ? where : &local;
    uint32_t i, streams;
    lumo_status st;

    if (!s || !pkg)
        return LUMO_ERR_ARG;
    if ((st = feed_chunk(s, pkg, LUMO_PKG_INFO, 0, 1, w)) || (st = feed_chunk(s, pkg, LUMO_PKG_IVGD, 0, 0, w)) ||
        (st = feed_chunk(s, pkg, LUMO_PKG_IVGS, 0, 0, w)) || (st = feed_chunk(s, pkg, LUMO_PKG_ORDR, 0, 0, w)))
        return st;
    /* The quantized bundle is what a client receives; binary32 if only that. */
    if ((st = feed_chunk(s, pkg, has_chunk(pkg, LUMO_PKG_IVGQ) ? LUMO_PKG_IVGQ : LUMO_PKG_IVGF, 0, 0, w)))
        return st;
    streams = stream_count(pkg);
    if (streams && streams != s->info.mesh_count) {
        w->type = LUMO_PKG_PMSH, w->index = streams;
        return LUMO_ERR_CORRUPT;
    }
    for (i = 0; i < s->info.mesh_count; i++) {
        st = feed_chunk(s, pkg, streams ? LUMO_PKG_PMSH : LUMO_PKG_MESH, i, 1, w);
        if (st) {
            if (streams && s->mesh[i].kind == SLOT_PM)
                w->batch = lumo_pmesh_batches(&s->mesh[i].pm);
            return st;
        }
    }
    for (i = 0; i < s->info.mesh_count; i++)
        if ((st = feed_chunk(s, pkg, LUMO_MSG_PRTV, i, 0, w)))
            return st;
    return feed_chunk(s, pkg, LUMO_MSG_PRTL, 0, 0, w);
}

lumo_status lumo_session_set_ivg_flags(lumo_session *s, unsigned flags)
{
    if (!s || (flags & ~LUMO_IVG_SMOOTH))
        return LUMO_ERR_ARG;
    s->cfg.ivg_flags = flags;
    return LUMO_OK;
}

int lumo_session_update(lumo_session *s)
{
    if (!s || !s->ivg || !s->ivg_dirty)
        return 0;
    s->ivg_dirty = 0;
    if (lumo_ivg_received_count(s->ivg) < lumo_ivg_vertex_count(s->ivg))
        lumo_ivg_pushpull(s->ivg, s->cfg.ivg_flags);
    return 1;
}

/* ---- readers ------------------------------------------------------------------------ */

const lumo_pkg_info *lumo_session_info(const lumo_session *s)
{
    return s && s->have_info ? &s->info : NULL;
}

const lumo_pkg_light *lumo_session_lights(const lumo_session *s, uint32_t *count)
{
    if (count)
        *count = s && s->have_info ? s->info.light_count : 0;
    return s ? s->lights : NULL;
}

const lumo_ivg *lumo_session_ivg(const lumo_session *s)
{
    return s ? s->ivg : NULL;
}

const lumo_ivg_order *lumo_session_ivg_order(const lumo_session *s)
{
    return s && s->have_ivg_order ? &s->ivg_order : NULL;
}

const lumo_scene_order *lumo_session_order(const lumo_session *s)
{
    return s && s->have_order ? &s->order : NULL;
}

void lumo_session_lighting_progress(const lumo_session *s, lumo_session_lighting *out)
{
    if (!out)
        return;
    memset(out, 0, sizeof *out);
    if (!s)
        return;
    out->records = s->ivg_records;
    if (s->have_ivg_order) {
        out->rounds = s->ivg_order.rounds;
        out->rounds_held = lumo_ivg_order_rounds_in(&s->ivg_order, s->ivg_records);
    }
}

lumo_status lumo_session_mesh(const lumo_session *s, uint32_t index, lumo_pmesh_view *out)
{
    if (!s || !out)
        return LUMO_ERR_ARG;
    if (index >= LUMO_MAX_MESHES || s->mesh[index].kind == SLOT_EMPTY)
        return LUMO_ERR_RANGE;
    if (s->mesh[index].kind == SLOT_RAW)
        *out = s->mesh[index].raw;
    else
        lumo_pmesh_get_view(&s->mesh[index].pm, out);
    return LUMO_OK;
}

lumo_status lumo_session_mesh_progress(const lumo_session *s, uint32_t index, lumo_session_progress *out)
{
    const lumo_session_mesh_slot *slot;
    lumo_pmesh_view v;
    lumo_status st;

    if ((st = lumo_session_mesh(s, index, &v)))
        return st;
    slot = &s->mesh[index];
    out->progressive = slot->kind == SLOT_PM;
    out->vertices = v.vertex_count;
    out->full_vertices = out->progressive ? slot->pm.h.vertices : v.vertex_count;
    out->batches = out->progressive ? lumo_pmesh_batches(&slot->pm) : 0;
    return LUMO_OK;
}

lumo_status lumo_session_prt(const lumo_session *s, uint32_t index, lumo_prt *out)
{
    if (!s || !out)
        return LUMO_ERR_ARG;
    if (index >= LUMO_MAX_MESHES || !s->mesh[index].prt)
        return LUMO_ERR_RANGE;
    /* every unit held was checked on arrival; parse again for the view */
    return lumo_prt_parse(out, s->mesh[index].prt, s->mesh[index].prt_held);
}

void lumo_session_prt_progress(const lumo_session *s, uint32_t index, uint32_t *held, uint32_t *size)
{
    int ok = s && index < LUMO_MAX_MESHES && s->mesh[index].prt;
    if (held)
        *held = ok ? s->mesh[index].prt_held : 0;
    if (size)
        *size = ok ? prt_size(&s->mesh[index]) : 0;
}

lumo_status lumo_session_prt_layout(const lumo_session *s, uint32_t index, uint32_t *fixed, uint32_t *vertex_bytes)
{
    size_t total, f;

    if (!s || !fixed || !vertex_bytes)
        return LUMO_ERR_ARG;
    if (index >= LUMO_MAX_MESHES || !s->mesh[index].prt ||
        lumo_prt_chunk_size(s->mesh[index].prt, LUMO_PRT_HEADER_SIZE, &total, &f))
        return LUMO_ERR_RANGE;
    *fixed = (uint32_t)f;
    *vertex_bytes = (uint32_t)lumo_prt_vertex_bytes(s->mesh[index].prt[2]);
    return LUMO_OK;
}

lumo_status lumo_session_prt_light(const lumo_session *s, lumo_prt_light *out)
{
    if (!s || !out)
        return LUMO_ERR_ARG;
    if (!s->prtl)
        return LUMO_ERR_RANGE;
    return lumo_prt_light_decode(s->prtl, 4u + 12u * (size_t)s->prtl[0] * s->prtl[0], out);
}

lumo_status lumo_session_stream_header(const lumo_session *s, uint32_t index, lumo_pmesh_header *out)
{
    if (!s || !out)
        return LUMO_ERR_ARG;
    if (index >= LUMO_MAX_MESHES || s->mesh[index].kind != SLOT_PM)
        return LUMO_ERR_RANGE;
    *out = s->mesh[index].pm.h;
    return LUMO_OK;
}

/* ---- dynamic scenes ------------------------------------------------------------ */

lumo_status lumo_session_move_light(lumo_session *s, uint32_t i, const lumo_q16_16 pos[3])
{
    if (!s || !pos)
        return LUMO_ERR_ARG;
    if (!s->have_info)
        return LUMO_ERR_STATE;
    if (i >= s->info.light_count || i >= LUMO_MAX_LIGHTS)
        return LUMO_ERR_RANGE;
    memcpy(s->lights[i].pos, pos, sizeof s->lights[i].pos);
    return LUMO_OK;
}

lumo_status lumo_session_set_mesh_pose(lumo_session *s, uint32_t i, const lumo_q16_16 t[3], lumo_q16_16 yaw_deg)
{
    if (!s || !t)
        return LUMO_ERR_ARG;
    if (!s->have_info)
        return LUMO_ERR_STATE;
    if (i >= s->info.mesh_count || i >= LUMO_MAX_MESHES)
        return LUMO_ERR_RANGE;
    memcpy(s->pose[i], t, 3 * sizeof *t);
    s->pose[i][3] = yaw_deg;
    return LUMO_OK;
}

lumo_status lumo_session_mesh_pose(const lumo_session *s, uint32_t i, lumo_q16_16 t[3], lumo_q16_16 *yaw_deg)
{
    if (!s || !t || !yaw_deg)
        return LUMO_ERR_ARG;
    if (i >= LUMO_MAX_MESHES)
        return LUMO_ERR_RANGE;
    memcpy(t, s->pose[i], 3 * sizeof *t);
    *yaw_deg = s->pose[i][3];
    return LUMO_OK;
}
