/* channel.c - channel surface from superellipse cross-sections (channel.h).
 * SPDX-License-Identifier: MIT
 *
 * One evaluation path (guide -> row at u, angle -> point at w) serves the init walks and
 * the stream alike. Vectors are struct cp_vec3 with cp_math's cp_v3_* operations; the
 * spline, Hermite and inertia formulas that run over the x, y, z coordinates take them
 * by index (comp, vec_of), the a/cos, b/sin halves are arrays of 2.
 */
#include "channel.h"
#include "cp_math.h"
#include "raster.h"

/* The five laws along the guide (natural cubic splines, B13). */
enum { Q_S = 0, Q_N = 1, Q_JI = 2, Q_JII = 3, Q_J12 = 4, NQ = 5 };

#define SAG_MARGIN CP_R(0.8) /* aim the derived step counts at 80 % of the tolerance */

/* ---------------------------------------------------------------------------------------
 * K_S, K_J (B11) by ln Gamma and digamma on 0 < x <= 4.
 *
 * Shift: Gamma(x) = Gamma(z) / pr, pr = prod_{i<S} (x + i), z = x + S, S = LG_SHIFT, so
 *   ln Gamma(x) = st(z) - ln pr,   psi(x) = ps(z) - rs,   rs = sum_{i<S} 1/(x + i);
 * Stirling: st(z) = (z - 1/2) ln z - z + ln sqrt(2 pi) + sum_k B_2k / (2k (2k-1) z^(2k-1)),
 *           ps(z) = ln z - 1/(2z) - sum_k B_2k / (2k z^2k).
 * With p = 1/n, K_S = 2p Gamma(p)^2 / Gamma(2p) and K_J = p Gamma(p) Gamma(3p) / Gamma(4p)
 * are K = c p prod_k Gamma(k p)^e_k, e = (2, -1, 0, 0) and (1, 0, 1, -1). Both e have
 * sum e_k = 1 and sum e_k (z_k - 1/2) = S - 1/2, so with ln z = ln S + ln(z/S) the large
 * parts of st collapse into one constant, LG_C0 = S^(S - 1/2) e^-S sqrt(2 pi):
 *   K = c p LG_C0 prod_k pr_k^-e_k exp(sum_k e_k ((z_k - 1/2) ln(z_k/S) + sum_k(z_k))),
 * and (sum e_k k = 0) d ln K/dn = -p^2 d ln K/dp = -p^2 (n + sum_k e_k k (ps_k - ln S - rs_k)).
 * S is a power of two: z/S is exact and ln(z/S) in [0, ln 2].
 * Error analysis. Float: S = 4 (z >= 4), series to z^-7 / z^-6: truncation <= 1/(1188 z^9)
 * = 3.2e-9 in st and 1/(240 z^8) = 6.4e-8 in ps. Rounding: the exponent is a sum of terms
 * <= 7.5 ln 2 = 5.2 (n = 1; <= 0.8 for n >= 4) whose ln(z/S) carry a few ulp of <= 0.7;
 * the products a few ulp: K to ~5e-7 relative (the laws' a and b amplify K's error about
 * 4-fold near the example's isotropic middle), and at the nodes it cancels exactly (S_i =
 * a b K_S(n_i) and a(u = i) use the same K_S(n_i)). Double: S = 16 (z >= 16), series to
 * z^-11: truncation <= 1/(156 z^13) = 1.4e-18; rounding a few ulp of the exponent (<= 4.4):
 * ~1e-15. pr <= 19!/3! = 2e16 (double), 8!/0! (float) and >= x (no overflow or
 * underflow). Fixed work: S products and divisions, 2 Horner polynomials (S steps, the
 * first S - T on zeros: exact), 1 log per x, no iteration. */
#if CP_REAL_DOUBLE
#define LG_SHIFT 16u
#define LG_TERMS 6u
#define LG_C0 1300882150951.44565933
static const cp_real lg_c[2][LG_SHIFT] = {
    {1.0 / 12.0, -1.0 / 360.0, 1.0 / 1260.0, -1.0 / 1680.0, 1.0 / 1188.0, -691.0 / 360360.0},
    {1.0 / 12.0, -1.0 / 120.0, 1.0 / 252.0, -1.0 / 240.0, 1.0 / 132.0, 0.0}};
#else
#define LG_SHIFT 4u
#define LG_TERMS 4u
#define LG_C0 5.87654378f
static const cp_real lg_c[2][LG_SHIFT] = {{8.33333333e-2f, -2.77777778e-3f, 7.93650794e-4f, -5.95238095e-4f},
                                          {8.33333333e-2f, -8.33333333e-3f, 3.96825397e-3f, 0.0f}};
#endif

CP_STATIC_ASSERT(LG_TERMS <= LG_SHIFT, series_fits_the_shift_loop);

/* The shift loop unrolled in speed builds (gcc, clang: the host's per-point instruction
 * counts), rolled in size builds (-Os: the image). The same operations either way. */
#if defined(__GNUC__) && !defined(__OPTIMIZE_SIZE__)
#define KC_UNROLL _Pragma("GCC unroll 16")
#else
#define KC_UNROLL
#endif

/* o = K_S, K_J, d ln K_S/dn, d ln K_J/dn at n in [1, CHANNEL_N_MAX]. The shift and the two
 * Horner series share one loop of LG_SHIFT rounds (lg_c padded with zeros past LG_TERMS:
 * the rounds before c_(T-1) keep hs = hp = 0 exactly, so the same operations on the
 * same values as separate loops; one rolled body in the image). */
static void kconst(cp_real n, cp_real *o)
{
    cp_real p = CP_R(1.0) / n, pr[4], st[4], ps[4];
    unsigned k, i;
    for (k = 0; k < 4u; k++) { /* x = (k + 1) p */
        cp_real x = (cp_real)(k + 1u) * p, rs = CP_R(0.0), z, zi, z2, lz, hs, hp;
        z = x + (cp_real)LG_SHIFT;
        zi = CP_R(1.0) / z;
        z2 = zi * zi;
        pr[k] = CP_R(1.0);
        hs = CP_R(0.0);
        hp = CP_R(0.0);
        KC_UNROLL
        for (i = 0; i < LG_SHIFT; i++) { /* the shift; the series c_(S-1) .. c_0 */
            cp_real v = x + (cp_real)i;
            pr[k] *= v;
            rs += CP_R(1.0) / v;
            hs = hs * z2 + lg_c[0][LG_SHIFT - 1u - i];
            hp = hp * z2 + lg_c[1][LG_SHIFT - 1u - i];
        }
        lz = cp_log(z * (CP_R(1.0) / (cp_real)LG_SHIFT));
        st[k] = (z - CP_R(0.5)) * lz + zi * hs;
        ps[k] = lz - CP_R(0.5) * zi - z2 * hp - rs;
    }
    o[0] = CP_R(2.0) * p * LG_C0 * pr[1] / (pr[0] * pr[0]) * cp_exp(CP_R(2.0) * st[0] - st[1]);
    o[1] = p * LG_C0 * pr[3] / (pr[0] * pr[2]) * cp_exp(st[0] + st[2] - st[3]);
    o[2] = -p * p * (n + CP_R(2.0) * (ps[0] - ps[1]));
    o[3] = -p * p * (n + ps[0] + CP_R(3.0) * ps[2] - CP_R(4.0) * ps[3]);
}

