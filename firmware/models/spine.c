/* spine.c - SPINE kernel: jets, init checks, the fixed-step march (RMF by double reflection,
 * transport M by Magnus-4 in increment form) and the points. See spine.h and
 * docs/MATH-spine.md sections 2-5 and 9.
 * SPDX-License-Identifier: MIT
 */
#include <string.h>

#include "spine.h"
#include "cp_math.h"

#if !CP_REAL_DOUBLE /* the M4F context budget (the double host build is about twice) */
CP_STATIC_ASSERT(sizeof(struct spine) <= 320u, spine_ctx_320);
#endif

static const uint8_t sp_nsp[4] = {6u, 11u, 12u, 12u}; /* used sp[] per kind */
static const uint8_t sp_nrp[4] = {1u, 2u, 3u, 4u};    /* used rp[] per law */

/* ---------------------------------------------------------------------- jets */

static void sp_law(const struct spine *s, cp_real u, struct spine_jet *j)
{
    const cp_real *k = s->rp;
    switch (s->law) {
    case SPINE_R_CONST:
        j->r = k[0];
        j->ru = CP_R(0.0);
        j->ruu = CP_R(0.0);
        break;
    case SPINE_R_LINEAR:
        j->r = k[0] + (k[1] - k[0]) * u;
        j->ru = k[1] - k[0];
        j->ruu = CP_R(0.0);
        break;
    case SPINE_R_COS: {
        cp_real w = CP_TWO_PI * k[2], sn, cs;
        cp_sincos(w * u, &sn, &cs);
        j->r = k[0] * cs + k[1];
        j->ru = -k[0] * w * sn;
        j->ruu = -k[0] * w * w * cs;
        break;
    }
    default: { /* SPINE_R_CUBIC, Bernstein */
        cp_real v = CP_R(1.0) - u;
        j->r = k[0] * v * v * v + CP_R(3.0) * k[1] * v * v * u + CP_R(3.0) * k[2] * v * u * u +
               k[3] * u * u * u;
        j->ru = CP_R(3.0) * ((k[1] - k[0]) * v * v + CP_R(2.0) * (k[2] - k[1]) * v * u +
                             (k[3] - k[2]) * u * u);
        j->ruu = CP_R(6.0) * ((k[2] - CP_R(2.0) * k[1] + k[0]) * v +
                              (k[3] - CP_R(2.0) * k[2] + k[1]) * u);
        break;
    }
    }
}

/* ARC and HELIX: r (cos p e1 + sin p e2), p = w u, and its u-derivatives */
static void sp_circle(const struct spine *s, cp_real r, cp_real w, cp_real u, struct spine_jet *j)
{
    cp_real sn, cs;
    struct cp_vec3 rad, tg;
    cp_sincos(w * u, &sn, &cs);
    cp_v3_comb(&rad, cs, &s->e1, sn, &s->e2);
    cp_v3_comb(&tg, -sn, &s->e1, cs, &s->e2);
    cp_v3_comb(&j->c, r, &rad, CP_R(0.0), &rad);
    cp_v3_comb(&j->cu, r * w, &tg, CP_R(0.0), &tg);
    cp_v3_comb(&j->cuu, -r * w * w, &rad, CP_R(0.0), &rad);
}

static void sp_add(struct cp_vec3 *o, const cp_real *p, cp_real q)
{
    o->x += q * p[0];
    o->y += q * p[1];
    o->z += q * p[2];
}

static void sp_bezier(const cp_real *p, cp_real u, struct spine_jet *j)
{
    cp_real v = CP_R(1.0) - u, w[4], d[3], e[2];
    int k;
    w[0] = v * v * v;
    w[1] = CP_R(3.0) * v * v * u;
    w[2] = CP_R(3.0) * v * u * u;
    w[3] = u * u * u;
    d[0] = CP_R(3.0) * v * v;
    d[1] = CP_R(6.0) * v * u;
    d[2] = CP_R(3.0) * u * u;
    e[0] = CP_R(6.0) * v;
    e[1] = CP_R(6.0) * u;
    j->c.x = j->c.y = j->c.z = CP_R(0.0);
    j->cu = j->c;
    j->cuu = j->c;
    for (k = 0; k < 4; k++) {
        sp_add(&j->c, p + 3 * k, w[k]);
    }
    for (k = 0; k < 3; k++) { /* differences P_{k+1} - P_k, each exact to one rounding */
        struct cp_vec3 q;
        q.x = p[3 * k + 3] - p[3 * k];
        q.y = p[3 * k + 4] - p[3 * k + 1];
        q.z = p[3 * k + 5] - p[3 * k + 2];
        sp_add(&j->cu, &q.x, d[k]);
        if (k < 2) {
            struct cp_vec3 q2;
            q2.x = p[3 * k + 6] - CP_R(2.0) * p[3 * k + 3] + p[3 * k];
            q2.y = p[3 * k + 7] - CP_R(2.0) * p[3 * k + 4] + p[3 * k + 1];
            q2.z = p[3 * k + 8] - CP_R(2.0) * p[3 * k + 5] + p[3 * k + 2];
            sp_add(&j->cuu, &q2.x, e[k]);
        }
    }
}

