/* spine.h - SPINE: the curvature lines of a canal surface (envelope of spheres of radius
 * R(u) centred on a 3D spine c(u)), issue 18. The kernel: spine, radius law, the fixed-step
 * march of the rotation-minimizing frame and of the 2x2 line transport, and the points.
 * SPDX-License-Identifier: MIT
 *
 * Mathematics: docs/MATH-spine.md (it overrides the issue). Notation of its section 1:
 *
 *     m(u, theta) = c + R n,   n = -a T + b (cos theta N1 + sin theta N2),
 *     a = dR/ds = R_u / |c_u|,  b = sqrt(1 - a^2),  (T, N1, N2) the RMF, N2 = T x N1.
 *
 * Family 1: the characteristic circles u = const (theta free). Family 2: the orthogonal
 * trajectories, labelled by theta0, their angle on the first circle (u = 0) measured from
 * the RMF vector N1(0). Every family-2 line is the same linear map of its label
 * (MATH-spine 5.2, 9.7):
 *
 *     y = M(u) (sin(theta0/2), cos(theta0/2)),   cos psi = (y2^2 - y1^2)/|y|^2,
 *     sin psi = 2 y1 y2 / |y|^2,                  n = -a T + b (cos psi P + sin psi Q).
 *
 * The node frame (P, Q) is local, not marched (MATH-spine 9.7): P = unit(e - (e.T) T) for a
 * fixed unit axis e that is never along T (struct spine ax), Q = T x P. The RMF's twist
 * against (P, Q) moves into the transport, which stays traceless (det M = 1):
 *
 *     M' = A M,   A = [[-d, s + r], [s - r, d]],   d = f c_uu.P,  s = f c_uu.Q,  r = eta c_uu.Q,
 *     f = R_u / (2 v sqrt(v^2 - R_u^2)),   eta = (e.T) / (2 v sqrt(1 - (e.T)^2)),   v = |c_u|,
 *     M(0) = the rotation by phi0/2, phi0 the angle of N1(0) from P(0).
 *
 * Numerics (MATH-spine 9.7): march nodes u_k = k / N (N = nsteps). M by N steps of the
 * two-point Hermite Magnus-4 (A and A' at the nodes: one jet per step), in increment form;
 * between two nodes, M by the quintic Hermite interpolant of (M, M', M'') at both ends. A
 * point at any u costs one jet, the frame and the interpolant; the march steps only when u
 * leaves its interval. Orders: 4 (march), 6 (interpolant). The iterator picks N by step
 * doubling (spine_path_init); this kernel takes N as given.
 *
 * Conventions (the same as tests/ref_spine.h, which judges this kernel):
 *   - u in [0, 1] is the normalized spine parameter; every length in mm, angles in radians.
 *   - N1(0) = the unit projection of the reference vector ref onto the plane normal to T(0);
 *     ref = (0, 0, 0) selects the principal normal c_uu - (c_uu.T)T at u = 0.
 *   - n points AWAY from the spine. An offset off gives c + (R + off) n: off = +r is the
 *     ball-end centre of an OUTSIDE tool, off = -r of an INSIDE tool (fillet, bore).
 *
 * Memory: struct spine is the whole context (<= 320 B in the float build with the iterator,
 * checked by static asserts); no allocation, no table: the march keeps its current node and
 * the interpolant of one interval. Points are evaluated at u = num / den (spine_eval): on
 * the forward pass the march goes on from its node or restarts from u = 0 when u is behind
 * it; the backward pass (the backward lines of a zigzag) marches forward to u = 1 once,
 * then back. Each pass is one fixed sequence of steps, so a point depends only on (pass,
 * u): seeks and resumes are bit for bit.
 */
#ifndef SPINE_H
#define SPINE_H

#include "cp_types.h"
#include "raster.h"

