/* canal.h - canal surface (envelope of spheres) touching the plane z = 0 along a plane curve C.
 * SPDX-License-Identifier: MIT
 *
 * Seed 000 (Frolov 2022), in the contact frame of docs MATH-canal §2.2, §5.2:
 * the spheres have centres rho(t) = (C(t), R(t)) and radii R(t), so every sphere
 * touches z = 0 at C(t) and C is a curvature line of the envelope. The other
 * curvature lines (family 2) need ONE quadrature shared by all of them:
 *
 *     Lambda(t) = integral_{t0}^{t} R'(tau) kappa_C(tau) dtau      (canal_g is the integrand)
 *
 * and a line with homogeneous label (alpha, b) passes at parameter t through
 *
 *     h = alpha + Lambda(t) b
 *     m = C + 2 R b (-p b t_C + h n_C + b k) / (q^2 b^2 + h^2),   p = R'/|C'|, q^2 = 1 + p^2
 *
 * (t_C unit tangent of C, n_C its LEFT unit normal, k = +z). A line starting on the
 * first circle (t = t0) at contact-frame angle u0 has alpha = q(t0) cos(u0/2),
 * b = sin(u0/2): u0 = 0 is C itself, u0 > 0 lies to the left of C (as travelled),
 * u0 = pi is the top of the circle. Family 1 (the characteristic circles, t = const)
 * at angle u is the label (q cos(u/2), sin(u/2)) at that t. Everything is
 * homogeneous of degree 0 in (h, b); nothing divides by zero (if b = 0 then h != 0).
 *
 * Parameter t: LINE and BEZIER use s in [0, 1]. ARC and ELLIPSE use the angle in
 * radians, travelled from a0 to a1; when a1 < a0 (clockwise) the internal parameter
 * is v = -angle so that t always increases along the travel and "left" is left of
 * travel: canal.t0 < canal.t1 always.
 *
 * Units: lengths mm, angles radians (the wire protocol converts from degrees).
 */
#ifndef CANAL_H
#define CANAL_H

#include "cp_types.h"

enum canal_curve_kind {
    /* cp = x0 y0 x1 y1: C(s) = P0 + s (P1 - P0), s in [0,1] */
    CANAL_LINE = 0,
    /* cp = cx cy r a0 a1: C = c + r (cos a, sin a), a from a0 to a1 */
    CANAL_ARC = 1,
    /* cp = cx cy A B a0 a1: C = c + (A cos a, B sin a) */
    CANAL_ELLIPSE = 2,
    /* cp = x0 y0 x1 y1 x2 y2 x3 y3: cubic Bezier, s in [0,1] */
    CANAL_BEZIER = 3
};

enum canal_radius_kind {
    /* rp = c: R = c */
    CANAL_R_CONST = 0,
    /* rp = r0 r1: R = r0 + (r1 - r0) s, s = the normalized parameter in [0,1] */
    CANAL_R_LINEAR = 1,
    /* rp = b c k: R = b cos(k theta) + c, theta = the curve angle (ARC/ELLIPSE) or
     * 2 pi s (LINE/BEZIER); k dimensionless */
    CANAL_R_COS = 2,
    /* rp = r0 .. r3: R = sum r_i B_i,3(s), Bernstein in the normalized s */
    CANAL_R_CUBIC = 3
};

/* Limits checked by canal_init. */
#define CANAL_COORD_MAX CP_R(1.0e4) /* |coordinate|, |radius| <= 10 m */
#define CANAL_K_MAX CP_R(64.0)      /* |k| of the COS law */
#define CANAL_SPAN_MAX CP_TWO_PI    /* |a1 - a0| <= one full turn */

struct canal_cfg {
    uint8_t curve;  /* enum canal_curve_kind */
    uint8_t radius; /* enum canal_radius_kind */
    cp_real cp[8];  /* curve parameters, mm and radians, as listed in enum canal_curve_kind */
    cp_real rp[4];  /* radius-law parameters, mm (k dimensionless), as in enum canal_radius_kind */
};

/* The validated surface. Read-only after canal_init. */
struct canal {
    uint8_t curve, radius;
    int8_t dir;         /* +1, or -1 for a clockwise ARC/ELLIPSE (t = -angle) */
    cp_real cp[8];      /* copy of the curve parameters */
    cp_real rp[4];      /* copy of the radius parameters */
    cp_real t0, t1;     /* parameter interval, t0 < t1 */
    cp_real rmin, rmax; /* exact min and max of R over [t0, t1], mm */
    cp_real cmin;       /* min |C'(t)| over [t0, t1] (sampled and refined), mm per unit t */
    cp_real inv_span;   /* 1 / (t1 - t0): d(normalized s)/dt */
    cp_real dth;        /* d(theta)/dt of the COS law: dir (ARC/ELLIPSE) or 2 pi (LINE/BEZIER) */
    cp_real kappa_c; /* the constant signed curvature of C when kappa_const (ARC: dir/r, LINE: 0) */
    uint8_t kappa_const; /* 1 for ARC and LINE: then Lambda(t) = kappa_c (R(t) - R(t0)) exactly */
    uint8_t k_int;       /* COS law on ARC/ELLIPSE with integer k in 1..8: cos/sin(k theta) by
                            complex powers of the curve's own (cos, sin)(theta); else 0 */
};

