/* fmt.c - allocation-free, stdio-free number and text formatting.
 * SPDX-License-Identifier: MIT
 */
#include "fmt.h"
#include "cp_math.h"
#include "parse.h"

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

/* ---- fmt_real: the shortest decimal that parse_real reads back to the same real ---- */

#if CP_REAL_DOUBLE
typedef uint64_t fmt_mant;
#else
typedef uint32_t fmt_mant;
#endif
#define FMT_REAL_DIGITS ((unsigned)PARSE_MAX_DIGITS) /* parse_real's kept digits */
#define FMT_REAL_TEXT 40u                             /* one number's text, sign included */
#define FMT_REAL_WIDEN 22u   /* bracket doublings: 4 << 22 units, beyond any estimate error */
#define FMT_REAL_BISECT 64u  /* bisection steps: more than the bits of fmt_mant */

/* Append the decimal digits of m (at most 20) to t at *n. */
static void mant_digits(char *t, size_t *n, fmt_mant m)
{
    char d[20];
    unsigned k = 0;
    do {
        d[k++] = (char)('0' + (unsigned)(m % 10u));
        m /= 10u;
    } while (m != 0u && k < 20u);
    while (k > 0u) {
        t[(*n)++] = d[--k];
    }
}

/* The text of m * 10^e into t (NUL-free, *n chars): canonical != 0 strips m's trailing
 * zeros and writes a plain decimal where it is short ("360", "12.5", "0.001"), else
 * "<m>e<e>". */
static void real_text(char *t, size_t *n, fmt_mant m, int e, int canonical)
{
    unsigned nd = 0, k;
    fmt_mant r = m;
    *n = 0;
    for (k = 0; canonical && k < 24u && r != 0u && r % 10u == 0u; k++) {
        r /= 10u;
        e++;
    }
    for (m = r; r != 0u && nd < 24u; nd++) {
        r /= 10u;
    }
    if (canonical && e >= 0 && nd + (unsigned)e <= FMT_REAL_DIGITS) {
        mant_digits(t, n, m);
        for (k = 0; k < (unsigned)e; k++) {
            t[(*n)++] = '0';
        }
        return;
    }
    if (canonical && e < 0 && (unsigned)-e <= nd + 4u) {
        size_t d0;
        unsigned lead = (unsigned)-e >= nd ? (unsigned)-e - nd : 0u; /* zeros after "0." */
        if (lead > 0u || (unsigned)-e == nd) {
            t[(*n)++] = '0';
            t[(*n)++] = '.';
        }
        for (k = 0; k < lead; k++) {
            t[(*n)++] = '0';
        }
        d0 = *n;
        mant_digits(t, n, m);
        if ((unsigned)-e < nd) { /* the point inside the digits: shift the tail right */
            size_t at = d0 + nd - (unsigned)-e, i;
            for (i = *n; i > at; i--) {
                t[i] = t[i - 1u];
            }
            t[at] = '.';
            (*n)++;
        }
        return;
    }
    mant_digits(t, n, m);
    t[(*n)++] = 'e';
    if (e < 0) {
        t[(*n)++] = '-';
        e = -e;
    }
    mant_digits(t, n, (fmt_mant)e);
}

/* parse_real of m * 10^e's text (real_text) times scale into *x; 0 if parse_real refuses
 * it (then *x is +inf-like: above everything). */
static int real_value(fmt_mant m, int e, int canonical, cp_real scale, cp_real *x)
{
    char t[FMT_REAL_TEXT];
    size_t n;
    real_text(t, &n, m, e, canonical);
    if (parse_real(t, n, x) != CP_ST_OK) {
        return 0;
    }
    *x *= scale;
    return 1;
}

/* real_value compared with a: -1 below, 0 equal, 1 above (a refused text: above). */
static int real_cmp(fmt_mant m, int e, int canonical, cp_real scale, cp_real a)
{
    cp_real x;
    if (!real_value(m, e, canonical, scale, &x)) {
        return 1;
    }
    return x < a ? -1 : x > a ? 1 : 0;
}

