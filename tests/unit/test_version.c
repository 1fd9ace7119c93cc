/* test_version.c — lumo/version.h: the library says the version its headers
 * state, as a string that parses back to the three numbers, and the format
 * versions are the readers' own constants. */
#include <stdio.h>
#include <stdlib.h>
#include "test_common.h"
#include "lumo/version.h"

static void test_number_matches_headers(void **state)
{
    (void)state;
    assert_int_equal(lumo_version(), LUMO_VERSION_NUMBER);
    assert_int_equal(LUMO_VERSION_NUMBER,
                     LUMO_VERSION_MAJOR * 10000 + LUMO_VERSION_MINOR * 100 + LUMO_VERSION_PATCH);
    assert_true(LUMO_VERSION_MINOR < 100 && LUMO_VERSION_PATCH < 100);
}

static void test_string_parses_back(void **state)
{
    unsigned a = 999, b = 999, c = 999;
    char tail = 0;
    (void)state;
    assert_string_equal(lumo_version_string(), LUMO_VERSION_STRING);
    assert_int_equal(sscanf(lumo_version_string(), "%u.%u.%u%c", &a, &b, &c, &tail), 3);
    assert_int_equal(a, LUMO_VERSION_MAJOR);
    assert_int_equal(b, LUMO_VERSION_MINOR);
    assert_int_equal(c, LUMO_VERSION_PATCH);
}

static void test_formats_are_the_readers(void **state)
{
    lumo_version_formats f;
    (void)state;
    memset(&f, 0xEE, sizeof f);
    lumo_version_formats_get(&f);
    assert_int_equal(f.package_major, LUMO_PKG_VERSION_MAJOR);
    assert_int_equal(f.package_minor, LUMO_PKG_VERSION_MINOR);
    assert_int_equal(f.pmesh, LUMO_PMESH_VERSION);
    assert_int_equal(f.ivg_bundle, LUMO_IVG_BUNDLE_VERSION);
    lumo_version_formats_get(NULL);   /* no crash */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_number_matches_headers),
        cmocka_unit_test(test_string_parses_back),
        cmocka_unit_test(test_formats_are_the_readers),
    };
    return cmocka_run_group_tests_name("version", tests, NULL, NULL);
}
