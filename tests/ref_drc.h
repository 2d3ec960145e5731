/* ref_drc.h - independent double-precision reference of DRC-EXP and the alternatives.
 * SPDX-License-Identifier: MIT
 *
 * Written from MATH-seeds-2-3-4.md part A only; includes no firmware header and shares
 * no code with firmware/models/drc.c. Differences on purpose: libm expm1 with the A.2 series
 * threshold (|q| < 1e-4), <complex.h> for every insertion (planar data too: the
 * twisted model reduces to real z), explicit angle bookkeeping with acos-free
 * atan2 forms, out-of-place passes. Also: DD4 (4-point Dubuc/Deslauriers), CCR
 * (centripetal Catmull-Rom, Barry-Goldman), CSPLINE (natural cubic spline, chord
 * parameter), sampled at 2^K uniform parameter steps per input segment, and the
 * measures of A.4 in double. Plain C99 + libm; no allocation (caller buffers).
 */
#ifndef REF_DRC_H
#define REF_DRC_H

#define REF_DRC_MAXN 16
#define REF_DRC_MAXOUT (128 * 15 + 1) /* K <= 7 on 16 points */

/* error codes (same meaning as enum cp_err's, own numbers) */
enum {
    REF_DRC_OK = 0,
    REF_DRC_TOO_FEW = 1,
    REF_DRC_COINCIDENT = 2,
    REF_DRC_TURN = 3,
    REF_DRC_NONFINITE = 4,
    REF_DRC_TWIST = 5,
    REF_DRC_TOO_MANY = 6
};

/* Steps 0 + 1: tangents T[n] of points P[n]. Returns a REF_DRC_* code. */
int ref_drc_tangents(const double (*P)[3], int n, double (*T)[3]);

/* Step 2 on one segment. */
void ref_drc_insert(const double A[3], const double TA[3], const double B[3],
                    const double TB[3], double M[3], double TM[3]);

/* K passes, out of place: out[] holds 2^K (n-1) + 1 points (and tangents if Tout).
 * Returns a REF_DRC_* code; *nout the count. */
int ref_drc_run(const double (*P)[3], int n, int K, double (*out)[3], double (*Tout)[3],
                int *nout);

/* The same three in long double: tests/ref_drc_ld.c compiles ref_drc.c with REF_DRC_LD = 1
 * (the same source; libm's long double functions through <tgmath.h>). The high-precision
 * recomputation of the scheme that host_sim's verdicts are checked against (issue 21);
 * 64-bit mantissa on x86-64, the double build's precision where long double is double
 * (the Cortex-M4F). */
int ref_drc_tangents_ld(const long double (*P)[3], int n, long double (*T)[3]);
void ref_drc_insert_ld(const long double A[3], const long double TA[3], const long double B[3],
                       const long double TB[3], long double M[3], long double TM[3]);
int ref_drc_run_ld(const long double (*P)[3], int n, int K, long double (*out)[3],
                   long double (*Tout)[3], int *nout);

/* Alternatives, 2^K samples per input segment; returns the count. */
int ref_dd4(const double (*P)[3], int n, int K, double (*out)[3]);
int ref_ccr(const double (*P)[3], int n, int K, double (*out)[3]);
int ref_cspline(const double (*P)[3], int n, int K, double (*out)[3]);

struct ref_measures {
    int extrema, signs, between, t_extrema;
    double kmin, kmax, tmin, tmax;
};

/* A.4 measures of a polyline (planar: signed by +z when sgn). */
void ref_measure(const double (*P)[3], int n, int sgn, struct ref_measures *m);

/* curvature of the circle through three points (signed by +z when sgn) */
double ref_kappa3(const double a[3], const double b[3], const double c[3], int sgn);

#endif /* REF_DRC_H */
