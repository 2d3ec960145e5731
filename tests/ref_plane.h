/* ref_plane.h - independent double-precision reference of the example model (a flat
 * strip, firmware/models/plane.h), written from its header's description only: no
 * firmware header, no firmware code.
 * SPDX-License-Identifier: MIT
 */
#ifndef REF_PLANE_H
#define REF_PLANE_H

struct ref_plane {
    double len, width;     /* mm */
    double u0, u1;         /* line labels, radians */
    unsigned n, steps, link;
};

/* Point k (0 <= k < n (steps + 1) + (n - 1) link) of the strip's zigzag raster: p[3] (mm)
 * and the unit normal nrm[3]. Returns 0, or -1 when k is past the last point. */
int ref_plane_point(const struct ref_plane *r, unsigned long k, double p[3], double nrm[3]);

#endif /* REF_PLANE_H */
