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
 * |x| > CP_SINCOS_XMAX is clamped to +-CP_SINCOS_XMAX (a finite, meaningless
 * result, never non-finite for finite x); NaN gives NaN. */
void cp_sincos(cp_real x, cp_real *s, cp_real *c);

/* The sincos kernel in two stages, so a caller can spread one evaluation over two
 * calls (canal_path.c makes the next line's label over the last two points of a line):
 * cp_sincos_stage1 (argument reduction and the sine polynomial) then
 * cp_sincos_stage2 (the cosine polynomial and the quadrant). The pair performs
 * exactly the operations of cp_sincos_kernel on the same float values, so the
 * result is bit-identical to cp_sincos(x) however far apart the stages run. */
/* Largest |x| the kernel and its stages take as is (float build). */
#define CP_SINCOS_XMAX CP_R(1.0e5)

struct cp_sincos_st {
    cp_real a, b; /* float: r^2 and the sine polynomial; double: x */
    int32_t k;    /* float: quadrant count */
};

#if CP_REAL_DOUBLE
static inline void cp_sincos_stage1(cp_real x, struct cp_sincos_st *st)
{
    st->a = x;
    st->b = 0.0;
    st->k = 0;
}

static inline void cp_sincos_stage2(const struct cp_sincos_st *st, cp_real *s, cp_real *c)
{
    *s = sin(st->a);
    *c = cos(st->a);
}

static inline void cp_sincos_kernel(cp_real x, cp_real *s, cp_real *c)
{
    *s = sin(x);
    *c = cos(x);
}

/* the inlined halves (the float build's cp_sincos_in1/in2): the stages themselves */
static inline void cp_sincos_in1(cp_real x, struct cp_sincos_st *st)
{
    cp_sincos_stage1(x, st);
}

static inline void cp_sincos_in2(const struct cp_sincos_st *st, cp_real *s, cp_real *c)
{
    cp_sincos_stage2(st, s, c);
}
#else
/* The float kernel of cp_sincos in two always-inline halves (cp_sincos_in1, cp_sincos_in2);
 * cp_sincos_kernel, the two inlined together, serves the per-point jet (canal_jet). */
/* Error analysis (float).
 * Reduction: k = nearest integer to x 2/pi; r = ((x - k P1) - k P2) - k P3 with
 * P1 + P2 + P3 = pi/2 to ~2^-72; P1 and P2 have 12 and 12 significant bits... here
 * P1 = 1.5703125 (exact, 9 bits) and P2 = 4.83751296997e-4 (exact, 17 bits), so
 * k P1 and k P2 are exact for |k| < 2^14 (|x| < 2.5e4) and the only rounding is in
 * the last term and the two subtractions: |r error| <= 2 ulp(pi/4) ~ 1.2e-7.
 * Kernels on |r| <= pi/4: sin by Taylor to r^9 (truncation r^11/11! < 1.7e-9),
 * cos to r^10 (truncation r^12/12! < 1.2e-10), Horner in float: a few ulp of 1. */
/* Precondition of the kernel and its stages: |x| <= CP_SINCOS_XMAX (cp_sincos clamps;
 * the jet's argument is bounded by canal_init's CANAL_COORD_MAX = 1e4). */
static CP_ALWAYS_INLINE void cp_sincos_in1(cp_real x, struct cp_sincos_st *st)
{
    const float two_over_pi = 0.636619772f;
    const float p1 = 1.5703125f;
    const float p2 = 4.837512969970703125e-4f;
    const float p3 = 7.54978995489e-8f;
    const float round_magic = 12582912.0f; /* 1.5 2^23: (v + M) - M = v rounded to even */
    float kf = x * two_over_pi;
    int32_t k;
    float r, r2;
    /* |x| <= CP_SINCOS_XMAX: |kf| <= 6.4e4 << 2^22, so kf + M lands in [2^23, 2^24)
     * where the float spacing is 1: the sum is kf rounded to the nearest integer, and
     * the difference is exact (-ffp-contract=off keeps both roundings). */
    kf = (kf + round_magic) - round_magic;
    k = (int32_t)kf;
    r = ((x - kf * p1) - kf * p2) - kf * p3;
    r2 = r * r;
    st->a = r2;
    st->b = r + r * r2 *
                    (-1.66666667e-1f +
                     r2 * (8.33333333e-3f + r2 * (-1.98412698e-4f + r2 * 2.75573192e-6f)));
    st->k = k;
}

static CP_ALWAYS_INLINE void cp_sincos_in2(const struct cp_sincos_st *st, cp_real *s, cp_real *c)
{
    float r2 = st->a, sr = st->b;
    float cr = 1.0f +
               r2 * (-0.5f + r2 * (4.16666667e-2f +
                                   r2 * (-1.38888889e-3f +
                                         r2 * (2.48015873e-5f + r2 * -2.75573192e-7f))));
    /* quarter k: (sin, cos) = (sr, cr), (cr, -sr), (-sr, -cr), (-cr, sr) for k & 3 = 0..3:
     * an odd k swaps and negates the new cos, k & 2 negates both (negation is exact) */
    if ((uint32_t)st->k & 1u) {
        float t = sr;
        sr = cr;
        cr = -t;
    }
    if ((uint32_t)st->k & 2u) {
        sr = -sr;
        cr = -cr;
    }
    *s = sr;
    *c = cr;
}