/* The 2-jet of C and R at t: everything the surface needs. */
struct canal_jet {
    cp_real x, y;       /* C(t), mm */
    cp_real dx, dy;     /* C'(t) */
    cp_real ddx, ddy;   /* C''(t) */
    cp_real r, dr, ddr; /* R(t), R'(t), R''(t) */
};

/* Per-t quantities shared by all points at that t (MATH-canal §9 step 4). */
struct canal_frame {
    cp_real x, y;   /* C(t), mm */
    cp_real tx, ty; /* unit tangent t_C (the left normal is (-ty, tx)) */
    cp_real r;      /* R(t), mm */
    cp_real p;      /* R'/|C'| = dR/ds (s = arclength of C) */
    cp_real q2;     /* 1 + p^2 */
    cp_real kappa;  /* signed curvature of C, 1/mm (> 0 turning left) */
    cp_real dpds;   /* dp/ds = P/c^4, 1/mm (needs R'') */
};

/* A surface point with its unit normal (out of the sphere: n = (m - rho)/R). */
struct canal_point {
    struct cp_vec3 m; /* mm */
    struct cp_vec3 n; /* unit */
};

/* Validate cfg and build the surface. Checks, each with its own code:
 *   CP_ERR_INVAL       curve or radius kind out of range, NULL pointers
 *   CP_ERR_NONFINITE   any used parameter NaN/Inf
 *   CP_ERR_RANGE       |coordinate| or |radius| > CANAL_COORD_MAX, |k| > CANAL_K_MAX,
 *                      ARC/ELLIPSE sweep |a1 - a0| > 2 pi, r <= 0 (ARC), A <= 0 or B <= 0
 *   CP_ERR_EMPTY       a0 == a1 (ARC/ELLIPSE)
 *   CP_ERR_DEGENERATE  C'(t) = 0 somewhere (LINE with P0 == P1, BEZIER with a cusp or
 *                      coincident control points): min |C'| <= 1e-5 of the curve's size
 *   CP_ERR_RADIUS      R(t) <= 0 somewhere on [t0, t1] (exact minimum, not sampled)
 *   CP_ERR_SEAM        C is closed and R does not close: R or dR/ds (per arc length of C)
 *                      differs at the seam beyond raster.h's tolerances. C is closed when
 *                      |C(t1) - C(t0)| <= RASTER_SEAM_GAP (1e-5) x its size (ARC: r,
 *                      ELLIPSE: max(A, B), BEZIER: the larger side of the control points'
 *                      box): an ARC or ELLIPSE of 360 degrees, a BEZIER with P3 = P0 (a
 *                      LINE never). raster_seam_check(R(t0), dR/ds(t0), R(t1), dR/ds(t1),
 *                      max(size, rmax)): |jump of R| <= 1e-5 max(size, rmax)(1 + |dR/ds|
 *                      at both ends), |jump of dR/ds| <= 1e-3 (1 + both |dR/ds|). So a COS
 *                      law on a 360 degree ARC or ELLIPSE closes for an integer k only (b
 *                      != 0), a LINEAR law only with r0 = r1, a CUBIC law on a closed
 *                      BEZIER when r0 = r3 and the ends' slopes 3 (r1 - r0)/|C'(0)| and
 *                      3 (r3 - r2)/|C'(1)| agree. A closed C with a tangent corner at the
 *                      seam (a BEZIER with P3 = P0 whose end tangents differ) is the user's
 *                      geometry and is allowed; R must still close there.
 * Order: NONFINITE anywhere first, then the curve's checks (canal_curve_check), then the
 * law's (canal_radius_check), then RADIUS, then SEAM. Returns CP_OK. */
CP_MUST_CHECK int canal_init(struct canal *c, const struct canal_cfg *cfg);

/* The checks of canal_init that need the curve alone (cfg->curve, cp; the law is not
 * read), the same code for the same fault: CP_ERR_INVAL (kind, NULL), NONFINITE, RANGE
 * (|coordinate| > CANAL_COORD_MAX, an angle beyond 4 pi, sweep > 2 pi, r, A or B <= 0),
 * EMPTY (a0 == a1), DEGENERATE. The protocol's CURVE calls it. Returns CP_OK. */
CP_MUST_CHECK int canal_curve_check(const struct canal_cfg *cfg);

