/*
 * tests/serve/test_protocol_example.c — the worked example of
 * docs/protocol.md §6: a whole session on the package
 * tests/fuzz/seeds/fuzz_package/example.lumo (one quad, a 3x2x2 IVG; made
 * by tests/fuzz/package_seeds/make.sh), every frame produced by the real
 * pieces: HELLO, REQUEST, END and BYE by the codec's encoders, WELCOME as
 * lumo-server builds it when it opens the package (serve/index.c), each
 * DATA as lumo-server plans it (serve/plan.c) with the package's bytes.
 *
 * The frames are printed as §6 shows them, annotated field by field (and
 * the package's bytes by what they are and where in the file they come
 * from). The test reads every code block of §6 back and checks that there
 * are as many as frames, that each holds exactly the bytes of its frame and
 * that its text is the generated text: a doc that drifts fails.
 *
 *   build/tests/bin/test_protocol_example --markdown   prints the section
 *   (from the line after its heading to the one before "## 7."), to paste
 *   into docs/protocol.md after a change of the protocol or the package.
 *
 * Run from the top of the tree.
 */
#include <ctype.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include "test_common.h"
#include "lumo/ivg.h"
#include "lumo/net.h"
#include "lumo/package.h"
#include "lumo/wire.h"
#include "serve/index.h"
#include "serve/plan.h"

#define EXAMPLE_PKG "tests/fuzz/seeds/fuzz_package/example.lumo"
#define EXAMPLE_DOC "docs/protocol.md"
#define EXAMPLE_HEAD "## 6. Worked example"
#define EXAMPLE_NEXT "\n## 7."
#define MAX_FRAMES 32
#define FRAME_CAP 4096
#define HEX_PER_LINE 12u
#define COMMENT_COL 37   /* 12 bytes of hex are 35 characters, then 2 spaces */

typedef struct frame {
    uint8_t b[FRAME_CAP];
    size_t  n;
    const char *intro;    /* the sentence before the block */
    lumo_net_request req; /* the request a DATA / END answers */
} frame;

static srv_pkg g_pkg;
static frame   g_frames[MAX_FRAMES];
static size_t  g_nframes;

/* ---- the session -------------------------------------------------------------------- */

static frame *next_frame(const char *intro)
{
    frame *f;
    assert_true(g_nframes < MAX_FRAMES);
    f = &g_frames[g_nframes++];
    memset(f, 0, sizeof *f);
    f->intro = intro;
    return f;
}

/* The request and lumo-server's answer to it: DATA frames planned by
 * serve/plan.c over the package's bytes, or END. */
static void ask(const char *intro, const char *answer_intro, uint8_t channel, uint32_t cursor, uint32_t amount)
{
    lumo_net_request r = {channel, 0, cursor, amount};
    srv_answer a;
    lumo_net_data d;
    frame *f = next_frame(intro);
    char err[256];
    int end = 0;

    assert_int_equal(lumo_net_request_encode(&r, f->b, FRAME_CAP, &f->n), LUMO_OK);
    assert_int_equal(srv_plan_start(&g_pkg, &r, LUMO_IVG_FORM_QUANTIZED, 64u << 10, &a, &end, err, sizeof err), LUMO_OK);
    if (end) {
        lumo_net_end e = {channel, 0};
        f = next_frame(answer_intro);
        f->req = r;
        assert_int_equal(lumo_net_end_encode(&e, f->b, FRAME_CAP, &f->n), LUMO_OK);
        return;
    }
    while (srv_plan_next(&g_pkg, &a, &d)) {
        f = next_frame(answer_intro);
        f->req = r;
        assert_int_equal(lumo_net_data_encode(&d, f->b, FRAME_CAP, &f->n), LUMO_OK);
        answer_intro = "The next DATA frame of the same answer.";
    }
}

