/* canal_path.c - the canal model's iterator over a canal-surface patch (both
 * curvature-line families; canal_path.h).
 * SPDX-License-Identifier: MIT
 *
 * Parameter grid. With N output steps and M Simpson panels per step, the
 * quadrature lives on half-nodes a = 0 .. 2 M N at t(a) = t0 + a hp, hp = h / (2M):
 * a panel spans [a, a + 2] and output node i is half-node 2 M i. Every t is
 * computed from its integer index (never accumulated), so a point depends only
 * on (i, label) and on the deterministic Lambda march.
 *
 * Error analysis of Lambda (MATH-canal §10). Composite Simpson on g = R' kappa_C:
 * |dLambda| <= (t1 - t0) (2 hp)^4 max|g''''| / 2880, and a label error moves a point
 * by at most 2 R_max |dLambda| (the stereographic map has Lipschitz constant <= 2R
 * in lambda). The panel count is fixed before streaming from a Richardson estimate
 * (64 vs 128 panels compared at every common node, error ratio 16 per halving), so
 * that 2 R_max |dLambda| <= CANAL_PATH_LAMBDA_TOL. Summation uses Kahan compensation:
 * without it float32 drift reaches ~3e-5 mm after 4096 steps; with it the sum is
 * within 1-2 ulp of the exact sum of the panel terms. Backward lines re-use the
 * identical panel terms in reverse order, and Lambda is snapped to its exact value 0
 * at t0, so every line starts from the same state on every run (resume is exact).
 */
#include "canal_path.h"
#include "cp_math.h"

#define RICH_COARSE 64u      /* Richardson estimate: coarse panel count over [t0, t1] */
#define SAG_MARGIN CP_R(0.9) /* measured midpoint sagitta must be <= 0.9 tol */
#define LINK_PROBES 16u      /* probe spacing 1/16 along each link arc and circle */

static cp_real t_at(const struct canal_path *tp, uint32_t a, cp_real hp)
{
    return tp->surf.t0 + (cp_real)a * hp;
}

static void kahan_add(struct canal_quad *q, cp_real d)
{
    cp_real y = d - q->comp;
    cp_real s = q->lam + y;
    q->comp = (s - q->lam) - y;
    q->lam = s;
}

/* Reset the quadrature to half-node 0 (Lambda(t0) = 0 exactly). */
static void quad_reset(const struct canal *c, struct canal_quad *q, struct canal_jet *j)
{
    canal_jet(c, c->t0, j);
    q->lam = CP_R(0.0);
    q->comp = CP_R(0.0);
    q->g = canal_g(j);
}

/* The half-node d half-nodes from a in the direction of a march (backward: d <= a, a
 * march never passes half-node 0). */
static uint32_t half_node(uint32_t a, uint32_t d, int fwd)
{
    return fwd ? a + d : a - d;
}

/* March npan Simpson panels from half-node a: forward (a -> a + 2 npan) or backward
 * (a -> a - 2 npan, 2 npan <= a). Leaves the jet of the final half-node in *j. */
static void quad_march(const struct canal_path *tp, struct canal_quad *q, uint32_t a, uint32_t npan,
                       int fwd, cp_real hp, struct canal_jet *j)
{
    const cp_real w = hp / CP_R(3.0);
    uint32_t m;
    if (tp->surf.kappa_const) {
        /* C has constant curvature (ARC, LINE): Lambda = int R' kappa dt = kappa (R(t) - R(t0))
         * exactly; no quadrature, one jet at the end node (MATH-canal §6). */
        canal_jet(&tp->surf, t_at(tp, half_node(a, 2u * npan, fwd), hp), j);
        q->lam = tp->surf.kappa_c * (j->r - tp->r0);
        q->comp = CP_R(0.0);
        q->g = CP_R(0.0);
        return;
    }
    for (m = 0; m < npan; m++) {
        cp_real gm, ge, d;
        canal_jet(&tp->surf, t_at(tp, half_node(a, 1u, fwd), hp), j);
        gm = canal_g(j);
        a = half_node(a, 2u, fwd);
        canal_jet(&tp->surf, t_at(tp, a, hp), j);
        ge = canal_g(j);
        /* the same three samples in the same order in both directions: t-ascending */
        d = w * ((fwd ? q->g : ge) + CP_R(4.0) * gm + (fwd ? ge : q->g));
        kahan_add(q, fwd ? d : -d);
        q->g = ge;
    }
}

/* Position emitted for a surface label at frame f (surface, tool centre or tip). */
static CP_ALWAYS_INLINE void emit_inline(const struct canal_path *tp, const struct canal_frame *f,
                                         cp_real h, cp_real b, struct canal_point *out)
{
    cp_real off = tp->output == RASTER_OUT_SURFACE ? CP_R(0.0) : tp->tool_r;
    canal_point_inline(f, h, b, off, out);
    if (tp->output == RASTER_OUT_TIP) {
        out->m.z -= tp->tool_r;
    }
}

/* Midpoint sagitta |p1 - (p0 + p2)/2| of the points emitted for labels (h[k], b[k]) at
 * frames f[k], k = 0, 1, 2: not finite (NaN or +Inf) exactly when one of the three
 * points is not (a non-finite coordinate makes its difference non-finite; finite points
 * are bounded, |m| <= ~1e4 mm as in finish, so the squares cannot overflow). (One emit
 * in a loop: the init walks' only copy of the point body.) */
