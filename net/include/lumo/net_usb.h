/*
 * lumo/net_usb.h — the stream protocol's USB binding (docs/protocol.md §8
 * "USB"): the interface a thin client offers and the one rule bulk
 * transfers follow. Both sides use it: lumo-server's libusb side
 * (server/serve/usb.c) and the FunctionFS gadget client
 * (boards/linux-gadget/).
 *
 * The frames are those of TCP: a byte stream, reliable, in order. On USB
 * the stream is carried by one bulk OUT endpoint (host to device) and one
 * bulk IN endpoint (device to host) of a vendor-specific interface. A bulk
 * transfer ends at a short packet (less than wMaxPacketSize) or when the
 * reader's buffer is full; a transfer whose length is an exact multiple of
 * wMaxPacketSize ends with a full packet, and a reader whose buffer is
 * larger keeps waiting for more. lumo's rule: **no transfer is a multiple
 * of wMaxPacketSize** — the writer sends such a length less one byte, and
 * that byte opens the next transfer (lumo_net_usb_transfer). So every
 * transfer ends with a short packet, the reader never waits for bytes not
 * yet written, and neither side needs zero-length packets (which not every
 * device controller, nor every FunctionFS version, sends on request).
 * Transfer boundaries carry no meaning: frames delimit themselves.
 *
 * Client rules: C99, no heap, no float.
 */
#ifndef LUMO_NET_USB_H
#define LUMO_NET_USB_H

#include <stddef.h>
#include <stdint.h>

/* The interface: vendor-specific class, subclass 'L', protocol 1 (this
 * binding). The server claims every interface with these three values, on
 * any VID:PID unless told one. */
#define LUMO_USB_CLASS     0xFFu
#define LUMO_USB_SUBCLASS  0x4Cu
#define LUMO_USB_PROTOCOL  0x01u
/* The gadget's default VID:PID: pid.codes' test pair (1209:0001), for
 * development only; a product uses its own. */
#define LUMO_USB_VID       0x1209u
#define LUMO_USB_PID       0x0001u
/* Bulk wMaxPacketSize at full, high and super speed. */
#define LUMO_USB_MPS_FS    64u
#define LUMO_USB_MPS_HS    512u
#define LUMO_USB_MPS_SS    1024u
/* The largest transfer either side writes at once (bytes). */
#define LUMO_USB_TRANSFER  16384u

/* Bytes of the next transfer when n bytes are waiting: at most cap, never
 * a non-zero multiple of mps (then one byte less). 0 when n is 0, or when
 * the rule cannot be met (mps 0 or 1, cap 0). A writer that does not know
 * the speed the link runs at passes LUMO_USB_MPS_FS: the larger packet
 * sizes are multiples of it, so the rule holds at every speed. */
size_t lumo_net_usb_transfer(size_t n, size_t cap, uint32_t mps);

#endif
