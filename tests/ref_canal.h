/* ref_canal.h - independent double-precision reference for the canal surface.
 * SPDX-License-Identifier: MIT
 *
 * Written from the DEFINITIONS in canal.h and MATH-canal §1-§3 only; it calls no
 * firmware code and shares no formula with it beyond the definitions:
 *   - own 2-jets of the four curves (LINE, ARC, ELLIPSE, BEZIER) and of the four
 *     radius laws (CONST, LINEAR, COS, CUBIC), all in double;
 *   - the characteristic circle (centre rho + a T, radius R c / sigma, axis T);
 *   - the surface in the contact frame, m(t, u) = C + (R/q^2)[-p(1 - cos u) t_C
 *     + q sin u n_C + (1 - cos u) k], with m_u and an ANALYTIC m_t (checked against
 *     a central difference by the tests);
 *   - the family-2 curvature lines as orthogonal trajectories of the circles,
 *     u' = -(m_t . m_u)/(m_u . m_u), integrated ADAPTIVELY (Dormand-Prince 5(4)
 *     with local-extrapolation and error control, default tolerance 1e-12 rad).
 * The closed-form Lambda / stereographic solution is deliberately NOT used.
 *
 * Parameter conventions (canal.h): LINE and BEZIER use s = t in [0, 1]; ARC and
 * ELLIPSE use the angle, with t = -angle when a1 < a0 (clockwise), so t0 < t1.
 * The normalised parameter of the LINEAR and CUBIC laws is (t - t0)/(t1 - t0);
 * the COS law uses the true curve angle (ARC/ELLIPSE) or 2 pi s (LINE/BEZIER).
 * Plain C99 + <math.h>; no allocation; every object is small (host and M4F).
 */
#ifndef REF_CANAL_H
#define REF_CANAL_H

enum { REF_LINE = 0, REF_ARC = 1, REF_ELLIPSE = 2, REF_BEZIER = 3 };
enum { REF_R_CONST = 0, REF_R_LINEAR = 1, REF_R_COS = 2, REF_R_CUBIC = 3 };

struct ref_canal {
    int curve, radius;
    double cp[8], rp[4];
    double t0, t1; /* internal parameter interval, t0 < t1 */
    double dir;    /* +1, or -1 for a clockwise ARC/ELLIPSE */
};

struct ref_jet {
    double x, y, dx, dy, ddx, ddy; /* C, C', C'' */
    double r, dr, ddr;             /* R, R', R'' (d/dt) */
};

/* Set up from the raw parameters (same meaning and order as canal_cfg.cp / .rp). */
void ref_canal_set(struct ref_canal *rc, int curve, int radius, const double cp[8],
                   const double rp[4]);

void ref_jet(const struct ref_canal *rc, double t, struct ref_jet *j);

/* Surface point m(t, u) (contact-frame angle u) and unit normal (m - rho)/R. */
void ref_point(const struct ref_canal *rc, double t, double u, double m[3], double n[3]);

/* m, m_t (analytic) and m_u at (t, u). */
void ref_partials(const struct ref_canal *rc, double t, double u, double m[3], double mt[3],
                  double mu[3]);

/* Right-hand side of the orthogonal-trajectory ODE: u' = -(m_t . m_u)/(m_u . m_u). */
double ref_uprime(const struct ref_canal *rc, double t, double u);

/* Characteristic circle at t: centre, radius, unit axis T = rho'/|rho'|. */
void ref_circle(const struct ref_canal *rc, double t, double centre[3], double *radius,
                double axis[3]);

/* One family-2 line, integrated adaptively to any requested t (either direction). */
struct ref_line {
    const struct ref_canal *rc;
    double t, u, f; /* current parameter, angle, and u'(t, u) */
    double h;       /* last accepted step size (magnitude) */
    double tol;     /* local error tolerance (absolute + relative), rad */
    long steps;     /* accepted steps so far */
    long rejects;   /* rejected steps so far */
    int fail;       /* non-zero if the step size underflowed */
};

void ref_line_start(struct ref_line *l, const struct ref_canal *rc, double t0, double u0);

/* Integrate from the current t to exactly t (forward or backward). 0 on success. */
int ref_line_advance(struct ref_line *l, double t);

/* Cubic Hermite interpolation of u between two states (t_a, u_a, f_a), (t_b, u_b, f_b). */
double ref_hermite(double ta, double ua, double fa, double tb, double ub, double fb, double t);

/* Total accepted RK steps of every line since program start (runtime bookkeeping). */
long ref_total_steps(void);

#endif /* REF_CANAL_H */
