/*
 * test_net_client.c — the client's protocol driver (lumo/net_client.h)
 * against an in-process fake server built from the real pieces
 * (tests/include/test_net_fake.h: the package opened and walked by the SDK,
 * answers planned by brute force from docs/protocol.md §2). Packages:
 *
 *   stream  tests/fuzz/seeds/fuzz_package/stream.lumo (7 meshes of 2 batches,
 *           the last one short; a 4x3x4 IVG in 13 rounds; ORDR)
 *   mixed   the same with meshes 0..2 replaced by the streams of
 *           tests/fuzz/seeds/fuzz_pmesh/ (17, 42 and 7 batches, each with a
 *           short last batch)
 *   split   baked here by lumo-bake (a 32x4x4 grid: a round of 32 binary32
 *           records does not fit a 4 KiB frame and is split; a sphere of 6
 *           batches)
 *
 * Every order, pipeline depth 1..8, fixed and adaptive request sizes (with
 * and without a clock), both IVG forms and small and large frames reach the
 * full scene, and the session then holds what lumo_session_feed_package (or
 * the binary32 bundle fed whole) gives: meshes and grid byte for byte.
 * Every request's predicted end is the server's plan (the regression of a
 * short last batch counted as a full one), resuming after cuts re-sends
 * nothing held, and hostile frames (wrong channel, wrong first, counts past
 * the end, DATA before WELCOME, WELCOME twice, END out of turn, records the
 * session refuses, ERROR) each give a lumo_status while the session keeps
 * its state and still draws.
 *
 * With LUMO_NET_CLIENT_SEEDS=DIR set, the conversations on the stream
 * package are written to DIR as seeds of tests/fuzz/fuzz_net_client.c.
 */
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>
#include "test_common.h"
#include "lumo/net_client.h"
#include "test_net_fake.h"
#include "test_ivg_entry.h"

#define STREAM_PKG "tests/fuzz/seeds/fuzz_package/stream.lumo"
#define PMESH_DIR  "tests/fuzz/seeds/fuzz_pmesh/"
#define FRAME_CAP  ((size_t)(1u << 20) + LUMO_NET_OVERHEAD)
#define ARENA      ((size_t)8 << 20)

enum { PKG_STREAM, PKG_MIXED, PKG_SPLIT, PKG_COUNT };
static const char *const pkg_names[PKG_COUNT] = {"stream", "mixed", "split"};
static fake_pkg g_pkg[PKG_COUNT];
static const char *g_argv0 = "build/tests/bin/test_net_client";

/* ---- packages ---------------------------------------------------------------- */

static uint8_t *read_file(const char *path, size_t *size)
{
    FILE *f = fopen(path, "rb");
    uint8_t *b;
    long n;

    if (!f)
        return NULL;
    fseek(f, 0, SEEK_END);
    n = ftell(f);
    fseek(f, 0, SEEK_SET);
    b = malloc((size_t)n);
    if (!b || fread(b, 1, (size_t)n, f) != (size_t)n) {
        free(b);
        b = NULL;
    }
    fclose(f);
    *size = (size_t)n;
    return b;
}

/* A package with the chunks of `src`, the PMSH chunks of meshes 0..2
 * replaced by whole streams from files (header, table and CRCs rebuilt). */
static uint8_t *repack(const lumo_package *src, const char *const streams[3], size_t *size)
{
    const uint8_t *payload[LUMO_PKG_MAX_CHUNKS];
    uint8_t *own[3] = {NULL, NULL, NULL}, *out;
    uint32_t len[LUMO_PKG_MAX_CHUNKS], type[LUMO_PKG_MAX_CHUNKS], n = src->chunk_count, i, pm = 0;
    size_t pos = LUMO_PKG_HEADER_SIZE + (size_t)n * LUMO_PKG_ENTRY_SIZE, total;

    for (i = 0; i < n; i++) {
        lumo_pkg_chunk c;
        assert_int_equal(lumo_package_chunk(src, i, &c), LUMO_OK);
        type[i] = c.type, payload[i] = src->data + c.offset, len[i] = c.length;
        if (c.type == LUMO_PKG_PMSH && pm < 3) {
            size_t sz;
            char path[256];
            snprintf(path, sizeof path, PMESH_DIR "%s", streams[pm]);
            assert_non_null(own[pm] = read_file(path, &sz));
            payload[i] = own[pm], len[i] = (uint32_t)sz;
            pm++;
        }
    }
    total = pos;
    for (i = 0; i < n; i++)
        total = ((total + 3) & ~(size_t)3) + len[i];
    assert_non_null(out = calloc(1, total));
    memcpy(out, "LUMO", 4);
    lumo_wire_put_le16(out + 4, LUMO_PKG_VERSION_MAJOR);
    lumo_wire_put_le16(out + 6, LUMO_PKG_VERSION_MINOR);
    lumo_wire_put_le32(out + 8, n);
    for (i = 0; i < n; i++) {
        uint8_t *e = out + LUMO_PKG_HEADER_SIZE + (size_t)i * LUMO_PKG_ENTRY_SIZE;
        pos = (pos + 3) & ~(size_t)3;
        lumo_wire_put_le32(e, type[i]);
        lumo_wire_put_le32(e + 4, (uint32_t)pos);
        lumo_wire_put_le32(e + 8, len[i]);
        lumo_wire_put_le32(e + 12, lumo_wire_crc32(0, payload[i], len[i]));
        memcpy(out + pos, payload[i], len[i]);
        pos += len[i];
    }
    lumo_wire_put_le32(out + 16, lumo_wire_crc32(0, out + LUMO_PKG_HEADER_SIZE, (size_t)n * LUMO_PKG_ENTRY_SIZE));
    lumo_wire_put_le32(out + 20, lumo_wire_crc32(0, out, 20));
    for (i = 0; i < 3; i++)
        free(own[i]);
    *size = total;
    return out;
}

/* lumo-bake beside this binary: BUILD/tests/bin/.. -> BUILD/bin/lumo-bake. */
static int bake_split(const char *out)
{
    char bin[1024], cmd[2048];
    const char *slash = strrchr(g_argv0, '/');
    int n = slash ? (int)(slash - g_argv0) : 1;

    snprintf(bin, sizeof bin, "%.*s/../../bin/lumo-bake", n, slash ? g_argv0 : ".");
    if (access(bin, X_OK) != 0) {
        fprintf(stderr, "test_net_client: %s not found (make builds it before the tests)\n", bin);
        return -1;
    }
    snprintf(cmd, sizeof cmd,
             "'%s' --default --dragon sphere --grid 32,4,4 --spp 2 --threads 1 --no-progress -o '%s' "
             "2>/dev/null", bin, out);
    return system(cmd) == 0 ? 0 : -1;
}

static int group_setup(void **state)
{
    static const char *const streams[3] = {"grid.lpm", "seam_albedo.lpm", "tiny_predicted.lpm"};
    char dir[] = "/tmp/test_net_client.XXXXXX", path[64];
    uint8_t *mixed;
    size_t size;
    int rc = 0;
    (void)state;

    if (fake_pkg_load(&g_pkg[PKG_STREAM], STREAM_PKG) != LUMO_OK)
        return -1;
    mixed = repack(&g_pkg[PKG_STREAM].pkg, streams, &size);
    if (fake_pkg_open(&g_pkg[PKG_MIXED], mixed, size) != LUMO_OK)
        return -1;
    if (!mkdtemp(dir))
        return -1;
    snprintf(path, sizeof path, "%s/split.lumo", dir);
    if (bake_split(path) || fake_pkg_load(&g_pkg[PKG_SPLIT], path) != LUMO_OK)
        rc = -1;
    unlink(path);
    rmdir(dir);
    return rc;
}

