/*
 * package_write.h — building .lumo packages (docs/package-format.md); the
 * client reads them with lumo/package.h.
 */
#ifndef SRV_PACKAGE_WRITE_H
#define SRV_PACKAGE_WRITE_H

#include <stddef.h>
#include <stdint.h>
#include "bake/bake.h"
#include "lumo/status.h"
#include "scene/scene.h"

/* A growable little-endian byte buffer. */
typedef struct srv_buf {
    uint8_t *p;
    size_t   len, cap;
    int      failed;    /* sticky out-of-memory flag */
} srv_buf;

void srv_buf_put(srv_buf *b, const void *data, size_t n);
void srv_buf_u16(srv_buf *b, uint32_t v);
void srv_buf_u32(srv_buf *b, uint32_t v);
void srv_buf_f32(srv_buf *b, float v);
void srv_buf_vec3(srv_buf *b, vec3 v);
void srv_buf_free(srv_buf *b);

typedef struct srv_pkg_writer {
    struct { uint32_t type; srv_buf data; } *chunks;
    size_t n, cap;
    int    failed;
} srv_pkg_writer;

void srv_pkgw_init(srv_pkg_writer *w);
void srv_pkgw_free(srv_pkg_writer *w);
/* Append a chunk (the bytes are copied). LUMO_OK, LUMO_ERR_LIMIT (more
 * than LUMO_PKG_MAX_CHUNKS chunks, or a chunk of 2 GiB or more) or
 * LUMO_ERR_NOMEM. */
lumo_status srv_pkgw_add(srv_pkg_writer *w, uint32_t type, const void *data, size_t len);
/* The whole package in one malloc'ed buffer. LUMO_OK, LUMO_ERR_LIMIT
 * (4 GiB or more) or LUMO_ERR_NOMEM. */
lumo_status srv_pkgw_serialize(const srv_pkg_writer *w, uint8_t **out, size_t *len);
/* The package into a file (written as PATH.partial, then renamed: never
 * a partial file under PATH): srv_pkgw_serialize's status, or LUMO_ERR_IO
 * when the file cannot be written; a message naming path in err. */
lumo_status srv_pkgw_write_file(const srv_pkg_writer *w, const char *path, char *err,
                                size_t errlen);

/* Scene chunks: INFO, and one raw MESH per mesh when raw_meshes (the
 * progressive-mesh stream, PMSH, is written by srv_pm_pack instead or
 * beside). LUMO_OK, LUMO_ERR_LIMIT (more than LUMO_PKG_MAX_LIGHTS lights,
 * or srv_pkgw_add's limits) or LUMO_ERR_NOMEM. */
lumo_status srv_pack_scene(srv_pkg_writer *w, const srv_scene *s, int raw_meshes);
/* IVG chunks: IVGD, then the bundle in both wire forms (IVGQ, IVGF) made by
 * the IVG encoder (server/package/ivg_encode.c), their records in the
 * stratified streaming order drawn from `seed` (package/ivg_order.h), then
 * IVGS, where each round starts in both. LUMO_OK, or with err srv_pkgw_add's
 * status or the encoder's (LUMO_ERR_NOMEM, LUMO_ERR_RANGE). */
lumo_status srv_pack_ivg(srv_pkg_writer *w, const srv_bake_result *r, uint32_t spp, uint64_t seed,
                         char *err, size_t errlen);

/* ORDR, the recommended interleaving of geometry and lighting, from the
 * PMSH and IVGS chunks already in w (call it last): every base mesh and
 * the IVG's corners first, then a cycle of one batch of every mesh that has
 * more and a lighting step of ceil((R - 1) / B) rounds (B: the most batches
 * a stream has after its base), so that the lighting ends no later than the
 * geometry (docs/package-format.md "ORDR"). LUMO_OK, LUMO_ERR_LIMIT, LUMO_ERR_NOMEM
 * or a stream header's error. */
lumo_status srv_pack_order(srv_pkg_writer *w);

#endif
