/* import_io.c — import_io.h: assimp's file callbacks over stdio, regular
 * files only. */
#include <assimp/cfileio.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "scene/import_io.h"
#include "scene/model_check.h"

static FILE *fp_of(struct aiFile *f)
{
    return (FILE *)(void *)f->UserData;
}

static size_t io_read(struct aiFile *f, char *buf, size_t size, size_t count)
{
    return fread(buf, size, count, fp_of(f));
}

static size_t io_write(struct aiFile *f, const char *buf, size_t size, size_t count)
{
    (void)f, (void)buf, (void)size, (void)count;
    return 0;   /* reading only */
}

static size_t io_tell(struct aiFile *f)
{
    long p = ftell(fp_of(f));
    return p < 0 ? 0 : (size_t)p;
}

static size_t io_size(struct aiFile *f)
{
    struct stat st;
    return fstat(fileno(fp_of(f)), &st) ? 0 : (size_t)st.st_size;
}

static enum aiReturn io_seek(struct aiFile *f, size_t off, enum aiOrigin o)
{
    int whence = o == aiOrigin_SET ? SEEK_SET : o == aiOrigin_CUR ? SEEK_CUR : SEEK_END;
    return fseek(fp_of(f), (long)off, whence) ? aiReturn_FAILURE : aiReturn_SUCCESS;
}

static void io_flush(struct aiFile *f)
{
    (void)f;
}

/* O_NONBLOCK: opening a FIFO must not wait for a writer; fstat on the
 * descriptor, so the file checked is the file read. */
static FILE *open_regular(const char *path)
{
    struct stat st;
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    FILE *fp;
    if (fd < 0)
        return NULL;
    if (fstat(fd, &st) || !S_ISREG(st.st_mode) || (unsigned long long)st.st_size > SRV_MODEL_MAX_BYTES ||
        fcntl(fd, F_SETFL, 0) || !(fp = fdopen(fd, "rb"))) {
        close(fd);
        return NULL;
    }
    return fp;
}

static struct aiFile *io_open(struct aiFileIO *io, const char *path, const char *mode)
{
    struct aiFile *f;
    FILE *fp;
    (void)io;
    if (!path || !mode || strpbrk(mode, "wa+") || !(fp = open_regular(path)))
        return NULL;
    if (!(f = calloc(1, sizeof *f))) {
        fclose(fp);
        return NULL;
    }
    f->ReadProc = io_read, f->WriteProc = io_write, f->TellProc = io_tell, f->FileSizeProc = io_size;
    f->SeekProc = io_seek, f->FlushProc = io_flush, f->UserData = (aiUserData)(void *)fp;
    return f;
}

static void io_close(struct aiFileIO *io, struct aiFile *f)
{
    (void)io;
    if (!f)
        return;
    fclose(fp_of(f));
    free(f);
}

struct aiFileIO *srv_import_io(void)
{
    static struct aiFileIO io = {io_open, io_close, NULL};
    return &io;
}
