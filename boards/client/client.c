/*
 * client.c — the thin client as a board program: the whole client of
 * seed 000 on any board of boards/board.h (docs/porting.md §7). It says
 * HELLO over the board's link, feeds what arrives to the protocol driver
 * (lumo/net_client.h) and the session (lumo/session.h), and draws the scene
 * with the soft rasterizer (lumo/raster.h) in bands as it refines: once
 * every base mesh and the grid's corners are in ("first"), then at each
 * share of k_shares (geometry and lighting count half each: the rule of
 * lumo-client's --frames-at), at each size of k_sizes. Every picture is
 * hashed (64-bit FNV-1a of its RGB565 bytes, little-endian, row by row) and
 * printed as "HASH frame-<share>-<W>x<H> 0x...", so runs on different
 * boards, and a live run and the replay of its bytes, can be compared.
 *
 * The link is a serial line (docs/protocol.md §1): a refused frame is
 * skipped to the next magic and the requests are asked again; a silence
 * while answers are due does the same; frames that answer what was asked
 * before are dropped (lumo_net_client_in_turn). Requests have fixed sizes
 * (REQUEST_VERTICES, REQUEST_ROUNDS), so what is asked, and the state the
 * scene is drawn in, depend only on the answers, never on timing.
 *
 * A picture of the board's screen size (CLIENT_SCREEN_W x CLIENT_SCREEN_H,
 * the lm3s6965evb's 128 x 64 OLED) is also reduced to 16 grey levels band
 * by band (grey4.h), hashed ("HASH grey-<share>-<W>x<H>") and handed to
 * board_display_grey4, so the screen shows the scene as it refines.
 *
 * Command line (board_cmdline; QEMU: -append): --replay FILE applies a
 * recording (the bytes a live run received) read with board_read_file,
 * the driver in replay mode; --record FILE writes the bytes received;
 * --out DIR writes every picture as DIR/frame-<share>-<W>x<H>.ppm (and
 * its grey reduction as DIR/grey-<share>-<W>x<H>.pgm); --hold keeps the
 * last picture on the board's screen when the scene is complete
 * (board_hold, never returns: QEMU until the test quits it);
 * --no-pictures streams the scene and draws nothing (throughput runs);
 * --updates N keeps the connection once the scene is complete and pulls
 * the lighting updates of a dynamic scene (docs/dynamic.md §6, protocol
 * §9) with the updates poller (lumo/net_updates.h) as lumo-client
 * --updates does: IVGU records and POSES applied to the session, a
 * picture ("frame-update-NNN") after each answer that changed something,
 * until N pictures are drawn, then BYE.
 *
 * Client rules (docs/architecture.md): C99, no heap, no float, no stdio.
 * Memory: board_scratch() holds the receive buffer, the recording, the
 * picture memory (vertex caches, a band, a file image) and, the rest, the
 * scene's arena.
 */
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include "lumo/arena.h"
#include "lumo/net.h"
#include "lumo/net_client.h"
#include "lumo/net_updates.h"
#include "lumo/raster.h"
#include "lumo/session.h"
#include "board.h"
#include "console.h"
#include "grey4.h"

int main(void);

/* ---- what this client asks for and draws ---------------------------------------- */

/* A board sizes the three buffers to its RAM (-DCLIENT_..., boards/rp2040). */
#ifndef CLIENT_MAX_PAYLOAD
#define CLIENT_MAX_PAYLOAD (16u << 10)
#endif
#ifndef CLIENT_PICTURE_BYTES
#define CLIENT_PICTURE_BYTES (4u << 20)
#endif
#ifndef CLIENT_RECORD_BYTES
#define CLIENT_RECORD_BYTES (2u << 20)
#endif
/* The pictures drawn ({W, H} each, the first also the size stated in
 * HELLO) and the rows of one band (a band costs W x rows x 6 bytes). */
#ifndef CLIENT_SIZES
#define CLIENT_SIZES {320, 240}, {160, 128}
#endif
#ifndef CLIENT_BAND_ROWS
#define CLIENT_BAND_ROWS 16u
#endif
/* A grey screen (grey4.h, board_display_grey4): pictures of this size are
 * also reduced to its 16 grey levels, hashed ("HASH grey-..."), shown on
 * the board's screen and, with --out, written as PGM; 0 x 0: none. */
#ifndef CLIENT_SCREEN_W
#define CLIENT_SCREEN_W 0u
#define CLIENT_SCREEN_H 0u
#endif
#define MAX_PAYLOAD      CLIENT_MAX_PAYLOAD   /* HELLO: largest frame payload taken */
#define RX_BYTES         (MAX_PAYLOAD + LUMO_NET_OVERHEAD)
#define TX_BYTES         256u         /* HELLO, REQUEST, BYE */
/* The cycle of lumo-bake's interleaving (package ORDR): a batch of 250
 * vertices per mesh, then 4 lighting rounds (docs/protocol.md §7). */
#define REQUEST_VERTICES 250u
#define REQUEST_ROUNDS   4u
#define PIPELINE         4u
#define SILENCE_MS       250u         /* no byte for this long: ask again */
#define MAX_TRIES        64u          /* asked again without an answer applied */
#define BAND_ROWS        CLIENT_BAND_ROWS
#define PICTURE_BYTES    CLIENT_PICTURE_BYTES   /* vertex caches, a band, a PPM image */
#define RECORD_BYTES     CLIENT_RECORD_BYTES    /* a recording, to write or to replay; 0: none */
#define DEFAULT_ALBEDO   ((lumo_q1_14)12288)   /* 0.75: lumo-render's for meshes without albedo */
/* The updates phase: records asked per request (the server splits an
 * answer into frames under MAX_PAYLOAD), the wait after an answer that
 * brought nothing new, and the silences tolerated while one is due. */
