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
 * trajectories, labelled by theta0, their angle on the first circle (u = 0). Every family-2
 * line is the same linear map of its label (MATH-spine 5.2):
 *
 *     y = M(u) (sin(theta0/2), cos(theta0/2)),  cos theta = (y2^2 - y1^2)/|y|^2,
 *     sin theta = 2 y1 y2 / |y|^2,   M' = A~ M,  A~ = f [[-c_uu.N1, c_uu.N2], [c_uu.N2, c_uu.N1]],
 *     f = R_u / (2 |c_u| sqrt(|c_u|^2 - R_u^2))            (traceless: det M = 1).
 *
 * Numerics (MATH-spine 9): a uniform grid in u, nodes u_i = i / N (i = 0..N, N = nsteps),
 * half nodes u_i + 1/(2N). The RMF by double reflection (Wang, Juttler, Zheng, Liu 2008) on
 * the 2N half steps; M by N steps of Magnus-4 on the Simpson nodes (u_i, u_i + h/2, u_i + h),
 * in increment form. Both are order 4; MATH-spine 9.3 gives the error constants (error ~
 * C / N^4 mm): helix tube 37.2, Bezier blend 0.47, tilted arc ~0, pipe 0.10; the float32
 * floor is 3-8e-6 mm (about 1 ulp of coordinates up to 100 mm). Choose N by that table (or
 * by step doubling: the model's job, not this kernel's).
 *
 * Conventions (the same as tests/ref_spine.h, which judges this kernel):
 *   - u in [0, 1] is the normalized spine parameter; every length in mm, angles in radians.
 *   - N1(0) = the unit projection of the reference vector ref onto the plane normal to T(0);
 *     ref = (0, 0, 0) selects the principal normal c_uu - (c_uu.T)T at u = 0.
 *   - n points AWAY from the spine. An offset off gives c + (R + off) n: off = +r is the
 *     ball-end centre of an OUTSIDE tool, off = -r of an INSIDE tool (fillet, bore).
 *
 * Memory: struct spine is the whole context (<= 320 B in the float build, checked by a static
 * assert); no allocation, no table: the march keeps only the current node. spine_node(i)
 * goes forward from the current node, or restarts from u = 0 when i is behind it;
 * spine_node_back(i) is the backward pass (forward to u = 1 once, then back) that the
 * backward lines of a zigzag use. Each pass is one fixed sequence of steps, so a node's
 * state depends only on (pass, node): seeks and resumes are bit for bit.
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
#define SPINE_NSTEPS_MAX 1024u      /* transport steps N (2N double reflections) */
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
    struct cp_vec3 c, cu, cuu;
    cp_real r, ru, ruu;
};

/* The context: the validated configuration and the march's current node. Read-only for the
 * caller; changed by spine_init and spine_node only. */
struct spine {
    uint8_t kind, law;
    uint16_t nsteps;    /* N */
    uint16_t node;      /* the march's current node i (0..N) */
    uint8_t back;       /* 1: node reached by a backward pass (spine_node_back), 0: forward */
    cp_real sp[12];     /* copy of the spine parameters */
    cp_real rp[4];      /* copy of the law parameters */
    struct cp_vec3 e1;  /* ARC, HELIX: unit in-plane start direction */
    struct cp_vec3 e2;  /* ARC, HELIX: ax x e1 */
    struct cp_vec3 ax;  /* ARC: unit normal; HELIX: unit axis */
    struct cp_vec3 n10; /* N1(0), unit, normal to T(0) */
    cp_real rmin, rmax; /* min and max of R over the init samples, mm */
    cp_real amax;       /* max |a| over the init samples (< 1) */
    /* the march at node `node`: */
    struct cp_vec3 x;   /* c(u_i) */
    struct cp_vec3 t;   /* unit T(u_i) */
    struct cp_vec3 r;   /* N1 carried by double reflection (renormalized at output only) */
    cp_real m[4];       /* transport M = [[m0, m1], [m2, m3]] */
    cp_real a0[2];      /* A~(u_i) = [[-a0[0], a0[1]], [a0[1], a0[0]]] */
    struct spine_jet j; /* the jet at u_i (the step's last evaluation, reused by the fill) */
};

