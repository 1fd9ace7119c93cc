/*
 * checkpoint.h — a long bake that can resume: the chunks of a srv_work
 * (work.h) appended to DIR/<name>.ckpt as they complete, read back by the
 * next run with the same key, which then computes only the rest. Since the
 * output of a chunk does not depend on who computed it, the resumed result
 * is byte-identical to an uninterrupted one.
 *
 * File (little-endian): a 48-byte header — "LUMOCKPT", u32 version 1,
 * u64 key, u64 items, u64 item_bytes, u64 chunk_items, u32 CRC-32 of the
 * 44 bytes before it — then records: u64 chunk index, the chunk's bytes,
 * u32 CRC-32 of index and bytes. Records are written with one write(2)
 * each, so a killed process leaves at most one torn record at the end; a
 * record that is short, out of range or fails its CRC ends the valid part
 * (the file is cut there and the rest recomputed). A file is outside data:
 * every field is checked, nothing is trusted.
 */
#ifndef SRV_CHECKPOINT_H
#define SRV_CHECKPOINT_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include "bake/work.h"

#define SRV_CKPT_HEADER 48

typedef struct srv_ckpt {
    int  fd;             /* open for appending, -1 when closed */
    char path[4096];
} srv_ckpt;

/* Open (creating DIR and the file when needed) the checkpoint of w in dir.
 * Chunks found are copied into out (w->items * w->item_bytes bytes) and
 * flagged in done[chunk] = 1 (srv_work_chunks(w) bytes, zeroed by the
 * caller); *resumed counts them. LUMO_OK; LUMO_ERR_STATE when the file
 * belongs to another bake (other key or sizes) or is not a checkpoint;
 * LUMO_ERR_IO when it cannot be read, cut or created. err says which. */
lumo_status srv_ckpt_open(srv_ckpt *ck, const char *dir, const srv_work *w, uint8_t *out, uint8_t *done,
                          size_t *resumed, char *err, size_t errlen);

/* Append chunk c (its bytes, srv_work_chunk's count * item_bytes). */
lumo_status srv_ckpt_append(srv_ckpt *ck, const srv_work *w, size_t c, const uint8_t *data, char *err,
                            size_t errlen);
void srv_ckpt_close(srv_ckpt *ck);

/* The reader, on any stream (the fuzz target feeds it arbitrary bytes
 * through fmemopen): checks the header against w, then copies every valid
 * record as srv_ckpt_open does. *valid_end: the length of the valid prefix
 * (0 for an empty stream). LUMO_OK, or LUMO_ERR_STATE for a header that is
 * not w's (message in err). */
lumo_status srv_ckpt_read(FILE *f, const srv_work *w, uint8_t *out, uint8_t *done, size_t *resumed,
                          long *valid_end, char *err, size_t errlen);

#endif