#define UPDATE_RECORDS   256u
#define UPDATE_POLL_MS   SILENCE_MS
#define UPDATE_MAX_SILENCES 40u

static const uint8_t k_shares[] = {10, 25, 50, 100};   /* percent of the scene */
static const uint16_t k_sizes[][2] = {CLIENT_SIZES};
#define NSHARES (sizeof k_shares / sizeof k_shares[0])
#define NSIZES  (sizeof k_sizes / sizeof k_sizes[0])

/* Instructions (board ticks) spent on one kind of work, and how often. */
typedef struct cost {
    uint64_t ticks;
    uint32_t n;
} cost;

/* One picture being drawn: everything lumo_raster_draw reads. */
typedef struct picture {
    lumo_raster_view view;
    lumo_raster_scene scene;
    lumo_raster_light lights[LUMO_MAX_LIGHTS];
    lumo_raster_mesh mesh[LUMO_MAX_MESHES];
    lumo_raster_vertex *cache[LUMO_MAX_MESHES];   /* NULL: drawn without one */
    uint32_t meshes;
    uint16_t *band;
    void *depth;
    uint8_t *image;                               /* PPM, with --out */
    uint8_t *grey;                                /* a band for the grey screen */
    uint8_t *grey_image;                          /* PGM of it, with --out */
    uint64_t grey_hash;
} picture;

typedef struct client {
    const char *replay, *record, *out;
    int no_pictures;              /* --no-pictures: stream only (throughput runs) */
    int hold;                     /* --hold: keep the last picture on the screen */
    lumo_arena work, pictures, scene_arena;
    lumo_session ses;
    lumo_net_client drv;
    uint8_t *rx, *log;            /* receive buffer; recording (or replay) */
    size_t rx_len, log_len, replay_at;
    uint8_t tx[TX_BYTES];
    unsigned next_share;
    int first_done, asked_again;
    uint32_t updates_wanted;      /* --updates N: pictures of the updates phase */
    lumo_net_updates upd;         /* the updates poller (no buffer of its own: rx, tx) */
    uint32_t upd_clock;           /* its clock, ms (see update_ask) */
    uint32_t upd_pictures, upd_silences, upd_seen;
    int upd_asked, bye_held;
    uint32_t tries;
    uint64_t bytes_in, raw_in;    /* DATA payload applied; every byte the link gave */
    uint32_t frames, stale, refused, silences, resends;
    uint32_t cuts, cut_bytes, welcome_again;   /* new connections (BOARD_LINK_NEW) */
    cost geometry, lighting, pushpull, decode, drawing, updating;
    uint32_t clock_ticks[8];      /* the driver's clock reads during one frame */
    unsigned clock_reads;
    picture pic;
} client;

static client g_client;

/* ---- console ------------------------------------------------------------------ */

static void say(const char *a, const char *b)
{
    con_str("client: ");
    con_str(a);
    if (b)
        con_str(b);
    con_nl();
}

static int fail(const char *why, const char *detail)
{
    con_str("client: error: ");
    con_str(why);
    if (detail)
        con_str(detail);
    con_nl();
    return -1;
}

/* ticks * ns per tick = instructions under QEMU's -icount shift=0
 * (docs/porting.md §4, "Cost measurement"). */
static uint64_t instructions(uint64_t ticks)
{
    uint32_t hz = board_tick_hz();

    return hz ? ticks * (1000000000u / hz) : 0;
}

/* "COST <label> <instructions> instructions[ (<n> <what>)]": the mean per
 * unit; nothing on a board without ticks (the host). */
static void cost_line(const char *label, const cost *k, const char *what)
{
    if (board_tick_hz() == 0)
        return;
    con_str("COST ");
    con_str(label);
    con_str(" ");
    con_u64(instructions(k->n ? k->ticks / k->n : k->ticks));
    con_str(" instructions");
    if (what) {
        con_str(" (");
        con_u64(k->n);
        con_str(" ");
        con_str(what);
        con_str(", ");
        con_u64(instructions(k->ticks));
        con_str(" in all)");
    }
    con_nl();
}

/* ---- the command line ----------------------------------------------------------- */

/* A decimal count 1..9999 into *out: 1, else 0. */
static int parse_count(const char *s, uint32_t *out)
{
    uint32_t v = 0;

    if (!*s)
        return 0;
    for (; *s; s++) {
        if (*s < '0' || *s > '9' || v > 999u)
            return 0;
        v = v * 10u + (uint32_t)(*s - '0');
    }
    *out = v;
    return v > 0;
}

