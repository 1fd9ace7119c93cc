/*
 * link_http.c — lumo-client --http URL: a .lumo package on a stock HTTP/1.1
 * server (nginx, a CDN), read with Range requests (libcurl, one connection
 * kept alive). No lumo-server: this link answers the protocol driver's
 * frames itself, with lumo-server's own pieces (server/serve/), so the
 * driver is unchanged (docs/protocol.md §7 "HTTP"):
 *
 *  - opening: the package header and chunk table (two ranges, both CRCs
 *    checked), then the WELCOME descriptors — INFO, each PMSH chunk's
 *    stream header (its length in its byte 6), IVGD, IVGS, ORDR — each whole
 *    chunk checked against the table's CRC, and WELCOME built as the server
 *    builds it (srv_welcome_build);
 *  - HELLO: that WELCOME, or ERROR as lumo-server would send it;
 *  - REQUEST: planned and cut into DATA frames by the server's request
 *    mapping (srv_plan_start / srv_plan_next over a srv_pkg whose chunks are
 *    filled as they are fetched). Geometry: the batch records' offsets are
 *    found by walking record heads (lumo_pmesh_next_record) on the fetched
 *    prefix of the stream, fetching what the walk lacks (at most the
 *    header's largest record per batch still to find); lighting: the bytes
 *    of the rounds asked, from IVGS's offsets. A chunk fetched to its end is
 *    checked against the table's CRC.
 *
 * Each REQUEST is answered when it is sent (the range requests it takes
 * happen then); read() hands out the frames made.
 */
#include <curl/curl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "lumo/net.h"
#include "lumo/package.h"
#include "lumo/pmesh.h"
#include "lumo/scene.h"
#include "lumo/session.h"
#include "lumo/wire.h"
#include "lumo_host/package_msg.h"
#include "lumo_host/package_check.h"
#include "serve/index.h"
#include "serve/plan.h"
#include "client.h"

#define FETCH_MIN  ((size_t)16 << 10)
#define FETCH_MAX  ((size_t)8 << 20)

typedef struct http_chunk {
    uint32_t type, offset, length, crc;
} http_chunk;

typedef struct http_link {
    CURL *curl;
    char curl_err[CURL_ERROR_SIZE];
    uint64_t file_size;               /* from Content-Range */
    uint32_t nchunks;
    http_chunk chunk[LUMO_PKG_MAX_CHUNKS];
    uint8_t *desc[4];                 /* INFO, IVGD, IVGS, ORDR payloads */
    uint32_t desc_len[4];
    srv_pkg pk;                       /* the server's view, filled as fetched */
    uint8_t *stream[LUMO_MAX_MESHES]; /* each PMSH chunk: a prefix fetched */
    uint32_t stream_chunk[LUMO_MAX_MESHES], fetched[LUMO_MAX_MESHES], known[LUMO_MAX_MESHES];
    uint8_t *bundle[2];               /* IVGF, IVGQ: a prefix fetched */
    uint32_t bundle_chunk[2], bfetched[2];
    uint8_t form, hello_seen;
    uint32_t max_payload;
    uint8_t *q;                       /* frames made, not read yet */
    size_t qhead, qlen, qcap;
    uint32_t ranges;                  /* range requests made */
    uint64_t range_bytes;
} http_link;

enum { D_INFO, D_IVGD, D_IVGS, D_ORDR };

static int fail(client_link *l, const char *fmt, const char *a, const char *b)
{
    snprintf(l->err, sizeof l->err, fmt, a, b);
    return -1;
}

/* ---- ranges ----------------------------------------------------------------------- */

typedef struct sink {
    uint8_t *dst;
    size_t want, got;
} sink;

static size_t on_body(char *p, size_t size, size_t n, void *ctx)
{
    sink *s = ctx;
    size_t k = size * n, take = k < s->want - s->got ? k : s->want - s->got;

    memcpy(s->dst + s->got, p, take);
    s->got += take;
    return take == k ? k : 0;   /* more than asked: abort the transfer */
}

/* Decimal digits at *s into *v (at most 19: no wrap); 0, or -1 when none. */
static int header_number(const char **s, uint64_t *v)
{
    int k = 0;

    for (*v = 0; **s >= '0' && **s <= '9' && k < 19; (*s)++, k++)
        *v = *v * 10 + (uint64_t)(**s - '0');
    return k == 0 || (**s >= '0' && **s <= '9') ? -1 : 0;
}

