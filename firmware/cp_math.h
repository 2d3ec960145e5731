/* cp_math.h - deterministic elementary functions for cp_real.
 * SPDX-License-Identifier: MIT
 *
 * The float build uses these kernels instead of libm's sinf/cosf/atan2f so that
 * (a) the native and the Cortex-M4F builds produce bit-identical results (only
 * +, -, *, / and sqrt, all IEEE correctly rounded, with -ffp-contract=off), and
 * (b) the M4F image does not pull newlib's 4 KB range-reduction tables.
 * The double build (host only) uses libm.
 */
#ifndef CP_MATH_H
#define CP_MATH_H

#include "cp_types.h"

/* sin and cos of x (radians). Float build: |x| <= 1e4, absolute error <= 2 ulp
 * of 1 (about 1.2e-7) after Cody-Waite reduction by pi/2 in three parts and
 * degree-9/10 Taylor kernels on [-pi/4, pi/4] (truncation < 2e-9).
 * Out-of-range |x| is reduced anyway (accuracy degrades, never non-finite for
 * finite x). */
void cp_sincos(cp_real x, cp_real *s, cp_real *c);

/* atan2(y, x) in (-pi, pi], radians; atan2(0, 0) = 0. Float build: error <= 2e-7
 * rad (octant reduction, then tan(pi/8) reduction and a degree-15 odd series). */
cp_real cp_atan2(cp_real y, cp_real x);

#endif /* CP_MATH_H */