static int parse_args(client *c)
{
    static char line[512];
    char *w[16];
    int n = 0, i;
    char *p = line;

    if (board_cmdline(line, sizeof line) != 0)
        return 0;   /* none: live, nothing written */
    while (*p && n < 16) {
        while (*p == ' ')
            *p++ = '\0';
        if (*p)
            w[n++] = p;
        while (*p && *p != ' ')
            p++;
    }
    for (i = 1; i < n; i++) {
        const char **opt;
        if (!strcmp(w[i], "--no-pictures")) {
            c->no_pictures = 1;
            continue;
        }
        opt = !strcmp(w[i], "--replay") ? &c->replay
                         : !strcmp(w[i], "--record") ? &c->record
                         : !strcmp(w[i], "--out") ? &c->out : NULL;
        if (!strcmp(w[i], "--hold"))
            c->hold = 1;
        else if (!strcmp(w[i], "--updates") && i + 1 < n && parse_count(w[i + 1], &c->updates_wanted))
            i++;
        else if (opt == NULL || i + 1 >= n)
            return fail("usage: client [--replay FILE] [--record FILE] [--out DIR] [--hold] [--no-pictures] "
                        "[--updates N]; not ", w[i]);
        else
            *opt = w[++i];
    }
    return c->replay && c->record ? fail("--replay and --record exclude each other", NULL) : 0;
}

/* ---- memory --------------------------------------------------------------------- */

/* Receive buffer, recording, picture memory; the rest is the scene's. */
static int carve_memory(client *c)
{
    size_t bytes;
    uint8_t *scratch = board_scratch(&bytes), *pics;

    if ((c->replay || c->record) && RECORD_BYTES == 0)
        return fail("this board keeps no recording (CLIENT_RECORD_BYTES 0)", NULL);
    lumo_arena_init(&c->work, scratch, bytes);
    c->rx = lumo_arena_alloc(&c->work, RX_BYTES);
    c->log = c->replay || c->record ? lumo_arena_alloc(&c->work, RECORD_BYTES) : c->rx;
    pics = lumo_arena_alloc(&c->work, PICTURE_BYTES);
    if (!c->rx || !c->log || !pics)
        return fail("board_scratch is too small", NULL);
    lumo_arena_init(&c->pictures, pics, PICTURE_BYTES);
    /* Not allocated (that would zero it): the arena zero-fills what it hands out. */
    lumo_arena_init(&c->scene_arena, c->work.base + c->work.used, lumo_arena_remaining(&c->work));
    return 0;
}

/* ---- the link, or the recording --------------------------------------------------- */

static int transmit(client *c, const uint8_t *p, size_t n)
{
    if (c->replay)
        return 0;   /* a recording answers what was asked when it was made */
    return board_link_write(p, n) ? fail("the link refused to send", NULL) : 0;
}

/* Bytes into buf: > 0 read, 0 a silence of SILENCE_MS, -1 the end. */
static int32_t receive(client *c, uint8_t *buf, size_t cap)
{
    int32_t n;

    if (c->replay) {
        size_t left = c->log_len - c->replay_at;
        n = (int32_t)(left < cap ? left : cap);
        memcpy(buf, c->log + c->replay_at, (size_t)n);
        c->replay_at += (size_t)n;
        return n > 0 ? n : -1;
    }
    n = board_link_read(buf, cap, SILENCE_MS);
    if (n > 0)
        c->raw_in += (uint64_t)n;
    if (n > 0 && c->record) {
        if ((size_t)n > RECORD_BYTES - c->log_len)
            return fail("the recording is full", NULL);
        memcpy(c->log + c->log_len, buf, (size_t)n);
        c->log_len += (size_t)n;
    }
    return n;
}

/* ---- progress: the first picture and the shares ------------------------------------- */

/* Every base mesh and the grid's corners are in (or there is no grid). */
static int first_picture_ready(const client *c, const lumo_net_progress *p)
{
    const lumo_pkg_info *info = lumo_session_info(&c->ses);
    lumo_session_progress mp;
    uint32_t m;

    if (c->drv.state != LUMO_NET_READY && c->drv.state != LUMO_NET_DONE)
        return 0;
    for (m = 0; m < info->mesh_count; m++)
        if (lumo_session_mesh_progress(&c->ses, m, &mp) || mp.batches == 0)
            return 0;
    return p->full_rounds == 0 || p->rounds > 0;
}

/* The scene held reaches `percent`: geometry and lighting half each (all
 * geometry without a grid), as lumo-client's --frames-at, in integers. */
static int reached(const lumo_net_progress *p, uint32_t percent)
{
    uint64_t gn = p->full_vertices ? p->vertices : 1, gd = p->full_vertices ? p->full_vertices : 1;
    uint64_t r = p->rounds, rd = p->full_rounds;

    if (p->done)
        return 1;
    if (rd == 0)
        return 100u * gn >= percent * gd;
    return 100u * (gn * rd + r * gd) >= 2u * percent * gd * rd;
}

/* ---- drawing ----------------------------------------------------------------------- */

static uint64_t fnv1a_bytes(uint64_t h, const uint8_t *p, size_t n)
{
    size_t i;

    for (i = 0; i < n; i++)
        h = (h ^ p[i]) * 0x100000001b3ull;
    return h;
}

static uint64_t fnv1a(uint64_t h, const uint16_t *px, size_t n)
{
    size_t i;

    for (i = 0; i < n; i++) {
        h = (h ^ (px[i] & 0xFFu)) * 0x100000001b3ull;
        h = (h ^ (px[i] >> 8)) * 0x100000001b3ull;
    }
    return h;
}