cp_real channel_ks(cp_real n)
{
    cp_real o[4];
    kconst(n, o);
    return o[0];
}

cp_real channel_kj(cp_real n)
{
    cp_real o[4];
    kconst(n, o);
    return o[1];
}

/* ---------------------------------------------------------------------------------------
 * Small helpers. Coordinate k (0 x, 1 y, 2 z) of a vector, for the formulas written per
 * coordinate. */
static cp_real comp(const struct cp_vec3 *v, unsigned k)
{
    return k == 0u ? v->x : (k == 1u ? v->y : v->z);
}

/* The vector of coordinates a[0], a[1], a[2]. */
static struct cp_vec3 vec_of(const cp_real *a)
{
    struct cp_vec3 v;
    v.x = a[0];
    v.y = a[1];
    v.z = a[2];
    return v;
}

/* a + k pi nearest ref (unwrapping mod pi). */
static CP_NOINLINE cp_real near(cp_real a, cp_real ref)
{
    return a + CP_PI * cp_floor((ref - a) / CP_PI + CP_R(0.5));
}

/* Row vector v times the rotation of eq. (10)-(12) about axis k (0 x: T(theta), 1 y:
 * T(phi), 2 z: T(psi)): the two other coordinates i = k+1, j = k+2 (mod 3) become
 * (v_i c - v_j s, v_i s + v_j c). R = A B C (row vectors): row r of R = e_r A B C, the
 * factors applied left to right. */
void channel_euler(struct channel_section *s, cp_real psi, cp_real theta, cp_real phi,
                   uint8_t order)
{
    static const uint8_t ax[2][3] = {{2u, 0u, 1u}, {0u, 1u, 2u}}, nx[3] = {1u, 2u, 0u};
    cp_real ang[3], v[6]; /* rows 0 (x, v[0..2]) and 2 (z, v[3..5]) of R */
    unsigned r, k, o = order == CHANNEL_ORDER_PRINTED ? 1u : 0u;
    ang[0] = theta;
    ang[1] = phi;
    ang[2] = psi;
    for (r = 0; r < 6u; r++) {
        v[r] = r == 0u || r == 5u ? CP_R(1.0) : CP_R(0.0); /* e_0, e_2 */
    }
    for (k = 0; k < 3u; k++) { /* each factor applied to both rows */
        unsigned a = ax[o][k], i = nx[a], j = nx[i]; /* i = a + 1, j = a + 2 (mod 3) */
        cp_real sn, cs;
        cp_sincos(ang[a], &sn, &cs);
        for (r = 0; r < 6u; r += 3u) {
            cp_real vi = v[r + i], vj = v[r + j];
            v[r + i] = vi * cs - vj * sn;
            v[r + j] = vi * sn + vj * cs;
        }
    }
    s->x = vec_of(&v[0]);
    s->z = vec_of(&v[3]);
}

/* ---------------------------------------------------------------------------------------
 * Row at u: guide segment m = floor(u) (last: N-2), t = u - m.
 * Guide: quintic Hermite on t in [0, 1] from P0, M0, A0 (t = 0) and P1, M1, A1 (t = 1) in
 * monomial form (the basis of B.2 step 2 expanded): c0 = P0, c1 = M0, c2 = A0/2 and
 *   c3 = 10 dP - 6 M0 - 4 M1 - 3/2 A0 + 1/2 A1, c4 = -15 dP + 8 M0 + 7 M1 + 3/2 A0 - A1,
 *   c5 = 6 dP - 3 M0 - 3 M1 - 1/2 A0 + 1/2 A1  (rows of hc over dP, M0, M1, A0, A1);
 * value, first and half the second derivative by one Horner pass (exact P0, M0, A0 at
 * t = 0: every higher term is multiplied by t = 0). */
static const cp_real hc[3][5] = {
    {CP_R(10.0), CP_R(-6.0), CP_R(-4.0), CP_R(-1.5), CP_R(0.5)},
    {CP_R(-15.0), CP_R(8.0), CP_R(7.0), CP_R(1.5), CP_R(-1.0)},
    {CP_R(6.0), CP_R(-3.0), CP_R(-3.0), CP_R(-0.5), CP_R(0.5)}};

/* Unit tangent and frame from the tangent r->t: r->sp = |r->t|, r->t /= r->sp (tau),
 * e1 = unit(e_y x tau) = (tau_z, 0, -tau_x)/vn, e2 = tau x e1; returns vn (the frame is
 * undefined at vn <= CHANNEL_FRAME_TOL: the callers' check; r->flags untouched). */
static cp_real frame(struct channel_row *r)
{
    cp_real vn;
    r->sp = cp_v3_unit(&r->t);
    r->e1.x = r->t.z;
    r->e1.y = CP_R(0.0);
    r->e1.z = -r->t.x;
    vn = cp_v3_unit(&r->e1);
    cp_v3_cross(&r->t, &r->e1, &r->e2);
    return vn;
}

/* Guide part: L, L', L'' -> tau, frame, |L'|; curvature vector kv = (L'' - (tau.L'')
 * tau)/|L'|^2, so kv.e_i = L''.e_i/|L'|^2; frame twist w = e2.e1' = e2.(tau'_z, 0,
 * -tau'_x)/vn with tau' = (L'' - (tau.L'') tau)/|L'|, whose tau part drops out
 * (e2_x tau_z - e2_z tau_x = 0): w = (e2_x L''_z - e2_z L''_x)/(|L'| vn).
 * Laws: natural cubic splines on [m, m + 1] (exact node values at t = 0). */
