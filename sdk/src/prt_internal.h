/* prt_internal.h — what the PRT client files share: the SH normalisation
 * constants and the Rx(+90 deg) rotation blocks (prt_tables.c, checked
 * against the server's double formulas by tests/prt/test_prt_client.c). */
#ifndef LUMO_PRT_INTERNAL_H
#define LUMO_PRT_INTERNAL_H

#include <stdint.h>
#include "lumo/fixed.h"
#include "lumo/prt.h"

/* K_l^m (m = 0) or sqrt(2) K_l^m (m > 0) in Q2.30, at l(l+1)/2 + m. */
extern const int32_t lumo_prt_sh_k[LUMO_PRT_MAX_ORDER * (LUMO_PRT_MAX_ORDER + 1) / 2];

/* The SH rotation of Rx(+90 deg), band l's (2l+1)^2 block row-major at
 * offset sum_{b<l} (2b+1)^2, Q2.30. */
extern const int32_t lumo_prt_rx90[286];

/* a / b rounded to nearest, ties away from zero; b > 0. */
static inline int64_t lumo_prt_div_round(int64_t a, int64_t b)
{
    return a >= 0 ? (a + b / 2) / b : -((-a + b / 2) / b);
}

#endif