/* The session's mesh i as the rasterizer draws it, and its vertex cache. */
static void take_mesh(client *c, uint32_t i)
{
    picture *pic = &c->pic;
    lumo_raster_mesh *m = &pic->mesh[pic->meshes];
    lumo_pmesh_view v;

    if (lumo_session_mesh(&c->ses, i, &v) || v.face_count == 0)
        return;
    memset(m, 0, sizeof *m);
    m->pos = v.positions;
    m->normal = v.normals;
    m->albedo = v.albedo;
    m->mesh_albedo[0] = m->mesh_albedo[1] = m->mesh_albedo[2] = DEFAULT_ALBEDO;
    m->tris = v.triangles;
    m->vertex_count = v.vertex_count;
    m->tri_count = v.face_count;
    /* Without room for a cache the bytes are the same, only slower. */
    pic->cache[pic->meshes] = lumo_arena_alloc(&c->pictures, lumo_raster_cache_bytes(v.vertex_count));
    if (pic->cache[pic->meshes] && lumo_raster_prepare(&pic->view, &pic->scene, m, pic->cache[pic->meshes]))
        pic->cache[pic->meshes] = NULL;
    pic->meshes++;
}

/* A picture of the grey screen's size: a band of its levels and, with
 * --out, its PGM image (header room below, as the PPM's). */
static int set_up_grey(client *c, uint16_t w, uint16_t h)
{
    picture *pic = &c->pic;

    pic->grey = pic->grey_image = NULL;
    pic->grey_hash = 0xcbf29ce484222325ull;
    if (w != CLIENT_SCREEN_W || h != CLIENT_SCREEN_H)
        return 0;
    pic->grey = lumo_arena_alloc(&c->pictures, (size_t)w / 2u * BAND_ROWS);
    pic->grey_image = c->out ? lumo_arena_alloc(&c->pictures, (size_t)w * h + 32u) : NULL;
    if (pic->grey_image)
        pic->grey_image += 32;
    return !pic->grey || (c->out && !pic->grey_image) ? -1 : 0;
}

/* View, lights (per-pixel, exposure 1, the IVG once a round is in: as
 * lumo-client draws), meshes and band memory for a w x h picture. */
static int set_up(client *c, uint16_t w, uint16_t h, const lumo_net_progress *p)
{
    picture *pic = &c->pic;
    const lumo_pkg_info *info = lumo_session_info(&c->ses);
    const lumo_pkg_light *lights = lumo_session_lights(&c->ses, &pic->scene.light_count);
    const lumo_ivg *ivg = lumo_session_ivg(&c->ses);
    lumo_raster_camera cam;
    uint32_t i;

    lumo_raster_camera_from_info(info, &cam);
    if (lumo_raster_view_init(&pic->view, &cam, w, h))
        return fail("the package's camera cannot be drawn", NULL);
    for (i = 0; i < pic->scene.light_count; i++)
        lumo_raster_light_from_pkg(&lights[i], &pic->lights[i]);
    pic->scene.lights = pic->lights;
    pic->scene.indirect = ivg && p->rounds ? lumo_raster_ivg_irradiance : NULL;
    pic->scene.indirect_ctx = ivg;
    pic->scene.exposure = LUMO_Q16_ONE;
    pic->scene.flags = LUMO_RASTER_PER_PIXEL;
    pic->band = lumo_arena_alloc(&c->pictures, (size_t)w * BAND_ROWS * 2u);
    pic->depth = lumo_arena_alloc(&c->pictures, (size_t)w * BAND_ROWS * 4u);
    /* The PPM header goes in the 32 bytes below the image (write_image). */
    pic->image = c->out ? lumo_arena_alloc(&c->pictures, (size_t)w * h * 3u + 32u) : NULL;
    if (pic->image)
        pic->image += 32;
    if (!pic->band || !pic->depth || (c->out && !pic->image) || set_up_grey(c, w, h))
        return fail("no memory for a picture", NULL);
    pic->meshes = 0;
    for (i = 0; i < info->mesh_count; i++)
        take_mesh(c, i);
    return 0;
}

/* RGB565 to 8-bit RGB (bit replication) into the image's rows. */
static void to_image(picture *pic, const lumo_raster_target *t)
{
    size_t i, n = (size_t)t->width * t->band_rows;
    uint8_t *o = pic->image + (size_t)t->band_y * t->width * 3u;

    for (i = 0; i < n; i++) {
        uint16_t v = pic->band[i];
        o[3 * i] = (uint8_t)((v >> 11 << 3) | (v >> 13));
        o[3 * i + 1] = (uint8_t)(((v >> 5 & 63u) << 2) | (v >> 9 & 3u));
        o[3 * i + 2] = (uint8_t)(((v & 31u) << 3) | (v >> 2 & 7u));
    }
}

/* The band's grey levels: hashed, shown on the board's screen (a board
 * without one says so and nothing is lost), kept as 0..255 (level x 17,
 * as QEMU's SSD0323 draws them) in the PGM image. */
static void to_grey(picture *pic, const lumo_raster_target *t)
{
    size_t i, n = (size_t)t->width / 2u * t->band_rows;
    uint8_t *o;

    grey4_band(pic->band, t->width, t->band_rows, t->band_y, pic->grey);
    pic->grey_hash = fnv1a_bytes(pic->grey_hash, pic->grey, n);
    (void)board_display_grey4(t->band_y, t->band_rows, t->width, pic->grey);
    if (!pic->grey_image)
        return;
    o = pic->grey_image + (size_t)t->band_y * t->width;
    for (i = 0; i < n; i++) {
        o[2 * i] = (uint8_t)((pic->grey[i] >> 4) * 17u);
        o[2 * i + 1] = (uint8_t)((pic->grey[i] & 15u) * 17u);
    }
}

/* Every band: clear, every mesh, hash (docs/rasterizer.md: the bytes do not
 * depend on the band split). */
