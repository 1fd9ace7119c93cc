/* bake_prt.c — lumo-bake --prt: per mesh a PRTV chunk after its PMSH
 * (transfer of the same progressive vertices, CPCA, Q1.14), and with
 * --prt-env the environment's SH lighting as a PRTL chunk. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "lumo_host/options.h"
#include "lumo_host/png_io.h"
#include "lumo/prt.h"
#include "bake_prt.h"

/* One "key=value" of the spec, each value through the strict option
 * parser (integers whole, numbers finite, both in range): the message
 * names the spec, the key and the value. */
typedef struct prt_key {
    const char *key;
    int         is_int;
    double      lo, hi;
} prt_key;

static const prt_key k_keys[] = {
    {"clusters", 1, 1, LUMO_PRT_MAX_CLUSTERS}, {"components", 1, 0, LUMO_PRT_MAX_COMPONENTS},
    {"alpha", 0, 0, 1e6},                      {"bounces", 1, 0, 8},
    {"strata", 1, 2, 256},                     {"registers", 1, 0, 65536},
};

static void set_key(bake_prt *p, int k, double v)
{
    switch (k) {
    case 0: p->o.cpca.clusters = (int)v; break;
    case 1: p->o.cpca.components = (int)v; break;
    case 2: p->o.cpca.alpha = v; break;
    case 3: p->o.transfer.bounces = (int)v; break;
    case 4: p->o.transfer.strata = (int)v; break;
    default: p->o.registers = (int)v; break;
    }
}

static int take(bake_prt *p, const char *tok, char *err, size_t errlen)
{
    const char *eq = strchr(tok, '=');
    char opt[64];
    size_t n = eq ? (size_t)(eq - tok) : strlen(tok);
    for (int k = 0; k < (int)(sizeof k_keys / sizeof k_keys[0]); k++) {
        int iv;
        double v;
        if (strlen(k_keys[k].key) != n || strncmp(tok, k_keys[k].key, n))
            continue;
        snprintf(opt, sizeof opt, "--prt %s", k_keys[k].key);
        if (!eq) {
            snprintf(err, errlen, "--prt: '%.40s' needs a value (%s=N)", tok, k_keys[k].key);
            return -1;
        }
        if (k_keys[k].is_int ? host_opt_int(opt, eq + 1, (int)k_keys[k].lo, (int)k_keys[k].hi, &iv, err, errlen)
                             : host_opt_double(opt, eq + 1, k_keys[k].lo, k_keys[k].hi, &v, err, errlen))
            return -1;
        set_key(p, k, k_keys[k].is_int ? iv : v);
        return 0;
    }
    snprintf(err, errlen, "--prt: unknown setting '%.*s' (clusters, components, alpha, bounces, strata, registers)",
             (int)(n > 40 ? 40 : n), tok);
    return -1;
}

int bake_prt_parse(bake_prt *p, const char *spec, int threads, int progress, char *err, size_t errlen)
{
    char buf[256], *save = NULL;
    int order;
    if (strlen(spec) >= sizeof buf) {
        snprintf(err, errlen, "--prt: a spec of %zu characters, at most %zu", strlen(spec), sizeof buf - 1);
        return -1;
    }
    snprintf(buf, sizeof buf, "%s", spec);
    srv_prt_default_options(&p->o);
    p->o.transfer.bounces = 1;
    p->o.transfer.threads = p->o.cpca.threads = threads;
    p->o.transfer.progress = progress;
    char *tok = strtok_r(buf, ",", &save);
    if (host_opt_int("--prt ORDER", tok ? tok : "", 1, LUMO_PRT_MAX_ORDER, &order, err, errlen))
        return -1;
    p->o.transfer.order = order;
    while ((tok = strtok_r(NULL, ",", &save)))
        if (take(p, tok, err, errlen))
            return -1;
    p->on = 1;
    return 0;
}

int bake_prt_mesh(const bake_prt *p, srv_pkg_writer *w, const float *xyz, const uint8_t *albedo, uint32_t nv,
                  const uint32_t *tris, uint32_t nf, char *err, size_t errlen)
{
    srv_prt_stats st;
    if (!p->on)
        return 0;
    if (srv_prt_pack(w, xyz, albedo, nv, tris, nf, &p->o, &st, err, errlen))
        return -1;
    fprintf(stderr, "lumo-bake: prt: %u vertices, order %d: transfer %.2f s; %u clusters (%d LBG passes, %.2f s), "
                    "overdraw %.4f, %.4f in %u passes; squared error %.3e (Q1.14 adds %.1e); PRTV %zu bytes\n",
            st.vertices, p->o.transfer.order, st.transfer_seconds, st.clusters, st.iterations, st.cluster_seconds,
            st.overdraw, st.overdraw_passes, st.passes, st.sq_error, st.quant_sq_error, st.bytes);
    return 0;
}

int bake_prt_env(const bake_prt *p, srv_pkg_writer *w, char *err, size_t errlen)
{
    uint8_t *rgb, *chunk;
    int iw, ih, order = p->o.transfer.order;
    size_t len;
    double c[3 * LUMO_PRT_MAX_COEFFS];
    if (!p->env)
        return 0;
    if (host_png_read_rgb8(p->env, &rgb, &iw, &ih)) {
        snprintf(err, errlen, "cannot read the environment map %s (an 8-bit PNG of at most 2^26 pixels)", p->env);
        return -1;
    }
    float *f = malloc(3u * (size_t)iw * (size_t)ih * sizeof *f);
    for (size_t i = 0; f && i < 3u * (size_t)iw * (size_t)ih; i++)
        f[i] = rgb[i] / 255.0f;   /* the PNG's values as linear radiance, W/m^2/sr */
    free(rgb);
    if (!f) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    srv_prt_env_project(f, iw, ih, order, c);
    free(f);
    if (srv_prt_encode_light(c, order, &chunk, &len)) {
        snprintf(err, errlen, "the environment map's SH coefficients are beyond Q16.16");
        return -1;
    }
    lumo_status st = srv_pkgw_add(w, SRV_PRT_PKG_PRTL, chunk, len);
    free(chunk);
    if (st)
        snprintf(err, errlen, "cannot add the PRTL chunk (%s)", lumo_strerror(st));
    return st ? -1 : 0;
}
