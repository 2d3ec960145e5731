/* out.c - what the output formats share (out.h).
 * SPDX-License-Identifier: MIT
 */
#include "out.h"

int out_point(struct path *path, const struct place *pl, uint32_t k, struct raster_pt *pt)
{
    int e;
    if (path_pos(path) != k && path_seek(path, k) != CP_OK) {
        return CP_ERR_RANGE;
    }
    e = path_next(path, pt);
    if (e == CP_OK && pl->on) {
        place_apply(pl, pt);
    }
    return e;
}

/* Out of line: one rounding, the same code for every coordinate of every format. */
CP_NOINLINE int32_t out_quantize(cp_real v, cp_real scale)
{
    return (int32_t)cp_floor(v * scale + CP_R(0.5));
}
