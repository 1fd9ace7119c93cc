/* test_net_usb.c — the USB binding's transfer rule (lumo/net_usb.h,
 * docs/protocol.md §8 "USB") on a model of bulk transfers: the writer's
 * transfers become packets of wMaxPacketSize (the last one short, or
 * none); a reader's transfer ends at a short packet or when its buffer is
 * full. Every byte the writer wrote must reach the reader without the
 * reader waiting on a transfer that never ends — at every length around
 * the multiples of the packet size, every reader buffer, every speed. The
 * naive writer (whole lengths) is shown to stall at exactly those edges. */
#include "test_common.h"
#include "lumo/net_usb.h"

/* The reader side of the model. */
typedef struct reader {
    size_t buf;       /* the reader's transfer size (a multiple of mps) */
    size_t in_xfer;   /* bytes of the transfer being filled */
    size_t got;       /* bytes of finished transfers */
    unsigned xfers;
} reader;

/* A packet of len bytes (len <= mps) reaches the reader. */
static void packet(reader *r, size_t len, uint32_t mps)
{
    r->in_xfer += len;
    if (len < mps || r->in_xfer == r->buf) {
        r->got += r->in_xfer;
        r->in_xfer = 0;
        r->xfers++;
    }
}

/* One writer transfer of len bytes: full packets, then the short rest. */
static void transfer(reader *r, size_t len, uint32_t mps)
{
    while (len >= mps) {
        packet(r, mps, mps);
        len -= mps;
    }
    if (len)
        packet(r, len, mps);
}

/* Write n bytes following the rule (or whole, naive); 1 when the reader
 * has them all in finished transfers, 0 when it still waits. */
static int deliver(size_t n, size_t cap, uint32_t mps, size_t reader_buf, int naive)
{
    reader r = {reader_buf, 0, 0, 0};

    while (n) {
        size_t k = naive ? (n < cap ? n : cap) : lumo_net_usb_transfer(n, cap, mps);
        assert_true(k > 0 && k <= n && k <= cap);
        if (!naive)
            assert_true(k % mps != 0);
        transfer(&r, k, mps);
        n -= k;
    }
    return r.in_xfer == 0;
}

static void test_rule_at_every_edge(void **state)
{
    static const uint32_t mps[] = {LUMO_USB_MPS_FS, LUMO_USB_MPS_HS, LUMO_USB_MPS_SS};
    unsigned s, k;
    size_t n;
    (void)state;

    for (s = 0; s < 3; s++)
        for (k = 1; k <= 64; k *= 4)
            for (n = 1; n <= 3u * LUMO_USB_TRANSFER + 2u * mps[s]; n += (n % mps[s] < 2 || n % mps[s] > mps[s] - 3) ? 1 : 61) {
                size_t rb = (size_t)k * mps[s];
                if (!deliver(n, LUMO_USB_TRANSFER, mps[s], rb, 0))
                    fail_msg("n %zu mps %u reader %zu: the reader waits", n, mps[s], rb);
            }
}

/* The edge is real: whole transfers of a multiple of the packet size leave
 * a reader with a larger buffer waiting; the rule does not. */
static void test_naive_writer_stalls(void **state)
{
    (void)state;
    assert_int_equal(deliver(512, LUMO_USB_TRANSFER, 512, 16384, 1), 0);
    assert_int_equal(deliver(512, LUMO_USB_TRANSFER, 512, 16384, 0), 1);
    assert_int_equal(deliver(16384 + 1024, LUMO_USB_TRANSFER, 512, 4096, 1), 0);
    assert_int_equal(deliver(16384 + 1024, LUMO_USB_TRANSFER, 512, 4096, 0), 1);
    assert_int_equal(deliver(513, LUMO_USB_TRANSFER, 512, 16384, 1), 1);
}

/* Speed unknown to the writer: the full-speed size keeps the rule at every
 * speed, since 512 and 1024 are multiples of 64. */
static void test_full_speed_rule_holds_at_high_speed(void **state)
{
    size_t n;
    (void)state;

    for (n = 1; n <= 4096; n++) {
        size_t k = lumo_net_usb_transfer(n, LUMO_USB_TRANSFER, LUMO_USB_MPS_FS);
        assert_true(k % LUMO_USB_MPS_HS != 0 && k % LUMO_USB_MPS_SS != 0);
    }
}

static void test_exact_values(void **state)
{
    (void)state;
    assert_int_equal(lumo_net_usb_transfer(0, 16384, 512), 0);
    assert_int_equal(lumo_net_usb_transfer(1, 16384, 512), 1);
    assert_int_equal(lumo_net_usb_transfer(511, 16384, 512), 511);
    assert_int_equal(lumo_net_usb_transfer(512, 16384, 512), 511);
    assert_int_equal(lumo_net_usb_transfer(513, 16384, 512), 513);
    assert_int_equal(lumo_net_usb_transfer(1024, 16384, 512), 1023);
    assert_int_equal(lumo_net_usb_transfer(20000, 16384, 512), 16383);   /* cap is a multiple */
    assert_int_equal(lumo_net_usb_transfer(20000, 1000, 512), 1000);
    assert_int_equal(lumo_net_usb_transfer(5, 16384, 0), 0);
    assert_int_equal(lumo_net_usb_transfer(5, 16384, 1), 0);
    assert_int_equal(lumo_net_usb_transfer(5, 0, 512), 0);
    assert_int_equal(lumo_net_usb_transfer(2, 16384, 2), 1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_rule_at_every_edge),
        cmocka_unit_test(test_naive_writer_stalls),
        cmocka_unit_test(test_full_speed_rule_holds_at_high_speed),
        cmocka_unit_test(test_exact_values),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
