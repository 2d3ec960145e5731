/* ref_gsr.h - independent double-precision reference of the generalized surface of
 * revolution (seed 003, MATH-seeds-2-3-4.md part C); used by tests/test_gsr.c and by
 * host_sim's judge (host_sim/judge_gsr.c).
 * SPDX-License-Identifier: MIT
 *
 * Written from the definitions of part C only; no firmware code, written differently:
 *   - scalar functions by explicit powers and libm sin/cos; a Bezier centre by de
 *     Casteljau (point) and its hodographs (derivatives), never the power basis;
 *   - frames straight from the paper's formulas: FIXED N = (T_z, 0, -T_x), B = +y;
 *     FRENET B = unit(C' x C''), N = B x T; N0 B = unit(T x N0), N = B x T (eq. 10);
 *     RMF by double reflection (Wang et al. 2008) on a dense table (REF_GSR_RMF nodes,
 *     REF_GSR_RMF_SUB steps each) from N(t0) = the projection of ref, and for any t a
 *     march from the node below in REF_GSR_RMF_SUB steps;
 *   - points by the trigonometric form G = C + f_N cos(theta) N + f_B sin(theta) B;
 *   - the unit normal from G_theta (analytic) x G_u (Richardson-extrapolated central
 *     differences, h = 1e-3 and 5e-4, error ~1e-12);
 *   - theta(psi) and psi(theta) of the rational quarter by the closed forms of C.2.
 * Kinds use the numbers of the protocol: centre 0 polynomial+sinusoid, 1 Bezier; frame
 * 0 FIXED, 1 FRENET, 2 N0, 3 RMF. Plain C99 + <math.h>, no allocation.
 */
#ifndef REF_GSR_H
#define REF_GSR_H

#define REF_GSR_RMF 1024
#define REF_GSR_RMF_SUB 4

struct ref_gsr {
    int centre, frame;
    double c[3][7], r[3][7], ref[3];
    double t0, t1;                    /* f_t(0), f_t(1) */
    double rmf[REF_GSR_RMF + 1][3];   /* RMF unit normals at t0 + k (t1 - t0) / REF_GSR_RMF */
};

/* Set up (and build the RMF table for frame 3). c: centre functions (centre 0) or Bezier
 * control points c[axis][i] (centre 1); r: f_N, f_B, f_t; w in RADIANS per unit. */
void ref_gsr_set(struct ref_gsr *g, int centre, const double c[3][7], const double r[3][7],
                 int frame, const double ref[3]);

/* f, f', f'' of one 7-number function at x. */
void ref_gsr_fn(const double a[7], double x, double d[3]);

/* C, C', C'' at t. */
void ref_gsr_centre(const struct ref_gsr *g, double t, double C[3], double D1[3], double D2[3]);

/* Unit T, N, B at t. */
void ref_gsr_frame(const struct ref_gsr *g, double t, double T[3], double N[3], double B[3]);

/* Surface point at (u, theta). */
void ref_gsr_point(const struct ref_gsr *g, double u, double theta, double P[3]);

/* Unit normal at (u, theta): unit(G_theta x G_u), outward where 1 - k.(G - C) > 0 and
 * f_t' > 0 (along +-T where f_t' = 0). */
void ref_gsr_normal(const struct ref_gsr *g, double u, double theta, double n[3]);

/* Eccentric angle of rational section position psi = q + v, and the inverse. */
double ref_gsr_theta(double psi);
double ref_gsr_psi(double theta);

/* Arc length of the ellipse (a cos t, b sin t) from th0 to th1 by adaptive Simpson
 * (absolute tolerance tol, Richardson-corrected panels), and its perimeter by the
 * arithmetic-geometric mean (complete elliptic integral E, ~1e-16 relative). */
double ref_gsr_arc(double a, double b, double th0, double th1, double tol);
double ref_gsr_perimeter(double a, double b);

/* ---- the far parts of the sweep (issue 22): an independent overlap measure ----
 * The solid of the sweep is the union of its section DISKS D(u) (the filled ellipses in
 * the normal planes). ref_gsr_far_dist gives the distance from a point q to the part of
 * that solid whose sections lie more than `near` mm of centre arc away from the section u
 * (both ways round on a closed centre), wherever it is below `need` (mm): on REF_GSR_FAR + 1
 * samples u' = k / REF_GSR_FAR each disk's distance exactly (the point's height over the
 * disk's plane and its in-plane distance to the filled ellipse, the closest ellipse point
 * by bisection of the derivative's sign), the samples within `lip` (the largest move of a
 * disk point between samples) of `need` refined by golden section over their two
 * neighbouring intervals (40 steps). A sample whose bounding ball (the larger semi-axis)
 * is `need` + lip away or more is skipped (the distance there is at least need).
 * A streamed tool centre q of radius r gouges that far part iff far_dist < r (need = r); a
 * surface point (r = 0) lies inside it iff far_dist = 0. Written from the definitions
 * alone (no firmware code; the firmware bounds pieces by capsules, this measures disks). */
#define REF_GSR_FAR 512
struct ref_gsr_far {
    double s[REF_GSR_FAR + 1];        /* centre arc length from u = 0, mm (8 chords a sample) */
    double c[REF_GSR_FAR + 1][3];     /* centre C(f_t(u)) */
    double fr[REF_GSR_FAR + 1][3][3]; /* T, N, B */
    double ab[REF_GSR_FAR + 1][2];    /* f_N, f_B */
    double len, rmax, lip;            /* total arc, largest semi-axis, largest sample move */
    int closed;                       /* |C(end) - C(start)| <= 1e-5 len */
};
void ref_gsr_far_init(struct ref_gsr_far *f, const struct ref_gsr *g);
/* min over the far sections u' of |q - D(u')| (mm; *uat: that u', -1 if none below need),
 * exact below need; otherwise a number >= need (1e30 when no section is far). */
double ref_gsr_far_dist(const struct ref_gsr *g, const struct ref_gsr_far *f, const double q[3],
                        double u, double near, double need, double *uat);

#endif /* REF_GSR_H */
