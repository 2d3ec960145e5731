/* raster.h - what every surface model shares: the raster vocabulary (the request struct
 * raster_cfg, the streamed point struct raster_pt, the mode/labels/span/output enums and
 * struct raster_head, the head of every model iterator) and the raster plumbing (the checks
 * of a raster request, the zigzag layout of its points, the restart position, and the
 * search for step/link counts that meet a chord tolerance).
 * SPDX-License-Identifier: MIT
 *
 * A raster (struct raster_cfg) is n lines (or rings) of steps + 1 points
 * each, zigzag (odd lines run backwards), consecutive lines joined by `link` points:
 *
 *   block j (j = 0..n-1) = line j (steps + 1 points) + the link j -> j + 1 (link points,
 *   none after the last line);  count = n (steps + 1) + (n - 1) link.
 *
 * Users: the model iterators canal_path.c, gsr.c, channel.c, drc.c, plane.c (*_path_*), path.c. What a line is, where a point lies and how a sagitta is measured stay
 * in the models; this module only does the integer and control-flow parts, so every
 * model keeps its own geometry and every function here is small and cannot loop.
 *
 * No function pointers (tools/stack.sh follows the call graph): the tolerance search is
 * a state (struct raster_fit) the model's init drives from its own loop, a walk of its
 * stream between two calls:
 *
 *     raster_fit_begin(&fit, cfg, &rule);
 *     for (round = 0; round <= RASTER_FIT_ROUNDS; round++) {
 *         set steps = fit.m[0], link = fit.m[1] - 1; walk the stream -> sag[2] (or error)
 *         err = raster_fit_update(&fit, sag);
 *         if (err != RASTER_FIT_MORE) break;        (CP_OK: counts final; CP_ERR_TOL)
 *     }
 *
 * raster_fit_update never answers RASTER_FIT_MORE after round RASTER_FIT_ROUNDS, so that
 * loop always ends with CP_OK or CP_ERR_TOL (at most RASTER_FIT_ROUNDS + 1 walks).
 *
 * Units: tol and sagittas in mm, u0/u1 as the model labels its lines (radians for every
 * model but the canal's lambda labels). No state outside the caller's structs.
 */
#ifndef RASTER_H
#define RASTER_H

#include "cp_math.h"

/* ---- the vocabulary of every model ---- */

/* What the lines of a raster are. */
enum raster_mode {
    RASTER_LINES = 0,  /* lines along the surface (canal: family-2 curvature lines), linked
                          along the rings */
    RASTER_CIRCLES = 1 /* rings across it (canal: family-1 characteristic circles), linked
                          along the lines */
};

/* How u0, u1 label the lines (the canal's choice; every other model: ANGLE). */
enum raster_labels {
    /* canal: contact-frame start angle on the first circle, radians, |u| <= pi */
    RASTER_LABEL_ANGLE = 0,
    /* canal: w = lambda(t0) = q0 cot(u0/2), dimensionless, |w| <= 1e4 (C itself is w = inf) */
    RASTER_LABEL_LAMBDA = 1
};

/* What bounds the circles of RASTER_CIRCLES (the canal's choice; every other model: LINES). */
enum raster_span {
    /* the lines that start at u0 and u1: the same patch as LINES */
    RASTER_SPAN_LINES = 0,
    /* canal: the fixed contact-frame angles u0..u1 on every circle; links run along
     * u = const (labels must be ANGLE) */
    RASTER_SPAN_ANGLE = 1
};

/* Output of each point. */
enum raster_output {
    RASTER_OUT_SURFACE = 0, /* the surface point m (no tool) */
    RASTER_OUT_CENTRE = 1,  /* ball-end tool centre m - r_tool n (5-axis, robots) */
    RASTER_OUT_TIP = 2      /* ball-end tool tip: centre - r_tool z (3-axis) */
};

/* link: derive the link points from tol (or from 1 um when tol == 0). */
#define RASTER_LINK_AUTO 0xFFFFu