static int draw_bands(client *c, uint16_t w, uint16_t h, uint64_t *hash)
{
    picture *pic = &c->pic;
    lumo_raster_target t;
    uint16_t y;
    uint32_t m;

    *hash = 0xcbf29ce484222325ull;
    for (y = 0; y < h; y = (uint16_t)(y + t.band_rows)) {
        uint16_t rows = (uint16_t)((unsigned)(h - y) < BAND_ROWS ? (unsigned)(h - y) : BAND_ROWS);
        if (lumo_raster_target_init(&t, w, h, y, rows, LUMO_PIXEL_RGB565, pic->band, pic->depth, 32) ||
            lumo_raster_clear(&t, 0))
            return fail("a band cannot be drawn", NULL);
        for (m = 0; m < pic->meshes; m++)
            if (lumo_raster_draw(&pic->view, &pic->scene, &pic->mesh[m], pic->cache[m], &t))
                return fail("a mesh cannot be drawn", NULL);
        *hash = fnv1a(*hash, pic->band, (size_t)w * rows);
        if (pic->image)
            to_image(pic, &t);
        if (pic->grey)
            to_grey(pic, &t);
    }
    return 0;
}

/* s + the decimal v at p (room for 10 digits is the caller's). */
static char *put_u32(char *p, uint32_t v)
{
    char d[10];
    int n = 0;

    do
        d[n++] = (char)('0' + v % 10u);
    while ((v /= 10u) != 0);
    while (n)
        *p++ = d[--n];
    return p;
}

static char *put_str(char *p, const char *s)
{
    size_t n = strlen(s);

    memcpy(p, s, n);
    return p + n;
}

/* "<kind>-<tag>-<W>x<H>" (kind: frame, grey) */
static void picture_name(char *out, const char *kind, const char *tag, uint16_t w, uint16_t h)
{
    char *p = put_str(put_str(out, kind), "-");

    p = put_str(p, tag);
    *p++ = '-';
    p = put_u32(p, w);
    *p++ = 'x';
    p = put_u32(p, h);
    *p = '\0';
}

/* DIR/<name>.ppm (P6, 3 bytes a pixel) or .pgm (P5, 1 byte): header, then
 * the image; the header goes in the 32 bytes below it. */
static int write_image(const client *c, const char *name, uint8_t *image, unsigned bytes_px, uint16_t w, uint16_t h)
{
    char path[256], *p;
    uint8_t *img = image - 32;
    size_t head;

    if (strlen(c->out) + strlen(name) + 8 > sizeof path)
        return fail("the --out path is too long", NULL);
    p = put_str(put_str(put_str(path, c->out), "/"), name);
    put_str(p, bytes_px == 3u ? ".ppm" : ".pgm")[0] = '\0';
    p = put_u32(put_str((char *)img, bytes_px == 3u ? "P6\n" : "P5\n"), w);
    p = put_str(put_u32(put_str(p, " "), h), "\n255\n");
    head = (size_t)(p - (char *)img);
    memmove(img + 32 - head, img, head);
    if (board_write_file(path, img + 32 - head, head + (size_t)w * h * bytes_px))
        return fail("cannot write ", path);
    return 0;
}

static void hash_line(const char *name, uint64_t hash)
{
    con_str("HASH ");
    con_str(name);
    con_str(" ");
    con_hex(hash, 16);
    con_nl();
}

static int draw_size(client *c, const char *tag, uint16_t w, uint16_t h, const lumo_net_progress *p)
{
    lumo_arena_mark mark = lumo_arena_get_mark(&c->pictures);
    uint32_t t0 = board_ticks();
    char name[48];
    cost one = {0, 0};
    uint64_t hash = 0;
    int rc;

    rc = set_up(c, w, h, p) || draw_bands(c, w, h, &hash);
    one.ticks = board_ticks() - t0;
    c->drawing.ticks += one.ticks;
    c->drawing.n++;
    picture_name(name, "frame", tag, w, h);
    if (rc == 0) {
        cost_line(name, &one, NULL);
        hash_line(name, hash);
        if (c->out)
            rc = write_image(c, name, c->pic.image, 3u, w, h);
    }
    if (rc == 0 && c->pic.grey) {
        picture_name(name, "grey", tag, w, h);
        hash_line(name, c->pic.grey_hash);
        if (c->out)
            rc = write_image(c, name, c->pic.grey_image, 1u, w, h);
    }
    lumo_arena_reset(&c->pictures, mark);
    return rc ? -1 : 0;
}

static int draw_picture(client *c, const char *tag, const lumo_net_progress *p)
{
    unsigned i;

    for (i = 0; i < NSIZES; i++)
        if (draw_size(c, tag, k_sizes[i][0], k_sizes[i][1], p))
            return -1;
    return 0;
}

/* Pictures for the first picture and every share the scene has passed. */
static int pictures_due(client *c)
{
    lumo_net_progress p;
    char tag[4];

    if (c->no_pictures)
        return 0;
    lumo_net_client_progress(&c->drv, &p);
    if (!c->first_done && first_picture_ready(c, &p)) {
        c->first_done = 1;
        if (draw_picture(c, "first", &p))
            return -1;
    }
    while (c->next_share < NSHARES && reached(&p, k_shares[c->next_share])) {
        put_u32(tag, k_shares[c->next_share++])[0] = '\0';
        if (draw_picture(c, tag, &p))
            return -1;
    }
    return 0;
}

/* ---- the conversation ------------------------------------------------------------- */

/* The driver's clock: milliseconds of board time; each read is kept so the
 * push-pull inside a lighting DATA can be told apart (net_client.h,
 * costs.update_ms: read right before and after it). */