static void session(void)
{
    char err[256];
    lumo_net_hello h;
    frame *f;

    if (g_nframes)
        return;
    if (srv_pkg_open(&g_pkg, EXAMPLE_PKG, err, sizeof err) != LUMO_OK)
        fail_msg("%s (run from the top of the tree)", err);
    memset(&h, 0, sizeof h);
    h.package = 0;
    h.arena_bytes = 8u << 20;
    h.max_payload = 64u << 10;
    h.width = 320;
    h.height = 240;
    h.ivg_form = LUMO_IVG_FORM_QUANTIZED;
    h.flags = LUMO_NET_FLAG_SMOOTHING;
    f = next_frame("The client starts fresh on the server's first package: HELLO with package 0, an arena of 8 MiB, "
                   "max payload 64 KiB, a 320×240 screen, quantized IVG and push-pull smoothing (40 bytes: N = 28, "
                   "no mesh cursors).");
    assert_int_equal(lumo_net_hello_encode(&h, NULL, f->b, FRAME_CAP, &f->n), LUMO_OK);
    static char welcome_intro[400];
    uint32_t head = g_pkg.mesh[0].h.header_bytes;
    snprintf(welcome_intro, sizeof welcome_intro,
             "The server answers with the WELCOME it built when it opened the package: the package id, the arena "
             "the scene needs, and five descriptors copied from the package — `INFO`, the %u-byte header of "
             "mesh 0's `PMSH` stream, `IVGD`, `IVGS` and `ORDR`.%s", head,
             head % 4 ? " The header is padded to a multiple of 4 bytes with zeros." : " Every length is a multiple "
             "of 4: no padding.");
    f = next_frame(welcome_intro);
    assert_true(g_pkg.welcome_len <= FRAME_CAP);
    memcpy(f->b, g_pkg.welcome, g_pkg.welcome_len);
    f->n = g_pkg.welcome_len;
    /* The client follows the package's ORDR: prefix (geometry mesh 0, 4
     * vertices; lighting, 1 round), then the cycle (geometry 250 vertices;
     * lighting 4 rounds) until both channels have ended. The quad is its
     * own base mesh: collapsing a corner would move the surface by half
     * its diagonal, beyond the simplifier's max_error
     * (docs/progressive-mesh.md §1.2). */
    ask("ORDR's first prefix step: the base mesh. REQUEST, geometry, mesh 0, cursor 0 (nothing held), "
        "amount 4 vertices (the stream's `base_vertices`).",
        "DATA with batch record 0, the base mesh (4 vertices, 2 faces: the whole quad, which keeps its "
        "corners), as stored in the `PMSH` chunk.",
        LUMO_NET_GEOMETRY, 0, 4);
    ask("ORDR's second prefix step: the corners. REQUEST, lighting, cursor 0, amount 1 round.",
        "DATA with round 0: the 8 corner records of the grid (one of them solid), in the quantized form "
        "HELLO asked for, as stored in the `IVGQ` chunk.",
        LUMO_NET_LIGHTING, 0, 1);
    ask("The cycle's geometry step: REQUEST, geometry, mesh 0, cursor 1 (the base mesh held), amount 250 "
        "vertices (`batch_vertices`).",
        "Mesh 0's stream has no split record: END, geometry, mesh 0.",
        LUMO_NET_GEOMETRY, 1, 250);
    ask("The cycle's lighting step: REQUEST, lighting, cursor 1, amount 4 rounds.",
        "DATA with rounds 1 to 4 (the 4 vertices of the middle slice x = 1, one per round: every other slice "
        "is used up by the corners) in one frame.",
        LUMO_NET_LIGHTING, 1, 4);
    ask("REQUEST, lighting, cursor 5 (every round held), amount 4.",
        "END, lighting: every channel has ended.",
        LUMO_NET_LIGHTING, 5, 4);
    f = next_frame("The client is done: BYE (12 bytes, an empty payload); the server closes the connection.");
    assert_int_equal(lumo_net_bye_encode(f->b, FRAME_CAP, &f->n), LUMO_OK);
}

/* ---- the annotated text ------------------------------------------------------------- */

typedef struct out {
    char  *s;
    size_t n, cap;
} out;

static void put(out *o, const char *fmt, ...)
{
    va_list ap;
    int k;
    for (;;) {
        va_start(ap, fmt);
        k = vsnprintf(o->s + o->n, o->cap - o->n, fmt, ap);
        va_end(ap);
        assert_true(k >= 0);
        if (o->n + (size_t)k < o->cap)
            break;
        o->cap = 2 * o->cap + (size_t)k + 256;
        o->s = realloc(o->s, o->cap);
        assert_non_null(o->s);
    }
    o->n += (size_t)k;
}

typedef struct cur {
    out *o;
    const uint8_t *b;
    size_t at, n;
} cur;

