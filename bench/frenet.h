/* frenet.h - BASELINE ONLY: the paper's two-quadrature Frenet form (MATH-canal §5.1).
 * SPDX-License-Identifier: MIT
 *
 * Not part of the firmware image. Used by `make bench` to compare cost and accuracy
 * with the contact-frame single quadrature of firmware/models/canal_path.c. Restricted to the
 * shape of the paper's example: C = ARC (cx, cy, r, counter-clockwise), R = b cos(k t) + c.
 *
 *   v(t, w) = v1 + 1 / (Phi (w + Psi)),  u_F = 2 atan v  (Frenet angle)
 *   Phi = exp(int X),  X = sigma tau v1 + R'|W| / (sigma^2 c),  Psi = int (sigma tau / 2) / Phi
 *   (ln Phi, Psi) advanced by classical RK4, one step per output point; needs rho'''.
 */
#ifndef FRENET_H
#define FRENET_H

#include "cp_math.h"

struct frenet {
    cp_real cx, cy, r, b, c, k; /* ARC and COS-law parameters */
    cp_real t0, h;              /* start, step */
    cp_real w;                  /* Frenet label of the line */
    cp_real y1, y2;             /* ln Phi, Psi at node i */
    cp_real x_prev, y_prev;     /* X and sigma tau / 2 at node i */
    uint32_t i;                 /* current node */
};

/* Line that starts at contact-frame angle u0 (radians, != 0) on the circle at t0;
 * n steps over [t0, t1]. Returns CP_OK or CP_ERR_RANGE if the Frenet frame or v1 is
 * singular at t0. */
int frenet_init(struct frenet *fr, cp_real cx, cp_real cy, cp_real r, cp_real b, cp_real c,
                cp_real k, cp_real t0, cp_real t1, uint32_t n, cp_real u0);

/* Point of node i (0 for the first call, then i + 1 each call): advances the RK4 state
 * by one step (except for the first call) and writes the surface point. */
void frenet_next(struct frenet *fr, struct cp_vec3 *m);

#endif /* FRENET_H */
