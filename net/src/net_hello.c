/*
 * net_hello.c — the opening of a conversation (docs/protocol.md §2, §3):
 * HELLO (client → server) and WELCOME (server → client), encoded and
 * decoded with the layout and limits of §2 and §5.
 */
#include <string.h>
#include "lumo/ivg.h"
#include "net_internal.h"

#define HELLO_FIXED   28u   /* §2 HELLO: the fields before the cursors */
#define WELCOME_FIXED 12u   /* §2 WELCOME: package id, arena, count */
#define MSG_HEAD      12u   /* a WELCOME message: type, index, length */

/* ---- HELLO ------------------------------------------------------------------- */

/* §2 HELLO, §5: at most LUMO_MAX_MESHES cursors (LIMIT); a max payload of
 * at least 4096 and an IVG form 0, 1 or 0xFF (RANGE). Width, height and
 * flags are informational and take any value. */
static lumo_status hello_check(const lumo_net_hello *m)
{
    if (m->mesh_count > LUMO_MAX_MESHES)
        return LUMO_ERR_LIMIT;
    if (m->max_payload < LUMO_NET_MIN_PAYLOAD)
        return LUMO_ERR_RANGE;
    if (m->ivg_form != LUMO_IVG_FORM_FLOAT && m->ivg_form != LUMO_IVG_FORM_QUANTIZED
        && m->ivg_form != LUMO_NET_FORM_NONE)
        return LUMO_ERR_RANGE;
    return LUMO_OK;
}

lumo_status lumo_net_hello_encode(const lumo_net_hello *m, const uint32_t *cursors, uint8_t *out,
                                  size_t cap, size_t *written)
{
    uint32_t len, i;
    uint8_t *p;
    lumo_status st;

    if (!m || hello_check(m) || (m->mesh_count && !cursors))
        return LUMO_ERR_ARG;
    len = HELLO_FIXED + 4u * m->mesh_count;
    st = net_room(out, cap, written, len);
    if (st)
        return st;
    p = out + LUMO_NET_HEADER;
    lumo_wire_put_le32(p, m->package);
    lumo_wire_put_le32(p + 4, m->arena_bytes);
    lumo_wire_put_le32(p + 8, m->max_payload);
    lumo_wire_put_le16(p + 12, m->width);
    lumo_wire_put_le16(p + 14, m->height);
    p[16] = m->ivg_form;
    p[17] = m->flags;
    lumo_wire_put_le16(p + 18, 0);   /* reserved */
    lumo_wire_put_le32(p + 20, m->resume_id);
    lumo_wire_put_le32(p + 24, m->mesh_count);
    for (i = 0; i < m->mesh_count; i++)
        lumo_wire_put_le32(p + HELLO_FIXED + 4u * i, cursors[i]);
    return net_sealed(out, LUMO_NET_HELLO, len, written);
}

lumo_status lumo_net_hello_decode(const lumo_net_frame *f, lumo_net_hello *m)
{
    const uint8_t *p;
    lumo_net_hello h;
    lumo_status st = net_payload(f, m, LUMO_NET_HELLO, HELLO_FIXED);

    if (st)
        return st;
    p = f->payload;
    h.mesh_count = lumo_wire_le32(p + 24);
    if (h.mesh_count > LUMO_MAX_MESHES)
        return LUMO_ERR_LIMIT;
    st = net_exact(f->len, HELLO_FIXED + 4u * h.mesh_count);
    if (st)
        return st;
    h.package = lumo_wire_le32(p);
    h.arena_bytes = lumo_wire_le32(p + 4);
    h.max_payload = lumo_wire_le32(p + 8);
    h.width = lumo_wire_le16(p + 12);
    h.height = lumo_wire_le16(p + 14);
    h.ivg_form = p[16];
    h.flags = p[17];
    h.resume_id = lumo_wire_le32(p + 20);
    h.cursors = p + HELLO_FIXED;
    st = hello_check(&h);
    if (st)
        return st;
    *m = h;
    return LUMO_OK;
}

uint32_t lumo_net_hello_cursor(const lumo_net_hello *m, uint32_t i)
{
    if (!m || !m->cursors || i >= m->mesh_count)
        return 0;
    return lumo_wire_le32(m->cursors + 4u * i);
}

/* ---- WELCOME ------------------------------------------------------------------- */

/* Zero bytes after a message of len bytes, to a multiple of 4 (§2 WELCOME). */
static uint32_t welcome_pad(uint32_t len)
{
    return (4u - (len & 3u)) & 3u;
}

/* Payload bytes of a WELCOME of these messages, or 0 when it is outside the
 * protocol: more than LUMO_NET_MAX_WELCOME_MSGS messages (§5), a message
 * without its bytes, or more than LUMO_NET_MAX_PAYLOAD in all (§1). */
