/*
 * index.c — a package mapped once and indexed for serving (serve/index.h).
 */
#include "serve/index.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#include "lumo/arena.h"
#include "lumo/net.h"
#include "lumo/prt.h"
#include "lumo/session.h"
#include "common/status_msg.h"
#include "lumo/wire.h"
#include "lumo_host/package_msg.h"
#include "lumo_host/package_check.h"

/* Offsets of every batch record of mesh i, walked with the SDK's one walk
 * over a stream; the walk must end exactly at the chunk's end with
 * batch_count records, each the one of its place (its CRC covers its
 * index). */
static lumo_status index_mesh(srv_pkg *p, uint32_t i, char *err, size_t errlen)
{
    srv_mesh_index *m = &p->mesh[i];
    const uint8_t *rec;
    size_t at, n;
    uint32_t b;
    lumo_status st;

    if ((st = lumo_package_find(&p->pkg, LUMO_PKG_PMSH, i, &m->stream, &m->len)))
        return srv_fail(err, errlen, LUMO_ERR_UNSUPPORTED, "%s: mesh %u has no progressive stream (PMSH): "
                    "lumo-server streams progressive meshes only (bake with --mesh pm)", p->path, i);
    if ((st = lumo_pmesh_read_header(m->stream, m->len, &m->h)))
        return srv_fail(err, errlen, st, "%s: mesh %u: stream header: %s", p->path, i, lumo_strerror(st));
    at = m->h.header_bytes;
    m->rec = malloc(((size_t)m->h.batch_count + 1) * sizeof *m->rec);
    if (!m->rec)
        return srv_fail(err, errlen, LUMO_ERR_NOMEM, "%s: out of memory", p->path);
    for (b = 0; b < m->h.batch_count; b++) {
        m->rec[b] = (uint32_t)at;
        if ((st = lumo_pmesh_next_record(m->stream, m->len, &at, &rec, &n)))
            return srv_fail(err, errlen, st == LUMO_ERR_RANGE ? LUMO_ERR_TRUNCATED : st,
                        "%s: mesh %u: batch record %u: %s", p->path, i, b,
                        lumo_strerror(st == LUMO_ERR_RANGE ? LUMO_ERR_TRUNCATED : st));
        if ((st = lumo_pmesh_record_check(rec, n, b)))
            return srv_fail(err, errlen, st, "%s: mesh %u: batch record %u: %s", p->path, i, b,
                            lumo_strerror(st));
        if (n > m->max_record)
            m->max_record = (uint32_t)n;
    }
    m->rec[b] = (uint32_t)at;
    if (at != m->len)
        return srv_fail(err, errlen, LUMO_ERR_CORRUPT, "%s: mesh %u: %zu bytes after the last batch record",
                    p->path, i, (size_t)m->len - at);
    return LUMO_OK;
}

/* Mesh i's PRTV chunk, if any: whole and valid (every cluster index in
 * range), for the mesh's full vertex count, its sizes for the plan. */
static lumo_status index_prt(srv_pkg *p, uint32_t i, char *err, size_t errlen)
{
    srv_mesh_index *m = &p->mesh[i];
    lumo_prt v;
    size_t total, fixed;
    lumo_status st;

    if (lumo_package_find(&p->pkg, LUMO_MSG_PRTV, i, &m->prt, &m->prt_len) != LUMO_OK) {
        m->prt = NULL;
        return LUMO_OK;
    }
    if ((st = lumo_prt_parse(&v, m->prt, m->prt_len)) || (st = lumo_prt_chunk_size(m->prt, m->prt_len, &total, &fixed)))
        return srv_fail(err, errlen, st, "%s: mesh %u: PRTV: %s", p->path, i, lumo_strerror(st));
    if (total != m->prt_len || v.vertices != m->h.vertices)
        return srv_fail(err, errlen, LUMO_ERR_CORRUPT, "%s: mesh %u: PRTV holds %u of %u vertex records for a "
                        "stream of %u vertices", p->path, i, v.vertices_held, v.vertices, m->h.vertices);
    m->prt_fixed = (uint32_t)fixed;
    m->prt_cbytes = (uint32_t)lumo_prt_cluster_bytes(v.order, v.components);
    m->prt_vbytes = (uint32_t)lumo_prt_vertex_bytes(v.components);
    p->has_prt = 1;
    return LUMO_OK;
}

/* The IVG's round table and both bundles (lumo_package_ivg_order checks the
 * table against the grid and walks both bundles' records: every round
 * starts on a record boundary). */
