/*
 * status_msg.c — see status_msg.h.
 */
#include <stdarg.h>
#include <stdio.h>
#include "common/status_msg.h"

lumo_status srv_fail(char *err, size_t errlen, lumo_status st, const char *fmt, ...)
{
    va_list ap;

    if (err && errlen) {
        va_start(ap, fmt);
        vsnprintf(err, errlen, fmt, ap);
        va_end(ap);
    }
    return st;
}
