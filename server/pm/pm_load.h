/*
 * pm/pm_load.h — triangle soups in and out for the progressive-mesh
 * tools: any file assimp reads (all meshes merged), and binary PLY out.
 */
#ifndef SRV_PM_LOAD_H
#define SRV_PM_LOAD_H

#include <stddef.h>
#include <stdint.h>
#include "lumo/status.h"

/* Positions (metres, 3 per vertex) and triangles, malloc'ed; with rgb not
 * NULL also the per-vertex albedo as 3 bytes (0..255) per vertex. LUMO_OK,
 * or with a one-line reason in err srv_import_file's status,
 * LUMO_ERR_NOMEM, or LUMO_ERR_LIMIT (2^30 vertices or faces or more). */
lumo_status srv_pm_load(const char *path, float **xyz, uint8_t **rgb, uint32_t *nv, uint32_t **tris,
                        uint32_t *nf, char *err, size_t errlen);

/* Binary little-endian PLY: float x y z, uchar-count int indices. LUMO_OK,
 * or LUMO_ERR_IO when the file cannot be written. */
lumo_status srv_pm_write_ply(const char *path, const float *xyz, uint32_t nv, const uint32_t *tris,
                             uint32_t nf);

#endif