void spine_jet(const struct spine *s, cp_real u, struct spine_jet *j)
{
    const cp_real *p = s->sp;
    switch (s->kind) {
    case SPINE_LINE:
        j->cu.x = p[3] - p[0];
        j->cu.y = p[4] - p[1];
        j->cu.z = p[5] - p[2];
        j->c.x = p[0] + u * j->cu.x;
        j->c.y = p[1] + u * j->cu.y;
        j->c.z = p[2] + u * j->cu.z;
        j->cuu.x = j->cuu.y = j->cuu.z = CP_R(0.0);
        break;
    case SPINE_ARC:
        sp_circle(s, p[6], p[10], u, j);
        sp_add(&j->c, p, CP_R(1.0));
        break;
    case SPINE_HELIX: {
        cp_real w = CP_TWO_PI * p[8], rise = p[7] * p[8]; /* dz/du = pitch turns */
        sp_circle(s, p[6], w, u, j);
        sp_add(&j->c, p, CP_R(1.0));
        sp_add(&j->c, &s->ax.x, rise * u);
        sp_add(&j->cu, &s->ax.x, rise);
        break;
    }
    default:
        sp_bezier(p, u, j);
        break;
    }
    sp_law(s, u, j);
}

/* ---------------------------------------------------------------------- init */

/* ARC/HELIX: unit axis from sp[3..5], e1 from the start direction sp[dx..dx+2] */
static int sp_basis(struct spine *s, int dx)
{
    struct cp_vec3 d;
    cp_real l, dl, dn;
    s->ax.x = s->sp[3];
    s->ax.y = s->sp[4];
    s->ax.z = s->sp[5];
    if (!(s->sp[6] > CP_R(0.0))) {
        return CP_ERR_RANGE;
    }
    l = cp_v3_norm(&s->ax);
    if (!(l > CP_R(0.0))) {
        return CP_ERR_DEGENERATE;
    }
    (void)cp_v3_unit(&s->ax);
    d.x = s->sp[dx];
    d.y = s->sp[dx + 1];
    d.z = s->sp[dx + 2];
    dl = cp_v3_norm(&d);
    dn = cp_v3_dot(&d, &s->ax);
    cp_v3_comb(&s->e1, CP_R(1.0), &d, -dn, &s->ax);
    if (!(cp_v3_norm(&s->e1) > CP_R(1e-4) * dl)) {
        return CP_ERR_DEGENERATE;
    }
    (void)cp_v3_unit(&s->e1);
    cp_v3_cross(&s->ax, &s->e1, &s->e2);
    return CP_OK;
}

/* copy and range-check the parameters; the kind's own checks */
static int sp_params(struct spine *s, const struct spine_cfg *cfg)
{
    int i, nsp = sp_nsp[cfg->kind], nrp = sp_nrp[cfg->law];
    for (i = 0; i < 12; i++) {
        s->sp[i] = i < nsp ? cfg->sp[i] : CP_R(0.0);
    }
    for (i = 0; i < 4; i++) {
        s->rp[i] = i < nrp ? cfg->rp[i] : CP_R(0.0);
    }
    for (i = 0; i < 12; i++) {
        if (!cp_finite(s->sp[i]) || (i < 4 && !cp_finite(s->rp[i])) ||
            (i < 3 && !cp_finite(cfg->ref[i]))) {
            return CP_ERR_NONFINITE;
        }
    }
    for (i = 0; i < 12; i++) {
        cp_real lim = (cfg->law == SPINE_R_COS && i == 2) ? SPINE_K_MAX : SPINE_COORD_MAX;
        if (cp_fabs(s->sp[i]) > SPINE_COORD_MAX || (i < 4 && cp_fabs(s->rp[i]) > lim)) {
            return CP_ERR_RANGE;
        }
    }
    if (cfg->kind == SPINE_ARC) {
        if (s->sp[10] == CP_R(0.0)) {
            return CP_ERR_EMPTY;
        }
        if (cp_fabs(s->sp[10]) > CP_TWO_PI) {
            return CP_ERR_RANGE;
        }
        return sp_basis(s, 7);
    }
    if (cfg->kind == SPINE_HELIX) {
        if (!(s->sp[8] > CP_R(0.0)) || s->sp[8] > SPINE_TURNS_MAX) {
            return CP_ERR_RANGE;
        }
        return sp_basis(s, 9);
    }
    return CP_OK;
}

/* |c_u| > 0, R > 0 and |a| < 1 on the half nodes and on u = k / SPINE_CHECK_N */
static int sp_samples(struct spine *s)
{
    uint32_t k, nh = 2u * s->nsteps, nall = nh + 1u + SPINE_CHECK_N + 1u;
    cp_real scale = CP_R(1.0), amax = CP_R(0.0), rmin = CP_R(1e30), rmax = CP_R(0.0);
    int i, bad_r = 0, bad_a = 0;
    for (i = 0; i < 12; i++) {
        cp_real q = cp_fabs(s->sp[i]);
        scale = q > scale ? q : scale;
    }
    for (k = 0; k < nall; k++) {
        struct spine_jet j;
        cp_real v, a;
        int half = k <= nh;
        cp_real u = half ? (cp_real)k / (cp_real)nh : (cp_real)(k - nh - 1u) / (cp_real)SPINE_CHECK_N;
        spine_jet(s, u, &j);
        v = cp_v3_norm(&j.cu);
        if (!(v > CP_R(1e-5) * (CP_R(1.0) + scale))) {
            return CP_ERR_DEGENERATE;
        }
        a = cp_fabs(j.ru) / v;
        bad_r |= !(j.r > CP_R(0.0));
        bad_a |= !(a < CP_R(1.0));
        amax = a > amax ? a : amax;
        rmin = j.r < rmin ? j.r : rmin;
        rmax = j.r > rmax ? j.r : rmax;
    }
    s->amax = amax;
    s->rmin = rmin;
    s->rmax = rmax;
    return bad_r ? CP_ERR_RADIUS : (bad_a ? CP_ERR_RANGE : CP_OK);
}

/* A~ at a node with jet j, unit tangent t and the carried RMF vector r (projected here):
 * out = (f c_uu.N1, f c_uu.N2), f = R_u / (2 v sqrt(v^2 - R_u^2)). Relative rounding of f a few
 * ulp; sqrt(v^2 - R_u^2) = v b loses digits only as b -> 0 (|a| -> 1, refused at init). */