/* The next n bytes (n <= HEX_PER_LINE) as one line, with the comment. */
static void field(cur *c, size_t n, const char *fmt, ...)
{
    char hex[64], text[512];
    va_list ap;
    size_t i, k = 0;

    assert_true(n >= 1 && n <= HEX_PER_LINE && c->at + n <= c->n);
    for (i = 0; i < n; i++)
        k += (size_t)sprintf(hex + k, i ? " %02X" : "%02X", c->b[c->at + i]);
    va_start(ap, fmt);
    vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    put(c->o, "%-*s%s\n", COMMENT_COL, hex, text);
    c->at += n;
}

/* n bytes, HEX_PER_LINE a line: "what, bytes a..b" on every line, offsets
 * from base. */
static void run(cur *c, size_t n, size_t base, const char *what)
{
    while (n) {
        size_t k = n < HEX_PER_LINE ? n : HEX_PER_LINE;
        field(c, k, "%s, bytes %zu..%zu", what, base, base + k - 1);
        base += k;
        n -= k;
    }
}

static uint32_t u32at(const cur *c) { return lumo_wire_le32(c->b + c->at); }
static uint16_t u16at(const cur *c) { return (uint16_t)(c->b[c->at] | c->b[c->at + 1] << 8); }
static float f32(const uint8_t *p)
{
    uint32_t v = lumo_wire_le32(p);
    float x;
    memcpy(&x, &v, 4);
    return x;
}
static void vec3(cur *c, const char *what)
{
    const uint8_t *p = c->b + c->at;
    field(c, 12, "%s (%g, %g, %g)", what, (double)f32(p), (double)f32(p + 4), (double)f32(p + 8));
}
static void u32f(cur *c, const char *what) { field(c, 4, "%s %u", what, u32at(c)); }

static const char *type_name(uint8_t t)
{
    static const char *const names[] = {"?", "HELLO", "WELCOME", "REQUEST", "DATA", "END", "ERROR", "BYE"};
    return t < 8 ? names[t] : "?";
}

static size_t file_off(const uint8_t *p) { return (size_t)(p - g_pkg.map); }

static void info_payload(cur *c)
{
    uint32_t lights, l;
    u32f(c, "mesh count");
    lights = u32at(c);
    u32f(c, "light count");
    u32f(c, "triangle count");
    field(c, 4, "reserved");
    vec3(c, "scene bounds min, m");
    vec3(c, "scene bounds max, m");
    vec3(c, "default camera eye");
    vec3(c, "camera target");
    vec3(c, "camera up");
    field(c, 4, "camera vertical field of view %g degrees", (double)f32(c->b + c->at));
    for (l = 0; l < lights; l++) {
        static const char *const kinds[] = {"point", "spot", "directional", "area"};
        uint32_t k = u32at(c);
        field(c, 4, "light %u: kind %u, %s", l, k, k < 4 ? kinds[k] : "?");
        vec3(c, "  position");
        vec3(c, "  direction (point: none)");
        vec3(c, "  edge u (area only)");
        vec3(c, "  edge v (area only)");
        field(c, 4, "  spot half angle %g degrees", (double)f32(c->b + c->at));
        field(c, 4, "  its cosine %g (not a spot: -1)", (double)f32(c->b + c->at));
        vec3(c, "  power, W per channel");
    }
}

static uint32_t varint(cur *c, const char *what)
{
    uint32_t v = 0, shift = 0;
    size_t n = 0;
    do {
        v |= (uint32_t)(c->b[c->at + n] & 0x7F) << shift;
        shift += 7;
    } while (c->b[c->at + n++] & 0x80);
    field(c, n, "%s %u (varint)", what, v);
    return v;
}

static void pmsh_header(cur *c)
{
    static const char *const counts[8] = {"vertices", "faces", "base_vertices", "base_faces", "batch_vertices",
                                          "max_batch_faces", "max_batch_moves", "max_batch_bytes"};
    uint32_t hb = c->b[c->at + 6];
    field(c, 4, "magic \"LPM1\"");
    field(c, 2, "stream version %u", u16at(c));
    field(c, 1, "header_bytes %u", hb);
    for (int i = 0; i < 8; i++)
        varint(c, counts[i]);
    field(c, 1, "quant_bits %u", c->b[c->at]);
    field(c, 1, "position_coding %u (%s)", c->b[c->at], c->b[c->at] == 2 ? "coded" : c->b[c->at] ? "predicted" : "absolute");
    field(c, 1, "flags 0x%02X (bit 0: albedo present, bit 1: lattice copies)", c->b[c->at]);
    vec3(c, "grid origin, m");
    field(c, 4, "grid range %g m", (double)f32(c->b + c->at));
    field(c, 4, "CRC-32 of the header's bytes 0..%u = 0x%08X", hb - 5, u32at(c));
}

