/*
 * ffs_desc.c — the gadget's FunctionFS descriptors and strings
 * (ffs_desc.h). Values from USB 2.0 §9.6 and USB 3.x §9.6.7; layout of
 * <linux/usb/functionfs.h>.
 */
#include "ffs_desc.h"
#include <string.h>
#include "lumo/net_usb.h"
#include "lumo/wire.h"

enum {
    MAGIC_DESCS_V2 = 3, MAGIC_STRINGS = 2,
    HAS_FS = 1, HAS_HS = 2, HAS_SS = 4,
    DT_INTERFACE = 4, DT_ENDPOINT = 5, DT_SS_EP_COMP = 0x30,
    BULK = 2, DIR_IN = 0x80
};

static uint8_t *interface(uint8_t *p)
{
    static const uint8_t d[9] = {9, DT_INTERFACE, 0, 0, 2, LUMO_USB_CLASS, LUMO_USB_SUBCLASS, LUMO_USB_PROTOCOL, 1};

    memcpy(p, d, sizeof d);
    return p + sizeof d;
}

/* An endpoint (7 bytes: FunctionFS takes the descriptor without the audio
 * fields), with its super-speed companion when ss. */
static uint8_t *endpoint(uint8_t *p, uint8_t address, uint16_t mps, int ss)
{
    p[0] = 7, p[1] = DT_ENDPOINT, p[2] = address, p[3] = BULK;
    lumo_wire_put_le16(p + 4, mps);
    p[6] = 0;
    p += 7;
    if (ss) {
        memset(p, 0, 6);
        p[0] = 6, p[1] = DT_SS_EP_COMP;
        p += 6;
    }
    return p;
}

/* One speed's set: interface, OUT, IN. */
static uint8_t *speed(uint8_t *p, uint16_t mps, int ss)
{
    p = interface(p);
    p = endpoint(p, 1, mps, ss);
    return endpoint(p, 2 | DIR_IN, mps, ss);
}

size_t ffs_descriptors(uint8_t *out, size_t cap)
{
    uint8_t *p = out + 24;
    size_t n;

    if (cap < FFS_DESC_BYTES)
        return 0;
    lumo_wire_put_le32(out, MAGIC_DESCS_V2);
    lumo_wire_put_le32(out + 8, HAS_FS | HAS_HS | HAS_SS);
    lumo_wire_put_le32(out + 12, 3);   /* descriptors per speed: fs */
    lumo_wire_put_le32(out + 16, 3);   /* hs */
    lumo_wire_put_le32(out + 20, 5);   /* ss: with the two companions */
    p = speed(p, LUMO_USB_MPS_FS, 0);
    p = speed(p, LUMO_USB_MPS_HS, 0);
    p = speed(p, LUMO_USB_MPS_SS, 1);
    n = (size_t)(p - out);
    lumo_wire_put_le32(out + 4, (uint32_t)n);
    return n;
}

size_t ffs_strings(uint8_t *out, size_t cap)
{
    static const char name[] = "lumo thin client";
    size_t n = 16 + 2 + sizeof name;

    if (cap < n)
        return 0;
    lumo_wire_put_le32(out, MAGIC_STRINGS);
    lumo_wire_put_le32(out + 4, (uint32_t)n);
    lumo_wire_put_le32(out + 8, 1);    /* strings */
    lumo_wire_put_le32(out + 12, 1);   /* languages */
    lumo_wire_put_le16(out + 16, 0x0409);   /* en-US */
    memcpy(out + 18, name, sizeof name);
    return n;
}