static void sp_atilde(const struct spine_jet *j, const struct cp_vec3 *t, const struct cp_vec3 *r,
                      cp_real out[2])
{
    struct cp_vec3 n1, n2;
    cp_real v = cp_v3_norm(&j->cu), f;
    cp_v3_comb(&n1, CP_R(1.0), r, -cp_v3_dot(r, t), t);
    (void)cp_v3_unit(&n1);
    cp_v3_cross(t, &n1, &n2);
    f = j->ru / (CP_R(2.0) * v * cp_sqrt((v - j->ru) * (v + j->ru)));
    out[0] = f * cp_v3_dot(&j->cuu, &n1);
    out[1] = f * cp_v3_dot(&j->cuu, &n2);
}

/* the march at node 0: x, t, r = N1(0), M = I, A~(0) */
static void sp_restart(struct spine *s)
{
    struct spine_jet j;
    spine_jet(s, CP_R(0.0), &j);
    s->x = j.c;
    s->t = j.cu;
    (void)cp_v3_unit(&s->t);
    s->r = s->n10;
    s->m[0] = CP_R(1.0);
    s->m[1] = CP_R(0.0);
    s->m[2] = CP_R(0.0);
    s->m[3] = CP_R(1.0);
    sp_atilde(&j, &s->t, &s->r, s->a0);
    s->j = j;
    s->node = 0u;
    s->back = 0u;
}

/* N1(0) from ref (non-zero) or the principal normal */
static int sp_frame0(struct spine *s, const cp_real ref[3])
{
    struct spine_jet j;
    struct cp_vec3 t, w;
    cp_real l, d;
    spine_jet(s, CP_R(0.0), &j);
    t = j.cu;
    (void)cp_v3_unit(&t);
    w.x = ref[0];
    w.y = ref[1];
    w.z = ref[2];
    l = cp_v3_norm(&w);
    if (l > CP_R(0.0)) {
        d = cp_v3_dot(&w, &t);
        cp_v3_comb(&s->n10, CP_R(1.0), &w, -d, &t);
        if (!(cp_v3_norm(&s->n10) > CP_R(1e-4) * l)) {
            return CP_ERR_FRAME_REF;
        }
    } else {
        d = cp_v3_dot(&j.cuu, &t);
        cp_v3_comb(&s->n10, CP_R(1.0), &j.cuu, -d, &t);
        if (!(cp_v3_norm(&s->n10) > CP_R(1e-4) * cp_v3_dot(&j.cu, &j.cu))) {
            return CP_ERR_FRENET;
        }
    }
    (void)cp_v3_unit(&s->n10);
    return CP_OK;
}

int spine_init(struct spine *s, const struct spine_cfg *cfg, uint16_t nsteps)
{
    int e;
    if (s == NULL || cfg == NULL || cfg->kind > SPINE_BEZIER || cfg->law > SPINE_R_CUBIC) {
        return CP_ERR_INVAL;
    }
    s->kind = cfg->kind;
    s->law = cfg->law;
    e = sp_params(s, cfg);
    if (e == CP_ERR_NONFINITE) {
        return e;
    }
    if (nsteps > SPINE_NSTEPS_MAX) {
        return CP_ERR_TOO_MANY;
    }
    if (nsteps == 0u) {
        return CP_ERR_RANGE;
    }
    if (e != CP_OK) {
        return e;
    }
    s->nsteps = nsteps;
    e = sp_samples(s);
    if (e != CP_OK) {
        return e;
    }
    e = sp_frame0(s, cfg->ref);
    if (e != CP_OK) {
        return e;
    }
    sp_restart(s);
    return CP_OK;
}

/* ---------------------------------------------------------------------- march */

/* One double reflection (MATH-spine 9.1) of r from (x0, t0) to (x1, t1). Exact on planar and
 * straight spines; local error -(h^5/720)(k^2 t^3 + k k' t' + 2 k'^2 t - k k'' t) in the angle
 * (h the step in arc length), order 4 globally. Rounding: each reflection is orthogonal up to
 * a few ulp, so |r| and r.T drift like sqrt(K) eps over K steps (~1e-6 at K = 2048 in
 * float); r is re-projected and normalized at every use (sp_atilde, spine_node), never in the
 * state, which keeps the step exactly invertible in exact arithmetic. */
static void sp_reflect(const struct cp_vec3 *x0, const struct cp_vec3 *t0, const struct cp_vec3 *x1,
                       const struct cp_vec3 *t1, struct cp_vec3 *r)
{
    struct cp_vec3 v1, rl, tl, v2;
    cp_real c1, c2;
    cp_v3_sub(x1, x0, &v1);
    c1 = cp_v3_dot(&v1, &v1);
    if (c1 > CP_R(0.0)) {
        cp_v3_comb(&rl, CP_R(1.0), r, -(CP_R(2.0) / c1) * cp_v3_dot(&v1, r), &v1);
        cp_v3_comb(&tl, CP_R(1.0), t0, -(CP_R(2.0) / c1) * cp_v3_dot(&v1, t0), &v1);
    } else {
        rl = *r;
        tl = *t0;
    }
    cp_v3_sub(t1, &tl, &v2);
    c2 = cp_v3_dot(&v2, &v2);
    if (c2 > CP_R(0.0)) {
        cp_v3_comb(r, CP_R(1.0), &rl, -(CP_R(2.0) / c2) * cp_v3_dot(&v2, &rl), &v2);
    } else {
        *r = rl;
    }
}

