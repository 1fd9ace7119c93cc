/* fuzz_net.c — hostile bytes into the protocol codec (lumo/net.h,
 * docs/protocol.md). The input is read three ways:
 *   1. as a serial byte stream of frames: frame decode, resynchronisation
 *      after every refusal (docs/protocol.md §1), each frame's payload
 *      through its decoder;
 *   2. the same after recomputing the CRC of every frame its headers chain
 *      to, so mutations reach the payload decoders (seeds: frame streams
 *      from the encoder in tests/fuzz/seeds/fuzz_net/);
 *   3. the bytes after the first as the payload of the type the first byte
 *      names.
 * Whatever a decoder takes is encoded again and must frame-decode and
 * decode to the same fields (and, for WELCOME, the same payload bytes):
 * abort on any mismatch. Every other decoder must refuse the frame (STATE).
 */
#include <stdint.h>
#include <stddef.h>
#include <string.h>
#include "lumo/net.h"
#include "lumo/wire.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define OUT_CAP ((size_t)1 << 20)
#define CHECK(c) do { if (!(c)) __builtin_trap(); } while (0)

static uint8_t g_out[OUT_CAP];
static uint8_t g_copy[OUT_CAP];
static uint8_t g_head[LUMO_NET_HEADER + LUMO_NET_DATA_HEAD];
static uint8_t g_text[LUMO_NET_MAX_TEXT + 1];
static uint32_t g_cursors[LUMO_MAX_MESHES];
static lumo_net_msg g_msgs[LUMO_NET_MAX_WELCOME_MSGS];

/* The re-encoded frame g_out[0..n) decoded as one whole frame of `type`. */
static lumo_net_frame reframe(size_t n, uint8_t type)
{
    lumo_net_frame f;
    size_t used = 0;

    CHECK(lumo_net_frame_decode(g_out, n, LUMO_NET_MAX_PAYLOAD, &f, &used) == LUMO_OK);
    CHECK(used == n && f.type == type);
    return f;
}

static void again_hello(const lumo_net_hello *h)
{
    lumo_net_hello d;
    lumo_net_frame f;
    size_t n = 0;
    uint32_t i;

    for (i = 0; i < h->mesh_count; i++)
        g_cursors[i] = lumo_net_hello_cursor(h, i);
    CHECK(lumo_net_hello_encode(h, g_cursors, g_out, OUT_CAP, &n) == LUMO_OK);
    f = reframe(n, LUMO_NET_HELLO);
    CHECK(lumo_net_hello_decode(&f, &d) == LUMO_OK);
    CHECK(d.package == h->package && d.arena_bytes == h->arena_bytes && d.max_payload == h->max_payload);
    CHECK(d.width == h->width && d.height == h->height && d.ivg_form == h->ivg_form);
    CHECK(d.flags == h->flags && d.resume_id == h->resume_id && d.mesh_count == h->mesh_count);
    for (i = 0; i < h->mesh_count; i++)
        CHECK(lumo_net_hello_cursor(&d, i) == g_cursors[i]);
}

static void again_welcome(const lumo_net_welcome *w, const lumo_net_frame *orig)
{
    lumo_net_welcome d;
    lumo_net_frame f;
    lumo_net_msg m;
    size_t n = 0, at = 0;
    uint32_t i;

    for (i = 0; i < w->count; i++)
        CHECK(lumo_net_welcome_next(w, &at, &g_msgs[i]) == LUMO_OK);
    CHECK(at == w->msgs_len && lumo_net_welcome_next(w, &at, &m) == LUMO_ERR_RANGE);
    if (orig->len + LUMO_NET_OVERHEAD > OUT_CAP)
        return;
    CHECK(lumo_net_welcome_encode(w->package_id, w->arena_need, g_msgs, w->count, g_out, OUT_CAP, &n) == LUMO_OK);
    f = reframe(n, LUMO_NET_WELCOME);
    /* No reserved field, zero padding: the same payload, byte for byte. */
    CHECK(f.len == orig->len && memcmp(f.payload, orig->payload, f.len) == 0);
    CHECK(lumo_net_welcome_decode(&f, &d) == LUMO_OK);
    CHECK(d.package_id == w->package_id && d.arena_need == w->arena_need && d.count == w->count);
    for (at = 0, i = 0; i < d.count; i++) {
        CHECK(lumo_net_welcome_next(&d, &at, &m) == LUMO_OK);
        CHECK(m.type == g_msgs[i].type && m.index == g_msgs[i].index && m.len == g_msgs[i].len);
        CHECK(m.len == 0 || memcmp(m.data, g_msgs[i].data, m.len) == 0);
    }
}