static int group_teardown(void **state)
{
    int i;
    (void)state;
    for (i = 0; i < PKG_COUNT; i++)
        fake_pkg_free(&g_pkg[i]);
    return 0;
}

/* What the packages must be for the runs to mean what they say. */
static void test_packages(void **state)
{
    const fake_pkg *mx = &g_pkg[PKG_MIXED], *sp = &g_pkg[PKG_SPLIT];
    uint32_t m, short_last = 0;
    (void)state;
    for (m = 0; m < mx->meshes; m++) {
        const lumo_pmesh_header *h = &mx->mesh[m].h;
        if (fake_batch_vertices(h, h->batch_count - 1) < h->batch_vertices)
            short_last++;
    }
    assert_int_equal(short_last, mx->meshes);   /* every stream ends with a short batch */
    assert_int_equal(mx->mesh[0].h.batch_count, 17);
    assert_int_equal(mx->mesh[1].h.batch_count, 42);
    assert_true(sp->has_ivg && sp->order.slices == 32);
    /* a round of 32 binary32 records does not fit a 4 KiB frame */
    assert_true(lumo_ivg_order_offset(&sp->order, LUMO_IVG_FORM_FLOAT, 2) -
                    lumo_ivg_order_offset(&sp->order, LUMO_IVG_FORM_FLOAT, 1) >
                LUMO_NET_MIN_PAYLOAD - LUMO_NET_DATA_HEAD);
}

/* ---- the reference: the package fed whole ------------------------------------- */

typedef struct world {
    lumo_session s;
    lumo_arena a;
    uint8_t *mem;
    lumo_net_client c;
} world;

static void world_init(world *w, size_t arena)
{
    memset(w, 0, sizeof *w);
    assert_non_null(w->mem = malloc(arena));
    lumo_arena_init(&w->a, w->mem, arena);
    assert_int_equal(lumo_session_init(&w->s, NULL, &w->a), LUMO_OK);
}

static void world_free(world *w)
{
    free(w->mem);
    w->mem = NULL;
}

/* The session lumo_session_feed_package gives (quantized), or the same
 * with the binary32 bundle. */
static void reference(world *w, const fake_pkg *k, uint8_t form)
{
    const uint8_t *d;
    uint32_t len, m;
    static const uint32_t order[] = {LUMO_PKG_INFO, LUMO_PKG_IVGD, LUMO_PKG_IVGS, LUMO_PKG_ORDR, LUMO_PKG_IVGF};
    size_t i;

    world_init(w, ARENA);
    if (form == LUMO_IVG_FORM_QUANTIZED) {
        assert_int_equal(lumo_session_feed_package(&w->s, &k->pkg, NULL), LUMO_OK);
    } else {
        for (i = 0; i < sizeof order / sizeof order[0]; i++)
            if (lumo_package_find(&k->pkg, order[i], 0, &d, &len) == LUMO_OK)
                assert_int_equal(lumo_session_feed(&w->s, order[i], 0, d, len), LUMO_OK);
        for (m = 0; m < k->meshes; m++)
            assert_int_equal(lumo_session_feed(&w->s, LUMO_MSG_PMSH, m, k->mesh[m].stream, k->mesh[m].len),
                             LUMO_OK);
    }
    lumo_session_update(&w->s);
}

static void same_meshes(const lumo_session *a, const lumo_session *b, uint32_t meshes)
{
    uint32_t m;

    for (m = 0; m < meshes; m++) {
        lumo_pmesh_view va, vb;
        assert_int_equal(lumo_session_mesh(a, m, &va), LUMO_OK);
        assert_int_equal(lumo_session_mesh(b, m, &vb), LUMO_OK);
        assert_int_equal(va.vertex_count, vb.vertex_count);
        assert_int_equal(va.face_count, vb.face_count);
        assert_memory_equal(va.positions, vb.positions, 3 * sizeof *va.positions * va.vertex_count);
        assert_memory_equal(va.normals, vb.normals, 3 * sizeof *va.normals * va.vertex_count);
        assert_memory_equal(va.triangles, vb.triangles, 3 * sizeof *va.triangles * va.face_count);
        assert_true(!va.albedo == !vb.albedo);
        if (va.albedo)
            assert_memory_equal(va.albedo, vb.albedo, 3 * sizeof *va.albedo * va.vertex_count);
    }
}

static void same_grid(const lumo_session *a, const lumo_session *b)
{
    const lumo_ivg *ga = lumo_session_ivg(a), *gb = lumo_session_ivg(b);
    uint32_t v, x;

    assert_true(!ga == !gb);
    if (!ga)
        return;
    assert_int_equal(lumo_ivg_vertex_count(ga), lumo_ivg_vertex_count(gb));
    assert_int_equal(lumo_ivg_received_count(ga), lumo_ivg_received_count(gb));
    for (v = 0; v < lumo_ivg_vertex_count(ga); v++) {
        assert_int_equal(lumo_ivg_is_received(ga, v), lumo_ivg_is_received(gb, v));
        assert_int_equal(lumo_ivg_is_solid(ga, v), lumo_ivg_is_solid(gb, v));
        for (x = 0; x < LUMO_IVG_AXES; x++)
            assert_memory_equal(IVG_ENTRY(ga, v, (lumo_ivg_axis)x),
                                IVG_ENTRY(gb, v, (lumo_ivg_axis)x), sizeof(lumo_ivg_entry));
    }
}

/* Every mesh's PRT held whole and equal (the streamed spans against the
 * package's chunks). */
static void same_prt(const lumo_session *a, const lumo_session *b, uint32_t meshes)
{
    uint32_t m;

    for (m = 0; m < meshes; m++) {
        lumo_prt pa, pb;
        uint32_t ha, sa, hb, sb;
        lumo_session_prt_progress(a, m, &ha, &sa);
        lumo_session_prt_progress(b, m, &hb, &sb);
        assert_int_equal(ha, sa);
        assert_int_equal(ha, hb);
        assert_int_equal(sa, sb);
        assert_int_equal(lumo_session_prt(a, m, &pa), LUMO_OK);
        assert_int_equal(lumo_session_prt(b, m, &pb), LUMO_OK);
        assert_int_equal(pa.vertices_held, pb.vertices_held);
        assert_memory_equal(pa.cluster_data, pb.cluster_data, ha - LUMO_PRT_HEADER_SIZE);
    }
}

/* ---- driving the driver ---------------------------------------------------------- */

typedef struct run_cfg {
    int pkg;
    uint8_t form;
    uint32_t max_payload;
    lumo_net_policy policy;
    int clock;          /* the fake clock (adaptive sizes measure it) */
    uint64_t seed;      /* interleaving of sends and receipts */
    uint32_t cuts;      /* connections cut at random frames, resumed */
    int prt;            /* ask for PRT (HELLO flag, docs/protocol.md §10) */
    const fake_pkg *k;  /* the package (NULL: g_pkg[pkg]) */
} run_cfg;

typedef struct run_stats {
    uint32_t requests, frames, resumes;
    uint64_t data_bytes;       /* DATA payload bytes delivered */
    uint64_t applied_before;   /* of those, bytes that arrived on a cut connection */
} run_stats;

static uint8_t *g_frame;      /* FRAME_CAP */
static uint32_t g_now;
static FILE *g_seed_file;     /* LUMO_NET_CLIENT_SEEDS: the frames after WELCOME */

