/*
 * net_frame.c — frames of the stream protocol (docs/protocol.md §1): the
 * receiver's checks in their order, zero-copy sealing and heads, and the
 * serial resynchronisation.
 */
#include "net_internal.h"

/* Types 1 (HELLO) .. 7 (BYE) of docs/protocol.md §2. */
static int net_type_known(uint8_t type)
{
    return type >= LUMO_NET_HELLO && type <= LUMO_NET_TYPE_LAST;
}

/* The 8 header bytes: magic "LS", version, type, payload length (§1). */
static void net_put_head(uint8_t *head, uint8_t type, uint32_t len)
{
    head[0] = LUMO_NET_MAGIC0;
    head[1] = LUMO_NET_MAGIC1;
    head[2] = LUMO_NET_VERSION;
    head[3] = type;
    lumo_wire_put_le32(head + 4, len);
}

/* §1, the checks a header allows: magic (CORRUPT), version (VERSION),
 * payload length against the receiver's limit (LIMIT). */
static lumo_status net_check_head(const uint8_t *head, uint32_t max_payload)
{
    uint32_t limit = max_payload < LUMO_NET_MAX_PAYLOAD ? max_payload : LUMO_NET_MAX_PAYLOAD;

    if (head[0] != LUMO_NET_MAGIC0 || head[1] != LUMO_NET_MAGIC1)
        return LUMO_ERR_CORRUPT;
    if (head[2] != LUMO_NET_VERSION)
        return LUMO_ERR_VERSION;
    return lumo_wire_le32(head + 4) > limit ? LUMO_ERR_LIMIT : LUMO_OK;
}

lumo_status lumo_net_frame_decode(const uint8_t *buf, size_t avail, uint32_t max_payload,
                                  lumo_net_frame *out, size_t *consumed)
{
    size_t size, body;
    lumo_status st;

    if (!out || !consumed || (!buf && avail))
        return LUMO_ERR_ARG;
    if (avail < LUMO_NET_HEADER) {
        *consumed = LUMO_NET_HEADER;
        return LUMO_ERR_TRUNCATED;
    }
    st = net_check_head(buf, max_payload);
    if (st)
        return st;
    /* Known header: wait for the whole frame (at most 16 MiB + 12). */
    body = LUMO_NET_HEADER + (size_t)lumo_wire_le32(buf + 4);
    size = body + LUMO_NET_TRAILER;
    if (avail < size) {
        *consumed = size;
        return LUMO_ERR_TRUNCATED;
    }
    if (lumo_wire_crc32(0, buf, body) != lumo_wire_le32(buf + body))
        return LUMO_ERR_CHECKSUM;
    if (!net_type_known(buf[3]))
        return LUMO_ERR_UNSUPPORTED;
    out->type = buf[3];
    out->len = lumo_wire_le32(buf + 4);
    out->payload = buf + LUMO_NET_HEADER;
    *consumed = size;
    return LUMO_OK;
}

void lumo_net_frame_seal(uint8_t *frame, uint8_t type, uint32_t len)
{
    size_t body = LUMO_NET_HEADER + (size_t)len;

    net_put_head(frame, type, len);
    lumo_wire_put_le32(frame + body, lumo_wire_crc32(0, frame, body));
}

uint32_t lumo_net_frame_head(uint8_t head[LUMO_NET_HEADER], uint8_t type, uint32_t len)
{
    net_put_head(head, type, len);
    return lumo_wire_crc32(0, head, LUMO_NET_HEADER);
}

/* §1 "Over a serial line": the next "LS" at or after from; a lone 'L' as
 * the last byte may be the first half of one. */
size_t lumo_net_resync(const uint8_t *buf, size_t avail, size_t from)
{
    size_t i;

    if (!buf || from >= avail)
        return avail;
    for (i = from; i + 1 < avail; i++)
        if (buf[i] == LUMO_NET_MAGIC0 && buf[i + 1] == LUMO_NET_MAGIC1)
            return i;
    return buf[avail - 1] == LUMO_NET_MAGIC0 ? avail - 1 : avail;
}