static void ivgd_payload(cur *c)
{
    const uint8_t *p = c->b + c->at;
    field(c, 6, "grid vertices per axis %u × %u × %u", (unsigned)(p[0] | p[1] << 8), (unsigned)(p[2] | p[3] << 8),
          (unsigned)(p[4] | p[5] << 8));
    field(c, 2, "reserved");
    vec3(c, "grid box min, m");
    vec3(c, "grid box max, m");
    u32f(c, "paths per vertex (--spp)");
    u32f(c, "seed, low 32 bits");
    u32f(c, "seed, high 32 bits");
    u32f(c, "valid (not solid) vertices");
}

static void u32_array(cur *c, uint32_t count, const char *what)
{
    uint32_t i = 0;
    while (i < count) {
        uint32_t k = count - i < 3 ? count - i : 3, j;
        char list[64];
        size_t len = 0;
        for (j = 0; j < k; j++)
            len += (size_t)sprintf(list + len, j ? ", %u" : "%u", lumo_wire_le32(c->b + c->at + 4 * j));
        field(c, 4 * k, "%s, r = %u..%u: %s", what, i, i + k - 1, list);
        i += k;
    }
}

static void ivgs_payload(cur *c)
{
    uint32_t rounds;
    u32f(c, "order seed, low 32 bits");
    u32f(c, "order seed, high 32 bits");
    field(c, 1, "slice axis %u (%c)", c->b[c->at], "xyz?"[c->b[c->at] < 3 ? c->b[c->at] : 3]);
    field(c, 3, "reserved");
    u32f(c, "slice count S");
    rounds = u32at(c);
    u32f(c, "round count R");
    u32_array(c, rounds + 1, "first record of round r");
    u32_array(c, rounds + 1, "IVGQ byte offset of round r");
    u32_array(c, rounds + 1, "IVGF byte offset of round r");
}

static void ordr_payload(cur *c)
{
    uint32_t prefix = u32at(c), steps, s;
    u32f(c, "prefix step count P");
    steps = prefix + u32at(c);
    u32f(c, "cycle step count C");
    for (s = 0; s < steps; s++) {
        const uint8_t *p = c->b + c->at;
        if (p[0] == LUMO_NET_GEOMETRY)
            field(c, 12, "%s step: geometry (00, 3 reserved), mesh %u, %u vertices", s < prefix ? "prefix" : "cycle",
                  lumo_wire_le32(p + 4), lumo_wire_le32(p + 8));
        else
            field(c, 12, "%s step: lighting (01, 3 reserved), mesh %u, %u round%s", s < prefix ? "prefix" : "cycle",
                  lumo_wire_le32(p + 4), lumo_wire_le32(p + 8), lumo_wire_le32(p + 8) == 1 ? "" : "s");
    }
}

static void welcome_payload(cur *c)
{
    uint32_t k, i;
    field(c, 4, "package id 0x%08X: the package header's CRC field (file bytes 20..23)", u32at(c));
    field(c, 4, "arena need %u bytes (the descriptors' needs + LUMO_ARENA_SLACK)", u32at(c));
    k = u32at(c);
    field(c, 4, "K = %u messages", k);
    for (i = 0; i < k; i++) {
        uint32_t type = u32at(c), index, len;
        const uint8_t *chunk;
        uint32_t chunk_len;
        size_t start;
        char fourcc[5];
        memcpy(fourcc, c->b + c->at, 4);
        fourcc[4] = 0;
        field(c, 4, "message %u: type \"%s\"", i + 1, fourcc);
        index = u32at(c);
        field(c, 4, "index %u", index);
        len = u32at(c);
        assert_int_equal(lumo_package_find(&g_pkg.pkg, type, index, &chunk, &chunk_len), LUMO_OK);
        assert_true(len <= chunk_len && memcmp(chunk, c->b + c->at + 4, len) == 0);
        field(c, 4, "L = %u: the %s%s chunk's %s, file bytes %zu..%zu", len, fourcc,
              type == LUMO_PKG_PMSH ? " (mesh 0)" : "", len == chunk_len ? "payload" : "first bytes",
              file_off(chunk), file_off(chunk) + len - 1);
        start = c->at;
        if (type == LUMO_PKG_INFO)
            info_payload(c);
        else if (type == LUMO_PKG_PMSH)
            pmsh_header(c);
        else if (type == LUMO_PKG_IVGD)
            ivgd_payload(c);
        else if (type == LUMO_PKG_IVGS)
            ivgs_payload(c);
        else if (type == LUMO_PKG_ORDR)
            ordr_payload(c);
        else
            run(c, len, 0, fourcc);
        assert_int_equal(c->at - start, len);
        if (len % 4)
            field(c, 4 - len % 4, "padding to a multiple of 4");
    }
}

