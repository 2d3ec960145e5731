/* toolpath.h - pull iterator over a canal-surface patch: exactly toolpath_count() points.
 * SPDX-License-Identifier: MIT
 *
 * The patch is bounded by two family-2 curvature lines (the lines that start at
 * contact-frame angles U0 and U1 on the first circle, t = t0) and by the first and
 * last characteristic circles (t = t0, t = t1). Two raster modes cover it:
 *
 *   TOOLPATH_LINES    n family-2 lines, start angles U0 + j (U1 - U0)/(n - 1), each
 *                     with steps + 1 points at t_i = t0 + i h (i from 0, never
 *                     accumulated). Zigzag: even lines run i = 0..steps, odd lines
 *                     i = steps..0. Consecutive lines are linked by `link` points on
 *                     the characteristic circle where they meet (family 1), so the
 *                     stream never jumps. count = n (steps + 1) + (n - 1) link.
 *   TOOLPATH_CIRCLES  n characteristic circles at t_j = t0 + j (t1 - t0)/(n - 1), each
 *                     with steps + 1 points evenly spaced in the contact-frame angle
 *                     from line U0 to line U1 (zigzag: odd circles run backwards).
 *                     Consecutive circles are linked by `link` points along the
 *                     bounding family-2 line where they meet.
 *                     count = n (steps + 1) + (n - 1) link.
 *
 * Lambda(t) is integrated once for all lines by composite Simpson with Kahan
 * summation, `substeps` Simpson panels per output step (2 jets per panel). Every
 * point is computed directly from (t_i, label_j); positions are never accumulated.
 *
 * Step counts are fixed before the first point: given, or derived at init from the
 * chord tolerance (rounded UP, then verified on the actual geometry, so the measured
 * sagitta never exceeds tol) and from the Simpson error bound of Lambda.
 * Before anything is emitted, init also walks the whole patch once and rejects it if
 * any point is on or beyond a cuspidal edge (surface, and tool-centre offset surface).
 */
#ifndef TOOLPATH_H
#define TOOLPATH_H

#include "canal.h"
#include "cp_math.h"

enum toolpath_mode {
    TOOLPATH_LINES = 0,  /* family-2 curvature lines, linked along circles */
    TOOLPATH_CIRCLES = 1 /* family-1 characteristic circles, linked along lines */
};

/* How u0, u1 label the family-2 lines. */
enum toolpath_labels {
    /* contact-frame start angle on the first circle, radians, |u| <= pi */
    TOOLPATH_LABEL_ANGLE = 0,
    /* w = lambda(t0) = q0 cot(u0/2), dimensionless, |w| <= 1e4 (C itself is w = inf) */
    TOOLPATH_LABEL_LAMBDA = 1
};

/* What bounds the circles of TOOLPATH_CIRCLES. */
enum toolpath_span {
    /* the family-2 lines that start at u0 and u1: the same patch as LINES */
    TOOLPATH_SPAN_LINES = 0,
    /* the fixed contact-frame angles u0..u1 on every circle; links run along u = const
     * (labels must be ANGLE) */
    TOOLPATH_SPAN_ANGLE = 1
};

/* Output of each point. */
enum toolpath_output {
    TOOLPATH_OUT_SURFACE = 0, /* the surface point m (no tool) */
    TOOLPATH_OUT_CENTRE = 1,  /* ball-end tool centre m - r_tool n (5-axis, robots) */
    TOOLPATH_OUT_TIP = 2      /* ball-end tool tip: centre - r_tool z (3-axis) */
};

struct toolpath_cfg {
    uint8_t mode;          /* enum toolpath_mode */
    uint8_t output;        /* enum toolpath_output */
    uint8_t labels;        /* enum toolpath_labels (default ANGLE) */
    uint8_t span;          /* enum toolpath_span, CIRCLES only (default LINES) */
    uint16_t n;            /* lines (LINES) or circles (CIRCLES), 1..CP_MAX_LINES */
    cp_real u0, u1;        /* bounding lines: start angles on the first circle, radians, |u| <= pi
                              (or lambda labels, see labels); u0 == u1 allowed only with n == 1 */
    uint16_t steps;        /* output steps per line/circle (points = steps + 1), 1..CP_MAX_STEPS;
                              0 = derive from tol */
    uint16_t substeps;     /* Simpson panels per output step, 1..CP_MAX_SUBSTEPS; 0 = derive from
                              the Lambda error bound (LAMBDA_TOL below) */
    uint16_t link;         /* points of each link move (excluding its ends), 0..CP_MAX_LINK;
                              0xFFFF = derive from tol (or 1 um when tol == 0) */
    cp_real tol;           /* chord tolerance, mm, in [1e-5, 10]; required when steps == 0,
                              else 0 or the tolerance used for derived link counts */
    cp_real tool_r;        /* ball-end tool radius, mm, 0 <= tool_r < min R; 0 with OUT_SURFACE */
    struct canal_cfg surf; /* the surface (validated by canal_init); last: the fields above
                              stay at Thumb's short load/store offsets */
};

