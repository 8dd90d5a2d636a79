/* The version: ggx_version() of the library the test links (libggx itself, shared or static as built) against the
 * header's macros and the build's project version (GGX_TEST_PROJECT_VERSION, from CMakeLists.txt).
 * SPDX-License-Identifier: MIT */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "ggx/ggx.h"

#if !defined(GGX_VERSION_MAJOR) || !defined(GGX_VERSION_MINOR) || !defined(GGX_VERSION_PATCH) ||                       \
    !defined(GGX_VERSION_STRING)
#error "ggx.h must give the version macros"
#endif
#if GGX_VERSION_MAJOR < 0 || GGX_VERSION_MINOR < 0 || GGX_VERSION_PATCH < 0
#error "the version numbers are integer constants >= 0"
#endif

static void macros_agree(void **state)
{
    (void)state;
    char s[64];
    snprintf(s, sizeof s, "%d.%d.%d", GGX_VERSION_MAJOR, GGX_VERSION_MINOR, GGX_VERSION_PATCH);
    assert_string_equal(GGX_VERSION_STRING, s);
    assert_string_equal(GGX_VERSION_STRING, GGX_TEST_PROJECT_VERSION);
}

static void library_agrees(void **state)
{
    (void)state;
    const char *v = ggx_version();
    assert_non_null(v);
    assert_string_equal(v, GGX_VERSION_STRING);
    assert_string_equal(v, GGX_TEST_PROJECT_VERSION);
    assert_ptr_equal(ggx_version(), v);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(macros_agree),
        cmocka_unit_test(library_agrees),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