static uint32_t fake_clock(void *ctx)
{
    (void)ctx;
    return g_now += 1;
}

static void driver_init(world *w, const run_cfg *r)
{
    lumo_net_client_config cfg;

    memset(&cfg, 0, sizeof cfg);
    cfg.arena_bytes = (uint32_t)ARENA;
    cfg.max_payload = r->max_payload;
    cfg.width = 320, cfg.height = 240;
    cfg.ivg_form = r->form;
    cfg.smoothing = 1;
    cfg.policy = r->policy;
    cfg.clock = r->clock ? fake_clock : NULL;
    cfg.prt = (uint8_t)r->prt;
    world_init(w, ARENA);
    assert_int_equal(lumo_net_client_init(&w->c, &w->s, &cfg), LUMO_OK);
}

static lumo_status deliver(world *w, const uint8_t *buf, size_t n)
{
    lumo_net_frame f;
    size_t used = 0;

    assert_int_equal(lumo_net_frame_decode(buf, n, w->c.cfg.max_payload, &f, &used), LUMO_OK);
    assert_int_equal(used, n);
    g_now += 1 + (uint32_t)(n >> 10);   /* a link of about 1 MB/s */
    return lumo_net_client_on_frame(&w->c, &f);
}

/* HELLO out, its fields checked (resuming: the cursors held), WELCOME in. */
static void connect_to(world *w, fake_server *srv, const fake_pkg *k)
{
    lumo_net_frame f;
    lumo_net_hello h;
    uint8_t out[512];
    size_t n = 0, used;
    uint32_t m;

    assert_int_equal(lumo_net_client_hello(&w->c, out, sizeof out, &n), LUMO_OK);
    assert_int_equal(lumo_net_frame_decode(out, n, LUMO_NET_MAX_PAYLOAD, &f, &used), LUMO_OK);
    assert_int_equal(lumo_net_hello_decode(&f, &h), LUMO_OK);
    assert_int_equal(h.max_payload, w->c.cfg.max_payload);
    assert_int_equal(h.ivg_form, w->c.cfg.ivg_form);
    if (h.resume_id) {
        assert_int_equal(h.resume_id, k->id);
        assert_int_equal(h.mesh_count, k->meshes);
        for (m = 0; m < k->meshes; m++)
            assert_int_equal(lumo_net_hello_cursor(&h, m), w->c.held[m]);
    }
    fake_server_init(srv, k, h.ivg_form, h.max_payload);
    srv->prt = (h.flags & LUMO_NET_FLAG_PRT) && k->has_prt;
    if (srv->prt)
        assert_int_equal(deliver(w, k->welcome_prt, k->welcome_prt_len), LUMO_OK);
    else
        assert_int_equal(deliver(w, k->welcome, k->welcome_len), LUMO_OK);
    assert_int_equal(w->c.state, LUMO_NET_READY);
}

/* Every frame the driver wants to send: REQUESTs to the server, each
 * predicted end checked against the server's plan. 1 once BYE is out. */
static int send_all(world *w, fake_server *srv, run_stats *st)
{
    uint8_t out[256];
    size_t n, used;

    for (;;) {
        lumo_net_frame f;
        lumo_net_request r;
        const lumo_net_pending *p;
        uint32_t plan;
        assert_int_equal(lumo_net_client_next(&w->c, out, sizeof out, &n), LUMO_OK);
        if (n == 0)
            return w->c.state == LUMO_NET_DONE;
        assert_int_equal(lumo_net_frame_decode(out, n, LUMO_NET_MAX_PAYLOAD, &f, &used), LUMO_OK);
        if (f.type == LUMO_NET_BYE) {
            assert_int_equal(w->c.state, LUMO_NET_DONE);
            return 1;
        }
        assert_int_equal(f.type, LUMO_NET_REQUEST);
        assert_int_equal(lumo_net_request_decode(&f, &r), LUMO_OK);
        assert_true(w->c.npending >= 1 && w->c.npending <= 8);
        p = &w->c.pending[w->c.npending - 1];
        assert_int_equal(p->channel, r.channel);
        assert_int_equal(p->cursor, r.cursor);
        plan = r.channel == LUMO_NET_GEOMETRY ? fake_geometry_end(&srv->k->mesh[r.mesh].h, r.cursor, r.amount)
             : r.channel == LUMO_NET_PRT      ? fake_prt_end(srv->k, r.mesh, r.cursor, r.amount)
                                              : fake_rounds_end(srv->k, r.cursor, r.amount);
        if (p->end != plan)
            fail_msg("%s request mesh %u cursor %u amount %u: the driver predicts end %u, the server sends "
                     "up to %u", r.channel ? "lighting" : "geometry", r.mesh, r.cursor, r.amount, p->end, plan);
        assert_int_equal(fake_server_request(srv, &r), LUMO_OK);
        st->requests++;
    }
}

/* A whole conversation (with r->cuts connections cut at random frames and
 * resumed); the session must end equal to the reference. */
static void run(const run_cfg *r, const world *ref, run_stats *st)
{
    static world w;
    fake_server srv;
    test_rng rng = {r->seed * 2654435761u + 1};
    const fake_pkg *k = r->k ? r->k : &g_pkg[r->pkg];
    uint32_t steps, cuts = 0, resumes = 0;
    uint64_t cut_at = 0;

    memset(st, 0, sizeof *st);
    driver_init(&w, r);
    connect_to(&w, &srv, k);
    if (r->cuts)
        cut_at = 1 + test_rng_next(&rng) % 12;
    for (steps = 0; steps < 200000; steps++) {
        uint32_t burst, i;
        size_t n;
        int cut = 0;
        if (send_all(&w, &srv, st))
            break;
        burst = 1 + (uint32_t)(test_rng_next(&rng) % 3);
        for (i = 0; i < burst && fake_server_frame(&srv, g_frame, FRAME_CAP, &n); i++) {
            lumo_status s = deliver(&w, g_frame, n);
            if (s)
                fail_msg("%s frame %u: %s", pkg_names[r->pkg], st->frames, lumo_strerror(s));
            if (g_seed_file && !cuts)
                fwrite(g_frame, 1, n, g_seed_file);
            st->frames++;
            st->data_bytes += n - LUMO_NET_OVERHEAD;
            if (cuts < r->cuts && st->frames == cut_at) {
                /* the link drops: what was asked and not received is lost */
                lumo_net_client_reset_link(&w.c);
                assert_int_equal(w.c.npending, 0);
                connect_to(&w, &srv, k);
                cuts++, resumes++;
                cut_at = st->frames + 1 + test_rng_next(&rng) % 12;
                cut = 1;
                break;
            }
        }
        if (i == 0 && !cut)
            fail_msg("%s: nothing to send and nothing to receive (%u requests in flight)", pkg_names[r->pkg],
                     w.c.npending);
    }
    assert_int_equal(w.c.state, LUMO_NET_DONE);
    st->resumes = resumes;
    {
        lumo_net_progress p;
        lumo_net_client_progress(&w.c, &p);
        assert_true(p.done);
        assert_int_equal(p.vertices, p.full_vertices);
        assert_int_equal(p.rounds, p.full_rounds);
    }
    lumo_session_update(&w.s);
    same_meshes(&w.s, &ref->s, k->meshes);
    same_grid(&w.s, &ref->s);
    if (r->prt)
        same_prt(&w.s, &ref->s, k->meshes);
    world_free(&w);
}