static cp_real sag3(const struct canal_path *tp, const struct canal_frame *f, const cp_real *h,
                    const cp_real *b)
{
    struct canal_point p[3];
    cp_real dx, dy, dz;
    unsigned k;
    for (k = 0; k < 3u; k++) {
        emit_inline(tp, &f[k], h[k], b[k], &p[k]);
    }
    dx = p[1].m.x - CP_R(0.5) * (p[0].m.x + p[2].m.x);
    dy = p[1].m.y - CP_R(0.5) * (p[0].m.y + p[2].m.y);
    dz = p[1].m.z - CP_R(0.5) * (p[0].m.z + p[2].m.z);
    return cp_sqrt(dx * dx + dy * dy + dz * dz);
}

/* Is label (h, b) regular on the surface and (with a tool) on the tool-centre surface? */
static int regular(const struct canal_path *tp, const struct canal_frame *f, cp_real h, cp_real b)
{
    return canal_regular(f, h, b, tp->tool_r);
}

/* Homogeneous label of the line starting at angle u on the FIRST circle:
 * (q0 cos(u/2), sin(u/2)) - MATH-canal §5.2. With span ANGLE (CIRCLES) the
 * frame-independent part (cos(u/2), sin(u/2)) of the fixed angle u instead (label_h). */
static void first_label(const struct canal_path *tp, cp_real u, cp_real *alpha, cp_real *b)
{
    cp_real sn, cs;
    if (tp->labels == RASTER_LABEL_LAMBDA) {
        *alpha = u; /* w = lambda(t0): the label (w, 1) */
        *b = CP_R(1.0);
        return;
    }
    cp_sincos(CP_R(0.5) * u, &sn, &cs);
    *alpha = (tp->span == RASTER_SPAN_ANGLE ? CP_R(1.0) : tp->q0) * cs;
    *b = sn;
}

/* h of the label at frame f (Lambda = lam) of the line whose first_label (or line_label)
 * is (alpha, b): alpha + lam b; span ANGLE, the fixed angle: q alpha. Its b is b. */
static cp_real label_h(const struct canal_path *tp, const struct canal_frame *f, cp_real lam,
                       cp_real alpha, cp_real b)
{
    return tp->span == RASTER_SPAN_ANGLE ? cp_sqrt(f->q2) * alpha : alpha + lam * b;
}

/* Start angle of family-2 line j. */
static cp_real line_u0(const struct canal_path *tp, uint32_t j)
{
    if (tp->head.n <= 1u) {
        return tp->u0;
    }
    return tp->u0 + (tp->u1 - tp->u0) * ((cp_real)j / (cp_real)(tp->head.n - 1u));
}

/* Half start angle x_j = u0 / 2 + j d of family-2 line j (ANGLE labels), d = lab_d.
 * The one formula every caller uses, so a label is the same bits whenever it is made.
 * (Not inlined: one copy for line_label and line_labels; called once per line.) */
static CP_NOINLINE cp_real line_half_angle(const struct canal_path *tp, uint32_t j)
{
    return CP_R(0.5) * tp->u0 + (cp_real)j * tp->lab_d;
}

/* Label of family-2 line j (LINES; also the init walk), the same as
 * first_label(line_u0(j)) up to rounding: (q0 cos x_j, sin x_j). Error: x_j carries
 * <= 2 roundings (~2.4e-7 rad relative to |x| <= pi/2) and cp_sincos <= 1.2e-7, so
 * the half-angle direction is off by <= ~4e-7 rad: <= 8 nm on a 10 mm radius - within
 * the float floor and measured by the reference tests. */
static void line_label(const struct canal_path *tp, uint32_t j, cp_real *alpha, cp_real *b)
{
    cp_real sn, cs;
    if (tp->labels == RASTER_LABEL_LAMBDA) {
        first_label(tp, line_u0(tp, j), alpha, b);
        return;
    }
    cp_sincos(line_half_angle(tp, j), &sn, &cs);
    *alpha = tp->q0 * cs;
    *b = sn;
}

/* Label (h, b) at frame f (Lambda = lam) of the CIRCLES-mode boundary u: the family-2
 * line that starts at u (span LINES) or the fixed contact-frame angle u (span ANGLE). */
static void bound_label(const struct canal_path *tp, cp_real u, const struct canal_frame *f,
                        cp_real lam, cp_real *h, cp_real *b)
{
    first_label(tp, u, h, b);
    *h = label_h(tp, f, lam, *h, *b);
}

/* Label of the point at fraction sig in [0, 1] of the way, uniform in contact-frame
 * angle, from label (ha, ba) to label (hb, bb) on the circle of frame f. Half-angle
 * directions d = (h/q, b) are rotated: no division by zero (|d| > 0 always). */
static void label_between(const struct canal_frame *f, cp_real ha, cp_real ba, cp_real hb,
                          cp_real bb, cp_real sig, cp_real *h, cp_real *b)
{
    cp_real q = cp_sqrt(f->q2);
    cp_real ax = ha / q, ay = ba, bx = hb / q, by = bb;
    cp_real na = cp_sqrt(ax * ax + ay * ay), nb = cp_sqrt(bx * bx + by * by);
    cp_real delta, sn, cs, dx, dy;
    ax /= na;
    ay /= na;
    bx /= nb;
    by /= nb;
    delta = cp_atan2(ax * by - ay * bx, ax * bx + ay * by);
    cp_sincos(sig * delta, &sn, &cs);
    dx = cs * ax - sn * ay;
    dy = cs * ay + sn * ax;
    *h = q * dx;
    *b = dy;
}

/* Label at fraction sig of the way from label (ha, ba) to (hb, bb) at frame f, by
 * normalised linear interpolation of the half-angle directions d = (h/q, b): no
 * trigonometry (a link move is a few points; its chord count allows for the up to
 * 2 tan(phi/2)/phi wider middle steps, phi = the half-angle gap; arc_probe). */