/* The raster request of a run, the same for every model (the model's geometry is its own
 * struct: canal_cfg, gsr_cfg, channel_cfg, drc_cfg). Plain data; checked by raster_check
 * and the model's init. */
struct raster_cfg {
    /* which lines */
    uint8_t mode;      /* enum raster_mode */
    uint8_t labels;    /* enum raster_labels (default ANGLE; LAMBDA: canal only) */
    uint8_t span;      /* enum raster_span, CIRCLES only (default LINES; ANGLE: canal only) */
    uint16_t n;        /* lines (LINES) or circles/rings (CIRCLES), 1..CP_MAX_LINES */
    cp_real u0, u1;    /* bounding lines: start angles on the first circle, radians, |u| <= pi
                          (or lambda labels, see labels); u0 == u1 allowed only with n == 1 */
    /* how finely */
    uint16_t steps;    /* output steps per line/circle (points = steps + 1), 1..CP_MAX_STEPS;
                          0 = derive from tol */
    uint16_t substeps; /* canal: Simpson panels per output step, 1..CP_MAX_SUBSTEPS; 0 = derive
                          from the Lambda error bound (CANAL_PATH_LAMBDA_TOL) */
    uint16_t link;     /* points of each link move (excluding its ends), 0..CP_MAX_LINK;
                          RASTER_LINK_AUTO = derive from tol (or 1 um when tol == 0) */
    cp_real tol;       /* chord tolerance, mm, in [1e-5, 10]; required when steps == 0,
                          else 0 or the tolerance used for derived link counts */
    /* what is emitted */
    uint8_t output;    /* enum raster_output */
    cp_real tool_r;    /* ball-end tool radius, mm, 0 <= tool_r < the model's bound (canal:
                          min R); 0 with RASTER_OUT_SURFACE */
};

/* One streamed point, every model. */
struct raster_pt {
    struct cp_vec3 p; /* emitted position, mm (surface point, tool centre or tool tip) */
    struct cp_vec3 n; /* unit surface normal (canal: out of the sphere) */
    cp_real t;        /* the model's curve parameter of the point */
    int16_t line;     /* line (LINES) or circle/ring (CIRCLES) index j; -1 for a link point */
    uint16_t index;   /* on a line: position i along it (0..steps, the line's running
                         coordinate, zigzag applied); link points: 1..link in travel order */
};

/* The head every model iterator starts with (its first member, `head`): the raster's
 * shape, fixed by the model's init, and the position of the stream. raster_seek moves the
 * position; path.c reads the shape for the stream header. */
struct raster_head {
    /* the shape (valid after a successful init) */
    uint8_t mode;   /* enum raster_mode */
    uint16_t n;     /* lines or circles/rings, 1..CP_MAX_LINES */
    uint32_t steps; /* segments per line (points: steps + 1), 1..CP_MAX_STEPS; 32 bits: a
                       model's init walks may double it (channel: up to 2 CP_MAX_STEPS =
                       131070) */
    uint16_t link;  /* link points between consecutive lines, 0..CP_MAX_LINK (init walks:
                       up to 2 CP_MAX_LINK + 1) */
    uint32_t count; /* points of the whole path, raster_count(n, steps, link); 0 until the
                       model's init succeeded */
    uint8_t overlap; /* 1: the init found far parts of the sweep that meet, with the tool
                        INSIDE (raster_overlap_report: reported, harmless); 0: none found, or
                        a model that does not report (its init sets 0) */
    /* the position */
    uint32_t k;     /* points emitted so far = index of the next point, 0..count */
};

/* ---- checks ---- */

