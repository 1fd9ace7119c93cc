/* pm_check.c — end-to-end checks of the progressive mesh (issue 5): the
 * server's levels, the stream, and the real client (sanitizer build of
 * liblumo) decoding it.
 *
 *   pm_check (--gen NAME | MODEL.ply) [--batch N] [--bits B]
 *
 * Prints one line per check and "RESULT: N passed, M failed". */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "lumo/package.h"
#include "lumo/pmesh.h"
#include "pm/pm.h"
#include "pm/pm_internal.h"
#include "lumo/wire.h"
#include "lumo_shared/pmesh_shared.h"
#include "pm/pm_client.h"
#include "pm/pm_load.h"
#include "pm/pm_stream.h"
#include "pm_meshes.h"

static int g_pass, g_fail;
static char g_name[256];

static void check(int ok, const char *what, const char *detail)
{
    if (ok)
        g_pass++;
    else
        g_fail++;
    printf("%s %s: %s%s%s\n", ok ? "ok  " : "FAIL", g_name, what, detail[0] ? " — " : "", detail);
}

/* ---- every level, by an incremental sweep --------------------------------- */
/* Corner events: at level `level` corner `corner` starts showing `value`. */
typedef struct { uint32_t level, corner, value; } event;

static int cmp_event(const void *a, const void *b)
{
    const event *x = a, *y = b;
    if (x->level != y->level)
        return x->level < y->level ? -1 : 1;
    return (x->corner > y->corner) - (x->corner < y->corner);
}

typedef struct { uint64_t *key; uint32_t *count; size_t mask; } multiset;

static uint64_t face_key(const uint32_t *t)
{
    uint32_t a = t[0], b = t[1], c = t[2], x;
    if (a > b) x = a, a = b, b = x;
    if (b > c) x = b, b = c, c = x;
    if (a > b) x = a, a = b, b = x;
    return ((uint64_t)a * 0x9E3779B97F4A7C15ull) ^ ((uint64_t)b << 21) ^ ((uint64_t)c << 42) ^ c ^ (b >> 11);
}

/* Keys are hashes of sorted triples; a 64-bit collision would only make a
 * false duplicate report, never hide one. */
static uint32_t *ms_slot(multiset *m, uint64_t k)
{
    size_t i = (size_t)(k * 0xff51afd7ed558ccdull >> 20) & m->mask;
    while (m->count[i] != UINT32_MAX && m->key[i] != k)
        i = (i + 1) & m->mask;
    if (m->count[i] == UINT32_MAX)
        m->key[i] = k, m->count[i] = 0;
    return &m->count[i];
}

static int face_bad(const uint32_t *t, uint32_t k)
{
    return t[0] == t[1] || t[1] == t[2] || t[0] == t[2] || t[0] >= k || t[1] >= k || t[2] >= k;
}

static void check_all_levels(const srv_pm *pm)
{
    size_t nev = 0, cap = 3 * (size_t)pm->faces;
    event *ev = malloc(sizeof *ev * (cap ? cap : 1));
    for (uint32_t f = 0; f < pm->faces; f++)
        for (int c = 0; c < 3; c++) {
            uint32_t o = pm->tris[3 * (size_t)f + c], L = pm->level[f];
            for (uint32_t a = o; a >= L; a = pm->parent[a]) {
                if (nev == cap)
                    ev = realloc(ev, sizeof *ev * (cap *= 2));
                ev[nev++] = (event){a + 1, 3 * f + (uint32_t)c, a};
            }
        }
    qsort(ev, nev, sizeof *ev, cmp_event);
    size_t slots = 1;
    while (slots < 2 * (nev + pm->faces) + 16)
        slots *= 2;
    multiset ms = {malloc(sizeof(uint64_t) * slots), malloc(sizeof(uint32_t) * slots), slots - 1};
    memset(ms.count, 0xff, sizeof(uint32_t) * slots);
    uint32_t *disp = malloc(sizeof *disp * 3 * (size_t)(pm->faces ? pm->faces : 1));
    uint32_t nf = 0, bad = 0, dups = 0, levels = 0, first_bad = 0;
    size_t e = 0;
    for (uint32_t k = pm->base_vertices; k <= pm->vertices; k++, levels++) {
        for (; e < nev && ev[e].level <= k; e++) {  /* corner moves to a new vertex */
            uint32_t f = ev[e].corner / 3;
            if (f >= nf)
                continue;  /* face not shown yet: it enters resolved below */
            (*ms_slot(&ms, face_key(disp + 3 * f)))--;
            disp[ev[e].corner] = ev[e].value;
            uint32_t *cnt = ms_slot(&ms, face_key(disp + 3 * f));
            dups += ++*cnt > 1;
            if (face_bad(disp + 3 * f, k) && !bad++)
                first_bad = k;
        }
        for (; nf < pm->faces && pm->level[nf] <= k; nf++) {
            for (int c = 0; c < 3; c++)
                disp[3 * nf + c] = srv_pm_resolve(pm, pm->tris[3 * nf + c], k);
            uint32_t *cnt = ms_slot(&ms, face_key(disp + 3 * nf));
            dups += ++*cnt > 1;
            if (face_bad(disp + 3 * nf, k) && !bad++)
                first_bad = k;
        }
        /* the sweep must agree with srv_pm_level on sampled levels */
        if (k % 97 == 0 || k == pm->vertices) {
            uint32_t *ref = malloc(sizeof *ref * 3 * (size_t)(pm->faces + 1));
            uint32_t rn = srv_pm_level(pm, k, ref);
            if (rn != nf || memcmp(ref, disp, sizeof *ref * 3 * nf))
                bad++;
            free(ref);
        }
    }
    /* Faces that did not change since the previous level stay valid: every
     * face is checked whenever it enters or one of its corners moves. */
    char d[160];
    snprintf(d, sizeof d, "%u levels (%u..%u vertices), %u bad, %u duplicated faces (first bad %u)",
             levels, pm->base_vertices, pm->vertices, bad, dups, first_bad);
    check(bad == 0 && dups == 0, "every level valid, no degenerate or duplicated face", d);
    free(ev), free(ms.key), free(ms.count), free(disp);
}

