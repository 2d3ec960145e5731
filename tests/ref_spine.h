/* ref_spine.h - independent double-precision reference of the SPINE canal surface (issue 18,
 * docs/MATH-spine.md): spheres of radius R(u) centred on a 3D spine c(u), their envelope, and
 * its curvature lines. Used by tests/test_ref_spine.c (and meant for a host_sim judge).
 * SPDX-License-Identifier: MIT
 *
 * Written from the DEFINITIONS of MATH-spine sections 1-4 only; it calls no firmware code and
 * shares nothing with the firmware's fixed-step schemes (MATH-spine section 9):
 *   - own jets (c, c_u, c_uu) of the four spines and a caller-supplied one, and (R, R_u,
 *     R_uu) of the canal's four radius laws, all in closed form;
 *   - the rotation-minimizing frame by ADAPTIVE integration of its ODE,
 *     dN1/du = -(N1 . dT/du) T (never double reflection);
 *   - each family-2 curvature line by the SAME adaptive integration of
 *     dtheta/du = (a/b)(k2 cos theta - k1 sin theta) |c_u|, carried together with the frame
 *     (never the 2x2 / Moebius transport);
 *   - points m = c + R n, n = -a T + b (cos theta N1 + sin theta N2), a = dR/ds, b = sqrt(1-a^2).
 * The integrator is Dormand-Prince 5(4) with local extrapolation on the state (N1, theta):
 * per accepted step the local error estimate is <= tol (1 + max|y|) in the max norm (tol =
 * 1e-12 by default: a unit vector and an angle in radians). The global error grows with the
 * number of steps (a few hundred per spine here), so positions are good to ~1e-10 R: on the
 * paper example the reduction test agrees with ref_canal.c (also 1e-12) to ~1e-9 mm.
 *
 * Parameter and frame conventions (every length in mm, every angle in radians):
 *   - u in [0, 1] is the normalized spine parameter; s (arc length) is never needed.
 *   - N1(0) = the unit projection of the start vector onto the plane normal to T(0): the
 *     given vector ref[] when it is not NULL and not zero, else the principal normal
 *     c_uu - (c_uu . T) T at u = 0 (the spine must bend at its start: that projection must
 *     exceed 1e-9 |c_u|^2, else REF_SPINE_EREF). A straight spine (LINE) needs ref[].
 *     N2 = T x N1 (right-handed); theta is measured from N1 towards N2.
 *   - A family-2 line is labelled by theta0, its angle on the first circle (u = 0).
 *   - n is the unit normal pointing AWAY from the spine (out of the sphere). An offset off
 *     gives the point c + (R + off) n: off = +r is the ball-end centre of an OUTSIDE tool
 *     (R + r), off = -r of an INSIDE tool (fillet, bore: R - r).
 * Plain C99 + <math.h>; no allocation; no recursion.
 */
#ifndef REF_SPINE_H
#define REF_SPINE_H

enum ref_spine_kind {
    /* sp = x0 y0 z0 x1 y1 z1: c(u) = P0 + u (P1 - P0) */
    REF_SPINE_LINE = 0,
    /* sp = cx cy cz nx ny nz r dx dy dz span: the circle of radius r > 0 about the centre C
     * in the plane normal to n (any length > 0), starting in the direction of d projected
     * onto that plane, turning by span radians (0 < |span| <= 2 pi; > 0 counter-clockwise
     * about n): c(u) = C + r (cos(span u) e1 + sin(span u) e2), e1 = unit(d - (d.n^)n^),
     * e2 = n^ x e1 */
    REF_SPINE_ARC = 1,
    /* sp = px py pz ax ay az r pitch turns dx dy dz: the helix about the axis through P with
     * direction a (any length > 0), radius r > 0, pitch mm per turn (> 0 right-handed about
     * a, < 0 left-handed, 0 a circle), turns > 0, starting in the direction of d projected
     * onto the plane normal to a: c(u) = P + r (cos p e1 + sin p e2) + pitch p/(2 pi) a^,
     * p = 2 pi turns u */
    REF_SPINE_HELIX = 2,
    /* sp = the four control points x0 y0 z0 .. x3 y3 z3: the cubic Bezier curve in u */
    REF_SPINE_BEZIER = 3,
    /* the caller's jet (ref_spine_init_user): it supplies c, c_u, c_uu AND R, R_u, R_uu */
    REF_SPINE_USER = 4
};

