/* bench_print.h - what the QEMU measurement programs (maxpoint_m4f.c, pollgap_m4f.c,
 * bench_m4f.c) print with, over semihosting, and their one conversion of TIMER0 ticks to
 * instructions.
 * SPDX-License-Identifier: MIT
 */
#ifndef BENCH_PRINT_H
#define BENCH_PRINT_H

#include <stddef.h>
#include <stdint.h>

/* A NUL-terminated string to the host's stdout (semihosting SYS_WRITE0). */
void print(const char *s);
/* v in decimal. */
void print_u32(uint32_t v);
/* v in decimal, with a '-' when negative. */
void print_i32(int32_t v);
/* v / 10^dec with dec decimals. */
void print_fixed(int32_t v, unsigned dec);

/* Instructions in the span from TIMER0 reading t0 to reading t1 (a down-counter at 25 MHz)
 * under -icount shift=7: one instruction is 128 ns, a tick 40 ns, so round(ticks * 40 /
 * 128), exact (one tick is 0.3125 instruction: the +-1 tick phase jitter never changes
 * the rounded count; docs/QEMU.md section 4). */
uint32_t ticks_to_insns(uint32_t t0, uint32_t t1);

#endif /* BENCH_PRINT_H */
