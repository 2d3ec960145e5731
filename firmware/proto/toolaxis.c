/* toolaxis.c - the tool axis of 5-axis output (toolaxis.h).
 * SPDX-License-Identifier: MIT
 */
#include "toolaxis.h"
#include "cp_math.h"

#define TOOLAXIS_RAD2DEG CP_R(57.295779513082320877)

void toolaxis_init(struct toolaxis *t, cp_real lead_deg, cp_real side_deg)
{
    cp_sincos(lead_deg * CP_DEG2RAD, &t->sl, &t->cl);
    cp_sincos(side_deg * CP_DEG2RAD, &t->ss, &t->cs);
}

void toolaxis_of(const struct toolaxis *t, const struct cp_vec3 *n, const struct cp_vec3 *d,
                 struct cp_vec3 *a)
{
    struct cp_vec3 tr, s;
    cp_real dn = cp_v3_dot(d, n), len;
    cp_v3_comb(&tr, CP_R(1.0), d, -dn, n); /* d without its normal part */
    len = cp_v3_norm(&tr);
    if (!(len > CP_R(1e-9) * cp_v3_norm(d))) {
        *a = *n; /* no travel in the tangent plane: the normal itself */
        return;
    }
    tr.x /= len;
    tr.y /= len;
    tr.z /= len;
    cp_v3_cross(n, &tr, &s);
    a->x = t->cs * (t->cl * n->x + t->sl * tr.x) + t->ss * s.x;
    a->y = t->cs * (t->cl * n->y + t->sl * tr.y) + t->ss * s.y;
    a->z = t->cs * (t->cl * n->z + t->sl * tr.z) + t->ss * s.z;
}

void toolaxis_ac(const struct cp_vec3 *a, cp_real *A, cp_real *C)
{
    cp_real r = cp_sqrt(a->x * a->x + a->y * a->y);
    *A = cp_atan2(r, a->z) * TOOLAXIS_RAD2DEG;
    *C = r > CP_R(0.0) ? cp_atan2(a->x, -a->y) * TOOLAXIS_RAD2DEG : CP_R(0.0);
}
