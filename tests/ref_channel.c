/* ref_channel.c - independent double reference of the channel surface (ref_channel.h).
 * SPDX-License-Identifier: MIT
 */
#include <math.h>

#include "ref_channel.h"

#define SNAP 1e-5
#define REF_PI 3.14159265358979323846

static void mat_mul(double a[3][3], double b[3][3], double o[3][3])
{
    double t[3][3];
    int i, j, k;
    for (i = 0; i < 3; i++) {
        for (j = 0; j < 3; j++) {
            t[i][j] = 0.0;
            for (k = 0; k < 3; k++) {
                t[i][j] += a[i][k] * b[k][j];
            }
        }
    }
    for (i = 0; i < 3; i++) {
        for (j = 0; j < 3; j++) {
            o[i][j] = t[i][j];
        }
    }
}

void ref_channel_euler(double psi, double theta, double phi, int printed, double x[3], double z[3])
{
    double tt[3][3] = {{1, 0, 0}, {0, cos(theta), sin(theta)}, {0, -sin(theta), cos(theta)}};
    double tf[3][3] = {{cos(phi), 0, -sin(phi)}, {0, 1, 0}, {sin(phi), 0, cos(phi)}};
    double tp[3][3] = {{cos(psi), sin(psi), 0}, {-sin(psi), cos(psi), 0}, {0, 0, 1}};
    double r[3][3];
    int i;
    if (printed) {
        mat_mul(tt, tf, r);
        mat_mul(r, tp, r);
    } else {
        mat_mul(tp, tt, r);
        mat_mul(r, tf, r);
    }
    for (i = 0; i < 3; i++) {
        x[i] = r[0][i];
        z[i] = r[2][i];
    }
}

double ref_channel_ks(double n)
{
    double e = 2.0 / n; /* S = 2 a b e B(e/2, e/2 + 1) */
    return 2.0 * e * tgamma(e / 2.0) * tgamma(e / 2.0 + 1.0) / tgamma(e + 1.0);
}

double ref_channel_kj(double n)
{
    double e = 2.0 / n; /* J_x = 1/2 a b^3 e B(3e/2, e/2) */
    return 0.5 * e * tgamma(1.5 * e) * tgamma(0.5 * e) / tgamma(2.0 * e);
}