void channel_row(const struct channel *ch, cp_real u, struct channel_row *r)
{
    const struct channel_section *s0, *s1;
    const cp_real *ac;
    struct cp_vec3 l2;
    cp_real lk[3], tk[3], l2k[3], v[NQ], dv[NQ], kk[4];
    cp_real t, tt, vn, w, pp, lp, js, qq, lq, r1, r2, a, b, dd, e, dal;
    unsigned m, k, j, i, fl; /* CHANNEL_ROW_* flags, stored at the end */
    r->u = u;
    if (!(u > CP_R(0.0))) {
        u = CP_R(0.0);
    }
    if (u > (cp_real)(ch->ns - 1u)) {
        u = (cp_real)(ch->ns - 1u);
    }
    m = (unsigned)u;
    if (m + 1u >= ch->ns) {
        m = ch->ns - 2u;
    }
    t = u - (cp_real)m;
    s0 = &ch->cfg->s[m];
    s1 = &ch->cfg->s[m + 1u];
    ac = ch->acc[m];
    for (k = 0; k < 3u; k++) {
        cp_real in[5], h = CP_R(0.0), d1 = CP_R(0.0), d2 = CP_R(0.0);
        in[0] = comp(&s1->c, k) - comp(&s0->c, k);
        in[1] = ch->d[m] * comp(&s0->z, k);
        in[2] = ch->d[m + 1u] * comp(&s1->z, k);
        in[3] = ac[k];
        in[4] = ac[3u + k];
        for (j = 6u; j-- > 0u;) { /* c5 .. c0 */
            cp_real cj = j == 2u ? CP_R(0.5) * in[3] : (j == 1u ? in[1] : comp(&s0->c, k));
            if (j >= 3u) {
                cj = CP_R(0.0);
                for (i = 0; i < 5u; i++) {
                    cj += hc[j - 3u][i] * in[i];
                }
            }
            d2 = d2 * t + d1;
            d1 = d1 * t + h;
            h = h * t + cj;
        }
        lk[k] = h;
        tk[k] = d1;
        l2k[k] = CP_R(2.0) * d2;
    }
    r->l = vec_of(lk);
    r->t = vec_of(tk);
    l2 = vec_of(l2k);
    vn = frame(r);
    fl = vn > CHANNEL_FRAME_TOL ? 0u : CHANNEL_ROW_FRAME;
    for (k = 0; k < 2u; k++) {
        r->k[k] = cp_v3_dot(&l2, k ? &r->e2 : &r->e1) / (r->sp * r->sp);
    }
    w = (r->e2.x * l2.z - r->e2.z * l2.x) / (r->sp * vn);
    tt = CP_R(1.0) - t;
    for (k = 0; k < NQ; k++) {
        cp_real ya = ch->y[k][m], yb = ch->y[k][m + 1u];
        /* second derivatives at nodes m, m + 1 (natural ends: 0) */
        cp_real sa = m > 0u ? ch->y2[k][m - 1u] : CP_R(0.0);
        cp_real sb = m + 2u < ch->ns ? ch->y2[k][m] : CP_R(0.0);
        v[k] = tt * ya + t * yb + ((tt * tt * tt - tt) * sa + (t * t * t - t) * sb) / CP_R(6.0);
        dv[k] = yb - ya + ((CP_R(1.0) - CP_R(3.0) * tt * tt) * sa + (CP_R(3.0) * t * t - CP_R(1.0)) * sb) /
                              CP_R(6.0);
    }
    r->s = v[Q_S];
    r->n = v[Q_N];
    if (!(v[Q_S] > CP_R(0.0)) || !(v[Q_N] >= CP_R(1.0))) {
        fl |= CHANNEL_ROW_BAD_LAW;
    }
    /* closed-form section (B.2 step 6): P = ab, Q = a^2 + b^2; a + b = r1, a - b = r2;
     * b = P/a (no cancellation). Log-derivatives for the normal: P'/P, Q'/Q. */
    kconst(v[Q_N], kk);
    pp = v[Q_S] / kk[0];
    lp = dv[Q_S] / v[Q_S] - kk[2] * dv[Q_N];
    js = v[Q_JI] + v[Q_JII];
    qq = js / (kk[1] * pp);
    lq = (dv[Q_JI] + dv[Q_JII]) / js - kk[3] * dv[Q_N] - lp; /* Q'/Q */
    /* Q <= 0 (J_I + J_II <= 0: spline overshoot) or NaN is no section: rejected
     * (CP_ERR_AREA_LAW by the init walks); 0 < Q < 2P is clamped to a = b and counted */
    if (!(qq > CP_R(0.0))) {
        fl |= CHANNEL_ROW_BAD_LAW;
    }
    if (qq < CP_R(2.0) * pp) {
        qq = CP_R(2.0) * pp;
        fl |= CHANNEL_ROW_CLAMP;
    }
    r1 = cp_sqrt(qq + CP_R(2.0) * pp);
    r2 = cp_sqrt(qq - CP_R(2.0) * pp);
    a = CP_R(0.5) * (r1 + r2);
    b = pp / a;
    r->ab[0] = a;
    r->ab[1] = b;
    /* orientation, tensor form; then the multiple of pi nearest the blend of node angles */
    dd = v[Q_JII] - v[Q_JI];
    e = CP_R(2.0) * v[Q_J12];
    r->alpha = near(CP_R(0.5) * cp_atan2(e, dd), ch->al[m] + t * (ch->al[m + 1u] - ch->al[m]));
    cp_sincos(r->alpha, &r->sa, &r->ca);
    /* derivatives, logarithmic: x = a'/a, b'/b = P'/P - x; Q'/2 = a^2 x + b^2 (P'/P - x), so
     * x = (Q'/2 - b^2 P'/P)/(a^2 - b^2), a^2 - b^2 = r1 r2; alpha' = (D J12' - J12 D')/(D^2 + E^2).
     * Near a = b (r2 <= 1e-3 r1) both are ill-conditioned: isotropic growth, alpha' = 0. */
    if (r2 > CP_R(1.0e-3) * r1) {
        r->dab[0] = (CP_R(0.5) * lq * qq - b * b * lp) / (r1 * r2);
        dal = (dd * dv[Q_J12] - v[Q_J12] * (dv[Q_JII] - dv[Q_JI])) / (dd * dd + e * e);
    } else {
        r->dab[0] = CP_R(0.5) * lp;
        dal = CP_R(0.0);
    }
    r->dab[1] = lp - r->dab[0];
    r->q = CP_R(2.0) / v[Q_N];
    r->dq = -r->q * dv[Q_N] / v[Q_N];
    r->wr = dal + w;
    r->flags = (uint8_t)fl;
}

/* (x, y) rotated by alpha. */
static void rot(const struct channel_row *r, const cp_real *v, cp_real *o)
{
    o[0] = v[0] * r->ca - v[1] * r->sa;
    o[1] = v[0] * r->sa + v[1] * r->ca;
}

/* o = f v + x e1 + y e2 (the row's frame), per component summed left to right. */
static CP_NOINLINE void comb(const struct channel_row *r, struct cp_vec3 *o,
                             const struct cp_vec3 *v, cp_real f, cp_real x, cp_real y)
{
    o->x = f * v->x + x * r->e1.x + y * r->e2.x;
    o->y = f * v->y + x * r->e1.y + y * r->e2.y;
    o->z = f * v->z + x * r->e1.z + y * r->e2.z;
}