#define TOOLPATH_LINK_AUTO 0xFFFFu

/* Target error of Lambda's quadrature in position: 2 R_max |dLambda| <= this, mm. */
#define TOOLPATH_LAMBDA_TOL CP_R(2.0e-5)

struct toolpath_pt {
    struct cp_vec3 p; /* emitted position, mm (surface point, tool centre or tool tip) */
    struct cp_vec3 n; /* unit surface normal, out of the sphere */
    cp_real t;        /* curve parameter of the point */
    int16_t line;     /* line (LINES) or circle (CIRCLES) index j; -1 for a link point */
    uint16_t index;   /* LINES: t index i (0..steps); CIRCLES: angle index (0..steps);
                         link points: 1..link in travel order */
};

struct toolpath {
    /* the integers first (Thumb's 16-bit loads and stores reach bytes below offset 32,
     * halfwords below 64, words below 128), the surface last */
    uint8_t mode, output, labels, span;
    uint16_t n, steps, substeps, link;
    int32_t lab_line; /* line whose label is cached in lab_a, lab_b (-1: none) */
    cp_real lab_a, lab_b;
    int32_t lab2_line; /* line whose label is cached in lab2_a, lab2_b (the next line) */
    cp_real lab2_a, lab2_b;
    /* LINES with ANGLE labels: the label of line j is (q0 cos x_j, sin x_j), x_j =
     * u0 / 2 + j lab_d. The next line's label is made in two halves over the last two
     * points of a line (cp_sincos_stage1, then stage2), so no point of the stream pays
     * a whole sincos on top of its own work: the per-point cost stays flat. */
    cp_real lab_d;
    int32_t st_line; /* line whose label's first half is in st (-1: none) */
    struct cp_sincos_st st;
    cp_real u0, u1, tool_r;
    cp_real hp;     /* half-panel width in t: output/node step = 2 substeps hp */
    cp_real q0;     /* q at t0 (labels) */
    cp_real r0;     /* R(t0): exact Lambda = kappa (R - r0) when the curvature of C is constant */
    uint32_t count; /* total points */
    uint32_t k;     /* points emitted so far */
    /* quadrature state */
    uint32_t node;     /* current node index of Lambda */
    cp_real lam, comp; /* Lambda at node, Kahan compensation */
    cp_real g_node;    /* integrand g at node */
    struct canal surf;
};

/* Validate cfg, derive step counts, walk the patch once for regularity.
 * Errors: every canal_init code, plus
 *   CP_ERR_INVAL     mode/output out of range, tool radius with OUT_SURFACE
 *   CP_ERR_NONFINITE u0, u1, tol or tool_r NaN/Inf
 *   CP_ERR_RANGE     |u| > pi, u0 == u1 with n > 1, n == 0, tol out of range,
 *                    steps == 0 with tol == 0, link > CP_MAX_LINK
 *   CP_ERR_TOO_MANY  n > CP_MAX_LINES, steps > CP_MAX_STEPS, substeps > CP_MAX_SUBSTEPS
 *   CP_ERR_TOOL      tool_r < 0 or tool_r >= min R over the interval
 *   CP_ERR_TOL       tol cannot be met within CP_MAX_STEPS (or the Lambda bound within
 *                    CP_MAX_SUBSTEPS)
 *   CP_ERR_CUSP      a point of the patch (or of the tool-centre surface) has D <= 0
 *   CP_ERR_NUMERIC   a non-finite value appeared during the walk
 * Returns CP_OK; then toolpath_next() yields exactly toolpath_count() points. */
CP_MUST_CHECK int toolpath_init(struct toolpath *tp, const struct toolpath_cfg *cfg);

/* Total number of points the iterator yields. */
uint32_t toolpath_count(const struct toolpath *tp);

/* Next point. Returns CP_OK, CP_ERR_DONE after the last point, or CP_ERR_NUMERIC if
 * a non-finite value appeared (the point is not written; cannot happen after a
 * successful init walk, kept as a guard). */
int toolpath_next(struct toolpath *tp, struct toolpath_pt *pt);

/* Restart at point k (0 <= k <= count): the next call of toolpath_next yields
 * exactly the point it yielded the first time at position k (resume after a
 * hang-up). Cost: re-integrates Lambda up to that node (bounded). */
CP_MUST_CHECK int toolpath_seek(struct toolpath *tp, uint32_t k);

#endif /* TOOLPATH_H */
