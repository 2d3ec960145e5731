/* fmt.c - allocation-free, stdio-free number and text formatting.
 * SPDX-License-Identifier: MIT
 */
#include "fmt.h"

int fmt_str(char *buf, size_t cap, size_t *pos, const char *s)
{
    size_t i;
    /* bounded by cap: a string longer than the remaining room is an error (the bytes
     * copied so far stay beyond *pos, which does not move) */
    for (i = 0; s[i] != '\0'; i++) {
        if (*pos + i >= cap) {
            return CP_ERR_FULL;
        }
        buf[*pos + i] = s[i];
    }
    *pos += i;
    return CP_OK;
}

/* The n lowest decimal digits of v into dst[0..n), last first. */
static CP_NOINLINE void put_digits(char *dst, unsigned n, uint32_t v)
{
    unsigned i;
    for (i = n; i > 0u; i--) {
        dst[i - 1u] = (char)('0' + (v % 10u));
        v /= 10u;
    }
}

int fmt_u32(char *buf, size_t cap, size_t *pos, uint32_t v)
{
    uint32_t t = v;
    unsigned n = 1;
    while (t >= 10u && n < 10u) { /* the digits: at most 10 for a uint32_t */
        t /= 10u;
        n++;
    }
    if (*pos + n > cap) {
        return CP_ERR_FULL;
    }
    put_digits(buf + *pos, n, v);
    *pos += n;
    return CP_OK;
}

/* '-' for v < 0; returns |v| (no overflow for INT32_MIN), or sets *err if no room. */
static uint32_t put_sign(char *buf, size_t cap, size_t *pos, int32_t v, int *err)
{
    if (v >= 0) {
        return (uint32_t)v;
    }
    if (*pos + 1u > cap) {
        *err = CP_ERR_FULL;
        return 0u;
    }
    buf[(*pos)++] = '-';
    return (uint32_t)(-(v + 1)) + 1u;
}

int fmt_i32(char *buf, size_t cap, size_t *pos, int32_t v)
{
    int err = CP_OK;
    uint32_t m = put_sign(buf, cap, pos, v, &err);
    return err != CP_OK ? err : fmt_u32(buf, cap, pos, m);
}

int fmt_fixed(char *buf, size_t cap, size_t *pos, int32_t v, unsigned decimals)
{
    uint32_t m, ip, fp, div = 1u;
    unsigned i;
    int err = CP_OK;
    if (decimals > 9u) {
        return CP_ERR_INVAL;
    }
    m = put_sign(buf, cap, pos, v, &err);
    if (err != CP_OK) {
        return err;
    }
    for (i = 0; i < decimals; i++) {
        div *= 10u;
    }
    ip = m / div;
    fp = m % div;
    err = fmt_u32(buf, cap, pos, ip);
    if (err != CP_OK || decimals == 0u) {
        return err;
    }
    if (*pos + 1u + decimals > cap) {
        return CP_ERR_FULL;
    }
    buf[(*pos)++] = '.';
    put_digits(buf + *pos, decimals, fp); /* the fraction's digits, leading zeros too */
    *pos += decimals;
    return CP_OK;
}
