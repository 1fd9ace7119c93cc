/*
 * golden_net.c — the protocol codec (lumo/net.h) over PRNG messages, hashed
 * stage by stage; host and board must print the same hashes. Each round
 * encodes one message of every type (HELLO with cursors, WELCOME with
 * padded messages, REQUEST, DATA whole and by its zero-copy head, END,
 * ERROR, BYE) into one stream, decodes the stream back, refuses a flipped
 * byte and a truncation of every frame, and runs a serial receiver over the
 * frames with garbage between them.
 */
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include "lumo/net.h"
#include "lumo/wire.h"
#include "board.h"
#include "golden.h"

int main(void);

#define ROUNDS   300
#define FRAMES   8          /* per round: the seven types, DATA twice */
#define STREAM   16384

static uint8_t g_src[512];                 /* random bytes messages point into */
static uint8_t g_stream[STREAM];           /* one round's frames */
static size_t  g_at[FRAMES + 1];           /* frame offsets in g_stream */
static uint8_t g_serial[STREAM + 1024];    /* the frames with garbage between */
static uint8_t g_work[STREAM];
static uint32_t g_cursors[LUMO_MAX_MESHES];
static char g_text[LUMO_NET_MAX_TEXT + 1];

static uint32_t rnd(bt_rng *r, uint32_t n)
{
    return (uint32_t)(bt_rng_next(r) % n);
}

/* ---- encoding ---------------------------------------------------------------------- */

static lumo_status put_hello(bt_rng *r, uint8_t *out, size_t cap, size_t *n)
{
    static const uint8_t forms[3] = {0, 1, LUMO_NET_FORM_NONE};
    lumo_net_hello h;
    uint32_t i;

    h.package = rnd(r, 4);
    h.arena_bytes = (uint32_t)bt_rng_next(r);
    h.max_payload = LUMO_NET_MIN_PAYLOAD + rnd(r, LUMO_NET_MAX_PAYLOAD);
    h.width = (uint16_t)bt_rng_next(r);
    h.height = (uint16_t)bt_rng_next(r);
    h.ivg_form = forms[rnd(r, 3)];
    h.flags = (uint8_t)rnd(r, 2);
    h.resume_id = rnd(r, 2) ? (uint32_t)bt_rng_next(r) : 0;
    h.mesh_count = h.resume_id ? rnd(r, LUMO_MAX_MESHES + 1) : 0;
    h.cursors = NULL;
    for (i = 0; i < h.mesh_count; i++)
        g_cursors[i] = rnd(r, 5000);
    return lumo_net_hello_encode(&h, g_cursors, out, cap, n);
}

static lumo_status put_welcome(bt_rng *r, uint8_t *out, size_t cap, size_t *n)
{
    lumo_net_msg msgs[6];
    uint32_t count = rnd(r, 7), id, need, i;

    for (i = 0; i < count; i++) {
        msgs[i].type = (uint32_t)bt_rng_next(r);
        msgs[i].index = rnd(r, LUMO_MAX_MESHES);
        msgs[i].len = rnd(r, 90);
        msgs[i].data = g_src + rnd(r, 256);
    }
    id = (uint32_t)bt_rng_next(r);   /* one draw per statement: a fixed order */
    need = (uint32_t)bt_rng_next(r);
    return lumo_net_welcome_encode(id, need, msgs, count, out, cap, n);
}

static lumo_status put_request(bt_rng *r, uint8_t *out, size_t cap, size_t *n)
{
    lumo_net_request q;

    q.channel = (uint8_t)rnd(r, 2);
    q.mesh = q.channel == LUMO_NET_GEOMETRY ? rnd(r, LUMO_MAX_MESHES) : 0;
    q.cursor = rnd(r, 100000);
    q.amount = 1 + rnd(r, 100000);
    return lumo_net_request_encode(&q, out, cap, n);
}

/* A DATA within the protocol: geometry (records = count >= 1) or lighting
 * (a form, records >= count, count 0 for a split round). */
