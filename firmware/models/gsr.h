/* gsr.h - generalized surfaces of revolution (Grigoriev, seed 003): an ellipse swept along a
 * space curve in its normal plane, with exact rational quarters and four frames.
 * SPDX-License-Identifier: MIT
 *
 * Geometry (../shared/docs/MATH-seeds-2-3-4.md part C, which overrides the paper):
 *
 *     t = f_t(u),  G(u, theta) = C(t) + f_N(u) cos(theta) N(t) + f_B(u) sin(theta) B(t)
 *
 * u in [0, 1] runs along the surface, theta is the ECCENTRIC angle of the section
 * (theta = 0 on +N, theta = 90 deg on +B), (N, B, T) is right-handed: N x B = T.
 *
 * Scalar family (every coordinate of C, and f_N, f_B, f_t): 7 numbers
 *     f(x) = a0 + a1 x + a2 x^2 + a3 x^3 + b sin(w x) + c cos(w x)
 * (w in radians per unit x; the protocol takes degrees). Jets are exact to the 3rd
 * derivative. The sinusoid costs one cp_sincos per evaluation when b or c != 0; a
 * function with b = c = 0 (e.g. every Bezier coordinate) costs no trigonometry.
 *
 * Centre C(t), t in [0, 1]: GSR_CENTRE_POLY (c[axis] = the 7 numbers of x, y, z) or
 * GSR_CENTRE_BEZIER (c[axis][i] = coordinate `axis` of control point i, i = 0..3).
 *
 * Frames (C.1-C.3):
 *   GSR_FRAME_FIXED   B = (0, 1, 0), N = B x T = (T_z, 0, -T_x) (corrected eq. 7); the centre
 *                     must have T_y = 0 identically (y constant; T_y must be exactly 0 at
 *                     every init sample and every walked point)
 *   GSR_FRAME_FRENET  B = unit(C' x C''), N = B x T (eq. 9; computed as the projection of
 *                     C'' on the normal plane, gsr.c)
 *   GSR_FRAME_N0      B = unit(T x N0), N = B x T = the projection of N0 on the normal
 *                     plane (eq. 10; N0 = ref)
 *   GSR_FRAME_RMF     rotation-minimizing frame (not in the paper): N(t_min) = the projection
 *                     of ref on the normal plane, then N' = -(N . T') T. Stored as the angle
 *                     phi(t) of N in the closed-form projection frame (U, V) of ref (U =
 *                     unit(ref - (ref.T) T), V = T x U; so ref must never be parallel to a
 *                     tangent: CP_ERR_FRAME_REF), where the RMF equation is the scalar
 *                     dphi/dt = (ref.T)(C''.V) / (|C'| |ref - (ref.T) T|): made at init by
 *                     composite Simpson quadrature, GSR_RMF_N x GSR_RMF_SUB steps over
 *                     [f_t(0), f_t(1)], kept as (phi, h dphi/dt) at GSR_RMF_N + 1 nodes. A
 *                     section interpolates phi by cubic Hermite and takes one cp_sincos (no
 *                     state: any seek(k) is exact). Init verifies the interpolation at every
 *                     interval midpoint against the quadrature.
 *
 * Sections (C.2): GSR_SECTION_TRIG (cos/sin of theta by cp_sincos) or GSR_SECTION_RATIONAL
 * (the exact rational quadratic quarter, weight sqrt(2)/2: no trigonometry). In the rational
 * form a section position is psi = q + v in [-2, 2]: quarter q = floor(psi) (mod 4), v =
 * psi - q in [0, 1]; gsr_psi gives psi of an eccentric angle by the closed form
 * v(theta) = (1 + tan((theta' - pi/4)/2) / tan(pi/8)) / 2, theta' = theta - q pi/2.
 *
 * Raster (struct raster_cfg, the same request as the canal; u0, u1 = v0, v1 in radians,
 * |v| <= pi):
 *   RASTER_LINES    n longitudinal lines at EVEN eccentric angles theta_j = v0 + j (v1 -
 *                     v0)/(n - 1) (rational form: psi(theta_j), one tangent per line), each
 *                     with steps + 1 points at u_i = i / steps; zigzag (odd lines run u = 1
 *                     -> 0); consecutive lines are linked by `link` points along the ring at
 *                     the line end (uniform in the section parameter).
 *   RASTER_CIRCLES  n rings (sections) at u_c = c (link + 1) / gsteps, gsteps = (n - 1)
 *                     (link + 1) (n = 1: u = 0), each with steps + 1 points from v0 to v1
 *                     (zigzag), uniform in the section parameter: the eccentric angle
 *                     (TRIG) or psi (RATIONAL: no trigonometry per point; the angle step
 *                     then varies by the quarter's speed ratio 1.17, C.2). Consecutive rings
 *                     are linked by `link` points along the line at v1 (even c) / v0 (odd c).
 *   count = n (steps + 1) + (n - 1) link. raster_pt: p the emitted position, n the unit
 *   OUTWARD surface normal (G_theta x G_u, pointing away from C), t = u (surface parameter),
 *   line = line/ring index (-1 on links), index = point index in it (links: 1..link).
 *   Tool (TOOL BALL r): the tool is OUTSIDE the surface (pipes, handles, nozzles):
 *   RASTER_OUT_CENTRE streams G + r n, RASTER_OUT_TIP that centre - r z. Where f_t' = 0
 *   (G2 of C.4 at u = 0, 1) the section plane is tangent to the surface and n = +-T; if its
 *   sign changes along the ring there the tool centre jumps and init fails (CP_ERR_TOL).
 * Step counts: given (steps, link), or derived from tol: rounded up, then the whole stream
 * is walked at twice its resolution (every point and every segment midpoint) and the
 * measured midpoint sagitta must be <= 0.9 tol (lines/rings and links separately, up to
 * GSR_WALK_ROUNDS refinements). The same walk checks that the sweep does not fold at any
 * point or midpoint, for the tool centre too.
 *
 * Units: mm, radians, u and t dimensionless. Everything is validated by gsr_init /
 * gsr_path_init; the step functions cannot fail afterwards.
 */