static const char *const order_names[] = {"interleaved", "geometry", "lighting"};

/* Every order x pipeline 1..8 x fixed / adaptive (with and without a clock)
 * x form x frame size on one package. */
static void all_policies(int pkg)
{
    static const uint32_t vertices[] = {1, 7, 40, 250, 100000};
    static const uint32_t rounds[] = {1, 2, 5, 1000};
    static const uint32_t payloads[] = {LUMO_NET_MIN_PAYLOAD, 1u << 20};
    static world ref[2];
    const char *dir = getenv("LUMO_NET_CLIENT_SEEDS");
    uint32_t form, order, pipe, sizes, pl, runs = 0;
    uint64_t frames = 0;

    for (form = 0; form < 2; form++)
        reference(&ref[form], &g_pkg[pkg], (uint8_t)form);
    for (form = 0; form < 2; form++)
        for (order = 0; order < 3; order++)
            for (pipe = 1; pipe <= 8; pipe++)
                for (sizes = 0; sizes < 3; sizes++)
                    for (pl = 0; pl < 2; pl++) {
                        run_cfg r;
                        run_stats st;
                        memset(&r, 0, sizeof r);
                        r.pkg = pkg, r.form = (uint8_t)form, r.max_payload = payloads[pl];
                        r.policy.order = (lumo_net_order)order;
                        r.policy.pipeline = pipe;
                        if (sizes == 0) {   /* fixed */
                            r.policy.vertices = vertices[(pipe + order) % 5];
                            r.policy.rounds = rounds[(pipe + form) % 4];
                        }
                        r.clock = sizes == 1;   /* adaptive measured, or adaptive doubling */
                        r.seed = runs;
                        if (dir && pkg == PKG_STREAM && sizes == 0 && pl == 0) {
                            /* the fuzz target's input: config, size, flags, frames */
                            char path[512];
                            uint8_t head[3];
                            snprintf(path, sizeof path, "%s/%s-%s-p%u", dir, order_names[order],
                                     form ? "quantized" : "float", pipe);
                            g_seed_file = fopen(path, "wb");
                            head[0] = (uint8_t)(order | (pipe - 1) << 2 | (form ? 0 : 1u << 5) | 1u << 6);
                            head[1] = (uint8_t)((pipe + order) % 5);
                            head[2] = (uint8_t)((pipe + form) % 4);
                            if (g_seed_file)
                                fwrite(head, 1, 3, g_seed_file);
                        }
                        run(&r, &ref[form], &st);
                        if (g_seed_file)
                            fclose(g_seed_file);
                        g_seed_file = NULL;
                        frames += st.frames;
                        runs++;
                    }
    print_message("%s: %u runs to the full scene, %llu frames\n", pkg_names[pkg], runs,
                  (unsigned long long)frames);
    for (form = 0; form < 2; form++)
        world_free(&ref[form]);
}

static void test_policies_stream(void **state)
{
    (void)state;
    all_policies(PKG_STREAM);
}

static void test_policies_mixed(void **state)
{
    (void)state;
    all_policies(PKG_MIXED);
}

static void test_policies_split(void **state)
{
    (void)state;
    all_policies(PKG_SPLIT);
}

/* The regression of 65e3ce1: a client that counted a short last batch as a
 * full one predicted fewer batches than the server sends, and its next
 * pipelined request failed with STATE. Every fixed amount from 1 to past
 * two batches, pipeline 8, every predicted end checked against the plan. */
static void test_short_last_batch(void **state)
{
    static world ref;
    uint32_t amount, runs = 0;
    (void)state;

    reference(&ref, &g_pkg[PKG_MIXED], LUMO_IVG_FORM_QUANTIZED);
    for (amount = 1; amount <= 2 * 40 + 25; amount++) {
        run_cfg r;
        run_stats st;
        memset(&r, 0, sizeof r);
        r.pkg = PKG_MIXED, r.form = LUMO_IVG_FORM_QUANTIZED, r.max_payload = 1u << 20;
        r.policy.order = LUMO_NET_ORDER_GEOMETRY_FIRST;
        r.policy.pipeline = 8;
        r.policy.vertices = amount;
        r.policy.rounds = 3;
        r.seed = amount;
        run(&r, &ref, &st);
        runs++;
    }
    /* and the plan itself, every cursor and amount of every stream */
    {
        uint32_t p, m, c, a;
        for (p = 0; p < PKG_COUNT; p++)
            for (m = 0; m < g_pkg[p].meshes; m++) {
                const lumo_pmesh_header *h = &g_pkg[p].mesh[m].h;
                for (c = 0; c < h->batch_count; c++)
                    for (a = 1; a <= 3 * h->batch_vertices + 3 && a <= h->vertices + 2; a++)
                        assert_int_equal(lumo_net_geometry_end(h, c, a), fake_geometry_end(h, c, a));
            }
    }
    print_message("short last batch: %u runs at pipeline 8, every predicted end = the server's plan\n", runs);
    world_free(&ref);
}

/* Cut after random frames (inside multi-frame answers and split rounds),
 * reset_link and HELLO with the cursors held: the scene completes, equal
 * to the reference, and no DATA carries a record held before the cut (the
 * driver refuses a DATA whose first is not its cursor). */
static void test_resume(void **state)
{
    static world ref[2];
    uint32_t p, form, i, resumes = 0;
    (void)state;

    for (p = 0; p < PKG_COUNT; p++) {
        for (form = 0; form < 2; form++)
            reference(&ref[form], &g_pkg[p], (uint8_t)form);
        for (i = 0; i < 12; i++) {
            run_cfg r;
            run_stats st;
            memset(&r, 0, sizeof r);
            r.pkg = (int)p, form = i & 1, r.form = (uint8_t)form;
            r.max_payload = i & 2 ? LUMO_NET_MIN_PAYLOAD : 1u << 20;
            r.policy.order = (lumo_net_order)(i % 3);
            r.policy.pipeline = 1 + i % 8;
            r.policy.vertices = i & 4 ? 0 : 60;
            r.policy.rounds = i & 4 ? 0 : 2;
            r.clock = 1;
            r.seed = 100 + i;
            r.cuts = 5;
            run(&r, &ref[form], &st);
            resumes += st.resumes;
        }
        for (form = 0; form < 2; form++)
            world_free(&ref[form]);
    }
    assert_true(resumes > 0);
    print_message("resume: %u cuts, every run to the full scene\n", resumes);
}

/* PRT (docs/protocol.md §10) on the committed PRT package: every order,
 * pipelines, fixed and adaptive sizes, frames of 4 KiB (spans cut inside
 * records) and 1 MiB, cut and resumed: each mesh's PRTV ends whole and
 * equal to the package's, the geometry and grid as without PRT; a client
 * that does not ask gets the plain WELCOME (its arena need smaller). */
static void test_prt(void **state)
{
    static fake_pkg k;
    static world ref;
    uint32_t i, resumes = 0;
    (void)state;
    assert_int_equal(fake_pkg_load(&k, "tests/fuzz/seeds/fuzz_package/prt.lumo"), LUMO_OK);
    assert_true(k.has_prt && k.need_prt > k.need);
    reference(&ref, &k, LUMO_IVG_FORM_QUANTIZED);
    for (i = 0; i < 16; i++) {
        run_cfg r;
        run_stats st;
        memset(&r, 0, sizeof r);
        r.k = &k, r.prt = 1;
        r.form = LUMO_IVG_FORM_QUANTIZED;
        r.max_payload = i & 1 ? LUMO_NET_MIN_PAYLOAD : 1u << 20;
        r.policy.order = (lumo_net_order)(i % 3);
        r.policy.pipeline = 1 + i % 8;
        r.policy.vertices = i & 2 ? 0 : 7;
        r.policy.rounds = i & 2 ? 0 : 1;
        r.clock = (i & 4) != 0;
        r.seed = 300 + i;
        r.cuts = i & 8 ? 6 : 0;
        run(&r, &ref, &st);
        resumes += st.resumes;
    }
    assert_true(resumes > 0);
    world_free(&ref);
    fake_pkg_free(&k);
    print_message("prt: 16 runs, %u cuts resumed, every PRTV whole\n", resumes);
}

