/* vsl_updates.c — the compacted update log behind the updates channel
 * (vsl_updates.h, docs/protocol.md §9). */
#include <stdlib.h>
#include <string.h>
#include "lumo/net.h"
#include "vsl/vsl_updates.h"

/* Trailing zero bits of x, capped (0 counts as the cap: on every lattice). */
static uint32_t tz(uint32_t x)
{
    uint32_t n = 0;
    while (n < 16 && !(x & 1u))
        x >>= 1, n++;
    return n;
}

lumo_status srv_vsl_updates_init(srv_vsl_updates *u, const int dims[3])
{
    memset(u, 0, sizeof *u);
    for (int a = 0; a < 3; a++)
        u->dims[a] = (uint16_t)dims[a];
    u->nverts = (uint32_t)dims[0] * (uint32_t)dims[1] * (uint32_t)dims[2];
    u->next = 1;
    u->pos = calloc(u->nverts, sizeof *u->pos);
    u->order = calloc(u->nverts, sizeof *u->order);
    u->coarse = calloc(u->nverts, sizeof *u->coarse);
    u->mark = calloc(u->nverts, 1);
    u->scratch = calloc(u->nverts, sizeof *u->scratch);
    u->e = calloc((size_t)u->nverts * LUMO_IVG_AXES, sizeof *u->e);
    if (!u->pos || !u->order || !u->coarse || !u->mark || !u->scratch || !u->e) {
        srv_vsl_updates_free(u);
        return LUMO_ERR_NOMEM;
    }
    for (uint32_t v = 0; v < u->nverts; v++) {
        uint32_t i = v % u->dims[0], j = v / u->dims[0] % u->dims[1], k = v / u->dims[0] / u->dims[1];
        uint32_t a = tz(i), b = tz(j), c = tz(k);
        u->coarse[v] = a < b ? (a < c ? a : c) : (b < c ? b : c);
    }
    pthread_mutex_init(&u->mu, NULL);
    return LUMO_OK;
}

void srv_vsl_updates_free(srv_vsl_updates *u)
{
    if (u->pos)
        pthread_mutex_destroy(&u->mu);
    free(u->pos), free(u->order), free(u->coarse), free(u->mark), free(u->scratch), free(u->e);
    memset(u, 0, sizeof *u);
}

/* Coarse first, then by index (ctx: the log). */
static int cmp_coarse(const void *a, const void *b, void *ctx)
{
    const uint32_t *coarse = ctx;
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    if (coarse[x] != coarse[y])
        return coarse[x] > coarse[y] ? -1 : 1;
    return (x > y) - (x < y);
}

static void encode(srv_vsl_updates *u, uint32_t v, const double *I)
{
    for (int h = 0; h < LUMO_IVG_AXES; h++) {
        float m[3][3];
        for (int ch = 0; ch < 3; ch++)
            for (int c = 0; c < 3; c++)
                m[ch][c] = (float)I[(size_t)v * SRV_VSL_IVG_VALUES + (size_t)((h * 3 + ch) * 3 + c)];
        srv_ivg_compress(m, (lumo_ivg_axis)h, &u->e[(size_t)v * LUMO_IVG_AXES + (size_t)h]);
    }
}

void srv_vsl_updates_publish(srv_vsl_updates *u, const double *I, const uint32_t *dirty, size_t n)
{
    uint32_t kept = 0, m = 0;
    if (!n)
        return;
    pthread_mutex_lock(&u->mu);
    for (size_t i = 0; i < n; i++)
        if (dirty[i] < u->nverts && !u->mark[dirty[i]])
            u->mark[dirty[i]] = 1, u->scratch[m++] = dirty[i];
    for (uint32_t i = 0; i < u->n; i++)   /* drop them from where they were */
        if (!u->mark[u->order[i]])
            u->order[kept++] = u->order[i];
    qsort_r(u->scratch, m, sizeof *u->scratch, cmp_coarse, u->coarse);
    for (uint32_t i = 0; i < m; i++) {
        uint32_t v = u->scratch[i];
        encode(u, v, I);
        u->pos[v] = u->next++;
        u->order[kept++] = v;
        u->mark[v] = 0;
    }
    u->n = kept;
    u->published += m;
    pthread_mutex_unlock(&u->mu);
}

