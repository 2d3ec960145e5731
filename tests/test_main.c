/* test_main.c - runs every test of tests.def; prints "<word>: N passed, N failed".
 * SPDX-License-Identifier: MIT
 *
 * Usage (host): unit [-k substring]   exit status 0 iff nothing failed.
 * On the target the word is fixed at build time (TEST_WORD) and the exit code
 * goes back through semihosting SYS_EXIT_EXTENDED (hal/cortex-m).
 */
#include <string.h>

#include "test.h"

#ifndef TEST_WORD
#define TEST_WORD "unit"
#endif

struct test_entry {
    const char *name;
    int (*fn)(void);
};

static const struct test_entry tests[] = {
#define TEST(name) {#name, test_##name},
#include "tests.def"
#undef TEST
};

int test_main(const char *filter);

int test_main(const char *filter)
{
    int passed = 0, failed = 0;
    size_t i;
    for (i = 0; i < sizeof tests / sizeof tests[0]; i++) {
        int line;
        if (filter != NULL && strstr(tests[i].name, filter) == NULL) {
            continue;
        }
        line = tests[i].fn();
        if (line == 0) {
            passed++;
        } else {
            failed++;
            printf("FAIL %s (line %d)\n", tests[i].name, line);
        }
    }
    printf("%s: %d passed, %d failed\n", TEST_WORD, passed, failed);
    return failed != 0;
}

#ifndef TEST_NO_MAIN
int main(int argc, char **argv)
{
    const char *filter = NULL;
    if (argc >= 3 && strcmp(argv[1], "-k") == 0) {
        filter = argv[2];
    }
    return test_main(filter);
}
#endif
