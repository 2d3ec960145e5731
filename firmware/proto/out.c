/* out.c - what the output formats share (out.h).
 * SPDX-License-Identifier: MIT
 */
#include "out.h"

int out_point(struct path *path, uint32_t k, struct raster_pt *pt)
{
    if (path_pos(path) != k && path_seek(path, k) != CP_OK) {
        return CP_ERR_RANGE;
    }
    return path_next(path, pt);
}

/* Out of line: one rounding, the same code for every coordinate of every format. */
CP_NOINLINE int32_t out_quantize(cp_real v, cp_real scale)
{
    return (int32_t)cp_floor(v * scale + CP_R(0.5));
}
