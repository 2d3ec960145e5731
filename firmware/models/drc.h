/* drc.h - discretely represented curves (seed 001): DRC-EXP thickening and its toolpaths.
 * SPDX-License-Identifier: MIT
 *
 * A few points P_0..P_{N-1} (N = 3..CP_MAX_DRC_POINTS, mm, planar or 3D) are thickened
 * pass by pass, N -> 2N - 1 (originals kept at even indices), so that the discrete
 * curvature changes regularly and never oscillates: the algorithm DRC-EXP of
 * ../shared/docs/MATH-seeds-2-3-4.md part A.2 (it overrides the paper).
 *
 *   step 0  chords d_i, adjoining-plane normals n_j (oriented consistently), signed
 *           turning phi_j, discrete curvature ks_j (3-point circle) and AP-dihedral
 *           torsion tau_i (correction A2); the rejections of A.3.
 *   step 1  tangent assignment, once: angle a_j = t_j phi_j of the tangent at vertex j
 *           from chord j, t_j in [0, 1] (the tangent lies inside the chord angle);
 *           G2 of the exponential-curvature segment model at every vertex by a
 *           DRC_T_BISECT-step bisection per vertex, DRC_SWEEPS Gauss-Seidel sweeps;
 *           end tangents from the neighbour's curvature ratio (N >= 4) or the circle
 *           (N = 3); 3D: the A3 tilt chi out of the adjoining plane.
 *           End tangents (spec clarification, issue 6 B1): the N >= 4 end angle
 *           a_0 = b_0 / r(q*) of A.2 is bounded by the neighbour vertex's turn,
 *           |a_0| <= |phi_1| (mirrored: |b_{N-2}| <= |phi_{N-2}|). A steep ratio next to
 *           a short chord would otherwise turn the end tangent past 90 deg (the curve
 *           looped behind P_0). The bound keeps every tangent < 90 deg from its chords
 *           and the end segment convex; circles are untouched (there a_0 = b_0 <= phi_1).
 *           tests/ref_drc.c implements the same rule.
 *           3D (issue 21, docs/DRC-TORSION.md): then every interior tangent is tilted
 *           until the intrinsic arcs (step 2) on both sides share the osculating plane.
 *   step 2  one pass acts on every segment (A, B, T_A, T_B) independently: closed
 *           form (planar: real exponential model, q by bisection) or, 3D, the intrinsic
 *           arc (exponential curvature, constant torsion, 16 exact helical pieces) fitted
 *           by Newton from the twisted exponential model's guess (complex z by
 *           DRC_NEWTON damped Newton steps). The arc family is closed under halving, so
 *           no inserted point kinks the osculating plane and the discrete torsion does
 *           not grow with the passes (it doubled per pass with the twisted model alone).
 * Because step 2 is per segment, K passes over one original segment are a binary
 * subdivision tree of depth K: the iterator streams it leaf by leaf with an explicit
 * stack of K nodes (stk[], no buffer of the final size), and drc_thicken() does one
 * whole pass in place for hosts and tests. Both call drc_insert(): the streamed
 * points equal the in-place ones bit for bit (tests/test_drc.c).
 *
 * Every count above is fixed (double build: the counts of A.2; float build: the
 * counts at which float precision is exhausted, see DRC_Q_BISECT). Nothing
 * allocates, nothing recurses; the only transcendental calls are cp_exp,
 * cp_sincos and cp_atan2 (cp_math.h: deterministic float kernels).
 *
 * Toolpaths (SURFACE DRC, docs/PROTOCOL.md, job_drc.c):
 *   CURVE mode (edge = 0): the thickened curve itself, one line of
 *     2^K (N - 1) + 1 points; pt.n = the unit tangent of the DRC model. Planar only
 *     (z = 0 everywhere, else CP_ERR_OFF_PLANE): see "Footprint".
 *   EDGE mode (edge = 1): a fillet along the sketched edge. The (planar, z = 0) DRC
 *     curve is the contact curve C of a canal surface (canal.h) whose radius is the
 *     raster's RADIUS law over the normalised arc length sigma in [0, 1] of the
 *     thickened polyline; the family-2 curvature lines of LINES n u0 u1 are streamed
 *     zigzag with link points on the end circles, exactly like RASTER_LINES;
 *     pt.n = the unit surface normal. Lambda = integral kappa dR is summed over the
 *     thickened points (drc.c, rule and error bound there).
 *
 * Footprint: the stream uses only the planar
 * core (validation, tangent assignment, planar insertion) and the iterator, ~5.5 KB of
 * M4F flash with job_drc.c (was ~10.2 KB). The 3D extension (adjoining-plane normals,
 * the twist rejection, the A3 tilt and the osculating-plane solve, the intrinsic arc with
 * its twisted-model guess, ~4.5 KB: docs/DRC-TORSION.md) and the A.4
 * measures stay in this library, compiled and tested on the host and in the M4F unit
 * image, but the stream does not reference them, so --gc-sections drops them from the
 * firmware image: a 3D point set is CP_ERR_OFF_PLANE at RUN (error:25). Other trade-offs:
 * the iterator keeps pointers to the geometry and the raster (no copies: less RAM and
 * code; both must outlive the run, as struct job does); one point routine serves init's
 * verification walk, next and seek; link points are uniform in contact-frame angle on
 * the end circle (their count exact for the chord tolerance, no lerp correction); the
 * CONST/LINEAR/CUBIC radius laws are one power-basis cubic; the raster is checked by
 * raster_check (raster.h, the codes of every model), and a non-finite sum of the radius
 * parameters is one CP_ERR_NONFINITE (huge finite values that overflow included).
 */
