/* frenet.c - BASELINE ONLY: the paper's two-quadrature Frenet form (MATH-canal §5.1).
 * SPDX-License-Identifier: MIT
 */
#include "frenet.h"

#if CP_REAL_DOUBLE
#define F_EXP(x) exp(x)
#define F_SIN(x) sin(x)
#define F_COS(x) cos(x)
#else
#define F_EXP(x) expf(x)
#define F_SIN(x) sinf(x)
#define F_COS(x) cosf(x)
#endif

struct fjet {
    cp_real rho[3], d1[3], d2[3], d3[3]; /* rho and its first three derivatives */
    cp_real x, y;                        /* X and sigma tau / 2 */
    cp_real v1;                          /* tan(u1/2) */
};

static void fjet_eval(const struct frenet *fr, cp_real t, struct fjet *j)
{
    cp_real st = F_SIN(t), ct = F_COS(t), sk = F_SIN(fr->k * t), ck = F_COS(fr->k * t);
    cp_real k = fr->k, b = fr->b;
    cp_real w[3], wn2, wn, sig, c2, c, det, stau, pp, qq;
    j->rho[0] = fr->cx + fr->r * ct;
    j->rho[1] = fr->cy + fr->r * st;
    j->rho[2] = b * ck + fr->c;
    j->d1[0] = -fr->r * st;
    j->d1[1] = fr->r * ct;
    j->d1[2] = -b * k * sk;
    j->d2[0] = -fr->r * ct;
    j->d2[1] = -fr->r * st;
    j->d2[2] = -b * k * k * ck;
    j->d3[0] = fr->r * st;
    j->d3[1] = -fr->r * ct;
    j->d3[2] = b * k * k * k * sk;
    w[0] = j->d1[1] * j->d2[2] - j->d1[2] * j->d2[1];
    w[1] = j->d1[2] * j->d2[0] - j->d1[0] * j->d2[2];
    w[2] = j->d1[0] * j->d2[1] - j->d1[1] * j->d2[0];
    wn2 = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
    wn = cp_sqrt(wn2);
    c2 = j->d1[0] * j->d1[0] + j->d1[1] * j->d1[1];
    c = cp_sqrt(c2);
    sig = cp_sqrt(c2 + j->d1[2] * j->d1[2]);
    det = w[0] * j->d3[0] + w[1] * j->d3[1] + w[2] * j->d3[2];
    stau = sig * det / wn2;
    pp = j->d2[2] * c2 - j->d1[2] * (j->d1[0] * j->d2[0] + j->d1[1] * j->d2[1]);
    qq = j->d1[0] * j->d2[1] - j->d1[1] * j->d2[0];
    j->v1 = -(c * wn + pp) / (sig * qq);
    j->x = stau * j->v1 + j->d1[2] * wn / (sig * sig * c);
    j->y = CP_R(0.5) * stau;
}

int frenet_init(struct frenet *fr, cp_real cx, cp_real cy, cp_real r, cp_real b, cp_real c,
                cp_real k, cp_real t0, cp_real t1, uint32_t n, cp_real u0)
{
    struct fjet j;
    cp_real q0, lam0, v10;
    fr->cx = cx;
    fr->cy = cy;
    fr->r = r;
    fr->b = b;
    fr->c = c;
    fr->k = k;
    fr->t0 = t0;
    fr->h = (t1 - t0) / (cp_real)n;
    fr->i = 0xFFFFFFFFu;
    fjet_eval(fr, t0, &j);
    if (!cp_finite(j.v1) || !cp_finite(j.x) || u0 == CP_R(0.0)) {
        return CP_ERR_RANGE;
    }
    q0 = cp_sqrt(CP_R(1.0) + j.d1[2] * j.d1[2] / (j.d1[0] * j.d1[0] + j.d1[1] * j.d1[1]));
    lam0 = q0 * F_COS(CP_R(0.5) * u0) / F_SIN(CP_R(0.5) * u0);
    v10 = j.v1;
    fr->w = (lam0 / q0 - v10) / (CP_R(1.0) + v10 * v10);
    fr->y1 = CP_R(0.0);
    fr->y2 = CP_R(0.0);
    fr->x_prev = j.x;
    fr->y_prev = j.y;
    return CP_OK;
}

void frenet_next(struct frenet *fr, struct cp_vec3 *m)
{
    struct fjet jm, j;
    cp_real t, sig, c, wv[3], wn, tt[3], bb[3], nn[3], a, rc, v, v2, cu, su, e;
    if (fr->i == 0xFFFFFFFFu) {
        fr->i = 0;
        t = fr->t0;
        fjet_eval(fr, t, &j);
    } else {
        cp_real h = fr->h, k1, k2, k3, k4;
        fr->i++;
        t = fr->t0 + (cp_real)fr->i * h;
        fjet_eval(fr, t - CP_R(0.5) * h, &jm);
        fjet_eval(fr, t, &j);
        /* RK4 on y1' = X(t), y2' = Y(t) exp(-y1) */
        k1 = fr->y_prev * F_EXP(-fr->y1);
        k2 = jm.y * F_EXP(-(fr->y1 + CP_R(0.5) * h * fr->x_prev));
        k3 = jm.y * F_EXP(-(fr->y1 + CP_R(0.5) * h * jm.x));
        k4 = j.y * F_EXP(-(fr->y1 + h * jm.x));
        fr->y2 += h / CP_R(6.0) * (k1 + CP_R(2.0) * k2 + CP_R(2.0) * k3 + k4);
        fr->y1 += h / CP_R(6.0) * (fr->x_prev + CP_R(4.0) * jm.x + j.x);
        fr->x_prev = j.x;
        fr->y_prev = j.y;
    }
    /* frame and point */
    c = cp_sqrt(j.d1[0] * j.d1[0] + j.d1[1] * j.d1[1]);
    sig = cp_sqrt(c * c + j.d1[2] * j.d1[2]);
    wv[0] = j.d1[1] * j.d2[2] - j.d1[2] * j.d2[1];
    wv[1] = j.d1[2] * j.d2[0] - j.d1[0] * j.d2[2];
    wv[2] = j.d1[0] * j.d2[1] - j.d1[1] * j.d2[0];
    wn = cp_sqrt(wv[0] * wv[0] + wv[1] * wv[1] + wv[2] * wv[2]);
    tt[0] = j.d1[0] / sig;
    tt[1] = j.d1[1] / sig;
    tt[2] = j.d1[2] / sig;
    bb[0] = wv[0] / wn;
    bb[1] = wv[1] / wn;
    bb[2] = wv[2] / wn;
    nn[0] = bb[1] * tt[2] - bb[2] * tt[1];
    nn[1] = bb[2] * tt[0] - bb[0] * tt[2];
    nn[2] = bb[0] * tt[1] - bb[1] * tt[0];
    a = -j.rho[2] * j.d1[2] / sig;
    rc = j.rho[2] * c / sig;
    e = F_EXP(fr->y1);
    v = j.v1 + CP_R(1.0) / (e * (fr->w + fr->y2));
    v2 = v * v;
    cu = (CP_R(1.0) - v2) / (CP_R(1.0) + v2);
    su = CP_R(2.0) * v / (CP_R(1.0) + v2);
    m->x = j.rho[0] + a * tt[0] + rc * (cu * nn[0] + su * bb[0]);
    m->y = j.rho[1] + a * tt[1] + rc * (cu * nn[1] + su * bb[1]);
    m->z = j.rho[2] + a * tt[2] + rc * (cu * nn[2] + su * bb[2]);
}