static double dot3(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross3(const double *a, const double *b, double *o)
{
    double t[3];
    t[0] = a[1] * b[2] - a[2] * b[1];
    t[1] = a[2] * b[0] - a[0] * b[2];
    t[2] = a[0] * b[1] - a[1] * b[0];
    o[0] = t[0];
    o[1] = t[1];
    o[2] = t[2];
}

static void unit3(double *a)
{
    double l = sqrt(dot3(a, a));
    a[0] /= l;
    a[1] /= l;
    a[2] /= l;
}

/* natural spline second derivatives: full system, Gaussian elimination with pivoting */
static void spline(int ns, const double *y, double *y2)
{
    double m[REF_CH_MAX][REF_CH_MAX + 1];
    int i, j, k;
    for (i = 0; i < ns; i++) {
        for (j = 0; j <= ns; j++) {
            m[i][j] = 0.0;
        }
        if (i == 0 || i == ns - 1) {
            m[i][i] = 1.0;
        } else {
            m[i][i - 1] = 1.0;
            m[i][i] = 4.0;
            m[i][i + 1] = 1.0;
            m[i][ns] = 6.0 * (y[i + 1] - 2.0 * y[i] + y[i - 1]);
        }
    }
    for (k = 0; k < ns; k++) {
        int p = k;
        for (i = k + 1; i < ns; i++) {
            if (fabs(m[i][k]) > fabs(m[p][k])) {
                p = i;
            }
        }
        for (j = 0; j <= ns; j++) {
            double t = m[k][j];
            m[k][j] = m[p][j];
            m[p][j] = t;
        }
        for (i = k + 1; i < ns; i++) {
            double f = m[i][k] / m[k][k];
            for (j = k; j <= ns; j++) {
                m[i][j] -= f * m[k][j];
            }
        }
    }
    for (i = ns - 1; i >= 0; i--) {
        double s = m[i][ns];
        for (j = i + 1; j < ns; j++) {
            s -= m[i][j] * y2[j];
        }
        y2[i] = s / m[i][i];
    }
}

static void frame(const double *d1, double *tau, double *e1, double *e2)
{
    static const double ey[3] = {0.0, 1.0, 0.0};
    int i;
    for (i = 0; i < 3; i++) {
        tau[i] = d1[i];
    }
    unit3(tau);
    cross3(ey, tau, e1);
    unit3(e1);
    cross3(tau, e1, e2);
}

int ref_channel_build(struct ref_channel *r, int ns, const struct ref_ch_sec *s)
{
    int i, k, q;
    r->ns = ns;
    for (i = 0; i < ns; i++) {
        r->s[i] = s[i];
    }
    for (i = 0; i < ns; i++) {
        double ch[3], len, kk, sg;
        int j = i < ns - 1 ? i + 1 : i - 1; /* neighbour that orients the tangent */
        for (k = 0; k < 3; k++) {
            ch[k] = i < ns - 1 ? s[j].c[k] - s[i].c[k] : s[i].c[k] - s[j].c[k];
        }
        sg = dot3(s[i].z, ch) > 0.0 ? 1.0 : -1.0;
        if (i == 0 || i == ns - 1) {
            kk = sqrt(dot3(ch, ch));
        } else {
            double cp[3];
            for (k = 0; k < 3; k++) {
                cp[k] = s[i].c[k] - s[i - 1].c[k];
            }
            len = sqrt(dot3(ch, ch));
            kk = 0.5 * (len + sqrt(dot3(cp, cp)));
        }
        for (k = 0; k < 3; k++) {
            r->m[i][k] = sg * kk * s[i].z[k];
        }
    }
    for (i = 0; i < ns; i++) {
        for (k = 0; k < 3; k++) {
            double left = 0.0, right = 0.0;
            int nl = 0;
            if (i > 0) { /* H''(1) of segment i-1 */
                left = -6.0 * (s[i].c[k] - s[i - 1].c[k]) + 2.0 * r->m[i - 1][k] + 4.0 * r->m[i][k];
                nl++;
            }
            if (i < ns - 1) { /* H''(0) of segment i */
                right = 6.0 * (s[i + 1].c[k] - s[i].c[k]) - 4.0 * r->m[i][k] - 2.0 * r->m[i + 1][k];
                nl++;
            }
            r->acc[i][k] = (left + right) / (double)nl;
        }
    }
    for (i = 0; i < ns; i++) {
        double tau[3], e1[3], e2[3], xa[3], a = s[i].a, b = s[i].b, jx, jy, al;
        frame(r->m[i], tau, e1, e2);
        for (k = 0; k < 3; k++) {
            xa[k] = s[i].x[k];
        }
        if (a < b) {
            cross3(s[i].z, s[i].x, xa);
            a = s[i].b;
            b = s[i].a;
        }
        al = atan2(dot3(xa, e2), dot3(xa, e1));
        if (i > 0) {
            while (al - r->al[i - 1] > 0.5 * REF_PI) {
                al -= REF_PI;
            }
            while (al - r->al[i - 1] < -0.5 * REF_PI) {
                al += REF_PI;
            }
        }
        r->al[i] = al;
        jx = ref_channel_kj(s[i].n) * a * pow(b, 3.0);
        jy = ref_channel_kj(s[i].n) * pow(a, 3.0) * b;
        r->y[0][i] = ref_channel_ks(s[i].n) * a * b;
        r->y[1][i] = s[i].n;
        r->y[2][i] = jx * cos(al) * cos(al) + jy * sin(al) * sin(al);
        r->y[3][i] = jx * sin(al) * sin(al) + jy * cos(al) * cos(al);
        r->y[4][i] = 0.5 * (jy - jx) * sin(2.0 * al);
    }
    for (q = 0; q < 5; q++) {
        spline(ns, r->y[q], r->y2[q]);
    }
    return 0;
}

void ref_channel_row(const struct ref_channel *r, double u, struct ref_ch_row *o)
{
    int m = (int)floor(u), k;
    double t, h[6], h1[6], h2[6], v[5], ks, kj, pp, qq, ref, lo;
    if (m > r->ns - 2) {
        m = r->ns - 2;
    }
    if (m < 0) {
        m = 0;
    }
    t = u - m;
    /* basis for P0, M0, A0, A1, M1, P1 (B.2 step 2) */
    h[0] = 1 - 10 * pow(t, 3) + 15 * pow(t, 4) - 6 * pow(t, 5);
    h[1] = t - 6 * pow(t, 3) + 8 * pow(t, 4) - 3 * pow(t, 5);
    h[2] = 0.5 * t * t - 1.5 * pow(t, 3) + 1.5 * pow(t, 4) - 0.5 * pow(t, 5);
    h[3] = 0.5 * pow(t, 3) - pow(t, 4) + 0.5 * pow(t, 5);
    h[4] = -4 * pow(t, 3) + 7 * pow(t, 4) - 3 * pow(t, 5);
    h[5] = 10 * pow(t, 3) - 15 * pow(t, 4) + 6 * pow(t, 5);
    h1[0] = -30 * t * t + 60 * pow(t, 3) - 30 * pow(t, 4);
    h1[1] = 1 - 18 * t * t + 32 * pow(t, 3) - 15 * pow(t, 4);
    h1[2] = t - 4.5 * t * t + 6 * pow(t, 3) - 2.5 * pow(t, 4);
    h1[3] = 1.5 * t * t - 4 * pow(t, 3) + 2.5 * pow(t, 4);
    h1[4] = -12 * t * t + 28 * pow(t, 3) - 15 * pow(t, 4);
    h1[5] = -h1[0];
    h2[0] = -60 * t + 180 * t * t - 120 * pow(t, 3);
    h2[1] = -36 * t + 96 * t * t - 60 * pow(t, 3);
    h2[2] = 1 - 9 * t + 18 * t * t - 10 * pow(t, 3);
    h2[3] = 3 * t - 12 * t * t + 10 * pow(t, 3);
    h2[4] = -24 * t + 84 * t * t - 60 * pow(t, 3);
    h2[5] = -h2[0];
    for (k = 0; k < 3; k++) {
        double c[6];
        int i;
        c[0] = r->s[m].c[k];
        c[1] = r->m[m][k];
        c[2] = r->acc[m][k];
        c[3] = r->acc[m + 1][k];
        c[4] = r->m[m + 1][k];
        c[5] = r->s[m + 1].c[k];
        o->l[k] = o->d1[k] = o->d2[k] = 0.0;
        for (i = 0; i < 6; i++) {
            o->l[k] += h[i] * c[i];
            o->d1[k] += h1[i] * c[i];
            o->d2[k] += h2[i] * c[i];
        }
    }
    frame(o->d1, o->tau, o->e1, o->e2);
    for (k = 0; k < 5; k++) {
        const double *y = r->y[k], *y2 = r->y2[k];
        v[k] = y2[m] * pow(1 - t, 3) / 6 + y2[m + 1] * pow(t, 3) / 6 + (y[m] - y2[m] / 6) * (1 - t) +
               (y[m + 1] - y2[m + 1] / 6) * t;
    }
    o->s = v[0];
    o->n = v[1];
    o->ji = v[2];
    o->jii = v[3];
    o->j12 = v[4];
    ks = ref_channel_ks(v[1]);
    kj = ref_channel_kj(v[1]);
    pp = v[0] / ks;
    qq = (v[2] + v[3]) / (kj * pp);
    if (qq < 2 * pp) {
        qq = 2 * pp;
    }
    o->a = 0.5 * (sqrt(qq + 2 * pp) + sqrt(qq - 2 * pp));
    o->b = 0.5 * (sqrt(qq + 2 * pp) - sqrt(qq - 2 * pp));
    o->alpha = 0.5 * atan2(2 * v[4], v[3] - v[2]);
    ref = r->al[m] * (1 - t) + r->al[m + 1] * t;
    lo = o->alpha;
    while (lo - ref > 0.5 * REF_PI) {
        lo -= REF_PI;
    }
    while (lo - ref < -0.5 * REF_PI) {
        lo += REF_PI;
    }
    o->alpha = lo;
}


static void point_at(const struct ref_ch_row *o, double w, double p[3])
{
    double c = cos(w), s = sin(w), x, y, ex = 2.0 / o->n;
    int k;
    if (fabs(c) < SNAP) {
        c = 0.0;
        s = s < 0 ? -1.0 : 1.0;
    }
    if (fabs(s) < SNAP) {
        s = 0.0;
        c = c < 0 ? -1.0 : 1.0;
    }
    x = o->a * (c > 0 ? 1.0 : (c < 0 ? -1.0 : 0.0)) * pow(fabs(c), ex);
    y = o->b * (s > 0 ? 1.0 : (s < 0 ? -1.0 : 0.0)) * pow(fabs(s), ex);
    for (k = 0; k < 3; k++) {
        p[k] = o->l[k] + (x * cos(o->alpha) - y * sin(o->alpha)) * o->e1[k] +
               (x * sin(o->alpha) + y * cos(o->alpha)) * o->e2[k];
    }
}

void ref_channel_point(const struct ref_channel *r, double u, double w, double p[3])
{
    struct ref_ch_row o;
    ref_channel_row(r, u, &o);
    point_at(&o, w, p);
}

void ref_channel_normal(const struct ref_channel *r, double u, double w, double nrm[3], double *g)
{
    double hu = 1e-6, hw, pa[3], pb[3], pc[3], pd[3], pu[3], pw[3], p[3];
    double c = cos(w), s = sin(w), top = r->ns - 1.0, ua, ub;
    struct ref_ch_row o;
    int k;
    /* on (or near) a section axis |c|^(2/n) is not differentiable: the symmetric chord
     * over +-1e-3 is parallel to the tangent there (the section is symmetric) */
    hw = (fabs(c) < 1e-3 || fabs(s) < 1e-3) ? 1e-3 : 1e-6;
    ua = u - hu < 0.0 ? u : u - hu;
    ub = u + hu > top ? u : u + hu;
    ref_channel_point(r, ua, w, pa);
    ref_channel_point(r, ub, w, pb);
    ref_channel_point(r, u, w - hw, pc);
    ref_channel_point(r, u, w + hw, pd);
    ref_channel_row(r, u, &o);
    point_at(&o, w, p);
    for (k = 0; k < 3; k++) {
        pu[k] = (pb[k] - pa[k]) / (ub - ua);
        pw[k] = pd[k] - pc[k];
    }
    cross3(pu, pw, nrm);
    unit3(nrm);
    for (k = 0; k < 3; k++) {
        p[k] -= o.l[k];
    }
    if (dot3(nrm, p) < 0.0) {
        nrm[0] = -nrm[0];
        nrm[1] = -nrm[1];
        nrm[2] = -nrm[2];
    }
    *g = dot3(pu, o.tau) / sqrt(dot3(o.d1, o.d1));
}

double ref_channel_area(const struct ref_channel *r, double u, int m)
{
    struct ref_ch_row o;
    double area = 0.0, x0 = 0.0, y0 = 0.0, xf = 0.0, yf = 0.0;
    int i, k;
    ref_channel_row(r, u, &o);
    for (i = 0; i <= m; i++) {
        double p[3], x, y;
        point_at(&o, 2.0 * REF_PI * (i % m) / m, p);
        for (k = 0; k < 3; k++) {
            p[k] -= o.l[k];
        }
        x = dot3(p, o.e1);
        y = dot3(p, o.e2);
        if (i == 0) {
            xf = x;
            yf = y;
        } else {
            area += x0 * y - x * y0;
        }
        x0 = x;
        y0 = y;
    }
    (void)xf;
    (void)yf;
    return 0.5 * fabs(area);
}

double ref_channel_off_section(const struct ref_channel *r, double u, const double p[3])
{
    struct ref_ch_row o;
    double d[3], x, y, z, ax[3], ay[3], rho;
    int k;
    ref_channel_row(r, u, &o);
    for (k = 0; k < 3; k++) {
        d[k] = p[k] - o.l[k];
        ax[k] = cos(o.alpha) * o.e1[k] + sin(o.alpha) * o.e2[k];
        ay[k] = -sin(o.alpha) * o.e1[k] + cos(o.alpha) * o.e2[k];
    }
    x = dot3(d, ax);
    y = dot3(d, ay);
    z = dot3(d, o.tau);
    rho = pow(pow(fabs(x / o.a), o.n) + pow(fabs(y / o.b), o.n), 1.0 / o.n);
    return fabs(rho - 1.0) * (o.a > o.b ? o.a : o.b) + fabs(z);
}

void ref_channel_wire(const struct ref_ch_sec *s, int m, double *len, double lam[3], double ax[3])
{
    double y[3], f1[3] = {0, 0, 0}, f2[3][3] = {{0}}, tot = 0.0, jt[3][3], v[3][3], pp[3][3];
    int i, j, k, sw;
    cross3(s->z, s->x, y);
    for (i = 0; i < m; i++) {
        int e;
        for (e = 0; e < 3; e += 2) { /* ends A, B of edge i; Simpson with the chord midpoint */
            double w = 2.0 * REF_PI * ((e == 2 ? i + 1 : i) % m) / m, c = cos(w), sn = sin(w), xx, yy;
            xx = s->a * (c < 0 ? -1 : 1) * pow(fabs(c), 2.0 / s->n);
            yy = s->b * (sn < 0 ? -1 : 1) * pow(fabs(sn), 2.0 / s->n);
            for (k = 0; k < 3; k++) {
                pp[e][k] = xx * s->x[k] + yy * y[k];
            }
        }
        for (k = 0; k < 3; k++) {
            pp[1][k] = 0.5 * (pp[0][k] + pp[2][k]);
        }
        {
            double l = sqrt((pp[2][0] - pp[0][0]) * (pp[2][0] - pp[0][0]) +
                            (pp[2][1] - pp[0][1]) * (pp[2][1] - pp[0][1]) +
                            (pp[2][2] - pp[0][2]) * (pp[2][2] - pp[0][2]));
            tot += l;
            for (j = 0; j < 3; j++) {
                f1[j] += l / 6.0 * (pp[0][j] + 4.0 * pp[1][j] + pp[2][j]);
                for (k = 0; k < 3; k++) {
                    f2[j][k] += l / 6.0 * (pp[0][j] * pp[0][k] + 4.0 * pp[1][j] * pp[1][k] +
                                           pp[2][j] * pp[2][k]);
                }
            }
        }
    }
    for (j = 0; j < 3; j++) {
        for (k = 0; k < 3; k++) {
            f2[j][k] -= f1[j] * f1[k] / tot;
        }
    }
    for (j = 0; j < 3; j++) {
        for (k = 0; k < 3; k++) {
            jt[j][k] = (j == k ? f2[0][0] + f2[1][1] + f2[2][2] : 0.0) - f2[j][k];
            v[j][k] = j == k ? 1.0 : 0.0;
        }
    }
    for (sw = 0; sw < 50; sw++) { /* cyclic Jacobi */
        int p, q;
        for (p = 0; p < 2; p++) {
            for (q = p + 1; q < 3; q++) {
                double th, t, c, sn;
                if (fabs(jt[p][q]) < 1e-300) {
                    continue;
                }
                th = (jt[q][q] - jt[p][p]) / (2.0 * jt[p][q]);
                t = (th >= 0 ? 1.0 : -1.0) / (fabs(th) + sqrt(th * th + 1.0));
                c = 1.0 / sqrt(t * t + 1.0);
                sn = t * c;
                for (k = 0; k < 3; k++) { /* J <- G^T J G */
                    double a1 = jt[k][p], a2 = jt[k][q];
                    jt[k][p] = c * a1 - sn * a2;
                    jt[k][q] = sn * a1 + c * a2;
                }
                for (k = 0; k < 3; k++) {
                    double a1 = jt[p][k], a2 = jt[q][k];
                    jt[p][k] = c * a1 - sn * a2;
                    jt[q][k] = sn * a1 + c * a2;
                }
                for (k = 0; k < 3; k++) {
                    double a1 = v[k][p], a2 = v[k][q];
                    v[k][p] = c * a1 - sn * a2;
                    v[k][q] = sn * a1 + c * a2;
                }
            }
        }
    }
    {
        int idx[3] = {0, 1, 2};
        for (i = 0; i < 3; i++) {
            for (j = i + 1; j < 3; j++) {
                if (jt[idx[j]][idx[j]] < jt[idx[i]][idx[i]]) {
                    int t = idx[i];
                    idx[i] = idx[j];
                    idx[j] = t;
                }
            }
        }
        for (i = 0; i < 3; i++) {
            lam[i] = jt[idx[i]][idx[i]];
        }
        for (k = 0; k < 3; k++) {
            ax[k] = v[k][idx[2]];
        }
        if (dot3(ax, s->z) < 0) {
            ax[0] = -ax[0];
            ax[1] = -ax[1];
            ax[2] = -ax[2];
        }
    }
    *len = tot;
}

/* ---- the far sections (ref_channel.h) ---- */

static double far_dist3(const double *a, const double *b)
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                (a[2] - b[2]) * (a[2] - b[2]));
}

