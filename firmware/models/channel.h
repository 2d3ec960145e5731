/* channel.h - channel surface from superellipse cross-sections by their inertia (seed 002).
 * SPDX-License-Identifier: MIT
 *
 * The model of Panchuk, Korchagin and Krysova as corrected and pinned down in
 * ../shared/docs/MATH-seeds-2-3-4.md part B (B.1 corrections, B.2 pipeline):
 *
 *   sections  N superellipses |x/a|^n + |y/b|^n = 1 (2 <= N <= CP_MAX_SECTIONS), each
 *             with a centre O_i and an orientation: rows x_i (the a axis), y_i = z_i x x_i,
 *             z_i (the section normal). channel_euler() makes the rows from angles,
 *             R = T(psi) T(theta) T(phi) (B5, recommended) or the printed T(theta) T(phi)
 *             T(psi) (whose example folds and is rejected).
 *   guide     L(u), u in [0, N-1], node i at u = i: C2 quintic Hermite segments through
 *             the centres; tangent M_i = k_i d_i, d_i = +-z_i towards the next centre
 *             (last: from the previous), k_i = mean adjacent chord (B6); node second
 *             derivatives A_i = mean of the one-sided cubic-Hermite values (B7).
 *   frame     tau = L'/|L'|, e1 = unit(e_y x tau), e2 = tau x e1 (B8; Frenet is not offered:
 *             it is ill-conditioned on the example, B8).
 *   laws      natural cubic splines (uniform knots) of S, n, J_I, J_II, J_I,II (B13), node
 *             data from K_S(n) = 2 Gamma(1/n)^2 / (n Gamma(2/n)) (S = a b K_S) and
 *             K_J(n) = Gamma(3/n) Gamma(1/n) / (n Gamma(4/n)) (J_x = a b^3 K_J, about the
 *             a axis) (B11), alpha_i = atan2(x_i.e2, x_i.e1) unwrapped mod pi.
 *   section   at any u in closed form (B.2 step 6): P = S/K_S = ab, Q = (J_I + J_II)/(K_J P)
 *             = a^2 + b^2 (0 < Q < 2P clamped to a = b and counted; Q <= 0 rejected),
 *             a >= b, alpha = 1/2 atan2(2 J_I,II, J_II - J_I) + k pi nearest the linear
 *             blend of the node angles.
 *   point     P(u, w) = L + (X cos alpha - Y sin alpha) e1 + (X sin alpha + Y cos alpha) e2,
 *             X = a sgn(cos w)|cos w|^(2/n), Y = b sgn(sin w)|sin w|^(2/n) (B10, B12), and
 *             the unit normal from the exact partial derivatives (outward: away from L).
 *             |cos w| or |sin w| below CHANNEL_AXIS_SNAP is taken as 0 (w on a section
 *             axis; the power |c|^(2/n) is infinitely steep there).
 *
 * Units: mm and radians. Every function that can fail is an _init; evaluation and
 * iteration after a successful init cannot fail (finiteness is guarded on emission).
 *
 * Iterator (path.h conventions, raster = struct raster_cfg):
 *   RASTER_LINES    n lines along the channel at section angles w_j = u0 + j (u1 - u0)/(n-1)
 *                     (radians, |w| <= pi), each with steps + 1 points at u_i = i (N-1)/steps;
 *                     zigzag (odd lines run u = N-1 .. 0); consecutive lines are linked by
 *                     `link` points on the section ring where they meet (w evenly between).
 *   RASTER_CIRCLES  n section rings at u_c = c (N-1)/(n-1) (n = 1: u = 0), each with steps + 1
 *                     points at w_i = u0 + i (u1 - u0)/steps; zigzag (odd rings run u1 .. u0);
 *                     links along the line w = const where they meet (u evenly between).
 *   count = n (steps + 1) + (n - 1) link. raster_pt: p = the output position, n = unit
 *   outward surface normal, t = u, line = j (or -1 on a link), index = i (link: 1..link).
 *   Output: SURFACE P; CENTRE P - r N: a ball tool INSIDE the duct (machining the channel
 *   wall from within, the port/nozzle case; the outside of a core is not offered); TIP the
 *   centre - r e_z. span and labels of the raster are ignored (w labels, span of angles).
 */
#ifndef CHANNEL_H
#define CHANNEL_H

#include "canal_path.h"

/* Largest superellipse exponent accepted (n in [1, CHANNEL_N_MAX]). */
#define CHANNEL_N_MAX CP_R(100.0)
/* Largest |coordinate| of a centre and largest semi-axis, mm. */
#define CHANNEL_COORD_MAX CP_R(1.0e4)
/* Orientation rows must be unit and orthogonal to this. They are used as given (not
 * re-orthonormalised): the guide tangent is d_i z_i normalised, and the node angle alpha_i
 * takes only the direction of x (or z x x) in the node frame, so a deviation within the
 * tolerance moves alpha_i by ~1e-4 rad at most. */