/* ---- the full level against the input mesh ------------------------------- */
typedef struct { float p[9]; } ptri;

/* Rotate so the lexicographically smallest corner comes first (winding kept). */
static ptri canon(const float *a, const float *b, const float *c)
{
    const float *v[3] = {a, b, c};
    int m = 0;
    for (int i = 1; i < 3; i++)
        if (v[i][0] < v[m][0] || (v[i][0] == v[m][0] && (v[i][1] < v[m][1] ||
            (v[i][1] == v[m][1] && v[i][2] < v[m][2]))))
            m = i;
    ptri t;
    for (int i = 0; i < 3; i++)
        memcpy(t.p + 3 * i, v[(m + i) % 3], 3 * sizeof(float));
    return t;
}

static int cmp_ptri(const void *a, const void *b)
{
    const float *x = ((const ptri *)a)->p, *y = ((const ptri *)b)->p;
    for (int i = 0; i < 9; i++)
        if (x[i] != y[i])
            return x[i] < y[i] ? -1 : 1;
    return 0;
}

/* Same vertex set (either winding): compare sorted corners. */
static ptri unordered(ptri t)
{
    ptri u = t;
    for (int i = 0; i < 3; i++)
        for (int j = i + 1; j < 3; j++)
            if (cmp_ptri(&(ptri){{u.p[3 * j], u.p[3 * j + 1], u.p[3 * j + 2]}},
                         &(ptri){{u.p[3 * i], u.p[3 * i + 1], u.p[3 * i + 2]}}) < 0)
                for (int k = 0; k < 3; k++) {
                    float x = u.p[3 * i + k];
                    u.p[3 * i + k] = u.p[3 * j + k], u.p[3 * j + k] = x;
                }
    return u;
}

typedef struct { ptri u; uint32_t f; } keyed;

static int cmp_keyed(const void *a, const void *b)
{
    const keyed *x = a, *y = b;
    int c = cmp_ptri(&x->u, &y->u);
    return c ? c : (x->f > y->f) - (x->f < y->f);
}

/* The input's faces minus degenerate ones and later copies of a vertex set
 * (the same rule as server/pm/pm_clean.c, stated on positions here). */
static size_t input_faces(const pm_test_mesh *in, ptri *out)
{
    keyed *k = malloc(sizeof *k * (in->nf + 1));
    uint8_t *keep = calloc(in->nf + 1, 1);
    size_t n = 0, nk = 0;
    for (uint32_t f = 0; f < in->nf; f++) {
        const float *a = in->xyz + 3 * in->tris[3 * f], *b = in->xyz + 3 * in->tris[3 * f + 1],
                    *c = in->xyz + 3 * in->tris[3 * f + 2];
        if (!memcmp(a, b, 12) || !memcmp(b, c, 12) || !memcmp(a, c, 12))
            continue;
        k[nk].u = unordered(canon(a, b, c));
        k[nk++].f = f;
    }
    qsort(k, nk, sizeof *k, cmp_keyed);
    for (size_t i = 0; i < nk; i++)
        keep[k[i].f] = i == 0 || cmp_ptri(&k[i].u, &k[i - 1].u) != 0;
    for (uint32_t f = 0; f < in->nf; f++)
        if (keep[f])
            out[n++] = canon(in->xyz + 3 * in->tris[3 * f], in->xyz + 3 * in->tris[3 * f + 1],
                             in->xyz + 3 * in->tris[3 * f + 2]);
    free(k), free(keep);
    return n;
}

