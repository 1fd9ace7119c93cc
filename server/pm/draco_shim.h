/*
 * pm/draco_shim.h — the one C door to libdraco's C++ encoder.
 *
 * The progressive-mesh stream (docs/progressive-mesh.md) carries every
 * batch's vertex positions as a Draco point-cloud bitstream, so stock Draco
 * tools can read each payload. The encoder settings are fixed in one place
 * (srv_draco_settings) so the stream can move to better compression as the
 * client decoder learns more of Draco.
 *
 * Buffers returned through `out` are malloc'ed; the caller frees them.
 * Functions return LUMO_OK, or on failure LUMO_ERR_NOMEM (out of memory),
 * LUMO_ERR_ARG (libdraco refused to encode: its message on stderr) or
 * LUMO_ERR_CORRUPT (libdraco cannot decode the buffer: its message on
 * stderr; or the buffer has no positions).
 */
#ifndef SRV_DRACO_SHIM_H
#define SRV_DRACO_SHIM_H

#include <stddef.h>
#include <stdint.h>
#include "lumo/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A quantization grid shared by every payload of one stream: a position p is
 * stored as round((p - origin) / range * (2^bits - 1)) per axis. */
typedef struct srv_draco_quant {
    int   bits;        /* 1..30 (Draco's limit); 12 is the paper-size default */
    float origin[3];   /* metres: the low corner of the grid */
    float range;       /* metres: the cube's edge length, > 0 */
} srv_draco_quant;

/* A grid covering [lo, hi] on every axis whose origin and range survive
 * libdraco's option storage unchanged (it keeps floats as std::to_string
 * text: six decimals), so the stream header can state the exact binary32
 * values every payload carries. Requires coordinates well above 1e-6. */
void srv_draco_grid(const float lo[3], const float hi[3], int bits, srv_draco_quant *q);

/* The encoder choice for point payloads. `speed` is Draco's 0..10 (10 - cl);
 * `method` 0 = sequential (keeps point order: required by the stream). */
typedef struct srv_draco_settings {
    int speed;
    int method;
} srv_draco_settings;

/* The settings the stream uses today (sequential, speed 5). */
srv_draco_settings srv_draco_default_settings(void);

/* Encode n points (xyz, metres) as a Draco point cloud with one quantized
 * POSITION attribute on grid q, plus a COLOR uint8 x3 attribute when rgb is
 * not NULL (3 bytes per point). Point order is preserved. */
lumo_status srv_draco_encode_points(const float *xyz, const uint8_t *rgb, size_t n,
                                    const srv_draco_quant *q, srv_draco_settings s, uint8_t **out,
                                    size_t *out_len);

/* Encode n points carrying one GENERIC int32 attribute of `comps`
 * components (values: n * comps), no prediction (the caller predicts),
 * entropy coded by libdraco, plus COLOR as above when rgb is not NULL.
 * Point order is preserved. */
lumo_status srv_draco_encode_ints(const int32_t *values, const uint8_t *rgb, size_t n, int comps,
                                  srv_draco_settings s, uint8_t **out, size_t *out_len);

/* Encode a triangle mesh single-shot (for size comparisons): positions
 * quantized on grid q, Draco compression level cl (0..10, as draco_encoder
 * -cl), EdgeBreaker unless cl == 0 (sequential). */
lumo_status srv_draco_encode_mesh(const float *xyz, size_t nv, const uint32_t *tris, size_t nt,
                                  const srv_draco_quant *q, int cl, uint8_t **out, size_t *out_len);

/* Decode a point cloud or mesh with libdraco (server tools and tests only):
 * positions dequantized to metres, malloc'ed into *xyz (3 per point). */
lumo_status srv_draco_decode_points(const uint8_t *buf, size_t len, float **xyz, size_t *n);

#ifdef __cplusplus
}
#endif

#endif /* SRV_DRACO_SHIM_H */
