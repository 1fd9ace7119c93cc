/*
 * net_client.c — the client's side of the stream protocol (lumo/net_client.h,
 * docs/protocol.md §3): WELCOME into the session, requests sized and
 * interleaved (seed 000 §5.1–5.2), DATA applied whole or not at all.
 */
#include <string.h>
#include "lumo/net_client.h"
#include "lumo/wire.h"
#include "net_internal.h"

#define DEFAULT_TARGET_MS 250u
#define DEFAULT_PIPELINE  4u
#define MAX_PIPELINE      8u
/* Adaptive sizes stay within these (a request smaller than one batch still
 * gets one; more than this many vertices or rounds per request buys no
 * throughput and delays the next picture). */
#define MAX_VERTICES      (1u << 20)
#define MAX_ROUNDS        4096u

lumo_status lumo_net_client_init(lumo_net_client *c, lumo_session *session, const lumo_net_client_config *cfg)
{
    if (!c || !session || !cfg || cfg->max_payload < LUMO_NET_MIN_PAYLOAD ||
        cfg->max_payload > LUMO_NET_MAX_PAYLOAD || cfg->policy.order > LUMO_NET_ORDER_LIGHTING_FIRST ||
        cfg->policy.pipeline > MAX_PIPELINE)
        return LUMO_ERR_ARG;
    memset(c, 0, sizeof *c);
    c->cfg = *cfg;
    if (!c->cfg.policy.target_ms)
        c->cfg.policy.target_ms = DEFAULT_TARGET_MS;
    if (!c->cfg.policy.pipeline) {
        c->cfg.policy.pipeline = DEFAULT_PIPELINE;
        c->pipeline_auto = 1;
    }
    c->session = session;
    return LUMO_OK;
}

static uint32_t now_ms(const lumo_net_client *c)
{
    return c->cfg.clock ? c->cfg.clock(c->cfg.clock_ctx) : 0;
}

static lumo_status fail(lumo_net_client *c, lumo_status st)
{
    c->state = LUMO_NET_FAILED;
    c->error = st;
    return st;
}

lumo_status lumo_net_client_hello(lumo_net_client *c, uint8_t *out, size_t cap, size_t *written)
{
    lumo_net_hello h;
    lumo_status st;

    if (!c || (c->state != LUMO_NET_START && c->state != LUMO_NET_READY))
        return LUMO_ERR_STATE;
    memset(&h, 0, sizeof h);
    h.package = c->cfg.package;
    h.arena_bytes = c->cfg.arena_bytes;
    h.max_payload = c->cfg.max_payload;
    h.width = c->cfg.width, h.height = c->cfg.height;
    h.ivg_form = c->cfg.ivg_form;
    h.flags = c->cfg.smoothing ? LUMO_NET_FLAG_SMOOTHING : 0;
    if (c->cfg.first_picture && !c->package_id && !c->cfg.replay)
        h.flags |= LUMO_NET_FLAG_FIRST_PICTURE;
    if (c->cfg.prt)
        h.flags |= LUMO_NET_FLAG_PRT;
    c->hello_ms = now_ms(c);
    h.resume_id = c->package_id;
    h.mesh_count = c->package_id ? c->mesh_count : 0;
    if ((st = lumo_net_hello_encode(&h, c->held, out, cap, written)))
        return st;
    c->state = LUMO_NET_HELLO_SENT;
    return LUMO_OK;
}

void lumo_net_client_reset_link(lumo_net_client *c)
{
    uint32_t m;

    /* Ask again in the order the lost requests were first asked: the round
     * robin resumes where it stood before the oldest of them, so a resumed
     * session makes the requests an uncut one makes (fixed sizes). */
    if (c->npending)
        c->turn = c->pending[0].turn;
    c->npending = 0;
    c->partial_records = 0;
    for (m = 0; m < c->mesh_count; m++) {
        c->asked[m] = c->held[m];
        if (c->prt_asked[m])
            lumo_session_prt_progress(c->session, m, &c->prt_asked[m], NULL);
    }
    c->rounds_asked = c->rounds_held;
    if (c->state == LUMO_NET_HELLO_SENT)
        c->state = c->package_id ? LUMO_NET_READY : LUMO_NET_START;
}

static uint32_t batch_vertices(const lumo_net_client *c, uint32_t m, uint32_t from, uint32_t to);

/* ---- WELCOME ------------------------------------------------------------------ */

/* A PRTV header the session took: the cursor of mesh m's PRT requests. */
static void take_prt(lumo_net_client *c, uint32_t m)
{
    if (m >= LUMO_MAX_MESHES)
        return;
    lumo_session_prt_progress(c->session, m, &c->prt_asked[m], NULL);
    c->has_prt = c->prt_asked[m] > 0 || c->has_prt;
}

