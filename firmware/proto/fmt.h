/* fmt.h - allocation-free, stdio-free number and text formatting into caller buffers.
 * SPDX-License-Identifier: MIT
 *
 * Every function appends to buf at *pos without exceeding cap and returns 0, or
 * CP_ERR_FULL (nothing partial is promised: the caller sizes buf for the worst case).
 * Output is deterministic: integer arithmetic only, identical on every target.
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

#endif /* FMT_H */
