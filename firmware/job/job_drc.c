/* job_drc.c - protocol commands of SURFACE DRC (docs/PROTOCOL.md, "DRC").
 * SPDX-License-Identifier: MIT
 *
 *   POINT x y [z]      append a point of the sketched curve (mm, z default 0,
 *                      |coordinate| <= 10000: error:6; z != 0: error:25, the stream is
 *                      planar; both drc_point_check, as at RUN); error:14 when
 *                      CP_MAX_DRC_POINTS are given
 *   POINTS CLEAR       forget the points
 *   THICKEN K | AUTO   K passes (0..CP_MAX_PASSES; above: error:14), or AUTO (default):
 *                      the smallest K whose chord sagitta meets TOL (verified at RUN)
 *   EDGE ON | OFF      ON: a fillet along the sketched edge (canal surface of the RADIUS
 *                      law over the normalised arc length, lines of LINES n u0 u1, TOOL);
 *                      OFF (default): the thickened curve itself. EDGE ON needs RADIUS
 *                      (RUN without it: error:10, job_ready); LINES defaults to one line
 *                      at u = 0 (the contact curve, where the fillet meets the plane)
 * Arguments are checked at once (error:3 arity, 4/5 numbers, 9 keyword by job.c from commands.def,
 * 6 range, 25 off the plane); the geometry at RUN (drc_path_init: error:31 fewer than 3
 * points, 33 coincident, 37 turn >= 90 deg, 17 TOL unreachable, ...).
 */
#include "job.h"

void job_drc_defaults(union path_geom *g)
{
    g->drc.n = 0u;
    g->drc.passes = DRC_PASSES_AUTO;
    g->drc.edge = 0u;
}

int job_drc_ready(const struct job *j)
{
    /* EDGE ON is a fillet: without a RADIUS law the job is incomplete (error:10); LINES
     * may default (one line, u = 0) */
    const struct drc_cfg *g = &j->geom.drc;
    return g->n > 0u && (g->edge == 0u || (j->have & JOB_HAVE_RADIUS) != 0u);
}

int job_drc_command(struct job *j, struct job_args *a)
{
    struct drc_cfg *g = &j->geom.drc;
    const cp_real *v = a->v;
    struct cp_vec3 q;
    int err;
    switch (a->cmd) {
    case DRC_CMD_POINT: /* x y [z] */
        q.x = v[0];
        q.y = v[1];
        q.z = a->na == 2u ? CP_R(0.0) : v[2];
        err = drc_point_check(&q, 1); /* drc_path_init's checks of the point alone */
        if (err != CP_OK) {
            a->limit = err == CP_ERR_OFF_PLANE ? "z = 0" : "|x|, |y|, |z| <= 1e4";
            return cp_status_of(err);
        }
        if (g->n >= CP_MAX_DRC_POINTS) {
            a->limit = "POINTS CLEAR";
            return CP_ST_TOO_MANY;
        }
        g->p[g->n] = q;
        g->n++;
        return CP_ST_OK;
    case DRC_CMD_POINTS_CLEAR:
        g->n = 0u;
        return CP_ST_OK;
    case DRC_CMD_THICKEN: /* AUTO (its value: DRC_PASSES_AUTO) | K */
        if (a->word == JOB_WORD_THICKEN_AUTO) {
            g->passes = (uint8_t)a->value;
            return CP_ST_OK;
        }
        if (a->u > CP_MAX_PASSES) {
            a->bad = JOB_ARG_U;
            return CP_ST_TOO_MANY;
        }
        g->passes = (uint8_t)a->u;
        return CP_ST_OK;
    case DRC_CMD_EDGE: /* OFF | ON: 0 | 1 */
        g->edge = (uint8_t)a->value;
        return CP_ST_OK;
    default: /* not DRC's (unreachable: job.c calls the owner's hook) */
        return CP_ST_UNKNOWN_CMD;
    }
}

/* $J: items 0..CP_MAX_DRC_POINTS - 1 the POINTs given (x y: z is 0, POINT checks it), then
 * THICKEN K (AUTO is the default), then EDGE ON (OFF is the default). */
int job_drc_dump(const struct job *j, unsigned i, struct job_args *a)
{
    const struct drc_cfg *g = &j->geom.drc;
    if (i < CP_MAX_DRC_POINTS) {
        job_dump_args(a, DRC_CMD_POINT, JOB_NO_WORD);
        a->na = 2u;
        if (i < g->n) {
            a->v[0] = g->p[i].x;
            a->v[1] = g->p[i].y;
            return JOB_DUMP_LINE;
        }
        return JOB_DUMP_SKIP;
    }
    if (i == CP_MAX_DRC_POINTS) {
        job_dump_args(a, DRC_CMD_THICKEN, JOB_NO_WORD);
        a->u = g->passes;
        return g->passes == DRC_PASSES_AUTO ? JOB_DUMP_SKIP : JOB_DUMP_LINE;
    }
    if (i == CP_MAX_DRC_POINTS + 1u) {
        job_dump_args(a, DRC_CMD_EDGE, JOB_WORD_EDGE_ON);
        return g->edge != 0u ? JOB_DUMP_LINE : JOB_DUMP_SKIP;
    }
    return JOB_DUMP_END;
}
