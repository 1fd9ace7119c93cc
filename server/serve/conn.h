/*
 * serve/conn.h — one client connection of lumo-server (docs/protocol.md §3,
 * docs/server.md "lumo-server").
 *
 * A connection owns a non-blocking socket, a fixed receive buffer and two
 * bounded queues:
 *
 *  - ops: what the client asked (HELLO's WELCOME, REQUESTs) in order, at
 *    most SRV_MAX_OPS (protocol.md §5: 16 outstanding requests; more are not
 *    read until answered);
 *  - jobs: frames ready to leave, at most SRV_MAX_JOBS. A job is a small
 *    generated head, a slice of the package mapping and a CRC trailer, sent
 *    with one sendmsg (writev) per batch of jobs: the package bytes are never
 *    copied. The jobs of an answer are made one at a time as the queue
 *    drains (serve/plan.h), so a request for a whole mesh costs no memory.
 *
 * The socket is read only while the ops queue has room and the output is at
 * most one frame behind (backpressure): a client that does not read stops
 * being read, and is closed once its output has made no progress for the
 * idle timeout. A refused frame ends a TCP client with ERROR; on the serial
 * listener the receive side resynchronises on the next magic instead
 * (protocol.md §1).
 *
 * Memory: sizeof(srv_conn) (about 1.5 KiB) plus, only after an error, the
 * ERROR frame (at most 280 bytes); nothing grows with the scene or the
 * requests — except an updates answer (protocol.md §9), whose frames are
 * made when its turn comes and kept until they have left (the records
 * asked, 46 or 148 bytes each).
 */
#ifndef SRV_SERVE_CONN_H
#define SRV_SERVE_CONN_H

#include <stddef.h>
#include <stdint.h>
#include "lumo/net.h"
#include "lumo/status.h"
#include "serve/index.h"
#include "serve/link.h"
#include "serve/plan.h"

#define SRV_RX_CAP         512u          /* receive buffer: the largest client frame
                                            (HELLO with LUMO_MAX_MESHES cursors) and more */
#define SRV_RX_MAX_PAYLOAD (64u << 10)   /* the server's stated limit (protocol.md §1) */
#define SRV_MAX_OPS        16u
#define SRV_MAX_JOBS       4u

typedef enum srv_conn_state {
    SRV_CONN_WAIT_HELLO = 0,
    SRV_CONN_READY,
    SRV_CONN_DRAINING,   /* not reading: finish the ops and jobs, then close */
    SRV_CONN_FAILING,    /* ERROR queued: send the jobs left, then close */
    SRV_CONN_CLOSED
} srv_conn_state;

typedef struct srv_job {
    uint8_t        head[LUMO_NET_HEADER + LUMO_NET_DATA_HEAD];
    uint8_t        tail[LUMO_NET_TRAILER];
    uint8_t        head_len, tail_len;
    uint8_t        type;        /* frame type (statistics) */
    uint8_t        defect;      /* link emulation: SRV_DEFECT_* */
    uint8_t        defect_byte; /* SRV_DEFECT_FLIP: the byte sent instead */
    uint32_t       defect_at;   /* frame offset of the defect */
    const uint8_t *body;        /* mapping slice, WELCOME frame or ERROR frame */
    uint32_t       body_len;
    uint32_t       done;        /* bytes of the frame on the wire already */
    int64_t        due_us;      /* leaves no earlier (latency) */
} srv_job;

/* SRV_OP_FIRST: the first picture's answers after WELCOME (HELLO flag
 * LUMO_NET_FLAG_FIRST_PICTURE, protocol.md §2): one op that plans, in turn,
 * the base batch of every mesh and lighting round 0; r.mesh counts them. */
enum { SRV_OP_WELCOME = 1, SRV_OP_REQUEST, SRV_OP_FIRST };
typedef struct srv_op {
    uint8_t          kind;
    lumo_net_request r;
    int64_t          due_us;    /* read time + latency */
} srv_op;

typedef struct srv_serve srv_serve;

typedef struct srv_conn {
    int             kind;       /* tag for the event loop (first field) */
    int             fd;
    int             serial;     /* accepted on the serial listener */
    int             usb;        /* a USB bridge's socket (serve/usb.h) */
    uint64_t        id;
    srv_serve      *srv;
    srv_conn_state  state;
    char            peer[64];

    /* after HELLO */
    const srv_pkg  *pkg;
    uint32_t        pkg_index, max_payload, arena, resume_id, resume_meshes;
    uint16_t        width, height;
    uint8_t         form, flags, hello_seen;
    uint8_t         prt;        /* HELLO asked for PRT and the package has it (§10) */

    /* receive side */
    uint8_t         rx[SRV_RX_CAP];
    uint32_t        rx_len;
    uint32_t        skip_left;  /* an oversized frame streamed through its CRC */
    uint32_t        skip_crc, skip_trailer;
    uint8_t         skip_type, skipping;
    uint8_t         eof;
    uint8_t         abort;      /* close with a reset: output left behind */

    /* queues */
    srv_op          ops[SRV_MAX_OPS];
    uint32_t        op_head, op_count;
    srv_answer      answer;
    int             answering;
    int64_t         answer_due_us;  /* the op's due + latency: its frames leave no earlier */
    srv_job         jobs[SRV_MAX_JOBS];
    uint32_t        job_head, job_count;
    uint8_t        *errframe;   /* the ERROR frame, allocated on error */
    uint8_t        *upd;        /* an updates answer's frames (protocol.md §9), allocated per answer */
    uint32_t        upd_len, upd_off;   /* its bytes; those made into jobs */

    /* link emulation and timing */
    srv_link        link;
    int64_t         connected_us, last_rx_us, deadline_us;
    int64_t         last_tx_us;  /* the last write that moved a byte */
    int             blocked;     /* the socket is full (a write took less than offered) */
    int64_t         wake_us;    /* when a time-based wait ends (0: none) */
    int             want_read, want_write;
    uint32_t        events;     /* epoll events registered */
    int             heap_idx;   /* in the server's timer heap, or -1 */
    struct srv_conn *prev, *next;

    /* statistics for the log line */
    uint64_t        bytes_out, data_bytes, bytes_in, garbage;
    uint32_t        frames_out, requests, resyncs, ends;
    lumo_status     status;     /* why it failed (LUMO_OK: it did not) */
    char            reason[160];
} srv_conn;

void srv_conn_init(srv_conn *c, srv_serve *s, int fd, int serial, uint64_t id, const char *peer, int64_t now);
/* The socket is readable (or hung up): read, parse, queue. */
void srv_conn_on_readable(srv_conn *c, int64_t now);
/* Make jobs from the ops, write what is due and what the link allows, and
 * compute want_read, want_write and wake_us. */
void srv_conn_pump(srv_conn *c, int64_t now);
/* Idle and slow-client timeouts, drain deadlines (idle_us: the timeout). */
void srv_conn_check_time(srv_conn *c, int64_t now, int64_t idle_us);
/* The socket hung up or failed: closed (with the socket's error as reason). */
void srv_conn_hangup(srv_conn *c);
/* Server shutdown: stop reading, finish what was asked until deadline. */
void srv_conn_drain(srv_conn *c, int64_t deadline_us);
/* The one log line of a closed connection (without trailing newline). */
void srv_conn_summary(const srv_conn *c, int64_t now, char *out, size_t cap);
void srv_conn_free(srv_conn *c);

#endif