/* The checks of canal_init that need the radius law alone (cfg->radius, rp): INVAL,
 * NONFINITE, RANGE (|parameter| > CANAL_COORD_MAX, |k| > CANAL_K_MAX). R > 0 over the
 * interval needs the curve: canal_init. The protocol's RADIUS calls it. Returns CP_OK. */
CP_MUST_CHECK int canal_radius_check(const struct canal_cfg *cfg);

/* The jet of C and R at t (any t; meaningful in [t0, t1]). Cannot fail. */
void canal_jet(const struct canal *restrict c, cp_real t, struct canal_jet *restrict j);

/* The jet without second derivatives (ddx, ddy, ddr are unspecified: some kinds set
 * them anyway): enough for canal_frame_pt and a point. */
void canal_jet1(const struct canal *restrict c, cp_real t, struct canal_jet *restrict j);

/* The part of the frame a point needs (x, y, tx, ty, r, p, q2); kappa and dpds are left
 * unset (they are for canal_regularity). Same values as canal_frame for those fields.
 * Returns 1/|C'|. */
cp_real canal_frame_pt(const struct canal_jet *restrict j, struct canal_frame *restrict f);

/* Per-t frame from a jet. Requires |C'| > 0 (guaranteed on [t0, t1] by canal_init). */
void canal_frame(const struct canal_jet *restrict j, struct canal_frame *restrict f);

/* The integrand of Lambda at t: R'(t) kappa_C(t) (7 flops, 1 sqrt, 1 div). */
cp_real canal_g(const struct canal_jet *j);

/* Surface point (and normal) of the line with homogeneous label (h, b) at this t:
 * h = alpha + Lambda(t) b. rad_off shrinks the spheres (ball-end tool centre:
 * rad_off = r_tool gives the tool centre on the offset surface, m - r_tool n);
 * use 0 for the surface itself. (h, b) must not both be 0. */
void canal_point(const struct canal_frame *f, cp_real h, cp_real b, cp_real rad_off,
                 struct canal_point *out);

/* The body of canal_point, for a caller's hot loop (canal_path_next inlines it; the
 * two give the same bits). Stereographic form (MATH-canal §5.2): 11 multiplications,
 * 1 division, no square root. */
static CP_ALWAYS_INLINE void canal_point_inline(const struct canal_frame *f, cp_real h, cp_real b,
                                                cp_real rad_off, struct canal_point *out)
{
    cp_real rr = f->r - rad_off;
    cp_real pb = f->p * b;
    cp_real w = CP_R(2.0) * b / (f->q2 * b * b + h * h);
    cp_real nx = w * (-pb * f->tx - h * f->ty);
    cp_real ny = w * (-pb * f->ty + h * f->tx);
    cp_real wb = w * b;
    out->n.x = nx;
    out->n.y = ny;
    out->n.z = wb - CP_R(1.0);
    out->m.x = f->x + rr * nx;
    out->m.y = f->y + rr * ny;
    out->m.z = rad_off + rr * wb;
}

/* Regularity of the (offset) surface at label (h, b): D b^2 with
 * D = 1 + p^2 + lambda^2 - 2 (R - rad_off)(kappa lambda + dp/ds), lambda = h/b.
 * > 0 regular; <= 0 on or beyond a cuspidal edge (MATH-canal §5.2). */
cp_real canal_regularity(const struct canal_frame *f, cp_real h, cp_real b, cp_real rad_off);

/* The cusp test of the models that stream canal points (canal_path.c, drc.c): 1 if label
 * (h, b) at frame f is regular with margin, canal_regularity > CANAL_CUSP_EPS (q^2 b^2 + h^2),
 * on the surface and, with a tool (tool_r > 0), on the tool centre's offset surface (rad_off
 * = tool_r); 0 on or near a cuspidal edge (or a NaN). */
#define CANAL_CUSP_EPS CP_R(1e-4)
int canal_regular(const struct canal_frame *f, cp_real h, cp_real b, cp_real tool_r);

/* Homogeneous label of the line that starts at contact-frame angle u0 (radians,
 * |u0| <= 2 pi) on the circle of frame f0 (the first circle): alpha = q0 cos(u0/2),
 * b = sin(u0/2). */
void canal_label(const struct canal_frame *f0, cp_real u0, cp_real *alpha, cp_real *b);

/* Contact-frame angle u in (-pi, pi] of label (h, b) at this t: 2 atan2(q b, h)
 * folded into (-pi, pi]. */
cp_real canal_angle(const struct canal_frame *f, cp_real h, cp_real b);

/* Characteristic circle at this t: centre rho + a T (a = -R R'/sigma), radius
 * r = R/q, and unit axis T = rho'/|rho'|. */
void canal_circle(const struct canal_jet *j, struct cp_vec3 *centre, cp_real *radius,
                  struct cp_vec3 *axis);

#endif /* CANAL_H */