static void label_lerp(const struct canal_frame *f, cp_real ha, cp_real ba, cp_real hb, cp_real bb,
                       cp_real sig, cp_real *h, cp_real *b)
{
    cp_real q = cp_sqrt(f->q2);
    cp_real ax = ha / q, ay = ba, bx = hb / q, by = bb;
    cp_real na = CP_R(1.0) / cp_sqrt(ax * ax + ay * ay),
            nb = CP_R(1.0) / cp_sqrt(bx * bx + by * by);
    cp_real wa = (CP_R(1.0) - sig) * na, wb = sig * nb;
    *h = q * (wa * ax + wb * bx); /* homogeneous: no need to normalise the result */
    *b = wa * ay + wb * by;
}

/* Angle between labels a and b at frame f, radians in [0, pi] (half-angle space x2). */
static cp_real label_gap(const struct canal_frame *f, cp_real ha, cp_real ba, cp_real hb,
                         cp_real bb)
{
    cp_real q = cp_sqrt(f->q2);
    cp_real ax = ha / q, ay = ba, bx = hb / q, by = bb;
    return CP_R(2.0) * cp_fabs(cp_atan2(ax * by - ay * bx, ax * bx + ay * by));
}

/* Number of uniform-angle segments so that a circular arc of radius rad and angle
 * gap has sagitta rad (1 - cos(gap / 2 segs)) <= tol, at most 70000 (0 for a zero gap:
 * its only caller, arc_probe, keeps at least 1). */
static uint32_t arc_segments(cp_real rad, cp_real gap, cp_real tol)
{
    cp_real x, dmax, segs;
    if (!(rad > tol)) {
        return 1u;
    }
    /* 1 - cos(d/2) <= tol/rad  <=>  d <= 2 acos(1 - tol/rad) = 4 asin(sqrt(tol / 2 rad)) */
    x = cp_sqrt(tol / (CP_R(2.0) * rad));
    dmax = CP_R(4.0) * cp_atan2(x, cp_sqrt(CP_R(1.0) - x * x));
    segs = cp_ceil(gap / (dmax * SAG_MARGIN)); /* gap >= 0: an integer >= 0 */
    if (segs > CP_R(70000.0)) {
        segs = CP_R(70000.0);
    }
    return (uint32_t)segs;
}

/* Richardson estimate of the Simpson panel count over [t0, t1] for
 * 2 R_max |dLambda| <= CANAL_PATH_LAMBDA_TOL. Returns the panel count (>= 1). */
static CP_NOINLINE uint32_t lambda_panels(const struct canal_path *tp)
{
    struct canal_quad qc, qf;
    struct canal_jet j;
    cp_real hpc = (tp->surf.t1 - tp->surf.t0) / (cp_real)(2u * RICH_COARSE);
    cp_real hpf = hpc * CP_R(0.5);
    cp_real err = CP_R(0.0), ratio, p;
    uint32_t i;
    quad_reset(&tp->surf, &qc, &j);
    qf = qc;
    for (i = 0; i < RICH_COARSE; i++) {
        cp_real d;
        quad_march(tp, &qc, 2u * i, 1u, 1, hpc, &j);
        quad_march(tp, &qf, 4u * i, 2u, 1, hpf, &j);
        d = cp_fabs(qf.lam - qc.lam);
        err = d > err ? d : err;
    }
    /* fine error ~ |fine - coarse| / 15; panels scale as err^(1/4) */
    err = err / CP_R(15.0) * CP_R(2.0) * tp->surf.rmax;
    ratio = err / CANAL_PATH_LAMBDA_TOL;
    p = CP_R(2.0) * (cp_real)RICH_COARSE * cp_sqrt(cp_sqrt(ratio)) * CP_R(1.25);
    /* err 0 (p 0), or NaN (p NaN), or p in (0, 1] (ceil 1): one panel */
    if (!(p > CP_R(1.0))) {
        return 1u;
    }
    if (p > CP_R(4.0e6)) {
        return 4000000u;
    }
    return (uint32_t)cp_ceil(p);
}

/* Start a walk of the grid (the check's carry): Lambda and the frame at t0, no sagitta. */
static void walk_reset(const struct canal_path *tp, struct canal_check *c, uint32_t m)
{
    struct canal_jet j;
    quad_reset(&tp->surf, &c->q, &j);
    canal_frame(&j, &c->f);
    c->smax = CP_R(0.0);
    c->i = 0u;
    c->m = m;
    c->walk++;
}

/* Step i of the walk that measures the grid's sagitta (CANAL_CHECK_SAG): the grid at twice
 * its resolution (each step of 2 substeps panels split in two: the same panel width hp as
 * the real run, so this Lambda is at least as accurate), the max midpoint sagitta of the
 * emitted positions along the family-2 lines the stream runs along: LINES every line (and
 * every output node and segment midpoint of it must be regular and finite), CIRCLES the
 * two bounding lines its link moves follow. Work: 2 frames and, on each of those n or 2
 * lines, 3 points. The carry (c->q, c->f: the step's first node; c->smax) moves on. */