/* ---- hostile frames ------------------------------------------------------------- */

/* What a renderer would read, copied, to prove nothing changed. */
typedef struct snapshot {
    uint32_t meshes, vertices[LUMO_MAX_MESHES], faces[LUMO_MAX_MESHES];
    uint8_t *mesh_bytes[LUMO_MAX_MESHES];
    size_t mesh_len[LUMO_MAX_MESHES];
    uint8_t *grid;
    size_t grid_len;
    uint32_t received;
} snapshot;

static void snap_take(snapshot *s, const lumo_session *ses, uint32_t meshes)
{
    const lumo_ivg *g = lumo_session_ivg(ses);
    uint32_t m, v, x;

    memset(s, 0, sizeof *s);
    s->meshes = meshes;
    for (m = 0; m < meshes; m++) {
        lumo_pmesh_view vw;
        size_t at = 0;
        if (lumo_session_mesh(ses, m, &vw) != LUMO_OK)
            continue;
        s->vertices[m] = vw.vertex_count, s->faces[m] = vw.face_count;
        s->mesh_len[m] = vw.vertex_count * 3 * (sizeof *vw.positions + sizeof *vw.normals) +
                         vw.face_count * 3 * sizeof *vw.triangles;
        assert_non_null(s->mesh_bytes[m] = malloc(s->mesh_len[m] + 1));
        memcpy(s->mesh_bytes[m] + at, vw.positions, vw.vertex_count * 3 * sizeof *vw.positions);
        at += vw.vertex_count * 3 * sizeof *vw.positions;
        memcpy(s->mesh_bytes[m] + at, vw.normals, vw.vertex_count * 3 * sizeof *vw.normals);
        at += vw.vertex_count * 3 * sizeof *vw.normals;
        memcpy(s->mesh_bytes[m] + at, vw.triangles, vw.face_count * 3 * sizeof *vw.triangles);
    }
    if (g) {
        s->received = lumo_ivg_received_count(g);
        s->grid_len = (size_t)lumo_ivg_vertex_count(g) * LUMO_IVG_AXES * sizeof(lumo_ivg_entry);
        assert_non_null(s->grid = malloc(s->grid_len));
        for (v = 0; v < lumo_ivg_vertex_count(g); v++)
            for (x = 0; x < LUMO_IVG_AXES; x++)
                memcpy(s->grid + ((size_t)v * LUMO_IVG_AXES + x) * sizeof(lumo_ivg_entry),
                       IVG_ENTRY(g, v, (lumo_ivg_axis)x), sizeof(lumo_ivg_entry));
    }
}

/* The session as the snapshot says, and drawable: every mesh's view, every
 * triangle's indices below its vertex count. */
static void snap_same(snapshot *s, const lumo_session *ses)
{
    snapshot now;
    uint32_t m, i;

    snap_take(&now, ses, s->meshes);
    for (m = 0; m < s->meshes; m++) {
        lumo_pmesh_view vw;
        assert_int_equal(now.vertices[m], s->vertices[m]);
        assert_int_equal(now.faces[m], s->faces[m]);
        assert_int_equal(now.mesh_len[m], s->mesh_len[m]);
        if (s->mesh_len[m])
            assert_memory_equal(now.mesh_bytes[m], s->mesh_bytes[m], s->mesh_len[m]);
        if (lumo_session_mesh(ses, m, &vw) == LUMO_OK)
            for (i = 0; i < 3 * vw.face_count; i++)
                assert_true(vw.triangles[i] < vw.vertex_count);
        free(now.mesh_bytes[m]);
        free(s->mesh_bytes[m]);
    }
    assert_int_equal(now.received, s->received);
    assert_int_equal(now.grid_len, s->grid_len);
    if (s->grid_len)
        assert_memory_equal(now.grid, s->grid, s->grid_len);
    free(now.grid);
    free(s->grid);
}

typedef struct hostile {
    world w;
    fake_server srv;
    run_stats st;
    lumo_net_frame next;   /* the server's next frame, decoded (in g_frame) */
    lumo_net_data d;       /* ... when it is DATA */
    size_t next_len;
} hostile;

/* A driver in the middle of a conversation: `frames` frames applied, the
 * server's next frame decoded in h->next (and h->d). */
static void hostile_start(hostile *h, int pkg, uint8_t form, uint32_t frames, uint32_t pipeline)
{
    run_cfg r;
    size_t used;
    uint32_t i;

    memset(&r, 0, sizeof r);
    r.pkg = pkg, r.form = form, r.max_payload = 1u << 20;
    r.policy.pipeline = pipeline;
    r.policy.vertices = 100;
    r.policy.rounds = 2;
    memset(&h->st, 0, sizeof h->st);
    driver_init(&h->w, &r);
    connect_to(&h->w, &h->srv, &g_pkg[pkg]);
    for (i = 0; i <= frames; i++) {
        assert_int_equal(send_all(&h->w, &h->srv, &h->st), 0);
        assert_true(fake_server_frame(&h->srv, g_frame, FRAME_CAP, &h->next_len));
        if (i < frames)
            assert_int_equal(deliver(&h->w, g_frame, h->next_len), LUMO_OK);
    }
    assert_int_equal(lumo_net_frame_decode(g_frame, h->next_len, LUMO_NET_MAX_PAYLOAD, &h->next, &used), LUMO_OK);
    memset(&h->d, 0, sizeof h->d);
    if (h->next.type == LUMO_NET_DATA)
        assert_int_equal(lumo_net_data_decode(&h->next, &h->d), LUMO_OK);
}

/* Feed a crafted frame: the status must be `want` (any error when
 * LUMO_OK is passed as "some error"), the session unchanged and drawable,
 * the driver failed for good. */
static void hostile_expect(hostile *h, const uint8_t *frame, size_t n, lumo_status want, const char *what)
{
    snapshot s;
    uint8_t out[256];
    size_t w;
    lumo_status st;

    snap_take(&s, &h->w.s, h->w.c.mesh_count);
    st = deliver(&h->w, frame, n);
    if (want != LUMO_OK ? st != want : st == LUMO_OK)
        fail_msg("%s: %s, want %s", what, lumo_strerror(st), want ? lumo_strerror(want) : "an error");
    print_message("%-32s %s\n", what, lumo_strerror(st));
    snap_same(&s, &h->w.s);
    assert_int_equal(h->w.c.state, LUMO_NET_FAILED);
    assert_int_equal(lumo_net_client_next(&h->w.c, out, sizeof out, &w), st);
    assert_int_equal(w, 0);
    assert_int_equal(deliver(&h->w, g_frame, h->next_len), st);   /* the good frame: still failed */
    world_free(&h->w);
}

static size_t data_frame(const lumo_net_data *d, uint8_t *out, size_t cap)
{
    size_t n = 0;
    assert_int_equal(lumo_net_data_encode(d, out, cap, &n), LUMO_OK);
    return n;
}

