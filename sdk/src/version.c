/*
 * version.c — the linked library's version (lumo/version.h): compiled from
 * the same macros the headers give an application, so comparing the two
 * catches a stale library.
 */
#include "lumo/version.h"

uint32_t lumo_version(void)
{
    return (uint32_t)LUMO_VERSION_NUMBER;
}

const char *lumo_version_string(void)
{
    return LUMO_VERSION_STRING;
}

void lumo_version_formats_get(lumo_version_formats *out)
{
    if (!out)
        return;
    out->package_major = (uint16_t)LUMO_PKG_VERSION_MAJOR;
    out->package_minor = (uint16_t)LUMO_PKG_VERSION_MINOR;
    out->pmesh = (uint16_t)LUMO_PMESH_VERSION;
    out->ivg_bundle = (uint16_t)LUMO_IVG_BUNDLE_VERSION;
}
