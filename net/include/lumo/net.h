/*
 * lumo/net.h — the stream protocol's codec (docs/protocol.md): frames and
 * the payload of every message type, encoded and decoded on both sides.
 *
 * Client rules (docs/architecture.md): C99, no heap, no float. Encoders
 * write into the caller's buffer and say how many bytes they wrote (NOMEM
 * when it is too small, nothing written); decoders read the caller's bytes,
 * check every length against the limits of docs/protocol.md §5, and write
 * their outputs only on success. Decoded messages point into the caller's
 * buffer (never copied), which must outlive them.
 */
#ifndef LUMO_NET_H
#define LUMO_NET_H

#include <stddef.h>
#include <stdint.h>
#include "lumo/config.h"
#include "lumo/fixed.h"
#include "lumo/pmesh.h"
#include "lumo/status.h"

#define LUMO_NET_VERSION      1u      /* the protocol version in every frame header */
#define LUMO_NET_MAGIC0       0x4Cu   /* 'L' */
#define LUMO_NET_MAGIC1       0x53u   /* 'S' */
#define LUMO_NET_HEADER       8u      /* magic, version, type, length */
#define LUMO_NET_TRAILER      4u      /* CRC-32 */
#define LUMO_NET_OVERHEAD     (LUMO_NET_HEADER + LUMO_NET_TRAILER)   /* frame bytes around a payload */
#define LUMO_NET_MAX_PAYLOAD  (16u << 20)   /* the largest payload of any frame (16 MiB) */
#define LUMO_NET_MIN_PAYLOAD  4096u   /* the smallest max payload a client may state */
#define LUMO_NET_MAX_TEXT     256u    /* ERROR text bytes */
#define LUMO_NET_MAX_WELCOME_MSGS (1u + 3u * LUMO_MAX_MESHES + 4u)   /* descriptors in a WELCOME, at most:
                                                                     * INFO, PMSH and PRTV per mesh, IVGD, IVGS, ORDR, PRTL */

/* Frame types (docs/protocol.md §2). */
typedef enum lumo_net_type {
    LUMO_NET_HELLO = 1, LUMO_NET_WELCOME = 2, LUMO_NET_REQUEST = 3, LUMO_NET_DATA = 4,
    LUMO_NET_END = 5, LUMO_NET_ERROR = 6, LUMO_NET_BYE = 7,
    LUMO_NET_POSES = 8   /* updates channel: where moved lights and meshes are (§9) */
} lumo_net_type;
#define LUMO_NET_TYPE_LAST LUMO_NET_POSES   /* the highest frame type */

/* The channels a REQUEST, DATA or END belongs to: the package's geometry
 * and lighting, the lighting updates of a dynamic scene (docs/protocol.md
 * §9, docs/dynamic.md), and a mesh's precomputed radiance transfer (§10,
 * docs/prt.md: byte spans of its PRTV chunk). */
typedef enum lumo_net_channel {
    LUMO_NET_GEOMETRY = 0, LUMO_NET_LIGHTING = 1, LUMO_NET_UPDATES = 2, LUMO_NET_PRT = 3
} lumo_net_channel;
/* The highest channel a REQUEST, DATA or END may name (RANGE above). */
#define LUMO_NET_CHANNEL_LAST LUMO_NET_PRT

#define LUMO_NET_FORM_NONE 0xFFu   /* HELLO: no IVG wanted */
#define LUMO_NET_FLAG_SMOOTHING 1u   /* HELLO: the client smooths its push-pull */
/* HELLO, fresh start: send the first picture with the WELCOME (the answers
 * to a base-mesh request per mesh and to lighting round 0, as if asked
 * right after WELCOME): one round trip less to the first picture. */
#define LUMO_NET_FLAG_FIRST_PICTURE 2u
/* HELLO: the client relights with the package's PRT (§10): the WELCOME
 * then carries each mesh's PRTV header and the PRTL, and their arena need. */
#define LUMO_NET_FLAG_PRT 4u

/* ---- frames ------------------------------------------------------------------ */

