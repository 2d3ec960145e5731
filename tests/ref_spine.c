/* ref_spine.c - independent double reference of the SPINE canal surface: jets, the RMF and
 * the family-2 curvature lines by adaptive Dormand-Prince 5(4). See ref_spine.h.
 * SPDX-License-Identifier: MIT
 */
#include <math.h>
#include <stddef.h>

#include "ref_spine.h"

#define RS_PI 3.14159265358979323846
#define RS_SAMPLES 256 /* init checks at u = k / RS_SAMPLES, k = 0..RS_SAMPLES */

/* ------------------------------------------------------------------ 3-vectors */

static double rs_dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void rs_cross(const double a[3], const double b[3], double o[3])
{
    double x = a[1] * b[2] - a[2] * b[1], y = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
    o[0] = x;
    o[1] = y;
}

static double rs_norm(const double a[3])
{
    return sqrt(rs_dot(a, a));
}

/* o = unit(v - (v . t) t) for a unit t; returns |v - (v . t) t| (o untouched if 0) */
static double rs_project(const double v[3], const double t[3], double o[3])
{
    double d = rs_dot(v, t), w[3], n;
    int i;
    for (i = 0; i < 3; i++) {
        w[i] = v[i] - d * t[i];
    }
    n = rs_norm(w);
    if (n > 0.0) {
        for (i = 0; i < 3; i++) {
            o[i] = w[i] / n;
        }
    }
    return n;
}

/* ------------------------------------------------------------------------ jets */

static void rs_law(const struct ref_spine *rs, double u, struct ref_spine_jet *j)
{
    const double *k = rs->rp;
    switch (rs->law) {
    case REF_SPINE_R_CONST:
        j->r = k[0];
        j->ru = 0.0;
        j->ruu = 0.0;
        break;
    case REF_SPINE_R_LINEAR:
        j->r = k[0] + (k[1] - k[0]) * u;
        j->ru = k[1] - k[0];
        j->ruu = 0.0;
        break;
    case REF_SPINE_R_COS: {
        double w = 2.0 * RS_PI * k[2];
        j->r = k[0] * cos(w * u) + k[1];
        j->ru = -k[0] * w * sin(w * u);
        j->ruu = -k[0] * w * w * cos(w * u);
        break;
    }
    default: { /* CUBIC, Bernstein */
        double v = 1.0 - u;
        j->r =
            k[0] * v * v * v + 3.0 * k[1] * v * v * u + 3.0 * k[2] * v * u * u + k[3] * u * u * u;
        j->ru = 3.0 * ((k[1] - k[0]) * v * v + 2.0 * (k[2] - k[1]) * v * u + (k[3] - k[2]) * u * u);
        j->ruu = 6.0 * ((k[2] - 2.0 * k[1] + k[0]) * v + (k[3] - 2.0 * k[2] + k[1]) * u);
        break;
    }
    }
}

/* ARC and HELIX: the circle part r (cos p e1 + sin p e2) with p = w u, and its derivatives */
static void rs_circle(const struct ref_spine *rs, double r, double w, double u,
                      struct ref_spine_jet *j)
{
    double cp = cos(w * u), sp = sin(w * u);
    int i;
    for (i = 0; i < 3; i++) {
        double rad = cp * rs->e1[i] + sp * rs->e2[i], tg = -sp * rs->e1[i] + cp * rs->e2[i];
        j->c[i] = r * rad;
        j->cu[i] = r * w * tg;
        j->cuu[i] = -r * w * w * rad;
    }
}

