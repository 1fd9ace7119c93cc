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
#include "lumo/session.h"

/* Flags of host_package_check. NEED_INFO: refuse a package without INFO
 * (every reader that draws; lumo-inspect also lists the stream-only
 * packages of lumo-pm build). DEEP: then feed the whole package to a
 * client session (lumo/session.h) in a heap arena it sizes — every MESH
 * value, PMSH batch and IVG record decoded as a client decodes it — for
 * the readers that do not decode it themselves (lumo-inspect,
 * lumo-server); lumo-render's own session is that pass. */
#define HOST_PKG_NEED_INFO 1u
#define HOST_PKG_DEEP      2u

/* LUMO_OK, or the SDK's status with "CHUNK ...: why" in buf (n bytes,
 * always terminated). */
lumo_status host_package_check(const lumo_package *pkg, unsigned flags, char *buf, size_t n);

/* The INFO payload and its lights, and the IVGD payload, on their own
 * (a reader that fetched them, as lumo-client over HTTP): LUMO_OK with the
 * decoded value, or the decoder's status with the sentence above in buf. */
lumo_status host_info_check(const uint8_t *p, uint32_t len, lumo_pkg_info *in, char *buf, size_t n);
lumo_status host_ivgd_check(const uint8_t *p, uint32_t len, lumo_ivg_desc *d, char *buf, size_t n);

/* Which message of a package a session refused (the `where` of
 * lumo_session_feed_package) and why, in words, into buf. */
void host_package_where(const lumo_session_where *w, lumo_status st, char *buf, size_t n);

#endif
