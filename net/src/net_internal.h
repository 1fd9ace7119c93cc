/*
 * net_internal.h — what the codec's sources (net/src/net_*.c) share: the
 * encoders' room check and the decoders' common entry. Not public.
 */
#ifndef LUMO_NET_INTERNAL_H
#define LUMO_NET_INTERNAL_H

#include <stddef.h>
#include <stdint.h>
#include "lumo/net.h"
#include "lumo/wire.h"

/* The encoders' last check before writing (lumo/net.h): ARG without an
 * output, NOMEM unless a frame of len payload bytes fits cap. */
static inline lumo_status net_room(const uint8_t *out, size_t cap, const size_t *written, uint32_t len)
{
    if (!written || (!out && cap))
        return LUMO_ERR_ARG;
    return cap < (size_t)len + LUMO_NET_OVERHEAD ? LUMO_ERR_NOMEM : LUMO_OK;
}

/* Seal the payload written at out + LUMO_NET_HEADER and report the frame. */
static inline lumo_status net_sealed(uint8_t *out, uint8_t type, uint32_t len, size_t *written)
{
    lumo_net_frame_seal(out, type, len);
    *written = (size_t)len + LUMO_NET_OVERHEAD;
    return LUMO_OK;
}

/* The decoders' entry (lumo/net.h): ARG without a frame or an output, STATE
 * for a frame of another type, TRUNCATED when the payload is shorter than
 * the type's fixed part (docs/protocol.md §1, last row). */
static inline lumo_status net_payload(const lumo_net_frame *f, const void *m, uint8_t type, uint32_t fixed)
{
    if (!f || !m || (!f->payload && f->len))
        return LUMO_ERR_ARG;
    if (f->type != type)
        return LUMO_ERR_STATE;
    return f->len < fixed ? LUMO_ERR_TRUNCATED : LUMO_OK;
}

/* A payload of exactly `want` bytes: shorter is TRUNCATED, longer CORRUPT. */
static inline lumo_status net_exact(uint32_t len, size_t want)
{
    if (len < want)
        return LUMO_ERR_TRUNCATED;
    return len > want ? LUMO_ERR_CORRUPT : LUMO_OK;
}

/* Channel (REQUEST, DATA, END): 0 geometry, 1 lighting or 2 updates (§9);
 * a lighting or updates message names mesh 0 (docs/protocol.md §2: "mesh
 * index (geometry), else 0"). RANGE otherwise. */
static inline lumo_status net_channel(uint8_t channel, uint32_t mesh)
{
    if (channel > LUMO_NET_CHANNEL_LAST)
        return LUMO_ERR_RANGE;
    /* geometry and PRT name a mesh; lighting and updates are the scene's */
    return channel != LUMO_NET_GEOMETRY && channel != LUMO_NET_PRT && mesh != 0 ? LUMO_ERR_RANGE : LUMO_OK;
}

/* The status an ERROR frame carries (a decoding failure, or a status
 * outside lumo_status as CORRUPT): what a client driver fails with. */
static inline lumo_status net_error_status(const lumo_net_frame *f)
{
    lumo_net_error e;
    lumo_status st = lumo_net_error_decode(f, &e);

    if (st)
        return st;
    return e.status > LUMO_OK && e.status < LUMO_STATUS_COUNT ? (lumo_status)e.status : LUMO_ERR_CORRUPT;
}

#endif /* LUMO_NET_INTERNAL_H */
