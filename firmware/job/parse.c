/* parse.c - deterministic number and token parsing.
 * SPDX-License-Identifier: MIT
 */
#include "parse.h"

#if CP_REAL_DOUBLE
typedef uint64_t mant_t;
#else
typedef uint32_t mant_t;
#endif

static char upper(char c)
{
    return (c >= 'a' && c <= 'z') ? (char)(c - 'a' + 'A') : c;
}

int parse_is(const char *s, size_t n, const char *kw)
{
    size_t i;
    for (i = 0; i < n; i++) {
        if (kw[i] == '\0' || upper(s[i]) != kw[i]) {
            return 0;
        }
    }
    return kw[n] == '\0';
}

/* (Not inlined: LTO had copied it into parse_real and exec_line.) */
CP_NOINLINE int parse_is_any(const char *s, size_t n, const char *const *kws, unsigned cnt)
{
    unsigned k;
    for (k = 0; k < cnt; k++) {
        if (parse_is(s, n, kws[k])) {
            return 1;
        }
    }
    return 0;
}

/* 10^e for 0 <= e <= 40 by squaring (exact up to 10^10 in float, 10^22 in double). */
static CP_NOINLINE cp_real pow10_real(unsigned e)
{
    cp_real r = CP_R(1.0), b = CP_R(10.0);
    unsigned i;
    for (i = 0; i < 6u; i++) { /* 2^6 > 40: fixed count */
        if (e & 1u) {
            r *= b;
        }
        b *= b;
        e >>= 1;
    }
    return r;
}

/* The spellings of a non-finite number, which parse_real refuses with their own code. */
static const char *const nonfinite_words[3] = {"NAN", "INF", "INFINITY"};

int parse_real(const char *s, size_t n, cp_real *out)
{
    size_t i = 0;
    int neg = 0, digits = 0, kept = 0, exp10 = 0, eneg = 0, edigits = 0, dot = 0;
    uint32_t ev = 0;
    mant_t m = 0;
    cp_real v;
    if (n == 0u) {
        return CP_ST_BAD_NUMBER;
    }
    if (s[0] == '+' || s[0] == '-') {
        neg = s[0] == '-';
        i = 1;
    }
    if (parse_is_any(s + i, n - i, nonfinite_words, 3u)) {
        return CP_ST_NONFINITE;
    }
    /* digits, with at most one '.' among them: a kept digit after it scales by 1/10,
     * a dropped one before it by 10 */
    for (; i < n; i++) {
        if (s[i] == '.' && !dot) {
            dot = 1;
            continue;
        }
        if (s[i] < '0' || s[i] > '9') {
            break;
        }
        digits++;
        if (kept < PARSE_MAX_DIGITS) {
            if (m != 0u || s[i] != '0') {
                kept++;
            }
            m = m * 10u + (mant_t)(s[i] - '0');
            exp10 -= dot;
        } else {
            exp10 += 1 - dot;
        }
    }
    if (digits == 0) {
        return CP_ST_BAD_NUMBER;
    }
    if (i < n && (s[i] == 'e' || s[i] == 'E')) {
        i++;
        if (i < n && (s[i] == '+' || s[i] == '-')) {
            eneg = s[i] == '-';
            i++;
        }
        for (; i < n && s[i] >= '0' && s[i] <= '9'; i++) {
            edigits++;
            if (ev < 1000u) {
                ev = ev * 10u + (uint32_t)(s[i] - '0');
            }
        }
        if (edigits == 0) {
            return CP_ST_BAD_NUMBER;
        }
        exp10 += eneg ? -(int)ev : (int)ev;
    }
    if (i != n) {
        return CP_ST_BAD_NUMBER;
    }
    if (m == 0u) {
        *out = CP_R(0.0);
        return CP_ST_OK;
    }
    if (exp10 > 40 || exp10 < -40 - PARSE_MAX_DIGITS) {
        return exp10 > 0 ? CP_ST_OUT_OF_RANGE : (*out = CP_R(0.0), CP_ST_OK);
    }
    v = (cp_real)m;
    if (exp10 >= 0) {
        v *= pow10_real((unsigned)exp10);
    } else {
        /* divide in chunks of at most 10^20 so no power overflows a float (10^39 would) */
        int e = -exp10, c;
        for (c = 0; c < 3 && e > 0; c++) { /* -exp10 <= 40 + PARSE_MAX_DIGITS < 60 */
            unsigned chunk = e > 20 ? 20u : (unsigned)e;
            v /= pow10_real(chunk);
            e -= (int)chunk;
        }
    }
    if (!(v <= PARSE_ABS_MAX)) {
        return CP_ST_OUT_OF_RANGE;
    }
    *out = neg ? -v : v;
    return CP_ST_OK;
}

/* (not inlined: one copy for the job's arguments and the machine's Resend numbers) */
CP_NOINLINE int parse_uint(const char *s, size_t n, uint32_t max, uint32_t *out)
{
    size_t i;
    uint32_t v = 0;
    int over = 0;
    if (n == 0u) {
        return CP_ST_BAD_NUMBER;
    }
    for (i = 0; i < n; i++) {
        uint32_t d;
        if (s[i] < '0' || s[i] > '9') {
            return CP_ST_BAD_NUMBER; /* "12x" is not a number, even if 12 is too large */
        }
        d = (uint32_t)(s[i] - '0');
        if (over || v > (UINT32_MAX - d) / 10u) {
            over = 1;
        } else {
            v = v * 10u + d;
        }
    }
    if (over || v > max) {
        return CP_ST_OUT_OF_RANGE;
    }
    *out = v;
    return CP_ST_OK;
}

unsigned parse_split(const char *line, size_t len, uint16_t *start, uint16_t *tlen, unsigned cap)
{
    size_t i = 0;
    unsigned nt = 0;
    while (i < len) {
        size_t b;
        while (i < len && line[i] == ' ') {
            i++;
        }
        if (i >= len) {
            break;
        }
        b = i;
        while (i < len && line[i] != ' ') {
            i++;
        }
        if (nt == cap) {
            return cap + 1u;
        }
        start[nt] = (uint16_t)b;
        tlen[nt] = (uint16_t)(i - b);
        nt++;
    }
    return nt;
}

uint16_t parse_trim(char *s, uint16_t n)
{
    uint16_t a = 0, b = n, i;
    while (a < b && s[a] == ' ') {
        a++;
    }
    while (b > a && s[b - 1u] == ' ') {
        b--;
    }
    for (i = a; i < b && a > 0u; i++) {
        s[i - a] = s[i];
    }
    return (uint16_t)(b - a);
}
