/* checkpoint.c — resumable chunks of a srv_work (format in checkpoint.h). */
#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "bake/checkpoint.h"
#include "lumo/wire.h"

#define CKPT_VERSION 1
static const char k_magic[8] = {'L', 'U', 'M', 'O', 'C', 'K', 'P', 'T'};

static void header_bytes(const srv_work *w, uint8_t h[SRV_CKPT_HEADER])
{
    memcpy(h, k_magic, 8);
    lumo_wire_put_le32(h + 8, CKPT_VERSION);
    lumo_wire_put_le64(h + 12, w->key);
    lumo_wire_put_le64(h + 20, w->items);
    lumo_wire_put_le64(h + 28, w->item_bytes);
    lumo_wire_put_le64(h + 36, w->chunk_items);
    lumo_wire_put_le32(h + 44, lumo_wire_crc32(0, h, 44));
}

/* One record at the stream's position: 1 when valid and new (copied into
 * out, flagged in done), 0 when valid but a repeat, -1 at the end of the
 * valid part. buf holds the largest chunk. */
static int read_record(FILE *f, const srv_work *w, uint8_t *buf, uint8_t *out, uint8_t *done)
{
    uint8_t head[8], tail[4];
    size_t first, count;
    if (fread(head, 1, 8, f) != 8)
        return -1;
    uint64_t c = lumo_wire_le64(head);
    if (c >= srv_work_chunks(w))
        return -1;
    srv_work_chunk(w, (size_t)c, &first, &count);
    size_t len = count * w->item_bytes;
    if (fread(buf, 1, len, f) != len || fread(tail, 1, 4, f) != 4)
        return -1;
    if (lumo_wire_le32(tail) != lumo_wire_crc32(lumo_wire_crc32(0, head, 8), buf, len))
        return -1;
    if (done[c])
        return 0;
    memcpy(out + first * w->item_bytes, buf, len);
    done[c] = 1;
    return 1;
}

lumo_status srv_ckpt_read(FILE *f, const srv_work *w, uint8_t *out, uint8_t *done, size_t *resumed,
                          long *valid_end, char *err, size_t errlen)
{
    uint8_t want[SRV_CKPT_HEADER], got[SRV_CKPT_HEADER];
    size_t n = fread(got, 1, sizeof got, f);
    *resumed = 0;
    *valid_end = 0;
    if (n == 0)
        return LUMO_OK;   /* created, killed before its header: a fresh start */
    header_bytes(w, want);
    if (n != sizeof got || memcmp(got, want, sizeof got)) {
        snprintf(err, errlen, "it is not the checkpoint of this bake (another scene, grid, spp, seed or "
                              "lumo-bake): remove it or give another --checkpoint directory");
        return LUMO_ERR_STATE;
    }
    uint8_t *buf = malloc(w->chunk_items * w->item_bytes);
    if (!buf) {
        snprintf(err, errlen, "out of memory");
        return LUMO_ERR_NOMEM;
    }
    long end = (long)sizeof got;
    for (int r; (r = read_record(f, w, buf, out, done)) >= 0; end = ftell(f))
        *resumed += (size_t)r;
    free(buf);
    *valid_end = end;
    return LUMO_OK;
}

static lumo_status io_error(srv_ckpt *ck, const char *what, char *err, size_t errlen)
{
    snprintf(err, errlen, "checkpoint %s: %s: %s", ck->path, what, strerror(errno));
    if (ck->fd >= 0)
        close(ck->fd);
    ck->fd = -1;
    return LUMO_ERR_IO;
}

/* Read what is there, cut the file after its valid part, write a header
 * when it had none. */
static lumo_status resume(srv_ckpt *ck, const srv_work *w, uint8_t *out, uint8_t *done, size_t *resumed,
                          char *err, size_t errlen)
{
    char why[400];
    long end;
    FILE *f = fdopen(dup(ck->fd), "rb");
    if (!f)
        return io_error(ck, "cannot read", err, errlen);
    lumo_status st = srv_ckpt_read(f, w, out, done, resumed, &end, why, sizeof why);
    fclose(f);
    if (st) {
        snprintf(err, errlen, "checkpoint %s: %s", ck->path, why);
        close(ck->fd);
        ck->fd = -1;
        return st;
    }
    if (ftruncate(ck->fd, end) || lseek(ck->fd, 0, SEEK_END) < 0)
        return io_error(ck, "cannot cut its damaged end", err, errlen);
    if (end == 0) {
        uint8_t h[SRV_CKPT_HEADER];
        header_bytes(w, h);
        if (write(ck->fd, h, sizeof h) != (ssize_t)sizeof h)
            return io_error(ck, "cannot write", err, errlen);
    }
    return LUMO_OK;
}

lumo_status srv_ckpt_open(srv_ckpt *ck, const char *dir, const srv_work *w, uint8_t *out, uint8_t *done,
                          size_t *resumed, char *err, size_t errlen)
{
    ck->fd = -1;
    *resumed = 0;
    if (snprintf(ck->path, sizeof ck->path, "%s/%s.ckpt", dir, w->name) >= (int)sizeof ck->path) {
        snprintf(err, errlen, "checkpoint directory name too long");
        return LUMO_ERR_LIMIT;
    }
    if (mkdir(dir, 0777) && errno != EEXIST) {
        snprintf(err, errlen, "checkpoint directory %s: %s", dir, strerror(errno));
        return LUMO_ERR_IO;
    }
    ck->fd = open(ck->path, O_RDWR | O_CREAT | O_CLOEXEC, 0666);
    if (ck->fd < 0)
        return io_error(ck, "cannot open", err, errlen);
    return resume(ck, w, out, done, resumed, err, errlen);
}

lumo_status srv_ckpt_append(srv_ckpt *ck, const srv_work *w, size_t c, const uint8_t *data, char *err,
                            size_t errlen)
{
    size_t first, count;
    srv_work_chunk(w, c, &first, &count);
    size_t len = count * w->item_bytes, total = 8 + len + 4;
    uint8_t *rec = malloc(total);
    if (!rec) {
        snprintf(err, errlen, "out of memory");
        return LUMO_ERR_NOMEM;
    }
    lumo_wire_put_le64(rec, c);
    memcpy(rec + 8, data, len);
    lumo_wire_put_le32(rec + 8 + len, lumo_wire_crc32(0, rec, 8 + len));
    /* One write per record: a process killed here leaves one torn record,
     * which the next run's CRC check drops. */
    ssize_t put = write(ck->fd, rec, total);
    free(rec);
    if (put != (ssize_t)total)
        return io_error(ck, "cannot append (disk full?)", err, errlen);
    return LUMO_OK;
}

void srv_ckpt_close(srv_ckpt *ck)
{
    if (ck->fd >= 0)
        close(ck->fd);
    ck->fd = -1;
}