/* Everything a point at node u_i needs (spine_node fills it; shared by all lines there). */
struct spine_state {
    cp_real u;           /* u_i = i / N */
    uint16_t node;       /* i */
    struct cp_vec3 c;    /* c(u_i), mm */
    struct cp_vec3 t;    /* unit tangent T */
    struct cp_vec3 n1;   /* RMF N1: unit, normal to T */
    struct cp_vec3 n2;   /* T x N1 */
    cp_real r;           /* R(u_i), mm (> 0) */
    cp_real a, b;        /* dR/ds (|a| < 1) and sqrt(1 - a^2) */
    cp_real as;          /* da/ds, 1/mm */
    cp_real k1, k2;      /* T' = k1 N1 + k2 N2 (per mm of arc) */
    cp_real m[4];        /* transport M(u_i), det = 1 up to rounding */
    /* shared by every point at this node: n = at + cos(theta) bn1 + sin(theta) bn2 */
    struct cp_vec3 at;   /* -a T */
    struct cp_vec3 bn1;  /* b N1 */
    struct cp_vec3 bn2;  /* b N2 */
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
 *                      |c_u| <= 1e-5 (1 + max |sp[i]|) at a half node u = k / (2N) or at
 *                      u = k / SPINE_CHECK_N (LINE with P0 = P1, Bezier cusp or coincident
 *                      control points; a cusp strictly between samples is not seen)
 *   CP_ERR_RADIUS      R <= 0 at a sample (the half nodes and u = k / SPINE_CHECK_N)
 *   CP_ERR_RANGE       |a| = |R_u| / |c_u| >= 1 at a sample (the half nodes, i.e. the nodes
 *                      and the Simpson midpoints where the transport evaluates A~, and
 *                      u = k / SPINE_CHECK_N). Proposed for its own code (CP_ERR_SLOPE), see
 *                      the report of issue 18.
 *   CP_ERR_FRAME_REF   ref non-zero and its projection on the normal plane at u = 0 is
 *                      <= 1e-4 |ref| (ref along T(0))
 *   CP_ERR_FRENET      ref zero and the principal normal at u = 0 is <= 1e-4 |c_u|^2 (a LINE,
 *                      or a spine straight or inflecting at its start)
 * D != 0 (regularity, spine_regularity) is NOT checked here: it depends on the lines and the
 * tool offset, and is the iterator's check. Returns CP_OK. On error *s is unusable. */
int spine_init(struct spine *s, const struct spine_cfg *cfg, uint16_t nsteps) CP_MUST_CHECK;

/* The jet of the spine and the law at u (meaningful for u in [0, 1]): c, c_u, c_uu (mm per
 * unit u), R, R_u, R_uu. One cp_sincos for ARC and HELIX, one for the COS law. Cannot fail. */
void spine_jet(const struct spine *s, cp_real u, struct spine_jet *j);

/* Bring the march to node i (0 <= i <= N) and fill *st. Forward from the current node (cost
 * (i - node) steps: 2 jets, 2 double reflections, 1 Magnus step each), or restarts from u = 0
 * when i < node (cost i steps). CP_ERR_RANGE if i > N or st NULL (nothing changed);
 * CP_ERR_NUMERIC if a non-finite value appeared (cannot happen after a successful init with
 * finite arithmetic; kept as the iterator's guard). Returns CP_OK. */
int spine_node(struct spine *s, uint16_t i, struct spine_state *st) CP_MUST_CHECK;

/* The backward pass: bring the march to node i as reached from node N by backward steps
 * (sp_step inverted: the same truncation error as the forward march in exact arithmetic,
 * only the rounding differs). From a forward state the march first goes on to N (cost
 * N - node steps, once per pass), then back (node - i steps); a backward state ahead of i
 * steps back, one behind i restarts (i = N is the forward state at N). Errors as
 * spine_node. */
int spine_node_back(struct spine *s, uint16_t i, struct spine_state *st) CP_MUST_CHECK;

/* The label of the line theta0 (radians, any finite value; |theta0| <= 1e5 in the float
 * build): one cp_sincos(theta0 / 2). Lines theta0 and theta0 + 2 pi are the same line. */
void spine_label(cp_real theta0, struct spine_label *lab);

/* The family-2 line with label lab at the node of st: pt->p = c + (R + off) n, pt->n = n
 * (unit, away from the spine), pt->t = u. line and index are not written. off in mm, |off|
 * < R for an inside tool (the caller's check). No trigonometry: y = M y0, then one division.
 * Rounding only (beyond the march): a few ulp of |c| + R. */
void spine_point_label(const struct spine_state *st, const struct spine_label *lab, cp_real off,
                       struct raster_pt *pt);

/* The same with the label made here from theta0 (one cp_sincos). */
void spine_point(const struct spine_state *st, cp_real theta0, cp_real off, struct raster_pt *pt);

/* The family-1 circle at the node of st, at angle theta in the transported frame (N1, N2)
 * (NOT a line label): one cp_sincos(theta). pt as for spine_point. */
void spine_circle_point(const struct spine_state *st, cp_real theta, cp_real off,
                        struct raster_pt *pt);

/* The angle of the line lab at st's node as (cos theta, sin theta), exact rational form. */
void spine_angle(const struct spine_state *st, const struct spine_label *lab, cp_real *ct,
                 cp_real *sn);

/* Regularity D = b^2 - (R + off)(a_s + b (k1 cos theta + k2 sin theta)) of the surface offset
 * by off, at angle (ct, sn) (MATH-spine 3.3, 8): the Jacobian is (R + off)|D|; D = 0 on a
 * cuspidal edge. A regular patch keeps D > 0 (the iterator's check, CP_ERR_CUSP). */
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
 * Every point is (node, label): the march of struct spine to a node, then one cp_sincos (the
 * label) and spine_point_label. The march nodes: N = q steps (LINES) or q (n - 1)(link + 1)
 * (CIRCLES, q rounded up to even), q >= 1 the least integer with N >= SPINE_PATH_NMIN (the march's accuracy,
 * MATH-spine 9.3: 32 nodes keep the helix tube, C = 37.2, at 3.5e-5 mm before float
 * rounding), N <= SPINE_NSTEPS_MAX (else CP_ERR_TOO_MANY).
 * Cost: q march steps per point (each 2 jets + 2 double reflections + 1 Magnus step); the
 * odd (backward) lines of LINES and their links run spine_node_back: one backward step per
 * node, the forward march on to u = 1 done by the line before. A seek costs at most one
 * restart plus the march to the point's node (2N steps for a point on a backward line).
 * Output: SURFACE the surface point m; CENTRE the ball-end centre m - r n (inside tool: the
 * canal surface of radius R - r, n points away from the spine); TIP that centre - r z.
 * Checked at init (before the first point), in this order: spine_init's codes; raster_check's
 * (raster.h); labels != ANGLE or span != LINES CP_ERR_INVAL; steps == 0: the steps from tol
 * by raster_fit (start 16, pilot, aim 0.8 tol, accept 0.9 tol) on the sagitta estimate
 * |P(i-1) - 2 P(i) + P(i+1)| / 8 of the emitted points of every line (each marched from
 * u = 0: n N march steps per walk) or circle, CP_ERR_TOL when N would exceed
 * SPINE_NSTEPS_MAX (measured against ref_spine: the worst chord 0.57-0.84 tol, test_spine
 * spine_path_tol); link == RASTER_LINK_AUTO: LINES derive it
 * from tol (1 um when tol = 0) by the exact on-circle sagitta of the link chords (the least
 * link meeting it, CP_ERR_TOL above CP_MAX_LINK); CIRCLES derive it with the steps in the
 * same raster_fit walks from the exact midpoint sagitta of every link segment on the lines
 * u0 and u1 (CIRCLES keep q even, >= 2, so those midpoints are march nodes: (n - 1)(link
 * + 1) <= SPINE_NSTEPS_MAX / 2);
 * N > SPINE_NSTEPS_MAX CP_ERR_TOO_MANY; tool_r >= the min R of spine_init's samples
 * CP_ERR_TOOL; then one forward march over all N nodes: at every node and every label of the
 * patch (the streamed lines and link labels; CIRCLES: the steps + 1 labels) the regularity D
 * of the surface (off = 0) and of the tool-centre surface (off = -r) must be > 0, else
 * CP_ERR_CUSP (a cusp strictly between nodes or labels is not seen); CP_ERR_NUMERIC for a
 * non-finite march. */
#define SPINE_PATH_NMIN 32u

struct spine_path {
    struct raster_head head; /* mode, n, steps, link, count, k (raster.h) */
    uint8_t output;          /* enum raster_output */
    uint16_t q;              /* march nodes per raster node step */
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
