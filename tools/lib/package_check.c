/* package_check.c — lumo_host/package_check.h: INFO and its lights, IVGD,
 * IVGS, ORDR and each mesh's PMSH header or MESH counts, through the SDK. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "lumo/arena.h"
#include "lumo/pmesh.h"
#include "lumo/wire.h"
#include "lumo_host/package_check.h"

static const char *const k_kinds[] = {"point", "spot", "directional", "area"};

static lumo_status check_lights(const uint8_t *p, uint32_t len, const lumo_pkg_info *in, char *buf, size_t n)
{
    for (uint32_t i = 0; i < in->light_count; i++) {
        lumo_pkg_light l;
        lumo_status st = lumo_scene_light_decode(p, len, i, &l);
        if (!st)
            continue;
        uint32_t kind = lumo_wire_le32(p + 80 + 72 * (size_t)i);
        if (st == LUMO_ERR_UNSUPPORTED)
            snprintf(buf, n, "INFO light %u of %u: unknown kind %u (0 point, 1 spot, 2 directional, 3 area)", i,
                     in->light_count, kind);
        else
            snprintf(buf, n, "INFO light %u of %u (%s): %s (finite values, unit direction, cosine in [-1, 1], "
                     "power >= 0; docs/package-format.md \"INFO\")", i, in->light_count,
                     kind < 4 ? k_kinds[kind] : "?", lumo_strerror(st));
        return st;
    }
    return LUMO_OK;
}

lumo_status host_info_check(const uint8_t *p, uint32_t len, lumo_pkg_info *in, char *buf, size_t n)
{
    lumo_status st = lumo_scene_info_decode(p, len, in);
    if (st) {
        snprintf(buf, n, "INFO (%u bytes, %u lights declared): %s (at most %u lights; bounds and camera finite, "
                 "field of view in (0, 180) degrees, eye off the target, up neither zero nor along the view)", len,
                 len >= 8 ? lumo_wire_le32(p + 4) : 0, lumo_strerror(st), (unsigned)LUMO_MAX_LIGHTS);
        return st;
    }
    return check_lights(p, len, in, buf, n);
}

static lumo_status check_info(const lumo_package *pkg, lumo_pkg_info *in, int need_info, char *buf, size_t n)
{
    const uint8_t *p;
    uint32_t len;
    if (lumo_package_find(pkg, LUMO_PKG_INFO, 0, &p, &len)) {
        if (need_info)
            snprintf(buf, n, "no INFO chunk, so no scene to draw (camera, lights); a package from lumo-pm build "
                     "holds a mesh stream only: see it with lumo-inspect --lod N --ply OUT.ply, or bake the model "
                     "into a scene with lumo-bake");
        return need_info ? LUMO_ERR_CORRUPT : LUMO_OK;
    }
    return host_info_check(p, len, in, buf, n);
}

/* The descriptor's raw fields, so the reader sees what was refused. */
lumo_status host_ivgd_check(const uint8_t *p, uint32_t len, lumo_ivg_desc *d, char *buf, size_t n)
{
    lumo_status st = lumo_scene_ivg_desc_decode(p, len, d);
    float f[6];
    if (!st)
        return LUMO_OK;
    if (len != 48) {
        snprintf(buf, n, "IVGD: %u bytes, the descriptor has 48: %s", len, lumo_strerror(st));
        return st;
    }
    for (int i = 0; i < 6; i++) {
        uint32_t w = lumo_wire_le32(p + 8 + 4 * i);
        memcpy(&f[i], &w, 4);
    }
    snprintf(buf, n, "IVGD: grid %ux%ux%u over (%g, %g, %g)-(%g, %g, %g): %s (each dimension in [%u, %u], "
             "the box finite with min < max)", lumo_wire_le16(p), lumo_wire_le16(p + 2), lumo_wire_le16(p + 4),
             f[0], f[1], f[2], f[3], f[4], f[5], lumo_strerror(st), (unsigned)LUMO_IVG_MIN_DIM,
             (unsigned)LUMO_IVG_MAX_DIM);
    return st;
}

static lumo_status check_ivgd(const lumo_package *pkg, char *buf, size_t n)
{
    const uint8_t *p;
    uint32_t len;
    lumo_ivg_desc d;
    return lumo_package_find(pkg, LUMO_PKG_IVGD, 0, &p, &len) ? LUMO_OK : host_ivgd_check(p, len, &d, buf, n);
}

