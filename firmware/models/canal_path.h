/* canal_path.h - the canal model's iterator: pull iterator over a canal-surface patch,
 * exactly canal_path_count() points (struct raster_pt, raster.h).
 * SPDX-License-Identifier: MIT
 *
 * The patch is bounded by two family-2 curvature lines (the lines that start at
 * contact-frame angles U0 and U1 on the first circle, t = t0) and by the first and
 * last characteristic circles (t = t0, t = t1). Two raster modes cover it:
 *
 *   RASTER_LINES   n family-2 lines, start angles U0 + j (U1 - U0)/(n - 1), each
 *                  with steps + 1 points at t_i = t0 + i h (i from 0, never
 *                  accumulated). Zigzag: even lines run i = 0..steps, odd lines
 *                  i = steps..0. Consecutive lines are linked by `link` points on
 *                  the characteristic circle where they meet (family 1), so the
 *                  stream never jumps. count = n (steps + 1) + (n - 1) link.
 *   RASTER_CIRCLES n characteristic circles at t_j = t0 + j (t1 - t0)/(n - 1), each
 *                  with steps + 1 points evenly spaced in the contact-frame angle
 *                  from line U0 to line U1 (zigzag: odd circles run backwards).
 *                  Consecutive circles are linked by `link` points along the
 *                  bounding family-2 line where they meet.
 *                  count = n (steps + 1) + (n - 1) link.
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
#ifndef CANAL_PATH_H
#define CANAL_PATH_H

#include "canal.h"
#include "raster.h"

/* Target error of Lambda's quadrature in position: 2 R_max |dLambda| <= this, mm. */
#define CANAL_PATH_LAMBDA_TOL CP_R(2.0e-5)

struct canal_path {
    struct raster_head head; /* mode, n, steps, link, count, k (raster.h) */
    /* the rest of the raster request */
    uint8_t output;          /* enum raster_output */
    uint8_t labels;          /* enum raster_labels */
    uint8_t span;            /* enum raster_span */
    cp_real u0, u1;          /* bounding lines (labels) */
    cp_real tool_r;          /* mm */
    /* the surface */
    struct canal surf;
    cp_real q0;              /* q at t0 (labels) */
    cp_real r0;              /* R(t0): exact Lambda = kappa (R - r0) when the curvature of C
                                is constant */
    /* the grid and Lambda's quadrature state */
    uint16_t substeps;       /* Simpson panels per output step */
    cp_real hp;              /* half-panel width in t: output/node step = 2 substeps hp */
    uint8_t quad_valid;      /* 1: node, lam, comp, g_node hold the quadrature; 0: none yet
                                (after a seek, at the start of an even line, and always when
                                the curvature of C is constant) */
    uint32_t node;           /* half-node index of Lambda's quadrature state */
    cp_real lam, comp;       /* Lambda at node, Kahan compensation */
    cp_real g_node;          /* integrand g at node */
    /* label caches. LINES with ANGLE labels: the label of line j is (q0 cos x_j, sin x_j),
     * x_j = u0 / 2 + j lab_d. The next line's label is made in two halves over the last two
     * points of a line (cp_sincos_stage1, then stage2), so no point of the stream pays a
     * whole sincos on top of its own work: the per-point cost stays flat. */
    cp_real lab_d;
    int32_t lab_line;        /* line whose label is cached in lab_a, lab_b (-1: none) */
    cp_real lab_a, lab_b;
    int32_t lab2_line;       /* line whose label is cached in lab2_a, lab2_b (the next line) */
    cp_real lab2_a, lab2_b;
    int32_t st_line;         /* line whose label's first half is in st (-1: none) */
    struct cp_sincos_st st;
};

/* Lambda's quadrature at a half-node: Lambda, its Kahan compensation, the integrand g. */
struct canal_quad {
    cp_real lam, comp, g;
};

/* ---- the check in slices (issue 22: a controller that always answers) ----
 *
 * canal_path_init is a long computation for a large job (it walks the whole patch once per
 * round of the tolerance search; hundreds of millions of instructions at CP_MAX_LINES x
 * CP_MAX_STEPS). The same work runs in slices so that its caller can read its link between
 * them (proto.c: '?' and Ctrl-X during RUN's check):
 *
 *     err = canal_path_check_begin(&tp, &surf, &raster, &chk);      (the surface, the raster)
 *     while (err == CANAL_CHECK_MORE) {                              (<= CANAL_CHECK_STEPS_MAX)
 *         (read the link)
 *         err = canal_path_check_step(&tp, &raster, &chk);
 *     }                                            (CP_OK: tp streams; else canal_path_init's code)
 *
 * Every step does at most CANAL_CHECK_WORK work units (one unit: a jet of C and R, or one
 * label or point of the patch checked), fixed before the step starts from the costs of its
 * phase; the worst step on the M4F is measured by `make pollgap`. The phases (enum
 * canal_check_phase) are canal_path_init's, in its order: the panel estimate of Lambda, then
 * per round of the tolerance search a walk of the grid (CIRCLES: its nodes and circles,
 * then its sagittas when the link is derived; LINES: its sagittas), then (LINES) the link
 * arcs at both ends. Results, counts and codes are exactly canal_path_init's: the same
 * operations in the same order, only cut between grid steps. surf and raster are read at
 * begin and raster at every step: it must not change until the check ends. */