enum spine_kind {
    /* sp = x0 y0 z0 x1 y1 z1: c(u) = P0 + u (P1 - P0). Straight: needs a non-zero ref. */
    SPINE_LINE = 0,
    /* sp = cx cy cz nx ny nz r dx dy dz span: the circle of radius r > 0 about the centre C in
     * the plane normal to n (any length > 0), starting in the direction d projected onto that
     * plane, turning by span radians (0 < |span| <= 2 pi; > 0 counter-clockwise about n):
     * c(u) = C + r (cos(span u) e1 + sin(span u) e2), e1 = unit(d - (d.n^)n^), e2 = n^ x e1 */
    SPINE_ARC = 1,
    /* sp = px py pz ax ay az r pitch turns dx dy dz: the helix about the axis through P with
     * direction a (any length > 0), radius r > 0, pitch mm per turn (> 0 right-handed about
     * a, < 0 left-handed, 0 a circle), 0 < turns <= SPINE_TURNS_MAX, starting in the
     * direction d projected onto the plane normal to a:
     * c(u) = P + r (cos p e1 + sin p e2) + pitch p / (2 pi) a^,  p = 2 pi turns u */
    SPINE_HELIX = 2,
    /* sp = the four control points x0 y0 z0 .. x3 y3 z3: the cubic Bezier curve in u */
    SPINE_BEZIER = 3
};

/* The radius laws of the canal model (canal.h CANAL_R_*), in the normalized u. */
enum spine_law {
    SPINE_R_CONST = 0,  /* rp = c: R = c */
    SPINE_R_LINEAR = 1, /* rp = r0 r1: R = r0 + (r1 - r0) u */
    SPINE_R_COS = 2,    /* rp = b c k: R = b cos(2 pi k u) + c, |k| <= SPINE_K_MAX */
    SPINE_R_CUBIC = 3   /* rp = r0 .. r3: R = sum r_i B_i,3(u), Bernstein */
};

/* Limits checked by spine_init. */
#define SPINE_COORD_MAX CP_R(1.0e4) /* |every length parameter| <= 10 m */
#define SPINE_K_MAX CP_R(64.0)      /* |k| of the COS law */
#define SPINE_TURNS_MAX CP_R(64.0)  /* helix turns */
#define SPINE_NSTEPS_MAX 1024u      /* march steps N */
#define SPINE_CHECK_N 256u          /* the spine's |c_u| is also sampled at u = k / 256 */

struct spine_cfg {
    uint8_t kind;  /* enum spine_kind */
    uint8_t law;   /* enum spine_law */
    uint8_t set;   /* protocol bookkeeping (job_spine.c), ignored by spine_init */
    cp_real sp[12]; /* spine parameters, mm and radians, as listed in enum spine_kind (unused
                       entries ignored) */
    cp_real rp[4];  /* radius-law parameters, mm (k dimensionless), as in enum spine_law */
    cp_real ref[3]; /* start vector of N1 (any length); all zero: the principal normal */
    cp_real dir[3]; /* protocol bookkeeping (job_spine.c SPINEDIR: the ARC/HELIX start
                       direction, copied into sp[] at RUN), ignored by spine_init */
};

/* The jet of the spine and the law at one u (spine_jet). */
struct spine_jet {
    struct cp_vec3 c, cu, cuu, cuuu;
    cp_real r, ru, ruu;
};

/* The context: the validated configuration and the march. Read-only for the caller;
 * changed by spine_init, spine_eval, spine_node and spine_node_back only. */
