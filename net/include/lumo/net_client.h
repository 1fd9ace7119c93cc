/*
 * lumo/net_client.h — the client's side of the stream protocol
 * (docs/protocol.md §3): from HELLO to the full scene, feeding what arrives
 * to a client session (lumo/session.h) and deciding what to ask for next.
 *
 * Transport-free: the caller moves bytes (TCP, serial, USB, a replay file)
 * and hands every decoded frame to lumo_net_client_on_frame; the driver
 * writes the frames to send into the caller's buffer. Client rules: no
 * heap, no float; its whole state is this struct.
 *
 * Requests (seed 000 §5.2): every request states its cursor, so the server
 * keeps no state and a request can be repeated. Their sizes are fixed by the
 * policy or adapt to what the driver measures on this client: the time from
 * a request to its last byte (link throughput and latency together) and the
 * time the session takes to apply it (decoding, push-pull), aiming each
 * response at policy.target_ms. Geometry and lighting are interleaved in the
 * policy's order; every order starts with the base meshes and the grid's
 * corners (the first picture).
 */
#ifndef LUMO_NET_CLIENT_H
#define LUMO_NET_CLIENT_H

#include <stddef.h>
#include <stdint.h>
#include "lumo/config.h"
#include "lumo/net.h"
#include "lumo/session.h"
#include "lumo/status.h"

/* Which channel the driver asks first (docs/protocol.md §7). */
typedef enum lumo_net_order {
    LUMO_NET_ORDER_INTERLEAVED = 0,  /* a batch of each mesh, then a lighting request, in turn */
    LUMO_NET_ORDER_GEOMETRY_FIRST,   /* every batch, then the lighting */
    LUMO_NET_ORDER_LIGHTING_FIRST    /* every lighting round, then the batches */
} lumo_net_order;

/* How the driver sizes, orders and pipelines its requests. */
typedef struct lumo_net_policy {
    lumo_net_order order;  /* interleaved, geometry first or lighting first */
    uint32_t vertices;     /* geometry request size; 0: adaptive */
    uint32_t rounds;       /* lighting request size (rounds); 0: adaptive */
    uint32_t target_ms;    /* adaptive: aim each response at this long (0: 250) */
    uint32_t smooth_budget_ms; /* a push-pull with smoothing that takes longer
                                  than this turns smoothing off for the rest
                                  of the session (0: never) */
    uint32_t pipeline;     /* requests in flight, 1..8; hides the link's latency.
                              0: at least 4, and more (up to 8) while the
                              answers in flight would take less than the
                              measured round trip (small requests, e.g. the
                              rest of a small mesh). The first picture's
                              requests (base meshes, the corners) go out
                              together whatever this is. */
} lumo_net_policy;

/* A clock in milliseconds (wrapping u32), for the adaptive sizes; NULL: the
 * sizes stay at their starting values (one batch, one round). */
typedef uint32_t (*lumo_net_clock)(void *ctx);

/* What the driver states in HELLO and how it asks (lumo_net_client_init). */
typedef struct lumo_net_client_config {
    uint32_t package;        /* which of the server's packages */
    uint32_t arena_bytes;    /* stated in HELLO */
    uint32_t max_payload;    /* largest frame payload this client takes */
    uint16_t width, height;  /* the display, pixels (stated in HELLO) */
    uint8_t  ivg_form;       /* LUMO_IVG_FORM_QUANTIZED, _FLOAT or LUMO_NET_FORM_NONE */
    uint8_t  smoothing;      /* push-pull smoothing (stated; the session's config decides) */
    lumo_net_policy policy;  /* request sizes, order, pipeline */
    uint8_t  first_picture;  /* ask the server to send the first picture with
                                the WELCOME (HELLO flag FIRST_PICTURE): one
                                round trip less to it */
    uint8_t  replay;         /* frames come from a recording: apply them in the
                                order they come, send nothing but HELLO */
    uint8_t  prt;            /* relight with the package's PRT (HELLO flag PRT,
                                docs/protocol.md §10): each mesh's PRTV streamed
                                in step with its geometry */
    lumo_net_clock clock;    /* milliseconds, or NULL (fixed sizes) */
    void *clock_ctx;         /* handed to clock */
} lumo_net_client_config;