#define CANAL_CHECK_MORE 1
#define CANAL_CHECK_WORK 2048u
/* Steps a check can take: each step does at least one grid step, label pair or link
 * march step. Per round <= 2 walks of <= 4 CP_MAX_STEPS + 1 nodes (the grid is refused
 * above 4 CP_MAX_STEPS steps) plus its set-up; rounds <= RASTER_FIT_ROUNDS + 1; the link
 * phase 2 (CP_MAX_LINES - 1) pairs and CP_MAX_STEPS march steps; the panel estimate 1. */
#define CANAL_CHECK_STEPS_MAX                                                                       \
    ((RASTER_FIT_ROUNDS + 1u) * (2u * (4u * CP_MAX_STEPS + 1u) + 1u) + 2u * CP_MAX_LINES +        \
     CP_MAX_STEPS + 2u)

enum canal_check_phase {
    CANAL_CHECK_LAMBDA = 0, /* the Simpson panel count of Lambda (one step) */
    CANAL_CHECK_ROUND = 1,  /* set up the next round of the tolerance search's grid */
    CANAL_CHECK_NODES = 2,  /* CIRCLES: the grid's nodes regular, its circles probed */
    CANAL_CHECK_SAG = 3,    /* the grid's sagittas (LINES: every line regular) */
    CANAL_CHECK_LINK = 4    /* LINES: the link arcs at t0, the march to t1, the arcs at t1 */
};

struct canal_check {
    uint8_t phase;         /* enum canal_check_phase of the next step */
    uint8_t walk;          /* walks of the patch begun (progress) */
    uint32_t i, m;         /* the phase's next unit and its count (progress: grid nodes or
                              steps, or link pairs and march steps) */
    uint32_t panels;       /* Simpson panels over [t0, t1] (LAMBDA's estimate) */
    struct raster_fit fit; /* the tolerance search */
    cp_real sag[2];        /* the round's measured sagittas (raster_fit_update) */
    uint32_t worst;        /* segments of the worst circle (CIRCLES) or link arc (LINES) */
    /* a walk's carry from one step to the next: Lambda and the frame at its node, and
     * the largest sagitta so far */
    struct canal_quad q;
    struct canal_frame f;
    cp_real smax;
};

/* Begin the check: everything canal_path_init validates before its walks (the surface,
 * the raster, the tool). Returns CANAL_CHECK_MORE (go on with canal_path_check_step) or
 * one of canal_path_init's codes. tp streams nothing until the check ends with CP_OK. */
CP_MUST_CHECK int canal_path_check_begin(struct canal_path *tp, const struct canal_cfg *surf,
                                         const struct raster_cfg *raster, struct canal_check *c);

/* One slice of the check (<= CANAL_CHECK_WORK units). Returns CANAL_CHECK_MORE, CP_OK (the
 * counts are fixed and tp is at point 0, as after canal_path_init) or canal_path_init's
 * code. raster: the one given to canal_path_check_begin, unchanged. */
CP_MUST_CHECK int canal_path_check_step(struct canal_path *tp, const struct raster_cfg *raster,
                                        struct canal_check *c);

/* Validate the surface (canal_init on surf, copied into tp) and the raster request (the
 * model's geometry first, then the raster, as every model), derive step counts, walk the
 * patch once for regularity. raster: every field of struct raster_cfg (labels LAMBDA and
 * span ANGLE are the canal's own). Neither surf nor raster is kept: both may change or go
 * after init.
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
 * Returns CP_OK; then canal_path_next() yields exactly canal_path_count() points. */
CP_MUST_CHECK int canal_path_init(struct canal_path *tp, const struct canal_cfg *surf,
                                  const struct raster_cfg *raster);

/* Total number of points the iterator yields (tp->head.count; 0 until init succeeded). */
uint32_t canal_path_count(const struct canal_path *tp);

/* Next point. Returns CP_OK, CP_ERR_DONE after the last point, or CP_ERR_NUMERIC if
 * a non-finite value appeared (the point is not written; cannot happen after a
 * successful init walk, kept as a guard). */
int canal_path_next(struct canal_path *tp, struct raster_pt *pt);

/* Restart at point k (0 <= k <= count): the next call of canal_path_next yields
 * exactly the point it yielded the first time at position k (resume after a
 * hang-up). Cost: re-integrates Lambda up to that node (bounded). */
CP_MUST_CHECK int canal_path_seek(struct canal_path *tp, uint32_t k);

#endif /* CANAL_PATH_H */