void ref_spine_jet(const struct ref_spine *rs, double u, struct ref_spine_jet *j)
{
    const double *p = rs->sp;
    int i;
    switch (rs->spine) {
    case REF_SPINE_LINE:
        for (i = 0; i < 3; i++) {
            j->c[i] = p[i] + u * (p[3 + i] - p[i]);
            j->cu[i] = p[3 + i] - p[i];
            j->cuu[i] = 0.0;
        }
        break;
    case REF_SPINE_ARC:
        rs_circle(rs, p[6], p[10], u, j);
        for (i = 0; i < 3; i++) {
            j->c[i] += p[i];
        }
        break;
    case REF_SPINE_HELIX: {
        double w = 2.0 * RS_PI * p[8], rise = p[7] / (2.0 * RS_PI); /* mm per radian */
        rs_circle(rs, p[6], w, u, j);
        for (i = 0; i < 3; i++) {
            j->c[i] += p[i] + rise * w * u * rs->ax[i];
            j->cu[i] += rise * w * rs->ax[i];
        }
        break;
    }
    case REF_SPINE_BEZIER: {
        double v = 1.0 - u;
        for (i = 0; i < 3; i++) {
            double q0 = p[i], q1 = p[3 + i], q2 = p[6 + i], q3 = p[9 + i];
            j->c[i] = v * v * v * q0 + 3.0 * v * v * u * q1 + 3.0 * v * u * u * q2 + u * u * u * q3;
            j->cu[i] = 3.0 * (v * v * (q1 - q0) + 2.0 * v * u * (q2 - q1) + u * u * (q3 - q2));
            j->cuu[i] = 6.0 * (v * (q2 - 2.0 * q1 + q0) + u * (q3 - 2.0 * q2 + q1));
        }
        break;
    }
    default:
        rs->fn(rs->ctx, u, j);
        return; /* the caller's jet includes R */
    }
    rs_law(rs, u, j);
}

/* --------------------------------------------------------------------- surface */

/* the frame at the jet: unit T, N1 = the unit projection of n1in, N2 = T x N1; |c_u| */
static double rs_frame(const struct ref_spine_jet *j, const double n1in[3], double t[3],
                       double n1[3], double n2[3])
{
    double v = rs_norm(j->cu);
    int i;
    for (i = 0; i < 3; i++) {
        t[i] = j->cu[i] / v;
    }
    (void)rs_project(n1in, t, n1);
    rs_cross(t, n1, n2);
    return v;
}

void ref_spine_surface(const struct ref_spine_jet *j, const double n1[3], double theta, double off,
                       double m[3], double n[3])
{
    double t[3], e1[3], e2[3], v = rs_frame(j, n1, t, e1, e2);
    double a = j->ru / v, b = sqrt(1.0 - a * a), ct = cos(theta), st = sin(theta);
    int i;
    for (i = 0; i < 3; i++) {
        n[i] = -a * t[i] + b * (ct * e1[i] + st * e2[i]);
        m[i] = j->c[i] + (j->r + off) * n[i];
    }
}

double ref_spine_dtheta(const struct ref_spine_jet *j, const double n1[3], double theta)
{
    double t[3], e1[3], e2[3], v = rs_frame(j, n1, t, e1, e2);
    double a = j->ru / v, b = sqrt(1.0 - a * a);
    /* T_u . N_i = (c_uu . N_i) / |c_u| (N_i normal to T): the per-u rates k_i |c_u| */
    double k1 = rs_dot(j->cuu, e1) / v, k2 = rs_dot(j->cuu, e2) / v;
    return a / b * (k2 * cos(theta) - k1 * sin(theta));
}

double ref_spine_regularity(const struct ref_spine_jet *j, const double n1[3], double theta,
                            double off)
{
    double t[3], e1[3], e2[3], v = rs_frame(j, n1, t, e1, e2);
    double a = j->ru / v, b = sqrt(1.0 - a * a);
    double as = (j->ruu - a * rs_dot(j->cu, j->cuu) / v) / (v * v); /* da/ds */
    double ke = (cos(theta) * rs_dot(j->cuu, e1) + sin(theta) * rs_dot(j->cuu, e2)) / (v * v);
    return b * b - (j->r + off) * (as + b * ke);
}

/* ------------------------------------------------------------------------ init */

static int rs_finite(const double *x, int n)
{
    int i;
    for (i = 0; i < n; i++) {
        if (!(x[i] - x[i] == 0.0)) {
            return 0;
        }
    }
    return 1;
}

/* ARC and HELIX: the unit axis from sp[3..5] and e1 from the start direction sp[dx..] */
static int rs_basis(struct ref_spine *rs, int dx)
{
    double n = rs_norm(rs->sp + 3);
    int i;
    if (!(n > 0.0) || !(rs->sp[6] > 0.0)) {
        return REF_SPINE_EDEGEN;
    }
    for (i = 0; i < 3; i++) {
        rs->ax[i] = rs->sp[3 + i] / n;
    }
    if (!(rs_project(rs->sp + dx, rs->ax, rs->e1) > 1e-9 * rs_norm(rs->sp + dx))) {
        return REF_SPINE_EDEGEN;
    }
    rs_cross(rs->ax, rs->e1, rs->e2);
    return REF_SPINE_OK;
}

