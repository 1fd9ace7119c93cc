/* package_msg.c — lumo_host/package_msg.h: the refusal of a package in one
 * sentence, naming the version when that is the reason. */
#include <stdio.h>
#include "lumo/package.h"
#include "lumo_host/package_msg.h"

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
    snprintf(buf, n, "not a valid package: %s", lumo_strerror(st));
    return buf;
}
