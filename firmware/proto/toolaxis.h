/* toolaxis.h - the tool axis of 5-axis output (TOOLAXIS): the streamed normal tilted by a
 * lead and a side angle, as A/C angles of a table-table machine or as a tool vector.
 * SPDX-License-Identifier: MIT
 *
 * At point p with unit normal n (the streamed one: placed, from the surface towards the
 * tool's side) moving along d (the chord to the next point, or from the previous one at
 * the path's last point), in the frame t = unit(d - (d.n) n) (the travel direction in
 * the tangent plane), s = n x t (its left side):
 *     a = cos(side) (cos(lead) n + sin(lead) t) + sin(side) s        (|a| = 1)
 * lead tilts the axis forward along the travel, side to its left. Where d has no part in
 * the tangent plane (|d - (d.n) n| <= 1e-9 |d|, or d = 0) a = n.
 * A/C (TOOLAXIS AC, a table-table A/C machine with tool centre point control, G43.4 in
 * LinuxCNC's sense): the table angles that bring a to the spindle's +Z:
 *     A = atan2(sqrt(a_x^2 + a_y^2), a_z)   in [0, 180] degrees
 *     C = atan2(a_x, -a_y)                  in [-180, 180] degrees (0 where A = 0)
 * so that a = (sin A sin C, -sin A cos C, cos A); C is not unwrapped (a wrapped rotary C:
 * LinuxCNC [AXIS_C] WRAPPED_ROTARY = 1 takes the short way across +-180).
 * Error: the angles are float32 atan2 of float32 components (cp_atan2: 1 ulp-class), |a|
 * within 1e-6 of 1: A and C within ~1e-4 degree, far below their 3 printed decimals.
 */
#ifndef TOOLAXIS_H
#define TOOLAXIS_H

#include "cp_types.h"

struct toolaxis {
    cp_real cl, sl; /* cos, sin of lead */
    cp_real cs, ss; /* cos, sin of side */
};

/* Set up the angles (degrees, within JOB_TOOLAXIS_ANGLE_MAX). */
void toolaxis_init(struct toolaxis *t, cp_real lead_deg, cp_real side_deg);

/* The unit tool axis a at a point with unit normal n moving along d (above). */
void toolaxis_of(const struct toolaxis *t, const struct cp_vec3 *n, const struct cp_vec3 *d,
                 struct cp_vec3 *a);

/* A and C of the unit axis a, degrees (above). */
void toolaxis_ac(const struct cp_vec3 *a, cp_real *A, cp_real *C);

#endif /* TOOLAXIS_H */
