/* test_wire.c — the byte layer shared by every reader and writer
 * (lumo/wire.h): little-endian integers, varints, bit fields, CRC-32. */
#include "test_common.h"
#include "lumo/wire.h"

static void test_crc32_check_value(void **state)
{
    (void)state;
    /* The standard check value of CRC-32/ISO-HDLC, whole and continued. */
    assert_int_equal(lumo_wire_crc32(0, (const uint8_t *)"123456789", 9), 0xCBF43926u);
    assert_int_equal(lumo_wire_crc32(lumo_wire_crc32(0, (const uint8_t *)"1234", 4),
                                     (const uint8_t *)"56789", 5), 0xCBF43926u);
    assert_int_equal(lumo_wire_crc32(0, NULL, 0), 0);
}

static void test_little_endian(void **state)
{
    uint8_t b[8];
    (void)state;
    lumo_wire_put_le64(b, 0x0807060504030201ull);
    for (int i = 0; i < 8; i++)
        assert_int_equal(b[i], i + 1);
    assert_int_equal(lumo_wire_le16(b), 0x0201);
    assert_int_equal(lumo_wire_le32(b + 4), 0x08070605u);
    assert_true(lumo_wire_le64(b) == 0x0807060504030201ull);
    lumo_wire_put_le16(b, 0xbeef);
    lumo_wire_put_le32(b + 2, 0xdeadbeefu);
    assert_int_equal(lumo_wire_le16(b), 0xbeef);
    assert_int_equal(lumo_wire_le32(b + 2), 0xdeadbeefu);
}

/* Every value written by put_varint reads back with its exact length. */
static void test_varint_round_trip(void **state)
{
    static const uint32_t v[] = {0, 1, 127, 128, 300, 16383, 16384, (1u << 28) - 1, 1u << 28,
                                 0xffffffffu};
    static const size_t len[] = {1, 1, 1, 2, 2, 2, 3, 4, 5, 5};
    uint8_t b[LUMO_WIRE_VARINT32_MAX];
    (void)state;
    for (size_t i = 0; i < sizeof v / sizeof v[0]; i++) {
        size_t n = lumo_wire_put_varint(b, v[i]), at = 0;
        uint32_t r = 7;
        assert_int_equal(n, len[i]);
        assert_int_equal(lumo_wire_varint(b, n, &at, 0xffffffffu, &r), LUMO_OK);
        assert_int_equal(at, n);
        assert_int_equal(r, v[i]);
        at = 0;
        assert_int_equal(lumo_wire_varint(b, n - 1, &at, 0xffffffffu, &r), LUMO_ERR_TRUNCATED);
        assert_int_equal(at, 0);
    }
}

static void test_varint_strict(void **state)
{
    static const uint8_t padded[] = {0x81, 0x00};                  /* 1 with a zero group */
    static const uint8_t six[] = {0x80, 0x80, 0x80, 0x80, 0x80, 0x01};
    static const uint8_t big[] = {0x80, 0x80, 0x80, 0x80, 0x01};   /* 2^28 */
    size_t at = 0;
    uint32_t v = 9;
    (void)state;
    assert_int_equal(lumo_wire_varint(padded, 2, &at, 100, &v), LUMO_ERR_CORRUPT);
    assert_int_equal(lumo_wire_varint(six, 6, &at, 0xffffffffu, &v), LUMO_ERR_CORRUPT);
    assert_int_equal(lumo_wire_varint(big, 5, &at, (1u << 28) - 1, &v), LUMO_ERR_CORRUPT);
    assert_int_equal(lumo_wire_varint(big, 5, &at, 1u << 28, &v), LUMO_OK);
    assert_int_equal(v, 1u << 28);
}

/* Draco's reader takes any coding and drops groups past 64 bits. */
static void test_leb128_permissive(void **state)
{
    static const uint8_t padded[] = {0x81, 0x80, 0x00};
    uint8_t wide[11];
    uint64_t v = 0;
    size_t at = 0;
    (void)state;
    assert_int_equal(lumo_wire_leb128(padded, 3, &at, 5, &v), LUMO_OK);
    assert_int_equal(at, 3);
    assert_true(v == 1);
    memset(wide, 0xff, sizeof wide);
    wide[9] = 0x7f;
    at = 0;
    assert_int_equal(lumo_wire_leb128(wide, 10, &at, 10, &v), LUMO_OK);
    assert_true(v == 0xffffffffffffffffull);
    at = 0;
    assert_int_equal(lumo_wire_leb128(wide, 11, &at, 9, &v), LUMO_ERR_CORRUPT);
}

/* Fields written LSB-first read back in order, across byte borders. */
static void test_bits_round_trip(void **state)
{
    static const uint32_t v[] = {1, 0, 5, 0x1ffff, 0xffffffffu, 3};
    static const unsigned n[] = {1, 3, 3, 17, 32, 2};
    uint8_t buf[8] = {0};
    size_t pos = 0;
    lumo_wire_bits b;
    uint32_t r;
    (void)state;
    for (size_t i = 0; i < 6; i++)
        lumo_wire_put_bits(buf, pos, v[i], n[i]), pos += n[i];
    /* bit 0: 1; bits 1-3: 0; bits 4-6: 5 = 1 0 1 low first; bit 7: 0x1ffff low bit */
    assert_int_equal(buf[0], 0xd1);
    lumo_wire_bits_init(&b, buf, sizeof buf);
    for (size_t i = 0; i < 6; i++) {
        assert_int_equal(lumo_wire_bits_read(&b, n[i], &r), LUMO_OK);
        assert_int_equal(r, v[i]);
    }
    assert_int_equal(lumo_wire_bits_left(&b), 64 - pos);
    assert_int_equal(lumo_wire_bits_read(&b, 9, &r), LUMO_ERR_TRUNCATED);
    assert_int_equal(lumo_wire_bits_left(&b), 64 - pos);   /* nothing consumed */
    assert_int_equal(lumo_wire_bits_read(&b, 6, &r), LUMO_OK);
    assert_int_equal(r, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_crc32_check_value),
        cmocka_unit_test(test_little_endian),
        cmocka_unit_test(test_varint_round_trip),
        cmocka_unit_test(test_varint_strict),
        cmocka_unit_test(test_leb128_permissive),
        cmocka_unit_test(test_bits_round_trip),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