/* Point and normal (B.2 step 7). In the section axes (index 0: a and cos w, 1: b and
 * sin w; |cos w| or |sin w| below CHANNEL_AXIS_SNAP counts as 0) with (X', Y') =
 * R(alpha)(X, Y) the in-plane offset:
 *   P = L + X' e1 + Y' e2,  P_u . tau = |L'| g,  g = 1 - k.(P - L) = 1 - k1 X' - k2 Y',
 *   in-plane part of P_u = R(alpha) [(X (a'/a + ln|cos w| q'), Y (b'/b + ln|sin w| q'))
 *   + (alpha' + w)(-Y, X)] (rotation by 90 degrees commutes with R(alpha));
 * the outward in-plane normal of the superellipse m ~ R(alpha)(sgn(c)|c|^(2-q)/a,
 * sgn(s)|s|^(2-q)/b) (|c|^(2-q) = c^2/|c|^q) is _|_ P_w, so N ~ g |L'| m - (m.P_u) tau
 * is _|_ P_u too: the exact unit normal, pointing away from the guide (m.P_u taken in
 * the section axes: rotations keep dot products). */
void channel_point(const struct channel_row *r, cp_real w, struct cp_vec3 *p, struct cp_vec3 *nrm,
                   cp_real *g)
{
    cp_real cs[2], x[2], v[2], mm[2], xp[2], m[2], gg, sm;
    struct cp_vec3 mv;
    unsigned i;
    cp_sincos(w, &cs[1], &cs[0]);
    for (i = 0; i < 2u; i++) {
        cp_real c = cs[i], lg = CP_R(0.0), e = CP_R(0.0);
        if (cp_fabs(c) >= CHANNEL_AXIS_SNAP) {
            lg = cp_log(cp_fabs(c));
            e = cp_exp(r->q * lg);
        }
        x[i] = r->ab[i] * (c < CP_R(0.0) ? -e : e);
        v[i] = x[i] * (r->dab[i] + lg * r->dq);
        mm[i] = e > CP_R(0.0) ? c * cp_fabs(c) / (e * r->ab[i]) : CP_R(0.0);
    }
    v[0] -= r->wr * x[1];
    v[1] += r->wr * x[0];
    mv.x = mm[0];
    mv.y = mm[1];
    mv.z = CP_R(0.0);
    (void)cp_v3_unit(&mv);
    mm[0] = mv.x;
    mm[1] = mv.y;
    sm = mm[0] * v[0] + mm[1] * v[1];
    rot(r, x, xp);
    rot(r, mm, m);
    gg = CP_R(1.0) - r->k[0] * xp[0] - r->k[1] * xp[1];
    comb(r, p, &r->l, CP_R(1.0), xp[0], xp[1]);
    comb(r, nrm, &r->t, -sm, gg * r->sp * m[0], gg * r->sp * m[1]);
    (void)cp_v3_unit(nrm);
    *g = gg;
}

/* ---------------------------------------------------------------------------------------
 * Init. */
int channel_section_check(const struct channel_section *s)
{
    const struct cp_vec3 *vec[3] = {&s->c, &s->x, &s->z};
    unsigned i, k;
    /* every number in order (a, b, n, centre, x, z): the first non-finite one, or
     * coordinate out of range, gives the code */
    if (!cp_finite(s->a) || !cp_finite(s->b) || !cp_finite(s->n)) {
        return CP_ERR_NONFINITE;
    }
    for (i = 0; i < 3u; i++) {
        for (k = 0; k < 3u; k++) {
            cp_real x = comp(vec[i], k);
            if (!cp_finite(x)) {
                return CP_ERR_NONFINITE;
            }
            if (cp_fabs(x) > CHANNEL_COORD_MAX) {
                return CP_ERR_RANGE;
            }
        }
    }
    if (!(s->a > CP_R(0.0)) || !(s->b > CP_R(0.0))) {
        return CP_ERR_SECTION;
    }
    if (!(s->n >= CP_R(1.0))) {
        return CP_ERR_EXPONENT;
    }
    if (s->a > CHANNEL_COORD_MAX || s->b > CHANNEL_COORD_MAX || s->n > CHANNEL_N_MAX) {
        return CP_ERR_RANGE;
    }
    for (i = 0; i < 3u; i++) { /* x.x = 1, z.z = 1, x.z = 0 */
        cp_real d = cp_v3_dot(i == 1u ? &s->z : &s->x, i == 0u ? &s->x : &s->z);
        if (cp_fabs(d - (i < 2u ? CP_R(1.0) : CP_R(0.0))) > CHANNEL_AXES_TOL) {
            return CP_ERR_RANGE;
        }
    }
    if (s->n != CP_R(2.0) && cp_fabs(s->a - s->b) <= CHANNEL_ISO_TOL * (s->a > s->b ? s->a : s->b)) {
        return CP_ERR_ISOTROPIC;
    }
    return CP_OK;
}

