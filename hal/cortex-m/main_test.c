/* main_test.c - entry of the Cortex-M4F unit-test image (build/m4f/unit.elf).
 * SPDX-License-Identifier: MIT
 *
 * Runs tests/test_main.c's table (compiled with -DTEST_NO_MAIN -DTEST_WORD='"m4f"'),
 * which prints "m4f: N passed, N failed" through newlib printf -> semihosting,
 * then hands the result to QEMU as its exit status.
 */
#include <stdio.h>

#include "semihost.h"
#include "startup.h"

int test_main(const char *filter); /* tests/test_main.c */

int main(void)
{
    int rc = test_main(NULL);
    printf("  note: m4f test stack peak %u of %u bytes\n", (unsigned)startup_stack_peak(),
           (unsigned)startup_stack_size());
    (void)fflush(stdout);
    semihost_exit(rc);
}