static uint32_t clock_ms(void *ctx)
{
    client *c = ctx;
    uint32_t t = board_ticks();

    if (c->clock_reads < 8)
        c->clock_ticks[c->clock_reads] = t;
    c->clock_reads++;
    return t / (board_tick_hz() / 1000u);
}

static int send_pending(client *c)
{
    size_t n;
    lumo_status st;

    do {
        if ((st = lumo_net_client_next(&c->drv, c->tx, sizeof c->tx, &n)))
            return fail("the driver: ", lumo_strerror(st));
        if (n && c->drv.state == LUMO_NET_DONE && c->updates_wanted) {
            c->bye_held = 1;   /* the updates phase ends the conversation */
            break;
        }
        if (n && transmit(c, c->tx, n))
            return -1;
    } while (n && c->drv.state != LUMO_NET_DONE);
    return 0;
}

static int say_hello(client *c)
{
    size_t n;
    lumo_status st = lumo_net_client_hello(&c->drv, c->tx, sizeof c->tx, &n);

    return st ? fail("HELLO: ", lumo_strerror(st)) : transmit(c, c->tx, n);
}

/* After a refused frame or a silence (docs/protocol.md §1, §7 "Serial
 * lines"): forget the requests in flight and ask again from the cursors
 * held, or say HELLO again while the WELCOME has not come. */
static int ask_again(client *c)
{
    if (c->replay)
        return 0;
    if (++c->tries > MAX_TRIES)
        return fail("the server does not answer", NULL);
    c->resends++;
    c->asked_again = 1;
    lumo_net_client_reset_link(&c->drv);
    return c->drv.state == LUMO_NET_START ? say_hello(c) : send_pending(c);
}

/* Costs of an applied DATA: per geometry batch, per lighting DATA and its
 * push-pull (the driver's 2nd and 3rd clock reads, see clock_ms). */
static void count(client *c, const lumo_net_frame *f, uint32_t ticks)
{
    lumo_net_data d;

    if (f->type != LUMO_NET_DATA || lumo_net_data_decode(f, &d))
        return;
    c->bytes_in += d.len;
    if (d.channel == LUMO_NET_GEOMETRY) {
        c->geometry.ticks += ticks;
        c->geometry.n += d.count;
    } else {
        c->lighting.ticks += ticks;
        c->lighting.n++;
        if (c->clock_reads == 4) {
            c->pushpull.ticks += c->clock_ticks[2] - c->clock_ticks[1];
            c->pushpull.n++;
        }
    }
}

static const char *frame_name(uint8_t type)
{
    static const char *names[] = {"?", "HELLO", "WELCOME", "REQUEST", "DATA", "END", "ERROR", "BYE"};
    return type < sizeof names / sizeof names[0] ? names[type] : "unknown";
}

/* One whole frame (used bytes): dropped when out of turn, else applied,
 * then the pictures now due and the requests now possible. */
static int take_frame(client *c, const lumo_net_frame *f, size_t used)
{
    uint32_t t0;
    lumo_status st;

    c->frames++;
    if (!lumo_net_client_in_turn(&c->drv, f)) {
        c->stale++;
        return 0;
    }
    if (f->type == LUMO_NET_WELCOME && c->drv.package_id)
        c->welcome_again += (uint32_t)used;   /* a new connection's: checked, nothing applied */
    c->clock_reads = 0;
    t0 = board_ticks();
    if ((st = lumo_net_client_on_frame(&c->drv, f))) {
        con_str("client: error: ");
        con_str(frame_name(f->type));
        return fail(" frame: ", lumo_strerror(st));
    }
    count(c, f, board_ticks() - t0);
    c->tries = 0;
    c->asked_again = 0;
    return pictures_due(c) || send_pending(c) ? -1 : 0;
}

/* Decode and take every whole frame in rx; skip what is refused to the
 * next magic (asking again once per loss); keep the rest. */
static int take_frames(client *c)
{
    size_t at = 0, used;
    lumo_net_frame f;
    lumo_status st;

    while (c->drv.state != LUMO_NET_DONE) {
        uint32_t t0 = board_ticks();
        st = lumo_net_frame_decode(c->rx + at, c->rx_len - at, MAX_PAYLOAD, &f, &used);
        c->decode.ticks += board_ticks() - t0;
        if (st == LUMO_ERR_TRUNCATED)
            break;
        if (st) {
            c->refused++;
            at = lumo_net_resync(c->rx, c->rx_len, at + 1);
            if (!c->asked_again && ask_again(c))
                return -1;
            continue;
        }
        at += used;
        if (take_frame(c, &f, used))
            return -1;
    }
    memmove(c->rx, c->rx + at, c->rx_len - at);
    c->rx_len -= at;
    return 0;
}

/* Nothing for SILENCE_MS while answers are due: a frame lost its end (a
 * dropped byte) or vanished; drop the partial frame and ask again. */
static int silence(client *c)
{
    size_t k = lumo_net_resync(c->rx, c->rx_len, 1);

    c->silences++;
    memmove(c->rx, c->rx + k, c->rx_len - k);
    c->rx_len -= k;
    return ask_again(c);
}

/* The link is back as a new connection (BOARD_LINK_NEW): the bytes of a
 * frame the cut left unfinished are dropped, the requests in flight
 * forgotten, and HELLO with the cursors held resumes, as a TCP client does
 * after a cut (docs/protocol.md §8): nothing applied is sent again. */