/* "Content-Range: bytes A-B/TOTAL" from the server, whose bytes are hostile:
 * curl's header line is not NUL-terminated, so it is copied first, and the
 * numbers are read whole (sscanf's %llu would take "-1" as 2^64 - 1). A
 * line that does not parse leaves the size unknown (load_table refuses). */
static size_t on_header(char *p, size_t size, size_t n, void *ctx)
{
    http_link *h = ctx;
    char line[160];
    const char *s = line;
    size_t len = size * n;
    uint64_t a, b, total;

    if (len < 14 || len >= sizeof line || strncasecmp(p, "Content-Range:", 14))
        return len;
    memcpy(line, p, len);
    line[len] = 0;
    for (s += 14; *s == ' ' || *s == '\t'; s++)
        ;
    if (strncmp(s, "bytes ", 6))
        return len;
    s += 6;
    if (header_number(&s, &a) || *s++ != '-' || header_number(&s, &b) || *s++ != '/' ||
        header_number(&s, &total) || strspn(s, "\r\n") != strlen(s) || a > b || b >= total)
        return len;
    h->file_size = total;
    return len;
}

/* Bytes [off, off + len) of the package into dst: a 206 answer of exactly
 * len bytes, or -1 with the reason in l->err. */
static int get_range(client_link *l, uint64_t off, size_t len, uint8_t *dst)
{
    http_link *h = l->impl;
    char range[64];
    sink s = {dst, len, 0};
    long code = 0;
    CURLcode rc;

    snprintf(range, sizeof range, "%llu-%llu", (unsigned long long)off, (unsigned long long)(off + len - 1));
    curl_easy_setopt(h->curl, CURLOPT_RANGE, range);
    curl_easy_setopt(h->curl, CURLOPT_WRITEDATA, &s);
    rc = curl_easy_perform(h->curl);
    curl_easy_getinfo(h->curl, CURLINFO_RESPONSE_CODE, &code);
    h->ranges++;
    if (code && code != 206) {
        snprintf(l->err, sizeof l->err, "%s: HTTP %ld for bytes %s%s", l->target, code, range,
                 code == 200 ? " (the server ignores Range requests)" : "");
        return -1;
    }
    if (rc != CURLE_OK) {
        snprintf(l->err, sizeof l->err, "%s: %s", l->target, h->curl_err[0] ? h->curl_err : curl_easy_strerror(rc));
        return -1;
    }
    if (s.got != len) {
        snprintf(l->err, sizeof l->err, "%s: only %zu of bytes %s: the file ends there (not a whole .lumo package)",
                 l->target, s.got, range);
        return -1;
    }
    h->range_bytes += len;
    return 0;
}

/* ---- the package's table and descriptors -------------------------------------------- */

static int find_chunk(const http_link *h, uint32_t type, uint32_t nth)
{
    uint32_t i;

    for (i = 0; i < h->nchunks; i++)
        if (h->chunk[i].type == type && nth-- == 0)
            return (int)i;
    return -1;
}