static lumo_status check_orders(const lumo_package *pkg, int have_info, char *buf, size_t n)
{
    const uint8_t *p;
    uint32_t len;
    lumo_ivg_order io;
    lumo_scene_order so;
    lumo_status st;
    if (!lumo_package_find(pkg, LUMO_PKG_IVGS, 0, &p, &len) && (st = lumo_package_ivg_order(pkg, &io))) {
        snprintf(buf, n, "IVGS (IVG streaming order, %u bytes): %s", len, lumo_strerror(st));
        return st;
    }
    if (have_info && !lumo_package_find(pkg, LUMO_PKG_ORDR, 0, &p, &len) && (st = lumo_package_order(pkg, &so))) {
        snprintf(buf, n, "ORDR (streaming order, %u bytes): %s", len, lumo_strerror(st));
        return st;
    }
    return LUMO_OK;
}

/* Mesh i: its PMSH stream header when the package has streams, else its MESH counts. */
static lumo_status check_mesh(const lumo_package *pkg, uint32_t i, int streams, char *buf, size_t n)
{
    const uint8_t *p;
    uint32_t len;
    lumo_pmesh_header h;
    lumo_pkg_mesh_info mi;
    lumo_status st;
    const char *what = streams ? "PMSH" : "MESH";
    if (lumo_package_find(pkg, streams ? LUMO_PKG_PMSH : LUMO_PKG_MESH, i, &p, &len)) {
        snprintf(buf, n, "mesh %u: no %s chunk (INFO counts the meshes)", i, what);
        return LUMO_ERR_CORRUPT;
    }
    st = streams ? lumo_pmesh_read_header(p, len, &h) : lumo_package_mesh_info(pkg, i, &mi);
    if (st)
        snprintf(buf, n, "%s %u (%u bytes): %s", what, i, len, lumo_strerror(st));
    return st;
}

void host_package_where(const lumo_session_where *w, lumo_status st, char *buf, size_t n)
{
    if (w->type == LUMO_PKG_PMSH)
        snprintf(buf, n, "progressive mesh %u, batch %u: %s", w->index, w->batch, lumo_strerror(st));
    else if (w->type == LUMO_PKG_MESH)
        snprintf(buf, n, "MESH chunk %u: %s (finite positions, unit normals, albedo in [0, 1], indices < V)",
                 w->index, lumo_strerror(st));
    else if (w->type == LUMO_PKG_INFO)
        snprintf(buf, n, "INFO: %s", lumo_strerror(st));
    else
        snprintf(buf, n, "IVG chunk %c%c%c%c: %s", (char)w->type, (char)(w->type >> 8), (char)(w->type >> 16),
                 (char)(w->type >> 24), lumo_strerror(st));
}

/* The whole package through a client session, as lumo-render feeds it. */
static lumo_status check_deep(const lumo_package *pkg, char *buf, size_t n)
{
    static lumo_session ses;   /* 21 KB: not on the stack */
    lumo_session_where w = {0, 0, 0};
    lumo_arena arena;
    size_t bytes;
    void *mem;
    lumo_status st = lumo_session_package_need(pkg, &bytes);
    if (st) {
        snprintf(buf, n, "session memory: %s", lumo_strerror(st));
        return st;
    }
    if (!(mem = malloc(bytes ? bytes : 1))) {
        snprintf(buf, n, "no memory for a %zu-byte session arena", bytes);
        return LUMO_ERR_NOMEM;
    }
    lumo_arena_init(&arena, mem, bytes);
    if ((st = lumo_session_init(&ses, NULL, &arena)) || (st = lumo_session_feed_package(&ses, pkg, &w)))
        host_package_where(&w, st, buf, n);
    free(mem);
    return st;
}

lumo_status host_package_check(const lumo_package *pkg, unsigned flags, char *buf, size_t n)
{
    int need_info = (flags & HOST_PKG_NEED_INFO) != 0;
    const uint8_t *p;
    uint32_t len;
    lumo_pkg_info in = {0};
    lumo_status st;
    int have_info = !lumo_package_find(pkg, LUMO_PKG_INFO, 0, &p, &len);
    int streams = !lumo_package_find(pkg, LUMO_PKG_PMSH, 0, &p, &len);
    snprintf(buf, n, "ok");
    if ((st = check_info(pkg, &in, need_info, buf, n)) || (st = check_ivgd(pkg, buf, n)) ||
        (st = check_orders(pkg, have_info, buf, n)))
        return st;
    for (uint32_t i = 0; have_info && i < in.mesh_count; i++)
        if ((st = check_mesh(pkg, i, streams, buf, n)))
            return st;
    if (have_info && !lumo_package_find(pkg, streams ? LUMO_PKG_PMSH : LUMO_PKG_MESH, in.mesh_count, &p, &len)) {
        snprintf(buf, n, "INFO counts %u meshes, the package holds more %s chunks", in.mesh_count,
                 streams ? "PMSH" : "MESH");
        return LUMO_ERR_CORRUPT;
    }
    return have_info && (flags & HOST_PKG_DEEP) ? check_deep(pkg, buf, n) : LUMO_OK;
}