static CP_NOINLINE int sag_step(const struct canal_path *tp, struct canal_check *c, uint32_t i)
{
    struct canal_jet j;
    struct canal_frame f[3];
    cp_real lam[3];
    uint32_t m = tp->substeps, k, l;
    int lines = tp->head.mode == RASTER_LINES;
    uint32_t nl = lines ? tp->head.n : 2u;
    f[0] = c->f;
    lam[0] = c->q.lam;
    /* m panels of width hp per half grid step, on the hp/2 half-node grid */
    for (k = 1; k < 3u; k++) {
        quad_march(tp, &c->q, 4u * m * i + 2u * m * (k - 1u), m, 1, tp->hp * CP_R(0.5), &j);
        canal_frame(&j, &f[k]);
        lam[k] = c->q.lam;
    }
    for (l = 0; l < nl; l++) {
        cp_real al, bl, s2, h[3], b[3];
        if (lines) {
            line_label(tp, l, &al, &bl);
        } else {
            first_label(tp, l ? tp->u1 : tp->u0, &al, &bl);
        }
        for (k = 0; k < 3u; k++) {
            h[k] = label_h(tp, &f[k], lam[k], al, bl);
            b[k] = bl;
            /* (a step's node k = 0 is the last step's k = 2, same inputs: checked
             * twice, the same verdict; cheaper in flash than skipping it) */
            if (lines && !regular(tp, &f[k], h[k], bl)) {
                return CP_ERR_CUSP;
            }
        }
        s2 = sag3(tp, f, h, b);
        c->smax = s2 > c->smax ? s2 : c->smax; /* (CIRCLES: a NaN is passed over) */
        if (lines && !cp_finite(s2)) {
            return CP_ERR_NUMERIC;
        }
    }
    c->f = f[2];
    return CP_OK;
}

/* The arc from label (ha, ba) to label (hb, bb) at frame f that a LINES link (lerp = 1:
 * label_lerp points) or a CIRCLES circle (lerp = 0: label_between points) follows: raise
 * *worst to its segment count for tol (a lerp's middle steps are wider by 2 tan(phi/2)/phi,
 * phi = gap/2: counted in), and probe that it stays on the regular sheet at sig = k /
 * LINK_PROBES: a circle k = 0..LINK_PROBES, a link only its interior k = 1..LINK_PROBES - 1
 * (its ends are its lines' nodes, which sag_step checked). CP_ERR_CUSP on a failed probe,
 * else CP_OK. */
static CP_NOINLINE int arc_probe(const struct canal_path *tp, const struct canal_frame *f,
                                 cp_real ha, cp_real ba, cp_real hb, cp_real bb, cp_real tol,
                                 int lerp, uint32_t *worst)
{
    cp_real off = tp->output == RASTER_OUT_SURFACE ? CP_R(0.0) : tp->tool_r;
    cp_real gap = label_gap(f, ha, ba, hb, bb), widen = CP_R(1.0), sn, cs;
    uint32_t segs, k;
    if (lerp) {
        cp_sincos(CP_R(0.25) * gap, &sn, &cs);
        widen = gap > CP_R(1e-6) ? CP_R(4.0) * sn / (cs * gap) : CP_R(1.0);
    }
    segs = arc_segments((f->r - off) / cp_sqrt(f->q2), gap * widen, tol);
    *worst = segs > *worst ? segs : *worst;
    for (k = (uint32_t)lerp; k <= LINK_PROBES - (uint32_t)lerp; k++) {
        cp_real hh, b2, sig = (cp_real)k / (cp_real)LINK_PROBES;
        if (lerp) {
            label_lerp(f, ha, ba, hb, bb, sig, &hh, &b2);
        } else {
            label_between(f, ha, ba, hb, bb, sig, &hh, &b2);
        }
        if (!regular(tp, f, hh, b2)) {
            return CP_ERR_CUSP;
        }
    }
    return CP_OK;
}

/* Unit i of the LINES link phase (CANAL_CHECK_LINK), which derives the link count: the
 * largest angle gap between neighbouring lines at t0 and t1 on circles of radius
 * (R - off)/q (arc_probe, into c->worst). Units: the n - 1 pairs of neighbours at t0 (the
 * carry: Lambda and frame at t0), the march to t1 one output step (substeps panels) at a
 * time, the n - 1 pairs at t1 (the carry: at t1 after the march). */
static CP_NOINLINE int link_step(const struct canal_path *tp, struct canal_check *c, uint32_t i)
{
    uint32_t pairs = (uint32_t)tp->head.n - 1u, steps = tp->head.steps, m = tp->substeps, jl;
    cp_real aa, ba, ab, bb;
    if (i >= pairs && i < pairs + steps) { /* the march from t0 to t1 */
        struct canal_jet j;
        quad_march(tp, &c->q, 2u * m * (i - pairs), m, 1, tp->hp, &j);
        if (i + 1u == pairs + steps) {
            canal_frame(&j, &c->f);
        }
        return CP_OK;
    }
    jl = i < pairs ? i : i - pairs - steps;
    line_label(tp, jl, &aa, &ba);
    line_label(tp, jl + 1u, &ab, &bb);
    return arc_probe(tp, &c->f, aa + c->q.lam * ba, ba, ab + c->q.lam * bb, bb, c->fit.tol, 1,
                     &c->worst);
}

/* The raster checks shared with the other models (raster_check: INVAL, NONFINITE, RANGE,
 * TOO_MANY, TOOL in that order) after the canal's own kinds (labels, span: INVAL first),
 * then substeps. */
static int validate(const struct raster_cfg *cfg)
{
    int err;
    /* labels and span are each 0 or 1; span ANGLE needs CIRCLES and angle labels */
    if ((cfg->labels | cfg->span) > 1u ||
        (cfg->span == RASTER_SPAN_ANGLE &&
         (cfg->mode != RASTER_CIRCLES || cfg->labels != RASTER_LABEL_ANGLE))) {
        return CP_ERR_INVAL;
    }
    err = raster_check(cfg, cfg->labels == RASTER_LABEL_LAMBDA ? CANAL_COORD_MAX : CP_PI);
    if (err == CP_OK && cfg->substeps > CP_MAX_SUBSTEPS) {
        err = CP_ERR_TOO_MANY;
    }
    return err;
}

