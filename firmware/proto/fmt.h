/* fmt.h - allocation-free, stdio-free number and text formatting into caller buffers.
 * SPDX-License-Identifier: MIT
 *
 * Every function appends to buf at *pos without exceeding cap and returns 0, or
 * CP_ERR_FULL (nothing partial is promised: the caller sizes buf for the worst case).
 * Output is deterministic: integer arithmetic only (fmt_real: IEEE arithmetic, as
 * parse_real), identical on every target.
 */
#ifndef FMT_H
#define FMT_H

#include "cp_types.h"

/* Append the NUL-free string s. */
int fmt_str(char *buf, size_t cap, size_t *pos, const char *s);

/* Append an unsigned decimal integer. */
int fmt_u32(char *buf, size_t cap, size_t *pos, uint32_t v);

/* Append a signed decimal integer. */
int fmt_i32(char *buf, size_t cap, size_t *pos, int32_t v);

/* Append v, given as an integer count of 10^-decimals units, as a fixed-point
 * decimal with exactly `decimals` (0-9) digits after the point, e.g.
 * fmt_fixed(.., -12345, 4) -> "-1.2345". */
int fmt_fixed(char *buf, size_t cap, size_t *pos, int32_t v, unsigned decimals);

/* Append the shortest decimal D (plain, "12.5", or "<digits>e<exp>") for which
 * parse_real(D) * scale == v exactly (scale > 0: the factor the job applied to the
 * wire's number, 1 for none), so that a number printed from the job reads back to the
 * same bits; with no such D (none exists only for values parse_real cannot produce)
 * the nearest above. The search calls parse_real (at most ~100 times): deterministic,
 * but real arithmetic, unlike the integer formatters above. CP_ERR_INVAL for a
 * non-finite v or scale <= 0; at most 1 + PARSE_MAX_DIGITS + 6 characters. */
int fmt_real(char *buf, size_t cap, size_t *pos, cp_real v, cp_real scale);

#endif /* FMT_H */