/* A decoded frame: its type and payload. */
typedef struct lumo_net_frame {
    uint8_t        type;       /* lumo_net_type */
    uint32_t       len;        /* payload bytes */
    const uint8_t *payload;    /* into the caller's buffer */
} lumo_net_frame;

/* Decode the frame at buf[0..avail): checks of docs/protocol.md §1 in
 * order (max_payload: the receiver's limit; above LUMO_NET_MAX_PAYLOAD it
 * counts as LUMO_NET_MAX_PAYLOAD). The header's checks (magic, version,
 * length) come as soon as its 8 bytes are there, before waiting for the
 * rest. On success *consumed = its size. TRUNCATED when more bytes are
 * needed: *consumed is then the frame's full size when the header is known
 * (so the caller can tell how much to wait for), else LUMO_NET_HEADER.
 * Unknown types are UNSUPPORTED (after the CRC check). On any other error
 * *out and *consumed are untouched. */
lumo_status lumo_net_frame_decode(const uint8_t *buf, size_t avail, uint32_t max_payload,
                                  lumo_net_frame *out, size_t *consumed);

/* Write header and CRC around a payload the caller has already written at
 * frame + LUMO_NET_HEADER (len bytes): zero-copy framing. frame must hold
 * len + LUMO_NET_OVERHEAD bytes. */
void lumo_net_frame_seal(uint8_t *frame, uint8_t type, uint32_t len);

/* Header of a frame whose payload the caller sends from elsewhere (a package
 * mapping): writes the 8 header bytes and returns the CRC state to continue
 * over the payload with lumo_wire_crc32; the final CRC goes after it
 * (lumo_wire_put_le32). Nothing is checked: len is the caller's to keep
 * within the receiver's max payload. */
uint32_t lumo_net_frame_head(uint8_t head[LUMO_NET_HEADER], uint8_t type, uint32_t len);

/* Serial resynchronisation: the offset of the first possible frame start
 * (magic) in buf[from..avail), or avail when there is none (a lone 0x4C at
 * the end is kept: avail - 1). */
size_t lumo_net_resync(const uint8_t *buf, size_t avail, size_t from);

/* ---- messages ------------------------------------------------------------------ */

/* HELLO: what the client is and wants (docs/protocol.md §2). */
typedef struct lumo_net_hello {
    uint32_t package;          /* which of the server's packages */
    uint32_t arena_bytes;      /* the client's arena, bytes */
    uint32_t max_payload;      /* the largest frame payload it takes */
    uint16_t width, height;    /* its display, pixels */
    uint8_t  ivg_form;         /* LUMO_IVG_FORM_* or LUMO_NET_FORM_NONE */
    uint8_t  flags;            /* LUMO_NET_FLAG_SMOOTHING */
    uint32_t resume_id;        /* 0: fresh */
    uint32_t mesh_count;       /* cursors that follow, <= LUMO_MAX_MESHES */
    const uint8_t *cursors;    /* mesh_count u32 (decode: into the frame) */
} lumo_net_hello;

/* One descriptor of a WELCOME (a session message, docs/client-session.md). */
typedef struct lumo_net_msg {
    uint32_t type, index, len;   /* a session message's type and index (lumo_session_feed); bytes */
    const uint8_t *data;         /* its payload (decode: into the frame) */
} lumo_net_msg;

/* WELCOME: the package's descriptors, the client's session messages. */
typedef struct lumo_net_welcome {
    uint32_t package_id;       /* the package's identity, for a resume */
    uint32_t arena_need;       /* arena bytes the whole scene takes */
    uint32_t count;            /* messages */
    const uint8_t *msgs;       /* decode: the packed messages, walk with lumo_net_welcome_next */
    size_t msgs_len;           /* bytes at msgs */
} lumo_net_welcome;

/* REQUEST: the next part of a channel. */
typedef struct lumo_net_request {
    uint8_t  channel;          /* lumo_net_channel */
    uint32_t mesh;             /* geometry: which mesh; lighting, updates: 0 */
    uint32_t cursor;           /* the first batch / round wanted; updates: the update position held */
    uint32_t amount;           /* vertices (geometry), rounds (lighting) or records (updates) wanted */
} lumo_net_request;