struct spine {
    uint8_t kind, law;
    uint8_t back;       /* 1: the march state was reached by a backward pass */
    uint16_t nsteps;    /* N: march steps, nodes u_k = k / N */
    uint16_t node;      /* the march's current node k (0..N) */
    cp_real sp[12];     /* the spine parameters; BEZIER: its power basis B0..B3 about u = 1/2,
                           c = B0 + B1 w + B2 w^2 + B3 w^3, w = u - 1/2 (spine_init) */
    cp_real rp[4];      /* the law parameters; CUBIC: its power basis about u = 1/2 */
    struct cp_vec3 e1;  /* ARC, HELIX: unit in-plane start direction */
    struct cp_vec3 e2;  /* ARC, HELIX: ax x e1 */
    struct cp_vec3 ax;  /* the frame axis e (unit, never along T): ARC the plane's normal,
                           HELIX the axis, LINE the reference made normal to the line, BEZIER
                           the best of six candidates (spine_init) */
    cp_real z0[2];      /* cos, sin of phi0/2: M(0) = [[z0[0], z0[1]], [-z0[1], z0[0]]] */
    cp_real rmin;       /* min R over the init samples, mm */
    /* the march at node `node`: */
    cp_real m[4];       /* M(u_k) = [[m0, m1], [m2, m3]] */
    cp_real g[3];       /* A(u_k) as (d, s, r) */
    cp_real gd[3];      /* dA/du (u_k) as (d, s, r) */
    cp_real pc[6][4];   /* M on the interval [u_lo, u_lo + 1/N] (lo = node - 1 forward, node
                           backward): M = sum_i pc[i] t^i, t = N (u - u_lo) in [0, 1] */
};

/* Everything a point at one u needs (spine_eval fills it; shared by all lines there). */
struct spine_state {
    cp_real u;           /* u = num / den */
    uint16_t node;       /* the march node at or below u */
    struct cp_vec3 c;    /* c(u), mm */
    struct cp_vec3 t;    /* unit tangent T */
    struct cp_vec3 n1;   /* the node frame P: unit, normal to T (not the RMF) */
    struct cp_vec3 n2;   /* Q = T x P */
    cp_real r;           /* R(u), mm (> 0) */
    cp_real a, b;        /* dR/ds (|a| < 1) and sqrt(1 - a^2) */
    cp_real as;          /* da/ds, 1/mm (spine_node, spine_node_back, spine_eval with full) */
    cp_real k1, k2;      /* T' = k1 P + k2 Q per mm of arc (the same) */
    cp_real m[4];        /* transport M(u), det = 1 up to rounding */
    /* shared by every point at this u: n = at + cos(psi) bn1 + sin(psi) bn2 */
    struct cp_vec3 at;   /* -a T */
    struct cp_vec3 bn1;  /* b P */
    struct cp_vec3 bn2;  /* b Q */
};

/* The homogeneous label of a family-2 line: (sin(theta0/2), cos(theta0/2)). */
struct spine_label {
    cp_real y1, y2;
};

/* Validate cfg and prepare the march at node 0. Checks, in this order, each with its code:
 *   CP_ERR_INVAL       s or cfg NULL, kind or law out of range
 *   CP_ERR_NONFINITE   a used parameter (sp, rp, ref) NaN or Inf
 *   CP_ERR_TOO_MANY    nsteps > SPINE_NSTEPS_MAX;   CP_ERR_RANGE nsteps = 0
 *   CP_ERR_RANGE       |parameter| > SPINE_COORD_MAX, COS |k| > SPINE_K_MAX, ARC/HELIX r <= 0,
 *                      |span| > 2 pi, HELIX turns <= 0 or > SPINE_TURNS_MAX
 *   CP_ERR_EMPTY       ARC span = 0
 *   CP_ERR_DEGENERATE  ARC/HELIX: zero normal/axis or a start direction along it; any spine:
 *                      |c_u| <= 1e-5 (1 + max |sp[i]|) at a node u = k / N or at
 *                      u = k / SPINE_CHECK_N (LINE with P0 = P1, Bezier cusp or coincident
 *                      control points; a cusp strictly between samples is not seen); BEZIER:
 *                      no frame axis keeps |e x T| >= SPINE_AXIS_MIN at the samples
 *   CP_ERR_RADIUS      R <= 0 at a sample (the nodes and u = k / SPINE_CHECK_N)
 *   CP_ERR_RANGE       |a| = |R_u| / |c_u| >= 1 at a sample (the nodes, where the march
 *                      evaluates A, and u = k / SPINE_CHECK_N). Proposed for its own code
 *                      (CP_ERR_SLOPE), see the report of issue 18.
 *   CP_ERR_FRAME_REF   ref non-zero and its projection on the normal plane at u = 0 is
 *                      <= 1e-4 |ref| (ref along T(0))
 *   CP_ERR_FRENET      ref zero and the principal normal at u = 0 is <= 1e-4 |c_u|^2 (a LINE,
 *                      or a spine straight or inflecting at its start)
 *   CP_ERR_SEAM        the spine closes (|c(1) - c(0)| <= RASTER_SEAM_GAP x its extent: an
 *                      ARC of 2 pi, a HELIX of pitch 0 and whole turns, a Bezier with
 *                      P3 = P0) and R or dR/ds does not (raster_seam_check, raster.h)
 * D != 0 (regularity, spine_regularity) is NOT checked here: it depends on the lines and the
 * tool offset, and is the iterator's check. Returns CP_OK. On error *s is unusable. */
