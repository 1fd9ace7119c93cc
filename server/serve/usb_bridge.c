/*
 * usb_bridge.c — the two pumps of a USB bridge (serve/usb.h): device IN to
 * a socket, the socket to device OUT under the binding's transfer rule
 * (lumo/net_usb.h). No libusb here: the transfers come through
 * srv_usb_io, so the pumps are tested with a device that disappears
 * (tests/usb/test_usb_bridge.c).
 */
#include "serve/usb.h"
#include "lumo/net_usb.h"

#include <errno.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

/* Wait up to SRV_USB_WAKE_MS for events on sock: 1 ready, 0 not yet, -1
 * the socket failed. */
static int wait_sock(int sock, short events)
{
    struct pollfd p = {sock, events, 0};
    int r = poll(&p, 1, (int)SRV_USB_WAKE_MS);

    if (r < 0)
        return errno == EINTR ? 0 : -1;
    if (r == 0)
        return 0;
    return (p.revents & (POLLERR | POLLNVAL)) ? -1 : 1;
}

/* All n bytes into the socket (non-blocking, waiting for room). 0, or the
 * reason it stopped. */
static srv_usb_end to_socket(const srv_usb_io *io, int sock, const uint8_t *p, size_t n)
{
    while (n) {
        ssize_t w;
        int r;

        if (*io->stop)
            return SRV_USB_END_STOP;
        if ((r = wait_sock(sock, POLLOUT)) < 0)
            return SRV_USB_END_SOCKET;
        if (r == 0)
            continue;
        w = send(sock, p, n, MSG_NOSIGNAL | MSG_DONTWAIT);
        if (w < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR))
            continue;
        if (w <= 0)
            return SRV_USB_END_SOCKET;
        p += w;
        n -= (size_t)w;
    }
    return 0;
}

srv_usb_end srv_usb_pump_in(const srv_usb_io *io, int sock)
{
    uint8_t buf[LUMO_USB_TRANSFER];
    srv_usb_end why = SRV_USB_END_STOP;

    while (!*io->stop) {
        size_t got = 0;
        int r = io->bulk_in(io->ctx, buf, sizeof buf, &got, SRV_USB_WAKE_MS);
        /* bytes that came before a timeout or a failure still belong to the stream */
        if (got && (why = to_socket(io, sock, buf, got)) != 0) {
            why = *io->stop ? SRV_USB_END_STOP : why;   /* shut by the other pump */
            break;
        }
        why = SRV_USB_END_STOP;
        if (r != SRV_USB_OK) {
            why = SRV_USB_END_DEVICE;
            break;
        }
    }
    *io->stop = 1;
    shutdown(sock, SHUT_RDWR);
    return why;
}

/* All n bytes to the device, each transfer cut by the rule. */
static srv_usb_end to_device(const srv_usb_io *io, const uint8_t *p, size_t n)
{
    while (n) {
        size_t k = lumo_net_usb_transfer(n, LUMO_USB_TRANSFER, io->mps), done = 0;

        if (*io->stop)
            return SRV_USB_END_STOP;
        if (k == 0 || io->bulk_out(io->ctx, p, k, &done, SRV_USB_WAKE_MS) != SRV_USB_OK)
            return SRV_USB_END_DEVICE;
        /* a timeout may have moved part of it: the rest goes as a transfer of its own */
        p += done;
        n -= done;
    }
    return 0;
}

srv_usb_end srv_usb_pump_out(const srv_usb_io *io, int sock)
{
    uint8_t buf[LUMO_USB_TRANSFER];
    srv_usb_end why = SRV_USB_END_STOP;

    while (!*io->stop) {
        ssize_t n;
        int r = wait_sock(sock, POLLIN);

        if (r < 0) {
            why = *io->stop ? SRV_USB_END_STOP : SRV_USB_END_SOCKET;
            break;
        }
        if (r == 0)
            continue;
        n = recv(sock, buf, sizeof buf, MSG_DONTWAIT);
        if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR))
            continue;
        if (n <= 0) {
            /* the loop closed the connection, or the other pump shut it */
            why = *io->stop ? SRV_USB_END_STOP : SRV_USB_END_SOCKET;
            break;
        }
        if ((why = to_device(io, buf, (size_t)n)) != 0)
            break;
        why = SRV_USB_END_STOP;
    }
    *io->stop = 1;
    shutdown(sock, SHUT_RDWR);
    return why;
}