/* The mantissa m of FMT_REAL_DIGITS digits (times 10^*e) whose text reads back (times
 * scale) as the smallest value >= a: bracket around the estimate a / scale, then bisect
 * (parse_real is monotonic in m). */
static fmt_mant real_search(cp_real a, cp_real scale, int *e)
{
    cp_real x = a / scale, top = CP_R(1.0);
    fmt_mant m0, lo, hi, w = 4u;
    unsigned k;
    for (k = 0; k < FMT_REAL_DIGITS; k++) {
        top *= CP_R(10.0); /* 10^digits, exact */
    }
    *e = 0;
    for (k = 0; k < 400u && x >= top; k++) { /* finite: at most ~310 steps */
        x /= CP_R(10.0);
        (*e)++;
    }
    for (k = 0; k < 400u && x * CP_R(10.0) < top; k++) {
        x *= CP_R(10.0);
        (*e)--;
    }
    m0 = (fmt_mant)(x + CP_R(0.5));
    lo = m0 > w ? m0 - w : 1u;
    hi = m0 + w;
    for (k = 0; k < FMT_REAL_WIDEN; k++) {
        int below = lo == 1u || real_cmp(lo, *e, 0, scale, a) < 0;
        if (below && real_cmp(hi, *e, 0, scale, a) >= 0) {
            break;
        }
        w *= 2u;
        lo = below ? lo : (m0 > w ? m0 - w : 1u);
        hi = m0 + w;
    }
    for (k = 0; k < FMT_REAL_BISECT && hi - lo > 1u; k++) {
        fmt_mant mid = lo + (hi - lo) / 2u;
        if (real_cmp(mid, *e, 0, scale, a) >= 0) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    return lo == 1u && real_cmp(1u, *e, 0, scale, a) >= 0 ? 1u : hi;
}

/* The text of a's shortest exact decimal (fmt_real) into t (*n chars); 0 if no decimal
 * reads back to a exactly (then *a is the value of the nearest one above). */
static int real_shortest(cp_real *a, cp_real scale, char *t, size_t *n)
{
    fmt_mant m, p10 = 1u;
    unsigned j;
    int e;
    m = real_search(*a, scale, &e);
    for (j = 1; j < FMT_REAL_DIGITS; j++) {
        p10 *= 10u;
    }
    /* m rounded to fewer digits, the fewest first, as long as it still reads back */
    for (j = FMT_REAL_DIGITS; j-- > 0u;) {
        fmt_mant mj = (m + p10 / 2u) / p10;
        if (mj != 0u && real_cmp(mj, e + (int)j, 1, scale, *a) == 0) {
            real_text(t, n, mj, e + (int)j, 1);
            return 1;
        }
        p10 /= 10u;
    }
    real_text(t, n, m, e, 0);
    if (real_cmp(m, e, 0, scale, *a) == 0) {
        return 1;
    }
    return !real_value(m, e, 0, scale, a); /* (refused: keep the text, give up) */
}

int fmt_real(char *buf, size_t cap, size_t *pos, cp_real v, cp_real scale)
{
    char t[FMT_REAL_TEXT + 1u];
    cp_real a = v < CP_R(0.0) ? -v : v;
    size_t n = 0;
    unsigned pass;
    if (!cp_finite(v) || !(scale > CP_R(0.0))) {
        return CP_ERR_INVAL;
    }
    if (!(a > CP_R(0.0))) {
        return fmt_str(buf, cap, pos, "0");
    }
    /* a value no decimal reads back to (one the firmware computed, not parsed): the
     * text of the nearest one above that does, as a dump of that value would print it */
    for (pass = 0; pass < 2u; pass++) {
        if (real_shortest(&a, scale, t + 1, &n)) {
            break;
        }
    }
    t[0] = '-';
    t[n + 1u] = '\0';
    return fmt_str(buf, cap, pos, v < CP_R(0.0) ? t : t + 1);
}