#ifndef DRC_H
#define DRC_H

#include "canal.h"
#include "raster.h"

/* Fixed iteration counts of A.2. The double build uses the published counts. The float
 * build stops where float precision is exhausted: a bisection halves a bracket of 98 (q)
 * or 1 (t) 30 / 28 times, leaving 9e-8 / 4e-9, below the float resolution of what is
 * bracketed; the Gauss-Seidel sweeps contract by ~0.35 per sweep (measured on the test
 * sets: tangent change 4e-7 after 12 sweeps, 2e-8 after 15), so 16 sweeps are at the
 * float floor. */
#if CP_REAL_DOUBLE
#define DRC_Q_BISECT 64 /* r^-1: bisection steps for q on [-DRC_Q_MAX, DRC_Q_MAX] */
#define DRC_T_BISECT 60 /* tangent parameter t_j on [0, 1], per vertex and sweep */
#define DRC_SWEEPS 40   /* Gauss-Seidel sweeps over the vertices */
#else
#define DRC_Q_BISECT 30
#define DRC_T_BISECT 28
#define DRC_SWEEPS 16
#endif
#define DRC_NEWTON 30   /* damped Newton steps of the 3D twisted model */
#define DRC_Q_MAX CP_R(49.0)

/* The exact 0 of an angle (issue 21): THE tolerance of every decision A.2 takes at an exact
 * 0 of an angle, in this file's code and in tests/ref_drc.c alike:
 *   step 0  a collinear vertex (turn 0: the tangent inherits the chords' line, G2 skipped):
 *           |sin turn_j| <= zero(chord j-1) + zero(chord j);
 *   step 1  the "end value" of the G2 bisection (no sign change on [0, 1]: the tangent on a
 *           chord): t_j phi_j within zero(chord j) is t_j = 0, (1 - t_j) phi_j within
 *           zero(chord j-1) is t_j = 1; an end angle within zero(end chord) is 0. The segment
 *           model's branches (a b > 0, exactly one zero) then see exact zeros: a bracket of
 *           2^-DRC_T_BISECT (float 4e-9, double 9e-19) is no zero;
 *   step 2  an end angle within zero(chord) is 0 (linear model), both builds and the judge.
 * zero(chord A-B) = DRC_ANGLE_ZERO (1 + (|A| + |B|)/c), c = |B - A|, |.| the max-abs
 * coordinate. Why: step 2 is discontinuous at a zero end angle (both end angles of one turn
 * take the exponential model, one angle 0 the linear one; they differ by O(the other angle x
 * chord)), and the zeros are structural: a tangent on its chord (collinear runs, G2 given up
 * next to an inflection) and, once there is one, every child at M of a segment with a zero
 * end (its angle there is -theta_A / 2 exactly, bit for bit in drc.c's insert). Computed,
 * such an angle is rounding noise: the chord direction d = (B - A)/c carries
 * <= 2 sqrt(3) eps (|A| + |B|)/c from the stored points, the tangent <= 4 eps (its rotation
 * and sincos), atan2 <= 4 eps: <= (8 + 4 (|A| + |B|)/c) eps in all, eps = 2^-24 in float.
 * DRC_ANGLE_ZERO = 16 eps makes zero() >= 2x that bound, so no structural zero is missed
 * in float; the double build and the references use the same float-sized zero, so every
 * build decides alike (tests: drc_judge_property, 1000 random sets vs a long double
 * recomputation). Cost: a genuine angle below zero() (9.5e-7 rad on a chord as long as the
 * coordinates, 1e-3 rad on a 0.05 mm leaf at 50 mm from the origin) takes the linear
 * model; near that threshold the float build's decision follows its rounding (measured:
 * 0 of 1000 random sets affected beyond host_sim's limits). */