/* Descriptors into the session, in the order WELCOME carries them. */
static lumo_status feed_welcome(lumo_net_client *c, const lumo_net_welcome *w)
{
    lumo_net_msg m;
    size_t at = 0;
    lumo_status st;

    while ((st = lumo_net_welcome_next(w, &at, &m)) == LUMO_OK) {
        if ((st = lumo_session_feed(c->session, m.type, m.index, m.data, m.len)))
            return st;
        if (m.type == LUMO_MSG_PRTV && c->cfg.prt)
            take_prt(c, m.index);
    }
    return st == LUMO_ERR_RANGE ? LUMO_OK : st;
}

/* What the session now holds: the streams' sizes, and (resuming) where each
 * cursor stands. */
static lumo_status take_scene(lumo_net_client *c)
{
    const lumo_pkg_info *info = lumo_session_info(c->session);
    lumo_pmesh_header h;
    uint32_t m;

    if (!info)
        return LUMO_ERR_CORRUPT;
    c->mesh_count = info->mesh_count;
    for (m = 0; m < c->mesh_count; m++) {
        if (lumo_session_stream_header(c->session, m, &h))
            return LUMO_ERR_UNSUPPORTED;   /* raw meshes are not streamed */
        c->batches[m] = h.batch_count;
    }
    /* Lighting streams only with its order (the package's IVGS). */
    c->has_ivg = lumo_session_ivg(c->session) != NULL && lumo_session_ivg_order(c->session) != NULL &&
                 c->cfg.ivg_form != LUMO_NET_FORM_NONE;
    c->rounds_total = c->has_ivg ? lumo_session_ivg_order(c->session)->rounds : 0;
    return LUMO_OK;
}

static void expect(lumo_net_client *c, uint8_t channel, uint32_t mesh, uint32_t end)
{
    lumo_net_pending *p = &c->pending[c->npending++];

    p->channel = channel, p->mesh = mesh, p->cursor = 0, p->end = end;
    p->sent_ms = c->hello_ms;   /* asked with HELLO: its round trip counts from there */
    p->turn = c->turn;
}

/* The answers the server sends after WELCOME when HELLO asked for the first
 * picture (protocol.md §2 HELLO): they are requests in flight as if the
 * client had asked right then, and their cursors advance the same way. */
static void expect_first_picture(lumo_net_client *c)
{
    lumo_pmesh_header h;
    uint32_t m;

    for (m = 0; m < c->mesh_count; m++) {
        lumo_session_stream_header(c->session, m, &h);
        c->asked[m] = lumo_net_geometry_end(&h, 0, h.base_vertices);
        expect(c, LUMO_NET_GEOMETRY, m, c->asked[m]);
    }
    if (c->has_ivg && c->rounds_total) {
        c->rounds_asked = 1;
        expect(c, LUMO_NET_LIGHTING, 0, 1);
    }
}

static lumo_status on_welcome(lumo_net_client *c, const lumo_net_frame *f)
{
    lumo_net_welcome w;
    lumo_status st;

    if ((st = lumo_net_welcome_decode(f, &w)))
        return st;
    if (c->package_id) {   /* resuming: the scene is the one we hold */
        if (w.package_id != c->package_id)
            return LUMO_ERR_STATE;
        c->state = LUMO_NET_READY;
        return LUMO_OK;
    }
    if (w.arena_need > c->cfg.arena_bytes)
        return LUMO_ERR_NOMEM;
    if ((st = feed_welcome(c, &w)) || (st = take_scene(c)))
        return st;
    c->package_id = w.package_id;
    c->state = LUMO_NET_READY;
    if (c->cfg.first_picture && !c->cfg.replay)
        expect_first_picture(c);
    return LUMO_OK;
}

/* ---- DATA ----------------------------------------------------------------------- */

/* Ms * 1024 per KiB of `bytes` taking `ms`, blended into `avg` (3/4 old). */
static uint32_t blend_rate(uint32_t avg, uint32_t ms, uint32_t bytes)
{
    uint64_t r;

    if (bytes == 0)
        return avg;
    r = ((uint64_t)ms << 20) / bytes;   /* ms * 1024 per 1024 bytes */
    if (r > 0xffffffffu)
        r = 0xffffffffu;
    return avg ? (uint32_t)(((uint64_t)avg * 3 + r) / 4) : (uint32_t)r;
}

/* Every record of a geometry DATA checked before any is applied (the walk,
 * each head, its batch index and its CRC), so that a damaged or foreign
 * frame changes nothing. */
static lumo_status check_records(const lumo_net_data *d)
{
    size_t at = 0, n;
    const uint8_t *rec;
    uint32_t k;
    lumo_status st;

    for (k = 0; k < d->count; k++) {
        if ((st = lumo_pmesh_next_record(d->bytes, d->len, &at, &rec, &n)))
            return st == LUMO_ERR_RANGE ? LUMO_ERR_TRUNCATED : st;
        if ((st = lumo_pmesh_record_check(rec, n, d->first + k)))
            return st;  /* damaged, or not record first + k */
    }
    return at == d->len ? LUMO_OK : LUMO_ERR_CORRUPT;
}