#ifndef GSR_H
#define GSR_H

#include "canal_path.h"

enum gsr_centre_kind {
    GSR_CENTRE_POLY = 0,  /* c[axis][0..6] = a0 a1 a2 a3 b c w of x(t), y(t), z(t) */
    GSR_CENTRE_BEZIER = 1 /* c[axis][i] = coordinate of control point i (i < 4), rest unused */
};

enum gsr_frame_kind {
    GSR_FRAME_FIXED = 0,  /* B = +y (centre curve in a plane y = const) */
    GSR_FRAME_FRENET = 1, /* Frenet */
    GSR_FRAME_N0 = 2,     /* N = projection of ref on the normal plane */
    GSR_FRAME_RMF = 3     /* rotation-minimizing, N(t_min) = projection of ref */
};

enum gsr_section_kind {
    GSR_SECTION_RATIONAL = 0, /* exact rational quarters (default: no trig per point) */
    GSR_SECTION_TRIG = 1      /* cos/sin of the eccentric angle */
};

/* Scalar functions: numbers per function, and the index of each number. */
#define GSR_FN 7
#define GSR_B 4 /* b of b sin(w x) */
#define GSR_C 5 /* c of c cos(w x) */
#define GSR_W 6 /* w, radians per unit x */

/* Limits checked by gsr_init. */
#define GSR_COEF_MAX CP_R(1.0e4)        /* |a_i|, |b|, |c|, |Bezier coordinate|, |ref|, mm */
#define GSR_W_MAX CP_R(402.1238596594935) /* |w| <= 64 turns per unit x (23040 deg) */
#define GSR_SAMPLES 256u                /* init scan: u = k / GSR_SAMPLES, k = 0..256 */
#define GSR_RMF_N 16u                   /* RMF table intervals over [f_t(0), f_t(1)] */
#define GSR_RMF_SUB 32u                 /* quadrature steps per table interval (even) */
#define GSR_RMF_TOL CP_R(2.0e-4)        /* max RMF interpolation error x max radius, mm */
#define GSR_WALK_ROUNDS 4               /* step-count refinements from the measured sagitta */
/* Degeneracy thresholds (C.3: 1e-9). The float build cannot resolve 1e-9: C' x C'' of a
 * straight piece is ~1e-7 relative there, so float uses 1e-5 (documented difference). */
#if CP_REAL_DOUBLE
#define GSR_EPS CP_R(1.0e-9)
#else
#define GSR_EPS CP_R(1.0e-5)
#endif

