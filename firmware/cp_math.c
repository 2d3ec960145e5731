/* cp_math.c - deterministic sin/cos/atan2 kernels (float) or libm (double).
 * SPDX-License-Identifier: MIT
 */
#include "cp_math.h"

#if CP_REAL_DOUBLE

void cp_sincos(cp_real x, cp_real *s, cp_real *c)
{
    *s = sin(x);
    *c = cos(x);
}

cp_real cp_atan2(cp_real y, cp_real x)
{
    if (x == 0.0 && y == 0.0) {
        return 0.0;
    }
    return atan2(y, x);
}

#else

/* Error analysis (float).
 * Reduction: k = nearest integer to x 2/pi; r = ((x - k P1) - k P2) - k P3 with
 * P1 + P2 + P3 = pi/2 to ~2^-72; P1 and P2 have 12 and 12 significant bits... here
 * P1 = 1.5703125 (exact, 9 bits) and P2 = 4.83751296997e-4 (exact, 17 bits), so
 * k P1 and k P2 are exact for |k| < 2^14 (|x| < 2.5e4) and the only rounding is in
 * the last term and the two subtractions: |r error| <= 2 ulp(pi/4) ~ 1.2e-7.
 * Kernels on |r| <= pi/4: sin by Taylor to r^9 (truncation r^11/11! < 1.7e-9),
 * cos to r^10 (truncation r^12/12! < 1.2e-10), Horner in float: a few ulp of 1. */
void cp_sincos(cp_real x, cp_real *s, cp_real *c)
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
    sr = r + r * r2 * (-1.66666667e-1f +
                       r2 * (8.33333333e-3f + r2 * (-1.98412698e-4f + r2 * 2.75573192e-6f)));
    cr = 1.0f + r2 * (-0.5f + r2 * (4.16666667e-2f +
                                     r2 * (-1.38888889e-3f +
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

/* atan on |z| <= tan(pi/8) = 0.41421: odd Taylor series to z^15; truncation
 * z^17/17 < 1.8e-8. Larger |z| <= 1 use atan z = pi/4 + atan((z - 1)/(z + 1)). */
static float atan_unit(float z)
{
    const float tan_pi_8 = 0.414213562f;
    float off = 0.0f, z2;
    if (z > tan_pi_8) {
        off = 0.785398163f;
        z = (z - 1.0f) / (z + 1.0f);
    } else if (z < -tan_pi_8) {
        off = -0.785398163f;
        z = (z + 1.0f) / (1.0f - z);
    }
    z2 = z * z;
    return off + (z + z * z2 * (-3.33333333e-1f +
                                z2 * (2.0e-1f +
                                      z2 * (-1.42857143e-1f +
                                            z2 * (1.11111111e-1f +
                                                  z2 * (-9.09090909e-2f +
                                                        z2 * (7.69230769e-2f +
                                                              z2 * -6.66666667e-2f)))))));
}

cp_real cp_atan2(cp_real y, cp_real x)
{
    const float pi = 3.14159265f;
    const float half_pi = 1.57079633f;
    float ax = fabsf(x), ay = fabsf(y), a;
    if (ax == 0.0f && ay == 0.0f) {
        return 0.0f;
    }
    if (ay <= ax) {
        a = atan_unit(ay / ax);
    } else {
        a = half_pi - atan_unit(ax / ay);
    }
    if (x < 0.0f) {
        a = pi - a;
    }
    return (y < 0.0f) ? -a : a;
}

#endif
