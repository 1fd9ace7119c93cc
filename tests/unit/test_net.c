/* test_net.c — the protocol codec (lumo/net.h, docs/protocol.md): every
 * message round-trips encode -> frame decode -> decode with all its fields;
 * every byte flip and truncation of a valid frame is refused with the
 * status and *consumed of §1; the limits and payload checks of §5; serial
 * resynchronisation; the zero-copy DATA path; encoders out of room. The
 * worked example of docs/protocol.md §6 is tests/serve/test_protocol_example.c. */
#include <stdio.h>
#include "test_common.h"
#include "lumo/ivg.h"
#include "lumo/net.h"
#include "lumo/package.h"
#include "lumo/wire.h"

#define BUF 4096

/* Any decoded message, for the decoder of a frame's own type. */
typedef union any_msg {
    lumo_net_hello h;
    lumo_net_welcome w;
    lumo_net_request r;
    lumo_net_data d;
    lumo_net_end e;
    lumo_net_error x;
} any_msg;

/* The decoder of type t, whatever the frame's type. */
static lumo_status decode_as(uint8_t t, const lumo_net_frame *f, any_msg *m)
{
    switch (t) {
    case LUMO_NET_HELLO: return lumo_net_hello_decode(f, &m->h);
    case LUMO_NET_WELCOME: return lumo_net_welcome_decode(f, &m->w);
    case LUMO_NET_REQUEST: return lumo_net_request_decode(f, &m->r);
    case LUMO_NET_DATA: return lumo_net_data_decode(f, &m->d);
    case LUMO_NET_END: return lumo_net_end_decode(f, &m->e);
    case LUMO_NET_ERROR: return lumo_net_error_decode(f, &m->x);
    default: return lumo_net_bye_decode(f);
    }
}

static lumo_status decode_any(const lumo_net_frame *f, any_msg *m)
{
    return decode_as(f->type, f, m);
}

/* Decode the whole frame buf[0..n) and assert it is one valid frame. */
static lumo_net_frame frame_of(const uint8_t *buf, size_t n)
{
    lumo_net_frame f;
    size_t used = 0;

    assert_int_equal(lumo_net_frame_decode(buf, n, LUMO_NET_MAX_PAYLOAD, &f, &used), LUMO_OK);
    assert_int_equal(used, n);
    assert_ptr_equal(f.payload, buf + LUMO_NET_HEADER);
    assert_int_equal(f.len, n - LUMO_NET_OVERHEAD);
    return f;
}

/* A frame of `type` around a payload written by hand (len bytes at p). */
static size_t craft(uint8_t *buf, uint8_t type, const uint8_t *p, uint32_t len)
{
    memmove(buf + LUMO_NET_HEADER, p, len);
    lumo_net_frame_seal(buf, type, len);
    return len + LUMO_NET_OVERHEAD;
}

/* The status of the payload p[0..len) as a frame of `type` through its
 * decoder; a refused payload must leave the output as it was. */
static lumo_status payload_status(uint8_t type, const uint8_t *p, uint32_t len)
{
    static uint8_t buf[BUF];
    any_msg m, before;
    lumo_net_frame f;
    lumo_status st;

    f = frame_of(buf, craft(buf, type, p, len));
    memset(&m, 0x5A, sizeof m);
    before = m;
    st = decode_any(&f, &m);
    if (st)
        assert_memory_equal(&m, &before, sizeof m);
    return st;
}

/* ---- the sample messages --------------------------------------------------------- */

static const uint32_t k_cursors[3] = {7, 0, 0xFFFFFFFFu};
static const uint8_t k_bytes[9] = {1, 2, 3, 4, 5, 6, 7, 8, 9};

static lumo_net_hello sample_hello(void)
{
    lumo_net_hello h = {0};
    h.package = 3;
    h.arena_bytes = 8u << 20;
    h.max_payload = 65536;
    h.width = 320;
    h.height = 240;
    h.ivg_form = LUMO_IVG_FORM_QUANTIZED;
    h.flags = LUMO_NET_FLAG_SMOOTHING;
    h.resume_id = 0xDEADBEEFu;
    h.mesh_count = 3;
    return h;
}

/* Messages of 5, 0, 8, 7 and 6 bytes: padded with 3, 0, 0, 1 and 2 zeros. */
static void sample_welcome_msgs(lumo_net_msg msgs[5])
{
    static const uint32_t len[5] = {5, 0, 8, 7, 6};
    uint32_t i;

    for (i = 0; i < 5; i++) {
        msgs[i].type = i == 0 ? LUMO_PKG_INFO : LUMO_PKG_PMSH;
        msgs[i].index = i == 0 ? 0 : i - 1;
        msgs[i].len = len[i];
        msgs[i].data = len[i] ? k_bytes + i % 2 : NULL;
    }
}

static const lumo_net_data k_data[3] = {
    {LUMO_NET_GEOMETRY, 0, 2, 10, 3, 3, k_bytes, 9},
    {LUMO_NET_LIGHTING, LUMO_IVG_FORM_QUANTIZED, 0, 4, 2, 5, k_bytes, 6},
    {LUMO_NET_LIGHTING, LUMO_IVG_FORM_FLOAT, 0, 6, 0, 1, k_bytes, 1},   /* a split round */
};
static const lumo_net_request k_request[2] = {
    {LUMO_NET_GEOMETRY, 1, 12, 500},
    {LUMO_NET_LIGHTING, 0, 3, 1},
};
static const lumo_net_end k_end[2] = {{LUMO_NET_GEOMETRY, 5}, {LUMO_NET_LIGHTING, 0}};

/* Every sample frame, encoded: the inputs of the flip and truncation tests. */
typedef struct sample {
    uint8_t b[256];
    size_t n;
} sample;
#define SAMPLES 12

static size_t build_samples(sample s[SAMPLES])
{
    lumo_net_hello h = sample_hello(), fresh = sample_hello();
    lumo_net_msg msgs[5];
    size_t k = 0, i;

    fresh.mesh_count = 0;
    sample_welcome_msgs(msgs);
    assert_int_equal(lumo_net_hello_encode(&h, k_cursors, s[k].b, 256, &s[k].n), LUMO_OK), k++;
    assert_int_equal(lumo_net_hello_encode(&fresh, NULL, s[k].b, 256, &s[k].n), LUMO_OK), k++;
    assert_int_equal(lumo_net_welcome_encode(0x1234, 99, msgs, 5, s[k].b, 256, &s[k].n), LUMO_OK), k++;
    for (i = 0; i < 2; i++, k++)
        assert_int_equal(lumo_net_request_encode(&k_request[i], s[k].b, 256, &s[k].n), LUMO_OK);
    for (i = 0; i < 3; i++, k++)
        assert_int_equal(lumo_net_data_encode(&k_data[i], s[k].b, 256, &s[k].n), LUMO_OK);
    for (i = 0; i < 2; i++, k++)
        assert_int_equal(lumo_net_end_encode(&k_end[i], s[k].b, 256, &s[k].n), LUMO_OK);
    assert_int_equal(lumo_net_error_encode(LUMO_ERR_RANGE, "cursor past the end", s[k].b, 256, &s[k].n),
                     LUMO_OK), k++;
    assert_int_equal(lumo_net_bye_encode(s[k].b, 256, &s[k].n), LUMO_OK), k++;
    assert_int_equal(k, SAMPLES);
    return k;
}