#define CHANNEL_AXES_TOL CP_R(1.0e-4)
/* Section plane containing the chord to a neighbour: |z.chord|/|chord| below this. */
#define CHANNEL_PLANE_TOL CP_R(1.0e-3)
/* Frame undefined: |e_y x tau| at or below this. */
#define CHANNEL_FRAME_TOL CP_R(1.0e-6)
/* Isotropic node section: |a - b| <= this * max(a, b) (allowed only for n = 2). */
#define CHANNEL_ISO_TOL CP_R(1.0e-6)
/* |cos w|, |sin w| below this count as 0 (w on a section axis). */
#define CHANNEL_AXIS_SNAP CP_R(1.0e-5)
/* Evaluation grid of the init regularity check: rows per guide segment, angles per row. */
#define CHANNEL_GRID_U 24u
#define CHANNEL_GRID_W 48u

/* Orientation conventions of channel_euler(). */
enum channel_order {
    CHANNEL_ORDER_SPIN_FIRST = 0, /* R = T(psi) T(theta) T(phi): B5, the recommended reading */
    CHANNEL_ORDER_PRINTED = 1     /* R = T(theta) T(phi) T(psi): eq. (14) as printed */
};

/* One cross-section (12 reals). */
struct channel_section {
    cp_real a, b;     /* semi-axes along x and y, mm, in (0, CHANNEL_COORD_MAX] (CP_ERR_SECTION
                         for <= 0, CP_ERR_RANGE above); a < b is allowed (axes are swapped) */
    cp_real n;        /* exponent, 1 (rhombus) .. CHANNEL_N_MAX; 2 = ellipse (CP_ERR_EXPONENT
                         below 1, CP_ERR_RANGE above) */
    struct cp_vec3 c; /* centre, mm, |coordinate| <= CHANNEL_COORD_MAX */
    struct cp_vec3 x; /* local x axis (the a axis), unit within CHANNEL_AXES_TOL */
    struct cp_vec3 z; /* section normal, unit, orthogonal to x within CHANNEL_AXES_TOL */
};

/* The geometry (lives in union path_geom; the iterator keeps a pointer to it). */
struct channel_cfg {
    uint8_t count; /* sections used, 2..CP_MAX_SECTIONS */
    struct channel_section s[CP_MAX_SECTIONS];
};

/* Everything the points of one u need (one evaluation of the laws and the guide). Index 0
 * of ab/dab is the a (cos w) half, 1 the b (sin w) half. */
struct channel_row {
    cp_real u;                  /* guide parameter, 0..N-1 */
    struct cp_vec3 l, t;        /* guide point (mm), unit tangent tau */
    struct cp_vec3 e1, e2;      /* frame: e1 = unit(e_y x tau), e2 = tau x e1 */
    cp_real ab[2];              /* semi-axes a >= b at u, mm */
    cp_real dab[2];             /* a'/a, b'/b (per unit u) */
    cp_real alpha, ca, sa;      /* angle of the a axis from e1 (rad), its cos and sin */
    cp_real q, dq;              /* 2 / n(u) and its derivative */
    cp_real k[2];               /* guide curvature vector . e1, . e2, 1/mm */
    cp_real sp;                 /* |L'(u)|, mm per unit u */
    cp_real wr;                 /* alpha' + frame twist e2.e1' (per unit u) */
    cp_real s, n;               /* area law S(u) (mm^2) and exponent n(u) */
    uint8_t flags;              /* CHANNEL_ROW_* */
};

#define CHANNEL_ROW_CLAMP 0x01u    /* Q < 2P: clamped to a = b (counted, struct channel) */
#define CHANNEL_ROW_BAD_LAW 0x02u  /* S <= 0, n < 1, or Q <= 0 (J_I + J_II <= 0: spline
                                      overshoot; no section): CP_ERR_AREA_LAW */
#define CHANNEL_ROW_FRAME 0x04u    /* |e_y x tau| <= CHANNEL_FRAME_TOL (CP_ERR_FRAME_REF) */

