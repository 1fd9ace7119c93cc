/*
 * common/status_msg.h — the server's one error style (docs/architecture.md):
 * a lumo_status, plus a line of text for a person in the caller's buffer.
 */
#ifndef SRV_COMMON_STATUS_MSG_H
#define SRV_COMMON_STATUS_MSG_H

#include <stddef.h>
#include "lumo/status.h"

/* Format the message into err[0..errlen) (err may be NULL) and return st:
 * `return srv_fail(err, errlen, LUMO_ERR_IO, "%s: %s", path, strerror(errno));` */
lumo_status srv_fail(char *err, size_t errlen, lumo_status st, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

#endif
