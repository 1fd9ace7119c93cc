/*
 * package_msg.h — why a package file was refused, in words for a person:
 * the one sentence every desktop tool prints when lumo_package_open fails.
 * A package of another major version gets "package version 1: re-bake it
 * with this lumo-bake (it writes version 2)" instead of the bare status.
 */
#ifndef HOST_PACKAGE_MSG_H
#define HOST_PACKAGE_MSG_H

#include <stddef.h>
#include <stdint.h>
#include "lumo/status.h"

/* The reason lumo_package_open(data, size) returned st, written into buf
 * (n bytes, always terminated); returns buf. */
const char *host_package_strerror(const uint8_t *data, size_t size, lumo_status st, char *buf, size_t n);

#endif