static lumo_status index_ivg(srv_pkg *p, char *err, size_t errlen)
{
    srv_ivg_index *g = &p->ivg;
    lumo_ivg_order o;
    const uint8_t *s;
    uint32_t n, r, f;
    lumo_status st;

    if (lumo_package_find(&p->pkg, LUMO_PKG_IVGD, 0, &s, &n) != LUMO_OK)
        return LUMO_OK;   /* no IVG: a lighting request is RANGE */
    if ((st = lumo_package_ivg_order(&p->pkg, &o)))
        return srv_fail(err, errlen, st, "%s: IVG streaming order (IVGS): %s", p->path, lumo_strerror(st));
    for (f = 0; f < 2; f++) {
        uint32_t type = f == LUMO_IVG_FORM_QUANTIZED ? LUMO_PKG_IVGQ : LUMO_PKG_IVGF;
        if ((st = lumo_package_find(&p->pkg, type, 0, &g->bundle[f], &g->bundle_len[f])))
            return srv_fail(err, errlen, LUMO_ERR_CORRUPT, "%s: no %s bundle", p->path, f ? "IVGQ" : "IVGF");
    }
    g->rounds = o.rounds;
    g->records = o.records;
    g->first = malloc(((size_t)o.rounds + 1) * sizeof *g->first);
    g->off[0] = malloc(((size_t)o.rounds + 1) * sizeof *g->off[0]);
    g->off[1] = malloc(((size_t)o.rounds + 1) * sizeof *g->off[1]);
    if (!g->first || !g->off[0] || !g->off[1])
        return srv_fail(err, errlen, LUMO_ERR_NOMEM, "%s: out of memory", p->path);
    for (r = 0; r <= o.rounds; r++) {
        g->first[r] = lumo_ivg_order_first(&o, r);
        for (f = 0; f < 2; f++)
            g->off[f][r] = lumo_ivg_order_offset(&o, (lumo_ivg_form)f, r);
    }
    for (f = 0; f < 2; f++)
        if (g->off[f][0] != SRV_IVG_BUNDLE_HEAD || g->off[f][o.rounds] != g->bundle_len[f])
            return srv_fail(err, errlen, LUMO_ERR_CORRUPT, "%s: the round table does not cover the %s bundle",
                        p->path, f ? "IVGQ" : "IVGF");
    g->present = 1;
    return LUMO_OK;
}

lumo_status srv_welcome_build(srv_pkg *p, const lumo_net_msg *msgs, uint32_t count, char *err, size_t errlen)
{
    size_t need = LUMO_ARENA_SLACK, cap = LUMO_NET_OVERHEAD + 12;
    uint32_t i;
    lumo_status st;

    for (i = 0; i < count; i++) {
        size_t b;
        if ((st = lumo_session_message_need(msgs[i].type, msgs[i].data, msgs[i].len, &b)))
            return srv_fail(err, errlen, st, "%s: descriptor %u: %s", p->path, i, lumo_strerror(st));
        need += b;
        cap += 12 + ((msgs[i].len + 3u) & ~(size_t)3);
    }
    if (need > UINT32_MAX || cap > LUMO_NET_OVERHEAD + (size_t)LUMO_NET_MAX_PAYLOAD)
        return srv_fail(err, errlen, LUMO_ERR_LIMIT, "%s: the scene's descriptors are too large to send", p->path);
    p->arena_need = (uint32_t)need;
    if (!(p->welcome = malloc(cap)))
        return srv_fail(err, errlen, LUMO_ERR_NOMEM, "%s: out of memory", p->path);
    if ((st = lumo_net_welcome_encode(p->id, p->arena_need, msgs, count, p->welcome, cap, &p->welcome_len)))
        return srv_fail(err, errlen, st, "%s: WELCOME: %s", p->path, lumo_strerror(st));
    return LUMO_OK;
}

/* The descriptors of WELCOME (docs/protocol.md §2): INFO, each stream's
 * header, IVGD and IVGS, then ORDR when present; with prt (§10) each
 * mesh's PRTV header and the PRTL after them. */
static lumo_status build_welcome(srv_pkg *p, int prt, char *err, size_t errlen)
{
    lumo_net_msg msgs[LUMO_NET_MAX_WELCOME_MSGS];
    uint32_t count = 0, i;
    const uint8_t *d;
    uint32_t n;

    if (lumo_package_find(&p->pkg, LUMO_PKG_INFO, 0, &d, &n))
        return srv_fail(err, errlen, LUMO_ERR_CORRUPT, "%s: no INFO chunk", p->path);
    msgs[count++] = (lumo_net_msg){LUMO_PKG_INFO, 0, n, d};
    for (i = 0; i < p->mesh_count; i++)
        msgs[count++] = (lumo_net_msg){LUMO_PKG_PMSH, i, p->mesh[i].h.header_bytes, p->mesh[i].stream};
    if (p->ivg.present) {
        if (lumo_package_find(&p->pkg, LUMO_PKG_IVGD, 0, &d, &n) == LUMO_OK)
            msgs[count++] = (lumo_net_msg){LUMO_PKG_IVGD, 0, n, d};
        if (lumo_package_find(&p->pkg, LUMO_PKG_IVGS, 0, &d, &n) == LUMO_OK)
            msgs[count++] = (lumo_net_msg){LUMO_PKG_IVGS, 0, n, d};
    }
    if (lumo_package_find(&p->pkg, LUMO_PKG_ORDR, 0, &d, &n) == LUMO_OK)
        msgs[count++] = (lumo_net_msg){LUMO_PKG_ORDR, 0, n, d};
    for (i = 0; prt && i < p->mesh_count; i++)
        if (p->mesh[i].prt)
            msgs[count++] = (lumo_net_msg){LUMO_MSG_PRTV, i, LUMO_PRT_HEADER_SIZE, p->mesh[i].prt};
    if (prt && lumo_package_find(&p->pkg, LUMO_MSG_PRTL, 0, &d, &n) == LUMO_OK)
        msgs[count++] = (lumo_net_msg){LUMO_MSG_PRTL, 0, n, d};
    return srv_welcome_build(p, msgs, count, err, errlen);
}