/* Start until the next frame is geometry DATA with at least `records`
 * records (or lighting, when lighting is set). */
static void hostile_until(hostile *h, int pkg, uint8_t form, int lighting, uint32_t records)
{
    uint32_t frames;

    for (frames = 0; frames < 400; frames++) {
        hostile_start(h, pkg, form, frames, 1);
        if (h->next.type == LUMO_NET_DATA && h->d.channel == (lighting ? LUMO_NET_LIGHTING : LUMO_NET_GEOMETRY) &&
            h->d.records >= records && (lighting || h->d.first > 0))
            return;
        world_free(&h->w);
    }
    fail_msg("no such frame");
}

static void test_hostile(void **state)
{
    static uint8_t buf[1u << 16];
    hostile h;
    lumo_net_data d;
    uint32_t n;
    (void)state;

    /* wrong channel: lighting records while geometry was asked */
    hostile_until(&h, PKG_MIXED, LUMO_IVG_FORM_QUANTIZED, 0, 1);
    d = h.d;
    d.channel = LUMO_NET_LIGHTING, d.mesh = 0, d.form = LUMO_IVG_FORM_QUANTIZED, d.first = h.w.c.rounds_held;
    hostile_expect(&h, buf, data_frame(&d, buf, sizeof buf), LUMO_ERR_STATE, "wrong channel");

    /* wrong mesh */
    hostile_until(&h, PKG_MIXED, LUMO_IVG_FORM_QUANTIZED, 0, 1);
    d = h.d;
    d.mesh = (d.mesh + 1) % h.w.c.mesh_count;
    hostile_expect(&h, buf, data_frame(&d, buf, sizeof buf), LUMO_ERR_STATE, "wrong mesh");

    /* wrong first: one batch ahead, and one behind (a record held sent again) */
    hostile_until(&h, PKG_MIXED, LUMO_IVG_FORM_QUANTIZED, 0, 1);
    d = h.d;
    d.first++;
    hostile_expect(&h, buf, data_frame(&d, buf, sizeof buf), LUMO_ERR_STATE, "first past the cursor");
    hostile_until(&h, PKG_MIXED, LUMO_IVG_FORM_QUANTIZED, 0, 1);
    d = h.d;
    d.first--;
    hostile_expect(&h, buf, data_frame(&d, buf, sizeof buf), LUMO_ERR_STATE, "first before the cursor");

    /* counts past the end of the stream, and past what was asked */
    hostile_until(&h, PKG_MIXED, LUMO_IVG_FORM_QUANTIZED, 0, 1);
    d = h.d;
    d.count = d.records = h.w.c.batches[d.mesh] - d.first + 1;
    hostile_expect(&h, buf, data_frame(&d, buf, sizeof buf), LUMO_ERR_STATE, "count past the end");
    hostile_until(&h, PKG_MIXED, LUMO_IVG_FORM_QUANTIZED, 0, 2);
    d = h.d;
    d.count = d.records = d.count - 1;   /* the bytes hold one record more than it says */
    hostile_expect(&h, buf, data_frame(&d, buf, sizeof buf), LUMO_OK, "fewer records than bytes");

    /* lighting: rounds past the end; records that are not the rounds' */
    hostile_until(&h, PKG_SPLIT, LUMO_IVG_FORM_QUANTIZED, 1, 1);
    d = h.d;
    d.count = h.w.c.rounds_total - d.first + 1;
    d.records = d.count > d.records ? d.count : d.records;
    hostile_expect(&h, buf, data_frame(&d, buf, sizeof buf), LUMO_ERR_STATE, "rounds past the end");
    hostile_until(&h, PKG_SPLIT, LUMO_IVG_FORM_QUANTIZED, 1, 2);
    d = h.d;
    {
        uint32_t k, pos = 0, b = 0;
        for (k = 0; k < d.records; k++)
            pos += b = fake_record_bytes(d.bytes + pos, d.form);
        d.records--, d.len -= b;   /* the last record left out */
    }
    hostile_expect(&h, buf, data_frame(&d, buf, sizeof buf), LUMO_OK, "a round missing a record");

    /* a record the session refuses: a flipped byte in the first record, in
     * the last record (after good ones: still nothing applied) */
    hostile_until(&h, PKG_MIXED, LUMO_IVG_FORM_QUANTIZED, 0, 1);
    n = (uint32_t)data_frame(&h.d, buf, sizeof buf);
    buf[LUMO_NET_HEADER + LUMO_NET_DATA_HEAD + 20] ^= 0x40;
    lumo_net_frame_seal(buf, LUMO_NET_DATA, n - LUMO_NET_OVERHEAD);
    hostile_expect(&h, buf, n, LUMO_ERR_CHECKSUM, "damaged first record");
    hostile_until(&h, PKG_MIXED, LUMO_IVG_FORM_QUANTIZED, 0, 3);
    n = (uint32_t)data_frame(&h.d, buf, sizeof buf);
    buf[n - LUMO_NET_TRAILER - 3] ^= 0x01;
    lumo_net_frame_seal(buf, LUMO_NET_DATA, n - LUMO_NET_OVERHEAD);
    hostile_expect(&h, buf, n, LUMO_ERR_CHECKSUM, "damaged last record of three");
    /* a lighting record for a vertex past the grid */
    hostile_until(&h, PKG_SPLIT, LUMO_IVG_FORM_QUANTIZED, 1, 2);
    n = (uint32_t)data_frame(&h.d, buf, sizeof buf);
    lumo_wire_put_le32(buf + LUMO_NET_HEADER + LUMO_NET_DATA_HEAD, 0x7ffffff0u);
    lumo_net_frame_seal(buf, LUMO_NET_DATA, n - LUMO_NET_OVERHEAD);
    hostile_expect(&h, buf, n, LUMO_ERR_RANGE, "IVG record past the grid");

    /* END while batches were asked */
    hostile_until(&h, PKG_MIXED, LUMO_IVG_FORM_QUANTIZED, 0, 1);
    {
        lumo_net_end e = {LUMO_NET_GEOMETRY, h.d.mesh};
        size_t w;
        assert_int_equal(lumo_net_end_encode(&e, buf, sizeof buf, &w), LUMO_OK);
        hostile_expect(&h, buf, w, LUMO_ERR_STATE, "END while batches are asked");
    }
    /* WELCOME twice */
    hostile_until(&h, PKG_MIXED, LUMO_IVG_FORM_QUANTIZED, 0, 1);
    hostile_expect(&h, g_pkg[PKG_MIXED].welcome, g_pkg[PKG_MIXED].welcome_len, LUMO_ERR_STATE, "WELCOME twice");
    /* a server's ERROR: its status */
    hostile_until(&h, PKG_MIXED, LUMO_IVG_FORM_QUANTIZED, 0, 1);
    {
        size_t w;
        assert_int_equal(lumo_net_error_encode(LUMO_ERR_LIMIT, "too much", buf, sizeof buf, &w), LUMO_OK);
        hostile_expect(&h, buf, w, LUMO_ERR_LIMIT, "ERROR from the server");
    }
    /* a client's frame from the server */
    hostile_until(&h, PKG_MIXED, LUMO_IVG_FORM_QUANTIZED, 0, 1);
    {
        size_t w;
        assert_int_equal(lumo_net_bye_encode(buf, sizeof buf, &w), LUMO_OK);
        hostile_expect(&h, buf, w, LUMO_ERR_STATE, "BYE from the server");
    }
}