/* One Magnus-4 step (MATH-spine 9.2) on the Simpson nodes, Ã given as (p, q) for
 * [[-p, q], [q, p]]:
 *   Omega = (h/6)(A0 + 4 Ah + A1) - (h^2/12)[Ah, A1 - A0]
 * The commutator of two such matrices X, Y is [[0, 2w], [-2w, 0]], w = x2 y1 - x1 y2, so
 * Omega = [[-s1, s2 + c], [s2 - c, s1]], c = -(h^2/6) w, and Omega^2 = d2 I with
 * d2 = s1^2 + s2^2 - c^2. exp(Omega) = C I + S Omega with C - 1 = d2 (1/2 + d2 (1/24 +
 * d2/720)), S = 1 + d2 (1/6 + d2 (1/120 + d2/5040)): truncation <= d2^4/8! relative, below
 * float and double rounding for |d2| <= 0.05 (d2 ~ (Gamma/N)^2; 3e-3 at N = 16 on the helix).
 * Local error ~ h^5 A~''''/2880 (Simpson on Omega1), order 4 globally.
 * Increment form M += (C - 1) M + S Omega M: the O(1) part of exp(Omega) is never rounded,
 * so a constant generator does not accumulate a one-sided rounding (MATH-spine 9.2 table:
 * 8e-6 mm instead of 2e-4 mm at N = 512 in float). det exp(Omega) = 1 exactly. */
static void sp_magnus(cp_real m[4], const cp_real a0[2], const cp_real ah[2], const cp_real a1[2],
                      cp_real h)
{
    cp_real s1 = h / CP_R(6.0) * (a0[0] + CP_R(4.0) * ah[0] + a1[0]);
    cp_real s2 = h / CP_R(6.0) * (a0[1] + CP_R(4.0) * ah[1] + a1[1]);
    cp_real w = ah[1] * (a1[0] - a0[0]) - ah[0] * (a1[1] - a0[1]);
    cp_real c = -(h * h / CP_R(6.0)) * w;
    cp_real o11 = -s1, o12 = s2 + c, o21 = s2 - c, o22 = s1;
    cp_real d2 = s1 * s1 + s2 * s2 - c * c;
    cp_real cm1 = d2 * (CP_R(0.5) + d2 * (CP_R(1.0) / CP_R(24.0) + d2 / CP_R(720.0)));
    cp_real sh = CP_R(1.0) + d2 * (CP_R(1.0) / CP_R(6.0) + d2 * (CP_R(1.0) / CP_R(120.0) +
                                                                 d2 / CP_R(5040.0)));
    cp_real p0 = o11 * m[0] + o12 * m[2], p1 = o11 * m[1] + o12 * m[3];
    cp_real p2 = o21 * m[0] + o22 * m[2], p3 = o21 * m[1] + o22 * m[3];
    cp_real d0 = cm1 * m[0] + sh * p0, d1 = cm1 * m[1] + sh * p1;
    cp_real dd2 = cm1 * m[2] + sh * p2, d3 = cm1 * m[3] + sh * p3;
    m[0] += d0;
    m[1] += d1;
    m[2] += dd2;
    m[3] += d3;
}

/* One march step from node i to i + dir (dir = +1 forward, -1 back): two double reflections
 * (to the half node and the node), one Magnus step over [u_i, u_i + dir h].
 * Backward (dir = -1) is the forward step run in reverse: double reflection is its own
 * inverse in exact arithmetic (the reflection in x_{i-1} - x_i is the first one again; the
 * second reflects in R1 v2, the image of the forward step's v2), and the Magnus step with
 * the Simpson nodes reversed and -h is exactly -Omega (s1, s2 and the commutator term all
 * change sign), whose exponential is the inverse of the forward step's. So a backward pass
 * makes the same truncation error as the forward march, node by node; only the rounding
 * differs (a few ulp per step, ~sqrt(K) eps over K steps: ~1e-6 relative in float at
 * K = 2048). The jets' u are k / (2N) with integer k: 0 and 1 exactly at the ends. */
static void sp_step(struct spine *s, int dir)
{
    struct spine_jet j;
    struct cp_vec3 xh, th;
    cp_real ah[2], a1[2];
    cp_real n2 = (cp_real)(2u * s->nsteps), h = CP_R(1.0) / (cp_real)s->nsteps;
    uint32_t k = dir > 0 ? 2u * s->node + 1u : 2u * s->node - 1u; /* the half node */
    uint32_t k1 = dir > 0 ? k + 1u : k - 1u;                          /* the next node */
    spine_jet(s, (cp_real)k / n2, &j);
    xh = j.c;
    th = j.cu;
    (void)cp_v3_unit(&th);
    sp_reflect(&s->x, &s->t, &xh, &th, &s->r);
    sp_atilde(&j, &th, &s->r, ah);
    spine_jet(s, (cp_real)k1 / n2, &j);
    s->x = j.c;
    s->t = j.cu;
    (void)cp_v3_unit(&s->t);
    sp_reflect(&xh, &th, &s->x, &s->t, &s->r);
    sp_atilde(&j, &s->t, &s->r, a1);
    sp_magnus(s->m, s->a0, ah, a1, dir > 0 ? h : -h);
    s->a0[0] = a1[0];
    s->a0[1] = a1[1];
    s->j = j;
    s->node = (uint16_t)(k1 / 2u);
    s->back = dir < 0 ? 1u : 0u;
}

/* o = k a */
static void sp_scale(struct cp_vec3 *o, cp_real k, const struct cp_vec3 *a)
{
    o->x = k * a->x;
    o->y = k * a->y;
    o->z = k * a->z;
}

