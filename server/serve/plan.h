/*
 * serve/plan.h — a REQUEST mapped to byte ranges of the package
 * (docs/protocol.md §2 REQUEST, DATA, END).
 *
 * Geometry (cursor c, amount n): batches c, c+1, ... as many whole batches
 * as hold at most n vertices together, at least one. Lighting (cursor c,
 * amount k): rounds c .. c+k-1 (fewer at the end). Past the end: END.
 *
 * An answer is produced one DATA frame at a time (srv_plan_next), each a
 * slice of the mapping under the client's max payload: whole records (a
 * batch record larger than the payload is LIMIT, found when the request is
 * planned), whole rounds, or a round too large for one frame split at
 * record boundaries (count 0 in all but the frame that ends the round). The
 * state is a few integers: the server keeps no per-client scene state.
 */
#ifndef SRV_SERVE_PLAN_H
#define SRV_SERVE_PLAN_H

#include <stdint.h>
#include "lumo/net.h"
#include "lumo/status.h"
#include "serve/index.h"

typedef struct srv_answer {
    uint8_t  channel;    /* LUMO_NET_GEOMETRY / LUMO_NET_LIGHTING */
    uint8_t  form;       /* lighting: the records' form */
    uint32_t mesh;
    uint32_t next, end;  /* batches or rounds still to send: [next, end) */
    uint32_t rec;        /* lighting: the next record (absolute index); past
                            first[next] while a round is being split */
    uint32_t pos;        /* lighting: its byte offset in the records area */
    uint32_t max_data;   /* bytes of records per frame: max payload - 24 */
} srv_answer;

/* Plan the answer to request r for a client with this max payload and IVG
 * form (LUMO_NET_FORM_NONE: none asked). *end_of_channel = 1 when the
 * answer is END (cursor at the end): nothing to plan. Errors: RANGE (mesh
 * past the count, cursor past the end, zero amount, unknown channel, a
 * lighting request without an IVG or without a form), LIMIT (a batch record
 * of the range does not fit the client's max payload). A message for a
 * person in err. */
lumo_status srv_plan_start(const srv_pkg *p, const lumo_net_request *r, uint8_t form, uint32_t max_payload,
                           srv_answer *a, int *end_of_channel, char *err, size_t errlen);

/* The next DATA frame of the answer: its head fields and bytes (d->bytes
 * points into the mapping). Returns 1 when a frame was produced, 0 when
 * the answer is complete. */
int srv_plan_next(const srv_pkg *p, srv_answer *a, lumo_net_data *d);


#endif