int spine_init(struct spine *s, const struct spine_cfg *cfg, uint16_t nsteps) CP_MUST_CHECK;

/* Least |e x T| over the samples that spine_init accepts for a Bezier's frame axis. Near
 * it the frame turns fast (eta ~ 1 / |e x T|) and the iterator's step doubling asks for
 * more march steps. */
#define SPINE_AXIS_MIN CP_R(1.0e-2)

/* The jet of the spine and the law at u (meaningful for u in [0, 1]): c, c_u, c_uu, c_uuu
 * (mm per unit u), R, R_u, R_uu. One cp_sincos kernel for ARC and HELIX, one for the COS
 * law. Rounding: a few ulp of max |sp| (BEZIER: Horner in |w| <= 1/2). Cannot fail. */
void spine_jet(const struct spine *s, cp_real u, struct spine_jet *j);

/* The state at u = num / den (0 <= num <= den, 1 <= den <= 65535) on the forward pass
 * (back = 0) or the backward pass (back = 1): one jet at u, the frame, and M from the
 * march: at a node (num N divisible by den) the node's M, else the interpolant of the
 * node's interval. The march steps as needed (forward: on to the node above u, or a
 * restart when u is behind it; backward: forward to node N once per pass, then back to the
 * node at or below u). full = 0 leaves st->as, k1, k2 unset (the streaming path). Cost
 * without a march step: one jet, ~60 flops of frame, 4 degree-5 Horner sums. CP_ERR_RANGE
 * for num > den, den = 0 or st NULL (nothing changed); CP_ERR_NUMERIC if a non-finite value
 * appeared (cannot happen after a successful init with finite arithmetic; kept as the
 * iterator's guard). Returns CP_OK. */
int spine_eval(struct spine *s, uint32_t num, uint32_t den, uint8_t back, uint8_t full,
               struct spine_state *st) CP_MUST_CHECK;

/* spine_eval(s, i, N, 0, 1, st): the state at march node i (0 <= i <= N), forward pass.
 * CP_ERR_RANGE if i > N. */
int spine_node(struct spine *s, uint16_t i, struct spine_state *st) CP_MUST_CHECK;

/* spine_eval(s, i, N, 1, 1, st): the state at node i on the backward pass (the march from
 * node N by backward steps: the Hermite Magnus step run with -h is exactly the inverse, so
 * a backward pass makes the forward march's truncation error, only the rounding differs). */
int spine_node_back(struct spine *s, uint16_t i, struct spine_state *st) CP_MUST_CHECK;

/* The label of the line theta0 (radians, any finite value; |theta0| <= 1e5 in the float
 * build): one cp_sincos(theta0 / 2). Lines theta0 and theta0 + 2 pi are the same line. */
void spine_label(cp_real theta0, struct spine_label *lab);

/* The family-2 line with label lab at the u of st: pt->p = c + (R + off) n, pt->n = n
 * (unit, away from the spine), pt->t = u. line and index are not written. off in mm, |off|
 * < R for an inside tool (the caller's check). No trigonometry: y = M y0, then one division.
 * Rounding only (beyond the march): a few ulp of |c| + R. */