/* the bounding ball of a section: a max(1, sqrt(2^(1 - 2/n))), a the larger semi-axis */
static double far_ball(const struct ref_ch_row *o)
{
    double a = o->a > o->b ? o->a : o->b, q = 2.0 / o->n;
    return q < 1.0 ? a * sqrt(pow(2.0, 1.0 - q)) : a;
}

void ref_channel_far_init(struct ref_channel_far *f, const struct ref_channel *r)
{
    const double top = r->ns - 1.0;
    struct ref_ch_row o;
    double ext = 0.0, prev[3];
    int k, m, q;
    f->rbmax = f->lip = f->piece = 0.0;
    for (k = 0; k <= REF_CH_FAR; k++) {
        ref_channel_row(r, top * k / REF_CH_FAR, &o);
        for (q = 0; q < 3; q++) {
            f->l[k][q] = o.l[q];
            f->t[k][q] = o.tau[q];
        }
        f->rb[k] = far_ball(&o);
        f->rbmax = f->rb[k] > f->rbmax ? f->rb[k] : f->rbmax;
        f->s[k] = 0.0;
        if (k > 0) {
            double a = 0.0;
            for (q = 0; q < 3; q++) {
                prev[q] = f->l[k - 1][q];
            }
            for (m = 1; m <= 8; m++) {
                ref_channel_row(r, top * (k - 1 + m / 8.0) / REF_CH_FAR, &o);
                a += far_dist3(prev, o.l);
                for (q = 0; q < 3; q++) {
                    prev[q] = o.l[q];
                }
            }
            f->s[k] = f->s[k - 1] + a;
            a += fabs(f->rb[k] - f->rb[k - 1]);
            f->lip = a > f->lip ? a : f->lip;
        }
    }
    for (k = 0; k < r->ns; k++) {
        double d = far_dist3(r->s[k].c, r->s[0].c);
        ext = d > ext ? d : ext;
    }
    f->len = f->s[REF_CH_FAR];
    for (k = 0; k < 64; k++) {
        int a = k * REF_CH_FAR / 64, b = (k + 1) * REF_CH_FAR / 64;
        f->piece = f->s[b] - f->s[a] > f->piece ? f->s[b] - f->s[a] : f->piece;
    }
    f->closed = far_dist3(f->l[REF_CH_FAR], f->l[0]) <= 1e-5 * ext;
}

