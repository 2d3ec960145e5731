/* bench_print.c - semihosting output of the QEMU measurement programs (bench_print.h).
 * SPDX-License-Identifier: MIT
 */
#include "bench_print.h"
#include "fmt.h"
#include "semihost.h"

void print(const char *s)
{
    semihost_write0(s);
}

void print_u32(uint32_t v)
{
    char b[12];
    size_t pos = 0;
    (void)fmt_u32(b, sizeof b - 1u, &pos, v);
    b[pos] = '\0';
    print(b);
}

void print_i32(int32_t v)
{
    char b[13];
    size_t pos = 0;
    (void)fmt_i32(b, sizeof b - 1u, &pos, v);
    b[pos] = '\0';
    print(b);
}

void print_fixed(int32_t v, unsigned dec)
{
    char b[16];
    size_t pos = 0;
    (void)fmt_fixed(b, sizeof b - 1u, &pos, v, dec);
    b[pos] = '\0';
    print(b);
}

uint32_t ticks_to_insns(uint32_t t0, uint32_t t1)
{
    return ((t0 - t1) * 40u + 64u) / 128u; /* down-counter; 25 MHz vs 2^7 ns/insn */
}