static lumo_status apply_geometry(lumo_net_client *c, const lumo_net_data *d)
{
    size_t at = 0, n;
    const uint8_t *rec;
    uint32_t k;
    lumo_status st;

    if ((st = check_records(d)))
        return st;
    for (k = 0; k < d->count; k++) {
        (void)lumo_pmesh_next_record(d->bytes, d->len, &at, &rec, &n);
        /* Past the checks only a record the decoder refuses stops here: the
         * records before it stay applied, and so do their cursors. */
        if ((st = lumo_session_feed(c->session, LUMO_MSG_PMSB, d->mesh, rec, n)))
            return st;
        c->held[d->mesh]++;
    }
    return LUMO_OK;
}

/* The records of a lighting DATA go to the session as one IVGR message: the
 * eight bytes before them in the frame are its head (form, records). */
static lumo_status apply_lighting(lumo_net_client *c, const lumo_net_data *d)
{
    lumo_status st;

    st = lumo_session_feed(c->session, LUMO_MSG_IVGR, 0, d->bytes - LUMO_NET_IVGR_HEAD,
                           d->len + LUMO_NET_IVGR_HEAD);
    if (st)
        return st;
    c->rounds_held += d->count;   /* 0 for a frame that continues a round */
    c->partial_records = d->count ? 0 : c->partial_records + d->records;
    return LUMO_OK;
}

/* PRT bytes of mesh m held (the session's cursor, docs/protocol.md §10). */
static uint32_t prt_held(const lumo_net_client *c, uint32_t m)
{
    uint32_t held = 0;

    lumo_session_prt_progress(c->session, m, &held, NULL);
    return held;
}

/* A PRT DATA's span goes to the session as one PRTS message: the four
 * bytes before it in the frame (records = the offset) are its head. */
static lumo_status apply_prt(lumo_net_client *c, const lumo_net_data *d)
{
    return lumo_session_feed(c->session, LUMO_MSG_PRTS, d->mesh, d->bytes - LUMO_NET_PRTS_HEAD,
                             d->len + LUMO_NET_PRTS_HEAD);
}

/* Where a channel's cursor stands now: batches of the mesh, PRTV bytes of
 * the mesh, or lighting rounds. */
static uint32_t held_of(const lumo_net_client *c, uint8_t channel, uint32_t mesh)
{
    if (channel == LUMO_NET_GEOMETRY)
        return c->held[mesh];
    return channel == LUMO_NET_PRT ? prt_held(c, mesh) : c->rounds_held;
}

/* The request a DATA or END answers: the oldest in flight (none in replay,
 * where the recording is taken as it comes). */
static const lumo_net_pending *answering(const lumo_net_client *c)
{
    return c->npending ? &c->pending[0] : NULL;
}

/* Does DATA d fit the conversation (docs/protocol.md §2, §3)? STATE when it
 * answers something not asked or not next (channel, mesh, first past or
 * before the cursor, more than asked, past the end); CORRUPT when its
 * lighting records are not those of the rounds it names (IVGS: the records
 * of a round add up over the frames of a split round). Nothing changes. */
static lumo_status check_data(const lumo_net_client *c, const lumo_net_data *d)
{
    const lumo_net_pending *p = answering(c);

    if (!p && !c->cfg.replay)
        return LUMO_ERR_STATE;
    if (p && (p->end <= p->cursor || d->channel != p->channel ||
              (d->channel != LUMO_NET_LIGHTING && d->mesh != p->mesh) || (uint64_t)d->first + d->count > p->end))
        return LUMO_ERR_STATE;   /* (a request at the end, the resync marker, is answered by END) */
    if (d->channel == LUMO_NET_PRT)
        return c->has_prt && d->mesh < c->mesh_count && c->prt_asked[d->mesh] && d->first == prt_held(c, d->mesh)
                   ? LUMO_OK : LUMO_ERR_STATE;
    if (d->channel == LUMO_NET_GEOMETRY) {
        if (d->mesh >= c->mesh_count || d->first != c->held[d->mesh] || d->count != d->records ||
            (uint64_t)d->first + d->count > c->batches[d->mesh])
            return LUMO_ERR_STATE;
        return LUMO_OK;
    }
    if (!c->has_ivg || d->form != c->cfg.ivg_form || d->first != c->rounds_held ||
        (uint64_t)d->first + d->count > c->rounds_total || (d->count == 0 && d->first >= c->rounds_total))
        return LUMO_ERR_STATE;
    {
        const lumo_ivg_order *o = lumo_session_ivg_order(c->session);
        uint32_t base = lumo_ivg_order_first(o, d->first);
        uint64_t have = (uint64_t)c->partial_records + d->records;
        if (d->count ? have != lumo_ivg_order_first(o, d->first + d->count) - base
                     : have >= lumo_ivg_order_first(o, d->first + 1) - base)
            return LUMO_ERR_CORRUPT;
    }
    return LUMO_OK;
}

