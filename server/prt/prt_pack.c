/* prt_pack.c — PRTV and PRTL chunks (prt/prt_pack.h; docs/package-format.md). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "lumo/prt.h"
#include "lumo/wire.h"
#include "package/package_write.h"
#include "pm/pm.h"
#include "prt/prt_pack.h"
#include "prt/sh.h"

/* v as Q1.14, or -1 when it does not fit. */
static int q14(double v, int16_t *out)
{
    double r = floor(v * 16384.0 + 0.5);
    if (!(r >= -32768.0 && r <= 32767.0))
        return -1;
    *out = (int16_t)r;
    return 0;
}

static int put_q14(uint8_t *p, double v)
{
    int16_t q;
    if (q14(v, &q))
        return -1;
    lumo_wire_put_le16(p, (uint16_t)q);
    return 0;
}

lumo_status srv_prt_encode(const srv_cpca *c, int order, const uint32_t *pass, uint8_t **out, size_t *len)
{
    if (c->k > LUMO_PRT_MAX_CLUSTERS || c->k > 65535 || c->npc > LUMO_PRT_MAX_COMPONENTS)
        return LUMO_ERR_LIMIT;
    if (order < 1 || order > LUMO_PRT_MAX_ORDER || c->dim != order * order)
        return LUMO_ERR_ARG;
    size_t cb = lumo_prt_cluster_bytes((unsigned)order, (unsigned)c->npc), vb = lumo_prt_vertex_bytes((unsigned)c->npc);
    size_t n = LUMO_PRT_HEADER_SIZE + (size_t)c->k * (cb + 2u) + (size_t)c->n * vb;
    uint8_t *b = calloc(1, n), *p;
    int bad = 0;
    if (!b)
        return LUMO_ERR_NOMEM;
    b[0] = LUMO_PRT_VERSION, b[1] = (uint8_t)order, b[2] = (uint8_t)c->npc, b[3] = 0;
    lumo_wire_put_le32(b + 4, (uint32_t)c->k);
    lumo_wire_put_le32(b + 8, c->n);
    p = b + LUMO_PRT_HEADER_SIZE;
    for (int k = 0; k < c->k; k++) {
        for (int d = 0; d < c->dim; d++, p += 2)
            bad |= put_q14(p, c->mean[k * c->dim + d]);
        for (int j = 0; j < c->npc; j++)
            for (int d = 0; d < c->dim; d++, p += 2)
                bad |= put_q14(p, c->basis[((size_t)k * (size_t)c->npc + (size_t)j) * (size_t)c->dim + (size_t)d]);
    }
    for (int k = 0; k < c->k; k++, p += 2)
        lumo_wire_put_le16(p, (uint16_t)(pass ? pass[k] : (uint32_t)k));
    for (uint32_t v = 0; v < c->n; v++) {
        lumo_wire_put_le16(p, (uint16_t)c->cluster[v]);
        p += 2;
        for (int j = 0; j < c->npc; j++, p += 2)
            bad |= put_q14(p, c->weight[(size_t)v * (size_t)c->npc + (size_t)j]);
    }
    if (bad) {
        free(b);
        return LUMO_ERR_RANGE;
    }
    *out = b, *len = n;
    return LUMO_OK;
}

static double get_q14(const uint8_t *p)
{
    return (int16_t)lumo_wire_le16(p) / 16384.0;
}

double srv_prt_quant_sq_error(const srv_cpca *c, const uint8_t *chunk, size_t len)
{
    size_t cb = lumo_prt_cluster_bytes((unsigned)chunk[1], (unsigned)c->npc), vb = lumo_prt_vertex_bytes((unsigned)c->npc);
    const uint8_t *cl = chunk + LUMO_PRT_HEADER_SIZE, *vx = cl + (size_t)c->k * (cb + 2u);
    double r[SRV_SH_MAX_COEFFS], s = 0.0;
    (void)len;
    for (uint32_t v = 0; v < c->n; v++) {
        const uint8_t *vr = vx + (size_t)v * vb, *m = cl + (size_t)lumo_wire_le16(vr) * cb;
        srv_cpca_reconstruct(c, v, r);
        for (int d = 0; d < c->dim; d++) {
            double q = get_q14(m + 2 * d);
            for (int j = 0; j < c->npc; j++)
                q += get_q14(vr + 2 + 2 * j) * get_q14(m + 2 * ((size_t)(j + 1) * (size_t)c->dim + (size_t)d));
            s += (q - r[d]) * (q - r[d]);
        }
    }
    return c->n ? s / c->n : 0.0;
}

void srv_prt_default_options(srv_prt_options *o)
{
    srv_prt_transfer_default_opts(&o->transfer);
    srv_cpca_default_opts(&o->cpca);
    o->registers = 256;
}

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* Chapter 5's metrics of a finished CPCA and its chunk. */
static void measure(const srv_pm *pm, const srv_cpca *c, const double *t, const uint32_t *pass, uint32_t npass,
                    const uint8_t *chunk, size_t len, srv_prt_stats *st)
{
    st->vertices = pm->vertices, st->triangles = pm->faces, st->clusters = (uint32_t)c->k;
    st->passes = pass ? npass : (uint32_t)c->k;
    st->iterations = c->iterations, st->cluster_seconds = c->cluster_seconds;
    st->overdraw = srv_cpca_overdraw(c, pm->tris, pm->faces, NULL);
    st->overdraw_passes = srv_cpca_overdraw(c, pm->tris, pm->faces, pass);
    st->sq_error = srv_cpca_sq_error(c, t);
    st->quant_sq_error = srv_prt_quant_sq_error(c, chunk, len);
    st->bytes = len;
}

