/* place.h - placement on the part: the rigid transform of every streamed point and normal
 * (PLACE, TILT: job.h struct job_place; docs/PROTOCOL.md "Placement on the part").
 * SPDX-License-Identifier: MIT
 *
 * The model yields p (mm, tool offset included) and its unit normal n in the part's frame;
 * the stream carries them on the table:
 *     p' = R p + off,   n' = R n,   R = T Rz
 * Rz turns by PLACE's rz about +Z (counter-clockwise seen from +Z); T inclines the base
 * plane by TILT's angle about the unit axis a = (cos axis, sin axis, 0) of the table's XY
 * plane through the part's origin (right hand about a; Rodrigues:
 * T = cos(t) I + sin(t) [a]x + (1 - cos(t)) a a^T). "The face is inclined 30 deg about the
 * line at 45 deg": TILT 45 30; a point of the part at +Y of a TILT 0 30 rises (z > 0).
 * off = (PLACE x, y, z). The transform is applied in one place, out.c's out_point, after
 * the model (every model, every output format); with no placement (R exactly I, off = 0:
 * `on` 0) the point is not touched, so the stream is byte-identical to one without
 * PLACE/TILT.
 *
 * Accuracy (float build; u = 2^-24 ~ 6e-8):
 *   the angles are reduced in degrees to |r| <= 45 by a multiple q of 90 (r = deg - 90 q
 *   is exact: Sterbenz, the operands are within a factor 2), so multiples of 90 give an
 *   exact 0 / +-1 matrix; then cp_sincos (abs error <= 1.2e-7). Each entry of R is a sum
 *   of at most 2 products of up to 3 such factors: |R - R_exact| <= ~6e-7 per entry
 *   (bound), |R^T R - I| <= 1.3e-7 measured (tests: place_matrix). A point: 3 products,
 *   2 sums and the offset's sum, |p' - p'_exact| <= 1e-6 |p| + 3 u (|p| + |off|) (bound):
 *   <= 0.3 um for |p| <= 173 mm and |off| <= 1.7 m; measured 0.09 um against a double
 *   transform for |p_i| <= 100 mm, |off_i| <= 1000 mm (place_accuracy). A normal stays
 *   unit to ~2e-7 (measured). The double build (host) is exact to ~1e-15 relative.
 * Cost on the M4F (make bench): place_apply 66 instructions per point (call included;
 * inlined in out_point), place_init 470 once per RUN (three cp_sincos); no per-point trig.
 */
#ifndef PLACE_H
#define PLACE_H

#include "cp_types.h"
#include "job.h"

struct place {
    struct cp_vec3 row[3]; /* R's rows: p'_i = row[i] . p + off_i */
    struct cp_vec3 off;    /* mm */
    uint8_t on;            /* 0: R = I exactly and off = 0 (place_apply not called) */
};

/* sin and cos of deg degrees, |deg| <= 360 (larger |deg|: still finite, less exact):
 * exact for multiples of 90, else cp_sincos's error after an exact reduction to 45. */
void place_sincos_deg(cp_real deg, cp_real *s, cp_real *c);

/* Build the transform of a job's PLACE and TILT (ranges of job.h, checked at the
 * commands): once per RUN. Cannot fail. */
void place_init(struct place *pl, const struct job_place *jp);

/* p <- R p + off, n <- R n (in place; pl->on or not: the caller tests pl->on). */
void place_apply(const struct place *pl, struct raster_pt *pt);

#endif /* PLACE_H */