/* Node i (0..gsteps) of the CIRCLES walk of the grid's nodes (CANAL_CHECK_NODES): both
 * bounding lines regular; at each circle (node c (link + 1)) its points regular, and the
 * step count its exact sagitta needs (c->worst). The carry (c->q, c->f) is node i - 1's. */
static int node_step(const struct canal_path *tp, struct canal_check *c, uint32_t i)
{
    uint32_t m = tp->substeps;
    cp_real aa, ba, ab, bb;
    if (i > 0u) {
        struct canal_jet j;
        quad_march(tp, &c->q, 2u * m * (i - 1u), m, 1, tp->hp, &j);
        canal_frame(&j, &c->f);
    }
    bound_label(tp, tp->u0, &c->f, c->q.lam, &aa, &ba);
    bound_label(tp, tp->u1, &c->f, c->q.lam, &ab, &bb);
    if (!regular(tp, &c->f, aa, ba) || !regular(tp, &c->f, ab, bb)) {
        return CP_ERR_CUSP;
    }
    /* a circle: its points, and the step count from its exact sagitta */
    if (i % (tp->head.link + 1u) == 0u &&
        arc_probe(tp, &c->f, aa, ba, ab, bb, c->fit.tol, 0, &c->worst) != CP_OK) {
        return CP_ERR_CUSP;
    }
    return CP_OK;
}

/* The tolerance search of the grid (raster_fit), by mode: LINES refines the steps (from
 * 16; an estimate above CP_MAX_STEPS is tried at CP_MAX_STEPS once), CIRCLES link + 1
 * (from 1; CP_ERR_TOL above CP_MAX_LINK + 1). Both verify a count whose measured midpoint
 * sagitta is <= SAG_MARGIN tol and aim the h^2 estimate at the same. */
static const struct raster_rule canal_rule[2] = {
    [RASTER_LINES] = {.aim = SAG_MARGIN, .accept = SAG_MARGIN, .start = 16u, .pilot = 0u,
                      .grow_shift = RASTER_GROW_BY_ONE, .clamp = 1u},
    [RASTER_CIRCLES] = {.aim = SAG_MARGIN, .accept = SAG_MARGIN, .start = 16u, .pilot = 0u,
                        .grow_shift = RASTER_GROW_BY_ONE, .clamp = 0u}};

/* The grid of a round of the tolerance search (CANAL_CHECK_ROUND). g is what the rounds
 * refine (c->fit): LINES the steps per line (grid = output steps, gsteps = g), CIRCLES
 * link + 1 (gsteps = (n - 1) g link steps between the first and the last circle, at least
 * 1; a single circle keeps its given link). The panels per grid step come from c->panels.
 * Then the round's walk begins: CIRCLES its nodes, LINES its sagittas. */
static int round_begin(struct canal_path *tp, const struct raster_cfg *cfg, struct canal_check *c)
{
    int lines = tp->head.mode == RASTER_LINES;
    uint32_t g = c->fit.m[lines ? 0u : 1u], gsteps, m;
    if (!lines && tp->head.n < 2u && cfg->link != RASTER_LINK_AUTO) {
        g = cfg->link + 1u;
    }
    gsteps = lines ? g : (tp->head.n > 1u ? (uint32_t)(tp->head.n - 1u) * g : 1u);
    /* panels >= 1, so m >= 1 */
    m = cfg->substeps ? cfg->substeps : (c->panels + gsteps - 1u) / gsteps;
    if (gsteps > CP_MAX_STEPS * 4u) {
        return CP_ERR_TOO_MANY;
    }
    if (m > CP_MAX_SUBSTEPS) {
        return CP_ERR_TOL;
    }
    tp->substeps = (uint16_t)m;
    if (lines) {
        tp->head.steps = (uint16_t)g;
    } else {
        tp->head.link = (uint16_t)(g - 1u);
    }
    tp->hp = (tp->surf.t1 - tp->surf.t0) / (cp_real)(2u * gsteps * m);
    c->worst = 1u;
    c->phase = lines ? CANAL_CHECK_SAG : CANAL_CHECK_NODES;
    walk_reset(tp, c, lines ? gsteps : gsteps + 1u);
    return CANAL_CHECK_MORE;
}

/* The counts are fixed: the stream's point count, and tp at point 0. */
static int check_done(struct canal_path *tp)
{
    /* n <= CP_MAX_LINES, steps <= CP_MAX_STEPS, link <= CP_MAX_LINK: no overflow */
    tp->head.count = raster_count(tp->head.n, tp->head.steps, tp->head.link);
    return canal_path_seek(tp, 0u); /* also clears the label caches */
}

/* A round's walks are done: the search decides (raster_fit_update; at most
 * RASTER_FIT_ROUNDS + 1 rounds). Verified: LINES goes on with the link arcs (regularity
 * always, the count from the tolerance unless given), CIRCLES takes the steps per circle
 * (given, or the worst circle's). */
static int round_end(struct canal_path *tp, const struct raster_cfg *cfg, struct canal_check *c)
{
    int err = raster_fit_update(&c->fit, c->sag);
    if (err == RASTER_FIT_MORE) {
        c->phase = CANAL_CHECK_ROUND;
        return CANAL_CHECK_MORE;
    }
    if (err != CP_OK) {
        return err; /* CP_ERR_TOL */
    }
    if (tp->head.mode == RASTER_LINES) {
        if (tp->head.n <= 1u) {
            tp->head.link = 0u;
            return check_done(tp);
        }
        c->phase = CANAL_CHECK_LINK;
        c->worst = 1u;
        walk_reset(tp, c, 2u * ((uint32_t)tp->head.n - 1u) + tp->head.steps);
        return CANAL_CHECK_MORE;
    }
    if (cfg->steps != 0u) {
        tp->head.steps = cfg->steps;
    } else {
        if (c->worst > CP_MAX_STEPS) {
            return CP_ERR_TOL;
        }
        tp->head.steps = (uint16_t)c->worst;
    }
    return check_done(tp);
}