static uint32_t welcome_size(const lumo_net_msg *msgs, uint32_t count)
{
    uint32_t total = WELCOME_FIXED, i;

    if (count > LUMO_NET_MAX_WELCOME_MSGS || (count && !msgs))
        return 0;
    for (i = 0; i < count; i++) {
        uint32_t len = msgs[i].len;

        if (len > LUMO_NET_MAX_PAYLOAD || (len && !msgs[i].data))
            return 0;
        total += MSG_HEAD + len + welcome_pad(len);   /* <= 32 MiB + 27: no wrap */
        if (total > LUMO_NET_MAX_PAYLOAD)
            return 0;
    }
    return total;
}

/* One message at p: head, bytes, zero padding; returns the bytes written. */
static uint32_t welcome_put_msg(uint8_t *p, const lumo_net_msg *msg)
{
    uint32_t pad = welcome_pad(msg->len);

    lumo_wire_put_le32(p, msg->type);
    lumo_wire_put_le32(p + 4, msg->index);
    lumo_wire_put_le32(p + 8, msg->len);
    if (msg->len)
        memcpy(p + MSG_HEAD, msg->data, msg->len);
    memset(p + MSG_HEAD + msg->len, 0, pad);
    return MSG_HEAD + msg->len + pad;
}

lumo_status lumo_net_welcome_encode(uint32_t package_id, uint32_t arena_need, const lumo_net_msg *msgs,
                                    uint32_t count, uint8_t *out, size_t cap, size_t *written)
{
    uint32_t len = welcome_size(msgs, count), at = WELCOME_FIXED, i;
    uint8_t *p;
    lumo_status st;

    if (!len)
        return LUMO_ERR_ARG;
    st = net_room(out, cap, written, len);
    if (st)
        return st;
    p = out + LUMO_NET_HEADER;
    lumo_wire_put_le32(p, package_id);
    lumo_wire_put_le32(p + 4, arena_need);
    lumo_wire_put_le32(p + 8, count);
    for (i = 0; i < count; i++)
        at += welcome_put_msg(p + at, &msgs[i]);
    return net_sealed(out, LUMO_NET_WELCOME, len, written);
}

/* The message at msgs[*at] of a list of size bytes (*at <= size): its head
 * and bytes inside the list (TRUNCATED), its padding zero (CORRUPT). On
 * success *at moves past it and *out (if given) describes it. */
static lumo_status welcome_msg(const uint8_t *msgs, size_t size, size_t *at, lumo_net_msg *out)
{
    const uint8_t *p = msgs + *at;
    size_t left = size - *at;
    uint32_t len, pad, i;

    if (left < MSG_HEAD)
        return LUMO_ERR_TRUNCATED;
    len = lumo_wire_le32(p + 8);
    pad = welcome_pad(len);
    if (len > left - MSG_HEAD || pad > left - MSG_HEAD - len)
        return LUMO_ERR_TRUNCATED;
    for (i = 0; i < pad; i++)
        if (p[MSG_HEAD + len + i])
            return LUMO_ERR_CORRUPT;
    if (out) {
        out->type = lumo_wire_le32(p);
        out->index = lumo_wire_le32(p + 4);
        out->len = len;
        out->data = p + MSG_HEAD;
    }
    *at += MSG_HEAD + len + pad;
    return LUMO_OK;
}

lumo_status lumo_net_welcome_decode(const lumo_net_frame *f, lumo_net_welcome *m)
{
    const uint8_t *p;
    size_t at = 0, size;
    uint32_t count, i;
    lumo_status st = net_payload(f, m, LUMO_NET_WELCOME, WELCOME_FIXED);

    if (st)
        return st;
    p = f->payload;
    count = lumo_wire_le32(p + 8);
    if (count > LUMO_NET_MAX_WELCOME_MSGS)
        return LUMO_ERR_LIMIT;
    size = f->len - WELCOME_FIXED;
    for (i = 0; i < count; i++) {
        st = welcome_msg(p + WELCOME_FIXED, size, &at, NULL);
        if (st)
            return st;
    }
    if (at != size)
        return LUMO_ERR_CORRUPT;   /* bytes after the last message */
    m->package_id = lumo_wire_le32(p);
    m->arena_need = lumo_wire_le32(p + 4);
    m->count = count;
    m->msgs = p + WELCOME_FIXED;
    m->msgs_len = size;
    return LUMO_OK;
}

lumo_status lumo_net_welcome_next(const lumo_net_welcome *m, size_t *at, lumo_net_msg *out)
{
    if (!m || !at || !out)
        return LUMO_ERR_ARG;
    if (*at >= m->msgs_len)
        return LUMO_ERR_RANGE;
    return welcome_msg(m->msgs, m->msgs_len, at, out);
}