/* Before WELCOME: DATA and END are out of turn; a WELCOME for more arena
 * than stated is NOMEM; nothing reaches the session. */
static void test_before_welcome(void **state)
{
    static uint8_t buf[1u << 16];
    hostile h;
    run_cfg r;
    uint8_t out[512];
    size_t n;
    lumo_net_end e = {LUMO_NET_GEOMETRY, 0};
    (void)state;

    hostile_until(&h, PKG_MIXED, LUMO_IVG_FORM_QUANTIZED, 0, 1);
    n = data_frame(&h.d, buf, sizeof buf);
    world_free(&h.w);
    memset(&r, 0, sizeof r);
    r.pkg = PKG_MIXED, r.form = LUMO_IVG_FORM_QUANTIZED, r.max_payload = 1u << 20;
    driver_init(&h.w, &r);
    assert_int_equal(lumo_net_client_hello(&h.w.c, out, sizeof out, &h.next_len), LUMO_OK);
    assert_int_equal(deliver(&h.w, buf, n), LUMO_ERR_STATE);
    assert_null(lumo_session_info(&h.w.s));
    world_free(&h.w);

    driver_init(&h.w, &r);
    assert_int_equal(lumo_net_client_hello(&h.w.c, out, sizeof out, &h.next_len), LUMO_OK);
    assert_int_equal(lumo_net_end_encode(&e, buf, sizeof buf, &n), LUMO_OK);
    assert_int_equal(deliver(&h.w, buf, n), LUMO_ERR_STATE);
    world_free(&h.w);

    /* nothing sent yet (START): a WELCOME is out of turn too */
    driver_init(&h.w, &r);
    assert_int_equal(deliver(&h.w, g_pkg[PKG_MIXED].welcome, g_pkg[PKG_MIXED].welcome_len), LUMO_ERR_STATE);
    assert_null(lumo_session_info(&h.w.s));
    world_free(&h.w);

    driver_init(&h.w, &r);
    h.w.c.cfg.arena_bytes = g_pkg[PKG_MIXED].need - 1;
    assert_int_equal(lumo_net_client_hello(&h.w.c, out, sizeof out, &n), LUMO_OK);
    assert_int_equal(deliver(&h.w, g_pkg[PKG_MIXED].welcome, g_pkg[PKG_MIXED].welcome_len), LUMO_ERR_NOMEM);
    assert_null(lumo_session_info(&h.w.s));
    world_free(&h.w);
}

/* ---- a lossy line ----------------------------------------------------------------- */

/* The server's frames become a byte stream on which a frame is damaged with
 * probability 1/loss (a byte flipped or dropped, as lumo-server --loss
 * does); the client parses it as lumo-client --serial does: a refused frame
 * is skipped to the next magic and asked again (lumo_net_client_resync,
 * once per loss: not again while its marker is in flight), a frame not
 * expected is dropped, and silence while something is awaited (the stream
 * ran dry) forces a resync. The scene must still be the reference's. */
#define LINE_CAP ((size_t)64 << 20)
static uint8_t *g_line;

typedef struct line {
    uint8_t *b;
    size_t len, cap;
    uint32_t damaged;
} line;

static void line_put(line *l, const uint8_t *p, size_t n, test_rng *rng, uint32_t loss)
{
    uint64_t r = test_rng_next(rng);
    size_t at = (size_t)((r >> 8) % n);

    assert_true(l->len + n <= l->cap);
    memcpy(l->b + l->len, p, n);
    if (loss && r % loss == 0) {
        l->damaged++;
        if ((r >> 40) & 1) {
            l->b[l->len + at] ^= (uint8_t)(1u << ((r >> 32) & 7));
        } else {
            memmove(l->b + l->len + at, l->b + l->len + at + 1, n - at - 1);
            n--;
        }
    }
    l->len += n;
}

static void lossy_send(world *w, fake_server *srv, const uint8_t *out, size_t n)
{
    lumo_net_frame f;
    lumo_net_request r;
    lumo_net_hello h;
    size_t used;

    assert_int_equal(lumo_net_frame_decode(out, n, LUMO_NET_MAX_PAYLOAD, &f, &used), LUMO_OK);
    if (f.type == LUMO_NET_REQUEST) {
        assert_int_equal(lumo_net_request_decode(&f, &r), LUMO_OK);
        assert_int_equal(fake_server_request(srv, &r), LUMO_OK);
    } else if (f.type == LUMO_NET_HELLO) {   /* the server starts over (its serial listener does) */
        assert_int_equal(lumo_net_hello_decode(&f, &h), LUMO_OK);
        fake_server_init(srv, srv->k, h.ivg_form, h.max_payload);
        srv->qn = FAKE_QUEUE;   /* marks "WELCOME owed" below */
    }
    (void)w;
}

static void lossy_run(int pkg, uint8_t form, uint32_t max_payload, uint32_t pipeline, uint32_t loss, uint64_t seed,
                      const world *ref, uint32_t *damaged, uint32_t *resyncs)
{
    static world w;
    static line l;   /* the buffer: test_lossy_line's */
    fake_server srv;
    test_rng rng = {seed * 7919 + 3};
    run_cfg r;
    uint8_t out[512];
    size_t n, at = 0;
    uint32_t steps, stale = 0, refused = 0;
    int resyncing = 0;

    memset(&r, 0, sizeof r);
    r.pkg = pkg, r.form = form, r.max_payload = max_payload;
    r.policy.pipeline = pipeline;
    r.policy.vertices = (uint32_t)(seed % 3) * 150;   /* fixed or adaptive */
    r.policy.rounds = (uint32_t)(seed % 3) * 2;
    r.clock = 1;
    driver_init(&w, &r);
    l.b = g_line, l.cap = LINE_CAP, l.len = 0, l.damaged = 0;
    fake_server_init(&srv, &g_pkg[pkg], form, max_payload);
    assert_int_equal(lumo_net_client_hello(&w.c, out, sizeof out, &n), LUMO_OK);
    lossy_send(&w, &srv, out, n);
    for (steps = 0; steps < 100000 && w.c.state != LUMO_NET_DONE; steps++) {
        lumo_net_frame f;
        size_t used;
        lumo_status st;
        /* the server's side: WELCOME owed after a HELLO, else the next frame */
        if (srv.qn == FAKE_QUEUE) {
            srv.qn = 0;
            line_put(&l, g_pkg[pkg].welcome, g_pkg[pkg].welcome_len, &rng, loss);
        } else if (fake_server_frame(&srv, g_frame, FRAME_CAP, &n)) {
            line_put(&l, g_frame, n, &rng, loss);
        }
        /* the client's side */
        st = lumo_net_frame_decode(l.b + at, l.len - at, max_payload, &f, &used);
        if (st == LUMO_ERR_TRUNCATED) {
            if (srv.answering || srv.qn)
                continue;   /* more is coming */
            /* silence: what is left is a damaged frame (or nothing): ask again */
            at = l.len;
            assert_int_equal(lumo_net_client_resync(&w.c, out, sizeof out, &n), LUMO_OK);
            (*resyncs)++;
            resyncing = 1;
        } else if (st) {
            at = lumo_net_resync(l.b, l.len, at + 1);
            refused++;
            if (resyncing)
                continue;
            assert_int_equal(lumo_net_client_resync(&w.c, out, sizeof out, &n), LUMO_OK);
            (*resyncs)++;
            resyncing = 1;
        } else {
            at += used;
            if (!lumo_net_client_expects(&w.c, &f)) {
                stale++;
                continue;
            }
            assert_int_equal(lumo_net_client_on_frame(&w.c, &f), LUMO_OK);
            resyncing = 0;
            n = 0;
        }
        if (n)
            lossy_send(&w, &srv, out, n);
        while (lumo_net_client_next(&w.c, out, sizeof out, &n) == LUMO_OK && n && w.c.state != LUMO_NET_DONE)
            lossy_send(&w, &srv, out, n);
        assert_int_not_equal(w.c.state, LUMO_NET_FAILED);
    }
    assert_int_equal(w.c.state, LUMO_NET_DONE);
    lumo_session_update(&w.s);
    same_meshes(&w.s, &ref->s, g_pkg[pkg].meshes);
    same_grid(&w.s, &ref->s);
    *damaged += l.damaged;
    (void)stale, (void)refused;
    world_free(&w);
}

