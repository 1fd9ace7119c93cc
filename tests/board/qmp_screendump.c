/*
 * qmp_screendump.c — take a QEMU screendump through QMP and quit QEMU
 * (boards/lm3s6965evb/client-test.sh: the lm3s6965evb's OLED).
 *
 *   qmp-screendump SOCKET OUT.ppm
 *
 * SOCKET is QEMU's `-qmp unix:SOCKET,server=on,wait=off`. Sends
 * qmp_capabilities, screendump (of the default console: the SSD0323's) and
 * quit, each after the answer to the one before; exit 0 when the screendump
 * was answered with "return", 1 otherwise (the answer is printed).
 */
#define _POSIX_C_SOURCE 200809L
#include <poll.h>
#include <stdio.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

/* Read until a line holding "return" or "error" (events are skipped), 10 s
 * at most; the line in buf. */
static int answer(int fd, char *buf, size_t cap)
{
    size_t n = 0;

    for (;;) {
        struct pollfd p = {fd, POLLIN, 0};
        char *nl;
        ssize_t r;
        if (poll(&p, 1, 10000) != 1 || (r = read(fd, buf + n, cap - 1 - n)) <= 0)
            return -1;
        n += (size_t)r;
        buf[n] = '\0';
        while ((nl = strchr(buf, '\n')) != NULL) {
            *nl = '\0';
            if (strstr(buf, "\"return\"") || strstr(buf, "\"error\""))
                return strstr(buf, "\"return\"") ? 0 : 1;
            n -= (size_t)(nl + 1 - buf);
            memmove(buf, nl + 1, n + 1);
        }
        if (n + 1 >= cap)
            return -1;
    }
}

static int ask(int fd, const char *cmd, char *buf, size_t cap)
{
    size_t len = strlen(cmd);

    return write(fd, cmd, len) == (ssize_t)len ? answer(fd, buf, cap) : -1;
}

int main(int argc, char **argv)
{
    struct sockaddr_un a;
    char cmd[1200], buf[4096];
    int fd, rc;

    if (argc != 3 || strlen(argv[1]) >= sizeof a.sun_path || strlen(argv[2]) > 1000) {
        fprintf(stderr, "usage: qmp-screendump SOCKET OUT.ppm\n");
        return 2;
    }
    memset(&a, 0, sizeof a);
    a.sun_family = AF_UNIX;
    strcpy(a.sun_path, argv[1]);
    if ((fd = socket(AF_UNIX, SOCK_STREAM, 0)) < 0 || connect(fd, (struct sockaddr *)&a, sizeof a) != 0) {
        perror("qmp-screendump: connect");
        return 1;
    }
    /* the greeting, then capabilities negotiation */
    if (ask(fd, "{\"execute\":\"qmp_capabilities\"}\n", buf, sizeof buf) != 0) {
        fprintf(stderr, "qmp-screendump: no QMP greeting or capabilities: %s\n", buf);
        return 1;
    }
    snprintf(cmd, sizeof cmd, "{\"execute\":\"screendump\",\"arguments\":{\"filename\":\"%s\"}}\n", argv[2]);
    rc = ask(fd, cmd, buf, sizeof buf);
    if (rc != 0)
        fprintf(stderr, "qmp-screendump: screendump: %s\n", buf);
    (void)ask(fd, "{\"execute\":\"quit\"}\n", buf, sizeof buf);
    close(fd);
    return rc == 0 ? 0 : 1;
}
