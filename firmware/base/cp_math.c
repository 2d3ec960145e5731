/* cp_math.c - deterministic sin/cos/atan2/exp/log kernels (float) or libm (double).
 * SPDX-License-Identifier: MIT
 */
#include "cp_math.h"

/* The external definitions of the inline helpers (C99 6.7.4: one copy for
 * the calls that are not inlined). */
extern cp_real cp_v3_dot(const struct cp_vec3 *a, const struct cp_vec3 *b);
extern cp_real cp_v3_norm(const struct cp_vec3 *a);
extern cp_real cp_v3_unit(struct cp_vec3 *v);
extern void cp_v3_sub(const struct cp_vec3 *a, const struct cp_vec3 *b, struct cp_vec3 *o);
extern void cp_v3_cross(const struct cp_vec3 *a, const struct cp_vec3 *b, struct cp_vec3 *o);
extern void cp_v3_comb(struct cp_vec3 *o, cp_real p, const struct cp_vec3 *a, cp_real q,
                       const struct cp_vec3 *b);
extern int cp_finite(cp_real x);

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

cp_real cp_exp(cp_real x)
{
    return exp(x > 709.7 ? 709.7 : x < -708.3 ? -708.3 : x);
}

cp_real cp_expm1(cp_real x)
{
    return expm1(x > 709.7 ? 709.7 : x);
}

cp_real cp_log(cp_real x)
{
    return log(x);
}

#else

/* Exact: |x| >= 2^23 is an integer already (and Inf/NaN pass through); below that the
 * conversion to int32_t truncates toward zero exactly and t - 1 is exact. floor(-0) is
 * +0 (no caller depends on the sign of a zero floor). */
cp_real cp_floorf(cp_real x)
{
    cp_real t;
    if (!(cp_fabs(x) < CP_R(8388608.0))) {
        return x;
    }
    t = (cp_real)(int32_t)x;
    return t > x ? t - CP_R(1.0) : t;
}

void cp_sincos(cp_real x, cp_real *s, cp_real *c)
{
    if (!(cp_fabs(x) <= CP_SINCOS_XMAX)) { /* |x| > XMAX or NaN */
        if (x != x) {
            *s = x;
            *c = x;
            return;
        }
        x = x > 0.0f ? CP_SINCOS_XMAX : -CP_SINCOS_XMAX;
    }
    {
        struct cp_sincos_st st;
        cp_sincos_stage1(x, &st);
        cp_sincos_stage2(&st, s, c);
    }
}

CP_NOINLINE void cp_sincos_stage1(cp_real x, struct cp_sincos_st *st)
{
    cp_sincos_in1(x, st);
}

CP_NOINLINE void cp_sincos_stage2(const struct cp_sincos_st *st, cp_real *s, cp_real *c)
{
    cp_sincos_in2(st, s, c);
}

/* atan z for z in [0, 1] (cp_atan2's only argument: a quotient of absolute values, or
 * NaN). On z <= tan(pi/8) = 0.41421: odd Taylor series to z^15; truncation
 * z^17/17 < 1.8e-8. Larger z use atan z = pi/4 + atan((z - 1)/(z + 1)). */
