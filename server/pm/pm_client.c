/* pm_client.c — run the client's progressive-mesh decoder over a stream on
 * the desktop (tools, tests, benchmarks). */
#include <stdlib.h>
#include <string.h>
#include "lumo/package.h"
#include "pm/pm_client.h"
#include "pm/pm_stream.h"

lumo_status srv_pm_client_open(srv_pm_client *c, const uint8_t *stream, size_t len)
{
    memset(c, 0, sizeof *c);
    lumo_status st = lumo_pmesh_read_header(stream, len, &c->h);
    if (st)
        return st;
    c->arena_bytes = lumo_pmesh_arena_bytes(&c->h);
    if (c->arena_bytes == SIZE_MAX || !(c->mem = malloc(c->arena_bytes)))
        return LUMO_ERR_NOMEM;
    lumo_arena_init(&c->arena, c->mem, c->arena_bytes);
    if ((st = lumo_pmesh_init(&c->pm, &c->h, &c->arena))) {
        srv_pm_client_close(c);
        return st;
    }
    c->stream = stream, c->len = len, c->at = c->h.header_bytes;
    return LUMO_OK;
}

lumo_status srv_pm_client_next(const srv_pm_client *c, const uint8_t **rec, size_t *bytes)
{
    size_t at = c->at;
    lumo_status st = lumo_pmesh_next_record(c->stream, c->len, &at, rec, bytes);
    return st == LUMO_ERR_RANGE ? LUMO_ERR_TRUNCATED : st;   /* past the end: a stream cut short */
}

lumo_status srv_pm_client_step(srv_pm_client *c)
{
    const uint8_t *rec;
    size_t n;
    lumo_status st = srv_pm_client_next(c, &rec, &n);
    if (!st && !(st = lumo_pmesh_apply(&c->pm, rec, n)))
        c->at += n;
    return st;
}

lumo_status srv_pm_client_until(srv_pm_client *c, uint32_t vertices)
{
    lumo_status st = LUMO_OK;
    lumo_pmesh_view v;
    lumo_pmesh_get_view(&c->pm, &v);
    while (!st && v.vertex_count < vertices && !lumo_pmesh_complete(&c->pm)) {
        st = srv_pm_client_step(c);
        lumo_pmesh_get_view(&c->pm, &v);
    }
    return st;
}

void srv_pm_client_close(srv_pm_client *c)
{
    free(c->mem);
    memset(c, 0, sizeof *c);
}

lumo_status srv_pm_find_stream(const uint8_t *file, size_t len, uint32_t nth,
                               const uint8_t **stream, size_t *stream_len)
{
    lumo_package pkg;
    uint32_t n;
    if (len >= 4 && !memcmp(file, "LPM1", 4)) {
        if (nth)
            return LUMO_ERR_RANGE;
        *stream = file, *stream_len = len;
        return LUMO_OK;
    }
    lumo_status st = lumo_package_open(&pkg, file, len);
    if (st)
        return st;
    if ((st = lumo_package_find(&pkg, LUMO_PKG_PMSH, nth, stream, &n)))
        return st;
    *stream_len = n;
    return LUMO_OK;
}