/* ---- round trips ---------------------------------------------------------------------- */

static void test_hello_round_trip(void **state)
{
    lumo_net_hello h = sample_hello(), d;
    uint8_t buf[256];
    lumo_net_frame f;
    size_t n = 0;
    uint32_t i;
    (void)state;
    assert_int_equal(lumo_net_hello_encode(&h, k_cursors, buf, sizeof buf, &n), LUMO_OK);
    assert_int_equal(n, 12 + 28 + 12);
    f = frame_of(buf, n);
    assert_int_equal(f.type, LUMO_NET_HELLO);
    assert_int_equal(lumo_net_hello_decode(&f, &d), LUMO_OK);
    assert_int_equal(d.package, 3);
    assert_int_equal(d.arena_bytes, 8u << 20);
    assert_int_equal(d.max_payload, 65536);
    assert_int_equal(d.width, 320);
    assert_int_equal(d.height, 240);
    assert_int_equal(d.ivg_form, LUMO_IVG_FORM_QUANTIZED);
    assert_int_equal(d.flags, LUMO_NET_FLAG_SMOOTHING);
    assert_int_equal(d.resume_id, 0xDEADBEEFu);
    assert_int_equal(d.mesh_count, 3);
    for (i = 0; i < 3; i++)
        assert_int_equal(lumo_net_hello_cursor(&d, i), k_cursors[i]);
    assert_int_equal(lumo_net_hello_cursor(&d, 3), 0);
    /* A fresh start: no cursors, none needed; the form "none". */
    h.mesh_count = 0;
    h.resume_id = 0;
    h.ivg_form = LUMO_NET_FORM_NONE;
    assert_int_equal(lumo_net_hello_encode(&h, NULL, buf, sizeof buf, &n), LUMO_OK);
    f = frame_of(buf, n);
    assert_int_equal(lumo_net_hello_decode(&f, &d), LUMO_OK);
    assert_int_equal(d.mesh_count, 0);
    assert_int_equal(d.resume_id, 0);
    assert_int_equal(d.ivg_form, LUMO_NET_FORM_NONE);
    /* All LUMO_MAX_MESHES cursors. */
    {
        static uint32_t many[LUMO_MAX_MESHES];
        static uint8_t big[12 + 28 + 4 * LUMO_MAX_MESHES];
        for (i = 0; i < LUMO_MAX_MESHES; i++)
            many[i] = i * 1000003u;
        h.mesh_count = LUMO_MAX_MESHES;
        assert_int_equal(lumo_net_hello_encode(&h, many, big, sizeof big, &n), LUMO_OK);
        assert_int_equal(n, sizeof big);
        f = frame_of(big, n);
        assert_int_equal(lumo_net_hello_decode(&f, &d), LUMO_OK);
        for (i = 0; i < LUMO_MAX_MESHES; i++)
            assert_int_equal(lumo_net_hello_cursor(&d, i), many[i]);
    }
}

static void test_welcome_round_trip(void **state)
{
    lumo_net_msg msgs[5], m;
    lumo_net_welcome w;
    uint8_t buf[256];
    lumo_net_frame f;
    size_t n = 0, at = 0;
    uint32_t i;
    (void)state;
    sample_welcome_msgs(msgs);
    assert_int_equal(lumo_net_welcome_encode(0xCAFEF00Du, 123456, msgs, 5, buf, sizeof buf, &n), LUMO_OK);
    /* 12 + (12 + 8) + 12 + (12 + 8) + (12 + 8) + (12 + 8) payload bytes. */
    assert_int_equal(n, 12 + 12 + 20 + 12 + 20 + 20 + 20);
    f = frame_of(buf, n);
    assert_int_equal(lumo_net_welcome_decode(&f, &w), LUMO_OK);
    assert_int_equal(w.package_id, 0xCAFEF00Du);
    assert_int_equal(w.arena_need, 123456);
    assert_int_equal(w.count, 5);
    assert_ptr_equal(w.msgs, f.payload + 12);
    assert_int_equal(w.msgs_len, f.len - 12);
    for (i = 0; i < 5; i++) {
        assert_int_equal(lumo_net_welcome_next(&w, &at, &m), LUMO_OK);
        assert_int_equal(m.type, msgs[i].type);
        assert_int_equal(m.index, msgs[i].index);
        assert_int_equal(m.len, msgs[i].len);
        assert_int_equal(at % 4, 0);
        if (m.len)
            assert_memory_equal(m.data, msgs[i].data, m.len);
    }
    assert_int_equal(at, w.msgs_len);
    assert_int_equal(lumo_net_welcome_next(&w, &at, &m), LUMO_ERR_RANGE);
    assert_int_equal(at, w.msgs_len);
    /* No messages at all. */
    assert_int_equal(lumo_net_welcome_encode(1, 2, NULL, 0, buf, sizeof buf, &n), LUMO_OK);
    assert_int_equal(n, 24);
    f = frame_of(buf, n);
    assert_int_equal(lumo_net_welcome_decode(&f, &w), LUMO_OK);
    assert_int_equal(w.count, 0);
    at = 0;
    assert_int_equal(lumo_net_welcome_next(&w, &at, &m), LUMO_ERR_RANGE);
}

static void test_request_round_trip(void **state)
{
    uint8_t buf[64];
    lumo_net_request r;
    lumo_net_frame f;
    size_t n = 0, i;
    (void)state;
    for (i = 0; i < 2; i++) {
        assert_int_equal(lumo_net_request_encode(&k_request[i], buf, sizeof buf, &n), LUMO_OK);
        assert_int_equal(n, 28);
        f = frame_of(buf, n);
        assert_int_equal(lumo_net_request_decode(&f, &r), LUMO_OK);
        assert_int_equal(r.channel, k_request[i].channel);
        assert_int_equal(r.mesh, k_request[i].mesh);
        assert_int_equal(r.cursor, k_request[i].cursor);
        assert_int_equal(r.amount, k_request[i].amount);
    }
}