void srv_vsl_updates_set_poses(srv_vsl_updates *u, const lumo_net_pose *p, uint32_t n)
{
    if (n > LUMO_NET_MAX_POSES)
        n = LUMO_NET_MAX_POSES;
    pthread_mutex_lock(&u->mu);
    if (n != u->nposes || memcmp(p, u->poses, n * sizeof *p)) {
        memcpy(u->poses, p, n * sizeof *p);
        u->nposes = n;
        u->poses_pos = u->next;
    }
    pthread_mutex_unlock(&u->mu);
}

uint32_t srv_vsl_updates_position(srv_vsl_updates *u)
{
    pthread_mutex_lock(&u->mu);
    uint32_t p = u->next - 1;
    pthread_mutex_unlock(&u->mu);
    return p;
}

/* The first index of order whose position is past cursor. */
static uint32_t first_after(const srv_vsl_updates *u, uint32_t cursor)
{
    uint32_t lo = 0, hi = u->n;
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2;
        if (u->pos[u->order[mid]] > cursor)
            hi = mid;
        else
            lo = mid + 1;
    }
    return lo;
}

/* One DATA frame at out of records order[at .. at + k). */
static size_t put_frame(const srv_vsl_updates *u, uint32_t at, uint32_t k, uint32_t first, uint8_t form,
                        uint8_t *out, size_t cap)
{
    srv_ivg_writer w;
    size_t written = 0;
    /* the bundle header lands under DATA's head, the records where DATA wants them */
    uint8_t *bundle = out + LUMO_NET_HEADER + LUMO_NET_DATA_HEAD - 16;
    srv_ivg_writer_begin(&w, bundle, cap - (size_t)(bundle - out), (lumo_ivg_form)form, u->dims);
    for (uint32_t i = 0; i < k; i++) {
        uint32_t v = u->order[at + i];
        srv_ivg_writer_add(&w, v, &u->e[(size_t)v * LUMO_IVG_AXES]);
    }
    size_t blen = srv_ivg_writer_finish(&w);
    if (!blen)
        return 0;
    lumo_net_data d = {LUMO_NET_UPDATES, form, 0, first, u->pos[u->order[at + k - 1]], k, bundle + 16,
                       (uint32_t)(blen - 16)};
    return lumo_net_data_encode(&d, out, cap, &written) ? 0 : written;
}

lumo_status srv_vsl_updates_answer(srv_vsl_updates *u, uint32_t cursor, uint32_t amount, uint8_t form,
                                   uint32_t max_payload, uint8_t **buf, size_t *len)
{
    size_t rec = srv_ivg_bundle_bytes((lumo_ivg_form)form, 1, 0) - 16;
    if (max_payload < LUMO_NET_DATA_HEAD + rec)
        return LUMO_ERR_LIMIT;
    uint32_t per = (uint32_t)((max_payload - LUMO_NET_DATA_HEAD) / rec);
    pthread_mutex_lock(&u->mu);
    uint32_t at = first_after(u, cursor), k = u->n - at < amount ? u->n - at : amount;
    uint32_t frames = (k + per - 1) / per;
    int poses = u->nposes && u->poses_pos > cursor;
    size_t cap = (size_t)frames * (LUMO_NET_OVERHEAD + LUMO_NET_DATA_HEAD) + (size_t)k * rec + 64 +
                 (poses ? LUMO_NET_OVERHEAD + 4 + (size_t)u->nposes * LUMO_NET_POSE_BYTES : 0);
    uint8_t *out = malloc(cap);
    size_t n = 0;
    lumo_status st = out ? LUMO_OK : LUMO_ERR_NOMEM;
    for (uint32_t first = cursor; !st && k; ) {
        uint32_t now = k < per ? k : per;
        size_t w = put_frame(u, at, now, first, form, out + n, cap - n);
        if (!w)
            st = LUMO_ERR_NOMEM;
        first = u->pos[u->order[at + now - 1]];
        n += w, at += now, k -= now;
    }
    size_t w = 0;
    if (!st && poses && (st = lumo_net_poses_encode(u->poses, u->nposes, out + n, cap - n, &w)) == LUMO_OK)
        n += w;
    pthread_mutex_unlock(&u->mu);
    lumo_net_end e = {LUMO_NET_UPDATES, 0};
    if (!st && (st = lumo_net_end_encode(&e, out + n, cap - n, &w)) == LUMO_OK)
        n += w;
    if (st) {
        free(out);
        return st;
    }
    *buf = out;
    *len = n;
    return LUMO_OK;
}
