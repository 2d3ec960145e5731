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

#if CP_REAL_DOUBLE
static inline void cp_sincos_kernel(cp_real x, cp_real *s, cp_real *c)
{
    *s = sin(x);
    *c = cos(x);
}
#else
/* The float kernel of cp_sincos, inlined into the per-point jet (canal_jet). */
/* Error analysis (float).
 * Reduction: k = nearest integer to x 2/pi; r = ((x - k P1) - k P2) - k P3 with
 * P1 + P2 + P3 = pi/2 to ~2^-72; P1 and P2 have 12 and 12 significant bits... here
 * P1 = 1.5703125 (exact, 9 bits) and P2 = 4.83751296997e-4 (exact, 17 bits), so
 * k P1 and k P2 are exact for |k| < 2^14 (|x| < 2.5e4) and the only rounding is in
 * the last term and the two subtractions: |r error| <= 2 ulp(pi/4) ~ 1.2e-7.
 * Kernels on |r| <= pi/4: sin by Taylor to r^9 (truncation r^11/11! < 1.7e-9),
 * cos to r^10 (truncation r^12/12! < 1.2e-10), Horner in float: a few ulp of 1. */
static CP_ALWAYS_INLINE void cp_sincos_kernel(cp_real x, cp_real *s, cp_real *c)
{
    const float two_over_pi = 0.636619772f;
    const float p1 = 1.5703125f;
    const float p2 = 4.837512969970703125e-4f;
    const float p3 = 7.54978995489e-8f;
    float kf = x * two_over_pi;
    int32_t k;
    float r, r2, sr, cr;
    kf = (kf >= 0.0f) ? (kf + 0.5f) : (kf - 0.5f);
    if (kf > 2147483520.0f) {
        kf = 2147483520.0f;
    } else if (kf < -2147483520.0f) {
        kf = -2147483520.0f;
    }
    k = (int32_t)kf; /* truncation of (v +- 0.5): round half away from zero */
    kf = (float)k;
    r = ((x - kf * p1) - kf * p2) - kf * p3;
    r2 = r * r;
    sr = r + r * r2 *
                 (-1.66666667e-1f +
                  r2 * (8.33333333e-3f + r2 * (-1.98412698e-4f + r2 * 2.75573192e-6f)));
    cr = 1.0f +
         r2 * (-0.5f + r2 * (4.16666667e-2f + r2 * (-1.38888889e-3f +
                                                    r2 * (2.48015873e-5f + r2 * -2.75573192e-7f))));
    switch ((uint32_t)k & 3u) {
    case 0u:
        *s = sr;
        *c = cr;
        break;
    case 1u:
        *s = cr;
        *c = -sr;
        break;
    case 2u:
        *s = -sr;
        *c = -cr;
        break;
    default:
        *s = -cr;
        *c = sr;
        break;
    }
}

#endif

/* atan2(y, x) in (-pi, pi], radians; atan2(0, 0) = 0. Float build: error <= 2e-7
 * rad (octant reduction, then tan(pi/8) reduction and a degree-15 odd series). */
cp_real cp_atan2(cp_real y, cp_real x);

#endif /* CP_MATH_H */