/* Header and table: the checks lumo_package_open makes of them. */
static int load_table(client_link *l)
{
    http_link *h = l->impl;
    uint8_t head[LUMO_PKG_HEADER_SIZE], table[LUMO_PKG_MAX_CHUNKS * LUMO_PKG_ENTRY_SIZE];
    char why[160];
    lumo_status st = LUMO_OK;
    uint32_t i, n;

    if (get_range(l, 0, sizeof head, head))
        return -1;
    if (!h->file_size)
        return fail(l, "%s: %s", l->target, "the server did not say the file's size (Content-Range)");
    if (memcmp(head, "LUMO", 4) || lumo_wire_crc32(0, head, 20) != lumo_wire_le32(head + 20))
        st = memcmp(head, "LUMO", 4) ? LUMO_ERR_CORRUPT : LUMO_ERR_CHECKSUM;
    else if (lumo_wire_le16(head + 4) != LUMO_PKG_VERSION_MAJOR)
        st = LUMO_ERR_VERSION;
    else if ((n = lumo_wire_le32(head + 8)) > LUMO_PKG_MAX_CHUNKS || lumo_wire_le32(head + 12))
        st = n > LUMO_PKG_MAX_CHUNKS ? LUMO_ERR_LIMIT : LUMO_ERR_UNSUPPORTED;
    if (st)
        return fail(l, "%s: %s", l->target, host_package_strerror(head, sizeof head, st, why, sizeof why));
    if (n && get_range(l, LUMO_PKG_HEADER_SIZE, (size_t)n * LUMO_PKG_ENTRY_SIZE, table))
        return -1;
    if (lumo_wire_crc32(0, table, (size_t)n * LUMO_PKG_ENTRY_SIZE) != lumo_wire_le32(head + 16))
        return fail(l, "%s: %s", l->target, "the chunk table's CRC does not match");
    uint32_t twice = 0;
    if (lumo_package_table_once(table, n, &twice)) {
        char what[] = {(char)twice, (char)(twice >> 8), (char)(twice >> 16), (char)(twice >> 24), 0};
        return fail(l, "%s: not a valid package: two %s chunks (the format allows one)", l->target, what);
    }
    h->nchunks = n;
    for (i = 0; i < n; i++) {
        const uint8_t *e = table + (size_t)i * LUMO_PKG_ENTRY_SIZE;
        http_chunk *c = &h->chunk[i];
        c->type = lumo_wire_le32(e), c->offset = lumo_wire_le32(e + 4);
        c->length = lumo_wire_le32(e + 8), c->crc = lumo_wire_le32(e + 12);
        if ((uint64_t)c->offset + c->length > h->file_size)
            return fail(l, "%s: %s", l->target, "the chunk table points past the end of the file");
    }
    h->pk.id = lumo_wire_le32(head + 20);
    return 0;
}

/* A whole chunk fetched and checked against the table's CRC. */
static int get_chunk(client_link *l, int i, uint8_t **out)
{
    http_link *h = l->impl;
    const http_chunk *c = &h->chunk[i];

    if (!(*out = malloc(c->length ? c->length : 1)))
        return fail(l, "%s: %s", l->target, "out of memory");
    if (c->length && get_range(l, c->offset, c->length, *out))
        return -1;
    if (lumo_wire_crc32(0, *out, c->length) != c->crc)
        return fail(l, "%s: %s", l->target, "a chunk's CRC does not match the table");
    return 0;
}

/* The index of mesh m: its stream buffer with the header fetched,
 * the header read, room for every record's offset. */
static int load_mesh(client_link *l, uint32_t m)
{
    http_link *h = l->impl;
    srv_mesh_index *mi = &h->pk.mesh[m];
    int i = find_chunk(h, LUMO_PKG_PMSH, m);
    lumo_status st;

    if (i < 0 || h->chunk[i].length < LUMO_PMESH_HEADER_MIN)
        return fail(l, "%s: %s", l->target, "a mesh has no progressive stream (PMSH): lumo-client streams those only");
    h->stream_chunk[m] = (uint32_t)i;
    if (!(h->stream[m] = malloc(h->chunk[i].length)))
        return fail(l, "%s: %s", l->target, "out of memory");
    /* the longest header or the whole chunk: the header says its length */
    size_t head = h->chunk[i].length < LUMO_PMESH_HEADER_MAX ? h->chunk[i].length : LUMO_PMESH_HEADER_MAX;
    if (get_range(l, h->chunk[i].offset, head, h->stream[m]))
        return -1;
    if ((st = lumo_pmesh_read_header(h->stream[m], head, &mi->h)))
        return fail(l, "%s: a stream header: %s", l->target, lumo_strerror(st));
    if (!(mi->rec = malloc(((size_t)mi->h.batch_count + 1) * sizeof *mi->rec)))
        return fail(l, "%s: %s", l->target, "out of memory");
    mi->stream = h->stream[m];
    mi->len = h->chunk[i].length;
    mi->rec[0] = mi->h.header_bytes;
    h->fetched[m] = mi->h.header_bytes;  /* what follows is fetched again with the records */
    return 0;
}

/* The round table from IVGS (decoded against IVGD) and room for both
 * bundles, fetched as rounds are asked. */