static void pick_data(bt_rng *r, lumo_net_data *d)
{
    d->channel = (uint8_t)rnd(r, 2);
    d->first = rnd(r, 1000);
    d->bytes = g_src + rnd(r, 256);
    d->len = rnd(r, 250);
    if (d->channel == LUMO_NET_GEOMETRY) {
        d->form = 0;
        d->mesh = rnd(r, LUMO_MAX_MESHES);
        d->count = d->records = 1 + rnd(r, 8);
        return;
    }
    d->form = (uint8_t)rnd(r, 2);
    d->mesh = 0;
    d->count = rnd(r, 4);
    d->records = d->count + rnd(r, 6) + (d->count == 0);
}

static lumo_status put_data(bt_rng *r, uint8_t *out, size_t cap, size_t *n)
{
    lumo_net_data d;

    pick_data(r, &d);
    return lumo_net_data_encode(&d, out, cap, n);
}

/* DATA by the zero-copy path: head, the bytes, the CRC continued over them. */
static lumo_status put_data_head(bt_rng *r, uint8_t *out, size_t cap, size_t *n)
{
    lumo_net_data d;
    uint32_t crc;
    size_t size;

    pick_data(r, &d);
    size = LUMO_NET_HEADER + LUMO_NET_DATA_HEAD + d.len + LUMO_NET_TRAILER;
    if (cap < size)
        return LUMO_ERR_NOMEM;
    crc = lumo_net_data_head(&d, out);
    memcpy(out + LUMO_NET_HEADER + LUMO_NET_DATA_HEAD, d.bytes, d.len);
    crc = lumo_wire_crc32(crc, d.bytes, d.len);
    lumo_wire_put_le32(out + size - LUMO_NET_TRAILER, crc);
    *n = size;
    return LUMO_OK;
}

static lumo_status put_end(bt_rng *r, uint8_t *out, size_t cap, size_t *n)
{
    lumo_net_end e;

    e.channel = (uint8_t)rnd(r, 2);
    e.mesh = e.channel == LUMO_NET_GEOMETRY ? rnd(r, LUMO_MAX_MESHES) : 0;
    return lumo_net_end_encode(&e, out, cap, n);
}

static lumo_status put_error(bt_rng *r, uint8_t *out, size_t cap, size_t *n)
{
    uint32_t len = rnd(r, LUMO_NET_MAX_TEXT + 1), i;

    for (i = 0; i < len; i++)
        g_text[i] = (char)(' ' + rnd(r, 95));
    g_text[len] = 0;
    return lumo_net_error_encode(rnd(r, LUMO_STATUS_COUNT), g_text, out, cap, n);
}

static lumo_status put_bye(bt_rng *r, uint8_t *out, size_t cap, size_t *n)
{
    (void)r;
    return lumo_net_bye_encode(out, cap, n);
}

typedef lumo_status (*put_fn)(bt_rng *r, uint8_t *out, size_t cap, size_t *n);
static const put_fn k_put[FRAMES] = {put_hello, put_welcome, put_request, put_data, put_data_head,
                                     put_end, put_error, put_bye};

/* One round's frames into g_stream (offsets in g_at); hashes their bytes. */
static int encode_round(bt_rng *r, uint64_t *h)
{
    size_t at = 0, n = 0;
    int k;

    for (k = 0; k < FRAMES; k++) {
        g_at[k] = at;
        if (k_put[k](r, g_stream + at, STREAM - at, &n) != LUMO_OK)
            return 1;
        *h = bt_fnv1a(*h, g_stream + at, (uint32_t)n);
        at += n;
    }
    g_at[FRAMES] = at;
    return 0;
}

/* ---- decoding ---------------------------------------------------------------------- */

static uint64_t hash_hello(uint64_t h, const lumo_net_frame *f)
{
    lumo_net_hello m;
    uint32_t i;
    lumo_status st = lumo_net_hello_decode(f, &m);

    h = bt_fnv1a_u32(h, (uint32_t)st);
    if (st)
        return h;
    h = bt_fnv1a_u32(h, m.package);
    h = bt_fnv1a_u32(h, m.arena_bytes);
    h = bt_fnv1a_u32(h, m.max_payload);
    h = bt_fnv1a_u32(h, (uint32_t)m.width << 16 | m.height);
    h = bt_fnv1a_u32(h, (uint32_t)m.ivg_form << 8 | m.flags);
    h = bt_fnv1a_u32(h, m.resume_id);
    h = bt_fnv1a_u32(h, m.mesh_count);
    for (i = 0; i < m.mesh_count; i++)
        h = bt_fnv1a_u32(h, lumo_net_hello_cursor(&m, i));
    return h;
}

