/* parse.h - deterministic, allocation-free number and token parsing for command lines.
 * SPDX-License-Identifier: MIT
 *
 * Numbers: [+-] digits [. digits] [(e|E) [+-] digits], or [+-] . digits ...
 * At most PARSE_MAX_DIGITS significant digits are kept (further digits only scale);
 * the result is the kept mantissa times a power of ten, computed with at most three
 * roundings (<= 1.5 ulp) identically on every target. No locale, no libc strtod.
 */
#ifndef PARSE_H
#define PARSE_H

#include "cp_types.h"
#include "cp_status.h"

#if CP_REAL_DOUBLE
#define PARSE_MAX_DIGITS 17
#else
#define PARSE_MAX_DIGITS 9
#endif

/* Largest |value| accepted by parse_real. Larger values are CP_ST_OUT_OF_RANGE. */
#define PARSE_ABS_MAX CP_R(1.0e9)

/* Parse the n characters at s (no terminator needed) as one number.
 * Returns CP_ST_OK and *out, or a wire status:
 *   CP_ST_BAD_NUMBER    empty, stray characters, no digits, exponent without digits
 *   CP_ST_NONFINITE     "nan", "inf", "infinity" in any case, with optional sign
 *   CP_ST_OUT_OF_RANGE  |value| > PARSE_ABS_MAX or exponent beyond +-40 */
int parse_real(const char *s, size_t n, cp_real *out);

/* Parse an unsigned decimal integer <= max. Same status codes. */
int parse_uint(const char *s, size_t n, uint32_t max, uint32_t *out);

/* Split line[0..len) at spaces into at most cap tokens (start offset, length).
 * Returns the token count, or cap + 1 if there were more than cap tokens. */
unsigned parse_split(const char *line, size_t len, uint16_t *start, uint16_t *tlen, unsigned cap);

/* Case-insensitive comparison of s[0..n) with an upper-case keyword. */
int parse_is(const char *s, size_t n, const char *kw);

/* 1 if s[0..n) is one of the cnt upper-case keywords kws[0..cnt) (parse_is), else 0. */
int parse_is_any(const char *s, size_t n, const char *const *kws, unsigned cnt);

/* Remove the spaces at both ends of s[0..n), in place (the rest moves to the front).
 * Returns the new length. */
uint16_t parse_trim(char *s, uint16_t n);

/* Longest keyword of commands.def, NUL included (job.c asserts it row by row). */
#define PARSE_KW_MAX 16u

#endif /* PARSE_H */
