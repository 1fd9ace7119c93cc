/* package_write.c — the .lumo container: header, chunk table, CRC-32 per
 * chunk (docs/package-format.md). The CRC is the client's own function, so
 * writer and reader cannot disagree. */
#include <errno.h>
#include <sys/stat.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "lumo/package.h"
#include "package/package_write.h"
#include "lumo/wire.h"

void srv_buf_put(srv_buf *b, const void *data, size_t n)
{
    if (b->failed)
        return;
    if (b->len + n > b->cap) {
        size_t cap = b->cap ? b->cap : 256;
        while (cap < b->len + n)
            cap *= 2;
        uint8_t *p = realloc(b->p, cap);
        if (!p) {
            b->failed = 1;
            return;
        }
        b->p = p;
        b->cap = cap;
    }
    if (n)
        memcpy(b->p + b->len, data, n);
    b->len += n;
}

void srv_buf_u16(srv_buf *b, uint32_t v)
{
    uint8_t x[2];
    lumo_wire_put_le16(x, (uint16_t)v);
    srv_buf_put(b, x, 2);
}

void srv_buf_u32(srv_buf *b, uint32_t v)
{
    uint8_t x[4];
    lumo_wire_put_le32(x, v);
    srv_buf_put(b, x, 4);
}

void srv_buf_f32(srv_buf *b, float v)
{
    uint32_t u;
    memcpy(&u, &v, 4);
    srv_buf_u32(b, u);
}

void srv_buf_vec3(srv_buf *b, vec3 v)
{
    srv_buf_f32(b, v.x);
    srv_buf_f32(b, v.y);
    srv_buf_f32(b, v.z);
}

void srv_buf_free(srv_buf *b)
{
    free(b->p);
    memset(b, 0, sizeof *b);
}

void srv_pkgw_init(srv_pkg_writer *w)
{
    memset(w, 0, sizeof *w);
}

void srv_pkgw_free(srv_pkg_writer *w)
{
    for (size_t i = 0; i < w->n; i++)
        srv_buf_free(&w->chunks[i].data);
    free(w->chunks);
    memset(w, 0, sizeof *w);
}

lumo_status srv_pkgw_add(srv_pkg_writer *w, uint32_t type, const void *data, size_t len)
{
    if (w->n == LUMO_PKG_MAX_CHUNKS || len > UINT32_MAX / 2)
        return LUMO_ERR_LIMIT;
    if (w->n == w->cap) {
        size_t cap = w->cap ? 2 * w->cap : 8;
        void *p = realloc(w->chunks, cap * sizeof *w->chunks);
        if (!p)
            return LUMO_ERR_NOMEM;
        w->chunks = p;
        w->cap = cap;
    }
    memset(&w->chunks[w->n], 0, sizeof w->chunks[w->n]);
    w->chunks[w->n].type = type;
    srv_buf_put(&w->chunks[w->n].data, data, len);
    if (w->chunks[w->n].data.failed)
        return LUMO_ERR_NOMEM;
    w->n++;
    return LUMO_OK;
}

static const uint8_t k_zero[4];

lumo_status srv_pkgw_serialize(const srv_pkg_writer *w, uint8_t **out, size_t *len)
{
    srv_buf table = {0}, file = {0};
    size_t pos = LUMO_PKG_HEADER_SIZE + w->n * LUMO_PKG_ENTRY_SIZE;
    for (size_t i = 0; i < w->n; i++) {
        const srv_buf *d = &w->chunks[i].data;
        pos = (pos + 3u) & ~(size_t)3u;          /* chunks start 4-byte aligned */
        srv_buf_u32(&table, w->chunks[i].type);
        srv_buf_u32(&table, (uint32_t)pos);
        srv_buf_u32(&table, (uint32_t)d->len);
        srv_buf_u32(&table, lumo_wire_crc32(0, d->p, d->len));
        pos += d->len;
    }
    if (pos > UINT32_MAX) {
        srv_buf_free(&table);
        return LUMO_ERR_LIMIT;
    }
    srv_buf_put(&file, "LUMO", 4);
    srv_buf_u16(&file, LUMO_PKG_VERSION_MAJOR);
    srv_buf_u16(&file, LUMO_PKG_VERSION_MINOR);
    srv_buf_u32(&file, (uint32_t)w->n);
    srv_buf_u32(&file, 0);                         /* flags */
    srv_buf_u32(&file, lumo_wire_crc32(0, table.p, table.len));
    srv_buf_u32(&file, file.failed ? 0 : lumo_wire_crc32(0, file.p, 20));
    srv_buf_put(&file, table.p, table.len);
    for (size_t i = 0; i < w->n; i++) {
        srv_buf_put(&file, k_zero, (4u - (file.len & 3u)) & 3u);
        srv_buf_put(&file, w->chunks[i].data.p, w->chunks[i].data.len);
    }
    int failed = file.failed || table.failed;
    srv_buf_free(&table);
    if (failed) {
        srv_buf_free(&file);
        return LUMO_ERR_NOMEM;
    }
    *out = file.p;
    *len = file.len;
    return LUMO_OK;
}

lumo_status srv_pkgw_write_file(const srv_pkg_writer *w, const char *path, char *err,
                                size_t errlen)
{
    uint8_t *data;
    size_t len;
    lumo_status st = srv_pkgw_serialize(w, &data, &len);
    if (st) {
        snprintf(err, errlen, "%s: package too large or out of memory", path);
        return st;
    }
    /* Written beside and renamed into place: a writer killed half-way
     * (an MPI job stopped, docs/server.md) never leaves a partial package
     * under the package's name. A path that exists and is not a regular
     * file (/dev/null, a pipe, a terminal) is written in place: renaming
     * over it would replace the device or pipe itself. */
    char tmp[4096];
    struct stat sb;
    int in_place = stat(path, &sb) == 0 && !S_ISREG(sb.st_mode);
    errno = 0;
    int ok = in_place || snprintf(tmp, sizeof tmp, "%s.partial", path) < (int)sizeof tmp;
    FILE *f = ok ? fopen(in_place ? path : tmp, "wb") : NULL;
    ok = f && fwrite(data, 1, len, f) == len;
    if (f && fclose(f))
        ok = 0;
    if (ok && !in_place && rename(tmp, path))
        ok = 0;
    int why = errno;
    free(data);
    if (!ok) {
        if (f && !in_place)
            remove(tmp);
        snprintf(err, errlen, "%s: cannot write: %s", path, why ? strerror(why) : "short write");
        return LUMO_ERR_IO;
    }
    return LUMO_OK;
}