/* The geometry (plain data; filled by the protocol commands, job_gsr.c). */
struct gsr_cfg {
    uint8_t centre;           /* enum gsr_centre_kind */
    uint8_t frame;            /* enum gsr_frame_kind */
    uint8_t section;          /* enum gsr_section_kind */
    uint8_t set;              /* protocol bookkeeping (job_gsr.c), ignored by gsr_init */
    cp_real c[3][GSR_FN];     /* centre: x, y, z (see enum gsr_centre_kind), mm; w rad */
    cp_real r[3][GSR_FN];     /* f_N(u), f_B(u) (mm), f_t(u) (dimensionless); w rad */
    struct cp_vec3 ref;       /* N0 (FRAME_N0) or the RMF start reference, any length > 0 */
};

/* The validated model. Keeps a pointer to the cfg, which must outlive it unchanged. */
struct gsr {
    const struct gsr_cfg *cfg; /* the geometry (caller-owned, read by every evaluation) */
    uint8_t frame;             /* copy of cfg->frame: enum gsr_frame_kind */
    uint8_t section;           /* copy of cfg->section: enum gsr_section_kind (RATIONAL:
                                  section parameter psi in [-2, 2]; TRIG: eccentric angle,
                                  rad) */
    cp_real t0, t1;           /* f_t(0), f_t(1): the t range of the centre, t0 < t1 */
    cp_real d1;               /* bound of |C'| from the coefficients (scale of the checks) */
    cp_real cp[3 * GSR_FN];   /* the centre's x, y, z (GSR_FN numbers each) in the power
                                 basis: the scalar family (a Bezier converted, b = c = 0) */
    cp_real rmax;             /* max(f_N, f_B) over the init samples, mm */
    cp_real ih;               /* RMF: GSR_RMF_N / (t1 - t0) */
    cp_real rmf[GSR_RMF_N + 1u][2]; /* RMF: phi (rad), h dphi/dt at node k (phi: angle of N in
                                       the projection frame of ref) */
};

/* Everything at one u that the points of its section need. */
struct gsr_sec {
    struct cp_vec3 c, t, n, b; /* C(t) (mm); unit tangent T, section axes N and B */
    cp_real fn, fb;            /* f_N(u), f_B(u), mm */
    cp_real dfn, dfb;          /* d f_N / du, d f_B / du, mm */
    cp_real ts;                /* f_t'(u) |C'(t)|: centre arc length per unit u, mm */
    cp_real tw;                /* ts * frame twist (N' . B per arc length): rad per unit u */
    cp_real k1, k2;            /* curvature vector of C along N and B, 1/mm */
    cp_real ft;                /* t = f_t(u) */
};

/* Validate the geometry and build the frame (RMF table). Errors:
 *   CP_ERR_INVAL       g or cfg NULL, a kind out of range
 *   CP_ERR_NONFINITE   a number is NaN or Inf
 *   CP_ERR_RANGE       |number| > GSR_COEF_MAX, |w| > GSR_W_MAX, ref = 0 (N0, RMF)
 *   CP_ERR_OFF_PLANE   FIXED frame with y(t) not constant (T_y != 0 at a sample)
 *   CP_ERR_FT_RANGE    f_t(u) outside [0, 1] or f_t' < 0 at a sample (decreasing), or
 *                      f_t(1) <= f_t(0) (f_t' = 0 at isolated u is allowed: G2 of C.4)
 *   CP_ERR_SECTION     f_N <= 0 or f_B <= 0 at a sample
 *   CP_ERR_DEGENERATE  |C'(t)| <= GSR_EPS * (bound of |C'|) at a sample
 *   CP_ERR_FRENET      FRENET with |C' x C''| <= GSR_EPS |C'||C''|, or B flipping between
 *                      samples (an inflection between them)
 *   CP_ERR_FRAME_REF   N0 with |T x N0| <= GSR_EPS |N0| (or flipping between samples); RMF
 *                      with T parallel to ref at t_min, or no axis of the 7 at >= 14 deg
 *                      from every tangent
 *   CP_ERR_TOL         RMF table interpolation error x max radius > GSR_RMF_TOL
 *   CP_ERR_FOLD        the sweep folds somewhere on a full section: 1 - k.(G - C) <= 0,
 *                      i.e. (k1 f_N)^2 + (k2 f_B)^2 >= 1 at a sample
 *   CP_ERR_NUMERIC     a non-finite value appeared
 *   CP_ERR_SEAM        the centre is closed and f_N or f_B does not close (checked last).
 *                      Closed: |C(f_t(1)) - C(f_t(0))| <= RASTER_SEAM_GAP (1e-5) x d1 (the
 *                      bound of |C'|, mm, at least the centre's length). Then f_N and f_B,
 *                      and their slopes per arc length of the centre (f' / ts), go to
 *                      raster_seam_check (raster.h: value within 1e-5 max(d1, rmax) (1 + the
 *                      slopes), slope within 1e-4 (1 + the slopes)). Where ts = 0 at an end
 *                      (f_t' = 0) only the values are compared. A corner of the centre at the
 *                      seam is allowed. Not checked: the FRAME at the seam (an RMF need not
 *                      return to its start, so an elliptic section f_N != f_B may turn there;
 *                      FIXED, FRENET and N0 follow the tangent and close with it).
 * Samples: u = k / GSR_SAMPLES, k = 0..GSR_SAMPLES (the raster walk of gsr_path_init
 * checks every streamed point and midpoint again). */