/* DATA: the answer to a REQUEST (docs/protocol.md §2 DATA). On the updates
 * channel (§9) first is the position the records start after (the cursor
 * asked) and count the position they bring the client to (> first). */
typedef struct lumo_net_data {
    uint8_t  channel;          /* lumo_net_channel */
    uint8_t  form;             /* lighting: the records' IVG form */
    uint32_t mesh;             /* geometry: which mesh; lighting, updates: 0 */
    uint32_t first, count, records;   /* first batch / round (updates: position held), how many (updates: position reached), records carried */
    const uint8_t *bytes;      /* decode: into the frame */
    uint32_t len;              /* bytes at bytes */
} lumo_net_data;
#define LUMO_NET_DATA_HEAD 24u   /* bytes of DATA's head, before the records */
/* The last 8 bytes of DATA's head (form, records) are the head of the
 * session's IVGR message, so the records feed the session in place. */
#define LUMO_NET_IVGR_HEAD 8u
/* On the PRT channel (§10) first = records = the span's byte offset in the
 * mesh's PRTV chunk and count its bytes: the last 4 bytes of the head are
 * the session's PRTS message's head. */
#define LUMO_NET_PRTS_HEAD 4u

/* END: a channel (of a mesh) has nothing more. */
typedef struct lumo_net_end {
    uint8_t  channel;          /* lumo_net_channel */
    uint32_t mesh;             /* geometry: which mesh; lighting: 0 */
} lumo_net_end;

/* ERROR: why the sender ends the conversation. */
typedef struct lumo_net_error {
    uint32_t status;           /* a lumo_status */
    uint32_t len;              /* bytes of text */
    const uint8_t *text;       /* len bytes without NUL, not NUL-terminated */
} lumo_net_error;

/* POSES (§9): the lights and meshes a dynamic scene has moved, in an
 * updates answer. Each pose is 24 bytes: u8 kind, 3 reserved, u32 index,
 * i32 x, y, z (Q16.16 m: a light's position, a mesh's translation from
 * where the package put it), i32 yaw (Q16.16 degrees about +y; lights 0). */
#define LUMO_NET_POSE_BYTES 24u
#define LUMO_NET_MAX_POSES  (LUMO_MAX_MESHES + LUMO_MAX_LIGHTS)
/* What a pose moves: a mesh or a light. */
enum { LUMO_NET_POSE_MESH = 0, LUMO_NET_POSE_LIGHT = 1 };
/* One pose of a POSES message (its 24 bytes decoded). */
typedef struct lumo_net_pose {
    uint8_t     kind;        /* LUMO_NET_POSE_MESH or _LIGHT */
    uint32_t    index;       /* the mesh's or light's index */
    lumo_q16_16 t[3];        /* metres */
    lumo_q16_16 yaw_deg;     /* degrees about +y (meshes) */
} lumo_net_pose;
/* A decoded POSES message: its count and packed poses. */
typedef struct lumo_net_poses {
    uint32_t count;          /* <= LUMO_NET_MAX_POSES */
    const uint8_t *raw;      /* decode: count packed poses, read with lumo_net_poses_get */
} lumo_net_poses;

/* Each encoder writes a whole frame (header, payload, CRC) at out[0..cap)
 * and sets *written; NOMEM when cap is too small (nothing written); ARG for
 * values outside the protocol, i.e. anything its decoder would refuse (e.g.
 * mesh_count > LUMO_MAX_MESHES, text longer than LUMO_NET_MAX_TEXT), checked
 * before the room. Each decoder takes a frame decoded by
 * lumo_net_frame_decode of its type (STATE for another type) and checks its
 * payload's exact layout and values (docs/protocol.md §5, "Decoder checks"):
 * shorter than the layout TRUNCATED, longer or ill-formed CORRUPT, a count
 * past a limit LIMIT, a field value outside its range RANGE.
 *
 * HELLO: the cursors come from `cursors` (mesh_count u32; NULL when
 * mesh_count is 0), m->cursors is ignored. */
lumo_status lumo_net_hello_encode(const lumo_net_hello *m, const uint32_t *cursors, uint8_t *out,
                                  size_t cap, size_t *written);