static int new_connection(client *c)
{
    c->cuts++;
    c->cut_bytes += (uint32_t)c->rx_len;
    c->rx_len = 0;
    c->tries = 0;
    c->asked_again = 0;
    lumo_net_client_reset_link(&c->drv);
    return say_hello(c);
}

static int converse(client *c)
{
    if (say_hello(c))
        return -1;
    while (c->drv.state != LUMO_NET_DONE) {
        int32_t n = receive(c, c->rx + c->rx_len, RX_BYTES - c->rx_len);
        if (n == BOARD_LINK_NEW && !c->replay) {
            if (new_connection(c))
                return -1;
            continue;
        }
        if (n < 0)
            return fail(c->replay ? "the recording ends before the scene is complete"
                                  : "the link closed before the scene was complete", NULL);
        if (n == 0 ? silence(c) : (c->rx_len += (size_t)n, take_frames(c)))
            return -1;
    }
    return 0;
}

/* ---- the updates phase (docs/dynamic.md §6) ------------------------------------------ */

/* The next REQUEST of the poller, when one is due. Its clock is the
 * board's link, not a timer (a board may have none): it advances by
 * SILENCE_MS at each silence, so "again UPDATE_POLL_MS after an answer
 * with nothing new" is "after a silence"; a replay moves it to where the
 * request is due (the recording holds the answer that followed). */
static int update_ask(client *c)
{
    int tries;

    for (tries = 0; tries < 2 && !c->upd_asked; tries++) {
        size_t n = 0;
        lumo_status st = lumo_net_updates_next(&c->upd, c->upd_clock, c->tx, sizeof c->tx, &n);
        if (st)
            return fail("updates: ", lumo_strerror(st));
        if (n) {
            c->upd_asked = 1;
            return transmit(c, c->tx, n);
        }
        if (!c->replay)
            return 0;
        c->upd_clock += UPDATE_POLL_MS;
    }
    return 0;
}

/* After an answer: a picture when it changed the lighting or the poses. */
static int update_picture(client *c)
{
    lumo_net_progress p;
    uint32_t seen = c->upd.records + c->upd.poses;
    char tag[16], *t;

    if (seen == c->upd_seen || c->no_pictures)
        return 0;
    c->upd_seen = seen;
    t = put_str(tag, "update-");
    if (c->upd_pictures < 100u)
        *t++ = '0';
    if (c->upd_pictures < 10u)
        *t++ = '0';
    put_u32(t, c->upd_pictures++)[0] = '\0';
    lumo_net_client_progress(&c->drv, &p);
    return draw_picture(c, tag, &p);
}

/* One frame of the updates channel to the poller (anything else there is
 * out of place: STATE). A refused frame fails the phase; the session keeps
 * its last good lighting (the poller applies all or nothing). */
static int take_update(client *c, const lumo_net_frame *f)
{
    uint32_t t0 = board_ticks(), answers = c->upd.answers;
    lumo_status st = lumo_net_updates_takes(f) || f->type == LUMO_NET_ERROR ? LUMO_OK : LUMO_ERR_STATE;

    c->frames++;
    if (!st && (st = update_ask(c)) == LUMO_OK)
        st = lumo_net_updates_on_frame(&c->upd, f, c->upd_clock);
    if (st) {
        con_str("client: error: updates: ");
        con_str(frame_name(f->type));
        return fail(" frame: ", lumo_strerror(st));
    }
    c->updating.ticks += board_ticks() - t0;
    if (c->upd.answers == answers)
        return 0;
    c->updating.n++;
    c->upd_asked = 0;
    c->upd_silences = 0;
    return update_picture(c);
}

static int take_update_frames(client *c)
{
    size_t at = 0, used;
    lumo_net_frame f;
    lumo_status st;

    while (c->upd_pictures < c->updates_wanted) {
        st = lumo_net_frame_decode(c->rx + at, c->rx_len - at, MAX_PAYLOAD, &f, &used);
        if (st == LUMO_ERR_TRUNCATED)
            break;
        if (st)
            return fail("updates: a refused frame: ", lumo_strerror(st));
        at += used;
        if (take_update(c, &f))
            return -1;
    }
    memmove(c->rx, c->rx + at, c->rx_len - at);
    c->rx_len -= at;
    return 0;
}

/* Pull updates until --updates N pictures are drawn, then the BYE held. */
static int updates_phase(client *c)
{
    lumo_status st = lumo_net_updates_init(&c->upd, &c->ses, LUMO_IVG_FORM_QUANTIZED, UPDATE_RECORDS,
                                           UPDATE_POLL_MS);
    uint8_t bye[16];
    size_t n;

    if (st)
        return fail("updates: ", lumo_strerror(st));
    say("pulling lighting updates", NULL);
    /* What followed the scene's last frame in rx (a replay reads ahead) is
     * the updates channel's. */
    if (take_update_frames(c))
        return -1;
    while (c->upd_pictures < c->updates_wanted) {
        int32_t got;
        if (update_ask(c))
            return -1;
        got = receive(c, c->rx + c->rx_len, RX_BYTES - c->rx_len);
        if (got == BOARD_LINK_NEW && !c->replay)
            return fail("updates: the link was cut (the updates phase does not resume)", NULL);
        if (got < 0)
            return fail(c->replay ? "updates: the recording ends before the pictures asked for"
                                  : "updates: the link closed", NULL);
        if (got == 0) {
            c->upd_clock += SILENCE_MS;
            if (c->upd_asked && ++c->upd_silences > UPDATE_MAX_SILENCES)
                return fail("updates: the server does not answer", NULL);
            continue;
        }
        c->rx_len += (size_t)got;
        if (take_update_frames(c))
            return -1;
    }
    if (c->bye_held && lumo_net_bye_encode(bye, sizeof bye, &n) == LUMO_OK)
        return transmit(c, bye, n);
    return 0;
}