static void again_request(const lumo_net_request *r)
{
    lumo_net_request d;
    lumo_net_frame f;
    size_t n = 0;

    CHECK(lumo_net_request_encode(r, g_out, OUT_CAP, &n) == LUMO_OK);
    f = reframe(n, LUMO_NET_REQUEST);
    CHECK(lumo_net_request_decode(&f, &d) == LUMO_OK);
    CHECK(d.channel == r->channel && d.mesh == r->mesh && d.cursor == r->cursor && d.amount == r->amount);
}

/* DATA through both paths: data_encode, and data_head + CRC over the bytes. */
static void again_data(const lumo_net_data *m)
{
    lumo_net_data d;
    lumo_net_frame f;
    size_t n = 0;
    uint32_t crc;

    if ((size_t)m->len + LUMO_NET_DATA_HEAD + LUMO_NET_OVERHEAD > OUT_CAP)
        return;
    CHECK(lumo_net_data_encode(m, g_out, OUT_CAP, &n) == LUMO_OK);
    crc = lumo_net_data_head(m, g_head);
    crc = lumo_wire_crc32(crc, m->bytes, m->len);
    CHECK(memcmp(g_head, g_out, sizeof g_head) == 0);
    CHECK(lumo_wire_le32(g_out + n - LUMO_NET_TRAILER) == crc);
    f = reframe(n, LUMO_NET_DATA);
    CHECK(lumo_net_data_decode(&f, &d) == LUMO_OK);
    CHECK(d.channel == m->channel && d.form == m->form && d.mesh == m->mesh && d.first == m->first);
    CHECK(d.count == m->count && d.records == m->records && d.len == m->len);
    CHECK(d.len == 0 || memcmp(d.bytes, m->bytes, d.len) == 0);
}

static void again_end(const lumo_net_end *e)
{
    lumo_net_end d;
    lumo_net_frame f;
    size_t n = 0;

    CHECK(lumo_net_end_encode(e, g_out, OUT_CAP, &n) == LUMO_OK);
    f = reframe(n, LUMO_NET_END);
    CHECK(lumo_net_end_decode(&f, &d) == LUMO_OK);
    CHECK(d.channel == e->channel && d.mesh == e->mesh);
}

static void again_error(const lumo_net_error *x)
{
    lumo_net_error d;
    lumo_net_frame f;
    size_t n = 0;

    CHECK(x->len <= LUMO_NET_MAX_TEXT);
    memcpy(g_text, x->text, x->len);
    g_text[x->len] = 0;
    CHECK(lumo_net_error_encode(x->status, (const char *)g_text, g_out, OUT_CAP, &n) == LUMO_OK);
    f = reframe(n, LUMO_NET_ERROR);
    CHECK(lumo_net_error_decode(&f, &d) == LUMO_OK);
    CHECK(d.status == x->status && d.len == x->len && memcmp(d.text, x->text, d.len) == 0);
}

static void again_bye(void)
{
    lumo_net_frame f;
    size_t n = 0;

    CHECK(lumo_net_bye_encode(g_out, OUT_CAP, &n) == LUMO_OK);
    f = reframe(n, LUMO_NET_BYE);
    CHECK(lumo_net_bye_decode(&f) == LUMO_OK);
}

static void again_poses(const lumo_net_poses *m)
{
    static lumo_net_pose p[LUMO_NET_MAX_POSES];
    lumo_net_poses d;
    lumo_net_pose q;
    lumo_net_frame f;
    size_t n = 0;
    uint32_t i;

    for (i = 0; i < m->count; i++)
        lumo_net_poses_get(m, i, &p[i]);
    CHECK(lumo_net_poses_encode(p, m->count, g_out, OUT_CAP, &n) == LUMO_OK);
    f = reframe(n, LUMO_NET_POSES);
    CHECK(lumo_net_poses_decode(&f, &d) == LUMO_OK && d.count == m->count);
    for (i = 0; i < d.count; i++) {
        lumo_net_poses_get(&d, i, &q);
        CHECK(q.kind == p[i].kind && q.index == p[i].index && q.yaw_deg == p[i].yaw_deg);
        CHECK(q.t[0] == p[i].t[0] && q.t[1] == p[i].t[1] && q.t[2] == p[i].t[2]);
    }
}