void spine_point_label(const struct spine_state *st, const struct spine_label *lab, cp_real off,
                       struct raster_pt *pt);

/* The same with the label made here from theta0 (one cp_sincos). */
void spine_point(const struct spine_state *st, cp_real theta0, cp_real off, struct raster_pt *pt);

/* The family-1 circle at the u of st, at angle psi in the node frame (P, Q) = (n1, n2) (NOT
 * a line label, NOT the RMF): one cp_sincos(psi). pt as for spine_point. */
void spine_circle_point(const struct spine_state *st, cp_real psi, cp_real off,
                        struct raster_pt *pt);

/* The angle psi of the line lab at st's u in the node frame, as (cos psi, sin psi), exact
 * rational form. */
void spine_angle(const struct spine_state *st, const struct spine_label *lab, cp_real *ct,
                 cp_real *sn);

/* Regularity D = b^2 - (R + off)(a_s + b (k1 cos psi + k2 sin psi)) of the surface offset
 * by off, at angle (ct, sn) in the node frame (MATH-spine 3.3, 8; st from a full
 * evaluation): the Jacobian is (R + off)|D|; D = 0 on a cuspidal edge. A regular patch
 * keeps D > 0 (the iterator's check, CP_ERR_CUSP). */
cp_real spine_regularity(const struct spine_state *st, cp_real ct, cp_real sn, cp_real off);

/* ---- the toolpath iterator (path.h; raster semantics of raster.h) ----
 *
 * A patch of the surface between the family-2 lines theta0 = u0 and u1 (start angles on the
 * first circle, radians, |u| <= pi; u0 == u1 with n = 1), u over [0, 1]:
 *   LINES    n family-2 lines theta0_j = u0 + j (u1 - u0)/(n - 1), steps + 1 points each at
 *            u = i / steps, zigzag (odd lines from u = 1 back to 0); the link from line j to
 *            j + 1 runs along the characteristic circle at the end u, through the lines of
 *            the labels between theta0_j and theta0_j+1 (label fraction a / (link + 1)).
 *   CIRCLES  n characteristic circles at u_j = j / (n - 1) (u = 0 for n = 1), each steps + 1
 *            points: the family-2 lines theta0 = u0 + i (u1 - u0)/steps at u_j (the same
 *            patch as LINES: raster span LINES), zigzag in theta0; the link from circle j to
 *            j + 1 runs along the line where circle j stopped, at u = (j + a/(link + 1))/(n-1).
 * Every point is (u, label): spine_eval at u = i / steps (LINES) or u = (j (link + 1) + a) /
 * ((n - 1)(link + 1)) (CIRCLES), then the label (one cp_sincos per line, cached) and
 * spine_point_label. The odd (backward) lines of LINES and their links are on the backward
 * pass.
 * The march: N = SPINE_PATH_NMIN, doubled (up to SPINE_NSTEPS_MAX) until the step-doubling
 * estimate of the march error, (R_max + tool_r) max_k ||M_N(u_k) - M_2N(u_k)|| / 15 over
 * the nodes of the N march (M relative to its size), is <= SPINE_MARCH_TOL and every
 * step keeps |h A| <= SPINE_STEP_MAX (the exp series' range), else CP_ERR_TOL; independent
 * of the points per line (MATH-spine 9.7: 32 steps give ~0.14 um on the helix tube; the
 * interpolant adds ~1 nm there).
 * Cost: one jet + frame + interpolant per point, plus a march step (one jet, A and A', the
 * Magnus step, the interpolant's 24 coefficients) each time u crosses a node: about
 * N / steps steps per point, i.e. one per steps / N points when steps > N. A backward line
 * first marches on to u = 1 (once per line); a seek costs at most one restart plus 2N steps.
 * Output: SURFACE the surface point m; CENTRE the ball-end centre m - r n (inside tool: the
 * canal surface of radius R - r, n points away from the spine); TIP that centre - r z.
 * Checked at init (before the first point), in this order: spine_init's codes; raster_check's
 * (raster.h); labels != ANGLE or span != LINES CP_ERR_INVAL; the march N (above); steps == 0:
 * the steps from tol by raster_fit (start 16, pilot, aim 0.8 tol, accept 0.9 tol) on the
 * sagitta estimate |P(i-1) - 2 P(i) + P(i+1)| / 8 of the emitted points of every line or
 * circle (measured against ref_spine: the worst chord 0.57-0.84 tol, test_spine
 * spine_path_tol), CP_ERR_TOL when steps would exceed CP_MAX_STEPS; link == RASTER_LINK_AUTO:
 * LINES derive it from tol (1 um when tol = 0) by the exact on-circle sagitta of the link
 * chords (the least link meeting it, CP_ERR_TOL above CP_MAX_LINK); CIRCLES derive it with
 * the steps in the same raster_fit walks from the exact midpoint sagitta of every link
 * segment on the lines u0 and u1; tool_r >= the min R of spine_init's samples CP_ERR_TOOL;
 * then at every streamed u and every march node, and every label of the patch (the streamed
 * lines and link labels; CIRCLES: the steps + 1 labels) the regularity D of the surface
 * (off = 0) and of the tool-centre surface (off = -r) must be > 0, else CP_ERR_CUSP (a cusp
 * strictly between those u or labels is not seen); CP_ERR_NUMERIC for a non-finite march.
 * Last, far parts whose spheres meet (a helix of pitch below 2 R, a spine whose ends come
 * close or that loops through itself) are REPORTED, not refused: the ball (m - r n, r < R)
 * lies in its own sphere, so inside the swept solid (raster.h raster_overlap_report on the
 * balls (c(u), R(u)): head.overlap = 1, docs/PROTOCOL.md "Far parts that meet, the tool
 * inside"). */