lumo_status lumo_net_hello_decode(const lumo_net_frame *f, lumo_net_hello *m);
/* Cursor i of a decoded HELLO (0 for i >= mesh_count). */
uint32_t lumo_net_hello_cursor(const lumo_net_hello *m, uint32_t i);

/* WELCOME: encoded from a list of messages. */
lumo_status lumo_net_welcome_encode(uint32_t package_id, uint32_t arena_need, const lumo_net_msg *msgs,
                                    uint32_t count, uint8_t *out, size_t cap, size_t *written);
lumo_status lumo_net_welcome_decode(const lumo_net_frame *f, lumo_net_welcome *m);
/* The next message of a decoded WELCOME: *at starts at 0; RANGE after the
 * last. (decode has checked the whole list already.) */
lumo_status lumo_net_welcome_next(const lumo_net_welcome *m, size_t *at, lumo_net_msg *out);

/* REQUEST: encoded and decoded as above. */
lumo_status lumo_net_request_encode(const lumo_net_request *m, uint8_t *out, size_t cap, size_t *written);
lumo_status lumo_net_request_decode(const lumo_net_frame *f, lumo_net_request *m);

/* DATA: the 24-byte head into out[LUMO_NET_HEADER..], then the bytes (which
 * may already be in place at out + LUMO_NET_HEADER + LUMO_NET_DATA_HEAD);
 * or only the head, for a sender that sends the bytes from a mapping
 * (lumo_net_data_head: writes LUMO_NET_HEADER + LUMO_NET_DATA_HEAD bytes
 * and returns the CRC state to continue over the bytes; it checks nothing:
 * m must be one lumo_net_data_encode takes). */
lumo_status lumo_net_data_encode(const lumo_net_data *m, uint8_t *out, size_t cap, size_t *written);
uint32_t lumo_net_data_head(const lumo_net_data *m, uint8_t out[LUMO_NET_HEADER + LUMO_NET_DATA_HEAD]);
lumo_status lumo_net_data_decode(const lumo_net_frame *f, lumo_net_data *m);

/* END: encoded and decoded as above. */
lumo_status lumo_net_end_encode(const lumo_net_end *m, uint8_t *out, size_t cap, size_t *written);
lumo_status lumo_net_end_decode(const lumo_net_frame *f, lumo_net_end *m);

/* ERROR: text is NUL-terminated (NULL: no text). */
lumo_status lumo_net_error_encode(uint32_t status, const char *text, uint8_t *out, size_t cap,
                                  size_t *written);
lumo_status lumo_net_error_decode(const lumo_net_frame *f, lumo_net_error *m);

/* BYE: the frame that ends a conversation. */
lumo_status lumo_net_bye_encode(uint8_t *out, size_t cap, size_t *written);
/* BYE has no fields: OK for an empty payload, CORRUPT for any other. */
lumo_status lumo_net_bye_decode(const lumo_net_frame *f);

/* POSES: count poses from p (kind 0 or 1, a light's yaw 0: ARG otherwise);
 * decode checks the count (LIMIT), the exact length (TRUNCATED /
 * CORRUPT) and every kind and light yaw (RANGE). */
lumo_status lumo_net_poses_encode(const lumo_net_pose *p, uint32_t count, uint8_t *out, size_t cap,
                                  size_t *written);
lumo_status lumo_net_poses_decode(const lumo_net_frame *f, lumo_net_poses *m);
/* Pose i of a decoded POSES (i < count). */
void lumo_net_poses_get(const lumo_net_poses *m, uint32_t i, lumo_net_pose *out);

/* ---- planning a geometry answer (§2 DATA "Geometry") --------------------------- */

/* Vertices held once batch records [0, b) of a stream are applied. */
uint32_t lumo_net_vertices_before(const lumo_pmesh_header *h, uint32_t b);

/* The end (exclusive) of the batches that answer a request for `amount`
 * vertices from batch `cursor`: as many whole batches as hold at most
 * amount vertices, at least one, never past batch_count. The server sends
 * exactly these; a client predicts its cursors with it. */
uint32_t lumo_net_geometry_end(const lumo_pmesh_header *h, uint32_t cursor, uint32_t amount);

#endif /* LUMO_NET_H */