static void batch_records(cur *c, uint32_t mesh, uint32_t first, uint32_t count)
{
    const srv_mesh_index *m = &g_pkg.mesh[mesh];
    uint32_t b;
    for (b = first; b < first + count; b++) {
        uint32_t len = m->rec[b + 1] - m->rec[b], side, draco;
        size_t off = file_off(m->stream + m->rec[b]), start = c->at;
        assert_memory_equal(c->b + c->at, m->stream + m->rec[b], len);
        put(c->o, "%-*s", COMMENT_COL, "");
        put(c->o, "batch record %u (%u bytes): PMSH (mesh %u) payload bytes %u..%u, file bytes %zu..%zu\n", b, len,
            mesh, m->rec[b], m->rec[b + 1] - 1, off, off + len - 1);
        side = varint(c, "  sizes: 2 · side_bytes + (1: a payload follows)");
        draco = side & 1u ? varint(c, "  draco_bytes") : 0;
        side >>= 1;
        field(c, 4, "  CRC-32 of index %u (a varint, not sent) and the record but these 4 bytes = 0x%08X", b,
              u32at(c));
        run(c, side, 0, "  split block (progressive-mesh.md §2.3)");
        run(c, draco, 0, "  Draco point cloud (progressive-mesh.md §2.4)");
        assert_int_equal(c->at - start, len);
    }
}

static double rgb9e5(uint32_t w, int ch)
{
    return ldexp((double)((w >> (9 * ch)) & 0x1FF), (int)(w >> 27) - 24);
}

static void ivg_records(cur *c, uint32_t records)
{
    const uint8_t *bundle = g_pkg.ivg.bundle[LUMO_IVG_FORM_QUANTIZED];
    uint32_t nx = (uint32_t)(bundle[6] | bundle[7] << 8), ny = (uint32_t)(bundle[8] | bundle[9] << 8);
    uint32_t i, rec = 0, round = 0;
    static const char *const axes[6] = {"+x", "-x", "+y", "-y", "+z", "-z"};
    for (i = 0; i < records; i++) {
        uint32_t w = u32at(c), v = w & 0x7FFFFFFFu, e;
        /* Which record of the bundle: the one whose bytes these are. */
        const uint8_t *p = bundle + SRV_IVG_BUNDLE_HEAD;
        size_t at;
        for (rec = 0; rec < g_pkg.ivg.records; rec++) {
            size_t rl = (lumo_wire_le32(p) & 0x80000000u) ? 4 : 46;
            if (rl <= c->n - c->at && memcmp(p, c->b + c->at, rl) == 0)
                break;
            p += rl;
        }
        assert_true(rec < g_pkg.ivg.records);
        for (round = 0; g_pkg.ivg.first[round + 1] <= rec; round++)
            ;
        at = file_off(p);
        field(c, 4, "record %u (round %u, file bytes %zu..%zu): vertex %u = (%u, %u, %u)%s", rec, round, at,
              at + ((w & 0x80000000u) ? 4 : 46) - 1, v, v % nx, v / nx % ny, v / nx / ny,
              (w & 0x80000000u) ? ", bit 31: solid" : "");
        if (w & 0x80000000u)
            continue;
        for (e = 0; e < 6; e++) {
            const uint8_t *q = c->b + c->at;
            uint32_t rgb = lumo_wire_le32(q + 3);
            field(c, 7, "  %s: d = (%d, %d, %d)/127, c = (%.4g, %.4g, %.4g)", axes[e], (int8_t)q[0], (int8_t)q[1],
                  (int8_t)q[2], rgb9e5(rgb, 0), rgb9e5(rgb, 1), rgb9e5(rgb, 2));
        }
    }
}