static CP_ALWAYS_INLINE void cp_sincos_kernel(cp_real x, cp_real *s, cp_real *c)
{
    struct cp_sincos_st st;
    cp_sincos_in1(x, &st);
    cp_sincos_in2(&st, s, c);
}

/* The stages out of line (cp_math.c: one copy of each, which cp_sincos calls too); the
 * per-point jet inlines the kernel and canal_path.c's label halves inline cp_sincos_in1
 * and cp_sincos_in2 (the same operations: a line's last point pays no call). */
void cp_sincos_stage1(cp_real x, struct cp_sincos_st *st);
void cp_sincos_stage2(const struct cp_sincos_st *st, cp_real *s, cp_real *c);

#endif

/* atan2(y, x) in (-pi, pi], radians; atan2(0, 0) = 0. Float build: error <= 2e-7
 * rad (octant reduction, then tan(pi/8) reduction and a degree-15 odd series). */
cp_real cp_atan2(cp_real y, cp_real x);

/* e^x. Float build: relative error <= 4 ulp (about 2.4e-7); x is clamped to
 * [-87.3, 88.7] (results 1.2e-38 .. 3.4e38: never inf, never subnormal); NaN gives
 * NaN. Double build: libm exp with x clamped to [-708.3, 709.7] (never inf). */
cp_real cp_exp(cp_real x);

/* e^x - 1 with full relative precision near 0 (no cancellation for small |x|):
 * float build, relative error <= 4 ulp on |x| <= ln 2 / 2, else cp_exp(x) - 1.
 * Same clamp as cp_exp. Double build: libm expm1 (x clamped above at 709.7). */
cp_real cp_expm1(cp_real x);

/* Natural logarithm. Float build: absolute error <= 2e-7 + 4 ulp of the result for
 * x > 0 (subnormals included); log(+inf) = +inf; x <= 0 or NaN gives NaN (callers
 * validate first: the firmware never feeds it a non-positive number). Double build:
 * libm log. */
cp_real cp_log(cp_real x);

/* 3-vectors (struct cp_vec3, cp_types.h): the one set of vector operations of the
 * firmware, used by every surface model. Every result is the plain expression in the
 * order written (-ffp-contract=off), so the bits do not depend on whether a call is
 * inlined. C99 inline definitions: a caller may inline them or call the one external
 * definition in cp_math.c. An output may alias an input (each is formed before it is
 * stored). */

/* a.b = ax bx + ay by + az bz, summed left to right. */
inline cp_real cp_v3_dot(const struct cp_vec3 *a, const struct cp_vec3 *b)
{
    return a->x * b->x + a->y * b->y + a->z * b->z;
}

/* |a| = sqrt(cp_v3_dot(a, a)). */
inline cp_real cp_v3_norm(const struct cp_vec3 *a)
{
    return cp_sqrt(cp_v3_dot(a, a));
}

/* o = a - b. */
inline void cp_v3_sub(const struct cp_vec3 *a, const struct cp_vec3 *b, struct cp_vec3 *o)
{
    o->x = a->x - b->x;
    o->y = a->y - b->y;
    o->z = a->z - b->z;
}

/* o = a x b: ox = ay bz - az by, oy = az bx - ax bz, oz = ax by - ay bx. */
inline void cp_v3_cross(const struct cp_vec3 *a, const struct cp_vec3 *b, struct cp_vec3 *o)
{
    cp_real x = a->y * b->z - a->z * b->y, y = a->z * b->x - a->x * b->z;
    o->z = a->x * b->y - a->y * b->x;
    o->x = x;
    o->y = y;
}

/* o = p a + q b, each component p a_k + q b_k (p = 1 or q = 0 are exact, q = 0 still adds
 * the product 0 b_k). */
inline void cp_v3_comb(struct cp_vec3 *o, cp_real p, const struct cp_vec3 *a, cp_real q,
                       const struct cp_vec3 *b)
{
    o->x = p * a->x + q * b->x;
    o->y = p * a->y + q * b->y;
    o->z = p * a->z + q * b->z;
}

/* v /= |v| as v * (1 / |v|) (one division); returns |v| (|v| = 0: v becomes NaN, the
 * callers check). Each component: 2 roundings beyond the norm's relative error. */
inline cp_real cp_v3_unit(struct cp_vec3 *v)
{
    cp_real l = cp_v3_norm(v), f = CP_R(1.0) / l;
    v->x *= f;
    v->y *= f;
    v->z *= f;
    return l;
}

/* 1 if x is finite, 0 for an infinity or a NaN: x - x is 0 exactly for a finite x (NaN
 * otherwise), one comparison, no libm. The one finite test of the firmware. */
inline int cp_finite(cp_real x)
{
    return x - x == CP_R(0.0);
}

#endif /* CP_MATH_H */