/* The canal's radius laws (firmware/models/canal.h), in the normalized spine parameter u. */
enum ref_spine_law {
    REF_SPINE_R_CONST = 0,  /* rp = c: R = c */
    REF_SPINE_R_LINEAR = 1, /* rp = r0 r1: R = r0 + (r1 - r0) u */
    REF_SPINE_R_COS = 2,    /* rp = b c k: R = b cos(2 pi k u) + c (canal: theta = 2 pi s) */
    REF_SPINE_R_CUBIC = 3   /* rp = r0 .. r3: R = sum r_i B_i,3(u), Bernstein */
};

/* Results of ref_spine_init (0 or one of these). */
enum ref_spine_err {
    REF_SPINE_OK = 0,
    REF_SPINE_EKIND = -1,  /* spine or law kind out of range, NULL pointer */
    REF_SPINE_ENAN = -2,   /* a parameter is not finite */
    REF_SPINE_EDEGEN = -3, /* |c_u| <= 1e-9 (1 + |c|) at one of 257 samples (LINE with
                              P0 = P1, Bezier cusp); ARC/HELIX: r <= 0, a zero normal or
                              axis, a start direction along it; ARC: span 0 or |span| >
                              2 pi; HELIX: turns <= 0 */
    REF_SPINE_ESLOPE = -4, /* R <= 0 or |a| = |R_u|/|c_u| >= 1 at one of 257 samples */
    REF_SPINE_EREF = -5    /* the start vector (given or principal normal) has a projection
                              onto the normal plane shorter than 1e-9 of its length (given)
                              or than 1e-9 |c_u|^2 (principal normal) */
};

/* The 2-jet of the spine and the radius law at u (d/du). */
struct ref_spine_jet {
    double c[3], cu[3], cuu[3]; /* c(u) mm, dc/du, d2c/du2 (mm per unit u) */
    double r, ru, ruu;          /* R(u) mm, dR/du, d2R/du2 */
};

/* REF_SPINE_USER: fills the whole jet at u (any u in [0, 1]); ctx is the caller's. */
typedef void (*ref_spine_user_fn)(const void *ctx, double u, struct ref_spine_jet *j);

struct ref_spine {
    int spine;            /* enum ref_spine_kind */
    int law;              /* enum ref_spine_law (unused for REF_SPINE_USER) */
    double sp[12];        /* spine parameters, as listed in enum ref_spine_kind */
    double rp[4];         /* law parameters, as listed in enum ref_spine_law */
    double e1[3], e2[3];  /* ARC, HELIX: the unit in-plane basis (e2 = axis x e1) */
    double ax[3];         /* ARC: unit normal; HELIX: unit axis */
    double n10[3];        /* N1(0): unit, normal to T(0) */
    ref_spine_user_fn fn; /* REF_SPINE_USER: the jet */
    const void *ctx;      /* REF_SPINE_USER: its context */
};

/* Set up and check (see enum ref_spine_err). ref: the start vector of N1 (NULL or zero: the
 * principal normal). Returns REF_SPINE_OK or the first failing check. */
int ref_spine_init(struct ref_spine *rs, int spine, const double sp[12], int law,
                   const double rp[4], const double ref[3]);

/* The same for a caller's jet (REF_SPINE_USER): fn must supply c and R with derivatives. */
int ref_spine_init_user(struct ref_spine *rs, ref_spine_user_fn fn, const void *ctx,
                        const double ref[3]);

/* The jet at u. Cannot fail (meaningful for u in [0, 1]). */
void ref_spine_jet(const struct ref_spine *rs, double u, struct ref_spine_jet *j);

/* The surface point c + (R + off) n at angle theta in the frame (T, N1, N2) at the jet's u,
 * and the unit normal n (away from the spine). n1 may be any vector not parallel to T: it
 * is projected and normalized here (N2 = T x N1). */
void ref_spine_surface(const struct ref_spine_jet *j, const double n1[3], double theta, double off,
                       double m[3], double n[3]);

/* dtheta/du of a family-2 line at angle theta, frame vector n1 (as above). */
double ref_spine_dtheta(const struct ref_spine_jet *j, const double n1[3], double theta);

