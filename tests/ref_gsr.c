/* ref_gsr.c - independent double reference of the generalized surface of revolution.
 * SPDX-License-Identifier: MIT
 */
#include "ref_gsr.h"

#include <math.h>
#include <string.h>

#define RPI 3.14159265358979323846

void ref_gsr_fn(const double a[7], double x, double d[3])
{
    double wx = a[6] * x, s = sin(wx), c = cos(wx);
    d[0] = a[0] + a[1] * x + a[2] * x * x + a[3] * x * x * x + a[4] * s + a[5] * c;
    d[1] = a[1] + 2.0 * a[2] * x + 3.0 * a[3] * x * x + a[6] * (a[4] * c - a[5] * s);
    d[2] = 2.0 * a[2] + 6.0 * a[3] * x - a[6] * a[6] * (a[4] * s + a[5] * c);
}

void ref_gsr_centre(const struct ref_gsr *g, double t, double C[3], double D1[3], double D2[3])
{
    int ax;
    for (ax = 0; ax < 3; ax++) {
        if (g->centre == 1) {
            const double *p = g->c[ax];
            double q0 = p[0] + t * (p[1] - p[0]), q1 = p[1] + t * (p[2] - p[1]),
                   q2 = p[2] + t * (p[3] - p[2]);
            double s0 = q0 + t * (q1 - q0), s1 = q1 + t * (q2 - q1);
            double h0 = p[1] - p[0], h1 = p[2] - p[1], h2 = p[3] - p[2];
            C[ax] = s0 + t * (s1 - s0);
            D1[ax] = 3.0 * ((1.0 - t) * (1.0 - t) * h0 + 2.0 * t * (1.0 - t) * h1 + t * t * h2);
            D2[ax] = 6.0 * ((1.0 - t) * (h1 - h0) + t * (h2 - h1));
        } else {
            double d[3];
            ref_gsr_fn(g->c[ax], t, d);
            C[ax] = d[0];
            D1[ax] = d[1];
            D2[ax] = d[2];
        }
    }
}

