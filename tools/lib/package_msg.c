/* package_msg.c — lumo_host/package_msg.h: the refusal of a package in one
 * sentence, naming the version when that is the reason. */
#include <stdio.h>
#include "lumo/package.h"
#include "lumo/wire.h"
#include "lumo_host/package_msg.h"

/* A chunk type the table holds twice though the format allows one, or 0
 * (the table is read only as far as the file holds it). */
static uint32_t twice(const uint8_t *data, size_t size)
{
    uint32_t count = size >= LUMO_PKG_HEADER_SIZE ? lumo_wire_le32(data + 8) : 0, type = 0;
    if (count > LUMO_PKG_MAX_CHUNKS || size < LUMO_PKG_HEADER_SIZE + (size_t)count * LUMO_PKG_ENTRY_SIZE)
        return 0;
    return lumo_package_table_once(data + LUMO_PKG_HEADER_SIZE, count, &type) ? type : 0;
}

const char *host_package_strerror(const uint8_t *data, size_t size, lumo_status st, char *buf, size_t n)
{
    uint16_t major, minor;
    if (st == LUMO_ERR_VERSION && lumo_package_peek_version(data, size, &major, &minor) == LUMO_OK) {
        if (major < LUMO_PKG_VERSION_MAJOR)
            snprintf(buf, n, "package version %u: re-bake it with this lumo-bake (it writes version %u)",
                     major, LUMO_PKG_VERSION_MAJOR);
        else
            snprintf(buf, n, "package version %u: newer than this build reads (version %u); update lumo", major,
                     LUMO_PKG_VERSION_MAJOR);
        return buf;
    }
    uint32_t dup = st == LUMO_ERR_CORRUPT ? twice(data, size) : 0;
    if (dup) {
        snprintf(buf, n, "not a valid package: two %c%c%c%c chunks (the format allows one)", (char)dup,
                 (char)(dup >> 8), (char)(dup >> 16), (char)(dup >> 24));
        return buf;
    }
    snprintf(buf, n, "not a valid package: %s", lumo_strerror(st));
    return buf;
}