/* the per-node quantities of MATH-spine 1 from the jet and the march */
static void sp_fill(const struct spine *s, struct spine_state *st)
{
    const struct spine_jet *j = &s->j; /* the jet at u = node / N */
    cp_real v, vv, a;
    st->node = s->node;
    st->u = (cp_real)s->node / (cp_real)s->nsteps;
    st->c = j->c;
    st->t = s->t;
    cp_v3_comb(&st->n1, CP_R(1.0), &s->r, -cp_v3_dot(&s->r, &s->t), &s->t);
    (void)cp_v3_unit(&st->n1);
    cp_v3_cross(&st->t, &st->n1, &st->n2);
    v = cp_v3_norm(&j->cu);
    vv = v * v;
    a = j->ru / v;
    st->r = j->r;
    st->a = a;
    st->b = cp_sqrt((CP_R(1.0) - a) * (CP_R(1.0) + a));
    st->as = (j->ruu - a * cp_v3_dot(&j->cu, &j->cuu) / v) / vv;
    st->k1 = cp_v3_dot(&j->cuu, &st->n1) / vv;
    st->k2 = cp_v3_dot(&j->cuu, &st->n2) / vv;
    st->m[0] = s->m[0];
    st->m[1] = s->m[1];
    st->m[2] = s->m[2];
    st->m[3] = s->m[3];
    sp_scale(&st->at, -a, &st->t);
    sp_scale(&st->bn1, st->b, &st->n1);
    sp_scale(&st->bn2, st->b, &st->n2);
}

/* fill st from the march; CP_ERR_NUMERIC if a non-finite value appeared */
static int sp_filled(const struct spine *s, struct spine_state *st)
{
    sp_fill(s, st);
    if (!cp_finite(st->m[0] + st->m[1] + st->m[2] + st->m[3]) ||
        !cp_finite(st->n1.x + st->n1.y + st->n1.z)) {
        return CP_ERR_NUMERIC;
    }
    return CP_OK;
}

int spine_node(struct spine *s, uint16_t i, struct spine_state *st)
{
    uint32_t k, n;
    if (s == NULL || st == NULL || i > s->nsteps) {
        return CP_ERR_RANGE;
    }
    if (s->back || i < s->node) {
        sp_restart(s);
    }
    n = (uint32_t)i - s->node;
    for (k = 0; k < n; k++) {
        sp_step(s, 1);
    }
    return sp_filled(s, st);
}

int spine_node_back(struct spine *s, uint16_t i, struct spine_state *st)
{
    uint32_t k, n;
    if (s == NULL || st == NULL || i > s->nsteps) {
        return CP_ERR_RANGE;
    }
    if (s->back && i > s->node) {
        sp_restart(s);
    }
    if (!s->back) {
        n = (uint32_t)s->nsteps - s->node; /* the forward march on to node N */
        for (k = 0; k < n; k++) {
            sp_step(s, 1);
        }
    }
    n = (uint32_t)s->node - i;
    for (k = 0; k < n; k++) {
        sp_step(s, -1);
    }
    return sp_filled(s, st);
}

/* ---------------------------------------------------------------------- points */

void spine_label(cp_real theta0, struct spine_label *lab)
{
    cp_sincos(CP_R(0.5) * theta0, &lab->y1, &lab->y2);
}

/* y = M y0; cos theta = (y2^2 - y1^2)/|y|^2, sin theta = 2 y1 y2/|y|^2 (MATH-spine 5.2): no
 * pole (|y| >= |y0| / ||M^-1|| > 0), each a few ulp; |(ct, sn)| = 1 to a few ulp. */
void spine_angle(const struct spine_state *st, const struct spine_label *lab, cp_real *ct,
                 cp_real *sn)
{
    cp_real y1 = st->m[0] * lab->y1 + st->m[1] * lab->y2;
    cp_real y2 = st->m[2] * lab->y1 + st->m[3] * lab->y2;
    cp_real q = CP_R(1.0) / (y1 * y1 + y2 * y2);
    *ct = (y2 * y2 - y1 * y1) * q;
    *sn = CP_R(2.0) * y1 * y2 * q;
}

/* m = c + (R + off)(-a T + b (ct N1 + sn N2)) */
static void sp_surface(const struct spine_state *st, cp_real ct, cp_real sn, cp_real off,
                       struct raster_pt *pt)
{
    cp_real rr = st->r + off;
    pt->n.x = st->at.x + ct * st->bn1.x + sn * st->bn2.x;
    pt->n.y = st->at.y + ct * st->bn1.y + sn * st->bn2.y;
    pt->n.z = st->at.z + ct * st->bn1.z + sn * st->bn2.z;
    pt->p.x = st->c.x + rr * pt->n.x;
    pt->p.y = st->c.y + rr * pt->n.y;
    pt->p.z = st->c.z + rr * pt->n.z;
    pt->t = st->u;
}

void spine_point_label(const struct spine_state *st, const struct spine_label *lab, cp_real off,
                       struct raster_pt *pt)
{
    cp_real ct, sn;
    spine_angle(st, lab, &ct, &sn);
    sp_surface(st, ct, sn, off, pt);
}

void spine_point(const struct spine_state *st, cp_real theta0, cp_real off, struct raster_pt *pt)
{
    struct spine_label lab;
    spine_label(theta0, &lab);
    spine_point_label(st, &lab, off, pt);
}

void spine_circle_point(const struct spine_state *st, cp_real theta, cp_real off,
                        struct raster_pt *pt)
{
    cp_real ct, sn;
    cp_sincos(theta, &sn, &ct);
    sp_surface(st, ct, sn, off, pt);
}

cp_real spine_regularity(const struct spine_state *st, cp_real ct, cp_real sn, cp_real off)
{
    cp_real g = st->as + st->b * (st->k1 * ct + st->k2 * sn);
    return st->b * st->b - (st->r + off) * g;
}

/* ---------------------------------------------------------------------- iterator */