static uint64_t hash_welcome(uint64_t h, const lumo_net_frame *f)
{
    lumo_net_welcome m;
    lumo_net_msg msg;
    size_t at = 0;
    lumo_status st = lumo_net_welcome_decode(f, &m);

    h = bt_fnv1a_u32(h, (uint32_t)st);
    if (st)
        return h;
    h = bt_fnv1a_u32(h, m.package_id);
    h = bt_fnv1a_u32(h, m.arena_need);
    h = bt_fnv1a_u32(h, m.count);
    while ((st = lumo_net_welcome_next(&m, &at, &msg)) == LUMO_OK) {
        h = bt_fnv1a_u32(h, msg.type);
        h = bt_fnv1a_u32(h, msg.index);
        h = bt_fnv1a_u32(h, msg.len);
        h = bt_fnv1a(h, msg.data, msg.len);
        h = bt_fnv1a_u32(h, (uint32_t)at);
    }
    return bt_fnv1a_u32(h, (uint32_t)st);
}

static uint64_t hash_request(uint64_t h, const lumo_net_frame *f)
{
    lumo_net_request m;
    lumo_status st = lumo_net_request_decode(f, &m);

    h = bt_fnv1a_u32(h, (uint32_t)st);
    if (st)
        return h;
    h = bt_fnv1a_u32(h, m.channel);
    h = bt_fnv1a_u32(h, m.mesh);
    h = bt_fnv1a_u32(h, m.cursor);
    return bt_fnv1a_u32(h, m.amount);
}

static uint64_t hash_data(uint64_t h, const lumo_net_frame *f)
{
    lumo_net_data m;
    lumo_status st = lumo_net_data_decode(f, &m);

    h = bt_fnv1a_u32(h, (uint32_t)st);
    if (st)
        return h;
    h = bt_fnv1a_u32(h, (uint32_t)m.channel << 8 | m.form);
    h = bt_fnv1a_u32(h, m.mesh);
    h = bt_fnv1a_u32(h, m.first);
    h = bt_fnv1a_u32(h, m.count);
    h = bt_fnv1a_u32(h, m.records);
    h = bt_fnv1a_u32(h, m.len);
    return bt_fnv1a(h, m.bytes, m.len);
}

static uint64_t hash_end(uint64_t h, const lumo_net_frame *f)
{
    lumo_net_end m;
    lumo_status st = lumo_net_end_decode(f, &m);

    h = bt_fnv1a_u32(h, (uint32_t)st);
    if (st)
        return h;
    h = bt_fnv1a_u32(h, m.channel);
    return bt_fnv1a_u32(h, m.mesh);
}

static uint64_t hash_error(uint64_t h, const lumo_net_frame *f)
{
    lumo_net_error m;
    lumo_status st = lumo_net_error_decode(f, &m);

    h = bt_fnv1a_u32(h, (uint32_t)st);
    if (st)
        return h;
    h = bt_fnv1a_u32(h, m.status);
    h = bt_fnv1a_u32(h, m.len);
    return bt_fnv1a(h, m.text, m.len);
}

/* A frame's fields through its own decoder. */
static uint64_t hash_frame(uint64_t h, const lumo_net_frame *f)
{
    h = bt_fnv1a_u32(h, (uint32_t)f->type << 24 | f->len);
    switch (f->type) {
    case LUMO_NET_HELLO: return hash_hello(h, f);
    case LUMO_NET_WELCOME: return hash_welcome(h, f);
    case LUMO_NET_REQUEST: return hash_request(h, f);
    case LUMO_NET_DATA: return hash_data(h, f);
    case LUMO_NET_END: return hash_end(h, f);
    case LUMO_NET_ERROR: return hash_error(h, f);
    default: return bt_fnv1a_u32(h, (uint32_t)lumo_net_bye_decode(f));
    }
}

/* The round's stream frame by frame; every frame must decode. */
static int decode_round(uint64_t *h)
{
    size_t at = 0, used = 0;
    int k;

    for (k = 0; k < FRAMES; k++) {
        lumo_net_frame f;
        lumo_status st = lumo_net_frame_decode(g_stream + at, g_at[FRAMES] - at, LUMO_NET_MAX_PAYLOAD, &f, &used);
        if (st != LUMO_OK || used != g_at[k + 1] - g_at[k])
            return 1;
        *h = hash_frame(*h, &f);
        at += used;
    }
    return 0;
}

