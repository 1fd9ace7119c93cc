/*
 * pm/pm_client.h — desktop helpers that drive the real client
 * (lumo/pmesh.h) over a whole stream: lumo-inspect, lumo-pm, tests and
 * benchmarks decode exactly as a device does.
 */
#ifndef SRV_PM_CLIENT_H
#define SRV_PM_CLIENT_H

#include <stddef.h>
#include <stdint.h>
#include "lumo/pmesh.h"

typedef struct srv_pm_client {
    lumo_pmesh_header h;
    lumo_pmesh        pm;
    lumo_arena        arena;
    void             *mem;          /* malloc'ed arena buffer */
    size_t            arena_bytes;
    const uint8_t    *stream;       /* not owned */
    size_t            len, at;      /* next record offset */
} srv_pm_client;

/* Read the header and set up the mesh; the stream must outlive the client. */
lumo_status srv_pm_client_open(srv_pm_client *c, const uint8_t *stream, size_t len);
/* Offset and size of the next record, or TRUNCATED at the end. */
lumo_status srv_pm_client_next(const srv_pm_client *c, const uint8_t **rec, size_t *bytes);
/* Apply the next record and advance. */
lumo_status srv_pm_client_step(srv_pm_client *c);
/* Apply records while the level has fewer than `vertices` vertices. */
lumo_status srv_pm_client_until(srv_pm_client *c, uint32_t vertices);
void srv_pm_client_close(srv_pm_client *c);

/* Find a stream: the nth PMSH chunk of a .lumo package (one per mesh), or
 * a raw stream file (nth 0). */
lumo_status srv_pm_find_stream(const uint8_t *file, size_t len, uint32_t nth,
                               const uint8_t **stream, size_t *stream_len);

#endif
