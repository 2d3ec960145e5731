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

/* (Not inlined: inlined into the canal's check begin, inside proto_poll, it cost the canal
 * image 12 B more than the call.) */
CP_NOINLINE void raster_fit_begin(struct raster_fit *f, const struct raster_cfg *c,
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

/* A piece of the curve for raster_overlap_check: the capsule of radius r about the segment
 * from a to b (the piece's ends), and the piece's length along the curve. */
struct ovl_piece {
    struct cp_vec3 a, b;
    cp_real rb;       /* the ball radius at b (the next piece's start) */
    cp_real r, len;
};

/* |a - b| */
static cp_real ovl_dist(const struct cp_vec3 *a, const struct cp_vec3 *b)
{
    struct cp_vec3 d;
    cp_v3_sub(a, b, &d);
    return cp_v3_norm(&d);
}

/* x clamped to [0, 1] (NaN: 0) */
static cp_real ovl_unit(cp_real x)
{
    return x > CP_R(0.0) ? (x < CP_R(1.0) ? x : CP_R(1.0)) : CP_R(0.0);
}

/* The distance from point x to the segment [a, b] (its closest point at the projection's
 * parameter clamped to [0, 1]; a segment of zero length is its point). */
static cp_real ovl_pt_seg(const struct cp_vec3 *x, const struct cp_vec3 *a, const struct cp_vec3 *b)
{
    struct cp_vec3 d, w, y;
    cp_real dd, t = CP_R(0.0);
    cp_v3_sub(b, a, &d);
    cp_v3_sub(x, a, &w);
    dd = cp_v3_dot(&d, &d);
    if (dd > CP_R(0.0)) {
        t = ovl_unit(cp_v3_dot(&w, &d) / dd);
    }
    cp_v3_comb(&y, CP_R(1.0), a, t, &d);
    return ovl_dist(x, &y);
}

/* A lower bound of the distance between the segments of pieces p and q: RASTER_OVERLAP_SEG
 * + 1 evenly spaced points of p's segment against q's segment, less half their spacing
 * (every point of p's segment is that close to one of them). */
static cp_real ovl_seg_dist(const struct ovl_piece *p, const struct ovl_piece *q)
{
    struct cp_vec3 d, x;
    cp_real best = CP_R(1.0e30);
    uint32_t m;
    cp_v3_sub(&p->b, &p->a, &d);
    for (m = 0; m <= RASTER_OVERLAP_SEG; m++) {
        cp_real e;
        cp_v3_comb(&x, CP_R(1.0), &p->a, (cp_real)m / (cp_real)RASTER_OVERLAP_SEG, &d);
        e = ovl_pt_seg(&x, &q->a, &q->b);
        best = e < best ? e : best;
    }
    return best - CP_R(0.5) * cp_v3_norm(&d) / (cp_real)RASTER_OVERLAP_SEG;
}

/* The piece after piece p, [u, u + du], in place: its start is p's end (p->b, p->rb); its
 * midpoint and end from ball(); the capsule radius is the largest of the three balls plus
 * RASTER_OVERLAP_SAG times the midpoint's distance from the chord; its length runs
 * through the midpoint. */
static int ovl_next(raster_ball_fn ball, const void *ctx, cp_real u, cp_real du,
                    struct ovl_piece *p)
{
    struct cp_vec3 m;
    cp_real rm, ra = p->rb;
    int err = ball(ctx, u + CP_R(0.5) * du, &m, &rm);
    p->a = p->b;
    if (err == CP_OK) {
        err = ball(ctx, u + du, &p->b, &p->rb);
    }
    p->r = ra > p->rb ? ra : p->rb;
    p->r = (rm > p->r ? rm : p->r) + RASTER_OVERLAP_SAG * ovl_pt_seg(&m, &p->a, &p->b);
    p->len = ovl_dist(&p->a, &m) + ovl_dist(&m, &p->b);
    return err;
}

int raster_overlap_check(raster_ball_fn ball, const void *ctx, cp_real grow,
                         struct raster_overlap *o)
{
    const cp_real du = CP_R(1.0) / (cp_real)RASTER_OVERLAP_K;
    struct ovl_piece pi, pj;
    struct cp_vec3 c0;
    cp_real len = CP_R(0.0), hmax = CP_R(0.0), rmax = CP_R(0.0), size = CP_R(0.0), near, gap;
    uint32_t i, j;
    int err, closed;
    o->ua = o->ub = CP_R(0.0);
    o->gap = CP_R(1.0e30);
    /* the curve's length, its longest piece, largest capsule and size */
    err = ball(ctx, CP_R(0.0), &pj.b, &pj.rb);
    c0 = pj.b;
    for (i = 0; i < RASTER_OVERLAP_K && err == CP_OK; i++) {
        err = ovl_next(ball, ctx, (cp_real)i * du, du, &pj);
        len += pj.len;
        hmax = pj.len > hmax ? pj.len : hmax;
        rmax = pj.r > rmax ? pj.r : rmax;
        gap = ovl_dist(&pj.b, &c0);
        size = gap > size ? gap : size;
    }
    if (err != CP_OK) {
        return err;
    }
    if (!cp_finite(len + rmax + grow)) {
        return CP_ERR_NUMERIC;
    }
    closed = ovl_dist(&pj.b, &c0) <= RASTER_SEAM_GAP * size;
    near = RASTER_OVERLAP_PI * (rmax + CP_R(0.5) * grow) + CP_R(2.0) * hmax;
    /* every pair of pieces i < j; `between`: the curve from the end of piece i to the
     * start of piece j */
    for (i = 0; i + 1u < RASTER_OVERLAP_K && err == CP_OK; i++) {
        cp_real between = CP_R(0.0);
        err = ball(ctx, (cp_real)i * du, &pi.b, &pi.rb);
        if (err == CP_OK) {
            err = ovl_next(ball, ctx, (cp_real)i * du, du, &pi);
        }
        pj = pi;
        for (j = i + 1u; j < RASTER_OVERLAP_K && err == CP_OK; j++) {
            err = ovl_next(ball, ctx, (cp_real)j * du, du, &pj);
            if (between >= near && (!closed || len - pi.len - between - pj.len >= near)) {
                gap = ovl_seg_dist(&pi, &pj) - pi.r - pj.r - grow;
                if (!(gap >= o->gap)) { /* the closest pair so far (a NaN too) */
                    o->ua = (cp_real)i * du;
                    o->ub = (cp_real)j * du;
                    o->gap = gap;
                }
                if (!(gap >= CP_R(0.0))) {
                    return cp_finite(gap) ? CP_ERR_OVERLAP : CP_ERR_NUMERIC;
                }
            }
            between += pj.len;
        }
    }
    return err;
}

/* (Not inlined: one copy for SPINE's and the channel's checks.) */
CP_NOINLINE int raster_overlap_report(raster_ball_fn ball, const void *ctx, struct raster_head *h)
{
    struct raster_overlap o;
    int err = raster_overlap_check(ball, ctx, CP_R(0.0), &o);
    h->overlap = err == CP_ERR_OVERLAP;
    return err == CP_ERR_OVERLAP ? CP_OK : err;
}
