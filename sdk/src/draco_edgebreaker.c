/*
 * draco_edgebreaker.c — EdgeBreaker connectivity (standard and valence).
 */
#include "draco_internal.h"

lumo_status ld_eb_decode_connectivity(ld_dec *d)
{
    (void)d;
    return LUMO_ERR_UNSUPPORTED;
}

lumo_status ld_eb_create_attributes_decoder(ld_dec *d, unsigned decoder, ld_seq *seq,
                                            uint8_t *traversal, uint8_t *vertex_attr)
{
    (void)d; (void)decoder; (void)seq; (void)traversal; (void)vertex_attr;
    return LUMO_ERR_UNSUPPORTED;
}

lumo_status ld_eb_sequence(ld_dec *d, unsigned decoder, ld_seq *seq)
{
    (void)d; (void)decoder; (void)seq;
    return LUMO_ERR_UNSUPPORTED;
}
