/*
 * net_poses.c — the POSES message of the updates channel (docs/protocol.md
 * §9): where a dynamic scene's moved lights and meshes are, 24 bytes each.
 */
#include "net_internal.h"

#define POSES_FIXED 4u   /* the count */

static lumo_status pose_check(const lumo_net_pose *p)
{
    if (p->kind > LUMO_NET_POSE_LIGHT)
        return LUMO_ERR_RANGE;
    return p->kind == LUMO_NET_POSE_LIGHT && p->yaw_deg != 0 ? LUMO_ERR_RANGE : LUMO_OK;
}

static void pose_read(const uint8_t *q, lumo_net_pose *p)
{
    p->kind = q[0];
    p->index = lumo_wire_le32(q + 4);
    p->t[0] = (lumo_q16_16)lumo_wire_le32(q + 8);
    p->t[1] = (lumo_q16_16)lumo_wire_le32(q + 12);
    p->t[2] = (lumo_q16_16)lumo_wire_le32(q + 16);
    p->yaw_deg = (lumo_q16_16)lumo_wire_le32(q + 20);
}

lumo_status lumo_net_poses_encode(const lumo_net_pose *p, uint32_t count, uint8_t *out, size_t cap,
                                  size_t *written)
{
    uint32_t i;
    uint8_t *q;
    lumo_status st;

    if ((count && !p) || count > LUMO_NET_MAX_POSES)
        return LUMO_ERR_ARG;
    for (i = 0; i < count; i++)
        if (pose_check(&p[i]))
            return LUMO_ERR_ARG;
    st = net_room(out, cap, written, POSES_FIXED + count * LUMO_NET_POSE_BYTES);
    if (st)
        return st;
    q = out + LUMO_NET_HEADER;
    lumo_wire_put_le32(q, count);
    for (i = 0, q += POSES_FIXED; i < count; i++, q += LUMO_NET_POSE_BYTES) {
        q[0] = p[i].kind;
        q[1] = q[2] = q[3] = 0;   /* reserved */
        lumo_wire_put_le32(q + 4, p[i].index);
        lumo_wire_put_le32(q + 8, (uint32_t)p[i].t[0]);
        lumo_wire_put_le32(q + 12, (uint32_t)p[i].t[1]);
        lumo_wire_put_le32(q + 16, (uint32_t)p[i].t[2]);
        lumo_wire_put_le32(q + 20, (uint32_t)p[i].yaw_deg);
    }
    return net_sealed(out, LUMO_NET_POSES, POSES_FIXED + count * LUMO_NET_POSE_BYTES, written);
}

lumo_status lumo_net_poses_decode(const lumo_net_frame *f, lumo_net_poses *m)
{
    lumo_net_pose p;
    uint32_t count, i;
    lumo_status st = net_payload(f, m, LUMO_NET_POSES, POSES_FIXED);

    if (st)
        return st;
    count = lumo_wire_le32(f->payload);
    if (count > LUMO_NET_MAX_POSES)
        return LUMO_ERR_LIMIT;
    st = net_exact(f->len, POSES_FIXED + count * LUMO_NET_POSE_BYTES);
    if (st)
        return st;
    for (i = 0; i < count; i++) {
        pose_read(f->payload + POSES_FIXED + i * LUMO_NET_POSE_BYTES, &p);
        if ((st = pose_check(&p)))
            return st;
    }
    m->count = count;
    m->raw = f->payload + POSES_FIXED;
    return LUMO_OK;
}

void lumo_net_poses_get(const lumo_net_poses *m, uint32_t i, lumo_net_pose *out)
{
    pose_read(m->raw + i * LUMO_NET_POSE_BYTES, out);
}