#define DRC_ANGLE_ZERO CP_R(9.5367431640625e-7) /* 2^-20 = 16 x 2^-24 */

/* Points closer than this fraction of the bounding-box size D are coincident
 * (A.3: 1e-12 D in double; the float build cannot resolve less than ~1e-6 D). */
#if CP_REAL_DOUBLE
#define DRC_COINCIDENT_REL 1.0e-12
#else
#define DRC_COINCIDENT_REL 1.0e-6f
#endif

/* Largest final point count of one curve: 2^CP_MAX_PASSES (CP_MAX_DRC_POINTS - 1) + 1. */
#define DRC_MAX_OUT ((((uint32_t)1u) << CP_MAX_PASSES) * (CP_MAX_DRC_POINTS - 1u) + 1u)

/* A point of a thickened curve: position (mm) and unit tangent. */
struct drc_pt {
    struct cp_vec3 p;
    struct cp_vec3 t;
};

/* The geometry of a DRC job (union path_geom member; lives in struct job for the
 * whole run, the iterator keeps a const pointer to it). */
struct drc_cfg {
    /* the curve */
    uint8_t n;      /* points given, 0..CP_MAX_DRC_POINTS (>= 3 at init) */
    struct cp_vec3 p[CP_MAX_DRC_POINTS]; /* the points, mm, |coordinate| <= CANAL_COORD_MAX */
    uint8_t passes; /* K, 0..CP_MAX_PASSES; DRC_PASSES_AUTO = derive from raster tol */
    /* what is streamed */
    uint8_t edge;   /* 0: the curve itself (CURVE mode); 1: fillet along it (EDGE mode) */
    /* EDGE mode only (not read with edge == 0): the fillet's radius law over the arc-length
     * fraction sigma in [0, 1] of the thickened curve, as the canal's RADIUS (canal.h):
     *   radius  enum canal_radius_kind: CANAL_R_CONST, CANAL_R_LINEAR, CANAL_R_COS or
     *           CANAL_R_CUBIC (CANAL_R_* above CUBIC: CP_ERR_INVAL)
     *   rp      its parameters, mm (COS: b, c, k with R = b + c cos(k sigma)); finite, each
     *           |rp[i]| <= CANAL_COORD_MAX, R(sigma) > 0 on [0, 1] (else CP_ERR_RADIUS) */
    uint8_t radius;
    cp_real rp[4];
};

#define DRC_PASSES_AUTO 0xFFu

