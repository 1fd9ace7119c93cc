/* status.c — human-readable names for lumo_status codes. */
#include "lumo/status.h"

static const char *const k_messages[LUMO_STATUS_COUNT] = {
    "ok",
    "invalid argument",
    "arena too small",
    "input truncated",
    "input corrupt",
    "value out of range",
    "non-finite number",
    "unsupported feature",
    "checksum mismatch",
    "unknown version",
    "invalid state for this call",
    "size computation overflow",
    "i/o error",
    "input exceeds a limit",
};

const char *lumo_strerror(lumo_status st)
{
    if ((unsigned)st >= (unsigned)LUMO_STATUS_COUNT)
        return "unknown error";
    return k_messages[st];
}
