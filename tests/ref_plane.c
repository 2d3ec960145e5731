/* ref_plane.c - the example model's reference (ref_plane.h): the raster walked line by
 * line, in double, from the description in plane.h.
 * SPDX-License-Identifier: MIT
 */
#include "ref_plane.h"

#define REF_PI 3.14159265358979323846

static double line_y(const struct ref_plane *r, double j)
{
    double v = r->n > 1u ? r->u0 + j * (r->u1 - r->u0) / (double)(r->n - 1u) : r->u0;
    return 0.5 * r->width * v / REF_PI;
}

int ref_plane_point(const struct ref_plane *r, unsigned long k, double p[3], double nrm[3])
{
    unsigned long per = (unsigned long)r->steps + 1ul, j;
    for (j = 0; j < r->n; j++) { /* line j, then its link */
        int back = (int)(j % 2ul);
        if (k < per) {
            double i = back ? (double)(r->steps - k) : (double)k;
            p[0] = r->len * i / (double)r->steps;
            p[1] = line_y(r, (double)j);
            break;
        }
        k -= per;
        if (j + 1ul < r->n && k < r->link) { /* straight move to the next line's start */
            double f = (double)(k + 1ul) / (double)(r->link + 1u);
            p[0] = back ? 0.0 : r->len;
            p[1] = (1.0 - f) * line_y(r, (double)j) + f * line_y(r, (double)j + 1.0);
            break;
        }
        k -= j + 1ul < r->n ? r->link : 0ul;
    }
    if (j == r->n) {
        return -1;
    }
    p[2] = 0.0;
    nrm[0] = 0.0;
    nrm[1] = 0.0;
    nrm[2] = 1.0;
    return 0;
}