static void test_data_round_trip(void **state)
{
    uint8_t buf[64];
    lumo_net_data d;
    lumo_net_frame f;
    size_t n = 0, i;
    (void)state;
    for (i = 0; i < 3; i++) {
        const lumo_net_data *m = &k_data[i];
        assert_int_equal(lumo_net_data_encode(m, buf, sizeof buf, &n), LUMO_OK);
        assert_int_equal(n, 12 + LUMO_NET_DATA_HEAD + m->len);
        f = frame_of(buf, n);
        assert_int_equal(lumo_net_data_decode(&f, &d), LUMO_OK);
        assert_int_equal(d.channel, m->channel);
        assert_int_equal(d.form, m->form);
        assert_int_equal(d.mesh, m->mesh);
        assert_int_equal(d.first, m->first);
        assert_int_equal(d.count, m->count);
        assert_int_equal(d.records, m->records);
        assert_int_equal(d.len, m->len);
        assert_ptr_equal(d.bytes, buf + LUMO_NET_HEADER + LUMO_NET_DATA_HEAD);
        assert_memory_equal(d.bytes, m->bytes, m->len);
    }
}

static void test_end_error_bye_round_trip(void **state)
{
    static char long_text[LUMO_NET_MAX_TEXT + 1];
    uint8_t buf[512];
    lumo_net_end e;
    lumo_net_error x;
    lumo_net_frame f;
    size_t n = 0, i;
    (void)state;
    for (i = 0; i < 2; i++) {
        assert_int_equal(lumo_net_end_encode(&k_end[i], buf, sizeof buf, &n), LUMO_OK);
        assert_int_equal(n, 20);
        f = frame_of(buf, n);
        assert_int_equal(lumo_net_end_decode(&f, &e), LUMO_OK);
        assert_int_equal(e.channel, k_end[i].channel);
        assert_int_equal(e.mesh, k_end[i].mesh);
    }
    assert_int_equal(lumo_net_error_encode(LUMO_ERR_NOMEM, "arena too small", buf, sizeof buf, &n), LUMO_OK);
    assert_int_equal(n, 12 + 8 + 15);
    f = frame_of(buf, n);
    assert_int_equal(lumo_net_error_decode(&f, &x), LUMO_OK);
    assert_int_equal(x.status, LUMO_ERR_NOMEM);
    assert_int_equal(x.len, 15);
    assert_memory_equal(x.text, "arena too small", 15);
    /* No text (NULL or empty) and the longest text. */
    assert_int_equal(lumo_net_error_encode(LUMO_ERR_STATE, NULL, buf, sizeof buf, &n), LUMO_OK);
    f = frame_of(buf, n);
    assert_int_equal(lumo_net_error_decode(&f, &x), LUMO_OK);
    assert_int_equal(x.status, LUMO_ERR_STATE);
    assert_int_equal(x.len, 0);
    memset(long_text, 'x', LUMO_NET_MAX_TEXT);
    assert_int_equal(lumo_net_error_encode(LUMO_ERR_IO, long_text, buf, sizeof buf, &n), LUMO_OK);
    f = frame_of(buf, n);
    assert_int_equal(lumo_net_error_decode(&f, &x), LUMO_OK);
    assert_int_equal(x.len, LUMO_NET_MAX_TEXT);
    assert_int_equal(lumo_net_bye_encode(buf, sizeof buf, &n), LUMO_OK);
    assert_int_equal(n, 12);
    f = frame_of(buf, n);
    assert_int_equal(f.type, LUMO_NET_BYE);
    assert_int_equal(lumo_net_bye_decode(&f), LUMO_OK);
}

/* A decoder given another type's frame: STATE, output untouched. */
static void test_wrong_type(void **state)
{
    static sample s[SAMPLES];
    size_t k, count = build_samples(s);
    (void)state;
    for (k = 0; k < count; k++) {
        lumo_net_frame f = frame_of(s[k].b, s[k].n);
        any_msg m, before;
        uint8_t t;
        assert_int_equal(decode_any(&f, &m), LUMO_OK);
        for (t = LUMO_NET_HELLO; t <= LUMO_NET_BYE; t++) {
            if (t == f.type)
                continue;
            memset(&m, 0x33, sizeof m);
            before = m;
            assert_int_equal(decode_as(t, &f, &m), LUMO_ERR_STATE);
            assert_memory_equal(&m, &before, sizeof m);
        }
    }
}

/* ---- frames: flips, truncations, limits, types, versions ------------------------------ */

/* Every single-byte change of a valid frame is refused by the frame checks
 * (CHECKSUM or a check before it), never accepted nor UNSUPPORTED, and
 * *out / *consumed stay as they were. */
static void test_byte_flips_refused(void **state)
{
    static sample s[SAMPLES];
    static const uint8_t masks[] = {0x01, 0x02, 0x10, 0x80, 0xFF, 0x5A};
    size_t k, i, j, count = build_samples(s);
    (void)state;
    for (k = 0; k < count; k++)
        for (i = 0; i < s[k].n; i++)
            for (j = 0; j < sizeof masks; j++) {
                uint8_t b[256];
                lumo_net_frame f = {0xEE, 0xEEEE, NULL};
                size_t used = 777;
                lumo_status st;
                memcpy(b, s[k].b, s[k].n);
                b[i] ^= masks[j];
                st = lumo_net_frame_decode(b, s[k].n, LUMO_NET_MAX_PAYLOAD, &f, &used);
                if (st != LUMO_ERR_CHECKSUM && st != LUMO_ERR_CORRUPT && st != LUMO_ERR_VERSION
                    && st != LUMO_ERR_LIMIT && st != LUMO_ERR_TRUNCATED)
                    fail_msg("sample %zu byte %zu ^ 0x%02x: status %d", k, i, masks[j], (int)st);
                assert_int_equal(f.type, 0xEE);
                if (st != LUMO_ERR_TRUNCATED)
                    assert_int_equal(used, 777);
                /* Which check fires is fixed by the byte (§1's order). */
                if (i < 2)
                    assert_int_equal(st, LUMO_ERR_CORRUPT);
                else if (i == 2)
                    assert_int_equal(st, LUMO_ERR_VERSION);
                else if (i == 3 || i >= 8)
                    assert_int_equal(st, LUMO_ERR_CHECKSUM);
            }
}

/* Every prefix of a valid frame: TRUNCATED, *consumed the header size
 * until the header is there, then the whole frame's size. */
static void test_truncations(void **state)
{
    static sample s[SAMPLES];
    size_t k, n, count = build_samples(s);
    (void)state;
    for (k = 0; k < count; k++)
        for (n = 0; n < s[k].n; n++) {
            lumo_net_frame f = {0xEE, 0xEEEE, NULL};
            size_t used = 777;
            assert_int_equal(lumo_net_frame_decode(s[k].b, n, LUMO_NET_MAX_PAYLOAD, &f, &used),
                             LUMO_ERR_TRUNCATED);
            assert_int_equal(used, n < LUMO_NET_HEADER ? LUMO_NET_HEADER : s[k].n);
            assert_int_equal(f.type, 0xEE);
        }
}

