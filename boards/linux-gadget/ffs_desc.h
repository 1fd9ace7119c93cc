/*
 * ffs_desc.h — what the gadget client writes to FunctionFS's ep0: the
 * descriptors of the lumo interface (lumo/net_usb.h, docs/protocol.md §8
 * "USB") at full, high and super speed, and its string. Byte images built
 * with lumo/wire.h, in the kernel's v2 layout
 * (Documentation/usb/functionfs.rst, <linux/usb/functionfs.h>).
 *
 * The interface: class FF/4C/01, two bulk endpoints: ep1 OUT (host to
 * device), ep2 IN (device to host) — FunctionFS names their files ep1 and
 * ep2 in that order.
 */
#ifndef LUMO_FFS_DESC_H
#define LUMO_FFS_DESC_H

#include <stddef.h>
#include <stdint.h>

#define FFS_DESC_BYTES    128u   /* room for the descriptors image */
#define FFS_STRINGS_BYTES 64u    /* room for the strings image */

/* The images into out[0..cap); their length, or 0 when cap is too small. */
size_t ffs_descriptors(uint8_t *out, size_t cap);
size_t ffs_strings(uint8_t *out, size_t cap);

#endif
