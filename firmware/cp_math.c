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

void cp_sincos(cp_real x, cp_real *s, cp_real *c)
{
    if (!(x >= -CP_SINCOS_XMAX && x <= CP_SINCOS_XMAX)) {
        if (x != x) {
            *s = x;
            *c = x;
            return;
        }
        x = x > 0.0f ? CP_SINCOS_XMAX : -CP_SINCOS_XMAX;
    }
    cp_sincos_kernel(x, s, c);
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
    return off +
           (z + z * z2 *
                    (-3.33333333e-1f +
                     z2 * (2.0e-1f +
                           z2 * (-1.42857143e-1f +
                                 z2 * (1.11111111e-1f +
                                       z2 * (-9.09090909e-2f +
                                             z2 * (7.69230769e-2f + z2 * -6.66666667e-2f)))))));
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