/* Check the raster fields every model uses, in this order (the first failing group
 * gives the code; a model checks its own extras after this, see its header):
 *   CP_ERR_INVAL     c NULL, mode > RASTER_CIRCLES, output > RASTER_OUT_TIP, or
 *                    tool_r != 0 with RASTER_OUT_SURFACE (NaN included)
 *   CP_ERR_NONFINITE u0, u1, tol or tool_r NaN or Inf
 *   CP_ERR_RANGE     n == 0, |u0| or |u1| > umax, u0 == u1 with n > 1, tol != 0 outside
 *                    [1e-5, 10] mm, steps == 0 with tol == 0 (nothing to derive steps
 *                    from), link > CP_MAX_LINK (other than RASTER_LINK_AUTO)
 *   CP_ERR_TOO_MANY  n > CP_MAX_LINES, steps > CP_MAX_STEPS
 *   CP_ERR_TOOL      tool_r < 0
 * umax > 0: bound of |u0|, |u1| (CP_PI for angle labels). Returns CP_OK otherwise.
 * Not checked here: labels, span, substeps (canal only), the tool against the surface. */
CP_MUST_CHECK int raster_check(const struct raster_cfg *c, cp_real umax);

/* ---- layout ---- */

/* Points of a raster: n (steps + 1) + (n - 1) link (n >= 1). n <= CP_MAX_LINES, steps <=
 * 2 CP_MAX_STEPS, link <= 2 CP_MAX_LINK + 1 (the doubled rasters of the init walks)
 * cannot overflow. */
uint32_t raster_count(uint32_t n, uint32_t steps, uint32_t link);

/* Where point k is (raster_locate). */
struct raster_at {
    uint32_t j;     /* block: line/ring j, or the link from line j to line j + 1 */
    uint32_t i;     /* position along the line in the line's running coordinate,
                       0..steps, zigzag applied (odd j: steps - r). On a link: the end where
                       line j stopped (steps for even j, 0 for odd j) */
    uint32_t a;     /* link point number 1..link (travel order); 0 on a line */
    int32_t line;   /* raster_pt.line: j on a line, -1 on a link */
    uint32_t index; /* raster_pt.index: i on a line, a on a link */
};

/* Point k (0 <= k; k < count for a point of the stream) of the raster (steps >= 1,
 * link): fills at. Cost: one division. Cannot fail. */
void raster_locate(uint32_t k, uint32_t steps, uint32_t link, struct raster_at *at);

/* Restart position of an iterator: h->k = k if k <= h->count (CP_OK), else CP_ERR_RANGE
 * (h unchanged). */
CP_MUST_CHECK int raster_seek(struct raster_head *h, uint32_t k);

/* ---- step and link counts from the chord tolerance ---- */

/* Walks after the first one (the search ends by round RASTER_FIT_ROUNDS). */
#define RASTER_FIT_ROUNDS 4
/* Least derived counts: steps per line, segments per link (link + 1). */
#define RASTER_MIN_STEPS 8u
/* raster_fit_update: walk again with the new counts in m[] (> 0: not a cp_err code). */
#define RASTER_FIT_MORE 1

/* How a model searches (a const table of the model; the models measure their sagittas
 * differently, so each keeps the rule its measure was tuned with). The estimate for a
 * count m with measured sagitta s (s ~ 1/m^2) is
 *     f = m sqrt(s / (aim tol)) 1.05,  want = ceil(f) (at least RASTER_MIN_STEPS / 1).
 * A count is verified when s <= accept tol. */
struct raster_rule {
    cp_real aim;        /* the sagitta the estimate aims at, x tol: (0, accept] */
    cp_real accept;     /* the sagitta that verifies a count, x tol: (0, 1] */
    uint16_t start;     /* first derived steps count, RASTER_MIN_STEPS..CP_MAX_STEPS */
    uint8_t pilot;      /* 1: the first walk is a pilot: every derived count is re-estimated
                           from it, up or down (even a verified one); 0: only grown */
    uint8_t grow_shift; /* a count re-estimated after the pilot (or any count, pilot 0) grows
                           by at least 1 + (m >> grow_shift): 0..31 (RASTER_GROW_BY_ONE:
                           by at least 1) */
    uint8_t clamp;      /* 1: an estimate above the maximum is tried at the maximum (CP_ERR_TOL
                           when the maximum itself fails); 0: CP_ERR_TOL at once */
};

