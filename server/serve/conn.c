/*
 * conn.c — one client connection: frames in, jobs out (serve/conn.h).
 */
#include "serve/conn.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/uio.h>
#include <unistd.h>
#include "lumo/ivg.h"
#include "vsl/vsl_updates.h"
#include "lumo/wire.h"
#include "serve/server.h"

static const srv_link_config *link_cfg(const srv_conn *c)
{
    return c->serial ? &c->srv->serial_link : &c->srv->link;
}

void srv_conn_init(srv_conn *c, srv_serve *s, int fd, int serial, uint64_t id, const char *peer, int64_t now)
{
    memset(c, 0, sizeof *c);
    c->fd = fd;
    c->serial = serial;
    c->id = id;
    c->srv = s;
    c->state = SRV_CONN_WAIT_HELLO;
    c->heap_idx = -1;
    c->connected_us = c->last_rx_us = c->last_tx_us = now;
    c->form = LUMO_NET_FORM_NONE;
    snprintf(c->peer, sizeof c->peer, "%s", peer);
    srv_link_init(&c->link, link_cfg(c), id, now);
}

void srv_conn_free(srv_conn *c)
{
    free(c->errframe);
    c->errframe = NULL;
    free(c->upd);
    c->upd = NULL;
}

static void set_reason(srv_conn *c, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void set_reason(srv_conn *c, const char *fmt, ...)
{
    va_list ap;

    if (c->reason[0])
        return;   /* the first reason is the one that counts */
    va_start(ap, fmt);
    vsnprintf(c->reason, sizeof c->reason, fmt, ap);
    va_end(ap);
}

static void close_now(srv_conn *c, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void close_now(srv_conn *c, const char *fmt, ...)
{
    va_list ap;

    if (!c->reason[0]) {
        va_start(ap, fmt);
        vsnprintf(c->reason, sizeof c->reason, fmt, ap);
        va_end(ap);
    }
    c->state = SRV_CONN_CLOSED;
}

/* ---- jobs ---------------------------------------------------------------------- */

static uint32_t job_len(const srv_job *j)
{
    return (uint32_t)j->head_len + j->body_len + j->tail_len;
}

/* Bytes the job puts on the wire (a dropped byte is not sent). */
static uint32_t job_wire_len(const srv_job *j)
{
    return job_len(j) - (j->defect == SRV_DEFECT_DROP ? 1u : 0u);
}

static srv_job *job_push(srv_conn *c, uint8_t type, int64_t due)
{
    srv_job *j = &c->jobs[(c->job_head + c->job_count++) % SRV_MAX_JOBS];

    j->head_len = j->tail_len = 0;
    j->body = NULL;
    j->body_len = j->done = 0;
    j->defect = SRV_DEFECT_NONE;
    j->defect_at = 0;
    j->defect_byte = 0;
    j->type = type;
    j->due_us = due;
    return j;
}

/* Loss emulation, decided when the job is complete. */
static void job_damage(srv_conn *c, srv_job *j)
{
    uint32_t at = 0;
    uint8_t x = 0;
    int kind;

    if (!c->serial)
        return;
    kind = srv_link_defect(&c->link, link_cfg(c), job_len(j), &at, &x);
    if (kind == SRV_DEFECT_NONE)
        return;
    j->defect = (uint8_t)kind;
    j->defect_at = at;
    if (kind == SRV_DEFECT_FLIP) {
        uint8_t b;
        if (at < j->head_len)
            b = j->head[at];
        else if (at < j->head_len + j->body_len)
            b = j->body[at - j->head_len];
        else
            b = j->tail[at - j->head_len - j->body_len];
        j->defect_byte = (uint8_t)(b ^ x);
    }
}

static void push_data(srv_conn *c, const lumo_net_data *d)
{
    srv_job *j = job_push(c, LUMO_NET_DATA, c->answer_due_us);
    uint32_t crc = lumo_net_data_head(d, j->head);

    j->head_len = LUMO_NET_HEADER + LUMO_NET_DATA_HEAD;
    j->body = d->bytes;
    j->body_len = d->len;
    crc = lumo_wire_crc32(crc, d->bytes, d->len);
    lumo_wire_put_le32(j->tail, crc);
    j->tail_len = LUMO_NET_TRAILER;
    c->data_bytes += d->len;
    job_damage(c, j);
}

static void push_end(srv_conn *c, uint8_t channel, uint32_t mesh, int64_t due)
{
    srv_job *j = job_push(c, LUMO_NET_END, due);
    lumo_net_end e = {channel, mesh};
    size_t n = 0;

    if (lumo_net_end_encode(&e, j->head, sizeof j->head, &n) == LUMO_OK)
        j->head_len = (uint8_t)n;
    c->ends++;
    job_damage(c, j);
}

static void push_welcome(srv_conn *c, int64_t due)
{
    srv_job *j = job_push(c, LUMO_NET_WELCOME, due);

    j->body = c->prt ? c->pkg->welcome_prt : c->pkg->welcome;
    j->body_len = (uint32_t)(c->prt ? c->pkg->welcome_prt_len : c->pkg->welcome_len);
    job_damage(c, j);
}

/* ---- failing ------------------------------------------------------------------- */

/* Drop what was asked and the jobs not yet started, queue ERROR (status,
 * text) and close once it is out (or at the deadline). */
static void fail(srv_conn *c, lumo_status st, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static void fail(srv_conn *c, lumo_status st, const char *fmt, ...)
{
    char text[LUMO_NET_MAX_TEXT];
    size_t n = 0;
    va_list ap;

    if (c->state == SRV_CONN_FAILING || c->state == SRV_CONN_CLOSED)
        return;
    va_start(ap, fmt);
    vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    c->status = st;
    set_reason(c, "error %s: %s", lumo_strerror(st), text);
    c->op_count = 0;
    c->answering = 0;
    /* a job already on its way stays whole: the client sees whole frames */
    if (c->job_count && c->jobs[c->job_head].done)
        c->job_count = 1;
    else
        c->job_count = 0;
    c->state = SRV_CONN_FAILING;
    c->deadline_us = srv_now_us() + (int64_t)c->srv->opt.drain_ms * 1000;
    if (!c->errframe && !(c->errframe = malloc(LUMO_NET_OVERHEAD + 8 + LUMO_NET_MAX_TEXT)))
        return;
    if (lumo_net_error_encode((uint32_t)st, text, c->errframe, LUMO_NET_OVERHEAD + 8 + LUMO_NET_MAX_TEXT, &n))
        return;
    {
        srv_job *j = job_push(c, LUMO_NET_ERROR, 0);
        j->body = c->errframe;
        j->body_len = (uint32_t)n;
    }
}

/* ---- frames from the client ---------------------------------------------------- */

static const char *type_name(unsigned t)
{
    static const char *names[] = {"?", "HELLO", "WELCOME", "REQUEST", "DATA", "END", "ERROR", "BYE"};
    return t < sizeof names / sizeof *names ? names[t] : "unknown";
}

static void push_op(srv_conn *c, uint8_t kind, const lumo_net_request *r, int64_t now)
{
    srv_op *o = &c->ops[(c->op_head + c->op_count++) % SRV_MAX_OPS];

    o->kind = kind;
    if (r)
        o->r = *r;
    o->due_us = now + link_cfg(c)->latency_us;
}

static void on_hello(srv_conn *c, const lumo_net_frame *f, int64_t now)
{
    lumo_net_hello h;
    const srv_pkg *p;
    lumo_status st;

    if (c->state != SRV_CONN_WAIT_HELLO && !c->serial) {
        fail(c, LUMO_ERR_STATE, "HELLO after HELLO");
        return;
    }
    if ((st = lumo_net_hello_decode(f, &h))) {
        fail(c, st, "HELLO: %s", lumo_strerror(st));
        return;
    }
    if (h.package >= c->srv->npkgs) {
        fail(c, LUMO_ERR_RANGE, "no package %u: this server has %u", h.package, c->srv->npkgs);
        return;
    }
    if (h.max_payload < LUMO_NET_MIN_PAYLOAD) {
        fail(c, LUMO_ERR_RANGE, "max payload %u is below %u", h.max_payload, LUMO_NET_MIN_PAYLOAD);
        return;
    }
    if (h.ivg_form != LUMO_IVG_FORM_FLOAT && h.ivg_form != LUMO_IVG_FORM_QUANTIZED &&
        h.ivg_form != LUMO_NET_FORM_NONE) {
        fail(c, LUMO_ERR_RANGE, "unknown IVG form %u", h.ivg_form);
        return;
    }
    p = &c->srv->pkgs[h.package];
    c->pkg = p;
    c->pkg_index = h.package;
    c->max_payload = h.max_payload > LUMO_NET_MAX_PAYLOAD ? LUMO_NET_MAX_PAYLOAD : h.max_payload;
    c->arena = h.arena_bytes;
    c->width = h.width, c->height = h.height;
    c->form = h.ivg_form;
    c->flags = h.flags;
    c->resume_id = h.resume_id;
    c->resume_meshes = h.mesh_count;
    c->hello_seen = 1;
    c->prt = (h.flags & LUMO_NET_FLAG_PRT) && p->has_prt;
    uint32_t need = c->prt ? p->arena_need_prt : p->arena_need;
    size_t wlen = c->prt ? p->welcome_prt_len : p->welcome_len;
    if (need > h.arena_bytes) {
        fail(c, LUMO_ERR_NOMEM, "the scene needs %u arena bytes, the client has %u", need, h.arena_bytes);
        return;
    }
    if (wlen - LUMO_NET_OVERHEAD > c->max_payload) {
        fail(c, LUMO_ERR_LIMIT, "WELCOME is %zu bytes, more than max payload %u", wlen - LUMO_NET_OVERHEAD,
             c->max_payload);
        return;
    }
    if (c->state == SRV_CONN_READY) {
        /* serial: the WELCOME was lost on the line; start over (what was
         * asked before is asked again from the client's cursors) */
        c->op_count = 0;
        c->answering = 0;
    }
    c->state = SRV_CONN_READY;
    push_op(c, SRV_OP_WELCOME, NULL, now);
    if ((h.flags & LUMO_NET_FLAG_FIRST_PICTURE) && !h.resume_id) {
        lumo_net_request first;
        memset(&first, 0, sizeof first);
        push_op(c, SRV_OP_FIRST, &first, now);
    }
}

/* The next request of the first picture (protocol.md §2 HELLO): the base
 * batch of mesh 0, 1, ..., then lighting round 0 when the client asked for
 * an IVG form and the package has one. 0 when none is left. */
static int first_picture_request(const srv_conn *c, uint32_t k, lumo_net_request *r)
{
    memset(r, 0, sizeof *r);
    if (k < c->pkg->mesh_count) {
        r->channel = LUMO_NET_GEOMETRY;
        r->mesh = k;
        r->amount = c->pkg->mesh[k].h.base_vertices;
        return 1;
    }
    if (k == c->pkg->mesh_count && c->pkg->ivg.present && c->form != LUMO_NET_FORM_NONE) {
        r->channel = LUMO_NET_LIGHTING;
        r->amount = 1;
        return 1;
    }
    return 0;
}

static void on_request(srv_conn *c, const lumo_net_frame *f, int64_t now)
{
    lumo_net_request r;
    srv_answer a;
    char err[160];
    int end;
    lumo_status st;

    if (c->state != SRV_CONN_READY) {
        fail(c, LUMO_ERR_STATE, "REQUEST before HELLO");
        return;
    }
    if ((st = lumo_net_request_decode(f, &r))) {
        fail(c, st, "REQUEST: %s", lumo_strerror(st));
        return;
    }
    if (r.channel == LUMO_NET_UPDATES) {   /* protocol.md §9: answered from the update log */
        if (c->form == LUMO_NET_FORM_NONE) {
            fail(c, LUMO_ERR_RANGE, "REQUEST: updates of the lighting need an IVG form in HELLO");
            return;
        }
        c->requests++;
        push_op(c, SRV_OP_REQUEST, &r, now);
        return;
    }
    if (r.channel == LUMO_NET_PRT && !c->prt) {
        fail(c, LUMO_ERR_RANGE, "REQUEST: PRT of a package without it, or not asked for in HELLO");
        return;
    }
    /* checked when read (RANGE, LIMIT), planned again when its turn comes */
    if ((st = srv_plan_start(c->pkg, &r, c->form, c->max_payload, &a, &end, err, sizeof err))) {
        fail(c, st, "%s", err);
        return;
    }
    c->requests++;
    push_op(c, SRV_OP_REQUEST, &r, now);
}

static void on_client_error(srv_conn *c, const lumo_net_frame *f)
{
    lumo_net_error e;

    if (lumo_net_error_decode(f, &e) == LUMO_OK) {
        int n = e.len > 120 ? 120 : (int)e.len;
        close_now(c, "the client reported %s: %.*s",
                  lumo_strerror(e.status < LUMO_STATUS_COUNT ? (lumo_status)e.status : LUMO_ERR_CORRUPT), n,
                  (const char *)e.text);
    } else {
        close_now(c, "the client sent a malformed ERROR");
    }
}

static void on_frame(srv_conn *c, const lumo_net_frame *f, int64_t now)
{
    switch (f->type) {
    case LUMO_NET_HELLO:
        on_hello(c, f, now);
        break;
    case LUMO_NET_REQUEST:
        on_request(c, f, now);
        break;
    case LUMO_NET_BYE:
        if (c->state != SRV_CONN_READY) {
            fail(c, LUMO_ERR_STATE, "BYE before HELLO");
            break;
        }
        set_reason(c, "bye");
        c->state = SRV_CONN_DRAINING;
        c->deadline_us = now + c->srv->idle_us;
        break;
    case LUMO_NET_ERROR:
        on_client_error(c, f);
        break;
    default:
        fail(c, LUMO_ERR_STATE, "%s is a server's frame", type_name(f->type));
        break;
    }
}

/* A frame the receive side refuses (protocol.md §1): the end of a TCP
 * client; on a serial line, skip to the next magic after its start. */
static void refuse(srv_conn *c, lumo_status st, const char *what)
{
    if (c->serial) {
        size_t skip = lumo_net_resync(c->rx, c->rx_len, 1);
        c->garbage += skip;
        c->resyncs++;
        memmove(c->rx, c->rx + skip, c->rx_len - skip);
        c->rx_len -= (uint32_t)skip;
        return;
    }
    fail(c, st, "refused frame: %s", what);
}

static void consume(srv_conn *c, size_t n)
{
    memmove(c->rx, c->rx + n, c->rx_len - n);
    c->rx_len -= (uint32_t)n;
}

/* An oversized frame (TCP): its payload streamed through the CRC, then
 * refused with the status the checks of protocol.md §1 would give. */
static void skip_frame(srv_conn *c)
{
    while (c->rx_len && c->skip_left) {
        uint32_t n = c->rx_len < c->skip_left ? c->rx_len : c->skip_left;
        c->skip_crc = lumo_wire_crc32(c->skip_crc, c->rx, n);
        c->skip_left -= n;
        consume(c, n);
    }
    if (c->skip_left || c->rx_len < LUMO_NET_TRAILER)
        return;
    c->skipping = 0;
    if (lumo_wire_le32(c->rx) != c->skip_crc)
        fail(c, LUMO_ERR_CHECKSUM, "refused frame: CRC mismatch");
    else if (c->skip_type < LUMO_NET_HELLO || c->skip_type > LUMO_NET_BYE)
        fail(c, LUMO_ERR_UNSUPPORTED, "refused frame: unknown type %u", c->skip_type);
    else if (c->skip_type == LUMO_NET_WELCOME || c->skip_type == LUMO_NET_DATA || c->skip_type == LUMO_NET_END)
        fail(c, LUMO_ERR_STATE, "%s is a server's frame", type_name(c->skip_type));
    else
        fail(c, LUMO_ERR_CORRUPT, "refused frame: a %s of %u bytes", type_name(c->skip_type), c->skip_trailer);
    consume(c, LUMO_NET_TRAILER);
}

static int reading(const srv_conn *c)
{
    return c->state == SRV_CONN_WAIT_HELLO || c->state == SRV_CONN_READY;
}

/* Requests outstanding (queued, and the one being answered) stay within
 * protocol.md §5's 16: more are not read until answered. */
static int room_for_ops(const srv_conn *c)
{
    return c->op_count + (c->answering ? 1u : 0u) < SRV_MAX_OPS;
}

/* Decode the frames in the receive buffer while there is room for what
 * they ask. */
static void parse(srv_conn *c, int64_t now)
{
    while (reading(c) && room_for_ops(c)) {
        const uint8_t *b = c->rx;
        uint32_t avail = c->rx_len, n;
        lumo_net_frame f;
        size_t used = 0;
        lumo_status st;

        if (c->skipping) {
            skip_frame(c);
            if (c->skipping)
                return;
            continue;
        }
        if (avail == 0)
            return;
        if (b[0] != LUMO_NET_MAGIC0 || (avail >= 2 && b[1] != LUMO_NET_MAGIC1)) {
            refuse(c, LUMO_ERR_CORRUPT, "bad magic");
            continue;
        }
        if (avail >= 3 && b[2] != LUMO_NET_VERSION) {
            refuse(c, LUMO_ERR_VERSION, "protocol version is not 1");
            continue;
        }
        if (avail < LUMO_NET_HEADER)
            return;
        n = lumo_wire_le32(b + 4);
        if (n > SRV_RX_MAX_PAYLOAD) {
            refuse(c, LUMO_ERR_LIMIT, "payload above the server's 64 KiB");
            continue;
        }
        if (n + LUMO_NET_OVERHEAD > SRV_RX_CAP) {
            /* Longer than any client message. A serial line refuses it at
             * once (a garbled length must not stall the line for 64 KiB);
             * TCP streams it through its CRC to refuse it as §1 says. */
            if (c->serial) {
                refuse(c, LUMO_ERR_LIMIT, "payload longer than any client message");
                continue;
            }
            c->skipping = 1;
            c->skip_type = b[3];
            c->skip_left = c->skip_trailer = n;
            c->skip_crc = lumo_wire_crc32(0, b, LUMO_NET_HEADER);
            consume(c, LUMO_NET_HEADER);
            continue;
        }
        if (avail < n + LUMO_NET_OVERHEAD)
            return;
        st = lumo_net_frame_decode(b, n + LUMO_NET_OVERHEAD, SRV_RX_MAX_PAYLOAD, &f, &used);
        if (st) {
            refuse(c, st, st == LUMO_ERR_CHECKSUM ? "CRC mismatch" : st == LUMO_ERR_UNSUPPORTED ? "unknown type"
                                                                                                 : lumo_strerror(st));
            continue;
        }
        on_frame(c, &f, now);
        consume(c, n + LUMO_NET_OVERHEAD);
    }
}

void srv_conn_on_readable(srv_conn *c, int64_t now)
{
    for (;;) {
        ssize_t n;

        if (!reading(c) || c->rx_len == SRV_RX_CAP || !room_for_ops(c))
            break;
        n = read(c->fd, c->rx + c->rx_len, SRV_RX_CAP - c->rx_len);
        if (n > 0) {
            c->rx_len += (uint32_t)n;
            c->bytes_in += (uint64_t)n;
            c->last_rx_us = now;
            parse(c, now);
            continue;
        }
        if (n == 0) {
            c->eof = 1;
            if (c->skipping || (c->rx_len && !c->serial)) {
                fail(c, LUMO_ERR_TRUNCATED, "the stream ended inside a frame");
            } else if (c->state == SRV_CONN_READY && (c->op_count || c->answering || c->job_count)) {
                set_reason(c, "client closed its side");
                c->state = SRV_CONN_DRAINING;
                c->deadline_us = now + c->srv->idle_us;
            } else if (reading(c)) {
                close_now(c, c->hello_seen ? "closed by the client" : "closed by the client before HELLO");
            }
            break;
        }
        if (errno == EINTR)
            continue;
        if (errno != EAGAIN && errno != EWOULDBLOCK)
            close_now(c, "read: %s", strerror(errno));
        break;
    }
}

/* ---- output -------------------------------------------------------------------- */

/* The next whole frame of the updates answer in c->upd (protocol.md §9). */
static int push_update_frame(srv_conn *c)
{
    const uint8_t *f = c->upd + c->upd_off;
    srv_job *j = job_push(c, f[3], c->answer_due_us);

    j->body = f;
    j->body_len = LUMO_NET_OVERHEAD + lumo_wire_le32(f + 4);
    c->upd_off += j->body_len;
    if (f[3] == LUMO_NET_END)
        c->ends++;
    else
        c->data_bytes += j->body_len - LUMO_NET_OVERHEAD - LUMO_NET_DATA_HEAD;
    job_damage(c, j);
    return 1;
}

/* An updates request: its frames from the log (END alone on a server
 * without a lighting engine), made into c->upd once the jobs of the last
 * such answer have left (they point into it). */
static int start_updates(srv_conn *c, const srv_op *o)
{
    srv_vsl_updates *u = c->srv->opt.updates;
    int64_t due = o->due_us + link_cfg(c)->latency_us;
    size_t len = 0;
    lumo_status st;

    free(c->upd);
    c->upd = NULL;
    c->upd_len = c->upd_off = 0;
    if (!u) {
        push_end(c, LUMO_NET_UPDATES, 0, due);
        return 1;
    }
    if ((st = srv_vsl_updates_answer(u, o->r.cursor, o->r.amount, c->form, c->max_payload, &c->upd, &len))) {
        fail(c, st, "updates: %s", lumo_strerror(st));
        return 1;
    }
    c->upd_len = (uint32_t)len;
    c->answer_due_us = due;
    return push_update_frame(c);
}

/* Start the next op or continue the answer: at most one new job. Returns 1
 * when a job was made. */
static int make_job(srv_conn *c, int64_t now)
{
    if (c->job_count >= SRV_MAX_JOBS)
        return 0;
    if (c->upd_off < c->upd_len)
        return push_update_frame(c);
    if (c->answering) {
        lumo_net_data d;
        if (srv_plan_next(c->pkg, &c->answer, &d)) {
            push_data(c, &d);
            return 1;
        }
        c->answering = 0;
    }
    while (c->op_count) {
        srv_op *o = &c->ops[c->op_head];
        char err[160];
        int end = 0;
        lumo_status st;

        if (o->due_us > now) {
            if (!c->wake_us || o->due_us < c->wake_us)
                c->wake_us = o->due_us;
            return 0;
        }
        if (o->kind == SRV_OP_FIRST) {
            /* stays at the head until its last request is planned */
            lumo_net_request r;
            if (first_picture_request(c, o->r.mesh++, &r)) {
                srv_op one = *o;
                one.r = r;
                o = &one;
                st = srv_plan_start(c->pkg, &o->r, c->form, c->max_payload, &c->answer, &end, err, sizeof err);
                if (st) {
                    fail(c, st, "%s", err);
                    return 1;
                }
                c->answering = 1;
                c->answer_due_us = o->due_us + link_cfg(c)->latency_us;
                return make_job(c, now);
            }
            c->op_head = (c->op_head + 1) % SRV_MAX_OPS;
            c->op_count--;
            continue;
        }
        if (o->kind == SRV_OP_REQUEST && o->r.channel == LUMO_NET_UPDATES) {
            srv_op one = *o;
            if (c->job_count)
                return 0;   /* the last answer's frames point into c->upd */
            c->op_head = (c->op_head + 1) % SRV_MAX_OPS;
            c->op_count--;
            return start_updates(c, &one);
        }
        c->op_head = (c->op_head + 1) % SRV_MAX_OPS;
        c->op_count--;
        if (o->kind == SRV_OP_WELCOME) {
            push_welcome(c, o->due_us + link_cfg(c)->latency_us);
            return 1;
        }
        st = srv_plan_start(c->pkg, &o->r, c->form, c->max_payload, &c->answer, &end, err, sizeof err);
        if (st) {
            fail(c, st, "%s", err);
            return 1;
        }
        if (end) {
            push_end(c, o->r.channel, o->r.channel == LUMO_NET_GEOMETRY || o->r.channel == LUMO_NET_PRT ? o->r.mesh : 0,
                     o->due_us + link_cfg(c)->latency_us);
            return 1;
        }
        c->answering = 1;
        c->answer_due_us = o->due_us + link_cfg(c)->latency_us;
        return make_job(c, now);
    }
    return 0;
}

/* Add the iovecs of bytes [from, to) of one part of a job (part: the bytes
 * at frame offsets [base, base + len)). */
static int add_part(const srv_job *j, struct iovec *iov, int n, int max, const uint8_t *part, uint32_t base,
                    uint32_t len, uint32_t from, uint32_t to)
{
    uint32_t lo = from > base ? from : base, hi = to < base + len ? to : base + len;

    if (lo >= hi)
        return n;
    if (j->defect != SRV_DEFECT_NONE && j->defect_at >= lo && j->defect_at < hi) {
        if (j->defect_at > lo && n < max)
            iov[n].iov_base = (void *)(part + (lo - base)), iov[n].iov_len = j->defect_at - lo, n++;
        if (j->defect == SRV_DEFECT_FLIP && n < max)
            iov[n].iov_base = (void *)&j->defect_byte, iov[n].iov_len = 1, n++;
        lo = j->defect_at + 1;
        if (lo >= hi)
            return n;
    }
    if (n < max)
        iov[n].iov_base = (void *)(part + (lo - base)), iov[n].iov_len = hi - lo, n++;
    return n;
}

/* The iovecs of what is left of job j, at most budget wire bytes. */
static int job_iov(const srv_job *j, struct iovec *iov, int n, int max, size_t *budget)
{
    uint32_t wire_left = job_wire_len(j) - j->done, take, from, to;

    take = *budget < wire_left ? (uint32_t)*budget : wire_left;
    *budget -= take;
    /* wire offsets to frame offsets: past a dropped byte, one more */
    from = j->done;
    to = j->done + take;
    if (j->defect == SRV_DEFECT_DROP) {
        if (from >= j->defect_at)
            from++;
        if (to > j->defect_at)
            to++;
    }
    n = add_part(j, iov, n, max, j->head, 0, j->head_len, from, to);
    n = add_part(j, iov, n, max, j->body, j->head_len, j->body_len, from, to);
    n = add_part(j, iov, n, max, j->tail, (uint32_t)j->head_len + j->body_len, j->tail_len, from, to);
    return n;
}

#define IOV_MAX_JOBS (SRV_MAX_JOBS * 5)

/* Write what is due; 1 when the socket took everything offered. */
static int write_some(srv_conn *c, int64_t now)
{
    struct iovec iov[IOV_MAX_JOBS];
    struct msghdr mh;
    size_t want = 0, budget, offered, written;
    uint32_t k;
    int n = 0;
    ssize_t w;
    int64_t wake = 0;

    for (k = 0; k < c->job_count; k++) {
        const srv_job *j = &c->jobs[(c->job_head + k) % SRV_MAX_JOBS];
        if (j->due_us > now) {
            wake = j->due_us;
            break;
        }
        want += job_wire_len(j) - j->done;
    }
    if (want == 0) {
        if (wake && (!c->wake_us || wake < c->wake_us))
            c->wake_us = wake;
        return 0;
    }
    budget = srv_link_budget(&c->link, link_cfg(c), now, want, &wake);
    if (budget == 0) {
        if (!c->wake_us || wake < c->wake_us)
            c->wake_us = wake;
        return 0;
    }
    offered = budget;
    for (k = 0; k < c->job_count && budget; k++) {
        const srv_job *j = &c->jobs[(c->job_head + k) % SRV_MAX_JOBS];
        if (j->due_us > now)
            break;
        n = job_iov(j, iov, n, IOV_MAX_JOBS, &budget);
    }
    offered -= budget;
    memset(&mh, 0, sizeof mh);
    mh.msg_iov = iov;
    mh.msg_iovlen = (size_t)n;
    do
        w = sendmsg(c->fd, &mh, MSG_NOSIGNAL | MSG_DONTWAIT);
    while (w < 0 && errno == EINTR);
    if (w < 0) {
        if (errno == EAGAIN || errno == EWOULDBLOCK) {
            c->want_write = 1;
            c->blocked = 1;   /* since last_tx_us, if nothing moves */
            return 0;
        }
        close_now(c, "send: %s (%llu bytes sent)", strerror(errno), (unsigned long long)c->bytes_out);
        return 0;
    }
    srv_link_spend(&c->link, link_cfg(c), (size_t)w);
    c->bytes_out += (uint64_t)w;
    c->last_tx_us = now;
    written = (size_t)w;
    while (w > 0 && c->job_count) {
        srv_job *j = &c->jobs[c->job_head];
        uint32_t left = job_wire_len(j) - j->done, t = (size_t)w < left ? (uint32_t)w : left;
        j->done += t;
        w -= t;
        if (j->done == job_wire_len(j)) {
            c->frames_out++;
            c->job_head = (c->job_head + 1) % SRV_MAX_JOBS;
            c->job_count--;
        }
    }
    if (written < offered) {
        c->want_write = 1;   /* the socket took part of it: wait for room */
        c->blocked = 1;
        return 0;
    }
    c->blocked = 0;
    return 1;
}

static int idle_output(const srv_conn *c)
{
    return !c->job_count && !c->op_count && !c->answering && c->upd_off >= c->upd_len;
}

void srv_conn_pump(srv_conn *c, int64_t now)
{
    int rounds = 0;

    c->wake_us = 0;
    c->want_write = 0;
    for (;;) {
        int made = 0;
        if (c->state == SRV_CONN_CLOSED)
            break;
        if (++rounds > 64) {
            c->want_write = 1;   /* more to send: come back when the loop has
                                    served the others (fairness) */
            break;
        }
        while (c->state != SRV_CONN_CLOSED && make_job(c, now))
            made = 1;
        if (c->rx_len && room_for_ops(c))
            parse(c, now);   /* frames left in the buffer while the ops were full */
        if (!c->job_count) {
            if (!made)
                break;
            continue;
        }
        if (!write_some(c, now) || c->state == SRV_CONN_CLOSED)
            break;
    }
    if (c->state == SRV_CONN_FAILING && !c->job_count)
        c->state = SRV_CONN_CLOSED;
    else if (c->state == SRV_CONN_DRAINING && idle_output(c))
        c->state = SRV_CONN_CLOSED;
    /* backpressure: read only while there is room for what the client may
     * ask and the output is at most one frame behind. Frames the link
     * emulation holds (latency, rate) would be in the kernel's buffer or on
     * the wire on a real link, where they do not stop the server reading:
     * with emulation on, the output is behind when the socket is full.
     * (Not reading them delayed each request by the time the queue took to
     * drain, and its emulated latency then started only at the read.) */
    {
        const srv_link_config *l = link_cfg(c);
        int behind = l->rate_bytes > 0 || l->latency_us > 0 ? c->blocked : c->job_count > 1;
        c->want_read = reading(c) && !c->eof && room_for_ops(c) && !behind && c->rx_len < SRV_RX_CAP;
    }
}

void srv_conn_check_time(srv_conn *c, int64_t now, int64_t idle_us)
{
    if (c->state == SRV_CONN_CLOSED)
        return;
    if ((c->state == SRV_CONN_FAILING || c->state == SRV_CONN_DRAINING) && c->deadline_us &&
        now >= c->deadline_us) {
        close_now(c, "%s: output not taken before the deadline",
                  c->state == SRV_CONN_FAILING ? "after error" : "draining");
        c->abort = 1;
        return;
    }
    if (c->blocked && c->job_count && now - c->last_tx_us >= idle_us) {
        close_now(c, "slow client: read nothing for %lld s", (long long)(idle_us / 1000000));
        c->abort = 1;
        return;
    }
    if (reading(c) && idle_output(c) && now - c->last_rx_us >= idle_us)
        fail(c, LUMO_ERR_STATE, "idle: sent nothing for %lld s", (long long)(idle_us / 1000000));
}

void srv_conn_hangup(srv_conn *c)
{
    int e = 0;
    socklen_t l = sizeof e;

    if (c->state == SRV_CONN_CLOSED)
        return;
    if (getsockopt(c->fd, SOL_SOCKET, SO_ERROR, &e, &l) < 0 || !e)
        e = ECONNRESET;
    close_now(c, "connection lost: %s (%llu bytes sent)", strerror(e), (unsigned long long)c->bytes_out);
}

void srv_conn_drain(srv_conn *c, int64_t deadline_us)
{
    if (c->state == SRV_CONN_WAIT_HELLO) {
        close_now(c, "server shutdown");
        return;
    }
    if (c->state == SRV_CONN_READY) {
        set_reason(c, "server shutdown");
        c->state = SRV_CONN_DRAINING;
    }
    if (!c->deadline_us || c->deadline_us > deadline_us)
        c->deadline_us = deadline_us;
}

static const char *form_name(uint8_t f)
{
    return f == LUMO_IVG_FORM_QUANTIZED ? "quantized" : f == LUMO_IVG_FORM_FLOAT ? "binary32" : "no IVG";
}

void srv_conn_summary(const srv_conn *c, int64_t now, char *out, size_t cap)
{
    int n = snprintf(out, cap, "#%llu %s %s: ", (unsigned long long)c->id, c->peer, c->serial ? "serial" : c->usb ? "usb" : "tcp");

    if (n < 0 || (size_t)n >= cap)
        return;
    if (c->hello_seen)
        n += snprintf(out + n, cap - (size_t)n, "HELLO %s %ux%u %s max %u%s, ", c->pkg ? c->pkg->name : "?",
                      c->width, c->height, form_name(c->form), c->max_payload,
                      c->resume_id ? (c->pkg && c->resume_id == c->pkg->id ? " resume" : " resume (other package)")
                                   : "");
    else
        n += snprintf(out + n, cap - (size_t)n, "no HELLO, ");
    if (n < 0 || (size_t)n >= cap)
        return;
    n += snprintf(out + n, cap - (size_t)n, "%u requests, %llu bytes sent in %u frames (%llu record bytes), %.2f s",
                  c->requests, (unsigned long long)c->bytes_out, c->frames_out, (unsigned long long)c->data_bytes,
                  (double)(now - c->connected_us) / 1e6);
    if (n < 0 || (size_t)n >= cap)
        return;
    if (c->serial && (c->resyncs || c->garbage))
        n += snprintf(out + n, cap - (size_t)n, ", %u resyncs over %llu garbage bytes", c->resyncs,
                      (unsigned long long)c->garbage);
    if (n < 0 || (size_t)n >= cap)
        return;
    snprintf(out + n, cap - (size_t)n, ": %s", c->reason[0] ? c->reason : "closed");
}
