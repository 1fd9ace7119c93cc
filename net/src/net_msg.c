/*
 * net_msg.c — the messages of a running conversation (docs/protocol.md §2,
 * §3): REQUEST, DATA (whole or as a head for zero-copy sending), END, ERROR
 * and BYE, encoded and decoded with the layout and limits of §2 and §5.
 */
#include <string.h>
#include "lumo/ivg.h"
#include "net_internal.h"

#define REQUEST_LEN 16u
#define END_LEN     8u
#define ERROR_FIXED 8u   /* status, text length */

/* Every REQUEST, DATA and END payload opens with the same 8 bytes (§2):
 * channel, three reserved zero bytes, mesh (u32). */
static void channel_put(uint8_t *p, uint8_t channel, uint32_t mesh)
{
    p[0] = channel;
    p[1] = p[2] = p[3] = 0;   /* reserved */
    lumo_wire_put_le32(p + 4, mesh);
}

static void channel_get(const uint8_t *p, uint8_t *channel, uint32_t *mesh)
{
    *channel = p[0];
    *mesh = lumo_wire_le32(p + 4);
}

/* ---- REQUEST ------------------------------------------------------------------- */

/* §2 REQUEST: a channel (lighting names mesh 0); §3: an amount of at least
 * 1 (a zero amount is RANGE). */
static lumo_status request_check(const lumo_net_request *m)
{
    lumo_status st = net_channel(m->channel, m->mesh);

    if (st)
        return st;
    return m->amount ? LUMO_OK : LUMO_ERR_RANGE;
}

lumo_status lumo_net_request_encode(const lumo_net_request *m, uint8_t *out, size_t cap, size_t *written)
{
    uint8_t *p;
    lumo_status st;

    if (!m || request_check(m))
        return LUMO_ERR_ARG;
    st = net_room(out, cap, written, REQUEST_LEN);
    if (st)
        return st;
    p = out + LUMO_NET_HEADER;
    channel_put(p, m->channel, m->mesh);
    lumo_wire_put_le32(p + 8, m->cursor);
    lumo_wire_put_le32(p + 12, m->amount);
    return net_sealed(out, LUMO_NET_REQUEST, REQUEST_LEN, written);
}

lumo_status lumo_net_request_decode(const lumo_net_frame *f, lumo_net_request *m)
{
    lumo_net_request r;
    lumo_status st = net_payload(f, m, LUMO_NET_REQUEST, REQUEST_LEN);

    if (st)
        return st;
    st = net_exact(f->len, REQUEST_LEN);
    if (st)
        return st;
    channel_get(f->payload, &r.channel, &r.mesh);
    r.cursor = lumo_wire_le32(f->payload + 8);
    r.amount = lumo_wire_le32(f->payload + 12);
    st = request_check(&r);
    if (st)
        return st;
    *m = r;
    return LUMO_OK;
}

/* ---- DATA ---------------------------------------------------------------------- */

/* §2 DATA, geometry: form 0, at least one batch record, records = count. */
static lumo_status data_check_geometry(const lumo_net_data *m)
{
    if (m->form != 0 || m->count == 0)
        return LUMO_ERR_RANGE;
    return m->records == m->count ? LUMO_OK : LUMO_ERR_CORRUPT;
}

/* §2 DATA, lighting: an IVG form, at least one record; count may be 0 (a
 * round split at record boundaries continues), and every round counted
 * brings a record at least (records >= count). */
static lumo_status data_check_lighting(const lumo_net_data *m)
{
    if (m->form > LUMO_IVG_FORM_QUANTIZED || m->records == 0)
        return LUMO_ERR_RANGE;
    return m->records >= m->count ? LUMO_OK : LUMO_ERR_CORRUPT;
}

/* §9 DATA, updates: an IVG form, at least one record, and the position
 * the records bring the client to lies after the one it held. */
static lumo_status data_check_updates(const lumo_net_data *m)
{
    if (m->form > LUMO_IVG_FORM_QUANTIZED || m->records == 0)
        return LUMO_ERR_RANGE;
    return m->count > m->first ? LUMO_OK : LUMO_ERR_CORRUPT;
}

static lumo_status data_check(const lumo_net_data *m)
{
    lumo_status st = net_channel(m->channel, m->mesh);

    if (st)
        return st;
    if (m->channel == LUMO_NET_UPDATES)
        return data_check_updates(m);
    return m->channel == LUMO_NET_GEOMETRY ? data_check_geometry(m) : data_check_lighting(m);
}

/* The 24-byte DATA head at p (§2); bytes 16..23 are the session's IVGR
 * head (form, records). */
static void data_put_head(uint8_t *p, const lumo_net_data *m)
{
    channel_put(p, m->channel, m->mesh);
    lumo_wire_put_le32(p + 8, m->first);
    lumo_wire_put_le32(p + 12, m->count);
    p[16] = m->form;
    p[17] = p[18] = p[19] = 0;   /* reserved */
    lumo_wire_put_le32(p + 20, m->records);
}

