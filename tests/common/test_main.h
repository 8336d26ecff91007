// The runner of every cmocka test program (C and C++): cmocka with the headers it needs, and
//   RTPBR_TEST_MAIN(cmocka_unit_test(a), cmocka_unit_test(b), ...)
// which defines main(void) running the listed tests, or, inside a main that reads arguments
// first, RTPBR_RUN_TESTS(group_setup, group_teardown, tests...), which returns cmocka's status
// from it.
#ifndef RTPBR_TEST_MAIN_H
#define RTPBR_TEST_MAIN_H

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#define RTPBR_RUN_TESTS(group_setup, group_teardown, ...)                                          \
    do {                                                                                           \
        const struct CMUnitTest tests[] = {__VA_ARGS__};                                           \
        return cmocka_run_group_tests(tests, group_setup, group_teardown);                         \
    } while (0)

#define RTPBR_TEST_MAIN(...)                                                                       \
    int main(void)                                                                                 \
    {                                                                                              \
        RTPBR_RUN_TESTS(NULL, NULL, __VA_ARGS__);                                                  \
    }

#endif