/* Each frame with one byte changed, and cut short: the status and, when
 * TRUNCATED, the bytes asked for. Nothing changed must ever pass. */
static int refuse_round(bt_rng *r, uint64_t *h)
{
    int k, bad = 0;

    for (k = 0; k < FRAMES; k++) {
        size_t size = g_at[k + 1] - g_at[k], used = 0, cut = rnd(r, (uint32_t)size);
        size_t at = rnd(r, (uint32_t)size);
        uint8_t flip = (uint8_t)(1 + rnd(r, 255));
        lumo_net_frame f;
        lumo_status st;

        memcpy(g_work, g_stream + g_at[k], size);
        g_work[at] ^= flip;
        st = lumo_net_frame_decode(g_work, size, LUMO_NET_MAX_PAYLOAD, &f, &used);
        bad |= st == LUMO_OK;
        *h = bt_fnv1a_u32(*h, (uint32_t)st);
        *h = bt_fnv1a_u32(*h, st == LUMO_ERR_TRUNCATED ? (uint32_t)used : 0);
        st = lumo_net_frame_decode(g_stream + g_at[k], cut, LUMO_NET_MAX_PAYLOAD, &f, &used);
        bad |= st != LUMO_ERR_TRUNCATED;
        *h = bt_fnv1a_u32(*h, (uint32_t)used);
    }
    return bad;
}

/* The frames with garbage between (bytes rich in 'L' and 'S'), one frame
 * garbled; a serial receiver resynchronises through it. Hashes where each
 * frame was found and what was refused; every good frame must be found. */
static int serial_round(bt_rng *r, uint64_t *h)
{
    static const uint8_t junk[4] = {0x4C, 0x53, 0x01, 0xA5};
    size_t n = 0, at = 0, used = 0;
    int k, found = 0, garbled = (int)rnd(r, FRAMES);

    for (k = 0; k < FRAMES; k++) {
        uint32_t g = rnd(r, 24), i;
        for (i = 0; i < g; i++)
            g_serial[n++] = junk[rnd(r, 4)];
        memcpy(g_serial + n, g_stream + g_at[k], g_at[k + 1] - g_at[k]);
        if (k == garbled)
            g_serial[n + LUMO_NET_HEADER - 1 + rnd(r, (uint32_t)(g_at[k + 1] - g_at[k]) - 7)] ^= 0x10;
        n += g_at[k + 1] - g_at[k];
    }
    while (at < n) {
        lumo_net_frame f;
        lumo_status st = lumo_net_frame_decode(g_serial + at, n - at, LUMO_NET_MAX_PAYLOAD, &f, &used);
        *h = bt_fnv1a_u32(*h, (uint32_t)at << 4 | (uint32_t)st);
        if (st == LUMO_OK) {
            *h = hash_frame(*h, &f);
            found++;
            at += used;
        } else {
            /* refused, or TRUNCATED (nothing more comes): the next magic */
            at = lumo_net_resync(g_serial, n, at + 1);
        }
    }
    return found < FRAMES - 1;
}

int main(void)
{
    bt_rng r = {0x4E45540000000001ull};
    uint64_t he = BT_FNV_OFFSET, hd = BT_FNV_OFFSET, hr = BT_FNV_OFFSET, hs = BT_FNV_OFFSET;
    uint32_t t0, i;
    int bad = 0;

    for (i = 0; i < sizeof g_src; i++)
        g_src[i] = (uint8_t)bt_rng_next(&r);
    t0 = board_ticks();
    for (i = 0; i < ROUNDS && !bad; i++) {
        bad |= encode_round(&r, &he);
        bad |= decode_round(&hd);
        bad |= refuse_round(&r, &hr);
        bad |= serial_round(&r, &hs);
    }
    golden_cost("net.rounds", t0);
    golden_hash("net.encode", he);
    golden_hash("net.decode", hd);
    golden_hash("net.refuse", hr);
    golden_hash("net.serial", hs);
    if (bad) {
        con_str("FAILED golden_net: a frame was refused or a garbled one accepted");
        con_nl();
    }
    return golden_done(bad);
}
