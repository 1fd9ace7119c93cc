/*
 * net_usb.c — the USB binding's transfer rule (lumo/net_usb.h,
 * docs/protocol.md §8 "USB").
 */
#include "lumo/net_usb.h"

size_t lumo_net_usb_transfer(size_t n, size_t cap, uint32_t mps)
{
    size_t k = n < cap ? n : cap;

    if (k == 0 || mps < 2u)
        return 0;
    /* a full last packet would leave the reader waiting: end one byte short */
    return k % mps == 0 ? k - 1u : k;
}