/* samples i, j far apart: at least near of arc both ways on a closed guide */
static int far_apart(const struct ref_channel_far *f, int i, int j, double near)
{
    double sep = fabs(f->s[j] - f->s[i]);
    return sep >= near && !(f->closed && f->len - sep < near);
}

/* height of p over the plane of the section at u (guide units) */
static double far_height(const struct ref_channel *r, double u, const double *p,
                         struct ref_ch_row *o)
{
    double d[3];
    int q;
    ref_channel_row(r, u, o);
    for (q = 0; q < 3; q++) {
        d[q] = p[q] - o->l[q];
    }
    return dot3(d, o->tau);
}

/* depth of p in the disk of row o (p in its plane): (1 - rho) min(a, b) */
static double far_in_disk(const struct ref_ch_row *o, const double *p)
{
    double d[3], x1, x2, X, Y, rho;
    int q;
    for (q = 0; q < 3; q++) {
        d[q] = p[q] - o->l[q];
    }
    x1 = dot3(d, o->e1);
    x2 = dot3(d, o->e2);
    X = x1 * cos(o->alpha) + x2 * sin(o->alpha);
    Y = -x1 * sin(o->alpha) + x2 * cos(o->alpha);
    rho = pow(pow(fabs(X / o->a), o->n) + pow(fabs(Y / o->b), o->n), 1.0 / o->n);
    return (1.0 - rho) * (o->a < o->b ? o->a : o->b);
}