/* the checks on RS_SAMPLES + 1 samples, then N1(0) */
static int rs_finish(struct ref_spine *rs, const double ref[3])
{
    struct ref_spine_jet j;
    double t[3];
    int k, i;
    for (k = 0; k <= RS_SAMPLES; k++) {
        double v;
        ref_spine_jet(rs, (double)k / RS_SAMPLES, &j);
        v = rs_norm(j.cu);
        if (!rs_finite(j.c, 3) || !rs_finite(j.cu, 3) || !(v > 1e-9 * (1.0 + rs_norm(j.c)))) {
            return REF_SPINE_EDEGEN;
        }
        if (!(j.r > 0.0) || !(fabs(j.ru) < v)) {
            return REF_SPINE_ESLOPE;
        }
    }
    ref_spine_jet(rs, 0.0, &j);
    for (i = 0; i < 3; i++) {
        t[i] = j.cu[i] / rs_norm(j.cu);
    }
    if (ref != NULL && rs_norm(ref) > 0.0) {
        if (!(rs_project(ref, t, rs->n10) > 1e-9 * rs_norm(ref))) {
            return REF_SPINE_EREF;
        }
    } else if (!(rs_project(j.cuu, t, rs->n10) > 1e-9 * rs_dot(j.cu, j.cu))) {
        return REF_SPINE_EREF;
    }
    return REF_SPINE_OK;
}

int ref_spine_init(struct ref_spine *rs, int spine, const double sp[12], int law,
                   const double rp[4], const double ref[3])
{
    int i, e = REF_SPINE_OK;
    if (rs == NULL || sp == NULL || rp == NULL || spine < REF_SPINE_LINE ||
        spine > REF_SPINE_BEZIER || law < REF_SPINE_R_CONST || law > REF_SPINE_R_CUBIC) {
        return REF_SPINE_EKIND;
    }
    rs->spine = spine;
    rs->law = law;
    rs->fn = NULL;
    rs->ctx = NULL;
    for (i = 0; i < 12; i++) {
        rs->sp[i] = sp[i];
    }
    for (i = 0; i < 4; i++) {
        rs->rp[i] = rp[i];
    }
    if (!rs_finite(rs->sp, 12) || !rs_finite(rs->rp, 4) || (ref != NULL && !rs_finite(ref, 3))) {
        return REF_SPINE_ENAN;
    }
    if (spine == REF_SPINE_ARC) {
        e = rs_basis(rs, 7);
        if (e == REF_SPINE_OK && !(sp[10] != 0.0 && fabs(sp[10]) <= 2.0 * RS_PI * (1.0 + 1e-15))) {
            e = REF_SPINE_EDEGEN;
        }
    } else if (spine == REF_SPINE_HELIX) {
        e = rs_basis(rs, 9);
        if (e == REF_SPINE_OK && !(sp[8] > 0.0)) {
            e = REF_SPINE_EDEGEN;
        }
    }
    return e != REF_SPINE_OK ? e : rs_finish(rs, ref);
}

int ref_spine_init_user(struct ref_spine *rs, ref_spine_user_fn fn, const void *ctx,
                        const double ref[3])
{
    int i;
    if (rs == NULL || fn == NULL) {
        return REF_SPINE_EKIND;
    }
    rs->spine = REF_SPINE_USER;
    rs->law = REF_SPINE_R_CONST;
    rs->fn = fn;
    rs->ctx = ctx;
    for (i = 0; i < 12; i++) {
        rs->sp[i] = 0.0;
    }
    for (i = 0; i < 4; i++) {
        rs->rp[i] = 0.0;
    }
    if (ref != NULL && !rs_finite(ref, 3)) {
        return REF_SPINE_ENAN;
    }
    return rs_finish(rs, ref);
}

/* ---------------------------------------------------------------------- lines */

