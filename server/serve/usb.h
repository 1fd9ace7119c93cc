/*
 * serve/usb.h — lumo-server's USB side (lumo-server --usb, docs/server.md
 * "USB", the binding of docs/protocol.md §8 "USB" and lumo/net_usb.h).
 *
 * A watcher thread finds thin clients with libusb: every interface of class
 * FF, subclass 4C, protocol 01 (on one VID:PID when given). It scans when
 * libusb's hotplug reports an arrival (where libusb offers hotplug) and
 * every SRV_USB_POLL_MS anyway (hotplug needs a udev daemon on Linux; an
 * initramfs or a container has none). Each scan opens a fresh libusb
 * context, so devices that came since the last one are seen either way.
 *
 * Each device found is claimed and bridged: two threads move bytes between
 * its bulk endpoints and one end of a socketpair (IN to the socket, the
 * socket to OUT, each transfer cut by lumo_net_usb_transfer); the other
 * end goes to the event loop as a connection like an accepted TCP one
 * (serve/conn.h, reliable: a refused frame ends it). So the session, the
 * backpressure (a bridge writes to the socket only as the loop reads) and
 * the link emulation are the TCP ones, and the loop stays one thread with
 * no libusb in it. A device that goes away (the bulk transfer says
 * NO_DEVICE or fails) shuts its socket: the loop closes that connection
 * only. A connection the loop closes ends its bridge and releases the
 * interface. One session per enumeration: a device comes back with a new
 * address, and its client resumes with HELLO and its cursors as after a
 * TCP cut (docs/protocol.md §8).
 *
 * Memory: per device, a bridge (two 16 KiB buffers, two threads, a libusb
 * context); nothing grows with the scene.
 */
#ifndef SRV_SERVE_USB_H
#define SRV_SERVE_USB_H

#include <stdatomic.h>
#include <stddef.h>
#include <stdint.h>
#include "lumo/status.h"

#define SRV_USB_POLL_MS  500u   /* scan this often even with hotplug */
#define SRV_USB_WAKE_MS  200u   /* a bridge thread checks for the end this often */

typedef struct srv_usb srv_usb;

/* Parse "VID:PID" (hex, e.g. 1209:0001). 0 or -1. */
int srv_usb_parse_id(const char *t, uint16_t *vid, uint16_t *pid);

/* Start watching (any_id: every VID:PID). LUMO_ERR_IO with err when libusb
 * cannot start (no usbfs: no USB on this machine), NOMEM. */
lumo_status srv_usb_start(srv_usb **out, int any_id, uint16_t vid, uint16_t pid, char *err, size_t errlen);
/* Readable when a device's connection waits to be taken. */
int srv_usb_event_fd(const srv_usb *u);
/* The socket of the next device's connection (non-blocking; the caller
 * owns it) and its name ("usb:BUS-PORT.PORT VVVV:PPPP"), or -1 when none
 * waits. */
int srv_usb_take(srv_usb *u, char *peer, size_t cap);
/* Stop watching, end every bridge (their sockets shut), free. */
void srv_usb_stop(srv_usb *u);

/* ---- the bridge's pumps, apart from libusb (tests/usb/test_usb_bridge.c) ---- */

/* A bulk transfer of at most n bytes, returning within timeout_ms:
 * SRV_USB_OK (*done bytes moved, possibly 0 at a timeout) or SRV_USB_GONE
 * (the device went away or the endpoint failed). */
enum { SRV_USB_OK = 0, SRV_USB_GONE = -1 };
typedef struct srv_usb_io {
    int (*bulk_in)(void *ctx, uint8_t *buf, size_t cap, size_t *done, unsigned timeout_ms);
    int (*bulk_out)(void *ctx, const uint8_t *buf, size_t n, size_t *done, unsigned timeout_ms);
    void *ctx;
    uint32_t mps;              /* the OUT endpoint's wMaxPacketSize */
    atomic_int *stop;          /* set by anyone: both pumps end within SRV_USB_WAKE_MS */
} srv_usb_io;

/* Why a pump ended. */
typedef enum srv_usb_end { SRV_USB_END_STOP = 1, SRV_USB_END_DEVICE, SRV_USB_END_SOCKET } srv_usb_end;

/* Device IN to the socket sock (blocking) until the device goes, the
 * socket closes or *stop. Sets *stop on the way out. */
srv_usb_end srv_usb_pump_in(const srv_usb_io *io, int sock);
/* The socket to device OUT, every transfer cut by lumo_net_usb_transfer,
 * until the socket's peer closes, the device goes or *stop. Sets *stop. */
srv_usb_end srv_usb_pump_out(const srv_usb_io *io, int sock);

#endif