static double dot3(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross3(const double *a, const double *b, double *o)
{
    double r[3];
    r[0] = a[1] * b[2] - a[2] * b[1];
    r[1] = a[2] * b[0] - a[0] * b[2];
    r[2] = a[0] * b[1] - a[1] * b[0];
    memcpy(o, r, sizeof r);
}

static void unit3(double *a)
{
    double l = sqrt(dot3(a, a));
    a[0] /= l;
    a[1] /= l;
    a[2] /= l;
}

static void tangent(const struct ref_gsr *g, double t, double x[3], double T[3])
{
    double D2[3];
    ref_gsr_centre(g, t, x, T, D2);
    unit3(T);
}

/* One double-reflection step of the RMF normal r from (x0, T0) to t1. */
static void dr_step(const struct ref_gsr *g, double x0[3], double T0[3], double r[3], double t1)
{
    double x1[3], T1[3], v1[3], v2[3], rl[3], tl[3], c1, c2, a, b;
    int i;
    tangent(g, t1, x1, T1);
    for (i = 0; i < 3; i++) {
        v1[i] = x1[i] - x0[i];
    }
    c1 = dot3(v1, v1);
    if (c1 == 0.0) {
        return; /* a step of length 0 (t1 = t0): nothing to transport */
    }
    a = 2.0 * dot3(v1, r) / c1;
    b = 2.0 * dot3(v1, T0) / c1;
    for (i = 0; i < 3; i++) {
        rl[i] = r[i] - a * v1[i];
        tl[i] = T0[i] - b * v1[i];
        v2[i] = T1[i] - tl[i];
    }
    c2 = dot3(v2, v2);
    a = c2 > 0.0 ? 2.0 * dot3(v2, rl) / c2 : 0.0;
    for (i = 0; i < 3; i++) {
        r[i] = rl[i] - a * v2[i];
        x0[i] = x1[i];
        T0[i] = T1[i];
    }
}

void ref_gsr_set(struct ref_gsr *g, int centre, const double c[3][7], const double r[3][7],
                 int frame, const double ref[3])
{
    double d[3], x[3], T[3], n[3], h;
    int k, s;
    memset(g, 0, sizeof *g);
    g->centre = centre;
    g->frame = frame;
    memcpy(g->c, c, sizeof g->c);
    memcpy(g->r, r, sizeof g->r);
    memcpy(g->ref, ref, sizeof g->ref);
    ref_gsr_fn(g->r[2], 0.0, d);
    g->t0 = d[0];
    ref_gsr_fn(g->r[2], 1.0, d);
    g->t1 = d[0];
    if (frame != 3) {
        return;
    }
    tangent(g, g->t0, x, T);
    h = dot3(ref, T);
    for (k = 0; k < 3; k++) {
        n[k] = ref[k] - h * T[k];
    }
    unit3(n);
    memcpy(g->rmf[0], n, sizeof n);
    h = (g->t1 - g->t0) / (double)(REF_GSR_RMF * REF_GSR_RMF_SUB);
    for (k = 0; k < REF_GSR_RMF; k++) {
        for (s = 1; s <= REF_GSR_RMF_SUB; s++) {
            dr_step(g, x, T, n, g->t0 + h * (double)(k * REF_GSR_RMF_SUB + s));
        }
        memcpy(g->rmf[k + 1], n, sizeof n);
    }
}

void ref_gsr_frame(const struct ref_gsr *g, double t, double T[3], double N[3], double B[3])
{
    double C[3], D1[3], D2[3];
    ref_gsr_centre(g, t, C, D1, D2);
    memcpy(T, D1, sizeof D1);
    unit3(T);
    if (g->frame == 0) {
        N[0] = T[2];
        N[1] = 0.0;
        N[2] = -T[0];
        B[0] = 0.0;
        B[1] = 1.0;
        B[2] = 0.0;
        return;
    }
    if (g->frame == 1) {
        cross3(D1, D2, B);
    } else if (g->frame == 2) {
        cross3(T, g->ref, B);
    } else {
        /* march from the node below */
        double span = g->t1 - g->t0, f = (t - g->t0) / span * REF_GSR_RMF, x[3], Tn[3], r[3];
        int k = (int)floor(f), s;
        k = k < 0 ? 0 : (k >= REF_GSR_RMF ? REF_GSR_RMF - 1 : k);
        f = g->t0 + span * (double)k / REF_GSR_RMF;
        tangent(g, f, x, Tn);
        memcpy(r, g->rmf[k], sizeof r);
        for (s = 1; s <= REF_GSR_RMF_SUB; s++) {
            dr_step(g, x, Tn, r, f + (t - f) * (double)s / REF_GSR_RMF_SUB);
        }
        f = dot3(r, T);
        for (s = 0; s < 3; s++) {
            N[s] = r[s] - f * T[s];
        }
        unit3(N);
        cross3(T, N, B);
        return;
    }
    unit3(B);
    cross3(B, T, N);
}

void ref_gsr_point(const struct ref_gsr *g, double u, double theta, double P[3])
{
    double ft[3], fn[3], fb[3], C[3], D1[3], D2[3], T[3], N[3], B[3];
    int i;
    ref_gsr_fn(g->r[0], u, fn);
    ref_gsr_fn(g->r[1], u, fb);
    ref_gsr_fn(g->r[2], u, ft);
    ref_gsr_centre(g, ft[0], C, D1, D2);
    ref_gsr_frame(g, ft[0], T, N, B);
    for (i = 0; i < 3; i++) {
        P[i] = C[i] + fn[0] * cos(theta) * N[i] + fb[0] * sin(theta) * B[i];
    }
}

void ref_gsr_normal(const struct ref_gsr *g, double u, double theta, double n[3])
{
    double fn[3], fb[3], ft[3], T[3], N[3], B[3], gt[3], gu[3], a[3], b[3], c[3], d[3];
    double h = 1e-3;
    int i;
    ref_gsr_fn(g->r[0], u, fn);
    ref_gsr_fn(g->r[1], u, fb);
    ref_gsr_fn(g->r[2], u, ft);
    ref_gsr_frame(g, ft[0], T, N, B);
    /* u +- h may leave [0, 1]: every function extends smoothly */
    ref_gsr_point(g, u + h, theta, a);
    ref_gsr_point(g, u - h, theta, b);
    ref_gsr_point(g, u + 0.5 * h, theta, c);
    ref_gsr_point(g, u - 0.5 * h, theta, d);
    for (i = 0; i < 3; i++) {
        double g1 = (a[i] - b[i]) / (2.0 * h), g2 = (c[i] - d[i]) / h;
        gu[i] = (4.0 * g2 - g1) / 3.0;
        gt[i] = -fn[0] * sin(theta) * N[i] + fb[0] * cos(theta) * B[i];
    }
    cross3(gt, gu, n); /* G_theta x G_u: away from C wherever the sweep is regular */
    unit3(n);
}

double ref_gsr_theta(double psi)
{
    double q = floor(psi), v;
    if (q > 1.0) {
        q = 1.0;
    }
    v = psi - q;
    return q * RPI / 2.0 + RPI / 4.0 + 2.0 * atan(tan(RPI / 8.0) * (2.0 * v - 1.0));
}

double ref_gsr_psi(double theta)
{
    double q = floor(theta / (RPI / 2.0));
    if (q > 1.0) {
        q = 1.0;
    }
    return q + 0.5 * (1.0 + tan((theta - q * RPI / 2.0 - RPI / 4.0) / 2.0) / tan(RPI / 8.0));
}

/* ---- ellipse arc length (checks gsr_arclen_*): adaptive Simpson and the AGM ---- */

static double arc_sp(double a, double b, double th)
{
    return hypot(a * sin(th), b * cos(th));
}

/* One adaptive Simpson level on [x0, x1] (fm the speed at the midpoint, whole the
 * Simpson value of the panel); Richardson-corrected on acceptance. */
static double arc_simpson(double a, double b, double x0, double x1, double f0, double fm,
                          double f1, double whole, double tol, int depth)
{
    double m = 0.5 * (x0 + x1), l = 0.5 * (x0 + m), r = 0.5 * (m + x1);
    double fl = arc_sp(a, b, l), fr = arc_sp(a, b, r);
    double sl = (m - x0) / 6.0 * (f0 + 4.0 * fl + fm), sr = (x1 - m) / 6.0 * (fm + 4.0 * fr + f1);
    double d = sl + sr - whole;
    if (depth <= 0 || fabs(d) <= 15.0 * tol) {
        return sl + sr + d / 15.0;
    }
    return arc_simpson(a, b, x0, m, f0, fl, fm, sl, 0.5 * tol, depth - 1) +
           arc_simpson(a, b, m, x1, fm, fr, f1, sr, 0.5 * tol, depth - 1);
}

double ref_gsr_arc(double a, double b, double th0, double th1, double tol)
{
    double f0 = arc_sp(a, b, th0), f1 = arc_sp(a, b, th1), fm = arc_sp(a, b, 0.5 * (th0 + th1));
    if (th1 == th0) {
        return 0.0;
    }
    return arc_simpson(a, b, th0, th1, f0, fm, f1, (th1 - th0) / 6.0 * (f0 + 4.0 * fm + f1), tol,
                       48);
}

double ref_gsr_perimeter(double a, double b)
{
    /* P = 4 A E(e), A = max, E(k) = K(k) (1 - sum_n 2^(n-1) c_n^2), K = pi / (2 AGM(1, k')),
     * a_0 = 1, b_0 = k' = B / A, c_0 = k, c_(n+1) = (a_n - b_n) / 2 */
    double A = a > b ? a : b, kp = (a > b ? b : a) / A;
    double an = 1.0, bn = kp, sum = 0.5 * (1.0 - kp * kp), w = 0.5;
    int n;
    for (n = 0; n < 12; n++) {
        double c = 0.5 * (an - bn), a1 = 0.5 * (an + bn);
        bn = sqrt(an * bn);
        an = a1;
        w *= 2.0;
        sum += w * c * c;
    }
    return 4.0 * A * (RPI / (2.0 * an)) * (1.0 - sum);
}

/* ---- the far parts of the sweep (ref_gsr.h) ---- */

/* the section at u: centre, frame, semi-axes */
static void far_section(const struct ref_gsr *g, double u, double C[3], double T[3], double N[3],
                        double B[3], double *fn, double *fb)
{
    double a[3], b[3], t[3], D1[3], D2[3];
    ref_gsr_fn(g->r[0], u, a);
    ref_gsr_fn(g->r[1], u, b);
    ref_gsr_fn(g->r[2], u, t);
    ref_gsr_centre(g, t[0], C, D1, D2);
    ref_gsr_frame(g, t[0], T, N, B);
    *fn = a[0];
    *fb = b[0];
}

/* distance from q to the filled ellipse {C + x N + y B : (x/fn)^2 + (y/fb)^2 <= 1} */
static double far_disk(const double q[3], const double C[3], const double T[3], const double N[3],
                       const double B[3], double fn, double fb)
{
    double d[3], h = 0.0, x = 0.0, y = 0.0, e = 0.0, lo = 0.0, hi = 1.5707963267948966;
    int i;
    for (i = 0; i < 3; i++) {
        d[i] = q[i] - C[i];
        h += T[i] * d[i];
        x += N[i] * d[i];
        y += B[i] * d[i];
    }
    x = fabs(x);
    y = fabs(y);
    if ((x / fn) * (x / fn) + (y / fb) * (y / fb) > 1.0) {
        /* closest point (fn cos p, fb sin p), p in [0, pi/2] (the quadrant of (x, y)):
         * the squared distance's derivative / 2 = x fn sin p - y fb cos p - (fn^2 - fb^2)
         * sin p cos p is <= 0 at 0 and >= 0 at pi/2, one sign change */
        for (i = 0; i < 60; i++) {
            double p = 0.5 * (lo + hi), sp = sin(p), cp = cos(p);
            if (x * fn * sp - y * fb * cp - (fn * fn - fb * fb) * sp * cp < 0.0) {
                lo = p;
            } else {
                hi = p;
            }
        }
        e = hypot(x - fn * cos(lo), y - fb * sin(lo));
    }
    return sqrt(h * h + e * e);
}

static double far_at(const struct ref_gsr *g, const double q[3], double u)
{
    double C[3], T[3], N[3], B[3], fn, fb;
    far_section(g, u, C, T, N, B, &fn, &fb);
    return far_disk(q, C, T, N, B, fn, fb);
}

static double far_norm(const double a[3], const double b[3])
{
    return hypot(hypot(a[0] - b[0], a[1] - b[1]), a[2] - b[2]);
}

void ref_gsr_far_init(struct ref_gsr_far *f, const struct ref_gsr *g)
{
    double prev[3] = {0.0, 0.0, 0.0};
    int k, m, i;
    f->len = 0.0;
    f->rmax = 0.0;
    f->lip = 0.0;
    for (k = 0; k <= REF_GSR_FAR; k++) {
        double *fr0 = f->fr[k][0], *fr1 = f->fr[k][1], *fr2 = f->fr[k][2], rad;
        far_section(g, (double)k / REF_GSR_FAR, f->c[k], fr0, fr1, fr2, &f->ab[k][0],
                    &f->ab[k][1]);
        rad = f->ab[k][0] > f->ab[k][1] ? f->ab[k][0] : f->ab[k][1];
        f->rmax = rad > f->rmax ? rad : f->rmax;
        if (k > 0) {
            double mv;
            for (m = 1; m <= 8; m++) { /* the interval's arc by 8 chords */
                double c[3], T[3], N[3], B[3], fn, fb;
                far_section(g, (k - 1 + m / 8.0) / REF_GSR_FAR, c, T, N, B, &fn, &fb);
                f->len += far_norm(c, prev);
                memcpy(prev, c, sizeof prev);
            }
            /* the largest move of a disk point from sample k - 1 to k */
            mv = far_norm(f->c[k], f->c[k - 1]) + rad * (far_norm(f->fr[k][1], f->fr[k - 1][1]) +
                                                        far_norm(f->fr[k][2], f->fr[k - 1][2])) +
                 fabs(f->ab[k][0] - f->ab[k - 1][0]) + fabs(f->ab[k][1] - f->ab[k - 1][1]);
            f->lip = mv > f->lip ? mv : f->lip;
        }
        f->s[k] = f->len;
        memcpy(prev, f->c[k], sizeof prev);
    }
    f->closed = far_norm(f->c[REF_GSR_FAR], f->c[0]) <= 1e-5 * f->len;
    (void)i;
}

double ref_gsr_far_dist(const struct ref_gsr *g, const struct ref_gsr_far *f, const double q[3],
                        double u, double near, double need, double *uat)
{
    double su, best = 1e30, dk[REF_GSR_FAR + 1], cut = need + f->lip;
    int k, k0 = (int)(u * REF_GSR_FAR), far[REF_GSR_FAR + 1];
    k0 = k0 < 0 ? 0 : k0 > REF_GSR_FAR ? REF_GSR_FAR : k0;
    su = f->s[k0] + (u * REF_GSR_FAR - k0) * (k0 < REF_GSR_FAR ? f->s[k0 + 1] - f->s[k0] : 0.0);
    *uat = -1.0;
    for (k = 0; k <= REF_GSR_FAR; k++) {
        double a = fabs(f->s[k] - su), lb;
        far[k] = a > near && (!f->closed || f->len - a > near);
        dk[k] = 1e30;
        if (!far[k]) {
            continue;
        }
        lb = far_norm(q, f->c[k]) - (f->ab[k][0] > f->ab[k][1] ? f->ab[k][0] : f->ab[k][1]);
        dk[k] = lb < cut ? far_disk(q, f->c[k], f->fr[k][0], f->fr[k][1], f->fr[k][2],
                                    f->ab[k][0], f->ab[k][1])
                         : lb;
        best = dk[k] < best ? dk[k] : best;
    }
    /* refine every far local minimum below the cut */
    for (k = 0; k <= REF_GSR_FAR; k++) {
        double a, b, x1, x2, f1, f2, gr = 0.6180339887498949;
        int it;
        if (!far[k] || dk[k] >= cut || (k > 0 && dk[k - 1] < dk[k]) ||
            (k < REF_GSR_FAR && dk[k + 1] < dk[k])) {
            continue;
        }
        a = (k > 0 && far[k - 1] ? k - 1 : k) / (double)REF_GSR_FAR;
        b = (k < REF_GSR_FAR && far[k + 1] ? k + 1 : k) / (double)REF_GSR_FAR;
        x1 = b - gr * (b - a);
        x2 = a + gr * (b - a);
        f1 = far_at(g, q, x1);
        f2 = far_at(g, q, x2);
        for (it = 0; it < 40; it++) {
            if (f1 < f2) {
                b = x2;
                x2 = x1;
                f2 = f1;
                x1 = b - gr * (b - a);
                f1 = far_at(g, q, x1);
            } else {
                a = x1;
                x1 = x2;
                f1 = f2;
                x2 = a + gr * (b - a);
                f2 = far_at(g, q, x2);
            }
        }
        if (dk[k] < best + 1e-15) {
            *uat = (double)k / REF_GSR_FAR;
        }
        if (f1 < best || f2 < best) {
            best = f1 < f2 ? f1 : f2;
            *uat = f1 < f2 ? x1 : x2;
        }
    }
    return best;
}