/* d/du of the state (N1, theta): the RMF ODE dN1/du = -(N1 . T_u) T with
 * T_u = (c_uu - (c_uu . T) T) / |c_u|, and dtheta/du of MATH-spine 4.2. N1 is used as it is
 * in the RMF part (the flow keeps N1 . T = 0 and |N1| = 1: both drift only by the
 * integration error) and projected for theta'. */
static void rs_rhs(const struct ref_spine *rs, double u, const double y[4], double f[4])
{
    struct ref_spine_jet j;
    double v, t[3], tu[3], d;
    int i;
    ref_spine_jet(rs, u, &j);
    v = rs_norm(j.cu);
    for (i = 0; i < 3; i++) {
        t[i] = j.cu[i] / v;
    }
    d = rs_dot(j.cuu, t);
    for (i = 0; i < 3; i++) {
        tu[i] = (j.cuu[i] - d * t[i]) / v;
    }
    d = rs_dot(y, tu);
    for (i = 0; i < 3; i++) {
        f[i] = -d * t[i];
    }
    f[3] = ref_spine_dtheta(&j, y, y[3]);
}

void ref_spine_line_start(struct ref_spine_line *l, const struct ref_spine *rs, double theta0)
{
    int i;
    l->rs = rs;
    l->u = 0.0;
    for (i = 0; i < 3; i++) {
        l->y[i] = rs->n10[i];
    }
    l->y[3] = theta0;
    rs_rhs(rs, 0.0, l->y, l->f);
    l->h = 1.0 / 64.0;
    l->tol = 1e-12;
    l->steps = 0;
    l->rejects = 0;
    l->fail = 0;
}

/* One Dormand-Prince 5(4) trial step of size h from (l->u, l->y) with k1 = l->f: the 5th-order
 * solution yn, its derivative fn at u + h (FSAL) and the max-norm error estimate. */
static double rs_dp_step(const struct ref_spine_line *l, double h, double un, double yn[4],
                         double fn[4])
{
    static const double c[6] = {1.0 / 5, 3.0 / 10, 4.0 / 5, 8.0 / 9, 1.0, 1.0};
    static const double a[6][6] = {
        {1.0 / 5},
        {3.0 / 40, 9.0 / 40},
        {44.0 / 45, -56.0 / 15, 32.0 / 9},
        {19372.0 / 6561, -25360.0 / 2187, 64448.0 / 6561, -212.0 / 729},
        {9017.0 / 3168, -355.0 / 33, 46732.0 / 5247, 49.0 / 176, -5103.0 / 18656},
        {35.0 / 384, 0.0, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784, 11.0 / 84}};
    static const double e[7] = {71.0 / 57600,      0.0,        -71.0 / 16695, 71.0 / 1920,
                                -17253.0 / 339200, 22.0 / 525, -1.0 / 40};
    double k[7][4], ys[4], err = 0.0;
    int s, q, i;
    for (i = 0; i < 4; i++) {
        k[0][i] = l->f[i];
    }
    /* stages 2..7; stage 7 is the derivative at the 5th-order solution (row 6 of a) */
    for (s = 1; s <= 6; s++) {
        for (i = 0; i < 4; i++) {
            double acc = 0.0;
            for (q = 0; q < s; q++) {
                acc += a[s - 1][q] * k[q][i];
            }
            ys[i] = l->y[i] + h * acc;
        }
        rs_rhs(l->rs, s == 6 ? un : l->u + c[s - 1] * h, ys, k[s]);
    }
    for (i = 0; i < 4; i++) {
        double d = 0.0;
        for (q = 0; q < 7; q++) {
            d += e[q] * k[q][i];
        }
        d = fabs(h * d);
        err = d > err ? d : err;
        yn[i] = ys[i];
        fn[i] = k[6][i];
    }
    return err;
}

/* Step-size control: accept when err <= tol (1 + max|y|); the next step is h times
 * 0.9 (sc/err)^(1/5), clamped to [0.2, 5]. A final step cut short to land on u does not
 * shrink the step carried to the next call. Error: err estimates the local error of the
 * embedded 4th-order solution; the propagated 5th-order one is smaller still, so the global
 * error of the state is below (accepted steps) x tol (1 + |y|) -- a few hundred steps per
 * spine at tol = 1e-12 give <= ~1e-10 in N1 and theta, i.e. <= ~1e-10 R in a point (the
 * tests measure 1e-11 .. 4e-9 mm against closed forms and ref_canal.c). */