static int load_ivg(client_link *l)
{
    http_link *h = l->impl;
    srv_ivg_index *g = &h->pk.ivg;
    lumo_ivg_desc desc;
    lumo_ivg_order o;
    uint32_t r, f;
    lumo_status st;
    char why[300];

    if (!h->desc[D_IVGD] || !h->desc[D_IVGS])
        return 0;   /* no IVG: lighting requests are RANGE */
    if (host_ivgd_check(h->desc[D_IVGD], h->desc_len[D_IVGD], &desc, why, sizeof why))
        return fail(l, "%s: %s", l->target, why);
    if ((st = lumo_ivg_order_decode(h->desc[D_IVGS], h->desc_len[D_IVGS], &desc, &o)))
        return fail(l, "%s: the IVG streaming order (IVGS): %s", l->target, lumo_strerror(st));
    g->rounds = o.rounds, g->records = o.records;
    g->first = malloc(((size_t)o.rounds + 1) * sizeof *g->first);
    g->off[0] = malloc(((size_t)o.rounds + 1) * sizeof *g->off[0]);
    g->off[1] = malloc(((size_t)o.rounds + 1) * sizeof *g->off[1]);
    if (!g->first || !g->off[0] || !g->off[1])
        return fail(l, "%s: %s", l->target, "out of memory");
    for (r = 0; r <= o.rounds; r++) {
        g->first[r] = lumo_ivg_order_first(&o, r);
        for (f = 0; f < 2; f++)
            g->off[f][r] = lumo_ivg_order_offset(&o, (lumo_ivg_form)f, r);
    }
    for (f = 0; f < 2; f++) {
        int i = find_chunk(h, f == LUMO_IVG_FORM_QUANTIZED ? LUMO_PKG_IVGQ : LUMO_PKG_IVGF, 0);
        if (i < 0 || g->off[f][o.rounds] != h->chunk[i].length)
            return fail(l, "%s: %s", l->target, "the IVG round table does not cover its bundle");
        h->bundle_chunk[f] = (uint32_t)i;
        if (!(h->bundle[f] = malloc(h->chunk[i].length)))
            return fail(l, "%s: %s", l->target, "out of memory");
        g->bundle[f] = h->bundle[f];
        g->bundle_len[f] = h->chunk[i].length;
    }
    g->present = 1;
    return 0;
}

/* INFO, the streams' headers, IVGD, IVGS, ORDR; then WELCOME. */
static int load_descriptors(client_link *l)
{
    static const uint32_t types[4] = {LUMO_PKG_INFO, LUMO_PKG_IVGD, LUMO_PKG_IVGS, LUMO_PKG_ORDR};
    http_link *h = l->impl;
    lumo_net_msg msgs[LUMO_NET_MAX_WELCOME_MSGS];
    lumo_pkg_info info;
    uint32_t k, m, n = 0;
    char why[300];

    for (k = 0; k < 4; k++) {
        int i = find_chunk(h, types[k], 0);
        if (i >= 0 && get_chunk(l, i, &h->desc[k]))
            return -1;
        h->desc_len[k] = i >= 0 ? h->chunk[i].length : 0;
    }
    if (!h->desc[D_INFO])
        return fail(l, "%s: %s", l->target, "no INFO chunk: a stream-only package holds no scene to draw");
    if (host_info_check(h->desc[D_INFO], h->desc_len[D_INFO], &info, why, sizeof why))
        return fail(l, "%s: %s", l->target, why);
    if (info.mesh_count > LUMO_MAX_MESHES)
        return fail(l, "%s: %s", l->target, "more meshes than LUMO_MAX_MESHES");
    h->pk.mesh_count = info.mesh_count;
    if (info.mesh_count && !(h->pk.mesh = calloc(info.mesh_count, sizeof *h->pk.mesh)))
        return fail(l, "%s: %s", l->target, "out of memory");
    for (m = 0; m < info.mesh_count; m++)
        if (load_mesh(l, m))
            return -1;
    if (load_ivg(l))
        return -1;
    msgs[n++] = (lumo_net_msg){LUMO_PKG_INFO, 0, h->desc_len[D_INFO], h->desc[D_INFO]};
    for (m = 0; m < info.mesh_count; m++)
        msgs[n++] = (lumo_net_msg){LUMO_PKG_PMSH, m, h->pk.mesh[m].h.header_bytes, h->stream[m]};
    if (h->pk.ivg.present) {
        msgs[n++] = (lumo_net_msg){LUMO_PKG_IVGD, 0, h->desc_len[D_IVGD], h->desc[D_IVGD]};
        msgs[n++] = (lumo_net_msg){LUMO_PKG_IVGS, 0, h->desc_len[D_IVGS], h->desc[D_IVGS]};
    }
    if (h->desc[D_ORDR])
        msgs[n++] = (lumo_net_msg){LUMO_PKG_ORDR, 0, h->desc_len[D_ORDR], h->desc[D_ORDR]};
    if (srv_welcome_build(&h->pk, msgs, n, l->err, sizeof l->err))
        return -1;
    return 0;
}

