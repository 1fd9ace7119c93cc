/*
 * tools/lumo-client/client.h — the Linux thin client's parts: the options
 * (main.c), the links that carry frames (link_tcp.c: TCP and a serial line
 * over TCP; link_replay.c: a recording, and the recorder; link_http.c: a
 * package on a stock HTTP server read with Range requests), the
 * conversation over a link (converse.c: frames into the protocol driver,
 * resume after a cut, resynchronisation on a lossy line) and the pictures
 * (draw.c: PNG frames and progress.csv as the scene refines).
 */
#ifndef LUMO_CLIENT_H
#define LUMO_CLIENT_H

#include <stdint.h>
#include <stdio.h>
#include "lumo/net_client.h"
#include "lumo/session.h"
#include "../lumo-render/render_backend.h"
#include "../lumo-render/session_scene.h"

/* ---- options (main.c) ---------------------------------------------------------- */

typedef struct options {
    const char *connect, *serial, *replay, *http;   /* exactly one: the source */
    const char *record, *out, *backend, *camera;
    lumo_raster_camera view;   /* --camera, parsed once (when camera != NULL) */
    double at[64];
    int nat, quiet, no_smoothing, use_float, per_vertex, fit;
    uint32_t package, arena_mib, retries, max_payload;
    uint32_t updates_s, update_every_ms, update_amount;   /* --updates (docs/dynamic.md) */
    lumo_net_policy policy;
    render_opts ro;
} options;

/* ---- links (link_*.c) ------------------------------------------------------------ */

#define LINK_TIMEOUT (-2L)   /* read: nothing arrived in time */
#define LINK_ERROR   (-1L)   /* read: failed (why in link->err) */

typedef struct client_link client_link;

typedef struct link_ops {
    const char *name;      /* "tcp", "serial", "replay", "http" */
    int lossy;             /* bytes may be lost or damaged: resynchronise, ask again */
    int resumable;         /* a dropped connection is opened again and resumed */
    int (*open)(client_link *l);                                  /* 0, or -1 with l->err */
    int (*send)(client_link *l, const uint8_t *p, size_t n);      /* 0, or -1 with l->err */
    /* Bytes read into buf (> 0), 0 at the end of the stream, LINK_TIMEOUT
     * after timeout_ms without a byte (-1: wait), LINK_ERROR. */
    long (*read)(client_link *l, uint8_t *buf, size_t cap, int timeout_ms);
    void (*close)(client_link *l);
} link_ops;

struct client_link {
    const link_ops *ops;
    const char *target;       /* HOST:PORT, FILE or URL */
    int fd;
    void *impl;               /* a link's own state (http) */
    char err[320];
    char note[160];           /* for the summary line (http: ranges fetched) */
    uint64_t bytes_in, bytes_out;   /* over every connection */
};

extern const link_ops link_tcp, link_serial, link_replay, link_http;

/* The recorder (link_replay.c): the frames the driver took, each exactly as
 * received, one after the other (docs/protocol.md "Replay files"). */
int record_open(FILE **f, const char *path, char *err, size_t errlen);
int record_frame(FILE *f, const uint8_t *frame, size_t n);

/* ---- the client ---------------------------------------------------------------- */

typedef struct client {
    options o;
    client_link l;
    lumo_session ses;
    lumo_net_client drv;
    host_scene scene;
    FILE *csv, *record;
    uint32_t t0;
    int next_at;
    int first_done;            /* the first picture has been drawn */
    uint32_t first_ms;
    uint64_t first_bytes;
    double last_fps;
    uint32_t frames_drawn;
    /* what the conversation saw */
    uint64_t taken_bytes;      /* bytes of the frames the driver took */
    uint32_t taken;            /* frames the driver took */
    uint64_t cut_bytes;        /* bytes of frames cut mid-way by a dropped connection */
    uint32_t cuts, failures;   /* connections dropped; reconnections that failed in a row */
    uint32_t refused, stale, timeouts, resyncs;   /* lossy lines */
    uint64_t garbage;          /* bytes skipped resynchronising */
    int resyncing;             /* a resync marker is in flight, nothing taken since */
    uint32_t silences;         /* silences in a row, nothing taken since */
    int bye_held;              /* --updates: the driver's BYE waits for the updates phase */
} client;

/* converse.c: HELLO to the full scene over c->l (opened here). 0 or -1
 * (a one-line error printed). */
int converse(client *c);

/* updates.c: after the scene is complete, --updates seconds of lighting
 * updates on the same link (rx: the receive buffer of cap bytes, *len
 * held), frames drawn as they come, then BYE. 0 or -1 (said). */
int updates_phase(client *c, uint8_t *rx, size_t cap, size_t *len);

/* draw.c */
int draw_update_frame(client *c, uint32_t n, double seconds, uint32_t records);   /* frame-update-NNN.png */
int draws_open(client *c);     /* progress.csv in the output directory */
int frames_due(client *c);     /* PNG frames for every threshold passed */
void draws_close(client *c);

#endif
