/*
 * package_write.h — building .lumo packages (docs/package-format.md); the
 * client reads them with lumo/package.h.
 */
#ifndef LUMO_SERVER_PACKAGE_WRITE_H
#define LUMO_SERVER_PACKAGE_WRITE_H

#include <stddef.h>
#include <stdint.h>
#include "bake/bake.h"
#include "scene/scene.h"

/* A growable little-endian byte buffer. */
typedef struct lumo_buf {
    uint8_t *p;
    size_t   len, cap;
    int      failed;    /* sticky out-of-memory flag */
} lumo_buf;

void lumo_buf_put(lumo_buf *b, const void *data, size_t n);
void lumo_buf_u16(lumo_buf *b, uint32_t v);
void lumo_buf_u32(lumo_buf *b, uint32_t v);
void lumo_buf_f32(lumo_buf *b, float v);
void lumo_buf_vec3(lumo_buf *b, vec3 v);
void lumo_buf_free(lumo_buf *b);

typedef struct lumo_pkg_writer {
    struct { uint32_t type; lumo_buf data; } *chunks;
    size_t n, cap;
    int    failed;
} lumo_pkg_writer;

void lumo_pkgw_init(lumo_pkg_writer *w);
void lumo_pkgw_free(lumo_pkg_writer *w);
/* Append a chunk (the bytes are copied). 0 or -1. */
int lumo_pkgw_add(lumo_pkg_writer *w, uint32_t type, const void *data, size_t len);
/* The whole package in one malloc'ed buffer. 0 or -1. */
int lumo_pkgw_serialize(const lumo_pkg_writer *w, uint8_t **out, size_t *len);
int lumo_pkgw_write_file(const lumo_pkg_writer *w, const char *path, char *err, size_t errlen);

/* Scene chunks: INFO, and one raw MESH per mesh when raw_meshes (the
 * progressive-mesh stream, PMSH, is written by lumo_pm_pack instead or
 * beside). 0 or -1. */
int lumo_pack_scene(lumo_pkg_writer *w, const lumo_scene *s, int raw_meshes);
/* IVG chunks: IVGD, then the bundle in both wire forms (IVGQ, IVGF) made by
 * the IVG encoder (server/package/ivg_encode.c). 0 or -1 with err. */
int lumo_pack_ivg(lumo_pkg_writer *w, const lumo_bake_result *r, uint32_t spp, uint64_t seed,
                  char *err, size_t errlen);

#endif