/* The oldest pending request is answered once its cursor reaches its end.
 * The link is two numbers (seed 000 §5.2: a request costs a round trip plus
 * its bytes): the shortest answer time seen is the round trip; an answer's
 * bytes flowed from a round trip after its request, or from the previous
 * answer's end when that came later (requests in flight back to back). */
static void retire(lumo_net_client *c, uint32_t t, uint32_t bytes)
{
    lumo_net_pending *p = &c->pending[0];
    uint32_t held = held_of(c, p->channel, p->mesh);
    uint32_t took, flow, from;

    c->data_bytes += bytes;
    if (held < p->end)
        return;
    took = t - p->sent_ms;
    if (!c->costs.rtt_ms || took < c->costs.rtt_ms)
        c->costs.rtt_ms = took ? took : 1;
    /* The answer flowed from when its first byte could come (a round trip
     * after the request) or, if the link was still busy with the previous
     * answer then, from that one's end. */
    from = p->sent_ms + c->costs.rtt_ms;
    if (c->retired && (int32_t)(c->retired_ms - from) > 0)
        from = c->retired_ms;
    flow = (int32_t)(t - from) > 0 ? t - from : 0;
    c->costs.ms_per_kib_q10 = blend_rate(c->costs.ms_per_kib_q10, flow ? flow : 1, c->data_bytes);
    c->data_bytes = 0;
    c->retired_ms = t;
    c->retired++;
    memmove(c->pending, c->pending + 1, --c->npending * sizeof *c->pending);
}

static lumo_status on_data(lumo_net_client *c, const lumo_net_frame *f)
{
    lumo_net_data d;
    uint32_t t0, t1, before;
    lumo_status st;

    if ((st = lumo_net_data_decode(f, &d)) || (st = check_data(c, &d)))
        return st;
    t0 = now_ms(c);
    before = held_of(c, d.channel, d.mesh);
    st = d.channel == LUMO_NET_GEOMETRY ? apply_geometry(c, &d)
       : d.channel == LUMO_NET_PRT      ? apply_prt(c, &d) : apply_lighting(c, &d);
    if (st)
        return st;
    if (d.channel == LUMO_NET_PRT) {
        (void)before;   /* PRT bytes are the link's and the apply's costs only */
    } else if (d.channel == LUMO_NET_GEOMETRY) {
        uint32_t v = batch_vertices(c, d.mesh, before, c->held[d.mesh]);
        c->costs.bytes_per_vertex = v ? d.len / v + 1 : c->costs.bytes_per_vertex;
        c->mesh_bytes[d.mesh] += d.len;
    } else {
        uint32_t u = now_ms(c);
        lumo_session_update(c->session);   /* push-pull after lighting (§4.1) */
        c->costs.update_ms = now_ms(c) - u;
        /* Smoothing is most of push-pull's time (seed 000 Fig. 7) and its
         * quality gain small: a client over its budget drops it. */
        if (c->cfg.policy.smooth_budget_ms && c->costs.update_ms > c->cfg.policy.smooth_budget_ms &&
            !c->smoothing_dropped) {
            lumo_session_set_ivg_flags(c->session, 0);
            c->smoothing_dropped = 1;
        }
        c->costs.bytes_per_round = d.count ? d.len / d.count : c->costs.bytes_per_round;
    }
    t1 = now_ms(c);
    c->costs.apply_ms_per_kib_q10 = blend_rate(c->costs.apply_ms_per_kib_q10, t1 - t0, d.len);
    c->bytes_in += d.len;
    if (c->npending)
        retire(c, t1, d.len);
    return LUMO_OK;
}

/* END answers a request at the end of its channel (a cursor at the stream's
 * batch count or the rounds' count): the driver asks for no such thing but
 * the marker of lumo_net_client_resync. A recording's END is taken as it
 * comes. */
static lumo_status check_end(const lumo_net_client *c, const lumo_net_end *e)
{
    const lumo_net_pending *p = answering(c);

    uint32_t size = 0;

    if (e->channel == LUMO_NET_PRT) {
        if (e->mesh >= c->mesh_count || !c->prt_asked[e->mesh])
            return LUMO_ERR_STATE;
        lumo_session_prt_progress(c->session, e->mesh, NULL, &size);
    } else if (e->channel == LUMO_NET_GEOMETRY ? e->mesh >= c->mesh_count : !c->has_ivg)
        return LUMO_ERR_STATE;
    if (!p)
        return c->cfg.replay ? LUMO_OK : LUMO_ERR_STATE;
    if (e->channel != p->channel || (e->channel != LUMO_NET_LIGHTING && e->mesh != p->mesh) ||
        p->cursor < (e->channel == LUMO_NET_GEOMETRY ? c->batches[e->mesh]
                     : e->channel == LUMO_NET_PRT    ? size : c->rounds_total))
        return LUMO_ERR_STATE;
    return LUMO_OK;
}