/* The LINES link phase is done: the link count from the worst arc, unless given (a given
 * count is kept even where the tolerance would need more; a cusp is refused either way). */
static int link_end(struct canal_path *tp, const struct raster_cfg *cfg, struct canal_check *c)
{
    if (cfg->link != RASTER_LINK_AUTO) {
        tp->head.link = cfg->link;
    } else if (c->worst - 1u > CP_MAX_LINK) {
        return CP_ERR_TOL;
    } else {
        tp->head.link = (uint16_t)(c->worst - 1u);
    }
    return check_done(tp);
}

int canal_path_check_begin(struct canal_path *tp, const struct canal_cfg *surf,
                           const struct raster_cfg *cfg, struct canal_check *c)
{
    struct canal_jet j;
    struct canal_frame f;
    int err;
    if (tp == NULL || surf == NULL || cfg == NULL || c == NULL) {
        return CP_ERR_INVAL;
    }
    tp->head.count = 0u; /* (until the check succeeds) */
    tp->head.overlap = 0u; /* not checked for the canal (raster.h) */
    tp->head.k = 0u;
    err = canal_init(&tp->surf, surf);
    if (err != CP_OK) {
        return err;
    }
    err = validate(cfg);
    if (err != CP_OK) {
        return err;
    }
    if (cfg->tool_r >= tp->surf.rmin) {
        return CP_ERR_TOOL;
    }
    tp->head.mode = cfg->mode;
    tp->output = cfg->output;
    tp->labels = cfg->labels;
    tp->span = cfg->span;
    tp->head.n = cfg->n;
    tp->u0 = cfg->u0;
    tp->u1 = cfg->u1;
    tp->tool_r = cfg->tool_r;
    canal_jet1(&tp->surf, tp->surf.t0, &j);
    canal_frame_pt(&j, &f);
    tp->q0 = cp_sqrt(f.q2);
    tp->r0 = j.r;
    tp->lab_d = tp->head.n > 1u ? CP_R(0.5) * (tp->u1 - tp->u0) / (cp_real)(tp->head.n - 1u) : CP_R(0.0);
    c->phase = CANAL_CHECK_LAMBDA;
    c->walk = 0u;
    c->i = 0u;
    c->m = 0u;
    c->sag[0] = CP_R(0.0); /* the count a mode does not refine stays verified */
    c->sag[1] = CP_R(0.0);
    raster_fit_begin(&c->fit, cfg, &canal_rule[tp->head.mode]);
    return CANAL_CHECK_MORE;
}

/* Work units of one unit of the current phase (canal_path.h: a jet, or a label or point
 * checked): SAG a grid step's marches (2 jets per panel, twice substeps panels) and its
 * lines (LINES: the n lines' label and 3 points each); NODES a node's march, its two
 * bounds and a circle's probes (2 units each: the rotation and the regularity); LINK a
 * march step or a pair's labels and probes (counted as both). At least 1 unit of the
 * phase per step. */
static uint32_t units_per_step(const struct canal_path *tp, const struct canal_check *c)
{
    uint32_t m = tp->substeps, probes = 2u * (LINK_PROBES + 1u), cost;
    switch ((enum canal_check_phase)c->phase) {
    case CANAL_CHECK_SAG:
        cost = 4u * m + 4u * (tp->head.mode == RASTER_LINES ? tp->head.n : 2u);
        break;
    case CANAL_CHECK_NODES:
        cost = 2u * m + 4u + probes;
        break;
    default: /* CANAL_CHECK_LINK */
        cost = 2u * m + 2u + probes;
        break;
    }
    return cost >= CANAL_CHECK_WORK ? 1u : CANAL_CHECK_WORK / cost;
}

int canal_path_check_step(struct canal_path *tp, const struct raster_cfg *cfg,
                          struct canal_check *c)
{
    uint32_t n, end;
    int err = CP_OK;
    switch ((enum canal_check_phase)c->phase) {
    case CANAL_CHECK_LAMBDA:
        c->panels = (cfg->substeps || tp->surf.kappa_const) ? 1u : lambda_panels(tp);
        c->phase = CANAL_CHECK_ROUND;
        return CANAL_CHECK_MORE;
    case CANAL_CHECK_ROUND:
        return round_begin(tp, cfg, c);
    case CANAL_CHECK_NODES:
    case CANAL_CHECK_SAG:
    case CANAL_CHECK_LINK:
        break;
    }
    n = units_per_step(tp, c);
    end = c->m - c->i > n ? c->i + n : c->m;
    for (; c->i < end && err == CP_OK; c->i++) {
        switch ((enum canal_check_phase)c->phase) {
        case CANAL_CHECK_NODES:
            err = node_step(tp, c, c->i);
            break;
        case CANAL_CHECK_SAG:
            err = sag_step(tp, c, c->i);
            break;
        default: /* CANAL_CHECK_LINK */
            err = link_step(tp, c, c->i);
            break;
        }
    }
    if (err != CP_OK) {
        return err;
    }
    if (c->i < c->m) {
        return CANAL_CHECK_MORE;
    }
    if (c->phase == CANAL_CHECK_NODES && (c->fit.derive & RASTER_FIT_LINK)) {
        c->phase = CANAL_CHECK_SAG; /* the circles' link: its sagittas along the bounds */
        walk_reset(tp, c, c->m - 1u);
        return CANAL_CHECK_MORE;
    }
    if (c->phase == CANAL_CHECK_LINK) {
        return link_end(tp, cfg, c);
    }
    c->sag[tp->head.mode == RASTER_LINES ? 0u : 1u] = c->smax;
    return round_end(tp, cfg, c);
}