/* Requests in flight at most: the first picture's (a base mesh per mesh and
 * the corners) plus a full pipeline. */
#define LUMO_NET_MAX_PENDING (LUMO_MAX_MESHES + 1u + 8u)

/* One outstanding request, as the driver predicts its answer. */
typedef struct lumo_net_pending {
    uint8_t  channel;              /* lumo_net_channel */
    uint32_t mesh, cursor, end;    /* batches / rounds [cursor, end) */
    uint32_t sent_ms;              /* the clock when it was written */
    uint32_t turn;                 /* the round robin's turn before it was picked:
                                    * a cut rewinds to the oldest lost request's */
} lumo_net_pending;

/* Per-unit costs the adaptive policy learns (fixed point: ms * 1024). */
typedef struct lumo_net_costs {
    uint32_t rtt_ms;               /* link: the shortest request-to-answer time seen */
    uint32_t ms_per_kib_q10;       /* link: ms per KiB once the answer flows */
    uint32_t bytes_per_vertex;     /* geometry bytes per vertex of the last DATA
                                      (each mesh's own from its mesh_bytes once
                                      it has batches) */
    uint32_t bytes_per_round;      /* lighting bytes per round */
    uint32_t apply_ms_per_kib_q10; /* session: ms to apply a KiB */
    uint32_t update_ms;            /* session: one push-pull (the clock read
                                      right before and right after
                                      lumo_session_update) */
} lumo_net_costs;

/* Where the conversation is: nothing sent, HELLO sent, WELCOME taken, ended, failed. */
typedef enum lumo_net_state {
    LUMO_NET_START = 0, LUMO_NET_HELLO_SENT, LUMO_NET_READY, LUMO_NET_DONE, LUMO_NET_FAILED
} lumo_net_state;

/* The driver. Fields are private; read progress with the functions below. */
typedef struct lumo_net_client {
    lumo_net_client_config cfg;
    lumo_session *session;
    lumo_net_state state;
    uint32_t package_id;              /* from WELCOME; kept for resume */
    uint32_t mesh_count;
    uint32_t held[LUMO_MAX_MESHES];   /* batch records applied per mesh */
    uint32_t asked[LUMO_MAX_MESHES];  /* batch records asked for (held + pending) */
    uint32_t batches[LUMO_MAX_MESHES];/* batch records of each stream */
    uint32_t mesh_bytes[LUMO_MAX_MESHES];  /* record bytes of the batches held, per mesh */
    uint32_t rounds_held, rounds_asked, rounds_total;
    uint8_t  has_ivg;
    uint8_t  has_prt;                 /* cfg.prt and the WELCOME carried a PRTV */
    uint32_t prt_asked[LUMO_MAX_MESHES];  /* PRTV bytes asked for (held + pending); 0: no PRT
                                             (its layout: lumo_session_prt_layout) */
    uint32_t turn;                    /* interleaving position */
    uint8_t  pipeline_auto;           /* policy.pipeline was 0 */
    lumo_net_pending pending[LUMO_NET_MAX_PENDING];
    uint32_t hello_ms;                /* when HELLO was written */
    uint32_t npending;
    uint32_t partial_records;         /* records of a round split over frames */
    uint64_t bytes_in;                /* payload bytes of DATA applied */
    lumo_net_costs costs;
    uint32_t retired_ms;              /* when the last request was answered */
    uint32_t retired;                 /* requests answered */
    uint32_t data_bytes;              /* bytes of the oldest pending request so far */
    uint8_t  smoothing_dropped;       /* smooth_budget_ms was exceeded */
    lumo_status error;                /* why FAILED */
} lumo_net_client;

/* Set up a driver for `session` (initialised, empty or holding a scene
 * being resumed). ARG for a NULL or a config outside the protocol. */
lumo_status lumo_net_client_init(lumo_net_client *c, lumo_session *session, const lumo_net_client_config *cfg);

/* The HELLO frame to send (fresh, or resuming what the session holds after
 * a cut: then every cursor continues where it was). */
lumo_status lumo_net_client_hello(lumo_net_client *c, uint8_t *out, size_t cap, size_t *written);