static lumo_status on_end(lumo_net_client *c, const lumo_net_frame *f)
{
    lumo_net_end e;
    lumo_status st;

    if ((st = lumo_net_end_decode(f, &e)) || (st = check_end(c, &e)))
        return st;
    if (c->npending)
        memmove(c->pending, c->pending + 1, --c->npending * sizeof *c->pending);
    return LUMO_OK;
}

lumo_status lumo_net_client_on_frame(lumo_net_client *c, const lumo_net_frame *f)
{
    lumo_status st;

    if (!c || !f)
        return LUMO_ERR_ARG;
    if (c->state == LUMO_NET_FAILED)
        return c->error;
    if (f->type == LUMO_NET_ERROR)
        return fail(c, net_error_status(f));
    if (c->state == LUMO_NET_HELLO_SENT && f->type == LUMO_NET_WELCOME)
        st = on_welcome(c, f);
    else if (c->state == LUMO_NET_READY && f->type == LUMO_NET_DATA)
        st = on_data(c, f);
    else if (c->state == LUMO_NET_READY && f->type == LUMO_NET_END)
        st = on_end(c, f);
    else
        st = LUMO_ERR_STATE;
    return st ? fail(c, st) : LUMO_OK;
}

/* ---- frames out of turn (a serial line, docs/protocol.md §1) --------------------------- */

/* The oldest request in flight is for this channel (and mesh). */
static int answers_oldest(const lumo_net_client *c, uint8_t channel, uint32_t mesh)
{
    const lumo_net_pending *p = &c->pending[0];

    return c->npending > 0 && p->channel == channel && (channel == LUMO_NET_LIGHTING || p->mesh == mesh);
}

static int data_in_turn(const lumo_net_client *c, const lumo_net_frame *f)
{
    lumo_net_data d;

    if (lumo_net_data_decode(f, &d))
        return 1;
    if (!c->cfg.replay && !answers_oldest(c, d.channel, d.mesh))
        return 0;
    if (d.channel == LUMO_NET_GEOMETRY || d.channel == LUMO_NET_PRT)
        return d.mesh < c->mesh_count && d.first == held_of(c, d.channel, d.mesh);
    return d.first == c->rounds_held;
}

static int end_in_turn(const lumo_net_client *c, const lumo_net_frame *f)
{
    lumo_net_end e;

    if (lumo_net_end_decode(f, &e))
        return 1;
    return c->cfg.replay || answers_oldest(c, e.channel, e.mesh);
}

int lumo_net_client_in_turn(const lumo_net_client *c, const lumo_net_frame *f)
{
    if (!c || !f)
        return 0;
    if (f->type == LUMO_NET_ERROR)
        return 1;
    if (f->type == LUMO_NET_WELCOME)
        return c->state == LUMO_NET_HELLO_SENT;
    if (c->state != LUMO_NET_READY)
        return 0;
    if (f->type == LUMO_NET_DATA)
        return data_in_turn(c, f);
    return f->type == LUMO_NET_END && end_in_turn(c, f);
}

/* ---- requests --------------------------------------------------------------------- */

static int mesh_open(const lumo_net_client *c, uint32_t m)
{
    return c->asked[m] < c->batches[m];
}

static int prt_open(const lumo_net_client *c, uint32_t m)
{
    uint32_t size = 0;

    if (!c->has_prt || !c->prt_asked[m])
        return 0;
    lumo_session_prt_progress(c->session, m, NULL, &size);
    return c->prt_asked[m] < size;
}

/* Vertex records of mesh m's PRT to ask for now: as many as the vertices
 * its geometry requests have asked (a client relights what it holds, in
 * the progressive order: docs/prt.md), all that is left once they have
 * asked the whole stream; 0 while the PRT is as far as the geometry.
 * The clusters and pass table come with the first request. */
static uint32_t prt_amount(const lumo_net_client *c, uint32_t m)
{
    lumo_pmesh_header h;
    uint32_t fixed, vb, have, want;

    if (!prt_open(c, m) || lumo_session_prt_layout(c->session, m, &fixed, &vb) ||
        lumo_session_stream_header(c->session, m, &h))
        return 0;
    have = c->prt_asked[m] > fixed ? (c->prt_asked[m] - fixed) / vb : 0;
    want = mesh_open(c, m) ? lumo_net_vertices_before(&h, c->asked[m]) : h.vertices;
    return want > have ? want - have : 0;
}