int channel_init(struct channel *ch, const struct channel_cfg *cfg)
{
    struct channel_row r;
    struct cp_vec3 cv[CP_MAX_SECTIONS];
    cp_real cq[CP_MAX_SECTIONS], cl[CP_MAX_SECTIONS], kk[4];
    unsigned i, e, k, q, ns;
    int err;
    ch->ns = 0u;
    ch->clamps = 0u;
    if (cfg == NULL) {
        return CP_ERR_INVAL;
    }
    ns = cfg->count;
    if (ns < 2u) {
        return CP_ERR_TOO_FEW;
    }
    if (ns > CP_MAX_SECTIONS) {
        return CP_ERR_TOO_MANY;
    }
    ch->cfg = cfg;
    ch->ns = (uint8_t)ns;
    for (i = 0; i < ns; i++) {
        err = channel_section_check(&cfg->s[i]);
        if (err != CP_OK) {
            return err;
        }
    }
    /* chord e = O_e - O_(e-1), 1 <= e < N: coincident centres, a section plane containing
     * the chord (either end) */
    for (e = 1u; e < ns; e++) {
        cp_v3_sub(&cfg->s[e].c, &cfg->s[e - 1u].c, &cv[e]);
        cl[e] = cp_v3_norm(&cv[e]);
        if (!(cl[e] > CP_R(1.0e-6) * (cfg->s[e - 1u].a + cfg->s[e - 1u].b))) {
            return CP_ERR_COINCIDENT;
        }
        for (i = e - 1u; i <= e; i++) {
            if (cp_fabs(cp_v3_dot(&cfg->s[i].z, &cv[e])) < CHANNEL_PLANE_TOL * cl[e]) {
                return CP_ERR_SECTION_PLANE;
            }
        }
    }
    /* node i: chords lo = max(i, 1) and hi = min(i + 1, N - 1) (the same one at the ends).
     * Tangent M_i = d_i z_i: sign towards the next centre (last: from the previous), |d_i|
     * = mean adjacent chord (B6). Node angles (B.2 step 4) in the frame that places the
     * sections (B8), tau = unit(M_i), unwrapped mod pi; a < b: the same curve with the axes
     * swapped (a along y, alpha + pi/2). Node data (step 5). */
    for (i = 0; i < ns; i++) {
        const struct channel_section *s = &cfg->s[i];
        const struct cp_vec3 *xa = &s->x; /* the a axis */
        struct cp_vec3 ya;
        cp_real a = s->a, b = s->b, jx, jy, sn, cs, t;
        unsigned lo = i > 0u ? i : 1u, hi = i + 1u < ns ? i + 1u : i;
        t = CP_R(0.5) * (cl[lo] + cl[hi]);
        ch->d[i] = cp_v3_dot(&s->z, &cv[hi]) > CP_R(0.0) ? t : -t;
        r.t.x = ch->d[i] * s->z.x;
        r.t.y = ch->d[i] * s->z.y;
        r.t.z = ch->d[i] * s->z.z;
        for (k = 0; k < 3u; k++) {
            ch->acc[i][k] = CP_R(0.0);
        }
        /* Node second derivatives A_i (B7) = mean of the one-sided cubic-Hermite values: on
         * chord e = i (d_(i-1), d_i now known) from node e - 1 to node e, H''(0) = 6 dP -
         * 4 M_(e-1) - 2 M_e at e - 1 (q = 0), H''(1) = -(6 dP - 2 M_(e-1) - 4 M_e) at e
         * (q = 1); halved, summed over the node's two chords (the lower one first), or twice
         * the one chord of an end node. */
        for (q = 0; q < 2u && i > 0u; q++) {
            unsigned nd = i - 1u + q;
            cp_real fa = q ? CP_R(2.0) : CP_R(4.0), sg = q ? CP_R(-0.5) : CP_R(0.5);
            const struct cp_vec3 *za = &cfg->s[i - 1u].z; /* the z axis of section i - 1 */
            for (k = 0; k < 3u; k++) {
                cp_real h = sg * (CP_R(6.0) * comp(&cv[i], k) - fa * ch->d[i - 1u] * comp(za, k) -
                                  (CP_R(6.0) - fa) * ch->d[i] * comp(&s->z, k));
                if (nd == 0u || nd + 1u == ns) {
                    h += h; /* exact: the same sum as adding h twice to 0 */
                }
                ch->acc[nd][k] += h;
            }
        }
        if (!(frame(&r) > CHANNEL_FRAME_TOL)) {
            return CP_ERR_FRAME_REF;
        }
        if (a < b) {
            cp_v3_cross(&s->z, &s->x, &ya); /* y = z x x */
            xa = &ya;
            a = s->b;
            b = s->a;
        }
        t = cp_atan2(cp_v3_dot(xa, &r.e2), cp_v3_dot(xa, &r.e1));
        ch->al[i] = i > 0u ? near(t, ch->al[i - 1u]) : t;
        kconst(s->n, kk);
        jx = a * b * b * b * kk[1];
        jy = a * a * a * b * kk[1];
        cp_sincos(ch->al[i], &sn, &cs);
        ch->y[Q_S][i] = a * b * kk[0];
        ch->y[Q_N][i] = s->n;
        ch->y[Q_JI][i] = jx * cs * cs + jy * sn * sn;
        ch->y[Q_JII][i] = jx * sn * sn + jy * cs * cs;
        ch->y[Q_J12][i] = (jy - jx) * sn * cs;
    }
    /* natural cubic splines, uniform knots (h = 1): y2[i-1] + 4 y2[i] + y2[i+1] =
     * r_i = 6 (y[i+1] - 2 y[i] + y[i-1]), y2 = 0 at both ends: N - 2 <= 2 unknowns
     * (CP_MAX_SECTIONS <= 4, cp_config.h), the Thomas solve written out: N = 3: y2_1 =
     * r_1/4; N = 4: y2_1 = (4 r_1 - r_2)/15, y2_2 = (4 r_2 - r_1)/15 (the same strictly
     * diagonally dominant matrix for the five laws; a few ulp). */
    for (q = 0; q < NQ; q++) {
        for (i = 1u; i + 1u < ns; i++) {
            cq[i] = CP_R(6.0) * (ch->y[q][i + 1u] - CP_R(2.0) * ch->y[q][i] + ch->y[q][i - 1u]);
        }
        for (i = 1u; i + 1u < ns; i++) {
            ch->y2[q][i - 1u] = ns == 4u ? (CP_R(4.0) * cq[i] - cq[3u - i]) / CP_R(15.0) : cq[i] / CP_R(4.0);
        }
    }
    return CP_OK;
}

/* ---------------------------------------------------------------------------------------
 * Wire inertia (eqs. 1-8, B2-B4): closed polygon, exact moments of each uniform segment:
 * int x dL = l (A + B)/2, int x_i x_j dL = l (A_i A_j + B_i B_j + (A_i B_j + A_j B_i)/2)/3.
 * Characteristic cubic lam^3 - I1 lam^2 + I2 lam - I3 = 0 in closed form: lam = I1/3 + mu,
 * mu^3 + P mu + Q = 0, P = I2 - I1^2/3 <= 0, Q = -2 I1^3/27 + I1 I2/3 - I3,
 * mu_k = 2 sqrt(-P/3) cos(phi - 2 pi k/3), phi = acos(3Q/(2P) sqrt(-3/P))/3.
 * Host/test use only (the M4F image drops it: gc-sections). */