/* raster_fit.derive: which counts the search derives (bit q for m[q]). */
#define RASTER_FIT_STEPS 0x01u
#define RASTER_FIT_LINK 0x02u

/* raster_rule.grow_shift for "grow by at least 1" (m >> 31 is 0 for every count). */
#define RASTER_GROW_BY_ONE 31u

/* The search state (the caller's; read m[] between the calls, write nothing). */
struct raster_fit {
    const struct raster_rule *rule; /* the model's rule (must outlive the search) */
    cp_real tol;                    /* mm: cfg tol, or 1 um when tol == 0 (links only) */
    uint32_t m[2];                  /* segments: m[0] = steps (1..CP_MAX_STEPS), m[1] = link
                                       + 1 (1..CP_MAX_LINK + 1) */
    uint8_t derive;                 /* RASTER_FIT_STEPS, RASTER_FIT_LINK: m[0], m[1] is derived
                                       (else given, never changed) */
    uint8_t round;                  /* walks measured so far */
};

/* Start a search for a raster c that passed raster_check: steps derived when c->steps == 0
 * (first m[0] = rule->start), else m[0] = c->steps; link derived when c->link ==
 * RASTER_LINK_AUTO and c->n > 1 (first m[1] = 1), else m[1] = link + 1 (1 when n == 1).
 * Cannot fail. */
void raster_fit_begin(struct raster_fit *f, const struct raster_cfg *c,
                      const struct raster_rule *rule);

/* The sagittas measured on a walk with the counts in m[]: sag[0] of the line/ring segments,
 * sag[1] of the link segments (mm, >= 0). Returns
 *   CP_OK            every derived count verified (or nothing derived): m[] final
 *   RASTER_FIT_MORE  m[] changed: walk again (never after round RASTER_FIT_ROUNDS)
 *   CP_ERR_TOL       a derived count would exceed CP_MAX_STEPS / CP_MAX_LINK + 1, or the
 *                    counts are not verified by round RASTER_FIT_ROUNDS
 * A NaN sagitta is not verified (its estimate: the maximum with clamp, else CP_ERR_TOL). */
int raster_fit_update(struct raster_fit *f, const cp_real *sag);

/* ---- closed curves: the seam (issue 22) ----
 *
 * A curve CLOSES when its end point equals its start point: |C(end) - C(start)| <=
 * RASTER_SEAM_GAP x the curve's size (its largest extent or radius, mm), the same relative
 * test for every model (an ARC or ELLIPSE of 360 degrees, a Bezier with P3 = P0, a closed
 * spine or guide; an ARC of 360 degrees is closed by construction, the test only absorbs
 * the rounding of its end angles). Only the position is required: a closed curve whose
 * tangents differ at the seam (a corner) is the user's geometry and is allowed; its laws
 * must still close.
 *
 * On a closed curve every law that sets the size of the section at a point (the canal's
 * and the spine's radius R, GSR's f_N and f_B, the channel's a, b and exponent) must close
 * too, or the streamed surface steps or creases at the seam: the model's init compares the
 * law's value v and its slope d = dv/ds PER ARC LENGTH s of the curve (not per parameter:
 * a parameter's speed may differ at the two ends) at the start (v0, d0) and at the end
 * (v1, d1) with raster_seam_check, and refuses the job with CP_ERR_SEAM before the first
 * point. An open curve is never compared (its ends may have any values). */