/* The model after channel_init (node data and spline second derivatives). */
struct channel {
    const struct channel_cfg *cfg; /* the sections (must outlive this struct) */
    uint8_t ns;                    /* N */
    uint16_t clamps;               /* 0 < Q < 2P clamps (to a = b) met by the init walks of
                                      channel_path_init, in walked samples, saturating at
                                      65535 (a warning: the caller reads it after a
                                      successful init, e.g. channel_path.ch.clamps); Q <= 0
                                      is rejected instead (CP_ERR_AREA_LAW) */
    cp_real d[CP_MAX_SECTIONS];    /* signed tangent magnitude: M_i = d_i z_i, mm */
    cp_real acc[CP_MAX_SECTIONS][3]; /* node second derivatives A_i (x, y, z), mm */
    cp_real al[CP_MAX_SECTIONS];   /* node angles alpha_i, unwrapped, rad */
    cp_real y[5][CP_MAX_SECTIONS]; /* node values of S, n, J_I, J_II, J_I,II */
    cp_real y2[5][CP_MAX_SECTIONS > 2 ? CP_MAX_SECTIONS - 2 : 1]; /* their natural-spline
                                         second derivatives at the interior nodes 1..N-2 (0
                                         at both ends; at least 1 column: C99 forbids a
                                         zero-length array, unused when N = 2) */
};

/* Orientation rows of section s from angles (radians) in the given order (enum
 * channel_order): s->x = row 0 and s->z = row 2 of R (row-vector convention of the paper,
 * T(theta) about x, T(phi) about y, T(psi) about z, eqs. (10)-(12)). */
void channel_euler(struct channel_section *s, cp_real psi, cp_real theta, cp_real phi,
                   uint8_t order);

/* Check one section alone (what channel_init checks per section): CP_OK, CP_ERR_NONFINITE,
 * CP_ERR_SECTION, CP_ERR_EXPONENT, CP_ERR_RANGE, CP_ERR_ISOTROPIC (the job commands report
 * these at once). */
CP_MUST_CHECK int channel_section_check(const struct channel_section *s);

/* K_S(n) and K_J(n) (B11): area = a b K_S, J_x = a b^3 K_J. n in [1, CHANNEL_N_MAX].
 * ln Gamma by a shift to z >= 4 (float) / 10 (double) and the Stirling series; error
 * analysis at lgam() in channel.c. K_S(2) = pi, K_J(2) = pi/4 to ~1e-15 (double). */
cp_real channel_ks(cp_real n);
cp_real channel_kj(cp_real n);

/* Validate cfg and build the model (the sections, the nodes and their frames; what lies
 * between the nodes is checked by channel_path_init's walks). Errors:
 *   CP_ERR_INVAL        cfg NULL
 *   CP_ERR_TOO_FEW      fewer than 2 sections     CP_ERR_TOO_MANY  more than CP_MAX_SECTIONS
 *   CP_ERR_NONFINITE    a NaN or Inf              CP_ERR_SECTION   a or b <= 0
 *   CP_ERR_EXPONENT     n < 1                     CP_ERR_RANGE     above a maximum, or axes
 *                                                 not unit/orthogonal (CHANNEL_AXES_TOL)
 *   CP_ERR_ISOTROPIC    a = b (CHANNEL_ISO_TOL) with n != 2
 *   CP_ERR_COINCIDENT   consecutive centres closer than 1e-6 of the centres' extent
 *   CP_ERR_SECTION_PLANE a section plane contains the chord to a neighbour (CHANNEL_PLANE_TOL)
 *   CP_ERR_FRAME_REF    a node tangent parallel to e_y (CHANNEL_FRAME_TOL) */
CP_MUST_CHECK int channel_init(struct channel *ch, const struct channel_cfg *cfg);

/* The row at u (clamped to [0, N-1]). Cannot fail; flags report clamps/bad laws. */
void channel_row(const struct channel *ch, cp_real u, struct channel_row *r);

/* Surface point P (mm) at section angle w (radians, |w| <= CP_SINCOS_XMAX) of row r, unit
 * outward normal nrm, and the sweep regularity g = 1 - k.(P - L) (> 0 after a successful
 * init). */
void channel_point(const struct channel_row *r, cp_real w, struct cp_vec3 *p, struct cp_vec3 *nrm,
                   cp_real *g);

/* Wire (length-weighted) inertia of section s sampled as a closed polygon of m vertices
 * (8 <= m <= 1e6): length L (mm), centroid (eq. 1, B2), inertia tensor about it (eqs. 4-5,
 * rho = 1), principal moments lam[0] <= lam[1] <= lam[2] from the characteristic cubic in
 * closed form (eqs. 6-7, B4; trigonometric roots) and the unit axis of lam[2] (the plane
 * normal of a planar section, sign towards +s->z). Host/test use: the pipeline takes the
 * normal from the orientation rows, so the M4F image does not link this (gc-sections).
 * Returns CP_OK or CP_ERR_RANGE (m out of range). */
CP_MUST_CHECK int channel_wire_inertia(const struct channel_section *s, uint32_t m, cp_real *len,
                                       struct cp_vec3 *centroid, cp_real lam[3],
                                       struct cp_vec3 *axis3);

