/*
 * draco_predict.c — prediction schemes and their transforms (paper §3,
 * libdraco compression/attributes/prediction_schemes): the corrections in
 * the stream plus a prediction give the portable values.
 */
#include "draco_internal.h"

#define LD_PRED_DIFFERENCE 0
#define LD_XFORM_WRAP 1

/* Integer adds wrap modulo 2^32 like libdraco's uint32 arithmetic. */
static inline int32_t ld_wrap_add(int32_t a, int32_t b)
{
    return (int32_t)((uint32_t)a + (uint32_t)b);
}

static lumo_status ld_wrap_read(ld_pred *p, ld_buf *b)
{
    uint32_t lo, hi;
    lumo_status st;
    if ((st = ld_u32(b, &lo)) || (st = ld_u32(b, &hi)))
        return st;
    p->min_value = (int32_t)lo;
    p->max_value = (int32_t)hi;
    if (p->min_value > p->max_value ||
        (int64_t)p->max_value - p->min_value >= INT32_MAX)
        return LUMO_ERR_CORRUPT;
    return LUMO_OK;
}

/* Wrap transform: clamp the prediction into [min, max], add the
 * correction, fold the result back into the range. */
static inline void ld_wrap_original(const ld_pred *p, const int32_t *pred,
                                    const int32_t *corr, int32_t *out)
{
    const int32_t max_dif = (int32_t)(1 + p->max_value - p->min_value);
    unsigned c;
    for (c = 0; c < p->comps; ++c) {
        int32_t v = pred[c] > p->max_value ? p->max_value
                  : (pred[c] < p->min_value ? p->min_value : pred[c]);
        v = ld_wrap_add(v, corr[c]);
        if (v > p->max_value)
            v = ld_wrap_add(v, -max_dif);
        else if (v < p->min_value)
            v = ld_wrap_add(v, max_dif);
        out[c] = v;
    }
}

lumo_status ld_pred_decode_data(ld_pred *p, ld_buf *b, ld_mem *m, uint32_t num_values,
                                uint8_t **state)
{
    (void)m;
    (void)num_values;
    *state = NULL;
    if (p->transform != LD_XFORM_WRAP)
        return LUMO_ERR_UNSUPPORTED;
    switch (p->method) {
    case LD_PRED_DIFFERENCE:
        return ld_wrap_read(p, b);
    default:
        return LUMO_ERR_UNSUPPORTED;
    }
}

static lumo_status ld_delta_compute(ld_pred *p, int32_t *v, uint32_t n)
{
    static const int32_t zero[LUMO_DRACO_MAX_COMPONENTS];
    const unsigned k = p->comps;
    uint32_t i;
    ld_wrap_original(p, zero, v, v);
    for (i = 1; i < n; ++i)
        ld_wrap_original(p, v + (size_t)(i - 1) * k, v + (size_t)i * k, v + (size_t)i * k);
    return LUMO_OK;
}

lumo_status ld_pred_compute(ld_pred *p, ld_mem *m, int32_t *values, uint32_t num_entries,
                            const uint8_t *state)
{
    (void)m;
    (void)state;
    switch (p->method) {
    case LD_PRED_DIFFERENCE:
        return ld_delta_compute(p, values, num_entries);
    default:
        return LUMO_ERR_UNSUPPORTED;
    }
}
