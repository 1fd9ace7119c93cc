/*
 * package/ivg_encode.h — the server's half of the Irradiance Vector Grid
 * wire forms (seed 000 §3.3; byte layout in lumo/ivg.h and
 * docs/ivg-format.md): compress a hemisphere's 3x3 irradiance matrix into a
 * direction and a colour, quantize them, and write sample bundles the client
 * (lumo_ivg_apply_bundle) decodes. Desktop C11, floats and no heap: the
 * caller gives the output buffer.
 */
#ifndef SRV_IVG_ENCODE_H
#define SRV_IVG_ENCODE_H

#include <stddef.h>
#include <stdint.h>
#include "lumo/ivg.h"
#include "lumo/status.h"

/* The largest colour RGB9E5 holds, (511/512) * 2^16; colours are clamped to
 * [0, SRV_IVG_C_MAX] in both wire forms. */
#define SRV_IVG_C_MAX 65408.0f

/* One hemisphere in float: unit direction d (or zero) and colour c (W/m^2),
 * so that M n = c (d . n) for n = delta. */
typedef struct srv_ivg_fentry {
    float d[3];
    float c[3];
} srv_ivg_fentry;

/* Compress M = (I^R | I^G | I^B) of hemisphere `axis` (lumo_ivg_axis):
 * I[k] is the irradiance vector of colour channel k (§3.1, eq. 1).
 *   d = normalize(I^R + I^G + I^B),  c_k = (I^k . delta) / (d . delta).
 * A zero sum gives d = c = 0. When d . delta <= 1e-6 (all light grazing
 * the hemisphere's plane) c is 0: M delta is then ~0 too. c is clamped to
 * [0, SRV_IVG_C_MAX]. */
void srv_ivg_compress(const float I[3][3], lumo_ivg_axis axis, srv_ivg_fentry *out);

/* d as three int8: round(d * 127) clamped to [-127, 127]. */
void srv_ivg_quantize_d(const float d[3], int8_t q[3]);

/* c as RGB9E5 following GL_EXT_texture_shared_exponent (N = 9, B = 15):
 * negative and NaN clamp to 0, large values to SRV_IVG_C_MAX. */
uint32_t srv_ivg_rgb9e5_pack(const float c[3]);
/* The exact values an RGB9E5 word stands for: m * 2^(E - 24). */
void srv_ivg_rgb9e5_unpack(uint32_t packed, float c[3]);

/* What a quantized entry decodes to, in float (q / 127, RGB9E5 values). */
void srv_ivg_dequantize(const srv_ivg_fentry *in, srv_ivg_fentry *out);

/* Bundle size for `data` records with entries and `solid` solid records. */
size_t srv_ivg_bundle_bytes(lumo_ivg_form form, uint32_t data, uint32_t solid);

/* Bundle writer over a caller buffer. Calls after an error do nothing and
 * return the first error. */
typedef struct srv_ivg_writer {
    uint8_t      *buf;
    size_t        cap, len;
    uint32_t      records;
    lumo_ivg_form form;
    lumo_status   error;
} srv_ivg_writer;

/* Start a bundle for a grid of `dims` (written into the header). */
lumo_status srv_ivg_writer_begin(srv_ivg_writer *w, uint8_t *buf, size_t cap,
                                 lumo_ivg_form form, const uint16_t dims[3]);
/* A vertex with its six hemispheres (+x, -x, +y, -y, +z, -z). The float
 * form writes d and c as given after clamping c to [0, SRV_IVG_C_MAX];
 * the quantized form writes srv_ivg_quantize_d and srv_ivg_rgb9e5_pack.
 * LUMO_ERR_NOMEM when the buffer is full, LUMO_ERR_RANGE for an index that
 * does not fit 31 bits. */
lumo_status srv_ivg_writer_add(srv_ivg_writer *w, uint32_t vertex, const srv_ivg_fentry e[LUMO_IVG_AXES]);
/* A vertex inside geometry: no data, the client's push-pull fills it. */
lumo_status srv_ivg_writer_add_solid(srv_ivg_writer *w, uint32_t vertex);
/* Patch the record count into the header; returns the bundle's length, or
 * 0 after an error. */
size_t srv_ivg_writer_finish(srv_ivg_writer *w);

#endif /* SRV_IVG_ENCODE_H */