/* Decoder `t` on frame f; on success the round trip above. */
static lumo_status decode_as(uint8_t t, const lumo_net_frame *f)
{
    lumo_net_hello h;
    lumo_net_welcome w;
    lumo_net_request r;
    lumo_net_data d;
    lumo_net_end e;
    lumo_net_error x;
    lumo_net_poses ps;
    lumo_status st;

    switch (t) {
    case LUMO_NET_POSES:
        if ((st = lumo_net_poses_decode(f, &ps)) == LUMO_OK)
            again_poses(&ps);
        return st;
    case LUMO_NET_HELLO:
        if ((st = lumo_net_hello_decode(f, &h)) == LUMO_OK)
            again_hello(&h);
        return st;
    case LUMO_NET_WELCOME:
        if ((st = lumo_net_welcome_decode(f, &w)) == LUMO_OK)
            again_welcome(&w, f);
        return st;
    case LUMO_NET_REQUEST:
        if ((st = lumo_net_request_decode(f, &r)) == LUMO_OK)
            again_request(&r);
        return st;
    case LUMO_NET_DATA:
        if ((st = lumo_net_data_decode(f, &d)) == LUMO_OK)
            again_data(&d);
        return st;
    case LUMO_NET_END:
        if ((st = lumo_net_end_decode(f, &e)) == LUMO_OK)
            again_end(&e);
        return st;
    case LUMO_NET_ERROR:
        if ((st = lumo_net_error_decode(f, &x)) == LUMO_OK)
            again_error(&x);
        return st;
    default:   /* BYE */
        if ((st = lumo_net_bye_decode(f)) == LUMO_OK)
            again_bye();
        return st;
    }
}

/* A frame's own decoder, then every other one (STATE). */
static void check_frame(const lumo_net_frame *f)
{
    uint8_t t;

    CHECK(f->type >= LUMO_NET_HELLO && f->type <= LUMO_NET_TYPE_LAST);
    decode_as(f->type, f);
    for (t = LUMO_NET_HELLO; t <= LUMO_NET_TYPE_LAST; t++)
        if (t != f->type)
            CHECK(decode_as(t, f) == LUMO_ERR_STATE);
}

/* Way 1: a serial receiver over d[0..size). */
static void walk_stream(const uint8_t *d, size_t size, uint32_t max_payload)
{
    size_t at = 0;

    while (at < size) {
        lumo_net_frame f;
        size_t used = 0, next;
        lumo_status st = lumo_net_frame_decode(d + at, size - at, max_payload, &f, &used);

        if (st == LUMO_OK) {
            CHECK(used >= LUMO_NET_OVERHEAD && used <= size - at && f.len == used - LUMO_NET_OVERHEAD);
            CHECK(f.payload == d + at + LUMO_NET_HEADER && f.len <= max_payload);
            check_frame(&f);
            at += used;
            continue;
        }
        if (st == LUMO_ERR_TRUNCATED) {
            CHECK(used > size - at);
            return;
        }
        next = lumo_net_resync(d, size, at + 1);
        CHECK(next > at && next <= size);
        at = next;
    }
}

/* Way 2: recompute the CRC of every frame the headers chain to. */
static void fix_crcs(uint8_t *d, size_t size)
{
    size_t at = 0;

    while (size - at >= LUMO_NET_OVERHEAD) {
        size_t body = LUMO_NET_HEADER + (size_t)lumo_wire_le32(d + at + 4);
        if (body > size - at - LUMO_NET_TRAILER)
            return;
        lumo_wire_put_le32(d + at + body, lumo_wire_crc32(0, d + at, body));
        at += body + LUMO_NET_TRAILER;
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    lumo_net_frame f;

    if (size > OUT_CAP)
        return 0;
    walk_stream(data, size, LUMO_NET_MAX_PAYLOAD);
    memcpy(g_copy, data, size);
    fix_crcs(g_copy, size);
    walk_stream(g_copy, size, LUMO_NET_MAX_PAYLOAD);
    walk_stream(g_copy, size, size ? 64u + data[0] : 0);   /* a small receiver limit too */
    if (size == 0)
        return 0;
    f.type = (uint8_t)(LUMO_NET_HELLO + data[0] % LUMO_NET_TYPE_LAST);
    f.len = (uint32_t)(size - 1);
    f.payload = data + 1;
    check_frame(&f);
    return 0;
}
