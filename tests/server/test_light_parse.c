/*
 * test_light_parse.c — the light syntax read field by field (issue 24,
 * round three; server/scene/light_parse.c): every refusal names the
 * option, the text, the field and its value; good lights of every kind
 * parse to what docs/scene-format.md says; a refused light leaves *out
 * untouched.
 */
#include "test_common.h"
#include "scene/scene.h"

static char g_err[512];

static void refused(const char *text, const char *says)
{
    srv_light l, keep;
    memset(&l, 0x5a, sizeof l);
    keep = l;
    if (srv_light_parse_as("--light", text, &l, g_err, sizeof g_err) == LUMO_OK)
        fail_msg("'%s' accepted", text);
    if (!strstr(g_err, says))
        fail_msg("'%s' says '%s', not '%s'", text, g_err, says);
    assert_memory_equal(&l, &keep, sizeof l);
}

static void test_fields(void **state)
{
    (void)state;
    refused("point:0,1:1,1,1", "--light 'point:0,1:1,1,1': position needs 3 numbers, got 2");
    refused("point:0,1,0,4:1,1,1", "position needs 3 numbers, got 4");
    refused("point::1,1,1", "position needs 3 numbers, got 0");
    refused("point:0,x,0:1,1,1", "position value 2 'x' is not a finite number");
    refused("point:0,1,0:1,1", "power needs 3 numbers, got 2");
    refused("point:0,1,0:1,-1,1", "power value 2 = -1 is outside [0, 1e+09] W");
    refused("point:0,1,0:1,1,inf", "power value 3 'inf' is not a finite number");
    refused("point:0,40000,0:1,1,1", "position value 2 = 40000 is outside [-32000, 32000] m");
    refused("laser:0,1,0:1,1,1", "kind 'laser' is not point, spot, directional or area");
    refused("point:0,1,0:1,1,1:7", "a point light is point:X,Y,Z:R,G,B (3 fields), got 4");
    refused("point:0:1:2:3:4:5:6", "got more than 5");
    refused("spot:0,1,0:0,0,0:30:1,1,1", "direction 0,0,0 has no length");
    refused("spot:0,1,0:0,-1,0:0:1,1,1", "cone half-angle 0 must be above 0 degrees");
    refused("spot:0,1,0:0,-1,0:181:1,1,1", "cone half-angle = 181 is outside [0, 180] degrees");
    refused("spot:0,1,0:0,-1,0:30,2:1,1,1", "cone half-angle needs 1 number, got 2");
    refused("directional:0,-1,0:1,1,-2", "irradiance value 3 = -2 is outside [0, 1e+09] W/m^2");
    refused("area:0,1,0:1,0,0:2,0,0:1,1,1", "edges U 1,0,0 and V 2,0,0 are parallel or zero: no area");
    /* nearly parallel (sine 1e-6) and tiny (1e-7 m edges): a normal float cannot make unit (fuzz_light_parse) */
    refused("area:0,1,0:1,0,0:1,0.000001,0:1,1,1", "edges U 1,0,0 and V 1,0.000001,0 are parallel or zero");
    refused("area:0,1,0:1e-7,0,0:0,0,1e-7:1,1,1", "edges U 1e-7,0,0 and V 0,0,1e-7 are parallel or zero");
    refused("area:0,1,0:1,0:0,0,1:1,1,1", "edge U needs 3 numbers, got 2");
    refused("point: 0,1,0:1,1,1", "position value 1 ' 0' is not a finite number");
    refused("", "kind '' is not");
}

static void test_good(void **state)
{
    srv_light l;
    (void)state;
    assert_int_equal(srv_light_parse("spot:0,2,0:0,-2,0:60:5,6,7", &l, g_err, sizeof g_err), LUMO_OK);
    assert_int_equal(l.kind, LUMO_LIGHT_SPOT);
    assert_true(fabsf(l.dir.y + 1.0f) < 1e-6f && fabsf(l.cos_half - 0.5f) < 1e-6f && l.power.z == 7.0f);
    assert_int_equal(srv_light_parse("area:0,2,0:1,0,0:0,0,1:9,9,9", &l, g_err, sizeof g_err), LUMO_OK);
    assert_true(fabsf(l.dir.y + 1.0f) < 1e-6f);   /* u x v: shines down */
    assert_int_equal(srv_light_parse("directional:0,-1,0:3,3,3", &l, g_err, sizeof g_err), LUMO_OK);
    assert_int_equal(srv_light_parse("point:-1.5e1,0x1p2,0:0,0,0", &l, g_err, sizeof g_err), LUMO_OK);
    assert_true(l.pos.x == -15.0f && l.pos.y == 4.0f);
}

static void test_long(void **state)
{
    char text[600];
    srv_light l;
    (void)state;
    memset(text, '1', sizeof text - 1);
    text[sizeof text - 1] = 0;
    assert_int_equal(srv_light_parse(text, &l, g_err, sizeof g_err), LUMO_ERR_LIMIT);
    assert_non_null(strstr(g_err, "longer than 511 characters"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fields), cmocka_unit_test(test_good), cmocka_unit_test(test_long),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
