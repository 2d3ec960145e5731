/* ref_channel.h - independent double-precision reference of the channel surface (seed 002).
 * SPDX-License-Identifier: MIT
 *
 * Written from ../shared/docs/MATH-seeds-2-3-4.md part B only; it calls no firmware code
 * and is written differently from firmware/models/channel.c:
 *   - orientation by explicit 3x3 matrix products of eqs. (10)-(12);
 *   - guide by the six quintic Hermite basis functions of B.2 step 2 (and their
 *     derivatives) as printed, the node second derivatives of B7 from the one-sided
 *     cubic-Hermite values;
 *   - natural splines by Gaussian elimination of the full N x N system (end rows
 *     y2 = 0), evaluated in the moment form with explicit h = 1;
 *   - Beta constants by libm tgamma; superellipse points by pow; a and b by the
 *     printed half-sum/half-difference (step 6);
 *   - the unit normal and the sweep regularity by central differences of the point
 *     (no analytic derivative), the area of a section by the shoelace formula;
 *   - wire inertia by a cyclic Jacobi eigen-solver.
 * Conventions shared with the firmware (they are the model's definition): w with
 * |cos w| or |sin w| < 1e-5 lies on a section axis; a >= b with the axes swapped.
 * Plain C99 + <math.h>, no allocation, small objects (host and M4F).
 */
#ifndef REF_CHANNEL_H
#define REF_CHANNEL_H

#define REF_CH_MAX 8

struct ref_ch_sec {
    double a, b, n;
    double c[3], x[3], z[3]; /* centre, local x axis, normal */
};

struct ref_channel {
    int ns;
    struct ref_ch_sec s[REF_CH_MAX];
    double m[REF_CH_MAX][3];  /* node tangents L'(i) */
    double acc[REF_CH_MAX][3]; /* node second derivatives L''(i) */
    double al[REF_CH_MAX];    /* node angles, unwrapped */
    double y[5][REF_CH_MAX], y2[5][REF_CH_MAX]; /* S, n, JI, JII, J12 and second derivatives */
};

/* Everything at one u. */
struct ref_ch_row {
    double l[3], d1[3], d2[3], tau[3], e1[3], e2[3];
    double s, n, ji, jii, j12, a, b, alpha;
};

/* Rows x (row 0) and z (row 2) of R = T(psi)T(theta)T(phi) (printed = 0) or
 * T(theta)T(phi)T(psi) (printed = 1); radians. */
void ref_channel_euler(double psi, double theta, double phi, int printed, double x[3], double z[3]);

double ref_channel_ks(double n);
double ref_channel_kj(double n);

/* Build the model; returns 0 (no validation: the tests feed valid data). */
int ref_channel_build(struct ref_channel *r, int ns, const struct ref_ch_sec *s);

void ref_channel_row(const struct ref_channel *r, double u, struct ref_ch_row *o);
void ref_channel_point(const struct ref_channel *r, double u, double w, double p[3]);
/* unit normal (away from the guide) and g = (P_u . tau)/|L'| by central differences */
void ref_channel_normal(const struct ref_channel *r, double u, double w, double nrm[3], double *g);
/* area of the section at u sampled as an m-gon (shoelace in the e1, e2 plane) */
double ref_channel_area(const struct ref_channel *r, double u, int m);
/* distance-like residual of p from the section at u: | (|X/a|^n + |Y/b|^n)^(1/n) - 1 |
 * max(a, b) plus the out-of-plane offset, X, Y in the section's own axes */
double ref_channel_off_section(const struct ref_channel *r, double u, const double p[3]);

/* Wire inertia of a section sampled as an m-gon: length, principal moments ascending
 * (Jacobi), unit axis of the largest (sign towards +z). */
void ref_channel_wire(const struct ref_ch_sec *s, int m, double *len, double lam[3], double ax[3]);

/* ---- the far sections (issue 22): an independent overlap measure ----
 * The duct is the union of its section DISKS D(u) (the filled superellipse in the plane
 * through L(u) normal to the guide). Two disks share a point iff a boundary point of one
 * lies in the other (their common points lie on the planes' common line, and the ends of
 * that segment are on a boundary). ref_channel_far_depth measures how deep the boundary
 * points P(u, w) of the sections u = k (N - 1) / REF_CH_FAR (w at REF_CH_FAR_W angles) lie
 * inside a far disk D(u'): u' where P's height over the plane of u' changes sign between two
 * samples (both at least `near` mm of guide arc from u, the shorter way round on a closed
 * guide) is refined by bisection (40 steps), and there the in-plane depth is
 * (1 - rho) min(a, b), rho = (|X/a|^n + |Y/b|^n)^(1/n) in the section's own axes (> 0:
 * inside). Written from the definitions (no firmware code: the firmware bounds 64 pieces by
 * capsules of bounding circles). ref_channel_far_ballgap is the least gap between the
 * bounding circles' balls a max(1, sqrt(2^(1 - 2/n))) (the firmware's documented bound,
 * raster.h and channel.c) of samples at least `near` apart: what a report rests on. */
#define REF_CH_FAR 128
#define REF_CH_FAR_W 48
struct ref_channel_far {
    double s[REF_CH_FAR + 1];    /* guide arc length from u = 0, mm (8 chords a sample) */
    double l[REF_CH_FAR + 1][3]; /* L */
    double t[REF_CH_FAR + 1][3]; /* unit tangent (the plane's normal) */
    double rb[REF_CH_FAR + 1];   /* the bounding ball's radius */
    double len, rbmax, piece, lip; /* total arc; largest ball; longest arc of a 1/64 of the
                                      guide; largest move of L plus ball between samples */
    int closed;                  /* |L(N-1) - L(0)| <= 1e-5 x the centres' extent */
};
void ref_channel_far_init(struct ref_channel_far *f, const struct ref_channel *r);
/* The greatest depth (mm; negative: no boundary point inside a far disk, and -1e30 when no
 * plane is crossed) and where (*ua: the boundary point's u, *ub: the disk's u; guide units). */
double ref_channel_far_depth(const struct ref_channel *r, const struct ref_channel_far *f,
                             double near, double *ua, double *ub);
/* The least |L(u) - L(u')| - rb(u) - rb(u') over the samples at least `near` apart (1e30:
 * none). */
double ref_channel_far_ballgap(const struct ref_channel_far *f, double near);

#endif /* REF_CHANNEL_H */