int canal_path_init(struct canal_path *tp, const struct canal_cfg *surf,
                    const struct raster_cfg *cfg)
{
    struct canal_check c;
    uint32_t s;
    int err = canal_path_check_begin(tp, surf, cfg, &c);
    for (s = 0; s < CANAL_CHECK_STEPS_MAX && err == CANAL_CHECK_MORE; s++) {
        err = canal_path_check_step(tp, cfg, &c);
    }
    return err == CANAL_CHECK_MORE ? CP_ERR_NUMERIC : err; /* (cannot run out: STEPS_MAX) */
}

uint32_t canal_path_count(const struct canal_path *tp)
{
    return tp->head.count;
}

/* Bring the quadrature to half-node `target` and leave the jet there in *j. One output
 * step on from the current node (forward, or backward with `back`) marches that step;
 * at the node, only the jet; from anywhere else (or no state: quad_valid 0) along the
 * deterministic route of the stream from half-node 0: forward, or for `back` (LINES odd lines) forward to the
 * last node of a line and then backward. Lambda is snapped to its exact value 0 when a
 * backward march reaches t0 (*j is then already the jet at t0). */
static CP_NOINLINE void quad_to(struct canal_path *tp, uint32_t target, int back, struct canal_jet *j)
{
    struct canal_quad q;
    uint32_t m2 = 2u * tp->substeps, from = tp->node;
    int valid = tp->quad_valid != 0u;
    if (valid && from == target) {
        canal_jet(&tp->surf, t_at(tp, target, tp->hp), j);
        return;
    }
    if (valid && (back ? from == target + m2 : target == from + m2)) {
        q.lam = tp->lam;
        q.comp = tp->comp;
        q.g = tp->g_node;
        quad_march(tp, &q, from, m2 / 2u, !back, tp->hp, j);
    } else {
        quad_reset(&tp->surf, &q, j);
        from = 0u;
        if (back) {
            from = m2 * tp->head.steps;
            quad_march(tp, &q, 0u, from / 2u, 1, tp->hp, j);
        }
        quad_march(tp, &q, from, (back ? from - target : target - from) / 2u, !back, tp->hp, j);
    }
    if (back && target == 0u) {
        q.lam = CP_R(0.0); /* snap to the exact Lambda(t0) */
        q.comp = CP_R(0.0);
    }
    tp->quad_valid = 1u;
    tp->node = target;
    tp->lam = q.lam;
    tp->comp = q.comp;
    tp->g_node = q.g;
}

int canal_path_seek(struct canal_path *tp, uint32_t k)
{
    if (raster_seek(&tp->head, k) != CP_OK) {
        return CP_ERR_RANGE;
    }
    tp->quad_valid = 0u; /* no quadrature state yet: next() positions it */
    if (k == 0u && tp->head.mode == RASTER_CIRCLES) {
        /* the stream starts at node 0: set it up now, so the first point costs what
         * every other point costs */
        struct canal_quad q;
        struct canal_jet jt;
        quad_reset(&tp->surf, &q, &jt);
        tp->quad_valid = 1u;
        tp->node = 0u;
        tp->lam = q.lam;
        tp->comp = q.comp;
        tp->g_node = q.g;
    }
    tp->lab_line = -1;
    tp->lab2_line = -1;
    tp->st_line = -1;
    if (tp->head.mode == RASTER_LINES && k < tp->head.count) {
        /* make the labels of k's line and of the next line now, so that the stream
         * itself never pays a whole label (seek is the resume path, not the hot one) */
        uint32_t jl = k / ((uint32_t)tp->head.steps + 1u + tp->head.link);
        line_label(tp, jl, &tp->lab_a, &tp->lab_b);
        tp->lab_line = (int32_t)jl;
        if (jl + 1u < tp->head.n) {
            line_label(tp, jl + 1u, &tp->lab2_a, &tp->lab2_b);
            tp->lab2_line = (int32_t)(jl + 1u);
        }
    }
    return CP_OK;
}

/* Copy a computed point out, refusing a non-finite one. */
static CP_ALWAYS_INLINE int finish(const struct canal_point *cp, cp_real t, int line,
                                   uint32_t index, struct raster_pt *pt)
{
    /* one test covers all six: m = (x + rr nx, y + rr ny, off + rr wb) with n = (nx,
     * ny, wb - 1) and rr = R - off >= rmin - tool_r > 0 (init), so a NaN or Inf in n
     * makes the matching m component non-finite too; a NaN or Inf in m makes the sum
     * non-finite, and finite components (|m| <= ~1e4 mm) cannot overflow it */
    if (!cp_finite(cp->m.x + cp->m.y + cp->m.z)) {
        return CP_ERR_NUMERIC;
    }
    pt->p = cp->m;
    pt->n = cp->n;
    pt->t = t;
    pt->line = (int16_t)line;
    pt->index = (uint16_t)index;
    return CP_OK;
}

/* Labels of LINES mode, by position r (travel order) in line jl: at its first point
 * the label of jl is taken from the next-line cache; at the point before its last the
 * first half of line jl + 1's label is made (cp_sincos_in1, inlined), at its last point
 * the second half (cp_sincos_in2), so no point pays a whole sincos. A point whose cache is not
 * ready (impossible after canal_path_seek, which makes both labels; kept as a guard)
 * makes what it needs itself. LAMBDA labels need no sincos: made at once. */