CP_MUST_CHECK int gsr_init(struct gsr *g, const struct gsr_cfg *cfg);

/* The checks of gsr_init that need one section function alone (fn: GSR_FN numbers, w in
 * radians; i = 0, 1, 2: f_N, f_B, f_t), the same code for the same fault: CP_ERR_INVAL,
 * NONFINITE, RANGE (|number| > GSR_COEF_MAX, |w| > GSR_W_MAX), and at gsr_init's samples
 * u = k / GSR_SAMPLES: f_N, f_B <= 0 CP_ERR_SECTION; f_t outside [0, 1], f_t' < 0 or
 * f_t(1) <= f_t(0) CP_ERR_FT_RANGE. The protocol's RADII calls it. Returns CP_OK. */
CP_MUST_CHECK int gsr_fn_check(const cp_real *fn, unsigned i);

/* The section at u in [0, 1] (after a successful gsr_init). */
void gsr_section(const struct gsr *g, cp_real u, struct gsr_sec *s);

/* Surface point p (mm) and unit outward normal n of section s at unit-circle
 * coordinates (cx, cy) = (cos theta, sin theta). */
void gsr_point(const struct gsr_sec *s, cp_real cx, cp_real cy, struct cp_vec3 *p,
               struct cp_vec3 *n);

/* Rational quarter: unit-circle coordinates of section position psi in [-2, 2] (see
 * top). Exact conic points: (cx^2 + cy^2 - 1) is a few ulp; no trigonometry. */
void gsr_unit_rational(cp_real psi, cp_real *cx, cp_real *cy);

/* psi of eccentric angle theta in [-pi, pi] (closed form v(theta), one cp_sincos). */
cp_real gsr_psi(cp_real theta);