/* ---- fetching what a request needs --------------------------------------------------- */

/* A chunk fetched to its end is checked whole against the table. */
static int check_complete(client_link *l, const uint8_t *data, uint32_t chunk)
{
    const http_chunk *c = &((http_link *)l->impl)->chunk[chunk];

    if (lumo_wire_crc32(0, data, c->length) != c->crc)
        return fail(l, "%s: %s", l->target, "a chunk's CRC does not match the table (the file changed?)");
    return 0;
}

/* More of mesh m's stream: at least `want` bytes past the prefix held. */
static int fetch_stream(client_link *l, uint32_t m, size_t want)
{
    http_link *h = l->impl;
    const http_chunk *c = &h->chunk[h->stream_chunk[m]];
    size_t left = c->length - h->fetched[m];

    want = want < FETCH_MIN ? FETCH_MIN : want > FETCH_MAX ? FETCH_MAX : want;
    want = want > left ? left : want;
    if (!want)
        return fail(l, "%s: %s", l->target, "a stream ends inside a batch record");
    if (get_range(l, (uint64_t)c->offset + h->fetched[m], want, h->stream[m] + h->fetched[m]))
        return -1;
    h->fetched[m] += (uint32_t)want;
    return h->fetched[m] == c->length ? check_complete(l, h->stream[m], h->stream_chunk[m]) : 0;
}

/* The offsets of mesh m's records [0, end]: record heads walked on the
 * fetched prefix, as lumo-server walks them at start-up. */
static int find_records(client_link *l, uint32_t m, uint32_t end)
{
    http_link *h = l->impl;
    srv_mesh_index *mi = &h->pk.mesh[m];

    while (h->known[m] < end) {
        size_t at = mi->rec[h->known[m]], n;
        const uint8_t *rec;
        lumo_status st = lumo_pmesh_next_record(h->stream[m], h->fetched[m], &at, &rec, &n);
        if (st == LUMO_ERR_RANGE || st == LUMO_ERR_TRUNCATED) {
            if (fetch_stream(l, m, (size_t)(end - h->known[m]) * mi->h.max_batch_bytes))
                return -1;
            continue;
        }
        if (st || (st = lumo_pmesh_record_check(rec, n, h->known[m])))
            return fail(l, "%s: a batch record: %s", l->target, lumo_strerror(st));
        mi->rec[++h->known[m]] = (uint32_t)at;
        if (n > mi->max_record)
            mi->max_record = (uint32_t)n;
    }
    if (h->known[m] == mi->h.batch_count && mi->rec[h->known[m]] != mi->len)
        return fail(l, "%s: %s", l->target, "bytes after a stream's last batch record");
    return 0;
}

/* The bytes of rounds up to `end` of form f's bundle (its header first,
 * so that the whole chunk's CRC can be checked once it is all here). */
static int fetch_rounds(client_link *l, uint8_t f, uint32_t end)
{
    http_link *h = l->impl;
    const http_chunk *c = &h->chunk[h->bundle_chunk[f]];
    uint32_t to = h->pk.ivg.off[f][end];

    if (to <= h->bfetched[f])
        return 0;
    if (get_range(l, (uint64_t)c->offset + h->bfetched[f], to - h->bfetched[f], h->bundle[f] + h->bfetched[f]))
        return -1;
    h->bfetched[f] = to;
    return to == c->length ? check_complete(l, h->bundle[f], h->bundle_chunk[f]) : 0;
}

/* ---- answers ----------------------------------------------------------------------- */

