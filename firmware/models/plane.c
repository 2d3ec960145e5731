/* plane.c - the example model: a flat strip (plane.h).
 * SPDX-License-Identifier: MIT
 */
#include "plane.h"

static int check_geometry(const struct plane_cfg *g)
{
    if (!cp_finite(g->len) || !cp_finite(g->width)) {
        return CP_ERR_NONFINITE;
    }
    if (!(g->len > CP_R(0.0)) || g->len > PLANE_SIZE_MAX || !(g->width > CP_R(0.0)) ||
        g->width > PLANE_SIZE_MAX) {
        return CP_ERR_RANGE;
    }
    return CP_OK;
}

int plane_path_init(struct plane_path *it, const struct plane_cfg *g, const struct raster_cfg *raster)
{
    int err;
    cp_real half;
    if (it == NULL) {
        return CP_ERR_INVAL;
    }
    it->head.count = 0u;
    it->head.k = 0u;
    it->head.overlap = 0u; /* a flat strip never meets itself */
    if (g == NULL || raster == NULL) {
        return CP_ERR_INVAL;
    }
    err = raster_check(raster, CP_PI);
    if (err != CP_OK) {
        return err;
    }
    if (raster->mode != RASTER_LINES || raster->output != RASTER_OUT_SURFACE) {
        return CP_ERR_INVAL;
    }
    err = check_geometry(g);
    if (err != CP_OK) {
        return err;
    }
    it->head.mode = RASTER_LINES;
    it->head.n = raster->n;
    it->head.steps = raster->steps != 0u ? raster->steps : RASTER_MIN_STEPS;
    it->head.link = raster->link == RASTER_LINK_AUTO ? 0u : raster->link;
    it->len = g->len;
    half = CP_R(0.5) * g->width / CP_PI;
    it->y0 = half * raster->u0;
    it->dy = raster->n > 1u ? half * (raster->u1 - raster->u0) / (cp_real)(raster->n - 1u)
                            : CP_R(0.0);
    it->head.count = raster_count(it->head.n, it->head.steps, it->head.link);
    return CP_OK;
}

uint32_t plane_path_count(const struct plane_path *it)
{
    return it->head.count;
}

int plane_path_next(struct plane_path *it, struct raster_pt *pt)
{
    struct raster_at at;
    cp_real x, y;
    if (it->head.k >= it->head.count) {
        return CP_ERR_DONE;
    }
    raster_locate(it->head.k, it->head.steps, it->head.link, &at);
    x = it->len * (cp_real)at.i / (cp_real)it->head.steps;
    y = it->y0 + (cp_real)at.j * it->dy;
    if (at.line < 0) { /* link point a of link + 1 segments from line j to line j + 1 */
        y += it->dy * (cp_real)at.a / (cp_real)(it->head.link + 1u);
    }
    pt->p.x = x;
    pt->p.y = y;
    pt->p.z = CP_R(0.0);
    pt->n.x = CP_R(0.0);
    pt->n.y = CP_R(0.0);
    pt->n.z = CP_R(1.0);
    pt->t = x / it->len;
    pt->line = (int16_t)at.line;
    pt->index = (uint16_t)at.index;
    it->head.k++;
    return CP_OK;
}

int plane_path_seek(struct plane_path *it, uint32_t k)
{
    return raster_seek(&it->head, k);
}
