/*
 * package_check.h — every scene payload of an opened package, checked
 * through the SDK's own decoders (lumo/scene.h, lumo/pmesh.h, lumo/ivg.h)
 * in the order a client meets them, the first refusal named in words:
 * which chunk, which record, what it holds and what the format allows.
 *
 * The one validation path of the desktop readers: lumo-inspect,
 * lumo-render, lumo-server (and so every lumo-client session it feeds)
 * call it right after lumo_package_open, so a package one of them refuses
 * is refused by all, with the same sentence. The decisions are the SDK's
 * (the session on a board makes the same ones); this module only says
 * where they fell.
 */
#ifndef HOST_PACKAGE_CHECK_H
#define HOST_PACKAGE_CHECK_H

#include <stddef.h>
#include "lumo/package.h"

/* LUMO_OK, or the SDK's status with "CHUNK ...: why" in buf (n bytes,
 * always terminated). need_info: refuse a package without INFO (every
 * reader that draws; 0 for lumo-inspect, which also lists the stream-only
 * packages of lumo-pm build). */
lumo_status host_package_check(const lumo_package *pkg, int need_info, char *buf, size_t n);

#endif