#define SPINE_PATH_NMIN 32u
#if CP_REAL_DOUBLE
#define SPINE_MARCH_TOL 2.0e-7 /* mm: the march's estimated error bound (double: 0.2 nm) */
#else
#define SPINE_MARCH_TOL 2.0e-5f /* mm (float: 0.02 um, a few float ulp of 100 mm) */
#endif
#define SPINE_STEP_MAX CP_R(0.25)    /* max (|d| + |s| + |r|) h over the march's nodes */

struct spine_path {
    struct raster_head head; /* mode, n, steps, link, count, k (raster.h) */
    uint8_t output;          /* enum raster_output */
    uint16_t den;            /* u = num / den: LINES steps, CIRCLES (n - 1)(link + 1) (1 for
                                n = 1) */
    uint16_t nl;             /* label intervals: LINES (n - 1)(link + 1), CIRCLES steps */
    cp_real tool_r;          /* mm */
    cp_real u0, u1;          /* label range, radians */
    uint32_t lab_l;          /* the label index of `lab` (UINT32_MAX: none yet) */
    struct spine_label lab;  /* the last label made: one cp_sincos per line, not per point */
    struct spine s;          /* the kernel and its march */
};

/* Validate and check the patch (see above). Returns CP_OK; then spine_path_next yields
 * exactly spine_path_count() points. */
CP_MUST_CHECK int spine_path_init(struct spine_path *it, const struct spine_cfg *cfg,
                                  const struct raster_cfg *raster);

/* Total points of the path (0 until a successful init). */
uint32_t spine_path_count(const struct spine_path *it);

/* Next point: CP_OK, CP_ERR_DONE after the last (CP_ERR_NUMERIC: the march's guard; the
 * position does not advance). pt->t = u, pt->line, pt->index as raster.h. */
int spine_path_next(struct spine_path *it, struct raster_pt *pt);

/* Restart at point k (0 <= k <= count; CP_ERR_RANGE otherwise): the next point is bit for
 * bit the k-th of a full walk (each pass of the march is one fixed sequence of steps). */
CP_MUST_CHECK int spine_path_seek(struct spine_path *it, uint32_t k);

#endif /* SPINE_H */