static void data_payload(cur *c, const frame *f)
{
    uint8_t channel = c->b[c->at];
    uint32_t first, count, records;
    field(c, 1, "channel %u: %s", channel, channel ? "lighting" : "geometry");
    field(c, 3, "reserved");
    field(c, 4, "mesh index %u", u32at(c));
    first = u32at(c);
    field(c, 4, channel ? "first round %u" : "first batch record %u", first);
    count = u32at(c);
    field(c, 4, "count %u %s%s", count, channel ? "round" : "batch record", count == 1 ? "" : "s");
    field(c, 1, channel ? "IVG form %u: quantized (as HELLO asked)" : "form %u (geometry)", c->b[c->at]);
    field(c, 3, "reserved");
    records = u32at(c);
    field(c, 4, channel ? "records %u IVG records" : "records %u (= count)", records);
    if (channel == LUMO_NET_GEOMETRY)
        batch_records(c, f->req.mesh, first, count);
    else
        ivg_records(c, records);
}

/* Prose, wrapped at 78 columns (a blank line stays a paragraph break). */
static void put_wrapped(out *o, const char *text)
{
    const char *p = text;
    size_t col = 0;
    while (*p) {
        size_t w = strcspn(p, " \n");
        if (w) {
            if (col && col + 1 + w > 78) {
                put(o, "\n");
                col = 0;
            } else if (col) {
                put(o, " ");
                col++;
            }
            put(o, "%.*s", (int)w, p);
            col += w;
            p += w;
        }
        if (*p == '\n' && p[1] == '\n') {
            put(o, "\n\n");
            col = 0;
            p += 2;
        } else if (*p) {
            p++;
        }
    }
    put(o, "\n");
}

static void frame_text(out *o, const frame *f)
{
    cur c = {o, f->b, 0, f->n};
    uint8_t type = f->b[3];
    uint32_t len = lumo_wire_le32(f->b + 4);

    put_wrapped(o, f->intro);
    put(o, "\n```\n");
    field(&c, 2, "magic \"LS\"");
    field(&c, 1, "version 1");
    field(&c, 1, "type %u: %s", type, type_name(type));
    field(&c, 4, "N = %u payload bytes", len);
    switch (type) {
    case LUMO_NET_HELLO:
        field(&c, 4, "package index 0 (the first)");
        field(&c, 4, "arena bytes 0x%08X = %u MiB", u32at(&c), u32at(&c) >> 20);
        field(&c, 4, "max payload 0x%08X = %u KiB", u32at(&c), u32at(&c) >> 10);
        field(&c, 2, "screen width %u", u16at(&c));
        field(&c, 2, "screen height %u", u16at(&c));
        field(&c, 1, "IVG form %u: quantized", c.b[c.at]);
        field(&c, 1, "flags: bit 0, push-pull smoothing");
        field(&c, 2, "reserved");
        field(&c, 4, "resume package id 0: a fresh start");
        field(&c, 4, "M = 0 mesh cursors");
        break;
    case LUMO_NET_WELCOME:
        welcome_payload(&c);
        break;
    case LUMO_NET_REQUEST: {
        uint8_t channel = c.b[c.at];
        field(&c, 1, "channel %u: %s", channel, channel ? "lighting" : "geometry");
        field(&c, 3, "reserved");
        field(&c, 4, "mesh index %u", u32at(&c));
        field(&c, 4, channel ? "cursor %u: rounds held" : "cursor %u: batch records held", u32at(&c));
        field(&c, 4, "amount %u %s%s", u32at(&c), channel ? "round" : "vertices", channel && u32at(&c) == 1 ? "" : (channel ? "s" : ""));
        break;
    }
    case LUMO_NET_DATA:
        data_payload(&c, f);
        break;
    case LUMO_NET_END: {
        uint8_t channel = c.b[c.at];
        field(&c, 1, "channel %u: %s", channel, channel ? "lighting" : "geometry");
        field(&c, 3, "reserved");
        field(&c, 4, "mesh index %u", u32at(&c));
        break;
    }
    default:
        break;
    }
    assert_int_equal(c.at, 8 + (size_t)len);
    field(&c, 4, "CRC-32 of the %zu bytes above = 0x%08X", c.at, u32at(&c));
    assert_int_equal(c.at, f->n);
    put(o, "```\n\n");
}