/* The streaming iterator (struct path's union). */
struct drc_path {
    struct raster_head head;          /* mode (RASTER_LINES, the only one), n (lines), steps
                                         (2^K (N-1)), link, count, k (raster.h) */
    /* the request (not copied: both must outlive the run) */
    const struct drc_cfg *g;          /* the geometry */
    const struct raster_cfg *rc;      /* the raster */
    /* the thickened curve */
    uint8_t edge;                     /* 0 CURVE mode, 1 EDGE mode (g->edge) */
    uint8_t passes;                   /* K in use (AUTO: the one found at init) */
    uint8_t nseg;                     /* original segments, N - 1 */
    struct cp_vec3 tan[CP_MAX_DRC_POINTS]; /* step 1: unit tangents at the original points */
    cp_real s_tot, lam_tot;           /* at the last point (forward walk) */
    cp_real kend[2];                  /* curvature of the first / last leaf (end circles) */
    /* the EDGE fillet */
    cp_real rp[4];                    /* radius law: COS b c k, else power-basis cubic (mm) */
    cp_real q0;                       /* sqrt(1 + (dR/ds)^2) at P_0 (labels) */
    /* the walk (the stream's position along a line) */
    int32_t line;                     /* line of the walk (-1: none) */
    uint8_t dir;                      /* walk direction: 0 P_0 -> P_{N-1}, 1 backward
                                         (EDGE: odd lines, zigzag) */
    uint32_t pos;                     /* walk position along the line, 0..steps */
    cp_real lab_a, lab_b;             /* label of the walk's line */
    cp_real s, lam, r_cur, kap;       /* walk: arc length, Lambda, R, last leaf's curvature */
    struct drc_pt cur;                /* the point of the walk */
    struct drc_pt stk[CP_MAX_PASSES]; /* stk[d - 1]: far end of the depth-d interval */
};

/* Size of K passes over n points: 2^K (n - 1) + 1, in *need.
 * Errors: CP_ERR_TOO_FEW n < 3, CP_ERR_TOO_MANY K > CP_MAX_PASSES. */
CP_MUST_CHECK int drc_size(uint32_t n, uint32_t passes, uint32_t *need);

/* Steps 0 and 1 on n points p[i * ps] (i < n): validate and write the unit tangents
 * t[i * ts]. Strides are in struct cp_vec3 units (a struct drc_pt array: ps = ts = 2).
 * Errors (nothing written), A.3:
 *   CP_ERR_TOO_FEW    n < 3
 *   CP_ERR_TOO_MANY   n > CP_MAX_DRC_POINTS
 *   CP_ERR_NONFINITE  a coordinate NaN/Inf
 *   CP_ERR_RANGE      |coordinate| > CANAL_COORD_MAX
 *   CP_ERR_COINCIDENT a chord <= DRC_COINCIDENT_REL D (D = bounding-box diagonal)
 *   CP_ERR_TURN       a turning angle >= 90 deg (d_{j-1} . d_j <= 0)
 *   CP_ERR_TWIST      |dihedral of consecutive oriented adjoining planes| >= 45 deg
 * All-collinear input is not an error (straight tangents). Returns CP_OK. */
CP_MUST_CHECK int drc_tangents(const struct cp_vec3 *p, unsigned ps, struct cp_vec3 *t,
                               unsigned ts, uint32_t n);

/* 1 if every position and tangent has z == 0 exactly (the planar closed form is used),
 * else 0. */
int drc_is_planar(const struct drc_pt *buf, uint32_t n);

/* Step 2 on one segment: the new point m between a and b (planar: 1 = the real model,
 * requires z == 0 everywhere; 0 = the 3D intrinsic arc, docs/DRC-TORSION.md). Cannot
 * fail: the inputs come from drc_tangents or an earlier pass (chord > 0, tangent angles
 * < 90 deg; the end angle bound above keeps that true for every planar set drc_tangents
 * accepts).
 * Tangent-triangle containment of m holds for convex segments (end angles of one turn,
 * ratio within r(+-DRC_Q_MAX) ~ 1:48, where q is not clamped). A segment with an
 * inflection or exactly one end angle on the chord (next to an inflection or a collinear
 * run, where G2 was given up) takes the linear-curvature model of A.2, an S-curve by
 * construction: its point lies off the (degenerate) triangle, as specified. */
void drc_insert(const struct drc_pt *a, const struct drc_pt *b, int planar, struct drc_pt *m);