static int ivg_open(const lumo_net_client *c)
{
    return c->has_ivg && c->rounds_asked < c->rounds_total;
}

/* Vertices in batches [from, to) of mesh m. */
static uint32_t batch_vertices(const lumo_net_client *c, uint32_t m, uint32_t from, uint32_t to)
{
    lumo_pmesh_header h;

    if (lumo_session_stream_header(c->session, m, &h) || from >= to)
        return 0;
    return lumo_net_vertices_before(&h, to) - lumo_net_vertices_before(&h, from);
}

/* Bytes per vertex of mesh m: what its batches held so far took (meshes
 * differ: a wall's one-vertex batch is mostly record framing, ~100 bytes a
 * vertex, the dragon's batches ~5); the last DATA's figure before any. */
static uint32_t mesh_bytes_per_vertex(const lumo_net_client *c, uint32_t m)
{
    uint32_t v = batch_vertices(c, m, 0, c->held[m]);

    return v && c->mesh_bytes[m] ? c->mesh_bytes[m] / v + 1 : c->costs.bytes_per_vertex;
}

/* How much one request should ask (seed 000 §5.2): fixed by the policy, or
 * what the measured link and apply costs fit into the target time. */
static uint32_t adaptive(const lumo_net_client *c, uint32_t bytes_per_unit, uint32_t fixed_ms,
                         uint32_t unit, uint32_t limit)
{
    uint64_t ms_per_unit_q10 = ((uint64_t)c->costs.ms_per_kib_q10 + c->costs.apply_ms_per_kib_q10) *
                               bytes_per_unit / 1024u;
    uint32_t budget = c->cfg.policy.target_ms > fixed_ms ? c->cfg.policy.target_ms - fixed_ms : 0;
    uint64_t n;

    if (!c->cfg.clock || !bytes_per_unit || !ms_per_unit_q10 || c->retired < 2) {
        /* Nothing measured yet: one unit, then twice as many each answer. */
        uint64_t start = (uint64_t)unit << (c->retired < 10 ? c->retired : 10);
        return start > limit ? limit : (uint32_t)start;
    }
    n = ((uint64_t)budget << 10) / ms_per_unit_q10;
    return n < unit ? unit : n > limit ? limit : (uint32_t)n;
}

static uint32_t geometry_amount(const lumo_net_client *c, uint32_t m)
{
    lumo_pmesh_header h;

    if (c->asked[m] == 0)   /* the base mesh first, whole */
        return batch_vertices(c, m, 0, 1);
    if (c->cfg.policy.vertices)
        return c->cfg.policy.vertices;
    if (lumo_session_stream_header(c->session, m, &h))
        return 1;
    return adaptive(c, mesh_bytes_per_vertex(c, m), 0, h.batch_vertices, MAX_VERTICES);
}

static uint32_t lighting_amount(const lumo_net_client *c)
{
    if (c->rounds_asked == 0)   /* the corners first */
        return 1;
    if (c->cfg.policy.rounds)
        return c->cfg.policy.rounds;
    return adaptive(c, c->costs.bytes_per_round, c->costs.update_ms, 1, MAX_ROUNDS);
}

/* The first picture needs every base mesh and the corners, whatever the
 * order; then the policy's order (seed 000 §5.1). Returns the channel
 * (and mesh) to ask next, or -1 when nothing is left. */
static int pick(lumo_net_client *c, uint32_t *mesh)
{
    uint32_t m, k, n = c->mesh_count + 1;

    for (m = 0; m < c->mesh_count; m++)
        if (c->asked[m] == 0 && mesh_open(c, m))
            return *mesh = m, LUMO_NET_GEOMETRY;
    if (c->rounds_asked == 0 && ivg_open(c))
        return LUMO_NET_LIGHTING;
    if (c->cfg.policy.order == LUMO_NET_ORDER_LIGHTING_FIRST && ivg_open(c))
        return LUMO_NET_LIGHTING;
    for (m = 0; m < c->mesh_count; m++)   /* PRT keeps up with the geometry asked */
        if (prt_amount(c, m))
            return *mesh = m, LUMO_NET_PRT;
    for (k = 0; k < n; k++) {
        uint32_t slot = (c->turn + k) % n;
        if (c->cfg.policy.order == LUMO_NET_ORDER_GEOMETRY_FIRST && slot == c->mesh_count)
            continue;
        if (slot < c->mesh_count ? mesh_open(c, slot) : ivg_open(c)) {
            c->turn = slot + 1;
            *mesh = slot;
            return slot < c->mesh_count ? LUMO_NET_GEOMETRY : LUMO_NET_LIGHTING;
        }
    }
    return ivg_open(c) ? LUMO_NET_LIGHTING : -1;
}