/* The label theta0 of label index l (0..nl). */
static cp_real sp_lab(const struct spine_path *it, uint32_t l)
{
    if (it->nl == 0u) {
        return it->u0;
    }
    return it->u0 + (it->u1 - it->u0) * ((cp_real)l / (cp_real)it->nl);
}

/* Point k as (march node, label index); line and index for raster_pt. The pass of a point
 * (*back): the odd lines of LINES and their links are on the backward pass. */
static void sp_where(const struct spine_path *it, uint32_t k, uint32_t *node, uint32_t *l,
                     uint8_t *back, struct raster_at *at)
{
    uint32_t lk = (uint32_t)it->head.link + 1u;
    raster_locate(k, it->head.steps, it->head.link, at);
    if (it->head.mode == RASTER_LINES) {
        *node = at->i * it->q;
        *l = at->j * lk + at->a;
        *back = (uint8_t)(at->j & 1u);
    } else {
        *node = (at->j * lk + at->a) * it->q;
        *l = at->i;
        *back = 0u;
    }
}

/* The emitted point at (node, label l) on the forward or backward pass. */
static int sp_emit(struct spine_path *it, uint32_t node, uint32_t l, uint8_t back,
                   struct raster_pt *pt)
{
    struct spine_state st;
    cp_real r = it->tool_r;
    int err = back ? spine_node_back(&it->s, (uint16_t)node, &st)
                   : spine_node(&it->s, (uint16_t)node, &st);
    if (err != CP_OK) {
        return err;
    }
    if (l != it->lab_l) { /* the label is a function of l alone: caching keeps seeks exact */
        spine_label(sp_lab(it, l), &it->lab);
        it->lab_l = l;
    }
    spine_point_label(&st, &it->lab, CP_R(0.0), pt);
    cp_v3_comb(&pt->p, CP_R(1.0), &pt->p, -r, &pt->n);
    if (it->output == RASTER_OUT_TIP) {
        pt->p.z -= r;
    }
    return cp_finite(pt->p.x + pt->p.y + pt->p.z) ? CP_OK : CP_ERR_NUMERIC;
}

/* D > 0 at every node and label of the patch, on the surface and the tool-centre surface. */
static CP_NOINLINE int sp_check_patch(struct spine_path *it)
{
    uint32_t i, l;
    for (i = 0; i <= it->s.nsteps; i++) {
        struct spine_state st;
        int err = spine_node(&it->s, (uint16_t)i, &st);
        if (err != CP_OK) {
            return err;
        }
        for (l = 0; l <= it->nl; l++) {
            struct spine_label lab;
            cp_real ct, sn, d0, d1;
            spine_label(sp_lab(it, l), &lab);
            spine_angle(&st, &lab, &ct, &sn);
            d0 = spine_regularity(&st, ct, sn, CP_R(0.0));
            d1 = spine_regularity(&st, ct, sn, -it->tool_r);
            if (!cp_finite(d0 + d1)) {
                return CP_ERR_NUMERIC;
            }
            if (!(d0 > CP_R(0.0)) || !(d1 > CP_R(0.0))) {
                return CP_ERR_CUSP;
            }
        }
    }
    return CP_OK;
}

/* The on-circle sagitta of the link segments from line j to j + 1 with m segments at the
 * end node of st (mm): the emitted points lie on a circle of radius rho = (R - r) b, and a
 * chord whose ends differ by d in (cos theta, sin theta) has the sagitta
 * rho (1 - sqrt(1 - d^2/4)). */
static cp_real sp_link_sag(const struct spine_path *it, const struct spine_state *st, uint32_t j,
                           uint32_t m, cp_real dl)
{
    cp_real rho = (st->r - it->tool_r) * st->b, c0, s0, worst = CP_R(0.0);
    struct spine_label lab;
    uint32_t a;
    spine_label(it->u0 + (cp_real)j * dl, &lab);
    spine_angle(st, &lab, &c0, &s0);
    for (a = 1u; a <= m; a++) {
        cp_real c1, s1, d2, sg;
        spine_label(it->u0 + ((cp_real)j + (cp_real)a / (cp_real)m) * dl, &lab);
        spine_angle(st, &lab, &c1, &s1);
        d2 = (c1 - c0) * (c1 - c0) + (s1 - s0) * (s1 - s0);
        d2 = CP_R(1.0) - CP_R(0.25) * d2;
        sg = rho * (CP_R(1.0) - cp_sqrt(d2 > CP_R(0.0) ? d2 : CP_R(0.0)));
        worst = sg > worst ? sg : worst;
        c0 = c1;
        s0 = s1;
    }
    return worst;
}

/* LINES with RASTER_LINK_AUTO: the least link + 1 = m (from the m = 1 estimate m ~
 * sqrt(sag / tol), then by ones) whose on-circle sagitta is <= tol on every link; CP_ERR_TOL
 * above CP_MAX_LINK + 1. The link of line j runs on the circle at u = 1 (even j) or 0. */
static CP_NOINLINE int sp_link_fit(struct spine_path *it, cp_real tol, uint32_t *link)
{
    struct spine_state st[2];
    cp_real dl = (it->u1 - it->u0) / (cp_real)(it->head.n - 1u), s1 = CP_R(0.0), e;
    uint32_t j, m;
    int err = spine_node(&it->s, 0u, &st[1]);
    if (err == CP_OK) {
        err = spine_node(&it->s, it->s.nsteps, &st[0]);
    }
    if (err != CP_OK) {
        return err;
    }
    for (j = 0; j + 1u < it->head.n; j++) {
        e = sp_link_sag(it, &st[j & 1u], j, 1u, dl);
        s1 = e > s1 ? e : s1;
    }
    e = cp_sqrt(s1 / tol);
    m = e < CP_R(1.0) ? 1u : e > CP_R(70.0) ? 70u : (uint32_t)e;
    for (; m <= (uint32_t)CP_MAX_LINK + 1u; m++) {
        cp_real w = CP_R(0.0);
        for (j = 0; j + 1u < it->head.n && w <= tol; j++) {
            e = sp_link_sag(it, &st[j & 1u], j, m, dl);
            w = e > w ? e : w;
        }
        if (w <= tol) {
            *link = m - 1u;
            return CP_OK;
        }
    }
    return CP_ERR_TOL;
}

