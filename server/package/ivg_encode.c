/*
 * ivg_encode.c — IVG compression, quantization and bundle writing on the
 * server (seed 000 §3.3 and §4.1; package/ivg_encode.h).
 */
#include <math.h>
#include <string.h>
#include "package/ivg_encode.h"

static float clamp_colour(float v)
{
    if (!(v > 0.0f))                 /* negative, zero and NaN */
        return 0.0f;
    return v > SRV_IVG_C_MAX ? SRV_IVG_C_MAX : v;
}

void srv_ivg_compress(const float I[3][3], lumo_ivg_axis axis, srv_ivg_fentry *out)
{
    int a = (int)axis / 2, k;
    float sign = ((int)axis & 1) ? -1.0f : 1.0f;
    double s[3], len, ddot;

    memset(out, 0, sizeof *out);
    for (k = 0; k < 3; k++)
        s[k] = (double)I[0][k] + I[1][k] + I[2][k];
    len = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
    if (!(len > 1e-30))
        return;
    for (k = 0; k < 3; k++)
        out->d[k] = (float)(s[k] / len);
    ddot = sign * s[a] / len;
    if (!(ddot > 1e-6))
        return;
    for (k = 0; k < 3; k++)
        out->c[k] = clamp_colour((float)(sign * I[k][a] / ddot));
}

void srv_ivg_quantize_d(const float d[3], int8_t q[3])
{
    int k;

    for (k = 0; k < 3; k++) {
        long v = isfinite(d[k]) ? lroundf(d[k] * 127.0f) : 0;
        q[k] = (int8_t)(v > 127 ? 127 : v < -127 ? -127 : v);
    }
}

/* GL_EXT_texture_shared_exponent, "RGB9E5": N = 9 mantissa bits, bias 15. */
uint32_t srv_ivg_rgb9e5_pack(const float c[3])
{
    float v[3], maxc;
    int k, e, exp_shared;
    double denom;
    uint32_t packed = 0;

    for (k = 0; k < 3; k++)
        v[k] = clamp_colour(c[k]);
    maxc = fmaxf(v[0], fmaxf(v[1], v[2]));
    /* floor(log2(maxc)) = e - 1 for maxc = m * 2^e, m in [0.5, 1). */
    frexpf(maxc, &e);
    exp_shared = (maxc > 0.0f && e - 1 > -16 ? e - 1 : -16) + 1 + 15;
    denom = ldexp(1.0, exp_shared - 15 - 9);
    if (floor(maxc / denom + 0.5) == 512.0) {
        exp_shared++;
        denom *= 2.0;
    }
    for (k = 0; k < 3; k++)
        packed |= (uint32_t)floor(v[k] / denom + 0.5) << (9 * k);
    return packed | (uint32_t)exp_shared << 27;
}

void srv_ivg_rgb9e5_unpack(uint32_t packed, float c[3])
{
    int k, e = (int)(packed >> 27);

    for (k = 0; k < 3; k++)
        c[k] = (float)ldexp((double)((packed >> (9 * k)) & 0x1FFu), e - 24);
}

void srv_ivg_dequantize(const srv_ivg_fentry *in, srv_ivg_fentry *out)
{
    int8_t q[3];
    int k;

    srv_ivg_quantize_d(in->d, q);
    srv_ivg_rgb9e5_unpack(srv_ivg_rgb9e5_pack(in->c), out->c);
    for (k = 0; k < 3; k++)
        out->d[k] = q[k] / 127.0f;
}

size_t srv_ivg_bundle_bytes(lumo_ivg_form form, uint32_t data, uint32_t solid)
{
    size_t rec = form == LUMO_IVG_FORM_FLOAT ? LUMO_IVG_FLOAT_RECORD : LUMO_IVG_QUANT_RECORD;
    return LUMO_IVG_BUNDLE_HEADER + (size_t)data * rec + (size_t)solid * 4u;
}

static void put_u16(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
}

static void put_u32(uint8_t *p, uint32_t v)
{
    put_u16(p, v & 0xFFFFu);
    put_u16(p + 2, v >> 16);
}

static void put_f32(uint8_t *p, float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    put_u32(p, u);
}

lumo_status srv_ivg_writer_begin(srv_ivg_writer *w, uint8_t *buf, size_t cap,
                                 lumo_ivg_form form, const uint16_t dims[3])
{
    static const uint8_t magic[4] = {0x49, 0x56, 0x47, 0x42};
    int a;

    memset(w, 0, sizeof *w);
    w->buf = buf;
    w->cap = cap;
    w->form = form;
    if (form != LUMO_IVG_FORM_FLOAT && form != LUMO_IVG_FORM_QUANTIZED)
        return w->error = LUMO_ERR_ARG;
    if (cap < LUMO_IVG_BUNDLE_HEADER)
        return w->error = LUMO_ERR_NOMEM;
    memcpy(buf, magic, 4);
    buf[4] = LUMO_IVG_BUNDLE_VERSION;
    buf[5] = (uint8_t)form;
    for (a = 0; a < 3; a++)
        put_u16(buf + 6 + 2 * a, dims[a]);
    put_u32(buf + 12, 0);
    w->len = LUMO_IVG_BUNDLE_HEADER;
    return LUMO_OK;
}

/* Room for `bytes` more and a valid index, or the writer's error. */
static lumo_status reserve(srv_ivg_writer *w, uint32_t vertex, size_t bytes)
{
    if (w->error)
        return w->error;
    if (vertex & LUMO_IVG_SOLID_BIT)
        return w->error = LUMO_ERR_RANGE;
    if (w->cap - w->len < bytes)
        return w->error = LUMO_ERR_NOMEM;
    return LUMO_OK;
}

static void put_entry(uint8_t *p, lumo_ivg_form form, const srv_ivg_fentry *e)
{
    int k;

    if (form == LUMO_IVG_FORM_QUANTIZED) {
        int8_t q[3];
        srv_ivg_quantize_d(e->d, q);
        for (k = 0; k < 3; k++)
            p[k] = (uint8_t)q[k];
        put_u32(p + 3, srv_ivg_rgb9e5_pack(e->c));
        return;
    }
    for (k = 0; k < 3; k++) {
        put_f32(p + 4 * k, e->d[k]);
        put_f32(p + 12 + 4 * k, clamp_colour(e->c[k]));
    }
}

lumo_status srv_ivg_writer_add(srv_ivg_writer *w, uint32_t vertex, const srv_ivg_fentry e[LUMO_IVG_AXES])
{
    size_t entry = w->form == LUMO_IVG_FORM_FLOAT ? LUMO_IVG_FLOAT_ENTRY : LUMO_IVG_QUANT_ENTRY;
    lumo_status st = reserve(w, vertex, 4u + LUMO_IVG_AXES * entry);
    int a;

    if (st)
        return st;
    put_u32(w->buf + w->len, vertex);
    w->len += 4u;
    for (a = 0; a < LUMO_IVG_AXES; a++, w->len += entry)
        put_entry(w->buf + w->len, w->form, &e[a]);
    w->records++;
    return LUMO_OK;
}

lumo_status srv_ivg_writer_add_solid(srv_ivg_writer *w, uint32_t vertex)
{
    lumo_status st = reserve(w, vertex, 4u);

    if (st)
        return st;
    put_u32(w->buf + w->len, vertex | LUMO_IVG_SOLID_BIT);
    w->len += 4u;
    w->records++;
    return LUMO_OK;
}

size_t srv_ivg_writer_finish(srv_ivg_writer *w)
{
    if (w->error)
        return 0;
    put_u32(w->buf + 12, w->records);
    return w->len;
}