static const char *const g_head =
    "A whole session, byte for byte, on a package small enough to print: "
    "`tests/fuzz/seeds/fuzz_package/example.lumo` (2812 bytes), baked by "
    "`tests/fuzz/package_seeds/make.sh` from `tests/fuzz/package_seeds/example.txt`\n"
    "(one quad of 4 vertices and 2 triangles — a progressive stream whose base mesh\n"
    "is the whole quad, since no corner may collapse — one point light, and a 3×2×2 IVG baked with\n"
    "`--spp 1 --seed 1`: round 0 is the 8 corners, rounds 1..4 one vertex each of\n"
    "the middle slice; a 2×2×2 grid would have the corners only). HELLO, REQUEST,\n"
    "END and BYE are what `lumo_net_*_encode` writes; WELCOME is the frame\n"
    "`lumo-server` builds when it opens the package (`server/serve/index.c`), and\n"
    "each DATA is its answer to the REQUEST before it (`server/serve/plan.c`) with\n"
    "the package's bytes, as stored. The client follows the package's `ORDR`: its\n"
    "prefix (the base mesh, then the corners), then its cycle (250 vertices, 4\n"
    "rounds) until both channels have ended.\n"
    "\n"
    "`tests/serve/test_protocol_example.c` produces these frames and checks every\n"
    "block below — its bytes and its text — against them, so a doc that drifts\n"
    "fails `make test`; `build/tests/bin/test_protocol_example --markdown` prints\n"
    "this section again. Each line is bytes in order, then what they are;\n"
    "multi-byte fields are little-endian, f32 is IEEE-754 binary32 (shown as a\n"
    "decimal), and package bytes say where in the file they come from. An\n"
    "annotation line without bytes heads a run of package bytes.";

static char *section_text(void)
{
    out o = {NULL, 0, 0};
    size_t i;
    session();
    put(&o, "\n");
    put_wrapped(&o, g_head);
    put(&o, "\n");
    for (i = 0; i < g_nframes; i++)
        frame_text(&o, &g_frames[i]);
    return o.s;
}

/* ---- reading the doc back ----------------------------------------------------------- */

/* The bytes at the start of a block's line ("4C 53  magic"): pairs of hex
 * digits one space apart, ended by two spaces or the line's end. */
static size_t line_bytes(const char *p, const char *eol, uint8_t *outb, size_t n, size_t cap)
{
    unsigned v;
    while (p + 2 <= eol && isxdigit((unsigned char)p[0]) && isxdigit((unsigned char)p[1])
           && (p + 2 == eol || p[2] == ' ') && sscanf(p, "%2x", &v) == 1) {
        assert_true(n < cap);
        outb[n++] = (uint8_t)v;
        p += 2;
        if (p == eol || p[1] == ' ')
            break;
        p++;
    }
    return n;
}

/* The next code block of text at or after *p (before limit): its text
 * [*start, *end) and its bytes. 0 when there is none. */
static int next_block(const char **p, const char *limit, const char **start, const char **end, uint8_t *bytes,
                      size_t cap, size_t *n)
{
    const char *a = strstr(*p, "\n```\n"), *q;
    if (!a || a >= limit)
        return 0;
    a += 5;
    *end = strstr(a, "\n```\n");
    assert_non_null(*end);
    (*end)++;
    *start = a;
    *n = 0;
    for (q = a; q < *end; ) {
        const char *eol = strchr(q, '\n');
        *n = line_bytes(q, eol, bytes, *n, cap);
        q = eol + 1;
    }
    *p = *end + 4;
    return 1;
}

static char *read_doc(void)
{
    FILE *f = fopen(EXAMPLE_DOC, "rb");
    char *doc;
    long len;
    if (!f)
        fail_msg(EXAMPLE_DOC " not found (run from the top of the tree)");
    fseek(f, 0, SEEK_END);
    len = ftell(f);
    fseek(f, 0, SEEK_SET);
    doc = malloc((size_t)len + 1);
    assert_non_null(doc);
    assert_int_equal(fread(doc, 1, (size_t)len, f), (size_t)len);
    fclose(f);
    doc[len] = 0;
    return doc;
}