int ref_spine_line_advance(struct ref_spine_line *l, double u)
{
    long guard = 0;
    if (u < l->u) {
        l->fail = 1;
        return -1;
    }
    while (l->u < u) {
        double h = l->h, yn[4], fn[4], err, sc, fac, ymax = 0.0;
        int last = 0, i;
        if (h >= (u - l->u) * (1.0 - 1e-12)) {
            h = u - l->u;
            last = 1;
        }
        err = rs_dp_step(l, h, last ? u : l->u + h, yn, fn);
        for (i = 0; i < 4; i++) {
            ymax = fabs(yn[i]) > ymax ? fabs(yn[i]) : ymax;
        }
        sc = l->tol * (1.0 + ymax);
        fac = err > 0.0 ? 0.9 * pow(sc / err, 0.2) : 5.0;
        fac = fac > 5.0 ? 5.0 : (fac < 0.2 ? 0.2 : fac);
        if (err <= sc) {
            l->u = last ? u : l->u + h;
            for (i = 0; i < 4; i++) {
                l->y[i] = yn[i];
                l->f[i] = fn[i];
            }
            l->steps++;
            if (!last || h * fac > l->h) {
                l->h = h * fac;
            }
        } else {
            l->rejects++;
            l->h = h * fac;
        }
        if (l->h < 1e-14 || ++guard > 1000000) {
            l->fail = 1;
            return -1;
        }
    }
    return 0;
}

void ref_spine_line_frame(const struct ref_spine_line *l, double t[3], double n1[3], double n2[3])
{
    struct ref_spine_jet j;
    ref_spine_jet(l->rs, l->u, &j);
    (void)rs_frame(&j, l->y, t, n1, n2);
}

void ref_spine_line_here(const struct ref_spine_line *l, double off, double m[3], double n[3])
{
    struct ref_spine_jet j;
    ref_spine_jet(l->rs, l->u, &j);
    ref_spine_surface(&j, l->y, l->y[3], off, m, n);
}

int ref_spine_line_point(const struct ref_spine *rs, double theta0, double u, double m[3],
                         double n[3])
{
    struct ref_spine_line l;
    ref_spine_line_start(&l, rs, theta0);
    if (ref_spine_line_advance(&l, u) != 0) {
        return -1;
    }
    ref_spine_line_here(&l, 0.0, m, n);
    return 0;
}

int ref_spine_circle_point(const struct ref_spine *rs, double u, double theta, double m[3],
                           double n[3])
{
    struct ref_spine_line l;
    struct ref_spine_jet j;
    ref_spine_line_start(&l, rs, 0.0);
    if (ref_spine_line_advance(&l, u) != 0) {
        return -1;
    }
    ref_spine_jet(rs, u, &j);
    ref_spine_surface(&j, l.y, theta, 0.0, m, n);
    return 0;
}

/* ---- the far spheres (ref_spine.h) ---- */

static double far_norm(const double a[3], const double b[3])
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                (a[2] - b[2]) * (a[2] - b[2]));
}

void ref_spine_far_init(struct ref_spine_far *f, const struct ref_spine *rs)
{
    struct ref_spine_jet j;
    double prev[3], ext = 0.0;
    int k, m, q;
    f->len = f->rmax = f->lip = f->piece = 0.0;
    for (k = 0; k <= REF_SPINE_FAR; k++) {
        ref_spine_jet(rs, (double)k / REF_SPINE_FAR, &j);
        for (q = 0; q < 3; q++) {
            f->c[k][q] = j.c[q];
        }
        f->r[k] = j.r;
        f->rmax = j.r > f->rmax ? j.r : f->rmax;
        f->s[k] = 0.0;
        if (k > 0) { /* the arc of the interval by 8 chords */
            double a = 0.0;
            for (q = 0; q < 3; q++) {
                prev[q] = f->c[k - 1][q];
            }
            for (m = 1; m <= 8; m++) {
                ref_spine_jet(rs, (k - 1 + m / 8.0) / REF_SPINE_FAR, &j);
                a += far_norm(prev, j.c);
                for (q = 0; q < 3; q++) {
                    prev[q] = j.c[q];
                }
            }
            f->s[k] = f->s[k - 1] + a;
            a += fabs(f->r[k] - f->r[k - 1]);
            f->lip = a > f->lip ? a : f->lip;
        }
        ext = far_norm(f->c[k], f->c[0]) > ext ? far_norm(f->c[k], f->c[0]) : ext;
    }
    f->len = f->s[REF_SPINE_FAR];
    for (k = 0; k < 64; k++) {
        int a = k * REF_SPINE_FAR / 64, b = (k + 1) * REF_SPINE_FAR / 64;
        f->piece = f->s[b] - f->s[a] > f->piece ? f->s[b] - f->s[a] : f->piece;
    }
    f->closed = far_norm(f->c[REF_SPINE_FAR], f->c[0]) <= 1e-5 * ext;
}

