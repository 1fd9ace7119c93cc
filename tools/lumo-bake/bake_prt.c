/* bake_prt.c — lumo-bake --prt: per mesh a PRTV chunk after its PMSH
 * (transfer of the same progressive vertices, CPCA, Q1.14), and with
 * --prt-env the environment's SH lighting as a PRTL chunk. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "lumo_host/png_io.h"
#include "lumo/prt.h"
#include "bake_prt.h"

static int kv(const char *tok, const char *key, double lo, double hi, double *out)
{
    size_t n = strlen(key);
    char *end;
    if (strncmp(tok, key, n) || tok[n] != '=')
        return 0;
    *out = strtod(tok + n + 1, &end);
    return *end || !(*out >= lo && *out <= hi) ? -1 : 1;
}

static int take(bake_prt *p, const char *tok)
{
    double v;
    int r;
    if ((r = kv(tok, "clusters", 1, LUMO_PRT_MAX_CLUSTERS, &v)) != 0)
        return r < 0 ? -1 : (p->o.cpca.clusters = (int)v, 0);
    if ((r = kv(tok, "components", 0, LUMO_PRT_MAX_COMPONENTS, &v)) != 0)
        return r < 0 ? -1 : (p->o.cpca.components = (int)v, 0);
    if ((r = kv(tok, "alpha", 0, 1e6, &v)) != 0)
        return r < 0 ? -1 : (p->o.cpca.alpha = v, 0);
    if ((r = kv(tok, "bounces", 0, 8, &v)) != 0)
        return r < 0 ? -1 : (p->o.transfer.bounces = (int)v, 0);
    if ((r = kv(tok, "strata", 2, 256, &v)) != 0)
        return r < 0 ? -1 : (p->o.transfer.strata = (int)v, 0);
    if ((r = kv(tok, "registers", 0, 65536, &v)) != 0)
        return r < 0 ? -1 : (p->o.registers = (int)v, 0);
    return -1;
}

int bake_prt_parse(bake_prt *p, const char *spec, int threads, int progress)
{
    char buf[256], *save = NULL, *end;
    snprintf(buf, sizeof buf, "%s", spec);
    srv_prt_default_options(&p->o);
    p->o.transfer.bounces = 1;
    p->o.transfer.threads = p->o.cpca.threads = threads;
    p->o.transfer.progress = progress;
    char *tok = strtok_r(buf, ",", &save);
    long order = tok ? strtol(tok, &end, 10) : 0;
    if (!tok || *end || order < 1 || order > LUMO_PRT_MAX_ORDER)
        return -1;
    p->o.transfer.order = (int)order;
    while ((tok = strtok_r(NULL, ",", &save)))
        if (take(p, tok))
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
        snprintf(err, errlen, "cannot read the environment map %s (8-bit PNG)", p->env);
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