/* A frame followed by more bytes: only the frame is consumed. */
static void test_frame_in_stream(void **state)
{
    uint8_t b[64];
    lumo_net_frame f;
    size_t n = 0, used = 0;
    (void)state;
    assert_int_equal(lumo_net_end_encode(&k_end[0], b, sizeof b, &n), LUMO_OK);
    memset(b + n, 0x4C, sizeof b - n);
    assert_int_equal(lumo_net_frame_decode(b, sizeof b, 4096, &f, &used), LUMO_OK);
    assert_int_equal(used, n);
    assert_int_equal(f.type, LUMO_NET_END);
}

/* §1: the length against the receiver's limit (and 16 MiB whatever the
 * receiver says), before waiting for the payload. */
static void test_frame_limits(void **state)
{
    uint8_t b[64];
    lumo_net_frame f = {0};
    size_t n = 0, used = 5;
    (void)state;
    assert_int_equal(lumo_net_request_encode(&k_request[0], b, sizeof b, &n), LUMO_OK);
    assert_int_equal(lumo_net_frame_decode(b, n, 16, &f, &used), LUMO_OK);
    assert_int_equal(lumo_net_frame_decode(b, n, 15, &f, &used), LUMO_ERR_LIMIT);
    assert_int_equal(lumo_net_frame_decode(b, 8, 15, &f, &used), LUMO_ERR_LIMIT);
    /* 16 MiB is allowed (and waited for), one byte more is not. */
    lumo_wire_put_le32(b + 4, LUMO_NET_MAX_PAYLOAD);
    used = 0;
    assert_int_equal(lumo_net_frame_decode(b, n, 0xFFFFFFFFu, &f, &used), LUMO_ERR_TRUNCATED);
    assert_int_equal(used, LUMO_NET_MAX_PAYLOAD + 12u);
    lumo_wire_put_le32(b + 4, LUMO_NET_MAX_PAYLOAD + 1);
    used = 3;
    assert_int_equal(lumo_net_frame_decode(b, n, 0xFFFFFFFFu, &f, &used), LUMO_ERR_LIMIT);
    assert_int_equal(lumo_net_frame_decode(b, 8, 0xFFFFFFFFu, &f, &used), LUMO_ERR_LIMIT);
    lumo_wire_put_le32(b + 4, 0xFFFFFFFFu);
    assert_int_equal(lumo_net_frame_decode(b, n, 0xFFFFFFFFu, &f, &used), LUMO_ERR_LIMIT);
    assert_int_equal(used, 3);
}

/* Types 0 and 9..255 (8 is POSES, §9): UNSUPPORTED once the CRC holds; a
 * wrong CRC first. */
static void test_unknown_type(void **state)
{
    static const uint8_t types[] = {0, 9, 10, 0x7F, 0xFF};
    uint8_t b[64], p[4] = {1, 2, 3, 4};
    lumo_net_frame f = {0};
    size_t i, used = 9;
    (void)state;
    for (i = 0; i < sizeof types; i++) {
        size_t n = craft(b, types[i], p, 4);
        assert_int_equal(lumo_net_frame_decode(b, n, 4096, &f, &used), LUMO_ERR_UNSUPPORTED);
        assert_int_equal(used, 9);
        b[n - 1] ^= 1;
        assert_int_equal(lumo_net_frame_decode(b, n, 4096, &f, &used), LUMO_ERR_CHECKSUM);
    }
}

/* A version other than 1: VERSION (before the CRC, whose bytes would be
 * another version's); a wrong magic: CORRUPT. */
static void test_version_and_magic(void **state)
{
    uint8_t b[64];
    lumo_net_frame f = {0};
    size_t n = 0, used = 9;
    unsigned v;
    (void)state;
    assert_int_equal(lumo_net_bye_encode(b, sizeof b, &n), LUMO_OK);
    for (v = 0; v < 256; v++) {
        if (v == LUMO_NET_VERSION)
            continue;
        b[2] = (uint8_t)v;
        lumo_wire_put_le32(b + 8, lumo_wire_crc32(0, b, 8));   /* even with a good CRC */
        assert_int_equal(lumo_net_frame_decode(b, n, 4096, &f, &used), LUMO_ERR_VERSION);
    }
    b[2] = LUMO_NET_VERSION;
    b[1] = 'T';
    lumo_wire_put_le32(b + 8, lumo_wire_crc32(0, b, 8));
    assert_int_equal(lumo_net_frame_decode(b, n, 4096, &f, &used), LUMO_ERR_CORRUPT);
    assert_int_equal(used, 9);
}

/* frame_head + the payload's CRC = seal, byte for byte. */
static void test_seal_and_head(void **state)
{
    uint8_t a[64], h[LUMO_NET_HEADER], p[13];
    uint32_t crc;
    size_t i;
    (void)state;
    for (i = 0; i < sizeof p; i++)
        p[i] = (uint8_t)(i * 37 + 1);
    memcpy(a + LUMO_NET_HEADER, p, sizeof p);
    lumo_net_frame_seal(a, LUMO_NET_DATA, sizeof p);
    crc = lumo_net_frame_head(h, LUMO_NET_DATA, sizeof p);
    crc = lumo_wire_crc32(crc, p, sizeof p);
    assert_memory_equal(a, h, LUMO_NET_HEADER);
    assert_int_equal(lumo_wire_le32(a + LUMO_NET_HEADER + sizeof p), crc);
    assert_int_equal(a[0], 0x4C);
    assert_int_equal(a[1], 0x53);
    assert_int_equal(a[2], 1);
    assert_int_equal(a[3], LUMO_NET_DATA);
    assert_int_equal(lumo_wire_le32(a + 4), sizeof p);
}

/* ---- serial resynchronisation ------------------------------------------------------ */

static void test_resync_offsets(void **state)
{
    static const uint8_t g[] = {0x00, 0x4C, 0x4C, 0x53, 0x01, 0x53, 0x4C};
    (void)state;
    assert_int_equal(lumo_net_resync(g, sizeof g, 0), 2);
    assert_int_equal(lumo_net_resync(g, sizeof g, 2), 2);
    assert_int_equal(lumo_net_resync(g, sizeof g, 3), 6);   /* the lone 'L' at the end is kept */
    assert_int_equal(lumo_net_resync(g, 6, 3), 6);          /* none */
    assert_int_equal(lumo_net_resync(g, sizeof g, 7), 7);
    assert_int_equal(lumo_net_resync(g, sizeof g, 100), 7);
    assert_int_equal(lumo_net_resync(g, 0, 0), 0);
    assert_int_equal(lumo_net_resync(g, 1, 0), 1);
}

/* A serial receiver: garbage, a frame, garbage holding a false magic, a
 * garbled frame, a frame. It decodes the good frames and skips the rest. */
