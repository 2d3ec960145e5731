/* raster.c - the raster plumbing shared by the model iterators (raster.h).
 * SPDX-License-Identifier: MIT
 */
#include "raster.h"

int raster_check(const struct raster_cfg *c, cp_real umax)
{
    if (c == NULL || c->mode > RASTER_CIRCLES || c->output > RASTER_OUT_TIP ||
        (c->output == RASTER_OUT_SURFACE && c->tool_r != CP_R(0.0))) {
        return CP_ERR_INVAL;
    }
    if (!cp_finite(c->u0) || !cp_finite(c->u1) || !cp_finite(c->tol) || !cp_finite(c->tool_r)) {
        return CP_ERR_NONFINITE;
    }
    if (c->n == 0u || cp_fabs(c->u0) > umax || cp_fabs(c->u1) > umax ||
        (c->u0 == c->u1 && c->n > 1u) ||
        (c->tol != CP_R(0.0) && (c->tol < CP_R(1e-5) || c->tol > CP_R(10.0))) ||
        (c->tol == CP_R(0.0) && c->steps == 0u) ||
        (c->link != RASTER_LINK_AUTO && c->link > CP_MAX_LINK)) {
        return CP_ERR_RANGE;
    }
    if (c->n > CP_MAX_LINES || c->steps > CP_MAX_STEPS) {
        return CP_ERR_TOO_MANY;
    }
    return c->tool_r < CP_R(0.0) ? CP_ERR_TOOL : CP_OK;
}

uint32_t raster_count(uint32_t n, uint32_t steps, uint32_t link)
{
    return n * (steps + 1u) + (n - 1u) * link;
}

void raster_locate(uint32_t k, uint32_t steps, uint32_t link, struct raster_at *at)
{
    uint32_t j = k / (steps + 1u + link), r = k % (steps + 1u + link);
    uint32_t a = r > steps ? r - steps : 0u, i = a ? steps : r; /* a link: line j's end */
    i = (j & 1u) ? steps - i : i;                                /* zigzag */
    at->j = j;
    at->i = i;
    at->a = a;
    at->line = a ? -1 : (int32_t)j;
    at->index = a ? a : i;
}

int raster_seek(struct raster_head *h, uint32_t k)
{
    if (k > h->count) {
        return CP_ERR_RANGE;
    }
    h->k = k;
    return CP_OK;
}

void raster_fit_begin(struct raster_fit *f, const struct raster_cfg *c,
                      const struct raster_rule *rule)
{
    f->rule = rule;
    f->tol = c->tol > CP_R(0.0) ? c->tol : CP_R(1e-3);
    f->derive = 0u;
    f->round = 0u;
    /* steps: given, or derived from the rule's start */
    if (c->steps == 0u) {
        f->derive |= RASTER_FIT_STEPS;
        f->m[0] = rule->start;
    } else {
        f->m[0] = c->steps;
    }
    /* link segments: derived from 1 (RASTER_LINK_AUTO with two lines or more), else
     * the given link points + 1 (1 for a single line: there is no link) */
    if (c->n < 2u) {
        f->m[1] = 1u;
    } else if (c->link == RASTER_LINK_AUTO) {
        f->derive |= RASTER_FIT_LINK;
        f->m[1] = 1u;
    } else {
        f->m[1] = (uint32_t)c->link + 1u;
    }
}

/* Per derived count q (steps, then link segments): verified counts stay (not on a pilot
 * walk); else the h^2 law of the sagitta gives the estimate (raster.h), clamped or
 * refused above the maximum, at least the minimum and, after a pilot (or always without
 * one), at least the growth step, so every round that does not end the search changes
 * m[] upwards (except the pilot's re-estimate, which may go down). */
int raster_fit_update(struct raster_fit *f, const cp_real *sag)
{
    const struct raster_rule *r = f->rule;
    unsigned q, pilot = r->pilot != 0u && f->round == 0u;
    int res = CP_OK;
    for (q = 0; q < 2u; q++) {
        uint32_t m = f->m[q], hi = q ? CP_MAX_LINK + 1u : CP_MAX_STEPS, want, g;
        cp_real est;
        if (((f->derive >> q) & 1u) == 0u || (!pilot && sag[q] <= r->accept * f->tol)) {
            continue;
        }
        if (f->round >= RASTER_FIT_ROUNDS) {
            return CP_ERR_TOL;
        }
        est = (cp_real)m * cp_sqrt(sag[q] / (r->aim * f->tol)) * CP_R(1.05);
        if (!(est <= (cp_real)hi)) { /* NaN included */
            if (r->clamp == 0u || m >= hi) {
                return CP_ERR_TOL;
            }
            est = (cp_real)hi;
        }
        want = (uint32_t)cp_ceil(est);
        g = q ? 1u : RASTER_MIN_STEPS;
        want = want < g ? g : want;
        g = m + 1u + (m >> r->grow_shift);
        want = !pilot && want < g ? g : want;
        if (want > hi) {
            return CP_ERR_TOL;
        }
        f->m[q] = want;
        res = RASTER_FIT_MORE;
    }
    f->round++;
    return res;
}

int raster_seam_check(cp_real v0, cp_real d0, cp_real dd0, cp_real v1, cp_real d1,
                      cp_real dd1, cp_real len)
{
    cp_real w = CP_R(1.0) + cp_fabs(d0) + cp_fabs(d1), pos = RASTER_SEAM_VALUE * len;
    /* (a NaN fails both comparisons) */
    if (!(cp_fabs(v1 - v0) <= pos * w) ||
        !(cp_fabs(d1 - d0) <= RASTER_SEAM_SLOPE * w + pos * (cp_fabs(dd0) + cp_fabs(dd1)))) {
        return CP_ERR_SEAM;
    }
    return CP_OK;
}
