/* fmt.c - allocation-free, stdio-free number and text formatting.
 * SPDX-License-Identifier: MIT
 */
#include "fmt.h"

int fmt_str(char *buf, size_t cap, size_t *pos, const char *s)
{
    size_t n = 0;
    size_t i;
    /* bounded: a string longer than the remaining room is an error anyway */
    while (n <= cap && s[n] != '\0') {
        n++;
    }
    if (*pos + n > cap) {
        return CP_ERR_FULL;
    }
    for (i = 0; i < n; i++) {
        buf[*pos + i] = s[i];
    }
    *pos += n;
    return CP_OK;
}

int fmt_u32(char *buf, size_t cap, size_t *pos, uint32_t v)
{
    char tmp[10];
    unsigned n = 0;
    unsigned i;
    do { /* at most 10 digits for a uint32_t */
        tmp[n++] = (char)('0' + (v % 10u));
        v /= 10u;
    } while (v != 0u && n < sizeof tmp);
    if (*pos + n > cap) {
        return CP_ERR_FULL;
    }
    for (i = 0; i < n; i++) {
        buf[*pos + i] = tmp[n - 1u - i];
    }
    *pos += n;
    return CP_OK;
}

int fmt_i32(char *buf, size_t cap, size_t *pos, int32_t v)
{
    uint32_t m;
    if (v < 0) {
        if (*pos + 1u > cap) {
            return CP_ERR_FULL;
        }
        buf[(*pos)++] = '-';
        m = (uint32_t)(-(v + 1)) + 1u; /* no overflow for INT32_MIN */
    } else {
        m = (uint32_t)v;
    }
    return fmt_u32(buf, cap, pos, m);
}

int fmt_fixed(char *buf, size_t cap, size_t *pos, int32_t v, unsigned decimals)
{
    static const uint32_t pow10[10] = {1u,      10u,      100u,      1000u,      10000u,
                                       100000u, 1000000u, 10000000u, 100000000u, 1000000000u};
    uint32_t m, ip, fp, d;
    unsigned i;
    int err;
    if (decimals > 9u) {
        return CP_ERR_INVAL;
    }
    if (v < 0) {
        if (*pos + 1u > cap) {
            return CP_ERR_FULL;
        }
        buf[(*pos)++] = '-';
        m = (uint32_t)(-(v + 1)) + 1u;
    } else {
        m = (uint32_t)v;
    }
    ip = m / pow10[decimals];
    fp = m % pow10[decimals];
    err = fmt_u32(buf, cap, pos, ip);
    if (err != CP_OK || decimals == 0u) {
        return err;
    }
    if (*pos + 1u + decimals > cap) {
        return CP_ERR_FULL;
    }
    buf[(*pos)++] = '.';
    for (i = decimals; i > 0u; i--) {
        d = (fp / pow10[i - 1u]) % 10u;
        buf[(*pos)++] = (char)('0' + d);
    }
    return CP_OK;
}
