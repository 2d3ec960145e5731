/* place.c - placement on the part (place.h).
 * SPDX-License-Identifier: MIT
 */
#include "place.h"

#include "cp_math.h" /* cp_sincos */

void place_sincos_deg(cp_real deg, cp_real *s, cp_real *c)
{
    /* q: the multiple of 90 nearest deg (|q| <= 4 for |deg| <= 360); r = deg - 90 q is
     * exact (|r| <= 45 and, for q != 0, 90 q and deg within a factor 2: Sterbenz) */
    cp_real q = cp_floor(deg / CP_R(90.0) + CP_R(0.5));
    cp_real r = deg - CP_R(90.0) * q;
    cp_real sr, cr;
    unsigned quad = ((unsigned)((int)q + 4) & 3u); /* (q mod 4): q + 4 >= 0 */
    cp_sincos(r * CP_DEG2RAD, &sr, &cr);
    switch (quad) {
    case 1u: /* +90: sin = cos r, cos = -sin r */
        *s = cr;
        *c = -sr;
        break;
    case 2u:
        *s = -sr;
        *c = -cr;
        break;
    case 3u:
        *s = -cr;
        *c = sr;
        break;
    default:
        *s = sr;
        *c = cr;
        break;
    }
}

void place_init(struct place *pl, const struct job_place *jp)
{
    static const cp_real ident[3][3] = {
        {CP_R(1.0), CP_R(0.0), CP_R(0.0)},
        {CP_R(0.0), CP_R(1.0), CP_R(0.0)},
        {CP_R(0.0), CP_R(0.0), CP_R(1.0)},
    };
    cp_real sz, cz, sa, ca, st, ct, k;
    cp_real t[3][3]; /* T, the tilt (Rodrigues about a = (ca, sa, 0)) */
    unsigned i;
    place_sincos_deg(jp->rz, &sz, &cz);
    place_sincos_deg(jp->axis, &sa, &ca);
    place_sincos_deg(jp->tilt, &st, &ct);
    k = CP_R(1.0) - ct; /* exact (ct in [0, 1]: Sterbenz); 0 exactly without a tilt */
    t[0][0] = ct + k * ca * ca;
    t[0][1] = k * ca * sa;
    t[0][2] = st * sa;
    t[1][0] = k * ca * sa;
    t[1][1] = ct + k * sa * sa;
    t[1][2] = -st * ca;
    t[2][0] = -st * sa;
    t[2][1] = st * ca;
    t[2][2] = ct;
    pl->off.x = jp->off[0];
    pl->off.y = jp->off[1];
    pl->off.z = jp->off[2];
    /* off: on unless exactly 0 (a NaN is not) */
    pl->on =
        (uint8_t) !(pl->off.x == CP_R(0.0) && pl->off.y == CP_R(0.0) && pl->off.z == CP_R(0.0));
    /* R = T Rz, Rz = [cz -sz 0; sz cz 0; 0 0 1]; on unless R is exactly I (no PLACE/TILT,
     * rz a multiple of 360, tilt 0) */
    for (i = 0; i < 3u; i++) {
        struct cp_vec3 *r = &pl->row[i];
        r->x = t[i][0] * cz + t[i][1] * sz;
        r->y = t[i][1] * cz - t[i][0] * sz;
        r->z = t[i][2];
        if (r->x != ident[i][0] || r->y != ident[i][1] || r->z != ident[i][2]) {
            pl->on = 1u;
        }
    }
}

void place_apply(const struct place *pl, struct raster_pt *pt)
{
    /* row . v summed left to right (cp_v3_dot's order), written out: no calls per point */
    const struct cp_vec3 *r0 = &pl->row[0], *r1 = &pl->row[1], *r2 = &pl->row[2];
    const cp_real px = pt->p.x, py = pt->p.y, pz = pt->p.z;
    const cp_real nx = pt->n.x, ny = pt->n.y, nz = pt->n.z;
    pt->p.x = r0->x * px + r0->y * py + r0->z * pz + pl->off.x;
    pt->p.y = r1->x * px + r1->y * py + r1->z * pz + pl->off.y;
    pt->p.z = r2->x * px + r2->y * py + r2->z * pz + pl->off.z;
    pt->n.x = r0->x * nx + r0->y * ny + r0->z * nz;
    pt->n.y = r1->x * nx + r1->y * ny + r1->z * nz;
    pt->n.z = r2->x * nx + r2->y * ny + r2->z * nz;
}