/* Closed curve: end-point gap <= this x the curve's size. */
#define RASTER_SEAM_GAP CP_R(1.0e-5)
/* The ends of a closed curve are known to within RASTER_SEAM_VALUE x len (mm): the rounding
 * of their parameters (float ARC/ELLIPSE end angles up to 4 pi, COS laws up to k = 64) and
 * the gap RASTER_SEAM_GAP allows. A law moves by its slope (and its slope by its second
 * derivative) times that, so the tolerances carry those terms:
 *   value closes: |v1 - v0| <= RASTER_SEAM_VALUE len (1 + |d0| + |d1|)
 *   slope closes: |d1 - d0| <= RASTER_SEAM_SLOPE (1 + |d0| + |d1|)
 *                               + RASTER_SEAM_VALUE len (|dd0| + |dd1|)
 * d is the tangent of the angle at which the section grows along the curve, so the slope
 * tolerance is a crease of about 0.006 degrees for a gentle law. */
#define RASTER_SEAM_VALUE CP_R(1.0e-5)
#define RASTER_SEAM_SLOPE CP_R(1.0e-4)

/* Does a law close at the seam of a closed curve? At the start of the curve: v0 the law's
 * value (mm), d0 its slope dv/ds (mm per mm of arc length s of the curve), dd0 its second
 * derivative d2v/ds2 (1/mm; 0 when the model does not have it: then the slope test has no
 * allowance for the rounding of the ends); v1, d1, dd1 the same at the end; len > 0 the
 * length scale of the job, mm (the larger of the curve's size and the law's largest
 * value). Returns CP_OK when the value and the slope close within the tolerances above,
 * else CP_ERR_SEAM (a NaN anywhere: CP_ERR_SEAM). Plain numbers, no model: each model's
 * init calls it once per law on a closed curve (canal: R; GSR: f_N, f_B; channel: a, b, n;
 * the spine: R). */
CP_MUST_CHECK int raster_seam_check(cp_real v0, cp_real d0, cp_real dd0, cp_real v1, cp_real d1,
                                    cp_real dd1, cp_real len);

/* ---- global overlap of the swept sections (issue 22) ----
 *
 * The local checks of the models (regularity D > 0, the sweep's fold test, with the tool)
 * see one section and its neighbours. Parts of a sweep far apart along its curve can still
 * meet: a curve that loops through itself, a Bezier whose ends come close, a helix whose
 * pitch is below the section's diameter. raster_overlap_check finds them before the first
 * point, with fixed work, from the model's BALLS: at u in [0, 1] the curve point c(u) and
 * a radius r(u) such that the whole section at u (the sphere of a canal surface, the
 * elliptic or superelliptic section of a sweep) lies within r(u) of c(u).
 *
 * The curve is cut into RASTER_OVERLAP_K pieces [k/K, (k+1)/K]; piece k is bounded by the
 * CAPSULE (all points within R_k of the segment from c_k to c_k+1) with
 *   R_k = max(r_k, r_k+1/2, r_k+1) + RASTER_OVERLAP_SAG d_k,
 * d_k the distance of the piece's midpoint c_k+1/2 from that segment: the piece's sagitta
 * (a piece of a circle is farthest from its chord at its midpoint; 2 d_k covers a piece
 * whose curvature doubles along it). The balls at the ends and the midpoint stand for the
 * piece's laws. Both are sampled bounds, not proofs: host_sim's judges measure the streamed
 * surfaces against the exact sweep, and a property test runs them on random jobs.
 * Two pieces are NEIGHBOURS when less than RASTER_OVERLAP_PI (r_max + tool) + 2 h_max of
 * curve separates them (h_max the longest piece chord; on a closed curve the shorter way
 * round counts): within that, a sweep that passes the local fold test cannot meet itself
 * (its curvature stays below 1 / (r + tool), and a curve of that curvature needs an arc of
 * pi (r + tool) to turn back; MATH-overlap in docs/ARCHITECTURE.md). Every other pair is
 * tested: their balls, each grown by `grow` (the tool: an outside tool's ball sweeps 2 r
 * beyond the surface it touches, so the caller passes 2 r; 0 for the surface alone), must
 * not meet:
 *   gap = (distance between the segments of pieces i and j) - R_i - R_j - grow >= 0,
 * the segments' distance bounded from below by RASTER_OVERLAP_SEG + 1 points of one against
 * the other, less half their spacing (1/16 of a piece: a looser bound by that much).
 * A job the check refuses may still be valid where the balls are loose: a flat section (its
 * ball is the larger semi-axis) or parts that come within about one piece of each other.
 * Work: K^2 + 4 K - 2 calls of ball() (4 350 at K = 64), fixed. */