/* The end of a PRT answer as the server computes it (docs/protocol.md
 * §10): the rest of the clusters and passes, then `amount` vertex records
 * past those held whole, within the chunk. */
static uint32_t prt_end(const lumo_net_client *c, uint32_t m, uint32_t cursor, uint32_t amount)
{
    uint32_t size = 0, fixed = 0, vb = 1;
    uint64_t held, end;

    (void)lumo_session_prt_layout(c->session, m, &fixed, &vb);   /* asked only with a PRTV */
    held = cursor > fixed ? (cursor - fixed) / vb : 0;
    end = fixed + (held + amount) * vb;
    lumo_session_prt_progress(c->session, m, NULL, &size);
    return end > size ? size : (uint32_t)end;
}

static lumo_status send_request(lumo_net_client *c, int channel, uint32_t mesh, uint8_t *out, size_t cap,
                                size_t *written)
{
    lumo_net_request r;
    lumo_net_pending *p = &c->pending[c->npending];
    lumo_status st;

    memset(&r, 0, sizeof r);
    r.channel = (uint8_t)channel;
    r.mesh = channel == LUMO_NET_LIGHTING ? 0 : mesh;
    r.cursor = channel == LUMO_NET_GEOMETRY ? c->asked[mesh] : channel == LUMO_NET_PRT ? c->prt_asked[mesh]
             : c->rounds_asked;
    r.amount = channel == LUMO_NET_GEOMETRY ? geometry_amount(c, mesh)
             : channel == LUMO_NET_PRT      ? prt_amount(c, mesh) : lighting_amount(c);
    if ((st = lumo_net_request_encode(&r, out, cap, written)))
        return st;
    p->channel = r.channel, p->mesh = r.mesh, p->cursor = r.cursor, p->sent_ms = now_ms(c);
    if (channel == LUMO_NET_PRT) {
        p->end = prt_end(c, mesh, r.cursor, r.amount);
        c->prt_asked[mesh] = p->end;
    } else if (channel == LUMO_NET_GEOMETRY) {
        lumo_pmesh_header h;
        lumo_session_stream_header(c->session, mesh, &h);
        p->end = lumo_net_geometry_end(&h, r.cursor, r.amount);   /* what the server sends */
        c->asked[mesh] = p->end;
    } else {
        p->end = r.cursor + r.amount > c->rounds_total ? c->rounds_total : r.cursor + r.amount;
        c->rounds_asked = p->end;
    }
    if (c->npending == 0)
        c->data_bytes = 0;
    c->npending++;
    return LUMO_OK;
}

/* Every base mesh and the corners asked for: the first picture is on its
 * way, and the policy's pipeline applies from now on. */
static int first_picture_asked(const lumo_net_client *c)
{
    uint32_t m;

    for (m = 0; m < c->mesh_count; m++)
        if (c->asked[m] == 0 && mesh_open(c, m))
            return 0;
    return c->rounds_asked > 0 || !ivg_open(c);
}

/* With the pipeline left to the driver (policy.pipeline 0): the answers in
 * flight, at the measured bytes per vertex and per round and the measured
 * flow, would leave the link idle before the answer to a request sent now
 * could arrive (they take less than a round trip). A count of requests
 * alone does not cover a round trip when the requests are small (the rest
 * of a small mesh: a few hundred bytes), and each such wait costs a round
 * trip of idle link. */
static int link_idles(const lumo_net_client *c)
{
    uint64_t bytes = 0;
    uint32_t k;

    if (!c->pipeline_auto || !c->cfg.clock || !c->costs.rtt_ms || !c->costs.ms_per_kib_q10)
        return 0;
    for (k = 0; k < c->npending; k++) {
        const lumo_net_pending *p = &c->pending[k];
        if (p->channel == LUMO_NET_GEOMETRY) {
            uint32_t from = c->held[p->mesh] > p->cursor ? c->held[p->mesh] : p->cursor;
            bytes += (uint64_t)batch_vertices(c, p->mesh, from, p->end) * mesh_bytes_per_vertex(c, p->mesh);
        } else if (p->channel == LUMO_NET_PRT) {
            uint32_t from = prt_held(c, p->mesh) > p->cursor ? prt_held(c, p->mesh) : p->cursor;
            bytes += p->end > from ? p->end - from : 0;
        } else {
            uint32_t from = c->rounds_held > p->cursor ? c->rounds_held : p->cursor;
            bytes += (uint64_t)(p->end > from ? p->end - from : 0) * c->costs.bytes_per_round;
        }
    }
    return ((bytes * c->costs.ms_per_kib_q10) >> 20) < c->costs.rtt_ms;
}