/* ---- even arc-length spacing on an elliptic section (C.2 "Speed"; library only: the
 * raster of gsr_path_* does not use it, the streamed points are uniform in theta / psi) ----
 *
 * Ellipse E(theta) = (a cos theta, b sin theta), a = f_N, b = f_B (mm), theta the eccentric
 * angle of the top comment. Speed |E'(theta)| = sqrt(a^2 sin^2 theta + b^2 cos^2 theta)
 * (mm/rad) is even about theta = 0 and theta = pi/2, so one quarter describes the whole
 * ellipse: the table holds the arc length s(theta_k) from theta = 0 at the GSR_ARCLEN_N + 1
 * nodes theta_k = k (pi/2) / GSR_ARCLEN_N of [0, pi/2] (each interval by 4-point
 * Gauss-Legendre, summed with Kahan compensation); the quarter length L_q = cum[N], the
 * perimeter P = 4 L_q (exact factor).
 *
 * gsr_arclen_angle(t, f) returns theta with s(theta) = f P (f in [-1, 1]; theta in
 * [-2 pi, 2 pi], odd in f, s measured from theta = 0 towards +B for f > 0): the quarter
 * and the position in it follow from 4|f| (exactly), odd quarters by the mirror
 * s(pi/2 + x) = 2 L_q - s(pi/2 - x); inside the quarter a fixed 6-step bisection of the
 * table gives the node interval [theta_k, theta_k+1], linear interpolation of s the start,
 * then GSR_ARCLEN_NEWTON Newton steps theta -= (s(theta) - target) / |E'(theta)| with
 * s(theta) = cum[j] + (4-point Gauss-Legendre from the nearer node theta_j to theta), each
 * step clamped to the interval (it brackets the root). Cost per call: GSR_ARCLEN_NEWTON x
 * 5 cp_sincos + 5 sqrt (M4F float, 2 steps: 960 instructions, `make bench` row
 * gsr_arclen_angle; gsr_arclen_init 20 928). gsr_arclen_frac is the
 * forward map (one partial quadrature, no iteration): f of theta.
 *
 * Error analysis (errors as |s(theta(f)) - f P| / P; measured by tests/test_gsr.c
 * gsr_arclen against adaptive Simpson and the AGM perimeter, f = j/40, sections 1.7 x 0.95
 * (the G1 section of C.2), 0.95 x 1.7, 1 x 1, 4 x 1, 1 x 16).
 * (1) Quadrature: the speed is analytic except at the branch points theta = m pi +-
 * i atanh(r) (a > b; pi/2 + m pi +- i atanh(r) when b > a), r = min(a, b) / max(a, b).
 * 4-point Gauss-Legendre on a panel of h = pi/128 errs like rho^-8, rho the Bernstein
 * ellipse of the panel through the branch point: at r = 0.56 (atanh 0.63 = 26 h) rho ~ 100,
 * far below double rounding; at the limit r = 1/GSR_ARCLEN_RATIO (atanh 0.0626 = 2.6 h)
 * rho ~ 10 on the panel next to the branch point. Measured (double): 7e-16 at 1.7 x 0.95,
 * 2e-16 at 4 x 1, 2.4e-14 at 1 x 16 (that is the quadrature floor: 4 Newton steps give the
 * same). The Newton partial panels span <= h/2 (rho larger still).
 * (2) Newton: the linear start errs by O(h^2 max|E''| / |E'|) (worst at r = 1/16), the
 * steps converge quadratically and are clamped to the bracketing node interval. Measured
 * (double, 2001 f): 1 / 2 / 3 steps give 9e-11 / 1.4e-15 / 2.7e-15 at 1.7 x 0.95 and
 * 2.4e-8 / 1.2e-13 / 2.4e-14 at 1 x 16; in float 1 step already reaches the rounding
 * level (1.5e-7 at 16 x 1). Hence GSR_ARCLEN_NEWTON = 3 (double), 2 (float: one spare).
 * (3) Rounding (float): the Kahan sum keeps cum[] to ~1 ulp of L_q; the result is
 * q pi/2 +- phi with pi/2 rounded, so theta carries ~1-2 ulp of its magnitude (up to
 * 5e-7 rad near 2 pi) and s(theta) that times |E'| <= max(a, b). Measured: <= 1.1e-7 of the
 * perimeter over the five sections (1.1e-7 at 1.7 x 0.95); gsr_arclen_frac round trip
 * <= 7e-8 (float), <= 8e-16 (double).
 * The double build uses libm sin/cos; the float build only + - * / sqrt and cp_sincos. */
#define GSR_ARCLEN_N 64u           /* table intervals over [0, pi/2] (a power of 2) */
#if CP_REAL_DOUBLE
#define GSR_ARCLEN_NEWTON 3u       /* Newton steps per gsr_arclen_angle (see (2)) */
#else
#define GSR_ARCLEN_NEWTON 2u
#endif
#define GSR_ARCLEN_RATIO CP_R(16.0) /* max(f_N, f_B) / min(f_N, f_B) limit */

/* Caller-owned table of one section (float: 272 B; double: 544 B). Read-only after init;
 * lq (mm) may be read: the perimeter is 4 lq. */
struct gsr_arclen {
    cp_real aa, bb;                   /* f_N^2, f_B^2, mm^2 */
    cp_real lq;                       /* quarter arc length L_q, mm */
    cp_real cum[GSR_ARCLEN_N + 1u];   /* s(theta_k), theta_k = k pi / (2 N), mm */
};

/* Build the table of the ellipse with semi-axes f_n (along N, theta = 0) and f_b (mm).
 * Errors (t then unusable):
 *   CP_ERR_INVAL      t NULL
 *   CP_ERR_NONFINITE  f_n or f_b NaN or Inf
 *   CP_ERR_SECTION    f_n <= 0 or f_b <= 0
 *   CP_ERR_RANGE      f_n or f_b > GSR_COEF_MAX, or max/min > GSR_ARCLEN_RATIO
 * Cost: GSR_ARCLEN_N x 4 cp_sincos + sqrt (one-off). */
CP_MUST_CHECK int gsr_arclen_init(struct gsr_arclen *t, cp_real f_n, cp_real f_b);