/* One pass in place: buf[0..n-1] (positions and tangents, e.g. from drc_tangents) ->
 * buf[0..2n-2], originals at even indices. cap = capacity of buf in points.
 * *n_out = 2n - 1 (also on CP_ERR_BUFFER: the size needed).
 * Errors: CP_ERR_TOO_FEW n < 2, CP_ERR_BUFFER cap < 2n - 1 (buf unchanged). */
CP_MUST_CHECK int drc_thicken(struct drc_pt *buf, uint32_t n, uint32_t cap, uint32_t *n_out);

/* Steps 0-2: n points in buf[].p -> tangents, then `passes` passes in place.
 * *n_out = 2^passes (n - 1) + 1 (the size needed, also on CP_ERR_BUFFER).
 * Errors: drc_size, drc_tangents codes, CP_ERR_BUFFER cap < *n_out (nothing written). */
CP_MUST_CHECK int drc_run(struct drc_pt *buf, uint32_t n, uint32_t passes, uint32_t cap,
                          uint32_t *n_out);

/* ---- discrete characteristics and the measures of A.4 (any polyline) ---- */

/* Curvature of the circle through a, b, c (1/mm): 2 sin(turn at b) / |c - a|, signed
 * by +z (left turn > 0) when sgn != 0, else >= 0. 0 for collinear or coincident. */
cp_real drc_kappa3(const struct cp_vec3 *a, const struct cp_vec3 *b, const struct cp_vec3 *c,
                   int sgn);

/* AP-dihedral torsion of chord b->c (A2): angle(AP(a,b,c), AP(b,c,d)) / |c - b|,
 * signed, 1/mm. 0 when an adjoining plane is undefined. */
cp_real drc_tau4(const struct cp_vec3 *a, const struct cp_vec3 *b, const struct cp_vec3 *c,
                 const struct cp_vec3 *d);

struct drc_measures {
    uint32_t extrema;      /* strict local extrema of k_1..k_{n-2} (steps < 1e-6 max|k| ignored) */
    uint32_t signs;        /* sign changes of k (|k| <= 1e-6 max|k| counts as 0 and is skipped) */
    uint32_t between;      /* odd i (the last pass's new points): k_i outside [min, max] of
                              k_{i-1}, k_{i+1} by more than 1e-6 max|k| */
    uint32_t t_extrema;    /* extrema of tau_2..tau_{n-4} (interior chords), 3D */
    cp_real kmin, kmax;    /* range of k over i = 1..n-2 */
    cp_real tmin, tmax;    /* range of tau over the interior chords (0 if none) */
};

/* Measures of A.4 on the polyline p[0..n-1] (n >= 3): curvature signed by +z when
 * sgn != 0 (planar data). The oscillation count of a method is
 * extrema(output) - extrema(input); new sign changes likewise.
 * Errors: CP_ERR_TOO_FEW n < 3. */
CP_MUST_CHECK int drc_measure(const struct cp_vec3 *p, uint32_t n, int sgn,
                              struct drc_measures *m);

/* Tangent-triangle containment (2D): 1 if m lies in the closed triangle of a, b and the
 * intersection of the tangent lines at a and b (or on the chord when the tangents are
 * parallel to it), with a relative slack of 1e-9 (double) / 1e-5 (float) of |b - a|. */
int drc_in_triangle(const struct drc_pt *a, const struct drc_pt *b, const struct cp_vec3 *m);

/* ---- the streaming iterator (path.h) ---- */