static int room(client_link *l, size_t n)
{
    http_link *h = l->impl;
    size_t need = h->qlen + n;

    if (h->qhead && h->qhead == h->qlen)
        h->qhead = h->qlen = 0, need = n;
    if (need <= h->qcap)
        return 0;
    h->qcap = need * 2 > FETCH_MIN ? need * 2 : FETCH_MIN;
    if (!(h->q = realloc(h->q, h->qcap)))
        return fail(l, "%s: %s", l->target, "out of memory");
    return 0;
}

static int queue_error(client_link *l, lumo_status st, const char *text)
{
    http_link *h = l->impl;
    size_t n = 0;

    if (room(l, LUMO_NET_OVERHEAD + 8 + LUMO_NET_MAX_TEXT))
        return -1;
    lumo_net_error_encode((uint32_t)st, text, h->q + h->qlen, h->qcap - h->qlen, &n);
    h->qlen += n;
    return 0;
}

static int on_hello(client_link *l, const lumo_net_frame *f)
{
    http_link *h = l->impl;
    lumo_net_hello m;
    char text[160];
    lumo_status st;

    if ((st = lumo_net_hello_decode(f, &m)))
        return queue_error(l, st, "HELLO");
    if (m.package != 0)
        return queue_error(l, LUMO_ERR_RANGE, "an HTTP URL holds one package: ask for package 0");
    if (h->pk.arena_need > m.arena_bytes) {
        snprintf(text, sizeof text, "the scene needs %u arena bytes, the client has %u", h->pk.arena_need,
                 m.arena_bytes);
        return queue_error(l, LUMO_ERR_NOMEM, text);
    }
    if (h->pk.welcome_len - LUMO_NET_OVERHEAD > m.max_payload)
        return queue_error(l, LUMO_ERR_LIMIT, "WELCOME is larger than the client's max payload");
    h->form = m.ivg_form;
    h->max_payload = m.max_payload > LUMO_NET_MAX_PAYLOAD ? LUMO_NET_MAX_PAYLOAD : m.max_payload;
    h->hello_seen = 1;
    if (room(l, h->pk.welcome_len))
        return -1;
    memcpy(h->q + h->qlen, h->pk.welcome, h->pk.welcome_len);
    h->qlen += h->pk.welcome_len;
    return 0;
}

/* Fetch what request r needs, so that the server's mapping finds it. */
static int fetch_for(client_link *l, const lumo_net_request *r)
{
    http_link *h = l->impl;

    if (r->amount == 0)
        return 0;   /* srv_plan_start refuses it */
    if (r->channel == LUMO_NET_GEOMETRY && r->mesh < h->pk.mesh_count) {
        const lumo_pmesh_header *hd = &h->pk.mesh[r->mesh].h;
        if (r->cursor < hd->batch_count)
            return find_records(l, r->mesh, lumo_net_geometry_end(hd, r->cursor, r->amount));
    }
    if (r->channel == LUMO_NET_LIGHTING && h->pk.ivg.present && r->cursor < h->pk.ivg.rounds &&
        (h->form == LUMO_IVG_FORM_FLOAT || h->form == LUMO_IVG_FORM_QUANTIZED)) {
        uint32_t end = r->amount > h->pk.ivg.rounds - r->cursor ? h->pk.ivg.rounds : r->cursor + r->amount;
        return fetch_rounds(l, h->form, end);
    }
    return 0;
}

static int on_request(client_link *l, const lumo_net_frame *f)
{
    http_link *h = l->impl;
    lumo_net_request r;
    lumo_net_data d;
    srv_answer a;
    char err[160];
    int end = 0;
    lumo_status st;

    if (!h->hello_seen)
        return queue_error(l, LUMO_ERR_STATE, "REQUEST before HELLO");
    if ((st = lumo_net_request_decode(f, &r)))
        return queue_error(l, st, "REQUEST");
    if (fetch_for(l, &r))
        return -1;
    if ((st = srv_plan_start(&h->pk, &r, h->form, h->max_payload, &a, &end, err, sizeof err)))
        return queue_error(l, st, err);
    if (end) {
        lumo_net_end e = {r.channel, r.channel == LUMO_NET_GEOMETRY ? r.mesh : 0};
        size_t n = 0;
        if (room(l, LUMO_NET_OVERHEAD + 8))
            return -1;
        lumo_net_end_encode(&e, h->q + h->qlen, h->qcap - h->qlen, &n);
        h->qlen += n;
        return 0;
    }
    while (srv_plan_next(&h->pk, &a, &d)) {
        size_t n = 0;
        if (room(l, LUMO_NET_OVERHEAD + LUMO_NET_DATA_HEAD + d.len))
            return -1;
        if ((st = lumo_net_data_encode(&d, h->q + h->qlen, h->qcap - h->qlen, &n)))
            return fail(l, "%s: DATA: %s", l->target, lumo_strerror(st));
        h->qlen += n;
    }
    return 0;
}