/* Feed one frame received. WELCOME: the descriptors go to the session
 * (NOMEM when the scene needs more arena than the session has). DATA must
 * answer the oldest request in flight: its channel and mesh, first = the
 * cursor held, no more batches or rounds than that request asked, never
 * past a stream's end (STATE otherwise), and lighting records that add up
 * to the rounds it names (IVGS; over the frames of a split round: CORRUPT
 * otherwise). Its geometry records are all checked (the walk, each head,
 * the batch indices, the CRCs) before the first is applied, so a damaged or
 * foreign DATA changes nothing; only a record the decoder refuses after
 * those checks leaves the records before it applied. Lighting records go to
 * the session as one IVGR message (all or nothing) and the session is
 * updated (push-pull). END answers only a request at the end of its channel
 * (STATE otherwise). ERROR: the server's status is returned. Anything else
 * is STATE. On any error the driver is FAILED (every later call returns the
 * same status) and the session keeps its last good state: it still draws. */
lumo_status lumo_net_client_on_frame(lumo_net_client *c, const lumo_net_frame *f);

/* Whether f is the conversation's next step, one lumo_net_client_on_frame
 * would take: WELCOME while waiting for it; a DATA at the cursor held (the
 * mesh's batches, or the lighting rounds) that, live, answers the oldest
 * request in flight; an END for that request (any END in replay); ERROR
 * always; and a DATA or END whose payload is malformed (on_frame then says
 * why). 0 for anything else. On a serial line (docs/protocol.md §1) the
 * client asks again after a refused frame (lumo_net_client_reset_link,
 * then lumo_net_client_next or, before WELCOME, lumo_net_client_hello), and
 * the rest of the answers to what it asked before still arrive: it drops
 * the frames this says are out of turn instead of failing on them. */
int lumo_net_client_in_turn(const lumo_net_client *c, const lumo_net_frame *f);

/* The next frame to send: a REQUEST while fewer than policy.pipeline are in
 * flight and something is left, BYE once everything has arrived. *written
 * is 0 when there is nothing to send now (wait for a frame). */
lumo_status lumo_net_client_next(lumo_net_client *c, uint8_t *out, size_t cap, size_t *written);

/* After a cut: forget the requests in flight (they will be asked again from
 * the cursors held) so that lumo_net_client_hello resumes. */
void lumo_net_client_reset_link(lumo_net_client *c);

/* ---- lossy links (a serial line: docs/protocol.md §1 and §7 "Serial lines") ----
 * Bytes may be lost or damaged: the caller skips a refused frame
 * (lumo_net_resync), and frames may arrive that answer requests sent before
 * a loss. Two calls keep the conversation exact:
 *
 * lumo_net_client_expects: 1 when on_frame would take f as the next frame
 * of the conversation (WELCOME while it is awaited, a DATA or END answering
 * the oldest request in flight as on_frame checks them, ERROR), 0 for a
 * frame to drop unseen (a late answer, a duplicate). Nothing changes.
 *
 * lumo_net_client_resync: after a loss (a refused frame, or silence while
 * something is awaited). Before WELCOME it writes HELLO again. Afterwards it
 * forgets the requests in flight (reset_link) and writes a marker: a
 * REQUEST at the end of mesh 0 (of the rounds without meshes), which the
 * server answers with END only, in turn after everything asked before it.
 * Until that END arrives every DATA is unexpected (stale); the requests
 * lumo_net_client_next writes meanwhile go out behind the marker and ask
 * again from the cursors held. *written is 0 when nothing is streamed. */
int lumo_net_client_expects(const lumo_net_client *c, const lumo_net_frame *f);
lumo_status lumo_net_client_resync(lumo_net_client *c, uint8_t *out, size_t cap, size_t *written);

/* How much of the scene the driver holds (lumo_net_client_progress). */
typedef struct lumo_net_progress {
    uint32_t vertices, full_vertices;   /* all meshes */
    uint32_t rounds, full_rounds;       /* IVG rounds held / total */
    uint64_t bytes;                     /* DATA payload bytes applied */
    int      done;                      /* 1 once the conversation has ended (state DONE) */
} lumo_net_progress;
/* The progress (above) into *out. */
void lumo_net_client_progress(const lumo_net_client *c, lumo_net_progress *out);

#endif /* LUMO_NET_CLIENT_H */