/* Validate g (drc_tangents codes, planar only) and the raster, fix the counts, walk once.
 * The iterator keeps g and raster by pointer: both must stay unchanged and alive until
 * the last next/seek.
 * K = g->passes, or with DRC_PASSES_AUTO the smallest K whose leaf sagitta (measured on
 * the thickened curve, and in EDGE mode on every streamed line) is <= raster->tol.
 * raster fields used: CURVE mode: tol (AUTO only); EDGE mode: n, u0, u1 (ANGLE labels
 * only), link, tol, output, tool_r; and g->radius, g->rp (the radius law over sigma). Every
 * raster is checked as for the other models (raster_check, in CURVE mode too), in this
 * order: g NULL or edge out of range, raster_check (INVAL, NONFINITE, RANGE, TOO_MANY,
 * TOOL), passes, the radius parameters, the EDGE extras, then the points.
 * EDGE mode needs a RADIUS (job.c job_ready: EDGE ON without RADIUS is an incomplete
 * job, error:10); without LINES the raster default applies: one line at u = 0 (the
 * contact curve C itself, where the fillet meets the plane).
 * Errors: the drc_tangents codes, plus
 *   CP_ERR_INVAL      g or raster NULL, edge/mode/output out of range, tool with
 *                     OUT_SURFACE; EDGE: labels not ANGLE, mode not LINES, a radius law
 *                     other than CONST/LINEAR/COS/CUBIC, a tool output with tool_r == 0
 *   CP_ERR_NONFINITE  u0, u1, tol, tool_r or a radius parameter NaN/Inf (or their sum)
 *   CP_ERR_TOO_MANY   passes > CP_MAX_PASSES, n > CP_MAX_LINES, steps > CP_MAX_STEPS
 *                     (the raster's, unused), 2^K (N-1) > CP_MAX_STEPS
 *   CP_ERR_RANGE      |u| > pi, u0 == u1 with n > 1, n == 0, tol != 0 out of [1e-5, 10],
 *                     tol == 0 with steps == 0 or with AUTO passes, link > CP_MAX_LINK
 *   CP_ERR_OFF_PLANE  a point off z = 0 (the stream is planar: "Footprint")
 *   CP_ERR_RADIUS     EDGE: R <= 0 at a point (or radius parameters out of range)
 *   CP_ERR_TOOL       tool_r < 0; EDGE: tool_r >= min R
 *   CP_ERR_TOL        AUTO: the tolerance needs more than CP_MAX_PASSES passes, or a link
 *                     more than CP_MAX_LINK points
 *   CP_ERR_CUSP       EDGE: a streamed point on or beyond a cuspidal edge (every point,
 *                     a line's first point and the link points included, with the
 *                     curvature of the end leaf there)
 *   CP_ERR_NUMERIC    a non-finite value in the walk, or a zero chord over two steps (a
 *                     line doubling back: its sagitta is undefined)
 * Returns CP_OK; then drc_path_next yields exactly drc_path_count() points. */
CP_MUST_CHECK int drc_path_init(struct drc_path *it, const struct drc_cfg *g,
                                const struct raster_cfg *raster);

/* The checks of drc_path_init (and drc_tangents) that need one point alone, the same code
 * for the same fault: per coordinate x, y, z CP_ERR_NONFINITE or CP_ERR_RANGE
 * (|coordinate| > CANAL_COORD_MAX), then with planar != 0 (the stream's data)
 * CP_ERR_OFF_PLANE for z != 0. The protocol's POINT calls it (planar). Returns CP_OK. */
CP_MUST_CHECK int drc_point_check(const struct cp_vec3 *q, int planar);

/* Points drc_path_next yields in all (n lines of steps + 1 points, n - 1 links of
 * link points); 0 until drc_path_init succeeded. */
uint32_t drc_path_count(const struct drc_path *it);

/* Next point (raster_pt conventions: line j or -1 for a link point, index).
 * Returns CP_OK, CP_ERR_DONE, or CP_ERR_NUMERIC for a non-finite point (nothing
 * written, the position unchanged; init has walked every point, so not expected). */
int drc_path_next(struct drc_path *it, struct raster_pt *pt);

/* Restart at point k (0 <= k <= count), bit for bit. CURVE mode: descends the tree
 * along the bits of the index (K inserts) at the next next(). EDGE mode: Lambda and the arc length are
 * sums along the line, so the walk restarts at the line's first point and re-walks
 * (at most steps inserts). Returns CP_OK or CP_ERR_RANGE. */
CP_MUST_CHECK int drc_path_seek(struct drc_path *it, uint32_t k);

#endif /* DRC_H */