static void check_full_level(const pm_test_mesh *in, const srv_pm *pm, const lumo_pmesh_view *v,
                             double step)
{
    ptri *want = malloc(sizeof *want * (in->nf + 1)), *got = malloc(sizeof *got * (v->face_count + 1));
    size_t nw = input_faces(in, want), bad_pos = 0;
    for (uint32_t f = 0; f < v->face_count; f++) {
        const uint32_t *t = v->triangles + 3 * f;
        got[f] = canon(pm->xyz + 3 * t[0], pm->xyz + 3 * t[1], pm->xyz + 3 * t[2]);
    }
    qsort(want, nw, sizeof *want, cmp_ptri);
    qsort(got, v->face_count, sizeof *got, cmp_ptri);
    int same = nw == v->face_count && !memcmp(want, got, sizeof *got * nw);
    double worst = 0;
    for (uint32_t i = 0; i < 3 * v->vertex_count; i++) {
        double d = fabs(v->positions[i] / 65536.0 - pm->xyz[i]);
        worst = d > worst ? d : worst;
        bad_pos += d > step;
    }
    char d[200];
    snprintf(d, sizeof d, "%u faces vs %zu input faces kept (%u input, %u vertices)", v->face_count,
             nw, in->nf, v->vertex_count);
    check(same && v->vertex_count == pm->vertices, "full level = input mesh (faces as sets, winding kept)", d);
    snprintf(d, sizeof d, "worst %.3g m, quantization step %.3g m", worst, step);
    check(bad_pos == 0, "full-level positions within the quantization step", d);
    free(want), free(got);
}

/* ---- the client against the server, level by level --------------------------- */
/* Normals from scratch over the whole level, the client's formula (area-
 * weighted integer face normals, scaled into int32, lumo_normalize3_q14):
 * the client's incremental normals must equal them exactly. */