/* Eccentric angle theta (rad) whose arc length from theta = 0 is f x perimeter (signed:
 * positive towards +B). f in [-1, 1] (clamped; NaN gives NaN); result in [-2 pi, 2 pi],
 * monotone in f; f = +-1/4, +-1/2, +-3/4, +-1 give the quarter angles (to rounding).
 * Even spacing of n points on [theta_a, theta_b]: f_j = fa + j (fb - fa) / (n - 1) with
 * fa, fb from gsr_arclen_frac. Cannot fail (t from a successful gsr_arclen_init). */
cp_real gsr_arclen_angle(const struct gsr_arclen *t, cp_real f);

/* The inverse: arc length from theta = 0 to theta, as a signed fraction of the perimeter
 * (theta in [-2 pi, 2 pi], clamped; NaN gives NaN; result in [-1, 1]). */
cp_real gsr_arclen_frac(const struct gsr_arclen *t, cp_real theta);

/* ---- the toolpath iterator (path.h) ---- */
struct gsr_path {
    struct raster_head head; /* mode, n, steps, link, count, k (raster.h) */
    /* the output */
    uint8_t output;          /* enum raster_output */
    cp_real tool_r;          /* mm */
    /* the raster's coordinates */
    cp_real s0, s1;          /* ends of the running coordinate: LINES u = 0, 1; CIRCLES the
                                section parameter (theta or psi) of v0 and v1 */
    cp_real v0, dv;          /* LINES: theta_j = v0 + j dv, radians */
    /* the model */
    struct gsr g;
    /* caches of the stream */
    cp_real su;              /* u of the cached section (-1: none) */
    struct gsr_sec sec;      /* the cached section */
    cp_real cs, cc[2];       /* sig of the cached unit-circle point (8: none), the point */
};

/* Validate geom (gsr_init) and the raster, derive and verify the step counts, walk the
 * whole stream for folds. Errors: every gsr_init code (checked first), then the raster's
 * (raster_check, raster.h: INVAL, NONFINITE, RANGE, TOO_MANY, TOOL in that order, then
 * tool_r > GSR_COEF_MAX), then the walks':
 *   CP_ERR_INVAL     rc NULL, mode/output out of range, tool radius with OUT_SURFACE
 *   CP_ERR_NONFINITE u0, u1, tol or tool_r NaN/Inf
 *   CP_ERR_RANGE     |v| > pi, v0 == v1 with n > 1, n == 0, tol outside [1e-5, 10] mm,
 *                    steps == 0 with tol == 0, link > CP_MAX_LINK, tool_r > GSR_COEF_MAX
 *   CP_ERR_TOO_MANY  n > CP_MAX_LINES, steps > CP_MAX_STEPS
 *   CP_ERR_TOOL      tool_r < 0
 *   CP_ERR_TOL       tol not met within CP_MAX_STEPS / CP_MAX_LINK / GSR_WALK_ROUNDS
 *   CP_ERR_FOLD      a streamed point or midpoint (or its tool centre) where the sweep folds,
 *                    or whose section folds somewhere (as gsr_init, at every walked u)
 *   CP_ERR_NUMERIC   a non-finite point
 *   CP_ERR_OVERLAP   (last) parts of the pipe far apart along its centre meet, with the tool
 *                    outside: raster_overlap_check (raster.h) on the balls (C, max(f_N, f_B))
 *                    grown by 2 tool_r; it may refuse a valid pipe with flat sections or
 *                    parts within about 1/64 of the centre of touching
 * Returns CP_OK; then gsr_path_next yields exactly gsr_path_count() points. */
CP_MUST_CHECK int gsr_path_init(struct gsr_path *it, const struct gsr_cfg *geom,
                                const struct raster_cfg *raster);

/* Total points of the path. */
uint32_t gsr_path_count(const struct gsr_path *it);

/* Next point: CP_OK, or CP_ERR_DONE after the last (any other code: a check of the init
 * walk failed, which is impossible after it since every point is the same computation;
 * kept as a guard, the position does not advance). */
int gsr_path_next(struct gsr_path *it, struct raster_pt *pt);

/* Restart at point k (0 <= k <= count; CP_ERR_RANGE otherwise): the next gsr_path_next
 * yields bit for bit what it yielded at k (every point is a function of k alone; the
 * caches are keyed and refilled by the same code). */
CP_MUST_CHECK int gsr_path_seek(struct gsr_path *it, uint32_t k);

#endif /* GSR_H */