/* ---- the link ---------------------------------------------------------------------- */

static int http_open(client_link *l)
{
    static int curl_ready;
    http_link *h;

    if (!curl_ready && curl_global_init(CURL_GLOBAL_DEFAULT) == CURLE_OK)
        curl_ready = 1;
    if (!(h = l->impl = calloc(1, sizeof *h)) || !(h->curl = curl_easy_init()))
        return fail(l, "%s: %s", l->target, "cannot start libcurl");
    h->pk.path = strdup(l->target);
    h->pk.name = h->pk.path;
    curl_easy_setopt(h->curl, CURLOPT_URL, l->target);
    curl_easy_setopt(h->curl, CURLOPT_ERRORBUFFER, h->curl_err);
    curl_easy_setopt(h->curl, CURLOPT_WRITEFUNCTION, on_body);
    curl_easy_setopt(h->curl, CURLOPT_HEADERFUNCTION, on_header);
    curl_easy_setopt(h->curl, CURLOPT_HEADERDATA, h);
    curl_easy_setopt(h->curl, CURLOPT_NOSIGNAL, 1L);
    curl_easy_setopt(h->curl, CURLOPT_CONNECTTIMEOUT, 10L);
    curl_easy_setopt(h->curl, CURLOPT_LOW_SPEED_LIMIT, 1L);   /* a stalled answer: 30 s */
    curl_easy_setopt(h->curl, CURLOPT_LOW_SPEED_TIME, 30L);
    curl_easy_setopt(h->curl, CURLOPT_FOLLOWLOCATION, 1L);
    curl_easy_setopt(h->curl, CURLOPT_HTTP_VERSION, (long)CURL_HTTP_VERSION_1_1);
    curl_easy_setopt(h->curl, CURLOPT_USERAGENT, "lumo-client");
    return load_table(l) || load_descriptors(l) ? -1 : 0;
}

/* The driver's frames: each answered now. */
static int http_send(client_link *l, const uint8_t *p, size_t n)
{
    size_t at = 0, used;
    lumo_net_frame f;

    while (at < n) {
        if (lumo_net_frame_decode(p + at, n - at, LUMO_NET_MAX_PAYLOAD, &f, &used))
            return fail(l, "%s: %s", l->target, "a frame the client made does not decode");
        if ((f.type == LUMO_NET_HELLO && on_hello(l, &f)) || (f.type == LUMO_NET_REQUEST && on_request(l, &f)))
            return -1;
        at += used;
        l->bytes_out += used;
    }
    return 0;
}

static long http_read(client_link *l, uint8_t *buf, size_t cap, int timeout_ms)
{
    http_link *h = l->impl;
    size_t n = h->qlen - h->qhead;

    (void)timeout_ms;
    if (!n) {
        snprintf(l->err, sizeof l->err, "nothing was asked that is not answered");
        return LINK_ERROR;
    }
    n = n < cap ? n : cap;
    memcpy(buf, h->q + h->qhead, n);
    h->qhead += n;
    l->bytes_in += n;
    return (long)n;
}

static void http_close(client_link *l)
{
    http_link *h = l->impl;
    uint32_t i;

    if (!h)
        return;
    snprintf(l->note, sizeof l->note, "%u range requests, %llu bytes fetched", h->ranges,
             (unsigned long long)h->range_bytes);
    for (i = 0; i < h->pk.mesh_count; i++)
        free(h->stream[i]);
    for (i = 0; i < 4; i++)
        free(h->desc[i]);
    free(h->bundle[0]);
    free(h->bundle[1]);
    free(h->q);
    srv_pkg_close(&h->pk);   /* the index arrays, WELCOME, the path; nothing is mapped */
    if (h->curl)
        curl_easy_cleanup(h->curl);
    free(h);
    l->impl = NULL;
}

const link_ops link_http = {"http", 0, 0, http_open, http_send, http_read, http_close};