static int normals_exact(const lumo_pmesh *pm)
{
    size_t n = pm->vertex_count;
    int64_t *sum = calloc(3 * n + 3, sizeof *sum);
    for (uint32_t f = 0; f < pm->face_count; f++) {
        const uint32_t *t = pm->tris + 3 * f;
        const int32_t *a = pm->qpos + 3 * t[0], *b = pm->qpos + 3 * t[1], *d = pm->qpos + 3 * t[2];
        int64_t e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
        int64_t c[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        for (int k = 0; k < 3; k++)
            for (int i = 0; i < 3; i++)
                sum[3 * t[k] + i] += c[i];
    }
    int ok = 1;
    for (size_t v = 0; v < n && ok; v++) {
        int64_t *s = sum + 3 * v;
        while (llabs(s[0]) > INT32_MAX / 2 || llabs(s[1]) > INT32_MAX / 2 || llabs(s[2]) > INT32_MAX / 2)
            s[0] /= 2, s[1] /= 2, s[2] /= 2;
        int32_t iv[3] = {(int32_t)s[0], (int32_t)s[1], (int32_t)s[2]};
        lumo_q1_14 want[3];
        if (lumo_normalize3_q14(iv, want))
            want[0] = want[1] = want[2] = 0;
        ok = !memcmp(want, pm->nrm + 3 * v, sizeof want);
    }
    free(sum);
    return ok;
}

static int client_matches(const srv_pm *pm, const lumo_pmesh *pm_client, uint32_t *ref, double step,
                          char *why, size_t n)
{
    lumo_pmesh_view view, *v = &view;
    lumo_pmesh_get_view(pm_client, v);
    uint32_t k = v->vertex_count, nf = srv_pm_level(pm, k, ref);
    if (nf != v->face_count || memcmp(ref, v->triangles, sizeof *ref * 3 * nf)) {
        snprintf(why, n, "level %u: %u faces, server %u, or indices differ", k, v->face_count, nf);
        return 0;
    }
    for (uint32_t i = 0; i < 3 * k; i++)
        if (fabs(v->positions[i] / 65536.0 - pm->xyz[i]) > step) {
            snprintf(why, n, "level %u: vertex %u off by more than a step", k, i / 3);
            return 0;
        }
    if (!pm->albedo != !v->albedo) {
        snprintf(why, n, "albedo %s on the client", v->albedo ? "unexpected" : "missing");
        return 0;
    }
    for (uint32_t i = 0; pm->albedo && i < 3 * k; i++)
        if (v->albedo[i] != (pm->albedo[i] * 16384 + 127) / 255) {
            snprintf(why, n, "level %u: vertex %u albedo differs", k, i / 3);
            return 0;
        }
    if (!normals_exact(pm_client)) {
        snprintf(why, n, "level %u: incremental normals differ from a full recomputation", k);
        return 0;
    }
    for (uint32_t i = 0; i < k; i++) {
        const lumo_q1_14 *q = v->normals + 3 * i;
        double len = sqrt((double)q[0] * q[0] + (double)q[1] * q[1] + (double)q[2] * q[2]) / 16384.0;
        if (len != 0 && fabs(len - 1) > 0.01) {
            snprintf(why, n, "level %u: normal %u has length %.4f", k, i, len);
            return 0;
        }
    }
    return 1;
}

/* Returns the client's final view through *cl (left open for the caller). */
static void check_client(const srv_pm *pm, const uint8_t *s, size_t len, double step, srv_pm_client *cl)
{
    uint32_t *ref = malloc(sizeof *ref * 3 * (size_t)(pm->faces + 1));
    char why[200] = "";
    lumo_status st = srv_pm_client_open(cl, s, len);
    uint32_t levels = 0;
    int ok = !st;
    while (ok && !lumo_pmesh_complete(&cl->pm)) {
        if ((st = srv_pm_client_step(cl))) {
            snprintf(why, sizeof why, "batch %u: %s", lumo_pmesh_batches(&cl->pm), lumo_strerror(st));
            ok = 0;
            break;
        }
        ok = client_matches(pm, &cl->pm, ref, step, why, sizeof why);
        levels++;
    }
    if (ok)
        snprintf(why, sizeof why, "%u batches, each level identical to srv_pm_level, arena %zu bytes",
                 levels, cl->arena_bytes);
    check(ok, "client applying batches in order reproduces the server's levels", why);
    free(ref);
}

/* ---- corrupt and truncated batches -------------------------------------------- */
typedef struct {
    uint32_t vc, fc, ba;
    uint32_t *tris, *next, *head;
    lumo_q16_16 *pos;
    lumo_q1_14 *nrm;
} snapshot;

static void snap(const lumo_pmesh *pm, snapshot *s)
{
    size_t c = 3 * (size_t)pm->h.faces, v = pm->h.vertices;
    s->vc = pm->vertex_count, s->fc = pm->face_count, s->ba = pm->batches_applied;
    s->tris = malloc(4 * c + 4), s->next = malloc(4 * c + 4), s->head = malloc(4 * v + 4);
    s->pos = malloc(12 * v + 4), s->nrm = malloc(6 * v + 4);
    memcpy(s->tris, pm->tris, 4 * c), memcpy(s->next, pm->next, 4 * c);
    memcpy(s->head, pm->head, 4 * v), memcpy(s->pos, pm->pos, 12 * v), memcpy(s->nrm, pm->nrm, 6 * v);
}

static int same_as(const lumo_pmesh *pm, const snapshot *s)
{
    size_t c = 3 * (size_t)pm->h.faces, v = pm->h.vertices;
    /* head[] of vertices not yet received is scratch until they arrive */
    return s->vc == pm->vertex_count && s->fc == pm->face_count && s->ba == pm->batches_applied &&
           !memcmp(s->tris, pm->tris, 4 * 3 * (size_t)s->fc) && !memcmp(s->next, pm->next, 4 * 3 * (size_t)s->fc) &&
           !memcmp(s->head, pm->head, 4 * (size_t)s->vc) && !memcmp(s->pos, pm->pos, 12 * (size_t)s->vc) &&
           !memcmp(s->nrm, pm->nrm, 6 * (size_t)s->vc) && c + v > 0;
}

static void unsnap(snapshot *s)
{
    free(s->tris), free(s->next), free(s->head), free(s->pos), free(s->nrm);
}

static void put32(uint8_t *p, uint32_t v)
{
    for (int i = 0; i < 4; i++)
        p[i] = (uint8_t)(v >> (8 * i));
}

/* Record rec (n bytes) with its block one byte longer (a zero byte added)
 * or shorter, its head rewritten and the CRC of record number `index`
 * fixed (docs/progressive-mesh.md §2.2): only the block's end rules
 * (§2.3: every byte used, the range code's end) can refuse it. A zero
 * byte more always is (the decoder reads the same bits and ends a byte
 * early); a byte less may read as other valid splits. out holds n + 16
 * bytes; returns the new length. */
static size_t resized(const uint8_t *rec, size_t n, int more, uint32_t index, uint8_t *out)
{
    lumo_pmesh_record_head rh;
    uint8_t idx[LUMO_WIRE_VARINT32_MAX];
    if (lumo_pmesh_read_record_head(rec, n, &rh) || (!more && rh.side_bytes < 2))
        return 0;
    uint32_t side = more ? rh.side_bytes + 1 : rh.side_bytes - 1;
    size_t at = lumo_wire_put_varint(out, side * 2u + (rh.draco_bytes != 0)), hb;
    if (rh.draco_bytes)
        at += lumo_wire_put_varint(out + at, rh.draco_bytes);
    hb = at + 4;
    memcpy(out + hb, rec + rh.head_bytes, more ? rh.side_bytes : side);
    if (more)
        out[hb + rh.side_bytes] = 0;
    memcpy(out + hb + side, rec + rh.head_bytes + rh.side_bytes, rh.draco_bytes);
    uint32_t crc = lumo_wire_crc32(0, idx, lumo_wire_put_varint(idx, index));
    crc = lumo_wire_crc32(crc, out, at);
    crc = lumo_wire_crc32(crc, out + hb, side + rh.draco_bytes);
    put32(out + at, crc);
    return hb + side + rh.draco_bytes;
}

/* One bad variant of the next record must fail and leave the mesh as it was. */
static int reject(srv_pm_client *cl, const uint8_t *r, size_t n, const snapshot *s, int *errs,
                  const char *what, size_t at)
{
    lumo_status st = lumo_pmesh_apply(&cl->pm, r, n);
    *errs += st != LUMO_OK;
    int ok = st != LUMO_OK && same_as(&cl->pm, s);
    if (!ok)
        fprintf(stderr, "batch %u, %s at %zu: %s, mesh %s\n", lumo_pmesh_batches(&cl->pm), what, at,
                st ? lumo_strerror(st) : "accepted", same_as(&cl->pm, s) ? "unchanged" : "CHANGED");
    return ok;
}

static int corrupt_variants(srv_pm_client *cl, const uint8_t *rec, size_t n, const uint8_t *later,
                            size_t later_n, int *tried)
{
    snapshot s;
    snap(&cl->pm, &s);
    uint8_t *b = malloc(n + 1);
    int ok = 1, errs = 0;
    for (size_t i = 0; i < n; i += 1 + n / 23) {     /* byte flips everywhere */
        memcpy(b, rec, n);
        b[i] ^= (uint8_t)((0x5a + i) | 1);  /* never zero */
        ok &= reject(cl, b, n, &s, &errs, "byte flip", i), (*tried)++;
    }
    for (size_t cut = 0; cut < n; cut += 1 + n / 7)  /* truncations */
        ok &= reject(cl, rec, cut, &s, &errs, "truncation", cut), (*tried)++;
    uint8_t *c = malloc(n + 16);                      /* a zero byte more in the block, CRC */
    size_t cn = resized(rec, n, 1, lumo_pmesh_batches(&cl->pm), c);  /* fixed: its end rules */
    if (cn)
        ok &= reject(cl, c, cn, &s, &errs, "block + 1 byte", 0), (*tried)++;
    free(c);
    if (later)                                        /* out of order: its CRC is another index's */
        ok &= lumo_pmesh_apply(&cl->pm, later, later_n) == LUMO_ERR_CHECKSUM && same_as(&cl->pm, &s), (*tried)++;
    ok &= lumo_pmesh_apply(&cl->pm, rec, n) == LUMO_OK;  /* the good copy still applies */
    free(b);
    unsnap(&s);
    return ok;
}

static void check_corruption(const srv_pm *pm, const uint8_t *s, size_t len, double step)
{
    srv_pm_client cl;
    int ok = !srv_pm_client_open(&cl, s, len), tried = 0;
    uint32_t nb = cl.h.batch_count;
    for (uint32_t i = 0; ok && i < nb; i++) {
        const uint8_t *rec, *later = NULL;
        size_t n, later_n = 0;
        ok = !srv_pm_client_next(&cl, &rec, &n);
        if (ok && i + 1 < nb)
            later = rec + n, later_n = len - (size_t)(later - s);
        if (later && lumo_pmesh_record_size(later, later_n, &later_n))
            later = NULL;
        int pick = i < 2 || i == nb / 2 || i + 1 == nb;
        if (ok && pick)
            ok = corrupt_variants(&cl, rec, n, later, later_n, &tried);
        else if (ok)
            ok = !lumo_pmesh_apply(&cl.pm, rec, n);
        cl.at += n;
    }
    lumo_pmesh_view v;
    lumo_pmesh_get_view(&cl.pm, &v);
    uint32_t *ref = malloc(sizeof *ref * 3 * (size_t)(pm->faces + 1));
    char why[200] = "";
    ok = ok && lumo_pmesh_complete(&cl.pm) && client_matches(pm, &cl.pm, ref, step, why, sizeof why);
    snprintf(why + strlen(why), sizeof why - strlen(why), "%s%d bad records rejected, mesh unchanged each time",
             why[0] ? "; " : "", tried);
    check(ok, "corrupt/truncated/out-of-order batches rejected whole, good ones still apply", why);
    free(ref);
    srv_pm_client_close(&cl);
}

/* Every level, not only batch boundaries: decode to the batch holding k,
 * rewind inside it, compare. One fresh client per level, so small meshes. */
static void check_rewind(const srv_pm *pm, const uint8_t *s, size_t len, double step)
{
    uint32_t *ref = malloc(sizeof *ref * 3 * (size_t)(pm->faces + 1)), levels = 0;
    char why[200] = "";
    int ok = 1;
    for (uint32_t k = pm->base_vertices; ok && k <= pm->vertices; k++, levels++) {
        srv_pm_client cl;
        lumo_status st = srv_pm_client_open(&cl, s, len);
        if (!st)
            st = srv_pm_client_until(&cl, k);
        if (!st)
            st = lumo_pmesh_rewind(&cl.pm, k);
        ok = !st && cl.pm.vertex_count == k && client_matches(pm, &cl.pm, ref, step, why, sizeof why);
        if (ok)  /* a rewound mesh is final */
            ok = srv_pm_client_step(&cl) == (lumo_pmesh_complete(&cl.pm) ? LUMO_ERR_TRUNCATED : LUMO_ERR_STATE) ||
                 cl.at >= len;
        if (!ok && !why[0])
            snprintf(why, sizeof why, "level %u: %s", k, lumo_strerror(st));
        srv_pm_client_close(&cl);
    }
    if (ok)
        snprintf(why, sizeof why, "%u levels, one vertex per step, each identical to srv_pm_level", levels);
    check(ok, "client rewinds to every level (lumo_pmesh_rewind)", why);
    free(ref);
}

/* ---- the seed changes nothing from the base mesh on --------------------------- */
/* Level k of pm as position triples (winding kept), sorted: comparable
 * across vertex numberings. */
static size_t level_ptris(const srv_pm *pm, uint32_t k, uint32_t *idx, ptri *out)
{
    uint32_t nf = srv_pm_level(pm, k, idx);
    for (uint32_t f = 0; f < nf; f++) {
        const uint32_t *t = idx + 3 * (size_t)f;
        out[f] = canon(pm->xyz + 3 * (size_t)t[0], pm->xyz + 3 * (size_t)t[1], pm->xyz + 3 * (size_t)t[2]);
    }
    qsort(out, nf, sizeof *out, cmp_ptri);
    return nf;
}

/* Built without the seed (options seed 0), the simplifier's collapses are
 * exactly the first `bounded` ones of the seeded run, the base mesh is the
 * same, and so is the level at the end of every round from the base mesh
 * on (faces as position triples): inside the base mesh the seed numbers the
 * vertices differently, so a round may list its (commuting) splits in
 * another order, which changes only levels inside a round. */
static void check_seed_levels(const pm_test_mesh *in, const srv_pm_options *po, const srv_pm *pm)
{
    srv_pm_options off = *po;
    srv_pm_clean_mesh m;
    srv_pm_collapses con, coff;
    srv_pm old;
    char d[200] = "";
    int ok = 0;
    off.seed = 0;
    memset(&con, 0, sizeof con), memset(&coff, 0, sizeof coff), memset(&old, 0, sizeof old);
    if (srv_pm_clean(in->xyz, in->rgb, in->nv, in->tris, in->nf, &m))
        goto out;
    if (!srv_pm_simplify(&m, po, &con) && !srv_pm_simplify(&m, &off, &coff) &&
        !srv_pm_build_albedo(in->xyz, in->rgb, in->nv, in->tris, in->nf, &off, &old)) {
        size_t t = 0;
        ok = coff.count == con.bounded && coff.bounded == coff.count && old.seed_vertices == old.base_vertices &&
             old.base_vertices == pm->base_vertices && old.base_faces == pm->base_faces;
        for (t = 0; ok && t < coff.count; t++)
            ok = coff.removed[t] == con.removed[t] && coff.target[t] == con.target[t] &&
                 coff.round[t] == con.round[t];
        snprintf(d, sizeof d, "%u bounded collapses of %u, %s", con.bounded, con.count,
                 ok ? "the same without the seed" : "DIFFERENT without the seed");
        uint32_t *idx = malloc(sizeof *idx * 3 * (size_t)(pm->faces + 1));
        ptri *a = malloc(sizeof *a * (pm->faces + 1)), *b = malloc(sizeof *b * (pm->faces + 1));
        uint32_t rounds = 0, same = 0, all = 0, ends = 0;
        for (t = 0; t <= coff.count; t++)
            ends += t == 0 || t == coff.count || coff.round[t - 1] != coff.round[t];
        /* every level of a small mesh; else every round end of up to 64
         * (more: evenly spread, the base mesh always) */
        int every = pm->vertices <= 2500;
        uint32_t stride = every || ends <= 64 ? 1 : (ends + 63) / 64, e = 0;
        for (t = coff.count + 1; ok && t-- > 0;) {
            /* t collapses done: level n - t; a round ends where the next
             * collapse is in a later round (or none is left) */
            int end = t == 0 || t == coff.count || coff.round[t - 1] != coff.round[t];
            if (!every && (!end || (e++ % stride && t != coff.count)))
                continue;
            uint32_t k = pm->vertices - (uint32_t)t;
            size_t na = level_ptris(pm, k, idx, a), nb = level_ptris(&old, k, idx, b);
            int eq = na == nb && !memcmp(a, b, sizeof *a * na);
            all++, same += eq;
            if (end)
                rounds++, ok = eq;
            if (!ok)
                snprintf(d, sizeof d, "level %u (end of a round) differs without the seed", k);
        }
        if (ok)
            snprintf(d + strlen(d), sizeof d - strlen(d),
                     "; %u round ends (of %u) identical from base %u on, %u of %u levels compared", rounds,
                     ends, pm->base_vertices, same, all);
        free(idx), free(a), free(b);
    }
    srv_pm_clean_free(&m);
out:
    srv_pm_collapses_free(&con), srv_pm_collapses_free(&coff), srv_pm_free(&old);
    check(ok, "levels from the base mesh on as without the seed", d);
}

/* ---- driver ------------------------------------------------------------------------ */
int main(int argc, char **argv)
{
    const char *gen = NULL, *file = NULL, *dump = NULL, *want_base = NULL;
    long base_max = -1;
    int want_lattice = -1;
    int want_rgb = 0;
    srv_pm_stream_options so;
    srv_pm_stream_stats st;
    srv_pm_options po;
    srv_pm_stream_default_options(&so);
    srv_pm_default_options(&po);
    so.stats = &st;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--gen") && i + 1 < argc)
            gen = argv[++i];
        else if (!strcmp(argv[i], "--batch") && i + 1 < argc)
            so.batch_vertices = (uint32_t)atoi(argv[++i]);
        else if (!strcmp(argv[i], "--albedo"))
            want_rgb = 1;
        else if (!strcmp(argv[i], "--absolute"))
            so.position_coding = LUMO_PMESH_POS_ABSOLUTE;
        else if (!strcmp(argv[i], "--predicted"))  /* residuals in Draco payloads (version 4's) */
            so.position_coding = LUMO_PMESH_POS_PREDICTED;
        else if (!strcmp(argv[i], "--lattice") && i + 1 < argc) {
            const char *v = argv[++i];  /* auto (default), on, off */
            so.lattice = !strcmp(v, "on") ? 1 : !strcmp(v, "off") ? 0 : -1;
        } else if (!strcmp(argv[i], "--expect-lattice") && i + 1 < argc)
            want_lattice = atoi(argv[++i]);  /* 1/0: the stream must (not) copy coordinates */
        else if (!strcmp(argv[i], "--rank-escape"))
            so.fan_rank_escape = 1;  /* every ranked fan coded explicitly after the escape */
        else if (!strcmp(argv[i], "--write-stream") && i + 1 < argc)
            dump = argv[++i];  /* for fuzz seeds and the unit test's data */
        else if (!strcmp(argv[i], "--bits") && i + 1 < argc)
            so.quant_bits = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--rounds") && i + 1 < argc)
            po.round_fraction = atof(argv[++i]);  /* 0: one collapse at a time */
        else if (!strcmp(argv[i], "--max-error") && i + 1 < argc)
            po.max_error = atof(argv[++i]);  /* 0: no limit (the seeds' small meshes split down to a few vertices) */
        else if (!strcmp(argv[i], "--base") && i + 1 < argc)
            want_base = argv[++i];  /* "V/F": the base mesh must be exactly that */
        else if (!strcmp(argv[i], "--base-max") && i + 1 < argc)
            base_max = atol(argv[++i]);  /* the base mesh has at most this many vertices */
        else
            file = argv[i];
    }
    pm_test_mesh in = {0};
    char err[256];
    if (gen ? pm_test_mesh_make(gen, &in) : !file || srv_pm_load(file, &in.xyz, want_rgb ? &in.rgb : NULL, &in.nv, &in.tris, &in.nf, err, sizeof err)) {
        fprintf(stderr, "pm_check: cannot load %s\n", gen ? gen : file ? file : "(nothing)");
        printf("RESULT: 0 passed, 1 failed\n");
        return 1;
    }
    snprintf(g_name, sizeof g_name, "%s/batch %u/%d bits/%s/rounds %g%s", gen ? gen : file, so.batch_vertices,
             so.quant_bits,
             so.position_coding == LUMO_PMESH_POS_CODED       ? "residuals in the range code"
             : so.position_coding == LUMO_PMESH_POS_PREDICTED ? "residuals in Draco payloads"
                                                              : "absolute",
             po.round_fraction,
             so.fan_rank_escape ? "/fans explicit" : "");
    if (so.lattice >= 0)
        snprintf(g_name + strlen(g_name), sizeof g_name - strlen(g_name), "/lattice %s", so.lattice ? "on" : "off");
    srv_pm pm;
    uint8_t *s = NULL;
    size_t len = 0;
    int built = !srv_pm_build_albedo(in.xyz, in.rgb, in.nv, in.tris, in.nf, &po, &pm);
    snprintf(err, sizeof err, "%u -> %u vertices (%u welded), %u faces (%u dropped), base %u/%u, seed %u/%u",
             in.nv, built ? pm.vertices : 0, built ? pm.welded : 0, built ? pm.faces : 0,
             built ? pm.dropped_faces : 0, built ? pm.base_vertices : 0, built ? pm.base_faces : 0,
             built ? pm.seed_vertices : 0, built ? pm.seed_faces : 0);
    check(built, "half-edge collapse build", err);
    if (built && want_base) {
        char got[32];
        snprintf(got, sizeof got, "%u/%u", pm.base_vertices, pm.base_faces);
        check(!strcmp(got, want_base), "base mesh keeps the shape", got);
    }
    if (built && base_max >= 0) {
        snprintf(err, sizeof err, "%u base vertices of %u, at most %ld", pm.base_vertices, pm.vertices, base_max);
        check(pm.base_vertices <= (uint32_t)base_max, "base mesh small (holes close)", err);
    }
    if (built) {
        check_all_levels(&pm);
        if (po.seed)
            check_seed_levels(&in, &po, &pm);
        lumo_pmesh_header sh;
        int streamed = !srv_pm_stream_build(&pm, &so, &s, &len, NULL, NULL) &&
                       !lumo_pmesh_read_header(s, len, &sh);
        snprintf(err, sizeof err, "%zu bytes, %.2f bits/triangle", len, pm.faces ? 8.0 * len / pm.faces : 0);
        check(streamed, "stream written", err);
        if (streamed && po.round_fraction > 0 && pm.vertices > 1000 && so.batch_vertices >= 100) {
            /* Rounds sort each round's splits by parent: the scan of
             * eligible vertices must cost far below w(n) (~13-19 bits on
             * the dragons). */
            double pb = st.splits ? (double)st.parent_bits / st.splits : 99;
            snprintf(err, sizeof err, "%.2f bits per split vertex (w(n) = %u)", pb,
                     lumo_pmesh_field_bits(pm.vertices));
            check(pb < 6.0, "lookup-table parents coded as increasing runs", err);
        }
        if (streamed && !so.quant_bits) {
            /* precision per mesh: the fewest bits whose step is at most
             * 1/EDGE_STEPS of the median edge (docs/progressive-mesh.md §2.1) */
            int b = (int)sh.quant_bits;
            double range, edge = srv_pm_median_edge(&pm);
            float rf;
            memcpy(&rf, &sh.range_bits, 4);
            range = rf;
            int fine = b == SRV_PM_MAX_AUTO_BITS || range / ((1 << b) - 1) <= 1.0001 * edge / SRV_PM_EDGE_STEPS;
            int fewest = b == SRV_PM_MIN_AUTO_BITS || range / ((1 << (b - 1)) - 1) > 0.9999 * edge / SRV_PM_EDGE_STEPS;
            snprintf(err, sizeof err, "%d bits, step %.3g, median edge %.3g", b, range / ((1 << b) - 1), edge);
            check(fine && fewest, "position bits from the median edge", err);
        }
        if (streamed && want_lattice >= 0) {
            /* per mesh (auto): copies where the mesh's coordinates repeat
             * on lattice lines, none where they would cost */
            snprintf(err, sizeof err, "header flags 0x%02x", sh.flags);
            check(!(sh.flags & LUMO_PMESH_LATTICE) == !want_lattice, "lattice copies chosen per mesh", err);
        }
        if (streamed && dump) {
            FILE *f = fopen(dump, "wb");
            check(f && fwrite(s, 1, len, f) == len && !fclose(f), "stream saved", dump);
        }
        if (streamed) {
            float range;
            memcpy(&range, &sh.range_bits, 4);
            double step = range / ((1 << sh.quant_bits) - 1) + 2.0 / 65536;  /* the stream's own bits */
            srv_pm_client cl;
            check_client(&pm, s, len, step, &cl);
            lumo_pmesh_view v;
            lumo_pmesh_get_view(&cl.pm, &v);
            check_full_level(&in, &pm, &v, step);
            srv_pm_client_close(&cl);
            check_corruption(&pm, s, len, step);
            if (pm.vertices <= 2500)
                check_rewind(&pm, s, len, step);
        }
    }
    free(s);
    srv_pm_free(&pm);
    pm_test_mesh_free(&in);
    printf("RESULT: %d passed, %d failed\n", g_pass, g_fail);
    return g_fail != 0;
}