/* Every code block of §6 holds its frame's bytes, and the generated text. */
static void test_doc_blocks(void **state)
{
    static uint8_t got[FRAME_CAP], want[FRAME_CAP];
    char *doc = read_doc(), *gen = section_text();
    const char *p = strstr(doc, EXAMPLE_HEAD), *limit, *g = gen;
    size_t i = 0;

    (void)state;
    if (!p)
        fail_msg(EXAMPLE_DOC " has no section \"" EXAMPLE_HEAD "\"");
    limit = strstr(p, EXAMPLE_NEXT);
    if (!limit)
        limit = p + strlen(p);
    for (;;) {
        const char *ds, *de, *gs, *ge;
        size_t dn, gn;
        int have_doc = next_block(&p, limit, &ds, &de, got, sizeof got, &dn);
        int have_gen = next_block(&g, gen + strlen(gen), &gs, &ge, want, sizeof want, &gn);
        if (!have_doc && !have_gen)
            break;
        if (!have_doc || !have_gen)
            fail_msg(EXAMPLE_DOC " §6 has %s code blocks than the session has frames (%zu); "
                     "regenerate it with test_protocol_example --markdown", have_doc ? "more" : "fewer", g_nframes);
        assert_int_equal(gn, g_frames[i].n);
        assert_memory_equal(want, g_frames[i].b, gn);
        if (dn != gn || memcmp(got, want, gn) != 0) {
            size_t k = 0;
            while (k < dn && k < gn && got[k] == want[k])
                k++;
            fail_msg(EXAMPLE_DOC " §6, block %zu (%s, %zu bytes): byte %zu differs from the frame (%zu bytes); "
                     "regenerate it with test_protocol_example --markdown",
                     i, type_name(want[3]), dn, k, gn);
        }
        if ((size_t)(de - ds) != (size_t)(ge - gs) || memcmp(ds, gs, (size_t)(de - ds)) != 0)
            fail_msg(EXAMPLE_DOC " §6, block %zu (%s): the bytes are right but the annotations differ from the "
                     "generated ones; regenerate it with test_protocol_example --markdown", i, type_name(want[3]));
        i++;
    }
    assert_int_equal(i, g_nframes);
    print_message("%zu frames checked\n", i);
    free(doc);
    free(gen);
}

/* The session covers the protocol: every message type a server and a
 * well-behaved client exchange, both channels, a split of the stream into
 * its base mesh and the rest, the corners and later rounds, and every byte
 * of mesh 0's stream and of the quantized IVG carried once. */
static void test_session_covers(void **state)
{
    size_t i, geo = 0, light = 0, types[8] = {0}, used;
    uint32_t rec_bytes;
    (void)state;
    session();
    for (i = 0; i < g_nframes; i++) {
        lumo_net_frame fr;
        assert_int_equal(lumo_net_frame_decode(g_frames[i].b, g_frames[i].n, LUMO_NET_MAX_PAYLOAD, &fr, &used), LUMO_OK);
        assert_int_equal(used, g_frames[i].n);
        types[g_frames[i].b[3]]++;
        if (g_frames[i].b[3] == LUMO_NET_DATA) {
            lumo_net_data d;
            assert_int_equal(lumo_net_data_decode(&fr, &d), LUMO_OK);
            if (d.channel == LUMO_NET_GEOMETRY)
                geo += d.len;
            else
                light += d.len;
        }
    }
    assert_int_equal(types[LUMO_NET_HELLO], 1);
    assert_int_equal(types[LUMO_NET_WELCOME], 1);
    assert_int_equal(types[LUMO_NET_REQUEST], 5);
    assert_int_equal(types[LUMO_NET_DATA], 3);
    assert_int_equal(types[LUMO_NET_END], 2);
    assert_int_equal(types[LUMO_NET_BYE], 1);
    assert_int_equal(g_pkg.mesh_count, 1);
    assert_int_equal(g_pkg.mesh[0].h.batch_count, 1);
    assert_int_equal(geo, g_pkg.mesh[0].len - g_pkg.mesh[0].h.header_bytes);
    rec_bytes = g_pkg.ivg.bundle_len[LUMO_IVG_FORM_QUANTIZED] - SRV_IVG_BUNDLE_HEAD;
    assert_int_equal(light, rec_bytes);
    assert_int_equal(g_pkg.ivg.rounds, 5);
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_session_covers),
        cmocka_unit_test(test_doc_blocks),
    };
    int rc;
    if (argc == 2 && strcmp(argv[1], "--markdown") == 0) {
        char *s = section_text();
        fputs(s, stdout);
        free(s);
        srv_pkg_close(&g_pkg);
        return 0;
    }
    rc = cmocka_run_group_tests(tests, NULL, NULL);
    if (g_nframes)
        srv_pkg_close(&g_pkg);
    return rc;
}