static void test_resync_stream(void **state)
{
    uint8_t st_buf[512], one[64];
    size_t at = 0, n = 0, got = 0, used;
    lumo_net_frame f;
    lumo_net_request r;
    static const uint8_t junk[] = {0x13, 0x4C, 0x00, 0x4C, 0x53, 0x01, 0x03, 0xFF, 0x4C};
    int guard = 0;
    (void)state;
    memcpy(st_buf + n, junk, sizeof junk), n += sizeof junk;
    assert_int_equal(lumo_net_request_encode(&k_request[0], one, sizeof one, &used), LUMO_OK);
    memcpy(st_buf + n, one, used), n += used;
    memcpy(st_buf + n, junk, sizeof junk), n += sizeof junk;
    memcpy(st_buf + n, one, used), st_buf[n + 14] ^= 0x40, n += used;   /* garbled */
    assert_int_equal(lumo_net_request_encode(&k_request[1], one, sizeof one, &used), LUMO_OK);
    memcpy(st_buf + n, one, used), n += used;
    while (at < n && guard++ < 100) {
        lumo_status s = lumo_net_frame_decode(st_buf + at, n - at, 4096, &f, &used);
        if (s == LUMO_OK) {
            assert_int_equal(lumo_net_request_decode(&f, &r), LUMO_OK);
            assert_int_equal(r.channel, k_request[got].channel);
            assert_int_equal(r.amount, k_request[got].amount);
            got++;
            at += used;
        } else if (s == LUMO_ERR_TRUNCATED && at + used > n) {
            break;   /* a false magic near the end would wait here */
        } else {
            at = lumo_net_resync(st_buf, n, at + 1);
        }
    }
    assert_int_equal(got, 2);
    assert_int_equal(at, n);
}

/* ---- zero copy ------------------------------------------------------------------------ */

/* lumo_net_data_head + CRC over the bytes + trailer = lumo_net_data_encode. */
static void test_data_zero_copy(void **state)
{
    uint8_t whole[128], pieces[128], inplace[128];
    size_t i, n = 0, m = 0;
    (void)state;
    for (i = 0; i < 3; i++) {
        const lumo_net_data *d = &k_data[i];
        uint32_t crc;
        assert_int_equal(lumo_net_data_encode(d, whole, sizeof whole, &n), LUMO_OK);
        crc = lumo_net_data_head(d, pieces);
        memcpy(pieces + LUMO_NET_HEADER + LUMO_NET_DATA_HEAD, d->bytes, d->len);
        crc = lumo_wire_crc32(crc, d->bytes, d->len);
        lumo_wire_put_le32(pieces + LUMO_NET_HEADER + LUMO_NET_DATA_HEAD + d->len, crc);
        assert_int_equal(n, LUMO_NET_HEADER + LUMO_NET_DATA_HEAD + d->len + 4);
        assert_memory_equal(whole, pieces, n);
        /* The bytes already in place at out + 32. */
        {
            lumo_net_data e = *d;
            memset(inplace, 0, sizeof inplace);
            memcpy(inplace + LUMO_NET_HEADER + LUMO_NET_DATA_HEAD, d->bytes, d->len);
            e.bytes = inplace + LUMO_NET_HEADER + LUMO_NET_DATA_HEAD;
            assert_int_equal(lumo_net_data_encode(&e, inplace, sizeof inplace, &m), LUMO_OK);
            assert_int_equal(m, n);
            assert_memory_equal(inplace, whole, n);
        }
    }
}

/* ---- encoders out of room, or given values outside the protocol ------------------------ */

/* Encode sample k into out[0..cap). */
static lumo_status encode_sample(int k, uint8_t *out, size_t cap, size_t *n)
{
    lumo_net_hello h = sample_hello();
    lumo_net_msg msgs[5];

    sample_welcome_msgs(msgs);
    switch (k) {
    case 0: return lumo_net_hello_encode(&h, k_cursors, out, cap, n);
    case 1: return lumo_net_welcome_encode(7, 8, msgs, 5, out, cap, n);
    case 2: return lumo_net_request_encode(&k_request[0], out, cap, n);
    case 3: return lumo_net_data_encode(&k_data[1], out, cap, n);
    case 4: return lumo_net_end_encode(&k_end[0], out, cap, n);
    case 5: return lumo_net_error_encode(LUMO_ERR_IO, "gone", out, cap, n);
    default: return lumo_net_bye_encode(out, cap, n);
    }
}

static void test_encoders_nomem(void **state)
{
    uint8_t b[256], ref[256];
    int k;
    (void)state;
    memset(ref, 0xA5, sizeof ref);
    for (k = 0; k < 7; k++) {
        size_t need = 0, cap;
        assert_int_equal(encode_sample(k, b, sizeof b, &need), LUMO_OK);
        for (cap = 0; cap < need; cap++) {
            size_t n = 4242;
            memset(b, 0xA5, sizeof b);
            assert_int_equal(encode_sample(k, b, cap, &n), LUMO_ERR_NOMEM);
            assert_int_equal(n, 4242);
            assert_memory_equal(b, ref, sizeof b);
        }
        assert_int_equal(encode_sample(k, NULL, 0, &need), LUMO_ERR_NOMEM);
        assert_int_equal(encode_sample(k, b, sizeof b, NULL), LUMO_ERR_ARG);
    }
}

