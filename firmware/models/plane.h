/* plane.h - the EXAMPLE model: a flat strip, rastered along its length. It exists to show
 * (and to test, `make example-model`) the add-a-model recipe of docs/ARCHITECTURE.md:
 * its own files plus one row per table. Compiled into an image only with CP_WITH_PLANE=1
 * (cp_config.h; 0 by default: no product image carries it).
 * SPDX-License-Identifier: MIT
 *
 * The strip: x in [0, len], y in [-width/2, width/2], z = 0, unit normal (0, 0, 1).
 * Raster (raster.h, RASTER_LINES only): line j runs along x at
 *     y_j = (width / 2) (v_j / pi),   v_j = u0 + j (u1 - u0) / (n - 1)   (v_0 = u0 if n == 1),
 * so LINES n u0 u1 in degrees maps -180..180 onto the strip's two edges. Point i of a
 * line is at x_i = len i / steps (zigzag: odd lines run back). A link is the straight
 * move between the ends of two lines, link points evenly spaced on it.
 * Counts: a straight line has no sagitta, so steps == 0 (derive) gives RASTER_MIN_STEPS
 * and a derived link (RASTER_LINK_AUTO) gives 0 points; given counts are kept.
 */
#ifndef PLANE_H
#define PLANE_H

#include "raster.h"

/* Largest strip length or width, mm (the job's coordinate bound). */
#define PLANE_SIZE_MAX CP_R(10000.0)

struct plane_cfg {
    cp_real len;   /* strip length along x, mm, (0, PLANE_SIZE_MAX] */
    cp_real width; /* strip width along y, mm, (0, PLANE_SIZE_MAX] */
};

struct plane_path {
    struct raster_head head; /* shape and position (raster.h) */
    cp_real len;             /* mm */
    cp_real y0, dy;          /* line j at y0 + j dy, mm */
};

/* Validate g and the raster, fix the counts. The iterator keeps copies: g and raster may
 * change afterwards. Errors, in this order:
 *   CP_ERR_INVAL      it, g or raster NULL; raster_check's INVAL; mode not RASTER_LINES,
 *                     output not RASTER_OUT_SURFACE (a tool is not modelled)
 *   (raster_check)    NONFINITE, RANGE (|u| > pi ...), TOO_MANY, TOOL
 *   CP_ERR_NONFINITE  len or width NaN/Inf
 *   CP_ERR_RANGE      len or width <= 0 or > PLANE_SIZE_MAX
 * Returns CP_OK; then plane_path_next yields exactly plane_path_count() points. */
CP_MUST_CHECK int plane_path_init(struct plane_path *it, const struct plane_cfg *g,
                                  const struct raster_cfg *raster);

/* Points of the path (0 until a successful init). */
uint32_t plane_path_count(const struct plane_path *it);

/* Next point: CP_OK, or CP_ERR_DONE after the last. */
int plane_path_next(struct plane_path *it, struct raster_pt *pt);

/* Restart at point k (0 <= k <= count): CP_OK, or CP_ERR_RANGE. */
CP_MUST_CHECK int plane_path_seek(struct plane_path *it, uint32_t k);

#endif /* PLANE_H */