static void test_lossy_line(void **state)
{
    static world ref[2];
    uint32_t p, form, i, damaged = 0, resyncs = 0, runs = 0;
    (void)state;

    assert_non_null(g_line = malloc(LINE_CAP));
    for (p = 0; p < PKG_COUNT; p++) {
        for (form = 0; form < 2; form++)
            reference(&ref[form], &g_pkg[p], (uint8_t)form);
        for (i = 0; i < 24; i++) {
            form = i & 1;
            lossy_run((int)p, (uint8_t)form, i & 2 ? LUMO_NET_MIN_PAYLOAD : 1u << 20, 1 + i % 8, 4 + i % 7,
                      i + 1, &ref[form], &damaged, &resyncs);
            runs++;
        }
        for (form = 0; form < 2; form++)
            world_free(&ref[form]);
    }
    free(g_line);
    g_line = NULL;
    assert_true(damaged > 50);
    print_message("lossy line: %u runs to the full scene through %u damaged frames, %u resyncs\n", runs, damaged,
                  resyncs);
}

/* The marker: before WELCOME, resync is HELLO again; after it, one REQUEST
 * at the end of mesh 0 that only END answers; every DATA is stale until
 * then; requests go out behind it. */
static void test_resync_marker(void **state)
{
    static uint8_t buf[1u << 16];
    hostile h;
    lumo_net_frame f;
    lumo_net_request r;
    lumo_net_end e;
    uint8_t out[512];
    size_t n, used;
    (void)state;

    hostile_until(&h, PKG_MIXED, LUMO_IVG_FORM_QUANTIZED, 0, 1);
    assert_true(lumo_net_client_expects(&h.w.c, &h.next));
    assert_int_equal(lumo_net_client_resync(&h.w.c, out, sizeof out, &n), LUMO_OK);
    assert_int_equal(lumo_net_frame_decode(out, n, LUMO_NET_MAX_PAYLOAD, &f, &used), LUMO_OK);
    assert_int_equal(lumo_net_request_decode(&f, &r), LUMO_OK);
    assert_int_equal(r.channel, LUMO_NET_GEOMETRY);
    assert_int_equal(r.mesh, 0);
    assert_int_equal(r.cursor, h.w.c.batches[0]);
    assert_int_equal(h.w.c.npending, 1);
    assert_false(lumo_net_client_expects(&h.w.c, &h.next));   /* the answer asked before: stale */
    assert_int_equal(lumo_net_client_next(&h.w.c, out, sizeof out, &n), LUMO_OK);
    assert_int_equal(n, 0);   /* pipeline 1: the marker is the request in flight */
    e.channel = LUMO_NET_GEOMETRY, e.mesh = 1;
    assert_int_equal(lumo_net_end_encode(&e, buf, sizeof buf, &n), LUMO_OK);
    assert_int_equal(lumo_net_frame_decode(buf, n, LUMO_NET_MAX_PAYLOAD, &f, &used), LUMO_OK);
    assert_false(lumo_net_client_expects(&h.w.c, &f));        /* another mesh's END */
    e.mesh = 0;
    assert_int_equal(lumo_net_end_encode(&e, buf, sizeof buf, &n), LUMO_OK);
    assert_int_equal(lumo_net_frame_decode(buf, n, LUMO_NET_MAX_PAYLOAD, &f, &used), LUMO_OK);
    assert_true(lumo_net_client_expects(&h.w.c, &f));
    assert_int_equal(lumo_net_client_on_frame(&h.w.c, &f), LUMO_OK);
    assert_false(lumo_net_client_expects(&h.w.c, &f));        /* a second END: stale */
    assert_false(lumo_net_client_expects(&h.w.c, &h.next));   /* nothing asked yet */
    assert_int_equal(lumo_net_client_next(&h.w.c, out, sizeof out, &n), LUMO_OK);
    assert_true(n > 0);                                        /* asked again from the cursors held */
    assert_int_equal(lumo_net_frame_decode(out, n, LUMO_NET_MAX_PAYLOAD, &f, &used), LUMO_OK);
    assert_int_equal(lumo_net_request_decode(&f, &r), LUMO_OK);
    assert_int_equal(r.cursor, r.channel == LUMO_NET_GEOMETRY ? h.w.c.held[r.mesh] : h.w.c.rounds_held);
    /* the answer of the old request is next again if this one asks the same */
    assert_int_equal(lumo_net_client_expects(&h.w.c, &h.next),
                     r.channel == h.d.channel && r.mesh == h.d.mesh && r.cursor == h.d.first);
    assert_false(lumo_net_client_expects(&h.w.c, (const lumo_net_frame *)&(lumo_net_frame){LUMO_NET_WELCOME, 0, buf}));
    world_free(&h.w);

    /* before WELCOME: HELLO again */
    {
        run_cfg rc;
        lumo_net_hello hh;
        memset(&rc, 0, sizeof rc);
        rc.pkg = PKG_MIXED, rc.form = LUMO_IVG_FORM_QUANTIZED, rc.max_payload = 1u << 20;
        driver_init(&h.w, &rc);
        assert_int_equal(lumo_net_client_hello(&h.w.c, out, sizeof out, &n), LUMO_OK);
        assert_int_equal(lumo_net_client_resync(&h.w.c, out, sizeof out, &n), LUMO_OK);
        assert_int_equal(lumo_net_frame_decode(out, n, LUMO_NET_MAX_PAYLOAD, &f, &used), LUMO_OK);
        assert_int_equal(lumo_net_hello_decode(&f, &hh), LUMO_OK);
        assert_int_equal(h.w.c.state, LUMO_NET_HELLO_SENT);
        assert_int_equal(lumo_net_frame_decode(g_pkg[PKG_MIXED].welcome, g_pkg[PKG_MIXED].welcome_len,
                                               LUMO_NET_MAX_PAYLOAD, &f, &used), LUMO_OK);
        assert_true(lumo_net_client_expects(&h.w.c, &f));
        world_free(&h.w);
    }
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_packages),
        cmocka_unit_test(test_policies_stream),
        cmocka_unit_test(test_policies_mixed),
        cmocka_unit_test(test_policies_split),
        cmocka_unit_test(test_short_last_batch),
        cmocka_unit_test(test_resume),
        cmocka_unit_test(test_prt),
        cmocka_unit_test(test_lossy_line),
        cmocka_unit_test(test_resync_marker),
        cmocka_unit_test(test_hostile),
        cmocka_unit_test(test_before_welcome),
    };
    int rc;

    (void)argc;
    g_argv0 = argv[0];
    if (!(g_frame = malloc(FRAME_CAP)))
        return 1;
    rc = cmocka_run_group_tests(tests, group_setup, group_teardown);
    free(g_frame);
    return rc;
}