/* What a decoder refuses, its encoder refuses (ARG), writing nothing. */
static void test_encoders_refuse(void **state)
{
    static char text[LUMO_NET_MAX_TEXT + 2];
    static lumo_net_msg many[LUMO_NET_MAX_WELCOME_MSGS + 1];
    uint8_t b[4096], ref[4096];
    lumo_net_hello h = sample_hello();
    lumo_net_request r = k_request[0];
    lumo_net_data d = k_data[0];
    lumo_net_end e = k_end[0];
    lumo_net_msg msg = {LUMO_PKG_INFO, 0, 4, NULL};
    size_t n = 99;
    (void)state;
    memset(b, 0xA5, sizeof b);
    memset(ref, 0xA5, sizeof ref);
    h.mesh_count = LUMO_MAX_MESHES + 1;
    assert_int_equal(lumo_net_hello_encode(&h, k_cursors, b, sizeof b, &n), LUMO_ERR_ARG);
    h = sample_hello();
    assert_int_equal(lumo_net_hello_encode(&h, NULL, b, sizeof b, &n), LUMO_ERR_ARG);
    h.max_payload = LUMO_NET_MIN_PAYLOAD - 1;
    assert_int_equal(lumo_net_hello_encode(&h, k_cursors, b, sizeof b, &n), LUMO_ERR_ARG);
    h = sample_hello();
    h.ivg_form = 2;
    assert_int_equal(lumo_net_hello_encode(&h, k_cursors, b, sizeof b, &n), LUMO_ERR_ARG);
    assert_int_equal(lumo_net_welcome_encode(1, 2, many, LUMO_NET_MAX_WELCOME_MSGS + 1, b, sizeof b, &n),
                     LUMO_ERR_ARG);
    assert_int_equal(lumo_net_welcome_encode(1, 2, &msg, 1, b, sizeof b, &n), LUMO_ERR_ARG);
    msg.len = LUMO_NET_MAX_PAYLOAD;
    msg.data = b;
    assert_int_equal(lumo_net_welcome_encode(1, 2, &msg, 1, b, sizeof b, &n), LUMO_ERR_ARG);
    r.channel = 4;   /* past the PRT channel */
    assert_int_equal(lumo_net_request_encode(&r, b, sizeof b, &n), LUMO_ERR_ARG);
    r = k_request[0];
    r.amount = 0;
    assert_int_equal(lumo_net_request_encode(&r, b, sizeof b, &n), LUMO_ERR_ARG);
    r = k_request[1];
    r.mesh = 1;
    assert_int_equal(lumo_net_request_encode(&r, b, sizeof b, &n), LUMO_ERR_ARG);
    d.count = d.records = 0;
    assert_int_equal(lumo_net_data_encode(&d, b, sizeof b, &n), LUMO_ERR_ARG);
    d = k_data[0];
    d.records = 4;
    assert_int_equal(lumo_net_data_encode(&d, b, sizeof b, &n), LUMO_ERR_ARG);
    d = k_data[0];
    d.len = LUMO_NET_MAX_PAYLOAD - LUMO_NET_DATA_HEAD + 1;
    assert_int_equal(lumo_net_data_encode(&d, b, sizeof b, &n), LUMO_ERR_ARG);
    d = k_data[0];
    d.bytes = NULL;
    assert_int_equal(lumo_net_data_encode(&d, b, sizeof b, &n), LUMO_ERR_ARG);
    d = k_data[1];
    d.form = 2;
    assert_int_equal(lumo_net_data_encode(&d, b, sizeof b, &n), LUMO_ERR_ARG);
    e.channel = 4;
    assert_int_equal(lumo_net_end_encode(&e, b, sizeof b, &n), LUMO_ERR_ARG);
    memset(text, 'y', LUMO_NET_MAX_TEXT + 1);
    assert_int_equal(lumo_net_error_encode(1, text, b, sizeof b, &n), LUMO_ERR_ARG);
    assert_int_equal(n, 99);
    assert_memory_equal(b, ref, sizeof b);
}

/* ---- payload checks of docs/protocol.md §5 ------------------------------------------------ */

static void test_hello_checks(void **state)
{
    uint8_t p[28 + 4 * (LUMO_MAX_MESHES + 2)], b[256];
    lumo_net_hello h = sample_hello();
    size_t n = 0;
    (void)state;
    assert_int_equal(lumo_net_hello_encode(&h, k_cursors, b, sizeof b, &n), LUMO_OK);
    memcpy(p, b + 8, 40);
    assert_int_equal(payload_status(LUMO_NET_HELLO, p, 40), LUMO_OK);
    assert_int_equal(payload_status(LUMO_NET_HELLO, p, 39), LUMO_ERR_TRUNCATED);
    assert_int_equal(payload_status(LUMO_NET_HELLO, p, 27), LUMO_ERR_TRUNCATED);
    p[40] = 0;
    assert_int_equal(payload_status(LUMO_NET_HELLO, p, 41), LUMO_ERR_CORRUPT);
    lumo_wire_put_le32(p + 24, LUMO_MAX_MESHES + 1);   /* M past the limit */
    assert_int_equal(payload_status(LUMO_NET_HELLO, p, 40), LUMO_ERR_LIMIT);
    memset(p + 28, 0, sizeof p - 28);
    assert_int_equal(payload_status(LUMO_NET_HELLO, p, 28 + 4 * (LUMO_MAX_MESHES + 1)), LUMO_ERR_LIMIT);
    lumo_wire_put_le32(p + 24, 0xFFFFFFFFu);
    assert_int_equal(payload_status(LUMO_NET_HELLO, p, 40), LUMO_ERR_LIMIT);
    lumo_wire_put_le32(p + 24, 3);
    lumo_wire_put_le32(p + 8, LUMO_NET_MIN_PAYLOAD - 1);
    assert_int_equal(payload_status(LUMO_NET_HELLO, p, 40), LUMO_ERR_RANGE);
    lumo_wire_put_le32(p + 8, LUMO_NET_MIN_PAYLOAD);
    assert_int_equal(payload_status(LUMO_NET_HELLO, p, 40), LUMO_OK);
    p[16] = 2;
    assert_int_equal(payload_status(LUMO_NET_HELLO, p, 40), LUMO_ERR_RANGE);
    p[16] = LUMO_NET_FORM_NONE;
    p[17] = 0xFF;   /* flags: informational */
    p[18] = p[19] = 0xEE;   /* reserved */
    assert_int_equal(payload_status(LUMO_NET_HELLO, p, 40), LUMO_OK);
}

static void test_welcome_checks(void **state)
{
    uint8_t p[256], b[256];
    lumo_net_msg msgs[5];
    size_t n = 0, len;
    (void)state;
    sample_welcome_msgs(msgs);
    assert_int_equal(lumo_net_welcome_encode(7, 8, msgs, 5, b, sizeof b, &n), LUMO_OK);
    len = n - 12;
    memcpy(p, b + 8, len);
    assert_int_equal(payload_status(LUMO_NET_WELCOME, p, (uint32_t)len), LUMO_OK);
    assert_int_equal(payload_status(LUMO_NET_WELCOME, p, 11), LUMO_ERR_TRUNCATED);
    /* Every shorter payload cuts a message: TRUNCATED; a longer one CORRUPT. */
    for (n = 12; n < len; n++)
        assert_int_equal(payload_status(LUMO_NET_WELCOME, p, (uint32_t)n), LUMO_ERR_TRUNCATED);
    p[len] = 0;
    assert_int_equal(payload_status(LUMO_NET_WELCOME, p, (uint32_t)len + 1), LUMO_ERR_CORRUPT);
    assert_int_equal(payload_status(LUMO_NET_WELCOME, p, (uint32_t)len + 4), LUMO_ERR_CORRUPT);
    /* Padding of message 0 (5 bytes + 3 zeros at 12 + 12 + 5). */
    p[12 + 12 + 5] = 1;
    assert_int_equal(payload_status(LUMO_NET_WELCOME, p, (uint32_t)len), LUMO_ERR_CORRUPT);
    p[12 + 12 + 5] = 0;
    p[12 + 12 + 7] = 0x80;
    assert_int_equal(payload_status(LUMO_NET_WELCOME, p, (uint32_t)len), LUMO_ERR_CORRUPT);
    p[12 + 12 + 7] = 0;
    /* A message length past the payload (also one that wraps). */
    lumo_wire_put_le32(p + 12 + 8, 0xFFFFFFFDu);
    assert_int_equal(payload_status(LUMO_NET_WELCOME, p, (uint32_t)len), LUMO_ERR_TRUNCATED);
    lumo_wire_put_le32(p + 12 + 8, 200);
    assert_int_equal(payload_status(LUMO_NET_WELCOME, p, (uint32_t)len), LUMO_ERR_TRUNCATED);
    lumo_wire_put_le32(p + 12 + 8, 5);
    /* Counts: fewer messages than the payload holds, more, past the limit. */
    lumo_wire_put_le32(p + 8, 4);
    assert_int_equal(payload_status(LUMO_NET_WELCOME, p, (uint32_t)len), LUMO_ERR_CORRUPT);
    lumo_wire_put_le32(p + 8, 6);
    assert_int_equal(payload_status(LUMO_NET_WELCOME, p, (uint32_t)len), LUMO_ERR_TRUNCATED);
    lumo_wire_put_le32(p + 8, LUMO_NET_MAX_WELCOME_MSGS + 1);
    assert_int_equal(payload_status(LUMO_NET_WELCOME, p, (uint32_t)len), LUMO_ERR_LIMIT);
    lumo_wire_put_le32(p + 8, 0xFFFFFFFFu);
    assert_int_equal(payload_status(LUMO_NET_WELCOME, p, (uint32_t)len), LUMO_ERR_LIMIT);
}

