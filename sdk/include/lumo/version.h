/*
 * lumo/version.h — which lumo this is, and which formats it reads.
 *
 * The SDK's version follows semantic versioning from 1.0 on: MAJOR changes
 * when the API or ABI of an installed library changes incompatibly, MINOR
 * when something is added, PATCH for fixes. Before 1.0 (now) a MINOR step
 * may break the API; CHANGELOG.md says what changed.
 *
 * The data formats have versions of their own, checked when the bytes are
 * read (LUMO_ERR_VERSION otherwise) and stated here beside the SDK's:
 *   package format    LUMO_PKG_VERSION_MAJOR.MINOR (lumo/package.h)
 *   progressive mesh  LUMO_PMESH_VERSION (lumo/pmesh.h)
 *   IVG bundle        LUMO_IVG_BUNDLE_VERSION (lumo/ivg.h)
 *   stream protocol   LUMO_NET_VERSION (lumo/net.h, in liblumo_net: the SDK
 *                     library does not depend on the codec)
 * A client built against one SDK reads exactly these; a tool's --version
 * prints them all.
 */
#ifndef LUMO_VERSION_H
#define LUMO_VERSION_H

#include <stdint.h>
#include "lumo/ivg.h"
#include "lumo/package.h"
#include "lumo/pmesh.h"

#define LUMO_VERSION_MAJOR 0   /* incompatible API or ABI changes (from 1.0 on) */
#define LUMO_VERSION_MINOR 1   /* additions */
#define LUMO_VERSION_PATCH 0   /* fixes */

#define LUMO_VERSION_STR_(x) #x   /* helper of LUMO_VERSION_STRING: x as a string */
#define LUMO_VERSION_XSTR_(x) LUMO_VERSION_STR_(x)   /* helper: x's value as a string */

/* "MAJOR.MINOR.PATCH" of the headers being compiled. */
#define LUMO_VERSION_STRING \
    LUMO_VERSION_XSTR_(LUMO_VERSION_MAJOR) "." LUMO_VERSION_XSTR_(LUMO_VERSION_MINOR) "." \
    LUMO_VERSION_XSTR_(LUMO_VERSION_PATCH)

/* One number that grows with every release: MAJOR * 10000 + MINOR * 100 +
 * PATCH, for `#if LUMO_VERSION_NUMBER >= 100` in an application. */
#define LUMO_VERSION_NUMBER (LUMO_VERSION_MAJOR * 10000 + LUMO_VERSION_MINOR * 100 + LUMO_VERSION_PATCH)

/* The version of the library linked, as LUMO_VERSION_NUMBER computes it: an
 * application compares it with the headers' to catch a stale library. */
uint32_t lumo_version(void);

/* The linked library's version as "MAJOR.MINOR.PATCH" (static, never NULL). */
const char *lumo_version_string(void);

/* The format versions the linked library reads (above). */
typedef struct lumo_version_formats {
    uint16_t package_major;   /* LUMO_PKG_VERSION_MAJOR */
    uint16_t package_minor;   /* LUMO_PKG_VERSION_MINOR */
    uint16_t pmesh;           /* LUMO_PMESH_VERSION */
    uint16_t ivg_bundle;      /* LUMO_IVG_BUNDLE_VERSION */
} lumo_version_formats;

/* Fill *out with the formats the linked library reads. */
void lumo_version_formats_get(lumo_version_formats *out);

#endif /* LUMO_VERSION_H */