/* The march for `steps` points per line (LINES) or circle (CIRCLES) and `link`: N = q span,
 * spine_init at that N, the tool against its least R. Sets head.steps and q. */
static int sp_setup(struct spine_path *it, const struct spine_cfg *cfg, uint32_t steps,
                    uint32_t link)
{
    uint32_t span, q;
    int err;
    span = it->head.mode == RASTER_LINES
               ? steps
               : (it->head.n > 1u ? (uint32_t)(it->head.n - 1u) : 1u) * (link + 1u);
    if (span > SPINE_NSTEPS_MAX) {
        return CP_ERR_TOO_MANY;
    }
    q = (SPINE_PATH_NMIN + span - 1u) / span;
    q = q * span > SPINE_NSTEPS_MAX ? SPINE_NSTEPS_MAX / span : q; /* >= 1 */
    if (it->head.mode == RASTER_CIRCLES) { /* even: the link segments' midpoints are nodes */
        q = (q + 1u) & ~1u;
        q = q * span > SPINE_NSTEPS_MAX ? q - 2u : q;
        if (q < 2u) {
            return CP_ERR_TOO_MANY;
        }
    }
    err = spine_init(&it->s, cfg, (uint16_t)(q * span));
    if (err != CP_OK) {
        return err;
    }
    if (!(it->tool_r < it->s.rmin)) {
        return CP_ERR_TOOL;
    }
    it->head.steps = steps;
    it->q = (uint16_t)q;
    return CP_OK;
}

/* |a - 2 b + c| / 8: the sagitta of the chords of a smooth curve through three consecutive
 * evenly spaced points (h^2 kappa / 8 to leading order). */
static cp_real sp_sag3(const struct cp_vec3 *a, const struct cp_vec3 *b, const struct cp_vec3 *c)
{
    struct cp_vec3 d;
    d.x = a->x - CP_R(2.0) * b->x + c->x;
    d.y = a->y - CP_R(2.0) * b->y + c->y;
    d.z = a->z - CP_R(2.0) * b->z + c->z;
    return CP_R(0.125) * cp_sqrt(cp_v3_dot(&d, &d));
}

/* The step sagitta of the raster (head.steps, q, the march at its N): the largest second
 * difference / 8 along every line (LINES: each line marched from u = 0, n N march steps)
 * or circle (CIRCLES: one forward march), on the emitted ball-centre (or surface) points. */
static CP_NOINLINE int sp_walk_steps(struct spine_path *it, cp_real *sag)
{
    uint32_t j, i, steps = it->head.steps, nodes;
    cp_real dv = it->u1 - it->u0;
    *sag = CP_R(0.0);
    for (j = 0; j < it->head.n; j++) {
        struct raster_pt p[3];
        struct spine_state st;
        memset(p, 0, sizeof p); /* p[0], p[1] are read only from i = 2 on */
        cp_real fj = it->head.n > 1u ? (cp_real)j / (cp_real)(it->head.n - 1u) : CP_R(0.0);
        nodes = it->head.mode == RASTER_LINES ? 0u : (uint32_t)(fj * (cp_real)it->s.nsteps + CP_R(0.5));
        for (i = 0; i <= steps; i++) {
            cp_real th;
            int err;
            if (it->head.mode == RASTER_LINES) {
                nodes = i * it->q;
                th = it->u0 + dv * fj;
            } else {
                th = it->u0 + dv * ((cp_real)i / (cp_real)steps);
            }
            err = (it->head.mode == RASTER_LINES || i == 0u) ? spine_node(&it->s, (uint16_t)nodes, &st)
                                                             : CP_OK;
            if (err != CP_OK) {
                return err;
            }
            p[0] = p[1];
            p[1] = p[2];
            spine_point(&st, th, -it->tool_r, &p[2]);
            if (i >= 2u) {
                cp_real e = sp_sag3(&p[0].p, &p[1].p, &p[2].p);
                if (!cp_finite(e)) {
                    return CP_ERR_NUMERIC;
                }
                *sag = e > *sag ? e : *sag;
            }
        }
    }
    return CP_OK;
}

/* CIRCLES: the link sagitta, |P(mid) - (P(a) + P(b))/2| of every link segment (nodes a q,
 * a q + q/2, (a + 1) q) on the lines theta0 = u0 and u1 (where the circles stop), one
 * forward march each. */
static CP_NOINLINE int sp_walk_links(struct spine_path *it, cp_real *sag)
{
    uint32_t e, a, segs = it->s.nsteps / it->q, h = it->q / 2u;
    *sag = CP_R(0.0);
    for (e = 0; e < 2u; e++) {
        cp_real th = e ? it->u1 : it->u0;
        struct raster_pt pa, pm, pb;
        struct spine_state st;
        int err = spine_node(&it->s, 0u, &st);
        if (err != CP_OK) {
            return err;
        }
        spine_point(&st, th, -it->tool_r, &pa);
        for (a = 0; a < segs; a++) {
            struct cp_vec3 d;
            cp_real x;
            err = spine_node(&it->s, (uint16_t)(a * it->q + h), &st);
            if (err == CP_OK) {
                spine_point(&st, th, -it->tool_r, &pm);
                err = spine_node(&it->s, (uint16_t)((a + 1u) * it->q), &st);
            }
            if (err != CP_OK) {
                return err;
            }
            spine_point(&st, th, -it->tool_r, &pb);
            d.x = pm.p.x - CP_R(0.5) * (pa.p.x + pb.p.x);
            d.y = pm.p.y - CP_R(0.5) * (pa.p.y + pb.p.y);
            d.z = pm.p.z - CP_R(0.5) * (pa.p.z + pb.p.z);
            x = cp_sqrt(cp_v3_dot(&d, &d));
            if (!cp_finite(x)) {
                return CP_ERR_NUMERIC;
            }
            *sag = x > *sag ? x : *sag;
            pa = pb;
        }
    }
    return CP_OK;
}