/* The largest WELCOME: LUMO_NET_MAX_WELCOME_MSGS empty messages decode. */
static void test_welcome_max_count(void **state)
{
    static lumo_net_msg msgs[LUMO_NET_MAX_WELCOME_MSGS];
    static uint8_t b[24 + 12 * LUMO_NET_MAX_WELCOME_MSGS];
    lumo_net_welcome w;
    lumo_net_frame f;
    lumo_net_msg m;
    size_t n = 0, at = 0;
    uint32_t i;
    (void)state;
    for (i = 0; i < LUMO_NET_MAX_WELCOME_MSGS; i++)
        msgs[i].index = i;
    assert_int_equal(lumo_net_welcome_encode(1, 2, msgs, LUMO_NET_MAX_WELCOME_MSGS, b, sizeof b, &n), LUMO_OK);
    assert_int_equal(n, sizeof b);
    f = frame_of(b, n);
    assert_int_equal(lumo_net_welcome_decode(&f, &w), LUMO_OK);
    for (i = 0; i < LUMO_NET_MAX_WELCOME_MSGS; i++) {
        assert_int_equal(lumo_net_welcome_next(&w, &at, &m), LUMO_OK);
        assert_int_equal(m.index, i);
    }
    assert_int_equal(lumo_net_welcome_next(&w, &at, &m), LUMO_ERR_RANGE);
}

static void put_request(uint8_t *p, uint8_t ch, uint32_t mesh, uint32_t amount)
{
    memset(p, 0, 17);
    p[0] = ch;
    lumo_wire_put_le32(p + 4, mesh);
    lumo_wire_put_le32(p + 8, 77);
    lumo_wire_put_le32(p + 12, amount);
}

static void test_request_checks(void **state)
{
    uint8_t p[17];
    (void)state;
    put_request(p, 0, 3, 1);
    assert_int_equal(payload_status(LUMO_NET_REQUEST, p, 16), LUMO_OK);
    assert_int_equal(payload_status(LUMO_NET_REQUEST, p, 15), LUMO_ERR_TRUNCATED);
    assert_int_equal(payload_status(LUMO_NET_REQUEST, p, 17), LUMO_ERR_CORRUPT);
    p[1] = p[2] = p[3] = 0xFF;   /* reserved: ignored */
    assert_int_equal(payload_status(LUMO_NET_REQUEST, p, 16), LUMO_OK);
    put_request(p, 0, 3, 0);
    assert_int_equal(payload_status(LUMO_NET_REQUEST, p, 16), LUMO_ERR_RANGE);
    put_request(p, 2, 3, 1);
    assert_int_equal(payload_status(LUMO_NET_REQUEST, p, 16), LUMO_ERR_RANGE);
    put_request(p, 1, 3, 1);
    assert_int_equal(payload_status(LUMO_NET_REQUEST, p, 16), LUMO_ERR_RANGE);
    put_request(p, 1, 0, 1);
    assert_int_equal(payload_status(LUMO_NET_REQUEST, p, 16), LUMO_OK);
    put_request(p, 3, 3, 1);   /* PRT names a mesh (§10) */
    assert_int_equal(payload_status(LUMO_NET_REQUEST, p, 16), LUMO_OK);
    put_request(p, 4, 0, 1);
    assert_int_equal(payload_status(LUMO_NET_REQUEST, p, 16), LUMO_ERR_RANGE);
}

static void put_data(uint8_t *p, uint8_t ch, uint8_t form, uint32_t mesh, uint32_t count, uint32_t records)
{
    memset(p, 0, 28);
    p[0] = ch;
    lumo_wire_put_le32(p + 4, mesh);
    lumo_wire_put_le32(p + 8, 5);
    lumo_wire_put_le32(p + 12, count);
    p[16] = form;
    lumo_wire_put_le32(p + 20, records);
}