int channel_wire_inertia(const struct channel_section *s, uint32_t m, cp_real *len,
                         struct cp_vec3 *centroid, cp_real lam[3], struct cp_vec3 *axis3)
{
    struct cp_vec3 ya;
    cp_real mom[3], sec[3][3], jt[3][3], pv[2][3], tot = CP_R(0.0), q = CP_R(2.0) / s->n;
    cp_real i1, i2, i3, pp, qq, rr, ph, sn, cs, best = CP_R(-1.0);
    unsigned i, j, k;
    uint32_t e;
    if (m < 8u || m > 1000000u) {
        return CP_ERR_RANGE;
    }
    cp_v3_cross(&s->z, &s->x, &ya);
    for (i = 0; i < 3u; i++) {
        mom[i] = CP_R(0.0);
        for (j = 0; j < 3u; j++) {
            sec[i][j] = CP_R(0.0);
        }
    }
    for (e = 0; e <= m; e++) {
        cp_real c, sw, x, y;
        cp_sincos(CP_TWO_PI * (cp_real)(e % m) / (cp_real)m, &sw, &c);
        x = c != CP_R(0.0) ? s->a * cp_exp(q * cp_log(cp_fabs(c))) : CP_R(0.0);
        y = sw != CP_R(0.0) ? s->b * cp_exp(q * cp_log(cp_fabs(sw))) : CP_R(0.0);
        x = c < CP_R(0.0) ? -x : x;
        y = sw < CP_R(0.0) ? -y : y;
        for (i = 0; i < 3u; i++) {
            pv[e & 1u][i] = x * comp(&s->x, i) + y * comp(&ya, i);
        }
        if (e > 0u) {
            const cp_real *pa = pv[(e - 1u) & 1u], *pb = pv[e & 1u];
            cp_real l, d[3];
            struct cp_vec3 dl;
            for (i = 0; i < 3u; i++) {
                d[i] = pb[i] - pa[i];
            }
            dl = vec_of(d);
            l = cp_v3_norm(&dl);
            tot += l;
            for (i = 0; i < 3u; i++) {
                mom[i] += l * CP_R(0.5) * (pa[i] + pb[i]);
                for (j = 0; j < 3u; j++) {
                    sec[i][j] += l * (pa[i] * pa[j] + pb[i] * pb[j] +
                                      CP_R(0.5) * (pa[i] * pb[j] + pa[j] * pb[i])) /
                                 CP_R(3.0);
                }
            }
        }
    }
    for (i = 0; i < 3u; i++) {
        mom[i] /= tot; /* centroid offset from the centre (B2: rho cancels) */
    }
    for (i = 0; i < 3u; i++) {
        for (j = 0; j < 3u; j++) {
            sec[i][j] -= tot * mom[i] * mom[j]; /* about the centroid */
        }
    }
    for (i = 0; i < 3u; i++) {
        for (j = 0; j < 3u; j++) {
            jt[i][j] = i == j ? sec[0][0] + sec[1][1] + sec[2][2] - sec[i][i] : -sec[i][j];
        }
    }
    i1 = jt[0][0] + jt[1][1] + jt[2][2];
    i2 = jt[0][0] * jt[1][1] + jt[1][1] * jt[2][2] + jt[0][0] * jt[2][2] - jt[0][1] * jt[0][1] -
         jt[1][2] * jt[1][2] - jt[0][2] * jt[0][2];
    i3 = jt[0][0] * (jt[1][1] * jt[2][2] - jt[1][2] * jt[1][2]) -
         jt[0][1] * (jt[0][1] * jt[2][2] - jt[1][2] * jt[0][2]) +
         jt[0][2] * (jt[0][1] * jt[1][2] - jt[1][1] * jt[0][2]);
    pp = i2 - i1 * i1 / CP_R(3.0);
    qq = -CP_R(2.0) * i1 * i1 * i1 / CP_R(27.0) + i1 * i2 / CP_R(3.0) - i3;
    rr = pp < CP_R(0.0) ? CP_R(1.5) * qq / pp * cp_sqrt(CP_R(-3.0) / pp) : CP_R(0.0);
    rr = rr > CP_R(1.0) ? CP_R(1.0) : (rr < CP_R(-1.0) ? CP_R(-1.0) : rr);
    ph = cp_atan2(cp_sqrt(CP_R(1.0) - rr * rr), rr) / CP_R(3.0);
    pp = pp < CP_R(0.0) ? CP_R(2.0) * cp_sqrt(-pp / CP_R(3.0)) : CP_R(0.0);
    for (k = 0; k < 3u; k++) {
        cp_sincos(ph - CP_TWO_PI * (cp_real)k / CP_R(3.0), &sn, &cs);
        lam[k] = i1 / CP_R(3.0) + pp * cs; /* phi in [0, pi/3]: k = 0 largest, 1 middle, 2 smallest */
    }
    sn = lam[0];
    lam[0] = lam[2];
    lam[2] = sn;
    /* axis of lam[2]: the largest cross product of two rows of J - lam[2] I */
    for (k = 0; k < 3u; k++) {
        cp_real a[3], b[3];
        struct cp_vec3 ra, rb, cx;
        i = k;
        j = (k + 1u) % 3u;
        for (e = 0; e < 3u; e++) {
            a[e] = jt[i][e] - (i == e ? lam[2] : CP_R(0.0));
            b[e] = jt[j][e] - (j == e ? lam[2] : CP_R(0.0));
        }
        ra = vec_of(a);
        rb = vec_of(b);
        cp_v3_cross(&ra, &rb, &cx);
        cs = cp_v3_norm(&cx);
        if (cs > best) {
            best = cs;
            *axis3 = cx;
        }
    }
    cs = (cp_v3_dot(axis3, &s->z) < CP_R(0.0) ? CP_R(-1.0) : CP_R(1.0)) / best;
    axis3->x *= cs;
    axis3->y *= cs;
    axis3->z *= cs;
    centroid->x = s->c.x + mom[0];
    centroid->y = s->c.y + mom[1];
    centroid->z = s->c.z + mom[2];
    *len = tot;
    return CP_OK;
}


/* ---------------------------------------------------------------------------------------
 * Iterator. Coordinate 0 is u in [lo, hi] = [0, N-1], 1 is w in [u0, u1]. Point k of the
 * raster (steps, link): block j = k / (steps + 1 + link) holds line/ring j (steps + 1
 * points, zigzag) then the link after it (link points). The "along" coordinate (LINES: u,
 * CIRCLES: w) runs over its range on a line/ring; the "across" one steps from line to line
 * and, on a link, moves evenly from line j to line j + 1 where line j ends. Fractions
 * num/den of a range (exact for the integer u spans: (hi - lo) num is an integer, one
 * rounding in the division). */
static CP_NOINLINE cp_real frac(const struct channel_path *cp, unsigned c, uint32_t num, uint32_t den)
{
    return den == 0u ? cp->lo[c] : cp->lo[c] + (cp->hi[c] - cp->lo[c]) * (cp_real)num / (cp_real)den;
}

/* Point k: output position and normal, t, line (-1: a link point), index in pt; surface
 * point s; through the row cache (key: u). Checks the row and the point: CP_OK,
 * CP_ERR_FRAME_REF, CP_ERR_AREA_LAW, CP_ERR_NUMERIC (non-finite), CP_ERR_FOLD (g <= 0). */