/* STEPS from the tolerance (raster.h raster_fit): walk, measure, re-estimate. */
static const struct raster_rule sp_rule = {.aim = CP_R(0.8), .accept = CP_R(0.9), .start = 16u,
                                           .pilot = 1u, .grow_shift = RASTER_GROW_BY_ONE,
                                           .clamp = 1u};

/* Derive steps (steps == 0) and, for CIRCLES, link (RASTER_LINK_AUTO, n > 1) by raster_fit;
 * *link: the link (given or derived; LINES: 0 here, derived later by sp_link_fit). */
static CP_NOINLINE int sp_fit(struct spine_path *it, const struct spine_cfg *cfg,
                              const struct raster_cfg *rc, uint32_t *link)
{
    struct raster_cfg one = *rc;
    struct raster_fit fit;
    cp_real sag[2];
    int round, err = RASTER_FIT_MORE;
    if (rc->mode == RASTER_LINES) {
        one.link = 0u; /* the links are derived on their own (sp_link_fit) */
    }
    raster_fit_begin(&fit, &one, &sp_rule);
    for (round = 0; round <= RASTER_FIT_ROUNDS && err == RASTER_FIT_MORE; round++) {
        err = sp_setup(it, cfg, fit.m[0], fit.m[1] - 1u);
        if (err == CP_ERR_TOO_MANY) {
            err = CP_ERR_TOL; /* more nodes than the march can take */
        }
        if (err == CP_OK) {
            err = sp_walk_steps(it, &sag[0]);
        }
        sag[1] = CP_R(0.0);
        if (err == CP_OK && rc->mode == RASTER_CIRCLES && it->head.n > 1u) {
            err = sp_walk_links(it, &sag[1]);
        }
        if (err == CP_OK) {
            err = raster_fit_update(&fit, sag);
        }
    }
    *link = fit.m[1] - 1u;
    return err; /* CP_OK: the last sp_setup was at the verified counts fit.m[] */
}

int spine_path_init(struct spine_path *it, const struct spine_cfg *cfg,
                    const struct raster_cfg *rc)
{
    uint32_t link;
    int err;
    if (it == NULL) {
        return CP_ERR_INVAL;
    }
    it->head.count = 0;
    err = spine_init(&it->s, cfg, 1u); /* the geometry's checks first (nodes set below) */
    if (err == CP_OK) {
        err = raster_check(rc, CP_PI);
    }
    if (err != CP_OK) {
        return err;
    }
    if (rc->labels != RASTER_LABEL_ANGLE || rc->span != RASTER_SPAN_LINES) {
        return CP_ERR_INVAL;
    }
    it->head.mode = rc->mode;
    it->head.n = rc->n;
    it->output = rc->output;
    it->tool_r = rc->tool_r;
    it->u0 = rc->u0;
    it->u1 = rc->u1;
    link = rc->link == RASTER_LINK_AUTO ? 0u : rc->link; /* LINES AUTO: derived below */
    if (rc->steps == 0u || (rc->mode == RASTER_CIRCLES && rc->link == RASTER_LINK_AUTO)) {
        err = sp_fit(it, cfg, rc, &link);
    } else {
        err = sp_setup(it, cfg, rc->steps, link);
    }
    if (err != CP_OK) {
        return err;
    }
    if (rc->mode == RASTER_LINES && rc->link == RASTER_LINK_AUTO && rc->n > 1u) {
        err = sp_link_fit(it, rc->tol > CP_R(0.0) ? rc->tol : CP_R(1.0e-3), &link);
        if (err != CP_OK) {
            return err;
        }
    }
    it->head.link = (uint16_t)link;
    it->nl = (uint16_t)(rc->mode == RASTER_LINES ? (uint32_t)(rc->n - 1u) * (link + 1u)
                                                 : it->head.steps);
    err = sp_check_patch(it);
    if (err != CP_OK) {
        return err;
    }
    it->head.count = raster_count(it->head.n, it->head.steps, it->head.link);
    it->head.k = 0u;
    it->lab_l = UINT32_MAX;
    return CP_OK;
}

uint32_t spine_path_count(const struct spine_path *it)
{
    return it->head.count;
}

int spine_path_seek(struct spine_path *it, uint32_t k)
{
    return raster_seek(&it->head, k);
}

int spine_path_next(struct spine_path *it, struct raster_pt *pt)
{
    struct raster_at at;
    uint32_t node, l;
    uint8_t back;
    int err;
    if (it->head.k >= it->head.count) {
        return CP_ERR_DONE;
    }
    sp_where(it, it->head.k, &node, &l, &back, &at);
    err = sp_emit(it, node, l, back, pt);
    pt->line = (int16_t)at.line;
    pt->index = (uint16_t)at.index;
    if (err == CP_OK) {
        it->head.k++;
    }
    return err;
}

#if !CP_REAL_DOUBLE
CP_STATIC_ASSERT(sizeof(struct spine_path) <= 320u, spine_path_ctx_320);
#endif
