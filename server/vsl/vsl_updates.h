/*
 * vsl_updates.h — the server's side of the updates channel
 * (docs/protocol.md §9): a compacted log of the IVG's changed vertices.
 * Every vertex the engine republishes gets a new position (1, 2, ...); the
 * log keeps each vertex once, at its latest position, with its current
 * entries. A client holding position c is sent, oldest first, the vertices
 * whose position is past c, with their values now — so a vertex changed
 * again while the client was away is sent once, its latest value, and a
 * client that falls far behind costs no more than the grid. The server
 * keeps no per-client state: the position is in the REQUEST.
 *
 * Within one publication vertices are ordered coarse to fine (those on the
 * coarsest lattice, every 2^L-th vertex along each axis, first — push-pull's
 * pyramid, seed 000 §4.1), so a client that takes part of an answer has a
 * change spread over the grid, as with the package's stratified rounds.
 *
 * Thread-safe: the engine publishes, connections answer.
 */
#ifndef SRV_VSL_UPDATES_H
#define SRV_VSL_UPDATES_H

#include <pthread.h>
#include <stddef.h>
#include <stdint.h>
#include "lumo/net.h"
#include "package/ivg_encode.h"
#include "vsl/vsl_ivg.h"

typedef struct srv_vsl_updates {
    pthread_mutex_t mu;
    uint16_t        dims[3];
    uint32_t        nverts;
    uint32_t       *pos;      /* per vertex: latest position, 0 = never published */
    uint32_t       *order;    /* the n published vertices by position */
    uint32_t        n;
    uint32_t        next;     /* the next position to give */
    uint32_t       *coarse;   /* per vertex: its lattice level (sort key) */
    uint8_t        *mark;     /* scratch: vertices of this publication */
    uint32_t       *scratch;
    srv_ivg_fentry *e;        /* per vertex, 6 hemispheres */
    uint64_t        published;   /* vertex publications in total */
    lumo_net_pose   poses[LUMO_NET_MAX_POSES];   /* moved lights and meshes now */
    uint32_t        nposes;
    uint32_t        poses_pos;   /* the position when they last changed: sent to clients behind it */
} srv_vsl_updates;

/* A log for a grid of dims. LUMO_OK, LUMO_ERR_NOMEM. */
lumo_status srv_vsl_updates_init(srv_vsl_updates *u, const int dims[3]);
void srv_vsl_updates_free(srv_vsl_updates *u);

/* Publish vertices dirty[0..n) with their values from I (nverts x 54, the
 * srv_vsl_ivg layout), compressed as the bake's (srv_ivg_compress). */
void srv_vsl_updates_publish(srv_vsl_updates *u, const double *I, const uint32_t *dirty, size_t n);

/* The answer to an updates REQUEST (cursor, amount records) for a client
 * with max_payload and IVG form: DATA frames of at most amount records in
 * all, POSES when they changed after cursor, then END, whole frames into *buf (malloc'd, the caller frees),
 * *len bytes. LUMO_ERR_NOMEM; LUMO_ERR_LIMIT when one record does not fit
 * the client's max payload. */
lumo_status srv_vsl_updates_answer(srv_vsl_updates *u, uint32_t cursor, uint32_t amount, uint8_t form,
                                   uint32_t max_payload, uint8_t **buf, size_t *len);

/* The poses now (lumo/net.h POSES: lights' positions, moved meshes'
 * translations and yaws); a change is sent, as one POSES frame before the
 * END of an answer, to every client not yet past it. */
void srv_vsl_updates_set_poses(srv_vsl_updates *u, const lumo_net_pose *p, uint32_t n);

/* The position the log has reached (the last given). */
uint32_t srv_vsl_updates_position(srv_vsl_updates *u);

#endif