static int at(struct channel_path *cp, uint32_t k, struct raster_pt *pt, struct cp_vec3 *s)
{
    cp_real x[2], g;
    struct raster_at ra;
    uint32_t den = cp->head.steps;
    unsigned al = cp->head.mode, ac = al ^ 1u; /* RASTER_LINES = 0: along u */
    raster_locate(k, cp->head.steps, cp->head.link, &ra);
    if (ra.a != 0u) { /* a link: where line/ring j ends, the exact end of the range */
        den = (uint32_t)cp->head.link + 1u;
        x[al] = (ra.j & 1u) ? cp->lo[al] : cp->hi[al];
    } else {
        x[al] = frac(cp, al, ra.i, den);
    }
    x[ac] = frac(cp, ac, ra.j * den + ra.a, ((uint32_t)cp->head.n - 1u) * den);
    pt->line = (int16_t)ra.line;
    pt->index = (uint16_t)ra.index;
    pt->t = x[0];
    if (cp->row.u != x[0]) {
        channel_row(&cp->ch, x[0], &cp->row);
    }
    channel_point(&cp->row, x[1], s, &pt->n, &g);
    /* ball centre inside the duct (0 with OUT_SURFACE) */
    pt->p.x = s->x - cp->tool_r * pt->n.x;
    pt->p.y = s->y - cp->tool_r * pt->n.y;
    pt->p.z = s->z - cp->tool_r * pt->n.z;
    if (cp->output == RASTER_OUT_TIP) {
        pt->p.z -= cp->tool_r;
    }
    if (cp->row.flags & CHANNEL_ROW_FRAME) {
        return CP_ERR_FRAME_REF;
    }
    if (cp->row.flags & CHANNEL_ROW_BAD_LAW) {
        return CP_ERR_AREA_LAW;
    }
    if (!cp_finite(pt->p.x + pt->p.y + pt->p.z + pt->n.x + pt->n.y + pt->n.z)) {
        return CP_ERR_NUMERIC;
    }
    return g > CP_R(0.0) ? CP_OK : CP_ERR_FOLD;
}

/* Set steps and link (<= 2 CP_MAX_LINK + 1); returns the points of the raster,
 * n (steps + 1) + (n - 1) link. */
static CP_NOINLINE uint32_t set_raster(struct channel_path *cp, uint32_t steps, uint32_t link)
{
    cp->head.steps = steps;
    cp->head.link = (uint16_t)link;
    return raster_count(cp->head.n, steps, link);
}

/* Walk the whole raster with seg[0] segments per line/ring and seg[1] per link, doubled
 * (steps = 2 seg[0], link = 2 seg[1] - 1: the emitted points are the even k, with exactly
 * the (u, w) the stream computes; every line/ring and link starts at an even k): every
 * point's checks (at), the tool-centre path against the surface path (no fold back);
 * sag[q] = max distance of an odd point from the chord of its two neighbours (the
 * emitted segment) over the segments of lines (q = 0) and links (q = 1). Counts Q < 2P
 * clamps. Work: the doubled raster's points. */
static CP_NOINLINE int walk(struct channel_path *cp, const uint32_t *seg, cp_real *sag)
{
    struct raster_pt pt;
    struct cp_vec3 sv, sp, op[2], dm, dc, cx;
    uint32_t k, cnt;
    unsigned kind = 0u;
    cnt = set_raster(cp, 2u * seg[0], 2u * seg[1] - 1u); /* steps up to 2 CP_MAX_STEPS: uint32_t */
    sag[0] = sag[1] = CP_R(0.0);
    for (k = 0; k < cnt; k++) {
        unsigned prev = kind;
        int err = at(cp, k, &pt, &sv);
        kind = pt.line < 0; /* a link point */
        if (err != CP_OK) {
            return err;
        }
        if ((cp->row.flags & CHANNEL_ROW_CLAMP) && cp->ch.clamps < 0xFFFFu) {
            cp->ch.clamps++;
        }
        if (k > 0u && cp->output != RASTER_OUT_SURFACE) {
            cp_v3_sub(&sv, &sp, &dm);                   /* surface step */
            cp_v3_sub(&pt.p, &op[(k - 1u) & 1u], &dc); /* output step */
            if (!(cp_v3_dot(&dm, &dc) > CP_R(0.0))) {
                return CP_ERR_TOOL;
            }
        }
        if (k >= 2u && (k & 1u) == 0u) {
            /* distance of the odd point (kind prev) from the chord line (not from the chord's
             * midpoint: |cos w|^(2/n) spaces the points very unevenly near the section axes,
             * which is no deviation from the chord) */
            cp_real d, lc;
            cp_v3_sub(&op[1], &op[0], &dm);
            cp_v3_sub(&pt.p, &op[0], &dc);
            cp_v3_cross(&dm, &dc, &cx);
            lc = cp_v3_norm(&dc);
            d = lc > CP_R(0.0) ? cp_v3_norm(&cx) / lc : cp_v3_norm(&dm);
            sag[prev] = d > sag[prev] ? d : sag[prev];
        }
        sp = sv;
        op[k & 1u] = pt.p;
    }
    return CP_OK;
}

/* The tolerance search (raster_fit): a pilot walk at 32 steps / 1 link segment, the estimate
 * from it aimed at SAG_MARGIN tol (up or down, at least 8 / 1), then verified with the
 * sagitta <= tol, each correction at least 1/8 larger, an estimate above the maximum
 * CP_ERR_TOL at once. */
static const struct raster_rule channel_rule = {.aim = SAG_MARGIN, .accept = CP_R(1.0),
                                                .start = 32u, .pilot = 1u, .grow_shift = 3u,
                                                .clamp = 0u};

/* channel_path_init, after channel_init: on a closed guide (the last centre on the first,
 * within RASTER_SEAM_GAP x the centres' extent) the section must close too, or the duct
 * steps at the seam: raster_seam_check (raster.h) of the semi-axes a, b and the exponent n
 * (each value, and its slope per mm of guide arc: d/du divided by |L'|) and of the
 * section's turn, the a axis's angle alpha in the frame (e1, e2) mod pi as the value
 * (a - b) sin(alpha_end - alpha_start): about how far the turned section's points move,
 * mm (0 for a = b, whose turn is no change). Length scale: the larger of the extent and
 * the largest semi-axis. Not compared: the slope of the turn, the guide's tangent (a
 * corner is the user's geometry). Returns CP_OK or CP_ERR_SEAM. */
