/* ref_canal.c - independent double-precision reference: jets, circles, adaptive
 * orthogonal trajectories (Dormand-Prince 5(4)). See ref_canal.h.
 * SPDX-License-Identifier: MIT
 */
#include <math.h>

#include "ref_canal.h"

#define REF_PI 3.14159265358979323846

static long ref_steps_total;

long ref_total_steps(void)
{
    return ref_steps_total;
}

void ref_canal_set(struct ref_canal *rc, int curve, int radius, const double cp[8],
                   const double rp[4])
{
    int i;
    rc->curve = curve;
    rc->radius = radius;
    for (i = 0; i < 8; i++) {
        rc->cp[i] = cp[i];
    }
    for (i = 0; i < 4; i++) {
        rc->rp[i] = rp[i];
    }
    rc->dir = 1.0;
    rc->t0 = 0.0;
    rc->t1 = 1.0;
    if (curve == REF_ARC || curve == REF_ELLIPSE) {
        double a0 = curve == REF_ARC ? cp[3] : cp[4];
        double a1 = curve == REF_ARC ? cp[4] : cp[5];
        if (a1 < a0) {
            rc->dir = -1.0;
            rc->t0 = -a0;
            rc->t1 = -a1;
        } else {
            rc->t0 = a0;
            rc->t1 = a1;
        }
    }
}

/* Radius law and its first two t-derivatives. */
static void ref_radius(const struct ref_canal *rc, double t, double *r, double *dr, double *ddr)
{
    const double *k = rc->rp;
    double is = 1.0 / (rc->t1 - rc->t0); /* ds/dt of the normalised parameter */
    double s = (t - rc->t0) * is;
    switch (rc->radius) {
    case REF_R_CONST:
        *r = k[0];
        *dr = 0.0;
        *ddr = 0.0;
        break;
    case REF_R_LINEAR:
        *r = k[0] + (k[1] - k[0]) * s;
        *dr = (k[1] - k[0]) * is;
        *ddr = 0.0;
        break;
    case REF_R_COS: {
        double th, dth;
        if (rc->curve == REF_ARC || rc->curve == REF_ELLIPSE) {
            th = rc->dir * t; /* the true curve angle */
            dth = rc->dir;
        } else {
            th = 2.0 * REF_PI * s;
            dth = 2.0 * REF_PI * is;
        }
        *r = k[0] * cos(k[2] * th) + k[1];
        *dr = -k[0] * k[2] * sin(k[2] * th) * dth;
        *ddr = -k[0] * k[2] * k[2] * cos(k[2] * th) * dth * dth;
        break;
    }
    default: { /* CUBIC, Bernstein basis */
        double v = 1.0 - s;
        *r = k[0] * v * v * v + 3.0 * k[1] * v * v * s + 3.0 * k[2] * v * s * s + k[3] * s * s * s;
        *dr = 3.0 * ((k[1] - k[0]) * v * v + 2.0 * (k[2] - k[1]) * v * s + (k[3] - k[2]) * s * s) * is;
        *ddr = 6.0 * ((k[2] - 2.0 * k[1] + k[0]) * v + (k[3] - 2.0 * k[2] + k[1]) * s) * is * is;
        break;
    }
    }
}

void ref_jet(const struct ref_canal *rc, double t, struct ref_jet *j)
{
    const double *c = rc->cp;
    switch (rc->curve) {
    case REF_LINE:
        j->x = c[0] + t * (c[2] - c[0]);
        j->y = c[1] + t * (c[3] - c[1]);
        j->dx = c[2] - c[0];
        j->dy = c[3] - c[1];
        j->ddx = 0.0;
        j->ddy = 0.0;
        break;
    case REF_ARC:
    case REF_ELLIPSE: {
        double a = rc->dir * t;
        double ax = c[2]; /* ARC: r; ELLIPSE: A */
        double by = rc->curve == REF_ARC ? c[2] : c[3];
        double ca = cos(a), sa = sin(a);
        j->x = c[0] + ax * ca;
        j->y = c[1] + by * sa;
        j->dx = -rc->dir * ax * sa;
        j->dy = rc->dir * by * ca;
        j->ddx = -ax * ca;
        j->ddy = -by * sa;
        break;
    }
    default: { /* cubic Bezier, s = t */
        double s = t, v = 1.0 - t;
        double b0 = v * v * v, b1 = 3.0 * v * v * s, b2 = 3.0 * v * s * s, b3 = s * s * s;
        double d0 = 3.0 * v * v, d1 = 6.0 * v * s, d2 = 3.0 * s * s;
        j->x = b0 * c[0] + b1 * c[2] + b2 * c[4] + b3 * c[6];
        j->y = b0 * c[1] + b1 * c[3] + b2 * c[5] + b3 * c[7];
        j->dx = d0 * (c[2] - c[0]) + d1 * (c[4] - c[2]) + d2 * (c[6] - c[4]);
        j->dy = d0 * (c[3] - c[1]) + d1 * (c[5] - c[3]) + d2 * (c[7] - c[5]);
        j->ddx = 6.0 * (v * (c[4] - 2.0 * c[2] + c[0]) + s * (c[6] - 2.0 * c[4] + c[2]));
        j->ddy = 6.0 * (v * (c[5] - 2.0 * c[3] + c[1]) + s * (c[7] - 2.0 * c[5] + c[3]));
        break;
    }
    }
    ref_radius(rc, t, &j->r, &j->dr, &j->ddr);
}