static int all_held(const lumo_net_client *c)
{
    uint32_t m;

    for (m = 0; m < c->mesh_count; m++) {
        uint32_t held = 0, size = 0;
        if (c->held[m] < c->batches[m])
            return 0;
        lumo_session_prt_progress(c->session, m, &held, &size);
        if (c->has_prt && c->prt_asked[m] && held < size)
            return 0;
    }
    return !c->has_ivg || c->rounds_held >= c->rounds_total;
}

lumo_status lumo_net_client_next(lumo_net_client *c, uint8_t *out, size_t cap, size_t *written)
{
    uint32_t mesh = 0, turn;
    int channel;
    lumo_status st;

    if (!c || !out || !written)
        return LUMO_ERR_ARG;
    *written = 0;
    if (c->state == LUMO_NET_FAILED)
        return c->error;
    turn = c->turn;
    if (c->state != LUMO_NET_READY)   /* waiting for WELCOME, or done: nothing to send */
        return c->state == LUMO_NET_DONE || c->state == LUMO_NET_HELLO_SENT ? LUMO_OK : LUMO_ERR_STATE;
    if (c->npending == 0 && all_held(c)) {
        if (!c->cfg.replay && (st = lumo_net_bye_encode(out, cap, written)))
            return st;
        c->state = LUMO_NET_DONE;
        return LUMO_OK;
    }
    if (c->cfg.replay)
        return LUMO_OK;   /* a recording answers what was asked when it was made */
    if ((c->npending >= (first_picture_asked(c) ? c->cfg.policy.pipeline : MAX_PIPELINE) &&
         !(c->npending < MAX_PIPELINE && link_idles(c))) ||
        (channel = pick(c, &mesh)) < 0)
        return LUMO_OK;
    if ((st = send_request(c, channel, mesh, out, cap, written))) {
        c->turn = turn;
        return st;
    }
    c->pending[c->npending - 1].turn = turn;
    return LUMO_OK;
}

/* ---- lossy links ------------------------------------------------------------------ */

int lumo_net_client_expects(const lumo_net_client *c, const lumo_net_frame *f)
{
    lumo_net_data d;
    lumo_net_end e;

    if (!c || !f || c->state == LUMO_NET_FAILED)
        return 0;
    switch (f->type) {
    case LUMO_NET_ERROR:
        return 1;
    case LUMO_NET_WELCOME:
        return c->state == LUMO_NET_HELLO_SENT;
    case LUMO_NET_DATA:
        return c->state == LUMO_NET_READY && lumo_net_data_decode(f, &d) == LUMO_OK && check_data(c, &d) == LUMO_OK;
    case LUMO_NET_END:
        return c->state == LUMO_NET_READY && lumo_net_end_decode(f, &e) == LUMO_OK && check_end(c, &e) == LUMO_OK;
    default:
        return 0;
    }
}

lumo_status lumo_net_client_resync(lumo_net_client *c, uint8_t *out, size_t cap, size_t *written)
{
    lumo_net_request r;
    lumo_net_pending *p;
    lumo_status st;
    int hello;

    if (!c || !out || !written)
        return LUMO_ERR_ARG;
    *written = 0;
    if (c->state == LUMO_NET_FAILED)
        return c->error;
    if (c->state == LUMO_NET_DONE)
        return LUMO_OK;
    hello = c->state != LUMO_NET_READY;   /* WELCOME lost (or nothing sent yet) */
    lumo_net_client_reset_link(c);
    if (hello)
        return lumo_net_client_hello(c, out, cap, written);
    memset(&r, 0, sizeof r);
    r.amount = 1;
    if (c->mesh_count) {
        r.channel = LUMO_NET_GEOMETRY, r.cursor = c->batches[0];
    } else if (c->has_ivg) {
        r.channel = LUMO_NET_LIGHTING, r.cursor = c->rounds_total;
    } else {
        return LUMO_OK;   /* nothing is streamed: nothing can be stale */
    }
    if ((st = lumo_net_request_encode(&r, out, cap, written)))
        return st;
    p = &c->pending[0];
    p->channel = r.channel, p->mesh = 0, p->cursor = p->end = r.cursor, p->sent_ms = now_ms(c);
    p->turn = c->turn;
    c->npending = 1;
    c->data_bytes = 0;
    return LUMO_OK;
}

void lumo_net_client_progress(const lumo_net_client *c, lumo_net_progress *out)
{
    lumo_session_progress p;
    uint32_t m;

    memset(out, 0, sizeof *out);
    for (m = 0; m < c->mesh_count; m++)
        if (lumo_session_mesh_progress(c->session, m, &p) == LUMO_OK) {
            out->vertices += p.vertices;
            out->full_vertices += p.full_vertices;
        }
    out->rounds = c->rounds_held;
    out->full_rounds = c->rounds_total;
    out->bytes = c->bytes_in;
    out->done = c->state == LUMO_NET_DONE;
}
