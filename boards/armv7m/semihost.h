/* semihost.h — the raw semihosting trap of mps2-an385 (see semihost.c). */
#ifndef LUMO_MPS2_SEMIHOST_H
#define LUMO_MPS2_SEMIHOST_H

#include <stdint.h>

/* Semihosting operation `op` with parameter block `arg`; returns r0. */
int32_t lumo_semihost_call(uint32_t op, const void *arg);

#endif
