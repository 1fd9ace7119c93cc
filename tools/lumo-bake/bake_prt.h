/* bake_prt.h — lumo-bake's PRT options (--prt, --prt-env) and the chunks
 * they add (docs/prt.md, docs/server.md). */
#ifndef BAKE_PRT_H
#define BAKE_PRT_H

#include <stddef.h>
#include "package/package_write.h"
#include "prt/prt_pack.h"

typedef struct bake_prt {
    int on;
    srv_prt_options o;
    const char *env;    /* equirectangular PNG, or NULL */
} bake_prt;

/* "ORDER[,clusters=K][,components=P][,alpha=A][,bounces=B][,strata=S][,registers=R]":
 * 0, or -1 with the refusal in err naming the setting and its value
 * ("--prt clusters 1.5: not an integer"). */
int bake_prt_parse(bake_prt *p, const char *spec, int threads, int progress, char *err, size_t errlen);

/* After the PMSH chunk of mesh (xyz, albedo, tris): its PRTV chunk, and a
 * line of seed 003's metrics (time, overdraw, squared error) on stderr. */
int bake_prt_mesh(const bake_prt *p, srv_pkg_writer *w, const float *xyz, const uint8_t *albedo, uint32_t nv,
                  const uint32_t *tris, uint32_t nf, char *err, size_t errlen);

/* The environment's PRTL chunk when --prt-env was given. */
int bake_prt_env(const bake_prt *p, srv_pkg_writer *w, char *err, size_t errlen);

#endif
