/* job_drc.c - protocol commands of SURFACE DRC (docs/PROTOCOL.md, "DRC").
 * SPDX-License-Identifier: MIT
 *
 *   POINT x y [z]      append a point of the sketched curve (mm, z default 0,
 *                      |coordinate| <= 10000); error:14 when CP_MAX_DRC_POINTS are given
 *   POINTS CLEAR       forget the points
 *   THICKEN K | AUTO   K passes (0..CP_MAX_PASSES; above: error:14), or AUTO (default):
 *                      the smallest K whose chord sagitta meets TOL (verified at RUN)
 *   EDGE ON | OFF      ON: a fillet along the sketched edge (canal surface of the RADIUS
 *                      law over the normalised arc length, lines of LINES n u0 u1, TOOL);
 *                      OFF (default): the thickened curve itself. EDGE ON needs RADIUS
 *                      (RUN without it: error:10, job_ready); LINES defaults to one line
 *                      at u = 0 (the contact curve, where the fillet meets the plane)
 * Arguments are checked at once (error:3 arity, 4/5 numbers, 6 range, 9 keyword); the
 * geometry at RUN (drc_path_init: error:31 fewer than 3 points, 33 coincident, 37 turn
 * >= 90 deg, 25 a point with z != 0 (the stream is planar), 17 TOL unreachable, ...).
 */
#include "job.h"
#include "parse.h"

CP_STATIC_ASSERT((JOB_HAVE_DRC_POINTS & ~JOB_HAVE_DRC_MASK) == 0u, drc_bit_in_mask);

void job_drc_defaults(union path_geom *g)
{
    g->drc.n = 0u;
    g->drc.passes = DRC_PASSES_AUTO;
    g->drc.edge = 0u;
}

/* Index of token t among kws[from..to) (to if none). */
static unsigned drc_kw(const struct job_line *l, unsigned t, unsigned from, unsigned to)
{
    static const char kws[8][8] = {"POINT", "POINTS", "THICKEN", "EDGE",
                                   "CLEAR", "AUTO",   "OFF",     "ON"};
    for (; from < to && !parse_is(l->s + l->st[t], l->ln[t], kws[from]); from++) {
    }
    return from;
}

int job_drc_command(struct job *j, const struct job_line *l)
{
    struct drc_cfg *g;
    cp_real v[3];
    uint32_t k;
    unsigned kw = l->nt == 0u ? 4u : drc_kw(l, 0u, 0u, 4u), a, i;
    int st;
    if (j == NULL || kw == 4u) {
        return j == NULL ? (kw != 4u) : JOB_NOT_MINE;
    }
    g = &j->geom.drc;
    if (kw == 0u) { /* POINT x y [z] */
        if (l->nt != 3u && l->nt != 4u) {
            return CP_ST_BAD_ARITY;
        }
        v[2] = CP_R(0.0);
        st = job_numbers(l, 1u, l->nt - 1u, v);
        for (i = 0; i < 3u; i++) {
            if (st == CP_ST_OK && cp_fabs(v[i]) > CANAL_COORD_MAX) {
                st = CP_ST_OUT_OF_RANGE;
            }
        }
        if (st == CP_ST_OK && g->n >= CP_MAX_DRC_POINTS) {
            st = CP_ST_TOO_MANY;
        }
        if (st == CP_ST_OK) {
            g->p[g->n].x = v[0];
            g->p[g->n].y = v[1];
            g->p[g->n].z = v[2];
            g->n++;
            j->have |= JOB_HAVE_DRC_POINTS;
        }
        return st;
    }
    if (l->nt != 2u) {
        return CP_ST_BAD_ARITY;
    }
    a = drc_kw(l, 1u, 4u, 8u); /* CLEAR 4, AUTO 5, OFF 6, ON 7 */
    if (kw == 2u && a != 5u) { /* THICKEN K */
        st = parse_uint(l->s + l->st[1], l->ln[1], 0xFFFFFFFFu, &k);
        if (st == CP_ST_OK && k > CP_MAX_PASSES) {
            st = CP_ST_TOO_MANY;
        }
        if (st == CP_ST_OK) {
            g->passes = (uint8_t)k;
        }
        return st;
    }
    if (kw == 1u && a == 4u) { /* POINTS CLEAR */
        g->n = 0u;
        j->have &= (uint16_t)~JOB_HAVE_DRC_POINTS;
    } else if (kw == 2u) { /* THICKEN AUTO */
        g->passes = DRC_PASSES_AUTO;
    } else if (kw == 3u && a - 6u < 2u) { /* EDGE OFF | ON */
        g->edge = (uint8_t)(a - 6u);
    } else {
        return CP_ST_BAD_KEYWORD;
    }
    return CP_ST_OK;
}