void ref_partials(const struct ref_canal *rc, double t, double u, double m[3], double mt[3],
                  double mu[3])
{
    struct ref_jet j;
    double c, tx, ty, nx, ny, kap, p, dp, q2, q, dq, F, dF, cu, su, omc, dd, bx, by, bz;
    double dbx, dby, dbz;
    ref_jet(rc, t, &j);
    c = sqrt(j.dx * j.dx + j.dy * j.dy);
    tx = j.dx / c;
    ty = j.dy / c;
    nx = -ty; /* left unit normal */
    ny = tx;
    kap = (j.dx * j.ddy - j.dy * j.ddx) / (c * c * c);
    dd = j.dx * j.ddx + j.dy * j.ddy; /* C'.C'' = c c' */
    p = j.dr / c;
    dp = (j.ddr * c * c - j.dr * dd) / (c * c * c); /* dp/dt */
    q2 = 1.0 + p * p;
    q = sqrt(q2);
    dq = p * dp / q;
    F = j.r / q2;
    dF = j.dr / q2 - 2.0 * j.r * p * dp / (q2 * q2);
    cu = cos(u);
    su = sin(u);
    omc = 1.0 - cu;
    /* bracket B = -p(1 - cos u) t_C + q sin u n_C + (1 - cos u) k */
    bx = -p * omc * tx + q * su * nx;
    by = -p * omc * ty + q * su * ny;
    bz = omc;
    m[0] = j.x + F * bx;
    m[1] = j.y + F * by;
    m[2] = F * bz;
    /* dB/dt with t_C' = kappa c n_C, n_C' = -kappa c t_C */
    dbx = -dp * omc * tx - p * omc * kap * c * nx + dq * su * nx - q * su * kap * c * tx;
    dby = -dp * omc * ty - p * omc * kap * c * ny + dq * su * ny - q * su * kap * c * ty;
    dbz = 0.0;
    mt[0] = j.dx + dF * bx + F * dbx;
    mt[1] = j.dy + dF * by + F * dby;
    mt[2] = dF * bz + F * dbz;
    mu[0] = F * (-p * su * tx + q * cu * nx);
    mu[1] = F * (-p * su * ty + q * cu * ny);
    mu[2] = F * su;
}

void ref_point(const struct ref_canal *rc, double t, double u, double m[3], double n[3])
{
    struct ref_jet j;
    double c, tx, ty, p, q2, q, F, cu, su, omc;
    ref_jet(rc, t, &j);
    c = sqrt(j.dx * j.dx + j.dy * j.dy);
    tx = j.dx / c;
    ty = j.dy / c;
    p = j.dr / c;
    q2 = 1.0 + p * p;
    q = sqrt(q2);
    F = j.r / q2;
    cu = cos(u);
    su = sin(u);
    omc = 1.0 - cu;
    m[0] = j.x + F * (-p * omc * tx - q * su * ty);
    m[1] = j.y + F * (-p * omc * ty + q * su * tx);
    m[2] = F * omc;
    n[0] = (m[0] - j.x) / j.r;
    n[1] = (m[1] - j.y) / j.r;
    n[2] = (m[2] - j.r) / j.r;
}

double ref_uprime(const struct ref_canal *rc, double t, double u)
{
    double m[3], mt[3], mu[3];
    ref_partials(rc, t, u, m, mt, mu);
    return -(mt[0] * mu[0] + mt[1] * mu[1] + mt[2] * mu[2]) /
           (mu[0] * mu[0] + mu[1] * mu[1] + mu[2] * mu[2]);
}

void ref_circle(const struct ref_canal *rc, double t, double centre[3], double *radius,
                double axis[3])
{
    struct ref_jet j;
    double c, sig, a;
    ref_jet(rc, t, &j);
    c = sqrt(j.dx * j.dx + j.dy * j.dy);
    sig = sqrt(c * c + j.dr * j.dr);
    axis[0] = j.dx / sig;
    axis[1] = j.dy / sig;
    axis[2] = j.dr / sig;
    a = -j.r * j.dr / sig;
    centre[0] = j.x + a * axis[0];
    centre[1] = j.y + a * axis[1];
    centre[2] = j.r + a * axis[2];
    *radius = j.r * c / sig;
}

