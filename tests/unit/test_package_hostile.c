/*
 * test_package_hostile.c — checksum-valid packages with hostile content
 * (issue 24): a chunk the format allows once appearing twice, INFO cameras
 * that cannot be placed, hostile light records and IVG descriptors. Each
 * is refused by the one decoder every reader uses (lumo/package.h,
 * lumo/scene.h), with its status, never dropped.
 */
#include "test_common.h"
#include <math.h>
#include "lumo/package.h"
#include "test_pkg_build.h"

static lumo_status open_chunks(const chunk *c, uint32_t n)
{
    static bytes p;
    lumo_package pkg;
    assemble(&p, c, n);
    return lumo_package_open(&pkg, p.b, p.n);
}

static void test_singletons_once(void **state)
{
    (void)state;
    static chunk c[4];
    info_chunk(&c[0]);
    ivgd_chunk(&c[1]);
    assert_int_equal(open_chunks(c, 2), LUMO_OK);
    info_chunk(&c[2]);
    assert_int_equal(open_chunks(c, 3), LUMO_ERR_CORRUPT);   /* two INFO */
    ivgd_chunk(&c[2]);
    assert_int_equal(open_chunks(c, 3), LUMO_ERR_CORRUPT);   /* two IVGD */
    mesh_chunk(&c[2], 1);
    mesh_chunk(&c[3], 1);
    assert_int_equal(open_chunks(c, 4), LUMO_OK);            /* MESH: one per mesh */
}

/* INFO with float `v` at byte `off`: the info decoder's status. */
static lumo_status info_with(unsigned off, float v)
{
    static chunk c;
    lumo_pkg_info in;
    info_chunk(&c);
    wr32(c.data.b + off, test_f32_bits(v));
    return lumo_scene_info_decode(c.data.b, c.data.n, &in);
}

static void test_camera_placed(void **state)
{
    (void)state;
    assert_int_equal(info_with(76, 40), LUMO_OK);
    assert_int_equal(info_with(64 + 4, 0), LUMO_ERR_RANGE);     /* up (0, 0, 0) */
    assert_int_equal(info_with(48, 0), LUMO_ERR_RANGE);         /* eye on the target (0, 1, 0) */
    assert_int_equal(info_with(64 + 8, 1), LUMO_OK);            /* up (0, 1, 1): not along the view */
    static chunk c;
    lumo_pkg_info in;
    info_chunk(&c);                                             /* up (0, 0, -7) along eye->target */
    wr32(c.data.b + 68, test_f32_bits(0)), wr32(c.data.b + 72, test_f32_bits(-7));
    assert_int_equal(lumo_scene_info_decode(c.data.b, c.data.n, &in), LUMO_ERR_RANGE);
    assert_int_equal(info_with(76, 180), LUMO_ERR_RANGE);
    assert_int_equal(info_with(16, NAN), LUMO_ERR_NONFINITE);
}

static lumo_status light_with(unsigned off, uint32_t bits)
{
    static chunk c;
    lumo_pkg_light l;
    info_chunk(&c);
    wr32(c.data.b + 80 + off, bits);
    return lumo_scene_light_decode(c.data.b, c.data.n, 0, &l);
}

static void test_lights_refused(void **state)
{
    (void)state;
    assert_int_equal(light_with(0, LUMO_LIGHT_SPOT), LUMO_OK);
    assert_int_equal(light_with(0, 4), LUMO_ERR_UNSUPPORTED);
    assert_int_equal(light_with(0, 0xFFFFFFFFu), LUMO_ERR_UNSUPPORTED);
    for (unsigned off = 4; off < 72; off += 4) {
        assert_int_equal(light_with(off, test_f32_bits(NAN)), LUMO_ERR_NONFINITE);
        assert_int_equal(light_with(off, test_f32_bits(INFINITY)), LUMO_ERR_NONFINITE);
    }
    assert_int_equal(light_with(56, test_f32_bits(1.5f)), LUMO_ERR_RANGE);    /* cosine above 1 */
    assert_int_equal(light_with(16, test_f32_bits(2.0f)), LUMO_ERR_RANGE);    /* direction */
    assert_int_equal(light_with(60, test_f32_bits(-1.0f)), LUMO_ERR_RANGE);   /* power */
}

static lumo_status ivgd_with(unsigned off, uint32_t v, int is16)
{
    static chunk c;
    lumo_ivg_desc d;
    ivgd_chunk(&c);
    if (is16)
        c.data.b[off] = (uint8_t)v, c.data.b[off + 1] = (uint8_t)(v >> 8);
    else
        wr32(c.data.b + off, v);
    return lumo_scene_ivg_desc_decode(c.data.b, c.data.n, &d);
}

static void test_ivgd_refused(void **state)
{
    (void)state;
    static const uint32_t dims[4] = {0, 1, 257, 65535};
    assert_int_equal(ivgd_with(0, 4, 1), LUMO_OK);
    for (unsigned a = 0; a < 3; a++)
        for (int i = 0; i < 4; i++)
            assert_int_equal(ivgd_with(2 * a, dims[i], 1), LUMO_ERR_RANGE);
    for (unsigned f = 0; f < 6; f++)
        assert_int_equal(ivgd_with(8 + 4 * f, test_f32_bits(NAN), 0), LUMO_ERR_NONFINITE);
    assert_int_equal(ivgd_with(8, test_f32_bits(5.0f), 0), LUMO_ERR_RANGE);    /* min x > max x */
    assert_int_equal(ivgd_with(8, test_f32_bits(1.0f), 0), LUMO_ERR_RANGE);    /* min x == max x */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_singletons_once), cmocka_unit_test(test_camera_placed),
        cmocka_unit_test(test_lights_refused), cmocka_unit_test(test_ivgd_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