static CP_NOINLINE int seam_check(const struct channel *ch)
{
    const struct channel_cfg *cfg = ch->cfg;
    struct channel_row r;
    struct cp_vec3 d;
    cp_real v[2][4], dv[2][3], len = CP_R(0.0), e = CP_R(0.0);
    unsigned i, q;
    int err = CP_OK;
    for (i = 1u; i < ch->ns; i++) {
        cp_v3_sub(&cfg->s[i].c, &cfg->s[0].c, &d);
        e = cp_v3_norm(&d);
        len = e > len ? e : len;
    }
    if (!(e <= RASTER_SEAM_GAP * len)) { /* e: the last centre's distance from the first */
        return CP_OK;                      /* open: its ends may differ */
    }
    for (i = 0; i < 2u; i++) { /* the start (u = 0) and the end (u = N - 1) */
        channel_row(ch, i ? (cp_real)(ch->ns - 1u) : CP_R(0.0), &r);
        v[i][0] = r.ab[0];
        v[i][1] = r.ab[1];
        v[i][2] = r.n;
        v[i][3] = r.alpha;
        dv[i][0] = r.ab[0] * r.dab[0] / r.sp;          /* da/ds = a (a'/a) / |L'| */
        dv[i][1] = r.ab[1] * r.dab[1] / r.sp;
        dv[i][2] = -r.dq * r.n / (r.q * r.sp);         /* n = 2/q: n' = -q' n / q */
        len = r.ab[0] > len ? r.ab[0] : len;
    }
    for (q = 0; q < 3u && err == CP_OK; q++) {
        err = raster_seam_check(v[0][q], dv[0][q], CP_R(0.0), v[1][q], dv[1][q], CP_R(0.0), len);
    }
    if (err == CP_OK) { /* the turn: a value only (the slopes 0) */
        cp_real sn, cs;
        cp_sincos(v[1][3] - v[0][3], &sn, &cs);
        e = (v[1][0] - v[1][1]) * sn;
        err = raster_seam_check(CP_R(0.0), CP_R(0.0), CP_R(0.0), e, CP_R(0.0), CP_R(0.0), len);
    }
    return err;
}

/* raster_overlap_check's ball at u in [0, 1]: the guide point L(u (N - 1)) and a radius
 * that holds the whole superellipse section there: with X = |x/a|^n, q = 2/n and a >= b,
 * x^2 + y^2 <= a^2 (X^q + (1 - X)^q) <= a^2 max(1, 2^(1 - q)) (X^q + (1 - X)^q is convex
 * for q >= 1, at most 1; concave for q < 1, at most 2^(1 - q) at X = 1/2); exact for a
 * circle (a = b, q = 1), loose by up to sqrt 2 for a flat section with a large n. */
static int ch_ball(const void *ctx, cp_real u, struct cp_vec3 *c, cp_real *r)
{
    const struct channel *ch = ctx;
    struct channel_row row;
    cp_real f = CP_R(1.0);
    channel_row(ch, u * (cp_real)(ch->ns - 1u), &row);
    if (row.q < CP_R(1.0)) { /* sqrt(2^(1 - q)) = e^((1 - q) ln 2 / 2) */
        f = cp_exp(CP_R(0.5) * (CP_R(1.0) - row.q) * CP_R(0.69314718055994530942));
    }
    *c = row.l;
    *r = row.ab[0] * f;
    return CP_OK; /* (a non-finite ball: raster_overlap_check's CP_ERR_NUMERIC) */
}

int channel_path_init(struct channel_path *cp, const struct channel_cfg *g,
                      const struct raster_cfg *rs)
{
    struct raster_fit fit;
    uint32_t seg[2], round;
    cp_real sag[2];
    int err;
    cp->head.count = 0u;
    cp->head.k = 0u;
    cp->head.overlap = 0u;
    err = raster_check(rs, CP_PI);
    if (err == CP_OK && rs->tool_r > CHANNEL_COORD_MAX) {
        err = CP_ERR_TOOL;
    }
    if (err == CP_OK) {
        err = channel_init(&cp->ch, g);
    }
    if (err == CP_OK) {
        err = seam_check(&cp->ch);
    }
    if (err != CP_OK) {
        return err;
    }
    cp->output = rs->output;
    cp->tool_r = rs->tool_r;
    cp->row.u = CP_R(-1.0);
    cp->lo[0] = CP_R(0.0);
    cp->hi[0] = (cp_real)(cp->ch.ns - 1u);
    /* the evaluation grid: whole rings (-pi..pi, CHANNEL_GRID_W samples) at CHANNEL_GRID_U
     * rows per segment, walked like a CIRCLES raster (fold, laws, frame, tool) */
    cp->head.mode = RASTER_CIRCLES;
    cp->head.n = (uint16_t)((cp->ch.ns - 1u) * CHANNEL_GRID_U + 1u);
    cp->lo[1] = -CP_PI;
    cp->hi[1] = CP_PI;
    seg[0] = CHANNEL_GRID_W / 2u;
    seg[1] = 1u;
    err = walk(cp, seg, sag);
    if (err != CP_OK) {
        return err;
    }
    cp->head.mode = rs->mode;
    cp->head.n = rs->n;
    cp->lo[1] = rs->u0;
    cp->hi[1] = rs->u1;
    /* segments per line (q = 0) and per link (q = 1): given, else for the tolerance by
     * channel_rule; lines 8..CP_MAX_STEPS, links 1..CP_MAX_LINK + 1 (tolerance 1 um when
     * tol = 0). Every try walks the doubled raster. */
    raster_fit_begin(&fit, rs, &channel_rule);
    err = RASTER_FIT_MORE;
    for (round = 0; round <= RASTER_FIT_ROUNDS && err == RASTER_FIT_MORE; round++) {
        err = walk(cp, fit.m, sag);
        if (err == CP_OK) {
            err = raster_fit_update(&fit, sag);
        }
    }
    if (err == CP_OK) { /* last: far parts of the duct that meet (reported: the tool inside) */
        err = raster_overlap_report(ch_ball, &cp->ch, &cp->head);
    }
    if (err != CP_OK) {
        return err;
    }
    cp->head.count = set_raster(cp, fit.m[0], fit.m[1] - 1u);
    return CP_OK;
}

uint32_t channel_path_count(const struct channel_path *cp)
{
    return cp->head.count;
}

int channel_path_seek(struct channel_path *cp, uint32_t k)
{
    return raster_seek(&cp->head, k);
}

int channel_path_next(struct channel_path *cp, struct raster_pt *pt)
{
    struct cp_vec3 s;
    int err;
    if (cp->head.k >= cp->head.count) {
        return CP_ERR_DONE;
    }
    err = at(cp, cp->head.k, pt, &s);
    if (err == CP_OK) {
        cp->head.k++;
    }
    return err;
}

#if CP_REAL_DOUBLE
CP_STATIC_ASSERT(sizeof(struct channel_path) <= 800u, channel_path_fits_budget);
CP_STATIC_ASSERT(sizeof(struct channel_cfg) <= 640u, channel_cfg_fits_budget);
#else
CP_STATIC_ASSERT(sizeof(struct channel_path) <= 400u, channel_path_fits_budget);
CP_STATIC_ASSERT(sizeof(struct channel_cfg) <= 320u, channel_cfg_fits_budget);
#endif