static lumo_status transfer_cpca(const srv_pm *pm, const srv_prt_options *o, uint8_t **chunk, size_t *len,
                                 srv_prt_stats *stats, char *err, size_t errlen)
{
    srv_prt_mesh m = {.nverts = pm->vertices, .ntris = pm->faces, .xyz = pm->xyz, .tris = pm->tris,
                      .albedo = pm->albedo};
    int nc = o->transfer.order * o->transfer.order;
    double *t = malloc((size_t)pm->vertices * (size_t)nc * sizeof *t);
    srv_cpca c;
    if (!t) {
        snprintf(err, errlen, "prt: out of memory");
        return LUMO_ERR_NOMEM;
    }
    double t0 = now_s();
    lumo_status st = srv_prt_transfer(&m, &o->transfer, t, err, errlen);
    if (stats)
        stats->transfer_seconds = now_s() - t0;
    srv_cpca_opts co = o->cpca;
    if (!st && (uint32_t)co.clusters > pm->vertices)
        co.clusters = (int)pm->vertices;
    if (!st && (st = srv_cpca_build(t, pm->vertices, nc, pm->xyz, &co, &c)) != LUMO_OK)
        snprintf(err, errlen, "prt: clustered PCA failed (%s)", lumo_strerror(st));
    if (!st) {
        uint32_t *pass = o->registers > 0 ? malloc((size_t)c.k * sizeof *pass) : NULL, npass = 0;
        if (pass && !(npass = srv_cpca_superclusters(&c, pm->tris, pm->faces, srv_cpca_per_pass(nc, c.npc, o->registers), pass)))
            free(pass), pass = NULL;
        if ((st = srv_prt_encode(&c, o->transfer.order, pass, chunk, len)) != LUMO_OK)
            snprintf(err, errlen, "prt: cannot encode the transfer (%s)", lumo_strerror(st));
        else if (stats)
            measure(pm, &c, t, pass, npass, *chunk, *len, stats);
        free(pass);
        srv_cpca_free(&c);
    }
    free(t);
    return st;
}

lumo_status srv_prt_pack(struct srv_pkg_writer *w, const float *xyz, const uint8_t *albedo, uint32_t nv,
                         const uint32_t *tris, uint32_t nf, const srv_prt_options *o, srv_prt_stats *stats,
                         char *err, size_t errlen)
{
    srv_pm pm;
    uint8_t *chunk = NULL;
    size_t len = 0;
    lumo_status st = srv_pm_build_albedo(xyz, albedo, nv, tris, nf, NULL, &pm);
    if (st) {
        snprintf(err, errlen, "prt: cannot build the progressive mesh");
        return st;
    }
    st = transfer_cpca(&pm, o, &chunk, &len, stats, err, errlen);
    if (!st && (st = srv_pkgw_add(w, SRV_PRT_PKG_PRTV, chunk, len)) != LUMO_OK)
        snprintf(err, errlen, "prt: cannot add the chunk (%s)", lumo_strerror(st));
    free(chunk);
    srv_pm_free(&pm);
    return st;
}

void srv_prt_env_project(const float *rgb, int w, int h, int order, double *out)
{
    int nc = order * order;
    double y[SRV_SH_MAX_COEFFS];
    memset(out, 0, 3u * (size_t)nc * sizeof *out);
    for (int r = 0; r < h; r++) {
        double th = M_PI * (r + 0.5) / h, st = sin(th);
        double dw = (M_PI / h) * (2.0 * M_PI / w) * st;   /* solid angle of a texel */
        for (int x = 0; x < w; x++) {
            double ph = 2.0 * M_PI * (x + 0.5) / w, d[3] = {st * cos(ph), cos(th), st * sin(ph)};
            const float *px = &rgb[3 * ((size_t)r * (size_t)w + (size_t)x)];
            srv_sh_eval(order, d, y);
            for (int c = 0; c < 3; c++)
                for (int i = 0; i < nc; i++)
                    out[c * nc + i] += px[c] * y[i] * dw;
        }
    }
}

lumo_status srv_prt_encode_light(const double *coeffs, int order, uint8_t **out, size_t *len)
{
    int nc = order * order;
    if (order < 1 || order > LUMO_PRT_MAX_ORDER)
        return LUMO_ERR_ARG;
    uint8_t *b = calloc(1, 4u + 12u * (size_t)nc);
    if (!b)
        return LUMO_ERR_NOMEM;
    b[0] = (uint8_t)order;
    for (int i = 0; i < 3 * nc; i++) {
        double q = floor(coeffs[i] * 65536.0 + 0.5);
        if (!(q >= -2147483648.0 && q <= 2147483647.0)) {
            free(b);
            return LUMO_ERR_RANGE;
        }
        lumo_wire_put_le32(b + 4 + 4 * i, (uint32_t)(int32_t)q);
    }
    *out = b, *len = 4u + 12u * (size_t)nc;
    return LUMO_OK;
}