/* The iterator (struct path's union member). */
struct channel_path {
    struct raster_head head; /* mode, n, steps, link, count, k (raster.h): LINES along u,
                                CIRCLES (rings) along w; the init walks double steps (up to
                                2 CP_MAX_STEPS) and link (up to 2 CP_MAX_LINK + 1) */
    /* the output */
    uint8_t output;          /* enum raster_output: SURFACE, CENTRE or TIP */
    cp_real tool_r;          /* tool radius (mm) */
    /* the raster's coordinates */
    cp_real lo[2], hi[2];    /* ranges of u (0, N-1) and w (u0, u1, rad) */
    /* the model */
    struct channel ch;
    /* cache of the stream */
    struct channel_row row;  /* cached row (row.u = -1: none) */
};

/* Validate the geometry (channel_init) and the raster, walk the evaluation grid (whole
 * rings of CHANNEL_GRID_W angles at CHANNEL_GRID_U rows per guide segment), derive steps/link
 * from the chord tolerance (rounded up, then verified on the emitted positions: the midpoint
 * sagitta of every segment <= tol) and walk every line, ring and link at twice the
 * resolution (one walk of the whole doubled raster per try: its even points are exactly the
 * emitted ones), all before anything is emitted. Every walked point is checked: laws (S > 0,
 * n >= 1), frame (|e_y x tau| > CHANNEL_FRAME_TOL), sweep regularity g = 1 - k.(P - L) > 0,
 * the tool-centre path not folding back against the surface path, finiteness. raster: mode, output, n (1..CP_MAX_LINES), u0, u1
 * (|u| <= pi; u0 == u1 only with n == 1), steps (0 = from tol), link (RASTER_LINK_AUTO =
 * from tol or 1 um), tol, tool_r. The raster is checked first (raster_check, raster.h:
 * INVAL, NONFINITE, RANGE, TOO_MANY, TOOL in that order, then tool_r > CHANNEL_COORD_MAX),
 * then the geometry (channel_init), then the walks. Errors: every channel_init code, plus
 *   CP_ERR_INVAL     raster NULL, mode/output out of range, a tool radius with OUT_SURFACE
 *   CP_ERR_NONFINITE u0, u1, tol or tool_r      CP_ERR_RANGE  as canal_path_init
 *   CP_ERR_TOO_MANY  n, steps above the maxima
 *   CP_ERR_TOOL      tool_r < 0 or tool_r > CHANNEL_COORD_MAX, or the tool-centre path folds
 *                    back (tool radius above the wall's radius of curvature) on a walk (grid
 *                    rings included)
 *   CP_ERR_TOL       tol needs more than CP_MAX_STEPS steps / CP_MAX_LINK link points
 *   CP_ERR_AREA_LAW  on a walk: S <= 0, n < 1, or Q = (J_I + J_II)/(K_J P) <= 0 (the laws'
 *                    splines overshoot into no section); 0 < Q < 2P is clamped to a = b and
 *                    counted instead (cp->ch.clamps, a warning)
 *   CP_ERR_FOLD, CP_ERR_FRAME_REF  also on the walk
 *   CP_ERR_NUMERIC   a non-finite value on the walk
 *   CP_ERR_SEAM      (right after channel_init) a closed guide (the last centre on the first,
 *                    within RASTER_SEAM_GAP x the centres' extent) whose sections do not
 *                    close: a, b or n (value, or slope per mm of guide) or the section's
 *                    turn in its plane, beyond raster_seam_check's tolerances (raster.h)
 * Last, far parts of the duct that meet are REPORTED, not refused (the ball is inside the
 * duct): raster_overlap_report (raster.h) on the balls (L(u), a max(1, sqrt(2^(1 - 2/n)))),
 * head.overlap = 1. The balls are loose for flat sections and at the open ends (a section is
 * flat, its ball reaches a past it), so two ends facing each other within 2 a are reported
 * too. */
CP_MUST_CHECK int channel_path_init(struct channel_path *cp, const struct channel_cfg *g,
                                    const struct raster_cfg *raster);

/* Points of the whole path (0 before a successful init). */
uint32_t channel_path_count(const struct channel_path *cp);

/* Next point: CP_OK, CP_ERR_DONE after the last, or a walk error of the point (CP_ERR_NUMERIC
 * for a non-finite value; the point is not consumed; cannot happen after the init walk,
 * which checked the same (u, w), kept as a guard). */
int channel_path_next(struct channel_path *cp, struct raster_pt *pt);

/* Restart at point k (0 <= k <= count): the next point is bit for bit the one first
 * yielded at k (every point is computed from (u, w) directly; the row cache is keyed by u).
 * Returns CP_OK or CP_ERR_RANGE. */
CP_MUST_CHECK int channel_path_seek(struct channel_path *cp, uint32_t k);

#endif /* CHANNEL_H */