/* Regularity D = b^2 - (R + off)(a_s + b kappa_E) of the (offset) surface at theta
 * (MATH-spine 3.3): the Jacobian is |m_s x m_theta| = (R + off)|D|; D = 0 on a cuspidal
 * edge. kappa2 = (a_s + b kappa_E) / D is the line's principal curvature (dn = -kappa dm). */
double ref_spine_regularity(const struct ref_spine_jet *j, const double n1[3], double theta,
                            double off);

/* One family-2 line with its frame, integrated adaptively to any u >= its current u. */
struct ref_spine_line {
    const struct ref_spine *rs;
    double u;     /* current parameter, in [0, 1] */
    double y[4];  /* N1 (not renormalized in the state) and theta, rad */
    double f[4];  /* d y / du at (u, y) */
    double h;     /* last accepted step (in u) */
    double tol;   /* local error tolerance (absolute + relative to max|y|); default 1e-12 */
    long steps;   /* accepted steps so far */
    long rejects; /* rejected steps so far */
    int fail;     /* non-zero after a step-size underflow or a backward request */
};

/* Start the line of start angle theta0 at u = 0 (frame N1(0)). */
void ref_spine_line_start(struct ref_spine_line *l, const struct ref_spine *rs, double theta0);

/* Integrate from the current u forward to exactly u (u >= l->u). 0 on success, -1 on
 * failure (l->fail set). */
int ref_spine_line_advance(struct ref_spine_line *l, double u);

/* The orthonormal frame at the line's current u: T, N1 (the state projected and normalized),
 * N2 = T x N1. */
void ref_spine_line_frame(const struct ref_spine_line *l, double t[3], double n1[3], double n2[3]);

/* The line's point c + (R + off) n and normal n at its current u. */
void ref_spine_line_here(const struct ref_spine_line *l, double off, double m[3], double n[3]);

/* Convenience (integrates from u = 0 each call): the point and normal of the line theta0 at
 * u, and the point at angle theta of the circle at u (family 1). 0 on success, -1 on an
 * integration failure. */
int ref_spine_line_point(const struct ref_spine *rs, double theta0, double u, double m[3],
                         double n[3]);
int ref_spine_circle_point(const struct ref_spine *rs, double u, double theta, double m[3],
                           double n[3]);

/* ---- the far spheres (issue 22): an independent overlap measure ----
 * The solid of the spine surface is the union of the spheres of radius R(u) about c(u).
 * Two of them, at u and u', OVERLAP when |c(u) - c(u')| < R(u) + R(u'); ref_spine_far_gap
 * gives the least gap |c(u) - c(u')| - R(u) - R(u') over the pairs whose spine arc between
 * them is at least `near` mm (on a closed spine, |c(1) - c(0)| <= 1e-5 x its extent, the
 * shorter way round), sampled at u = k / REF_SPINE_FAR (arc lengths of 8 chords a sample)
 * and the best pair refined by alternating golden sections in u and u' (40 steps each,
 * 4 rounds) inside the pair's two neighbouring intervals. Every gap it returns is the gap of
 * a real pair (an upper bound of the least one); the least one is at most `lip` (the
 * largest move of c plus that of R between samples) below the sampled minimum.
 * Written from the definition alone (no firmware code: the firmware bounds 64 pieces by
 * capsules, this measures spheres). */
#define REF_SPINE_FAR 512
struct ref_spine_far {
    double s[REF_SPINE_FAR + 1]; /* spine arc length from u = 0, mm */
    double c[REF_SPINE_FAR + 1][3];
    double r[REF_SPINE_FAR + 1];
    double len, rmax, lip, piece; /* total arc, largest R, largest sample move, longest arc
                                     of a 1/64 of u, mm */
    int closed;
};
void ref_spine_far_init(struct ref_spine_far *f, const struct ref_spine *rs);
/* The least gap (mm) over the pairs at least `near` mm of arc apart, *ua < *ub where it is
 * (1e30, -1, -1 when no pair is that far apart). */
double ref_spine_far_gap(const struct ref_spine *rs, const struct ref_spine_far *f, double near,
                         double *ua, double *ub);

#endif /* REF_SPINE_H */
