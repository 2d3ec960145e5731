/* accuracy.c - host benchmark: max error vs step count, contact-frame single
 * quadrature (firmware/models/canal_path.c) against the paper's Frenet two-quadrature form
 * (bench/frenet.c), on the paper's example where the exact grid is elementary:
 * Lambda(t) = (11/6)(cos 2t - 1) (MATH-canal §7), evaluated in long double at the
 * same (cp_real) t nodes the firmware used.
 * Prints one table row per N and the smallest N reaching 1 um for each method.
 * SPDX-License-Identifier: MIT
 */
#include <stdio.h>

#include "frenet.h"
#include "canal_path.h"

#define NLINES 5
static const double u0s[NLINES] = {-0.5, -0.33, -0.16, 0.01, 0.18};

/* exact point of the line starting at contact angle u0 (t0 = 0, q0 = 1) at t */
static void exact(long double t, long double u0, long double m[3])
{
    long double st = sinl(t), ct = cosl(t);
    long double R = 5.5L * cosl(2.0L * t) + 10.5L;
    long double p = -(11.0L / 3.0L) * sinl(2.0L * t);
    long double lam0 = cosl(0.5L * u0), b = sinl(0.5L * u0);
    long double h = lam0 + (11.0L / 6.0L) * (cosl(2.0L * t) - 1.0L) * b;
    long double den = (1.0L + p * p) * b * b + h * h;
    long double s = 2.0L * R * b / den;
    /* t_C = (-sin, cos), n_C = (-cos, -sin) */
    m[0] = 3.0L * ct + s * (-p * b * -st + h * -ct);
    m[1] = 3.0L * st + s * (-p * b * ct + h * -st);
    m[2] = s * b;
}

static double err3(const struct cp_vec3 *p, const long double m[3])
{
    long double dx = (long double)p->x - m[0], dy = (long double)p->y - m[1],
                dz = (long double)p->z - m[2];
    return (double)sqrtl(dx * dx + dy * dy + dz * dz);
}

/* ellipse = 1: the same circle given as an ELLIPSE with A = B = 3, which takes the
 * general Simpson + Kahan quadrature path instead of the exact constant-curvature
 * Lambda of ARC. */
static double ours(uint32_t n, int ellipse)
{
    struct raster_cfg cfg = {0};
    struct canal_cfg surf = {0};
    struct canal_path tp;
    struct raster_pt pt;
    double worst = 0.0;
    surf.curve = ellipse ? CANAL_ELLIPSE : CANAL_ARC;
    surf.radius = CANAL_R_COS;
    surf.cp[2] = CP_R(3.0);
    surf.cp[3] = ellipse ? CP_R(3.0) : CP_R(0.0);
    surf.cp[4] = ellipse ? CP_R(0.0) : CP_TWO_PI;
    surf.cp[5] = ellipse ? CP_TWO_PI : CP_R(0.0);
    surf.rp[0] = CP_R(5.5);
    surf.rp[1] = CP_R(10.5);
    surf.rp[2] = CP_R(2.0);
    cfg.mode = RASTER_LINES;
    cfg.n = NLINES;
    cfg.u0 = (cp_real)u0s[0];
    cfg.u1 = (cp_real)u0s[NLINES - 1];
    cfg.steps = (uint16_t)n;
    cfg.substeps = 1;
    cfg.link = 0;
    if (canal_path_init(&tp, &surf, &cfg) != CP_OK) {
        return -1.0;
    }
    while (canal_path_next(&tp, &pt) == CP_OK) {
        long double m[3];
        double e;
        long double u0 = (long double)cfg.u0 +
                         ((long double)cfg.u1 - (long double)cfg.u0) * pt.line / (NLINES - 1);
        exact((long double)pt.t, (long double)(cp_real)u0, m);
        e = err3(&pt.p, m);
        worst = e > worst ? e : worst;
    }
    return worst;
}

static double frenet(uint32_t n)
{
    double worst = 0.0;
    int l;
    for (l = 0; l < NLINES; l++) {
        struct frenet fr;
        uint32_t i;
        cp_real u0 = (cp_real)u0s[l];
        if (u0 == CP_R(0.0)) {
            continue;
        }
        if (frenet_init(&fr, 0, 0, 3, CP_R(5.5), CP_R(10.5), 2, 0, CP_TWO_PI, n, u0) != CP_OK) {
            return -1.0;
        }
        for (i = 0; i <= n; i++) {
            struct cp_vec3 p;
            long double m[3];
            double e;
            cp_real t = fr.t0 + (cp_real)i * fr.h;
            frenet_next(&fr, &p);
            exact((long double)t, (long double)u0, m);
            e = err3(&p, m);
            worst = e > worst ? e : worst;
        }
    }
    return worst;
}

int main(void)
{
    uint32_t n, n_ours = 0, n_fr = 0, n_ours01 = 0, n_fr01 = 0, n_simp = 0;
    printf("accuracy (%s build), paper example, %d lines u0 in [-0.5, 0.18], max |error| mm\n",
           CP_REAL_NAME, NLINES);
    printf("%8s %16s %16s %14s\n", "N", "contact exact-L", "contact Simpson", "Frenet+RK4");
    for (n = 16; n <= 8192; n *= 2) {
        double a = ours(n, 0), c = ours(n, 1), b = frenet(n);
        if (a < 0.0 || c < 0.0) {
            printf("%8u %16s %16s %14.3e\n", (unsigned)n, "(> max steps)", "(> max steps)", b);
        } else {
            printf("%8u %16.3e %16.3e %14.3e\n", (unsigned)n, a, c, b);
        }
        if (n_simp == 0 && c >= 0.0 && c <= 1e-3) {
            n_simp = n;
        }
        if (n_ours01 == 0 && a >= 0.0 && a <= 1e-4) {
            n_ours01 = n;
        }
        if (n_fr01 == 0 && b >= 0.0 && b <= 1e-4) {
            n_fr01 = n;
        }
        if (n_ours == 0 && a >= 0.0 && a <= 1e-3) {
            n_ours = n;
        }
        if (n_fr == 0 && b >= 0.0 && b <= 1e-3) {
            n_fr = n;
        }
    }
    printf("accuracy-%s: 1 um needs N = %u (contact exact), %u (contact Simpson), %u (Frenet); "
           "0.1 um needs N = %u (contact exact), %u (Frenet); 0 = never\n",
           CP_REAL_NAME, (unsigned)n_ours, (unsigned)n_simp, (unsigned)n_fr, (unsigned)n_ours01,
           (unsigned)n_fr01);
    return 0;
}