lumo_status lumo_net_data_encode(const lumo_net_data *m, uint8_t *out, size_t cap, size_t *written)
{
    lumo_status st;

    if (!m || data_check(m) || m->len > LUMO_NET_MAX_PAYLOAD - LUMO_NET_DATA_HEAD || (m->len && !m->bytes))
        return LUMO_ERR_ARG;
    st = net_room(out, cap, written, LUMO_NET_DATA_HEAD + m->len);
    if (st)
        return st;
    /* memmove: the bytes may already be in place at out + 32. */
    if (m->len)
        memmove(out + LUMO_NET_HEADER + LUMO_NET_DATA_HEAD, m->bytes, m->len);
    data_put_head(out + LUMO_NET_HEADER, m);
    return net_sealed(out, LUMO_NET_DATA, LUMO_NET_DATA_HEAD + m->len, written);
}

uint32_t lumo_net_data_head(const lumo_net_data *m, uint8_t out[LUMO_NET_HEADER + LUMO_NET_DATA_HEAD])
{
    lumo_net_frame_head(out, LUMO_NET_DATA, LUMO_NET_DATA_HEAD + m->len);
    data_put_head(out + LUMO_NET_HEADER, m);
    return lumo_wire_crc32(0, out, LUMO_NET_HEADER + LUMO_NET_DATA_HEAD);
}

lumo_status lumo_net_data_decode(const lumo_net_frame *f, lumo_net_data *m)
{
    const uint8_t *p;
    lumo_net_data d;
    lumo_status st = net_payload(f, m, LUMO_NET_DATA, LUMO_NET_DATA_HEAD);

    if (st)
        return st;
    p = f->payload;
    channel_get(p, &d.channel, &d.mesh);
    d.first = lumo_wire_le32(p + 8);
    d.count = lumo_wire_le32(p + 12);
    d.form = p[16];
    d.records = lumo_wire_le32(p + 20);
    d.bytes = p + LUMO_NET_DATA_HEAD;
    d.len = f->len - LUMO_NET_DATA_HEAD;
    st = data_check(&d);
    if (st)
        return st;
    *m = d;
    return LUMO_OK;
}

/* ---- END ----------------------------------------------------------------------- */

lumo_status lumo_net_end_encode(const lumo_net_end *m, uint8_t *out, size_t cap, size_t *written)
{
    uint8_t *p;
    lumo_status st;

    if (!m || net_channel(m->channel, m->mesh))
        return LUMO_ERR_ARG;
    st = net_room(out, cap, written, END_LEN);
    if (st)
        return st;
    p = out + LUMO_NET_HEADER;
    channel_put(p, m->channel, m->mesh);
    return net_sealed(out, LUMO_NET_END, END_LEN, written);
}

lumo_status lumo_net_end_decode(const lumo_net_frame *f, lumo_net_end *m)
{
    lumo_net_end e;
    lumo_status st = net_payload(f, m, LUMO_NET_END, END_LEN);

    if (st)
        return st;
    st = net_exact(f->len, END_LEN);
    if (st)
        return st;
    channel_get(f->payload, &e.channel, &e.mesh);
    st = net_channel(e.channel, e.mesh);
    if (st)
        return st;
    *m = e;
    return LUMO_OK;
}

/* ---- ERROR --------------------------------------------------------------------- */

/* Bytes of text before its NUL, counting no further than one past
 * LUMO_NET_MAX_TEXT (NULL: none). */
static uint32_t error_text_len(const char *text)
{
    uint32_t n = 0;

    while (text && n <= LUMO_NET_MAX_TEXT && text[n])
        n++;
    return n;
}

lumo_status lumo_net_error_encode(uint32_t status, const char *text, uint8_t *out, size_t cap,
                                  size_t *written)
{
    uint32_t n = error_text_len(text);
    lumo_status st;

    if (n > LUMO_NET_MAX_TEXT)
        return LUMO_ERR_ARG;
    st = net_room(out, cap, written, ERROR_FIXED + n);
    if (st)
        return st;
    lumo_wire_put_le32(out + LUMO_NET_HEADER, status);
    lumo_wire_put_le32(out + LUMO_NET_HEADER + 4, n);
    if (n)
        memcpy(out + LUMO_NET_HEADER + ERROR_FIXED, text, n);
    return net_sealed(out, LUMO_NET_ERROR, ERROR_FIXED + n, written);
}

/* §2 ERROR, §5: a text of at most 256 bytes without NUL (CORRUPT: what the
 * encoder's C string cannot carry), filling the payload. */
lumo_status lumo_net_error_decode(const lumo_net_frame *f, lumo_net_error *m)
{
    uint32_t n;
    lumo_status st = net_payload(f, m, LUMO_NET_ERROR, ERROR_FIXED);

    if (st)
        return st;
    n = lumo_wire_le32(f->payload + 4);
    if (n > LUMO_NET_MAX_TEXT)
        return LUMO_ERR_CORRUPT;
    st = net_exact(f->len, ERROR_FIXED + n);
    if (st)
        return st;
    if (n && memchr(f->payload + ERROR_FIXED, 0, n))
        return LUMO_ERR_CORRUPT;
    m->status = lumo_wire_le32(f->payload);
    m->len = n;
    m->text = f->payload + ERROR_FIXED;
    return LUMO_OK;
}

/* ---- BYE ----------------------------------------------------------------------- */

lumo_status lumo_net_bye_encode(uint8_t *out, size_t cap, size_t *written)
{
    lumo_status st = net_room(out, cap, written, 0);

    if (st)
        return st;
    return net_sealed(out, LUMO_NET_BYE, 0, written);
}

lumo_status lumo_net_bye_decode(const lumo_net_frame *f)
{
    lumo_status st = net_payload(f, f, LUMO_NET_BYE, 0);

    return st ? st : net_exact(f->len, 0);
}
