/* semihost.h — the raw ARM semihosting trap (see semihost.c). */
#ifndef LUMO_ARMV7M_SEMIHOST_H
#define LUMO_ARMV7M_SEMIHOST_H

#include <stdint.h>

/* Semihosting operation `op` with parameter block `arg`; returns r0. */
int32_t armv7m_semihost_call(uint32_t op, const void *arg);

#endif
