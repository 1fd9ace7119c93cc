/*
 * lumo/net_updates.h — the client's side of the updates channel
 * (docs/protocol.md §9, docs/dynamic.md): the lighting of a dynamic scene
 * changes on the server (seed 004's photon streaming re-evaluates the IVG
 * where the VSLs changed) and the client pulls the changed grid vertices
 * at its own pace. Each REQUEST states the update position the client
 * holds and how many records it takes; the server answers with DATA frames
 * carrying the current records of the vertices changed after that position
 * (oldest change first, the stratified order within a change), each frame
 * saying the position its records bring the client to, then END. The
 * records replace the vertices the session holds (an IVGU message: the
 * lighting channel's progress is untouched) and push-pull fills the grid
 * again once the answer is complete.
 *
 * Used beside lumo_net_client once the package's lighting is streamed (or
 * at any time after WELCOME): the caller routes the updates channel's
 * frames here (lumo_net_updates_takes). Client rules: no heap, no float.
 */
#ifndef LUMO_NET_UPDATES_H
#define LUMO_NET_UPDATES_H

#include <stddef.h>
#include <stdint.h>
#include "lumo/net.h"
#include "lumo/session.h"
#include "lumo/status.h"

/* The poller. Fields are private: read records, answers and poses for
 * statistics. */
typedef struct lumo_net_updates {
    lumo_session *session; /* the session the updates go to (not owned) */
    uint8_t  form;         /* IVG form asked: LUMO_IVG_FORM_QUANTIZED or _FLOAT */
    uint8_t  in_flight;    /* a request is outstanding */
    uint8_t  applied;      /* records applied in the answer in flight */
    uint32_t amount;       /* records per request, >= 1 */
    uint32_t poll_ms;      /* after an answer with nothing new, ask again this much later */
    uint32_t cursor;       /* update position held (0: none) */
    uint32_t answer_records;   /* records of the answer in flight so far */
    uint32_t last_ms;      /* when the last answer ended */
    uint8_t  wait;         /* the last answer had nothing new: poll_ms applies */
    uint32_t records;      /* records applied, in total */
    uint32_t answers;      /* answers ended (END taken) */
    uint32_t poses;        /* poses applied, in total */
    lumo_status error;     /* why it failed (sticky); LUMO_OK while working */
} lumo_net_updates;

/* A poller for `session` (it must hold the scene's IVGD: a WELCOME was
 * fed). ARG for a NULL, a form other than quantized or binary32, or a zero
 * amount. */
lumo_status lumo_net_updates_init(lumo_net_updates *u, lumo_session *session, uint8_t form, uint32_t amount,
                                  uint32_t poll_ms);

/* 1 when f belongs to the updates channel (a DATA or END of channel 2,
 * whatever its payload's validity past the channel byte, or a POSES),
 * else 0. */
int lumo_net_updates_takes(const lumo_net_frame *f);

/* The next REQUEST to send at time now_ms (a wrapping millisecond clock):
 * one when none is in flight and the poll interval has passed (at once
 * after an answer that brought records). *written is 0 when there is
 * nothing to send now. */
lumo_status lumo_net_updates_next(lumo_net_updates *u, uint32_t now_ms, uint8_t *out, size_t cap,
                                  size_t *written);

/* Feed one frame of the updates channel. DATA must answer the request in
 * flight: its first = the position held, its form the one asked, its
 * records within the amount asked (STATE, RANGE, CORRUPT otherwise); the
 * records go to the session as one IVGU message (all or nothing, the
 * session's checks) and the position advances to the frame's count.
 * POSES moves the session's lights and sets its meshes' poses (every index
 * within the info's counts, RANGE otherwise, checked before any applies). END
 * ends the answer; push-pull runs when it brought records. ERROR: the
 * server's status. On an error the poller fails (every later call returns
 * it) and the session keeps its last good state: it still draws. */
lumo_status lumo_net_updates_on_frame(lumo_net_updates *u, const lumo_net_frame *f, uint32_t now_ms);

#endif /* LUMO_NET_UPDATES_H */