/* Both WELCOMEs: the PRT one first, kept aside, then the plain one. */
static lumo_status build_welcomes(srv_pkg *p, char *err, size_t errlen)
{
    lumo_status st;

    if (p->has_prt) {
        if ((st = build_welcome(p, 1, err, errlen)))
            return st;
        p->welcome_prt = p->welcome, p->welcome_prt_len = p->welcome_len, p->arena_need_prt = p->arena_need;
        p->welcome = NULL;
    }
    return build_welcome(p, 0, err, errlen);
}

lumo_status srv_pkg_open(srv_pkg *p, const char *path, char *err, size_t errlen)
{
    struct stat sb;
    lumo_pkg_info info;
    const char *slash;
    void *map;
    uint32_t i;
    int fd;
    lumo_status st;

    memset(p, 0, sizeof *p);
    if ((fd = open(path, O_RDONLY | O_CLOEXEC)) < 0)
        return srv_fail(err, errlen, LUMO_ERR_IO, "%s: %s", path, strerror(errno));
    if (fstat(fd, &sb) < 0 || !S_ISREG(sb.st_mode) || sb.st_size <= 0) {
        int e = errno;
        close(fd);
        return srv_fail(err, errlen, LUMO_ERR_IO, "%s: %s", path,
                    sb.st_size <= 0 && !e ? "empty or not a regular file" : strerror(e));
    }
    map = mmap(NULL, (size_t)sb.st_size, PROT_READ, MAP_SHARED, fd, 0);
    close(fd);
    if (map == MAP_FAILED)
        return srv_fail(err, errlen, LUMO_ERR_IO, "%s: mmap: %s", path, strerror(errno));
    p->map = map;
    p->size = (size_t)sb.st_size;
    if (!(p->path = strdup(path))) {
        srv_pkg_close(p);
        return srv_fail(err, errlen, LUMO_ERR_NOMEM, "%s: out of memory", path);
    }
    slash = strrchr(p->path, '/');
    p->name = slash ? slash + 1 : p->path;

    if ((st = lumo_package_open(&p->pkg, p->map, p->size))) {
        char why[160];
        /* "package version 1: re-bake it with this lumo-bake", as every tool says it */
        srv_fail(err, errlen, st, "%s: %s", path, host_package_strerror(p->map, p->size, st, why, sizeof why));
        srv_pkg_close(p);
        return st;
    }
    char why[300];
    if ((st = host_package_check(&p->pkg, HOST_PKG_NEED_INFO | HOST_PKG_DEEP, why, sizeof why))) {
        srv_fail(err, errlen, st, "%s: %s", path, why);
        goto failed;
    }
    p->id = lumo_wire_le32(p->map + 20);
    if ((st = lumo_package_info(&p->pkg, &info))) {
        srv_fail(err, errlen, st, "%s: INFO: %s", path, lumo_strerror(st));
        goto failed;
    }
    p->mesh_count = info.mesh_count;
    if (p->mesh_count > LUMO_MAX_MESHES) {
        st = srv_fail(err, errlen, LUMO_ERR_LIMIT, "%s: %u meshes, more than LUMO_MAX_MESHES (%u)", path,
                  p->mesh_count, (unsigned)LUMO_MAX_MESHES);
        goto failed;
    }
    if (p->mesh_count && !(p->mesh = calloc(p->mesh_count, sizeof *p->mesh))) {
        st = srv_fail(err, errlen, LUMO_ERR_NOMEM, "%s: out of memory", path);
        goto failed;
    }
    for (i = 0; i < p->mesh_count; i++)
        if ((st = index_mesh(p, i, err, errlen)) || (st = index_prt(p, i, err, errlen)))
            goto failed;
    if ((st = index_ivg(p, err, errlen)) || (st = build_welcomes(p, err, errlen)))
        goto failed;
    return LUMO_OK;
failed:
    srv_pkg_close(p);
    return st;
}

void srv_pkg_close(srv_pkg *p)
{
    uint32_t i;

    if (p->mesh)
        for (i = 0; i < p->mesh_count; i++)
            free(p->mesh[i].rec);
    free(p->mesh);
    free(p->ivg.first);
    free(p->ivg.off[0]);
    free(p->ivg.off[1]);
    free(p->welcome);
    free(p->welcome_prt);
    if (p->map)
        munmap((void *)p->map, p->size);
    free(p->path);
    memset(p, 0, sizeof *p);
}