static void test_data_checks(void **state)
{
    uint8_t p[28];
    (void)state;
    put_data(p, 0, 0, 4, 2, 2);
    assert_int_equal(payload_status(LUMO_NET_DATA, p, 28), LUMO_OK);
    assert_int_equal(payload_status(LUMO_NET_DATA, p, 24), LUMO_OK);   /* no bytes: the session's call */
    assert_int_equal(payload_status(LUMO_NET_DATA, p, 23), LUMO_ERR_TRUNCATED);
    p[1] = p[2] = p[3] = p[17] = p[19] = 0xFF;   /* reserved */
    assert_int_equal(payload_status(LUMO_NET_DATA, p, 28), LUMO_OK);
    put_data(p, 0, 0, 4, 0, 0);   /* geometry needs a batch */
    assert_int_equal(payload_status(LUMO_NET_DATA, p, 28), LUMO_ERR_RANGE);
    put_data(p, 0, 0, 4, 2, 3);
    assert_int_equal(payload_status(LUMO_NET_DATA, p, 28), LUMO_ERR_CORRUPT);
    put_data(p, 0, 1, 4, 2, 2);
    assert_int_equal(payload_status(LUMO_NET_DATA, p, 28), LUMO_ERR_RANGE);
    put_data(p, 4, 0, 0, 2, 2);   /* no channel 4 */
    assert_int_equal(payload_status(LUMO_NET_DATA, p, 28), LUMO_ERR_RANGE);
    /* PRT (§10): first = records = the span's offset (5), count = its bytes */
    put_data(p, 3, 0, 6, 4, 5);
    assert_int_equal(payload_status(LUMO_NET_DATA, p, 28), LUMO_OK);
    assert_int_equal(payload_status(LUMO_NET_DATA, p, 27), LUMO_ERR_CORRUPT);   /* 3 bytes, count 4 */
    put_data(p, 3, 0, 6, 4, 6);
    assert_int_equal(payload_status(LUMO_NET_DATA, p, 28), LUMO_ERR_CORRUPT);   /* records != first */
    put_data(p, 3, 1, 6, 4, 5);
    assert_int_equal(payload_status(LUMO_NET_DATA, p, 28), LUMO_ERR_RANGE);     /* a form */
    put_data(p, 3, 0, 6, 0, 5);
    assert_int_equal(payload_status(LUMO_NET_DATA, p, 24), LUMO_ERR_RANGE);     /* no byte */
    put_data(p, 2, 1, 0, 6, 2);   /* updates (§9): from position 5 to 6 */
    assert_int_equal(payload_status(LUMO_NET_DATA, p, 28), LUMO_OK);
    put_data(p, 2, 1, 0, 5, 2);   /* not past the position held */
    assert_int_equal(payload_status(LUMO_NET_DATA, p, 28), LUMO_ERR_CORRUPT);
    put_data(p, 2, 1, 0, 6, 0);
    assert_int_equal(payload_status(LUMO_NET_DATA, p, 28), LUMO_ERR_RANGE);
    put_data(p, 2, 1, 1, 6, 2);
    assert_int_equal(payload_status(LUMO_NET_DATA, p, 28), LUMO_ERR_RANGE);
    put_data(p, 1, 1, 0, 2, 9);
    assert_int_equal(payload_status(LUMO_NET_DATA, p, 28), LUMO_OK);
    put_data(p, 1, 1, 0, 0, 4);   /* a split round continues */
    assert_int_equal(payload_status(LUMO_NET_DATA, p, 28), LUMO_OK);
    put_data(p, 1, 1, 0, 0, 0);
    assert_int_equal(payload_status(LUMO_NET_DATA, p, 28), LUMO_ERR_RANGE);
    put_data(p, 1, 1, 0, 3, 2);
    assert_int_equal(payload_status(LUMO_NET_DATA, p, 28), LUMO_ERR_CORRUPT);
    put_data(p, 1, 2, 0, 2, 2);
    assert_int_equal(payload_status(LUMO_NET_DATA, p, 28), LUMO_ERR_RANGE);
    put_data(p, 1, 0, 1, 2, 2);
    assert_int_equal(payload_status(LUMO_NET_DATA, p, 28), LUMO_ERR_RANGE);
}

static void test_end_error_bye_checks(void **state)
{
    uint8_t p[300];
    (void)state;
    memset(p, 0, sizeof p);
    lumo_wire_put_le32(p + 4, 9);
    assert_int_equal(payload_status(LUMO_NET_END, p, 8), LUMO_OK);
    assert_int_equal(payload_status(LUMO_NET_END, p, 7), LUMO_ERR_TRUNCATED);
    assert_int_equal(payload_status(LUMO_NET_END, p, 9), LUMO_ERR_CORRUPT);
    p[1] = p[3] = 0x11;   /* reserved */
    assert_int_equal(payload_status(LUMO_NET_END, p, 8), LUMO_OK);
    p[0] = 1;   /* lighting of mesh 9 */
    assert_int_equal(payload_status(LUMO_NET_END, p, 8), LUMO_ERR_RANGE);
    p[0] = 2;
    assert_int_equal(payload_status(LUMO_NET_END, p, 8), LUMO_ERR_RANGE);
    /* ERROR: L <= 256 (CORRUPT past it, §5), the payload exactly 8 + L. */
    memset(p, 'e', sizeof p);
    lumo_wire_put_le32(p, LUMO_ERR_RANGE);
    lumo_wire_put_le32(p + 4, 3);
    assert_int_equal(payload_status(LUMO_NET_ERROR, p, 11), LUMO_OK);
    assert_int_equal(payload_status(LUMO_NET_ERROR, p, 10), LUMO_ERR_TRUNCATED);
    assert_int_equal(payload_status(LUMO_NET_ERROR, p, 7), LUMO_ERR_TRUNCATED);
    assert_int_equal(payload_status(LUMO_NET_ERROR, p, 12), LUMO_ERR_CORRUPT);
    lumo_wire_put_le32(p + 4, 256);
    assert_int_equal(payload_status(LUMO_NET_ERROR, p, 264), LUMO_OK);
    lumo_wire_put_le32(p + 4, 257);
    assert_int_equal(payload_status(LUMO_NET_ERROR, p, 265), LUMO_ERR_CORRUPT);
    lumo_wire_put_le32(p + 4, 0xFFFFFFFFu);
    assert_int_equal(payload_status(LUMO_NET_ERROR, p, 20), LUMO_ERR_CORRUPT);
    lumo_wire_put_le32(p + 4, 3);
    p[9] = 0;   /* a NUL the encoder's C string could not carry */
    assert_int_equal(payload_status(LUMO_NET_ERROR, p, 11), LUMO_ERR_CORRUPT);
    /* BYE: nothing. */
    assert_int_equal(payload_status(LUMO_NET_BYE, p, 0), LUMO_OK);
    assert_int_equal(payload_status(LUMO_NET_BYE, p, 1), LUMO_ERR_CORRUPT);
}

/* The worked example of docs/protocol.md §6 (a whole session, checked byte
 * for byte against the doc) is tests/serve/test_protocol_example.c. */

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hello_round_trip),
        cmocka_unit_test(test_welcome_round_trip),
        cmocka_unit_test(test_request_round_trip),
        cmocka_unit_test(test_data_round_trip),
        cmocka_unit_test(test_end_error_bye_round_trip),
        cmocka_unit_test(test_wrong_type),
        cmocka_unit_test(test_byte_flips_refused),
        cmocka_unit_test(test_truncations),
        cmocka_unit_test(test_frame_in_stream),
        cmocka_unit_test(test_frame_limits),
        cmocka_unit_test(test_unknown_type),
        cmocka_unit_test(test_version_and_magic),
        cmocka_unit_test(test_seal_and_head),
        cmocka_unit_test(test_resync_offsets),
        cmocka_unit_test(test_resync_stream),
        cmocka_unit_test(test_data_zero_copy),
        cmocka_unit_test(test_encoders_nomem),
        cmocka_unit_test(test_encoders_refuse),
        cmocka_unit_test(test_hello_checks),
        cmocka_unit_test(test_welcome_checks),
        cmocka_unit_test(test_welcome_max_count),
        cmocka_unit_test(test_request_checks),
        cmocka_unit_test(test_data_checks),
        cmocka_unit_test(test_end_error_bye_checks),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