static float atan_unit(float z)
{
    const float tan_pi_8 = 0.414213562f;
    float off = 0.0f, z2;
    if (z > tan_pi_8) {
        off = 0.785398163f;
        z = (z - 1.0f) / (z + 1.0f);
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

/* 2^k for -126 <= k <= 127, exactly, from the exponent bits. */
static float pow2i(int32_t k)
{
    union {
        float f;
        uint32_t u;
    } v;
    v.u = (uint32_t)(k + 127) << 23;
    return v.f;
}

/* e^r - 1 on |r| <= ln 2 / 2 = 0.3466: Taylor to r^8 (truncation r^9/9! < 2.0e-10,
 * relative to |e^r - 1| >= 0.83 |r|: every term carries r), Horner in float: about
 * 2 ulp relative. */
static float expm1_core(float r)
{
    return r + r * r *
                   (0.5f +
                    r * (1.66666667e-1f +
                         r * (4.16666667e-2f +
                              r * (8.33333333e-3f +
                                   r * (1.38888889e-3f +
                                        r * (1.98412698e-4f + r * 2.48015873e-5f))))));
}

/* Error analysis (float). Reduction x = k ln2 + r with k = nearest integer to
 * x / ln 2 (the 1.5 2^23 rounding trick, exact for |k| < 2^22) and r = (x - k L1) - k L2,
 * L1 = 0.693145752 (exact, 16 significant bits: k L1 exact for |k| <= 128) and
 * L2 = 1.42860677e-6 (L1 + L2 = ln 2 to 1e-13): one rounding in k L2 and one in the
 * subtraction, |r error| <= 1 ulp(0.35) = 3e-8 absolute = 3e-8 relative on e^x.
 * e^r = 1 + expm1_core(r): <= 2 ulp. Scaling by 2^k is exact (two factors so that
 * k = 128 and k = -126 stay normal). Total <= 4 ulp. */
cp_real cp_exp(cp_real x)
{
    const float inv_ln2 = 1.44269504f;
    const float l1 = 0.693145752f;
    const float l2 = 1.42860677e-6f;
    const float round_magic = 12582912.0f;
    float kf, r;
    int32_t k, k1;
    if (x != x) {
        return x;
    }
    if (x > 88.7f) {
        x = 88.7f;
    } else if (x < -87.3f) {
        x = -87.3f;
    }
    kf = (x * inv_ln2 + round_magic) - round_magic;
    k = (int32_t)kf;
    r = (x - kf * l1) - kf * l2;
    k1 = k / 2;
    return ((1.0f + expm1_core(r)) * pow2i(k1)) * pow2i(k - k1);
}

cp_real cp_expm1(cp_real x)
{
    if (x >= -0.346573590f && x <= 0.346573590f) {
        return expm1_core(x);
    }
    return cp_exp(x) - 1.0f;
}

/* Error analysis (float). x = m 2^e with m in [sqrt(1/2), sqrt(2)) from the bits
 * (subnormals first scaled by 2^25, exactly). log m = 2 atanh(s), s = (m - 1)/(m + 1),
 * |s| <= 0.1716: odd series to s^9 (truncation 2 s^11 / 11 < 7.5e-10), m - 1 exact
 * (Sterbenz), s within 1.5 ulp; result e L1 + (e L2 + log m) with L1 = 0.693145752
 * (e L1 exact for |e| <= 150) and L2 = 1.42860677e-6: about 2e-7 + 4 ulp absolute. */
cp_real cp_log(cp_real x)
{
    const float l1 = 0.693145752f;
    const float l2 = 1.42860677e-6f;
    union {
        float f;
        uint32_t u;
    } v;
    int32_t e = 0;
    float m, s, s2, lm;
    if (!(x > 0.0f)) {
        return (x - x) / (x - x); /* NaN for x <= 0 and for NaN */
    }
    if (!cp_finite(x)) {
        return x; /* +inf (x > 0 here) */
    }
    if (x < 1.17549435e-38f) {
        x *= 33554432.0f; /* 2^25: subnormal to normal, exact */
        e = -25;
    }
    v.f = x;
    e += (int32_t)((v.u >> 23) & 0xFFu) - 127;
    v.u = (v.u & 0x007FFFFFu) | 0x3F800000u; /* m in [1, 2) */
    m = v.f;
    if (m > 1.41421356f) {
        m *= 0.5f; /* exact */
        e += 1;
    }
    s = (m - 1.0f) / (m + 1.0f);
    s2 = s * s;
    lm = 2.0f * s +
         2.0f * s * s2 *
             (3.33333333e-1f + s2 * (2.0e-1f + s2 * (1.42857143e-1f + s2 * 1.11111111e-1f)));
    return (float)e * l1 + ((float)e * l2 + lm);
}

#endif