double ref_channel_far_depth(const struct ref_channel *r, const struct ref_channel_far *f,
                             double near, double *ua, double *ub)
{
    const double top = r->ns - 1.0;
    struct ref_ch_row o;
    double best = -1e30;
    int i, j, m, it, q;
    *ua = *ub = -1.0;
    for (i = 0; i <= REF_CH_FAR; i++) {
        double u = top * i / REF_CH_FAR;
        for (m = 0; m < REF_CH_FAR_W; m++) {
            double p[3], w = 2.0 * 3.14159265358979323846 * m / REF_CH_FAR_W, h0, h1, d[3];
            ref_channel_point(r, u, w, p);
            for (q = 0; q < 3; q++) {
                d[q] = p[q] - f->l[0][q];
            }
            h0 = dot3(d, f->t[0]);
            for (j = 1; j <= REF_CH_FAR; j++) {
                for (q = 0; q < 3; q++) {
                    d[q] = p[q] - f->l[j][q];
                }
                h1 = dot3(d, f->t[j]);
                if ((h0 < 0.0) != (h1 < 0.0) && far_apart(f, i, j - 1, near) &&
                    far_apart(f, i, j, near)) {
                    double lo = top * (j - 1) / REF_CH_FAR, hi = top * j / REF_CH_FAR, hl = h0, x;
                    for (it = 0; it < 40; it++) { /* bisection of the height's sign */
                        double mid = 0.5 * (lo + hi), hm = far_height(r, mid, p, &o);
                        if ((hm < 0.0) == (hl < 0.0)) {
                            lo = mid;
                            hl = hm;
                        } else {
                            hi = mid;
                        }
                    }
                    (void)far_height(r, 0.5 * (lo + hi), p, &o);
                    x = far_in_disk(&o, p);
                    if (x > best) {
                        best = x;
                        *ua = u;
                        *ub = 0.5 * (lo + hi);
                    }
                }
                h0 = h1;
            }
        }
    }
    return best;
}

double ref_channel_far_ballgap(const struct ref_channel_far *f, double near)
{
    double best = 1e30;
    int i, j;
    for (i = 0; i <= REF_CH_FAR; i++) {
        for (j = i + 1; j <= REF_CH_FAR; j++) {
            if (far_apart(f, i, j, near)) {
                double g = far_dist3(f->l[i], f->l[j]) - f->rb[i] - f->rb[j];
                best = g < best ? g : best;
            }
        }
    }
    return best;
}