void ref_line_start(struct ref_line *l, const struct ref_canal *rc, double t0, double u0)
{
    l->rc = rc;
    l->t = t0;
    l->u = u0;
    l->f = ref_uprime(rc, t0, u0);
    l->h = 0.05 * (rc->t1 - rc->t0);
    l->tol = 1e-12;
    l->steps = 0;
    l->rejects = 0;
    l->fail = 0;
}

/* Dormand-Prince 5(4), FSAL, propagate the 5th-order solution. */
int ref_line_advance(struct ref_line *l, double t)
{
    static const double c2 = 1.0 / 5, c3 = 3.0 / 10, c4 = 4.0 / 5, c5 = 8.0 / 9;
    static const double a21 = 1.0 / 5;
    static const double a31 = 3.0 / 40, a32 = 9.0 / 40;
    static const double a41 = 44.0 / 45, a42 = -56.0 / 15, a43 = 32.0 / 9;
    static const double a51 = 19372.0 / 6561, a52 = -25360.0 / 2187, a53 = 64448.0 / 6561,
                        a54 = -212.0 / 729;
    static const double a61 = 9017.0 / 3168, a62 = -355.0 / 33, a63 = 46732.0 / 5247,
                        a64 = 49.0 / 176, a65 = -5103.0 / 18656;
    static const double b1 = 35.0 / 384, b3 = 500.0 / 1113, b4 = 125.0 / 192,
                        b5 = -2187.0 / 6784, b6 = 11.0 / 84;
    static const double e1 = 71.0 / 57600, e3 = -71.0 / 16695, e4 = 71.0 / 1920,
                        e5 = -17253.0 / 339200, e6 = 22.0 / 525, e7 = -1.0 / 40;
    const struct ref_canal *rc = l->rc;
    int guard = 0;
    while (l->t != t) {
        double rem = t - l->t, sgn = rem > 0.0 ? 1.0 : -1.0;
        double h = l->h, hs, k1, k2, k3, k4, k5, k6, k7, un, err, sc, fac;
        int last = 0;
        if (h >= fabs(rem) * (1.0 - 1e-12)) {
            h = fabs(rem);
            last = 1;
        }
        hs = sgn * h;
        k1 = l->f;
        k2 = ref_uprime(rc, l->t + c2 * hs, l->u + hs * (a21 * k1));
        k3 = ref_uprime(rc, l->t + c3 * hs, l->u + hs * (a31 * k1 + a32 * k2));
        k4 = ref_uprime(rc, l->t + c4 * hs, l->u + hs * (a41 * k1 + a42 * k2 + a43 * k3));
        k5 = ref_uprime(rc, l->t + c5 * hs,
                        l->u + hs * (a51 * k1 + a52 * k2 + a53 * k3 + a54 * k4));
        k6 = ref_uprime(rc, l->t + hs,
                        l->u + hs * (a61 * k1 + a62 * k2 + a63 * k3 + a64 * k4 + a65 * k5));
        un = l->u + hs * (b1 * k1 + b3 * k3 + b4 * k4 + b5 * k5 + b6 * k6);
        k7 = ref_uprime(rc, last ? t : l->t + hs, un);
        err = fabs(hs * (e1 * k1 + e3 * k3 + e4 * k4 + e5 * k5 + e6 * k6 + e7 * k7));
        sc = l->tol * (1.0 + fabs(un));
        fac = err > 0.0 ? 0.9 * pow(sc / err, 0.2) : 5.0;
        fac = fac > 5.0 ? 5.0 : (fac < 0.2 ? 0.2 : fac);
        if (err <= sc) {
            l->t = last ? t : l->t + hs;
            l->u = un;
            l->f = k7;
            l->steps++;
            ref_steps_total++;
            /* do not let a short final step to a node shrink the step for the next call */
            if (!last || h * fac > l->h) {
                l->h = h * fac;
            }
        } else {
            l->rejects++;
            l->h = h * fac;
        }
        if (l->h < 1e-14 * (fabs(l->t) + 1.0) || ++guard > 1000000) {
            l->fail = 1;
            return -1;
        }
    }
    return 0;
}

double ref_hermite(double ta, double ua, double fa, double tb, double ub, double fb, double t)
{
    double h = tb - ta, s = (t - ta) / h, s2 = s * s, s3 = s2 * s;
    return (2.0 * s3 - 3.0 * s2 + 1.0) * ua + (s3 - 2.0 * s2 + s) * h * fa +
           (-2.0 * s3 + 3.0 * s2) * ub + (s3 - s2) * h * fb;
}
