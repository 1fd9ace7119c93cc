/*
 * link_replay.c — replay files (docs/protocol.md "Replay files"): the frames
 * a client took, each exactly as it was received, one after the other, and
 * nothing else — no header, no timing. Over a TCP connection that was never
 * cut that is the received byte stream itself; what is left out otherwise is
 * what the driver never took (a frame cut by a dropped connection, the
 * WELCOME of a resumed connection, the garbage, damaged and stale frames of
 * a serial line). Replaying feeds the frames to a driver in replay mode
 * (lumo_net_client_config.replay): applied in their order, nothing asked, so
 * the session passes through the states of the recorded run, and the
 * pictures drawn at them are the same byte for byte.
 */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>
#include "client.h"

int record_open(FILE **f, const char *path, char *err, size_t errlen)
{
    if (!(*f = fopen(path, "wb"))) {
        snprintf(err, errlen, "%s: %s", path, strerror(errno));
        return -1;
    }
    return 0;
}

int record_frame(FILE *f, const uint8_t *frame, size_t n)
{
    return f && (fwrite(frame, 1, n, f) != n || fflush(f)) ? -1 : 0;
}

static int replay_open(client_link *l)
{
    if ((l->fd = open(l->target, O_RDONLY | O_CLOEXEC)) < 0) {
        snprintf(l->err, sizeof l->err, "%s: %s", l->target, strerror(errno));
        return -1;
    }
    return 0;
}

/* A recording answers what was asked when it was made: nothing goes out. */
static int replay_send(client_link *l, const uint8_t *p, size_t n)
{
    (void)l, (void)p, (void)n;
    return 0;
}

static long replay_read(client_link *l, uint8_t *buf, size_t cap, int timeout_ms)
{
    ssize_t n;

    (void)timeout_ms;
    do
        n = read(l->fd, buf, cap);
    while (n < 0 && errno == EINTR);
    if (n < 0) {
        snprintf(l->err, sizeof l->err, "%s: %s", l->target, strerror(errno));
        return LINK_ERROR;
    }
    l->bytes_in += (uint64_t)n;
    return (long)n;
}

static void replay_close(client_link *l)
{
    if (l->fd >= 0)
        close(l->fd);
    l->fd = -1;
}

const link_ops link_replay = {"replay", 0, 0, replay_open, replay_send, replay_read, replay_close};