static CP_NOINLINE void line_labels(struct canal_path *tp, uint32_t jl, uint32_t r)
{
    uint32_t nx = jl + 1u;
    if (tp->lab_line != (int32_t)jl) {
        if (tp->lab2_line == (int32_t)jl) {
            tp->lab_a = tp->lab2_a;
            tp->lab_b = tp->lab2_b;
        } else {
            line_label(tp, jl, &tp->lab_a, &tp->lab_b);
        }
        tp->lab_line = (int32_t)jl;
    }
    if (r + 1u < tp->head.steps || nx >= tp->head.n || tp->lab2_line == (int32_t)nx) {
        return;
    }
    if (tp->labels == RASTER_LABEL_LAMBDA) {
        line_label(tp, nx, &tp->lab2_a, &tp->lab2_b);
        tp->lab2_line = (int32_t)nx;
        return;
    }
    if (tp->st_line != (int32_t)nx) {
        cp_sincos_in1(line_half_angle(tp, nx), &tp->st);
        tp->st_line = (int32_t)nx;
    }
    if (r >= tp->head.steps) {
        cp_real sn, cs;
        cp_sincos_in2(&tp->st, &sn, &cs);
        tp->lab2_a = tp->q0 * cs;
        tp->lab2_b = sn;
        tp->lab2_line = (int32_t)nx;
    }
}

/* One point of either mode. Point k is position r of block jl (a line or circle of
 * steps + 1 points in travel order, then its link points r - steps = 1..link). Odd
 * blocks run backwards. A link point sits at the end of its line (LINES: the node of
 * index i, as its last point) or on the bounding line between two circles (CIRCLES:
 * the link's own node, forward). */
int canal_path_next(struct canal_path *tp, struct raster_pt *pt)
{
    uint32_t block = (uint32_t)tp->head.steps + 1u + tp->head.link;
    uint32_t jl = tp->head.k / block, r = tp->head.k % block;
    uint32_t rr = r <= tp->head.steps ? r : tp->head.steps, i, a;
    int back = (int)(jl & 1u), lines = tp->head.mode == RASTER_LINES, err;
    struct canal_jet j;
    struct canal_frame f;
    struct canal_point cp;
    cp_real t, hh, b2;
    if (tp->head.k >= tp->head.count) {
        return CP_ERR_DONE;
    }
    i = back ? tp->head.steps - rr : rr;
    if (!lines) {
        a = (jl * (tp->head.link + 1u) + (r - rr)) * (2u * tp->substeps);
        t = t_at(tp, a, tp->hp);
        quad_to(tp, a, 0, &j);
    } else {
        a = i * (2u * tp->substeps);
        t = t_at(tp, a, tp->hp);
        if (tp->surf.kappa_const) {
            /* constant curvature: exact Lambda, no quadrature state to march */
            canal_jet1(&tp->surf, t, &j);
            tp->lam = tp->surf.kappa_c * (j.r - tp->r0);
            tp->quad_valid = 0u;
        } else {
            if (r == 0u && !back) {
                tp->quad_valid = 0u; /* an even line starts at t0 afresh: Lambda = 0 */
            }
            /* (an odd line starts, r = 0, at the node where the previous line ended, or
             * after a seek from scratch: forward to it, then no backward panel) */
            quad_to(tp, a, back, &j);
        }
    }
    canal_frame_pt(&j, &f);
    if (lines) {
        if (tp->lab_line != (int32_t)jl || r + 1u >= tp->head.steps) {
            line_labels(tp, jl, r); /* a line's first and last two points, its links */
        }
        hh = tp->lab_a + tp->lam * tp->lab_b; /* the streaming hot path */
        b2 = tp->lab_b;
        if (r > tp->head.steps) {
            /* link point: between the labels of lines jl and jl + 1 (both cached: the
             * next one was made at the line's last point) */
            cp_real hl, bl; /* (not hh, b2 themselves: their address would cost the hot path) */
            label_lerp(&f, hh, b2, tp->lab2_a + tp->lam * tp->lab2_b, tp->lab2_b,
                       (cp_real)(r - tp->head.steps) / (cp_real)(tp->head.link + 1u), &hl, &bl);
            hh = hl;
            b2 = bl;
        }
    } else {
        cp_real aa, ba, ab, bb;
        bound_label(tp, tp->u0, &f, tp->lam, &aa, &ba);
        bound_label(tp, tp->u1, &f, tp->lam, &ab, &bb);
        /* link point: along the bounding line the circle ended on (it makes both bound
         * labels too, still less work than a circle point) */
        hh = back ? aa : ab;
        b2 = back ? ba : bb;
        if (r <= tp->head.steps) {
            label_between(&f, aa, ba, ab, bb, (cp_real)i / (cp_real)tp->head.steps, &aa, &ba);
            hh = aa;
            b2 = ba;
        }
    }
    emit_inline(tp, &f, hh, b2, &cp);
    err = finish(&cp, t, r > tp->head.steps ? -1 : (int)jl, r > tp->head.steps ? r - tp->head.steps : i, pt);
    if (err == CP_OK) {
        tp->head.k++;
    }
    return err;
}

#if CP_REAL_DOUBLE
CP_STATIC_ASSERT(sizeof(struct canal_path) <= 2u * CP_CANAL_PATH_BUDGET, canal_path_fits_budget);
#else
CP_STATIC_ASSERT(sizeof(struct canal_path) <= CP_CANAL_PATH_BUDGET, canal_path_fits_budget);
#endif