static double far_pair(const struct ref_spine *rs, double u, double v)
{
    struct ref_spine_jet a, b;
    ref_spine_jet(rs, u, &a);
    ref_spine_jet(rs, v, &b);
    return far_norm(a.c, b.c) - a.r - b.r;
}

/* golden section of the pair's gap in one coordinate (which = 0: u, 1: v) over [lo, hi] */
static void far_golden(const struct ref_spine *rs, double *u, double *v, int which, double lo,
                       double hi)
{
    const double g = 0.6180339887498949;
    double a = lo, b = hi, x1 = b - g * (b - a), x2 = a + g * (b - a), f1, f2;
    int it;
    f1 = which ? far_pair(rs, *u, x1) : far_pair(rs, x1, *v);
    f2 = which ? far_pair(rs, *u, x2) : far_pair(rs, x2, *v);
    for (it = 0; it < 40; it++) {
        if (f1 < f2) {
            b = x2;
            x2 = x1;
            f2 = f1;
            x1 = b - g * (b - a);
            f1 = which ? far_pair(rs, *u, x1) : far_pair(rs, x1, *v);
        } else {
            a = x1;
            x1 = x2;
            f1 = f2;
            x2 = a + g * (b - a);
            f2 = which ? far_pair(rs, *u, x2) : far_pair(rs, x2, *v);
        }
    }
    {
        double x = 0.5 * (a + b), cur = far_pair(rs, *u, *v);
        double t = which ? far_pair(rs, *u, x) : far_pair(rs, x, *v);
        if (t < cur) { /* keep the better point: the result stays a real pair's gap */
            if (which) {
                *v = x;
            } else {
                *u = x;
            }
        }
    }
}

double ref_spine_far_gap(const struct ref_spine *rs, const struct ref_spine_far *f, double near,
                         double *ua, double *ub)
{
    double best = 1e30, u, v;
    int i, j, bi = -1, bj = -1, round;
    for (i = 0; i <= REF_SPINE_FAR; i++) {
        for (j = i + 1; j <= REF_SPINE_FAR; j++) {
            double sep = f->s[j] - f->s[i], g;
            if (sep < near || (f->closed && f->len - sep < near)) {
                continue;
            }
            g = far_norm(f->c[i], f->c[j]) - f->r[i] - f->r[j];
            if (g < best) {
                best = g;
                bi = i;
                bj = j;
            }
        }
    }
    *ua = *ub = -1.0;
    if (bi < 0) {
        return best;
    }
    u = (double)bi / REF_SPINE_FAR;
    v = (double)bj / REF_SPINE_FAR;
    for (round = 0; round < 4; round++) {
        double lo = (bi > 0 ? bi - 1 : 0) / (double)REF_SPINE_FAR;
        double hi = (bi < REF_SPINE_FAR ? bi + 1 : bi) / (double)REF_SPINE_FAR;
        far_golden(rs, &u, &v, 0, lo, hi);
        lo = (bj > 0 ? bj - 1 : 0) / (double)REF_SPINE_FAR;
        hi = (bj < REF_SPINE_FAR ? bj + 1 : bj) / (double)REF_SPINE_FAR;
        far_golden(rs, &u, &v, 1, lo, hi);
    }
    *ua = u;
    *ub = v;
    return far_pair(rs, u, v);
}