#define RASTER_OVERLAP_K 64u
#define RASTER_OVERLAP_SAG CP_R(2.0)   /* capsule margin over the piece's midpoint sagitta */
#define RASTER_OVERLAP_SEG 8u         /* points of a segment against the other */
#define RASTER_OVERLAP_PI CP_R(3.1416) /* the neighbour arc, in units of r_max + tool */

/* The ball of the section at u: c (mm) and r >= 0 (mm). Returns CP_OK or the model's
 * error (then the check stops with it). */
typedef int (*raster_ball_fn)(const void *ctx, cp_real u, struct cp_vec3 *c, cp_real *r);

/* The closest pair of non-neighbouring pieces found (raster_overlap_check). */
struct raster_overlap {
    cp_real ua, ub; /* the pieces' start parameters, ua < ub (0 and 0: no pair tested) */
    cp_real gap;    /* their gap as above, mm (a large number when no pair was tested) */
};

/* Test every pair of non-neighbouring pieces of the curve u -> ball(ctx, u) (above), the
 * balls grown by grow >= 0 (mm). Closed curve (its end ball's centre within
 * RASTER_SEAM_GAP x the curve's size of the start's): the neighbour arc also counts across
 * the seam. Returns CP_OK (o: the closest pair, gap >= 0), CP_ERR_OVERLAP (o: the first
 * pair whose gap < 0), or ball()'s error; CP_ERR_NUMERIC for a non-finite ball. */
CP_MUST_CHECK int raster_overlap_check(raster_ball_fn ball, const void *ctx, cp_real grow,
                                       struct raster_overlap *o);

/* ---- the report of an overlap with the tool inside (issue 22) ----
 *
 * Where the ball tool is INSIDE the swept spheres or sections (SPINE: the centre m - r n,
 * r < R, so the ball lies in the sphere of its own point; the channel: the ball inside the
 * duct, which its init's fold walks check against the wall's curvature; the canal's fillet),
 * an overlap of far parts is NOT an error: the ball stays inside the swept solid near its
 * own point, so it stays inside the union of all the sections, which is the cavity the
 * job cuts. Where far parts overlap, the part of the streamed surface that lies inside
 * another part's sphere or section is air: the tool cuts nothing there (time wasted, and a
 * host sees points it did not expect). The model's init therefore REPORTS it:
 * raster_overlap_report runs raster_overlap_check on the balls of the surface (grow 0: an
 * inside ball never reaches beyond its own section) and sets h->overlap; the protocol shows
 * the flag in the run's header and status reports (docs/PROTOCOL.md "Far parts that meet").
 * What the flag means is raster_overlap_check's guarantee: 1 when two non-neighbouring
 * pieces' capsules meet (it may be 1 for sections that come within about a piece's
 * sagitta of touching, or for flat sections whose ball is loose), 0 when every such pair is
 * apart. An outside tool (GSR) does not report: its overlap is CP_ERR_OVERLAP. */

/* raster_overlap_check(ball, ctx, 0, ...) for an inside tool: h->overlap = 1 on
 * CP_ERR_OVERLAP (then CP_OK), else 0. Returns CP_OK or the check's other errors (ball()'s
 * own, CP_ERR_NUMERIC). Work: raster_overlap_check's. */
CP_MUST_CHECK int raster_overlap_report(raster_ball_fn ball, const void *ctx,
                                        struct raster_head *h);

#endif /* RASTER_H */
