/*
 * net_updates.c — the updates channel's client side (lumo/net_updates.h,
 * docs/protocol.md §9): pull the changed IVG vertices of a dynamic scene,
 * apply them as IVGU runs, push-pull once per answer.
 */
#include "lumo/ivg.h"
#include "lumo/net_updates.h"
#include "lumo/wire.h"
#include "net_internal.h"

lumo_status lumo_net_updates_init(lumo_net_updates *u, lumo_session *session, uint8_t form, uint32_t amount,
                                  uint32_t poll_ms)
{
    if (!u || !session || form > LUMO_IVG_FORM_QUANTIZED || amount == 0)
        return LUMO_ERR_ARG;
    u->session = session;
    u->form = form;
    u->in_flight = u->applied = u->wait = 0;
    u->amount = amount;
    u->poll_ms = poll_ms;
    u->cursor = u->answer_records = u->last_ms = 0;
    u->records = u->answers = u->poses = 0;
    u->error = LUMO_OK;
    return LUMO_OK;
}

int lumo_net_updates_takes(const lumo_net_frame *f)
{
    if (f && f->type == LUMO_NET_POSES)
        return 1;
    if (!f || (f->type != LUMO_NET_DATA && f->type != LUMO_NET_END) || f->len < 1)
        return 0;
    return f->payload[0] == LUMO_NET_UPDATES;
}

lumo_status lumo_net_updates_next(lumo_net_updates *u, uint32_t now_ms, uint8_t *out, size_t cap,
                                  size_t *written)
{
    lumo_net_request r;
    lumo_status st;

    if (!u || !out || !written)
        return LUMO_ERR_ARG;
    *written = 0;
    if (u->error)
        return u->error;
    if (u->in_flight || (u->wait && (uint32_t)(now_ms - u->last_ms) < u->poll_ms))
        return LUMO_OK;
    r.channel = LUMO_NET_UPDATES;
    r.mesh = 0;
    r.cursor = u->cursor;
    r.amount = u->amount;
    if ((st = lumo_net_request_encode(&r, out, cap, written)))
        return st;
    u->in_flight = 1;
    u->answer_records = 0;
    u->applied = 0;
    return LUMO_OK;
}

static lumo_status fail(lumo_net_updates *u, lumo_status st)
{
    u->error = st;
    return st;
}

/* A DATA of the answer in flight: the records at the position held. */
static lumo_status on_data(lumo_net_updates *u, const lumo_net_frame *f)
{
    lumo_net_data d;
    lumo_status st = lumo_net_data_decode(f, &d);

    if (st)
        return st;
    if (d.channel != LUMO_NET_UPDATES || !u->in_flight || d.first != u->cursor)
        return LUMO_ERR_STATE;
    if (d.form != u->form)
        return LUMO_ERR_RANGE;
    if (d.records > u->amount - u->answer_records)
        return LUMO_ERR_CORRUPT;
    /* DATA's bytes 16.. are the IVGU message: form, reserved, records, the records */
    st = lumo_session_feed(u->session, LUMO_MSG_IVGU, 0, f->payload + LUMO_NET_DATA_HEAD - LUMO_NET_IVGR_HEAD,
                           f->len - (LUMO_NET_DATA_HEAD - LUMO_NET_IVGR_HEAD));
    if (st)
        return st;
    u->cursor = d.count;
    u->answer_records += d.records;
    u->records += d.records;
    u->applied = 1;
    return LUMO_OK;
}

static lumo_status on_end(lumo_net_updates *u, const lumo_net_frame *f, uint32_t now_ms)
{
    lumo_net_end e;
    lumo_status st = lumo_net_end_decode(f, &e);

    if (st)
        return st;
    if (e.channel != LUMO_NET_UPDATES || !u->in_flight)
        return LUMO_ERR_STATE;
    if (u->applied)
        lumo_session_update(u->session);   /* push-pull once per answer (seed 000 §4.1) */
    u->in_flight = 0;
    u->wait = u->answer_records == 0;
    u->last_ms = now_ms;
    u->answers++;
    return LUMO_OK;
}

/* POSES of the answer in flight: every index checked before any applies. */
static lumo_status on_poses(lumo_net_updates *u, const lumo_net_frame *f)
{
    const lumo_pkg_info *info = lumo_session_info(u->session);
    lumo_net_poses m;
    lumo_net_pose p;
    uint32_t i;
    lumo_status st = lumo_net_poses_decode(f, &m);

    if (st)
        return st;
    if (!u->in_flight || !info)
        return LUMO_ERR_STATE;
    for (i = 0; i < m.count; i++) {
        lumo_net_poses_get(&m, i, &p);
        if (p.index >= (p.kind == LUMO_NET_POSE_LIGHT ? info->light_count : info->mesh_count))
            return LUMO_ERR_RANGE;
    }
    for (i = 0; i < m.count; i++) {
        lumo_net_poses_get(&m, i, &p);
        st = p.kind == LUMO_NET_POSE_LIGHT ? lumo_session_move_light(u->session, p.index, p.t)
                                           : lumo_session_set_mesh_pose(u->session, p.index, p.t, p.yaw_deg);
        if (st)
            return st;
    }
    u->poses += m.count;
    return LUMO_OK;
}

lumo_status lumo_net_updates_on_frame(lumo_net_updates *u, const lumo_net_frame *f, uint32_t now_ms)
{
    lumo_status st;

    if (!u || !f)
        return LUMO_ERR_ARG;
    if (u->error)
        return u->error;
    switch (f->type) {
    case LUMO_NET_DATA:
        st = on_data(u, f);
        break;
    case LUMO_NET_END:
        st = on_end(u, f, now_ms);
        break;
    case LUMO_NET_POSES:
        st = on_poses(u, f);
        break;
    case LUMO_NET_ERROR:
        st = net_error_status(f);
        break;
    default:
        st = LUMO_ERR_STATE;
    }
    return st ? fail(u, st) : LUMO_OK;
}