/* ---- start and end ------------------------------------------------------------------ */

static int start(client *c)
{
    lumo_session_config scfg = {{0, LUMO_SESSION_LOD_ALL}, LUMO_IVG_SMOOTH};
    lumo_net_client_config ncfg;
    lumo_status st;

    if (c->replay && board_read_file(c->replay, c->log, RECORD_BYTES, &c->log_len))
        return fail("cannot read the recording ", c->replay);
    memset(&ncfg, 0, sizeof ncfg);
    ncfg.arena_bytes = (uint32_t)c->scene_arena.size;
    ncfg.max_payload = MAX_PAYLOAD;
    ncfg.width = k_sizes[0][0];
    ncfg.height = k_sizes[0][1];
    ncfg.ivg_form = LUMO_IVG_FORM_QUANTIZED;
    ncfg.smoothing = 1;
    ncfg.policy.order = LUMO_NET_ORDER_INTERLEAVED;
    ncfg.policy.vertices = REQUEST_VERTICES;
    ncfg.policy.rounds = REQUEST_ROUNDS;
    ncfg.policy.pipeline = PIPELINE;
    ncfg.replay = c->replay != NULL;
    ncfg.clock = board_tick_hz() >= 1000u ? clock_ms : NULL;   /* costs only: sizes are fixed */
    ncfg.clock_ctx = c;
    if ((st = lumo_session_init(&c->ses, &scfg, &c->scene_arena)) ||
        (st = lumo_net_client_init(&c->drv, &c->ses, &ncfg)))
        return fail("set-up: ", lumo_strerror(st));
    return 0;
}

/* "client: done: ..." — what arrived and what the line did to it. */
static void report_counts(const client *c)
{
    lumo_net_progress p;

    lumo_net_client_progress(&c->drv, &p);
    con_str("client: done: ");
    con_u64(p.vertices);
    con_str(" vertices, IVG ");
    con_u64(p.rounds);
    con_str("/");
    con_u64(p.full_rounds);
    con_str(" rounds, ");
    con_u64(c->bytes_in);
    con_str(" DATA bytes; ");
    con_u64(c->frames);
    con_str(" frames, ");
    con_u64(c->stale);
    con_str(" out of turn, ");
    con_u64(c->refused);
    con_str(" refused, ");
    con_u64(c->silences);
    con_str(" silences, ");
    con_u64(c->resends);
    con_str(" times asked again; ");
    con_u64(c->raw_in);
    con_str(" bytes received, ");
    con_u64(c->cuts);
    con_str(" connections (");
    con_u64(c->welcome_again);
    con_str(" WELCOME bytes again, ");
    con_u64(c->cut_bytes);
    con_str(" bytes of cut frames dropped)");
    con_nl();
    if (!c->updates_wanted)
        return;
    con_str("client: updates: ");
    con_u64(c->upd.records);
    con_str(" records, ");
    con_u64(c->upd.poses);
    con_str(" poses in ");
    con_u64(c->upd.answers);
    con_str(" answers, ");
    con_u64(c->upd_pictures);
    con_str(" pictures");
    con_nl();
}

static void report_memory(const client *c)
{
    size_t stack = board_stack_peak();

    con_str("MEM scene arena peak ");
    con_u64(c->scene_arena.peak);
    con_str(" of ");
    con_u64(c->scene_arena.size);
    con_str(" bytes, picture arena peak ");
    con_u64(c->pictures.peak);
    con_str(" of ");
    con_u64(c->pictures.size);
    con_str(" bytes");
    con_nl();
    if (stack != 0) {
        con_str("stack peak: ");
        con_u64(stack);
        con_str(" bytes");
        con_nl();
    }
}

static void report(const client *c, uint32_t t0)
{
    cost total = {0, 0}, decode = c->decode;

    report_counts(c);
    cost_line("geometry.batch", &c->geometry, "batches");
    cost_line("lighting.data", &c->lighting, "DATA frames, push-pull included");
    cost_line("lighting.pushpull", &c->pushpull, "push-pulls");
    decode.n = c->frames;
    cost_line("frame.decode", &decode, "frames, CRC and checks");
    cost_line("picture", &c->drawing, "pictures");
    if (c->updates_wanted)
        cost_line("updates.answer", &c->updating, "answers, records and push-pull");
    total.ticks = board_ticks() - t0;
    cost_line(c->replay ? "session.total" : "session.total.with-waiting", &total, NULL);
    report_memory(c);
}

int main(void)
{
    client *c = &g_client;
    uint32_t t0 = board_ticks();
    int rc;

    if (parse_args(c) || carve_memory(c) || start(c))
        return 2;
    say(c->replay ? "replaying " : "streaming over the board's link", c->replay);
    rc = converse(c);
    if (rc == 0 && c->updates_wanted)
        rc = updates_phase(c);
    if (rc == 0 && c->record && board_write_file(c->record, c->log, c->log_len))
        rc = fail("cannot write the recording ", c->record);
    report(c, t0);
    if (rc == 0 && c->hold) {
        say("holding the last picture on the screen", NULL);
        board_hold();
    }
    return rc ? 1 : 0;
}
