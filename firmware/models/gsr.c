/* gsr.c - generalized surfaces of revolution: model, frames, rational sections, iterator.
 * SPDX-License-Identifier: MIT
 *
 * One evaluation path: sec_eval (the section at u: scalar jets, centre jet, frame, every
 * check of C.3) and gsr_point (the surface point and normal at a unit-circle point) serve
 * gsr_init's sample scan, the raster walk of gsr_path_init and gsr_path_next alike.
 *
 * Surface normal. With the frame derivatives along arc length s of the centre
 *     T' = k1 N + k2 B,   N' = -k1 T + w B,   B' = -k2 T - w N
 * (k1, k2 the curvature vector of C on N and B, w the frame's twist: 0 for FIXED and RMF,
 * the torsion for FRENET, -(N0.T) k2 / |N0 - (N0.T) T| for N0), and A = cos theta,
 * S = sin theta, a = f_N, b = f_B:
 *     G_theta = -a S N + b A B
 *     G_u     = ts (1 - k1 a A - k2 b S) T + (a' A - tw b S) N + (b' S + tw a A) B
 * (ts = f_t' |C'|, tw = ts w). The T component is ts times the sweep regularity
 * g = 1 - k.(G - C) of C.3: g > 0 (checked at init) keeps G_u off the section plane, and
 * n = cp_v3_unit(G_theta x G_u) = cp_v3_unit(b A uT N + a S uT B - (a S uB + b A uN) T) points away
 * from C (its in-plane part is the ellipse's outward normal times uT > 0).
 *
 * Frames. All four are the projection frame of an axis a: U = cp_v3_unit(a - (a.T) T), V = T x U,
 * rotated by phi: N = cos phi U + sin phi V, B = T x N. N0: a = N0, phi = 0. FIXED: a = +y,
 * phi = -90 deg (N = -V = (T_z, 0, -T_x), B = U = +y exactly when T_y = 0, C.1). FRENET:
 * a = C'' (U = the principal normal, V = T x U = cp_v3_unit(C' x C''), eq. 9; |U|^2 before
 * normalizing over |a|^2 = |C' x C''|^2 / (|C'| |C''|)^2, the test of C.3). RMF: a = ref,
 * phi from the table. The twist (per arc length) of the projection frame is
 *     U'.V / |C'| = (a'.V - (a.T)(C''.V) / |C'|) / (|a - (a.T) T| |C'|)
 * (a' = C''' for FRENET, where C''.V = 0 and it is the torsion B.C''' / |C' x C''| |C'|;
 * 0 otherwise), plus phi' / |C'|, which cancels it for the RMF by construction.
 *
 * RMF table. In the projection frame of ref the RMF (N' parallel to T) is the scalar
 * equation dphi/dt = -U'.V = (ref.T)(C''.V)/(|C'| |ref - (ref.T) T|), integrated from
 * phi(t0) = 0 by composite Simpson over GSR_RMF_N * GSR_RMF_SUB = 512 steps (error ~ h^4;
 * float rounding grows like sqrt(256) ulp of phi: ~2e-6 rad). Interpolation: cubic Hermite
 * on phi with the node slopes, error <= h^4/384 max|phi''''| (~1e-7 rad for the helix of
 * C.4 with h = 1/16), then one cp_sincos. Init compares it at every interval midpoint with
 * the quadrature itself and rejects (CP_ERR_TOL) if the angle error times the largest
 * section radius exceeds GSR_RMF_TOL.
 *
 * Rational quarter (C.2, weight w = sqrt(2)/2): on the unit square poles (1,0), (1,1),
 * (0,1), x = ((1-v)^2 + 2w v(1-v)) / D, y = (2w v(1-v) + v^2) / D, D = (1-v)^2 + 2w v(1-v)
 * + v^2 >= (1 + w)/2: no cancellation, a few ulp on the unit circle.
 */
#include "gsr.h"
#include "cp_math.h"
#include "raster.h"

#define SQRT2 CP_R(1.41421356237309504880)
#define HALF_PI CP_R(1.57079632679489661923)
#define TAN_PI_8 CP_R(0.41421356237309504880)
#define SAG_MARGIN CP_R(0.9)


static const struct cp_vec3 ey = {CP_R(0.0), CP_R(1.0), CP_R(0.0)};
static const struct cp_vec3 zero = {CP_R(0.0), CP_R(0.0), CP_R(0.0)};

/* Scalar family at x: d[0], d[3], d[6], d[9] = f, f', f'', f''' (stride 3: one component
 * of a vector jet, see centre_jet and sec_eval). */
static void sfun(const cp_real *a, cp_real x, cp_real *d)
{
    cp_real a1 = a[1], a2 = a[2], a3 = a[3], b = a[GSR_B], c = a[GSR_C];
    d[0] = a[0] + x * (a1 + x * (a2 + x * a3));
    d[3] = a1 + x * (CP_R(2.0) * a2 + x * CP_R(3.0) * a3);
    d[6] = CP_R(2.0) * a2 + x * CP_R(6.0) * a3;
    d[9] = CP_R(6.0) * a3;
    if (b != CP_R(0.0) || c != CP_R(0.0)) {
        cp_real w = a[GSR_W], sn, cs, p, q;
        cp_sincos(w * x, &sn, &cs);
        p = b * sn + c * cs;
        q = w * (b * cs - c * sn);
        d[0] += p;
        d[3] += q;
        d[6] -= w * w * p;
        d[9] -= w * w * q;
    }
}

/* Centre jet at t: j[0] = C, j[1] = C', j[2] = C'', j[3] = C''' from the power-basis
 * coefficients g->cp (sfun per axis: d[k][axis] is the k-th derivative). */
static CP_NOINLINE void centre_jet(const struct gsr *g, cp_real t, struct cp_vec3 *j)
{
    cp_real d[4][3];
    unsigned ax, k;
    for (ax = 0; ax < 3u; ax++) {
        sfun(&g->cp[ax * GSR_FN], t, &d[0][ax]);
    }
    for (k = 0; k < 4u; k++) {
        j[k].x = d[k][0];
        j[k].y = d[k][1];
        j[k].z = d[k][2];
    }
}

/* A projection frame: U, V and its twist w (per arc length, see top). */
struct pframe {
    struct cp_vec3 u, v;
    cp_real w;
};

/* Projection frame f of axis a (derivative ad) at unit tangent T (d2 = C'', sp = |C'|).
 * Returns |a - (a.T) T|^2 / |a|^2 (0 or NaN: a parallel to T or zero). */
static cp_real proj(const struct cp_vec3 *a, const struct cp_vec3 *ad, const struct cp_vec3 *T,
                    const struct cp_vec3 *d2, cp_real sp, struct pframe *f)
{
    cp_real pa = cp_v3_dot(a, T), q, wl;
    cp_v3_comb(&f->u, CP_R(1.0), a, -pa, T);
    q = cp_v3_dot(&f->u, &f->u) / cp_v3_dot(a, a);
    wl = cp_v3_unit(&f->u);
    cp_v3_cross(T, &f->u, &f->v);
    f->w = (cp_v3_dot(ad, &f->v) - pa * cp_v3_dot(d2, &f->v) / sp) / (wl * sp);
    return q;
}

/* RMF angle phi at t: cubic Hermite on the table. */
static cp_real rmf_phi(const struct gsr *g, cp_real t)
{
    cp_real x = (t - g->t0) * g->ih, o;
    const cp_real *a, *b;
    uint32_t k;
    x = x > CP_R(0.0) ? x : CP_R(0.0);
    k = (uint32_t)x;
    k = k < GSR_RMF_N ? k : GSR_RMF_N - 1u;
    x -= (cp_real)k;
    a = g->rmf[k];
    b = g->rmf[k + 1u];
    o = CP_R(1.0) - x;
    return o * o * ((CP_R(1.0) + CP_R(2.0) * x) * a[0] + x * a[1]) +
           x * x * ((CP_R(3.0) - CP_R(2.0) * x) * b[0] - o * b[1]);
}

/* 1 if a section function's value f (and derivative df) at a u fails C.3: f_N or f_B
 * (i = 0, 1) f <= 0 (CP_ERR_SECTION), f_t (i = 2) outside [0, 1] or df < 0
 * (CP_ERR_FT_RANGE). sec_eval and gsr_fn_check. */
static int fn_bad(unsigned i, cp_real f, cp_real df)
{
    return i == 2u ? !(f >= CP_R(0.0) && f <= CP_R(1.0) && df >= CP_R(0.0)) : !(f > CP_R(0.0));
}

/* The section at u with every check of C.3 (the fold for the whole section: (k1 f_N)^2 +
 * (k2 f_B)^2 < 1). Returns the first failed check, CP_OK otherwise (the section is filled
 * either way). */
static int sec_eval(const struct gsr *g, cp_real u, struct gsr_sec *s)
{
    const struct gsr_cfg *cf = g->cfg;
    const struct cp_vec3 *ax = &cf->ref, *ad = &zero;
    struct cp_vec3 jet[4]; /* C, C', C'', C''' (centre_jet) */
    const struct cp_vec3 *d2 = &jet[2], *d3 = &jet[3];
    struct pframe pf;
    cp_real f[4][3], sp, s2, q, w, ty, cs[2] = {CP_R(1.0), CP_R(0.0)};
    unsigned i;
    int err = CP_OK;
    for (i = 0; i < 3u; i++) { /* f[k][i]: k-th derivative of f_N, f_B, f_t */
        sfun(cf->r[i], u, &f[0][i]);
    }
    s->fn = f[0][0];
    s->fb = f[0][1];
    s->dfn = f[1][0];
    s->dfb = f[1][1];
    s->ft = f[0][2];
    centre_jet(g, f[0][2], jet);
    s->c = jet[0];
    s->t = jet[1];
    ty = s->t.y;
    s2 = cp_v3_dot(&s->t, &s->t);
    sp = cp_v3_unit(&s->t);
    s->ts = f[1][2] * sp;
    if (g->frame == GSR_FRAME_FRENET) {
        ax = d2;
        ad = d3;
    } else if (g->frame == GSR_FRAME_FIXED) {
        ax = &ey;
        cs[0] = CP_R(0.0);
        cs[1] = CP_R(-1.0);
    }
    q = proj(ax, ad, &s->t, d2, sp, &pf);
    if (g->frame == GSR_FRAME_RMF) {
        cp_sincos(rmf_phi(g, f[0][2]), &cs[1], &cs[0]);
        pf.w = CP_R(0.0);
    }
    cp_v3_comb(&s->n, cs[0], &pf.u, cs[1], &pf.v);
    cp_v3_cross(&s->t, &s->n, &s->b);
    s->tw = s->ts * pf.w;
    s->k1 = cp_v3_dot(d2, &s->n) / s2;
    s->k2 = cp_v3_dot(d2, &s->b) / s2;
    w = (s->k1 * s->fn) * (s->k1 * s->fn) + (s->k2 * s->fb) * (s->k2 * s->fb);
    if (g->frame == GSR_FRAME_FIXED && ty != CP_R(0.0)) {
        err = CP_ERR_OFF_PLANE;
    } else if (fn_bad(2u, f[0][2], f[1][2])) {
        err = CP_ERR_FT_RANGE;
    } else if (fn_bad(0u, s->fn, CP_R(0.0)) || fn_bad(1u, s->fb, CP_R(0.0))) {
        err = CP_ERR_SECTION;
    } else if (!(sp > GSR_EPS * g->d1)) {
        err = CP_ERR_DEGENERATE;
    } else if (!(q > GSR_EPS * GSR_EPS)) {
        err = g->frame == GSR_FRAME_FRENET ? CP_ERR_FRENET : CP_ERR_FRAME_REF;
    } else if (!cp_finite(cp_v3_dot(&s->c, &s->n) + s->tw + w)) {
        /* C.N is finite iff C and N are (|C| <= ~1e5 mm from the coefficient limits, |N|
         * = 1: no product overflows; an Inf or NaN component makes a product Inf or NaN) */
        err = CP_ERR_NUMERIC;
    } else if (!(w < CP_R(1.0))) {
        err = CP_ERR_FOLD;
    }
    return err;
}

/* RMF table: phi(t) = integral of dphi/dt = -|C'| w (w the twist of the projection frame
 * of ref, proj) from phi(t0) = 0, composite Simpson over GSR_RMF_N * GSR_RMF_SUB steps.
 * Nodes every GSR_RMF_SUB steps store (phi, h dphi/dt). Returns the largest angle error of
 * the Hermite interpolation at the interval midpoints against the quadrature (rad), or -1
 * if ref is parallel to T somewhere. */
static CP_NOINLINE cp_real rmf_build(struct gsr *g)
{
    const uint32_t total = GSR_RMF_N * GSR_RMF_SUB;
    struct cp_vec3 j[4];
    struct pframe pf;
    cp_real span = g->t1 - g->t0, f[3] = {CP_R(0.0), CP_R(0.0), CP_R(0.0)}, phi = CP_R(0.0),
            pm = CP_R(0.0), tm = CP_R(0.0), worst = CP_R(0.0), w, sp, t;
    uint32_t i;
    g->ih = (cp_real)GSR_RMF_N / span;
    for (i = 0; i <= total; i++) {
        t = g->t0 + span * ((cp_real)i / (cp_real)total);
        centre_jet(g, t, j);
        sp = cp_v3_unit(&j[1]);
        if (!(proj(&g->cfg->ref, &zero, &j[1], &j[2], sp, &pf) > GSR_EPS * GSR_EPS)) {
            return CP_R(-1.0);
        }
        f[0] = f[1];
        f[1] = f[2];
        f[2] = -pf.w * sp;
        if (i > 0u && i % 2u == 0u) {
            phi += span / (cp_real)(3u * total) * (f[0] + CP_R(4.0) * f[1] + f[2]);
        }
        if (i % GSR_RMF_SUB == GSR_RMF_SUB / 2u) {
            pm = phi; /* and its t, checked at the next node */
            tm = t;
        } else if (i % GSR_RMF_SUB == 0u) {
            g->rmf[i / GSR_RMF_SUB][0] = phi;
            g->rmf[i / GSR_RMF_SUB][1] = f[2] / g->ih;
            if (i > 0u) {
                w = cp_fabs(rmf_phi(g, tm) - pm);
                /* NaN is sticky (w > NaN is false): a NaN error fails CP_ERR_TOL */
                worst = (w > worst || !cp_finite(w)) ? w : worst;
            }
        }
    }
    return worst;
}

/* A number of the geometry: CP_ERR_NONFINITE (NaN, Inf), CP_ERR_RANGE (|x| > max), else
 * CP_OK. */
static int check_num(cp_real x, cp_real max)
{
    if (!cp_finite(x)) {
        return CP_ERR_NONFINITE;
    }
    return cp_fabs(x) <= max ? CP_OK : CP_ERR_RANGE;
}

/* The 3 functions fn[0..2] of GSR_FN numbers each (|w| <= GSR_W_MAX, every other
 * |number| <= GSR_COEF_MAX), in order: the first failing number's code, else CP_OK. */
static int check_fns(const cp_real (*fn)[GSR_FN])
{
    uint32_t i, k;
    int err = CP_OK;
    for (i = 0; i < 3u && err == CP_OK; i++) {
        for (k = 0; k < GSR_FN && err == CP_OK; k++) {
            err = check_num(fn[i][k], k == GSR_W ? GSR_W_MAX : GSR_COEF_MAX);
        }
    }
    return err;
}

int gsr_fn_check(const cp_real *fn, unsigned i)
{
    cp_real d[4u * 3u]; /* sfun's output (stride 3) */
    cp_real f0 = CP_R(0.0);
    uint32_t k;
    int err = CP_OK;
    if (fn == NULL || i > 2u) {
        return CP_ERR_INVAL;
    }
    for (k = 0; k < GSR_FN && err == CP_OK; k++) { /* check_fns' order */
        err = check_num(fn[k], k == GSR_W ? GSR_W_MAX : GSR_COEF_MAX);
    }
    for (k = 0; k <= GSR_SAMPLES && err == CP_OK; k++) { /* gsr_init's samples */
        sfun(fn, (cp_real)k / (cp_real)GSR_SAMPLES, d);
        if (fn_bad(i, d[0], d[3])) {
            err = i == 2u ? CP_ERR_FT_RANGE : CP_ERR_SECTION;
        }
        f0 = k == 0u ? d[0] : f0;
    }
    if (err == CP_OK && i == 2u && !(d[0] > f0)) { /* f_t(1) > f_t(0) */
        err = CP_ERR_FT_RANGE;
    }
    return err;
}

/* gsr_init, last step: on a closed centre (|C(t1) - C(t0)| <= RASTER_SEAM_GAP d1) f_N and
 * f_B must close in value and in slope per arc length of the centre, d/ds = (d/du) / ts
 * (raster_seam_check, no second derivatives; where ts = 0 at an end the slopes are not
 * compared: 0 at both ends). Length scale: the larger of d1 and rmax. */
static CP_NOINLINE int seam_check(const struct gsr *g)
{
    struct gsr_sec e[2];
    struct cp_vec3 gap;
    cp_real inv[2], len = g->d1 > g->rmax ? g->d1 : g->rmax;
    unsigned i;
    int err;
    for (i = 0; i < 2u; i++) {
        (void)sec_eval(g, (cp_real)i, &e[i]); /* both were samples of gsr_init: CP_OK */
        inv[i] = e[i].ts > CP_R(0.0) ? CP_R(1.0) / e[i].ts : CP_R(0.0);
    }
    cp_v3_sub(&e[1].c, &e[0].c, &gap);
    if (!(cp_sqrt(cp_v3_dot(&gap, &gap)) <= RASTER_SEAM_GAP * g->d1)) {
        return CP_OK; /* open */
    }
    if (inv[0] == CP_R(0.0) || inv[1] == CP_R(0.0)) {
        inv[0] = inv[1] = CP_R(0.0);
    }
    err = raster_seam_check(e[0].fn, e[0].dfn * inv[0], CP_R(0.0), e[1].fn, e[1].dfn * inv[1],
                            CP_R(0.0), len);
    if (err == CP_OK) {
        err = raster_seam_check(e[0].fb, e[0].dfb * inv[0], CP_R(0.0), e[1].fb,
                                e[1].dfb * inv[1], CP_R(0.0), len);
    }
    return err;
}

int gsr_init(struct gsr *g, const struct gsr_cfg *cf)
{
    cp_real a[4u * 3u]; /* sfun's output (stride 3): f_t(0), f_t(1) */
    cp_real worst = CP_R(0.0), d1 = CP_R(0.0), rmax = CP_R(0.0);
    struct gsr_sec s;
    struct cp_vec3 bp = zero;
    uint32_t k;
    int err;
    if (g == NULL || cf == NULL || cf->centre > GSR_CENTRE_BEZIER ||
        cf->frame > GSR_FRAME_RMF || cf->section > GSR_SECTION_TRIG) {
        return CP_ERR_INVAL;
    }
    g->cfg = cf;
    g->frame = cf->frame;
    g->section = cf->section;
    /* every number in order: the centre's, the sections', ref (the first failing one
     * gives the code) */
    err = check_fns(cf->c);
    if (err == CP_OK) {
        err = check_fns(cf->r);
    }
    if (err == CP_OK) {
        err = check_num(cf->ref.x, GSR_COEF_MAX);
    }
    if (err == CP_OK) {
        err = check_num(cf->ref.y, GSR_COEF_MAX);
    }
    if (err == CP_OK) {
        err = check_num(cf->ref.z, GSR_COEF_MAX);
    }
    if (err != CP_OK) {
        return err;
    }
    for (k = 0; k < 3u * GSR_FN; k++) { /* the centre's numbers, converted below */
        g->cp[k] = cf->c[k / GSR_FN][k % GSR_FN];
    }
    for (k = 0; k < 3u; k++) {
        /* the centre in the power basis (a Bezier is converted: the cubic family with
         * b = c = 0, no trigonometry), and the bound of |C'| over [0, 1], the scale of the
         * degeneracy tests */
        cp_real *c = &g->cp[k * GSR_FN], p0 = c[0], p1 = c[1], p2 = c[2], p3 = c[3];
        if (cf->centre == GSR_CENTRE_BEZIER) { /* c holds the control points' coordinate */
            c[1] = CP_R(3.0) * (p1 - p0);
            c[2] = CP_R(3.0) * ((p0 - p1) + (p2 - p1));
            c[3] = (p3 - p0) + CP_R(3.0) * (p1 - p2);
            c[GSR_B] = CP_R(0.0);
            c[GSR_C] = CP_R(0.0);
        }
        d1 += cp_fabs(c[1]) + CP_R(2.0) * cp_fabs(c[2]) + CP_R(3.0) * cp_fabs(c[3]) +
              cp_fabs(c[GSR_W]) * (cp_fabs(c[GSR_B]) + cp_fabs(c[GSR_C]));
    }
    g->d1 = d1;
    if (cf->frame >= GSR_FRAME_N0 && !(cp_v3_dot(&cf->ref, &cf->ref) > CP_R(0.0))) {
        return CP_ERR_RANGE;
    }
    sfun(cf->r[2], CP_R(0.0), a);
    g->t0 = a[0];
    sfun(cf->r[2], CP_R(1.0), a);
    g->t1 = a[0];
    if (!(g->t1 > g->t0 && g->t0 >= CP_R(0.0) && g->t1 <= CP_R(1.0))) {
        return CP_ERR_FT_RANGE;
    }
    if (cf->frame == GSR_FRAME_RMF) {
        worst = rmf_build(g);
        if (worst < CP_R(0.0)) {
            return CP_ERR_FRAME_REF;
        }
    }
    for (k = 0; k <= GSR_SAMPLES; k++) {
        err = sec_eval(g, (cp_real)k / (cp_real)GSR_SAMPLES, &s);
        if (err != CP_OK) {
            return err;
        }
        rmax = s.fn > rmax ? s.fn : rmax;
        rmax = s.fb > rmax ? s.fb : rmax;
        if (!(cp_v3_dot(&s.b, &bp) >= CP_R(0.0))) { /* B flipped between samples */
            return cf->frame == GSR_FRAME_FRENET ? CP_ERR_FRENET : CP_ERR_FRAME_REF;
        }
        bp = s.b;
    }
    g->rmax = rmax;
    return worst * rmax <= GSR_RMF_TOL ? seam_check(g) : CP_ERR_TOL;
}

void gsr_section(const struct gsr *g, cp_real u, struct gsr_sec *s)
{
    (void)sec_eval(g, u, s);
}

/* gsr_point with its N and B coordinates ax = f_N cx, by = f_B cy given (pt_at needs them
 * too). */
static void point(const struct gsr_sec *s, cp_real cx, cp_real cy, cp_real ax, cp_real by,
                  struct cp_vec3 *p, struct cp_vec3 *n)
{
    cp_real fn = s->fn, fb = s->fb;
    cp_real ut = s->ts * (CP_R(1.0) - s->k1 * ax - s->k2 * by);
    cp_real un = s->dfn * cx - s->tw * by;
    cp_real ub = s->dfb * cy + s->tw * ax;
    cp_v3_comb(p, CP_R(1.0), &s->c, ax, &s->n);
    cp_v3_comb(p, CP_R(1.0), p, by, &s->b);
    cp_v3_comb(n, fb * cx * ut, &s->n, fn * cy * ut, &s->b);
    cp_v3_comb(n, CP_R(1.0), n, -(fn * cy * ub + fb * cx * un), &s->t);
    (void)cp_v3_unit(n);
}

void gsr_point(const struct gsr_sec *s, cp_real cx, cp_real cy, struct cp_vec3 *p,
               struct cp_vec3 *n)
{
    point(s, cx, cy, s->fn * cx, s->fb * cy, p, n);
}

void gsr_unit_rational(cp_real psi, cp_real *cx, cp_real *cy)
{
    /* quarter by truncation of psi + 2 >= 0 (no floor call); where rounding puts psi a
     * hair into the next quarter, v is a hair outside [0, 1]: the rational quarter extends
     * smoothly and stays on the circle there */
    int32_t qi = (int32_t)(psi + CP_R(2.0)) - 2;
    cp_real v, w, m, a, b, id, x, y;
    uint32_t r;
    qi = qi < 1 ? qi : 1; /* psi = 2: quarter 1 at v = 1 */
    v = psi - (cp_real)qi;
    w = CP_R(1.0) - v;
    m = SQRT2 * v * w; /* 2 (sqrt(2)/2) v (1 - v) */
    a = w * w;
    b = v * v;
    id = CP_R(1.0) / (a + m + b);
    x = (a + m) * id;
    y = (m + b) * id;
    for (r = (uint32_t)qi & 3u; r > 0u; r--) { /* quarter q: q turns of 90 deg */
        a = x;
        x = -y;
        y = a;
    }
    *cx = x;
    *cy = y;
}

cp_real gsr_psi(cp_real th)
{
    cp_real q = cp_floor(th / HALF_PI), sn, cs;
    q = q < CP_R(1.0) ? q : CP_R(1.0); /* th = pi: quarter 1 at v = 1 */
    cp_sincos(CP_R(0.5) * ((th - q * HALF_PI) - CP_R(0.5) * HALF_PI), &sn, &cs);
    return q + CP_R(0.5) * (CP_R(1.0) + sn / (cs * TAN_PI_8));
}

/* ---- even arc length on an elliptic section (gsr.h; not used by the iterator) ---- */

#define ARC_H (HALF_PI / (cp_real)GSR_ARCLEN_N) /* table step, rad */

/* 4-point Gauss-Legendre on [-1, 1]: nodes +-x[i], weights w[i] */
static const cp_real gl4_x[2] = {CP_R(0.33998104358485626480), CP_R(0.86113631159405257522)};
static const cp_real gl4_w[2] = {CP_R(0.65214515486254614263), CP_R(0.34785484513745385737)};

/* |E'(th)| = sqrt(a^2 sin^2 + b^2 cos^2), mm/rad (no cancellation: both terms >= 0) */
static cp_real arc_speed(const struct gsr_arclen *t, cp_real th)
{
    cp_real sn, cs;
    cp_sincos(th, &sn, &cs);
    return cp_sqrt(t->aa * sn * sn + t->bb * cs * cs);
}

/* Signed arc length from x0 to x1 (4-point Gauss-Legendre, one panel). */
static cp_real arc_gl(const struct gsr_arclen *t, cp_real x0, cp_real x1)
{
    cp_real m = CP_R(0.5) * (x0 + x1), hw = CP_R(0.5) * (x1 - x0), sum = CP_R(0.0);
    uint32_t i;
    for (i = 0; i < 2u; i++) {
        cp_real d = hw * gl4_x[i];
        sum += gl4_w[i] * (arc_speed(t, m - d) + arc_speed(t, m + d));
    }
    return hw * sum;
}

/* s(phi) for phi in [0, pi/2]: the table node nearest phi plus one panel (<= h/2). */
static cp_real arc_part(const struct gsr_arclen *t, cp_real phi)
{
    uint32_t j = (uint32_t)(phi / ARC_H + CP_R(0.5));
    j = j < GSR_ARCLEN_N ? j : GSR_ARCLEN_N;
    return t->cum[j] + arc_gl(t, (cp_real)j * ARC_H, phi);
}

/* phi in [0, pi/2] with s(phi) = s, s in [0, L_q]. */
static cp_real arc_inv(const struct gsr_arclen *t, cp_real s)
{
    uint32_t lo = 0u, i;
    cp_real p0, p1, phi;
    for (i = GSR_ARCLEN_N / 2u; i > 0u; i >>= 1) { /* log2 N steps: cum[lo] <= s */
        lo = t->cum[lo + i] <= s ? lo + i : lo;
    }
    p0 = (cp_real)lo * ARC_H;
    p1 = (cp_real)(lo + 1u) * ARC_H;
    /* cum[lo + 1] - cum[lo] >= h min(a, b) > 0 */
    phi = p0 + ARC_H * (s - t->cum[lo]) / (t->cum[lo + 1u] - t->cum[lo]);
    for (i = 0; i < GSR_ARCLEN_NEWTON; i++) {
        uint32_t j = phi - p0 < p1 - phi ? lo : lo + 1u;
        cp_real r = t->cum[j] + arc_gl(t, (cp_real)j * ARC_H, phi) - s;
        phi -= r / arc_speed(t, phi);
        phi = phi > p0 ? phi : p0;
        phi = phi < p1 ? phi : p1;
    }
    return phi;
}

int gsr_arclen_init(struct gsr_arclen *t, cp_real fn, cp_real fb)
{
    cp_real lo, hi, sum = CP_R(0.0), comp = CP_R(0.0);
    uint32_t k;
    if (t == NULL) {
        return CP_ERR_INVAL;
    }
    if (!cp_finite(fn) || !cp_finite(fb)) {
        return CP_ERR_NONFINITE;
    }
    if (!(fn > CP_R(0.0)) || !(fb > CP_R(0.0))) {
        return CP_ERR_SECTION;
    }
    lo = fn < fb ? fn : fb;
    hi = fn < fb ? fb : fn;
    if (hi > GSR_COEF_MAX || hi > GSR_ARCLEN_RATIO * lo) {
        return CP_ERR_RANGE;
    }
    t->aa = fn * fn;
    t->bb = fb * fb;
    t->cum[0] = CP_R(0.0);
    for (k = 0; k < GSR_ARCLEN_N; k++) { /* Kahan: cum[] to ~1 ulp of L_q */
        cp_real y = arc_gl(t, (cp_real)k * ARC_H, (cp_real)(k + 1u) * ARC_H) - comp;
        cp_real n = sum + y;
        comp = (n - sum) - y;
        sum = n;
        t->cum[k + 1u] = sum;
    }
    t->lq = sum;
    return CP_OK;
}

/* Quarter index of x in [0, 4] by comparisons (3 at x = 4). */
static uint32_t arc_quarter(cp_real x)
{
    return x >= CP_R(2.0) ? (x >= CP_R(3.0) ? 3u : 2u) : (x >= CP_R(1.0) ? 1u : 0u);
}

cp_real gsr_arclen_angle(const struct gsr_arclen *t, cp_real f)
{
    cp_real x, r, th;
    uint32_t q;
    if (!(f == f)) {
        return f;
    }
    x = CP_R(4.0) * cp_fabs(f); /* exact */
    x = x < CP_R(4.0) ? x : CP_R(4.0);
    q = arc_quarter(x);
    r = x - (cp_real)q; /* exact (Sterbenz), in [0, 1] */
    if (q & 1u) {       /* odd quarter: mirror about its end, s(x) = L_q - s(pi/2 - x) */
        th = (cp_real)(q + 1u) * HALF_PI - arc_inv(t, t->lq - r * t->lq);
    } else {
        th = (cp_real)q * HALF_PI + arc_inv(t, r * t->lq);
    }
    return f < CP_R(0.0) ? -th : th;
}

cp_real gsr_arclen_frac(const struct gsr_arclen *t, cp_real th)
{
    cp_real x, phi, s;
    uint32_t q;
    if (!(th == th)) {
        return th;
    }
    x = cp_fabs(th);
    x = x < CP_R(4.0) * HALF_PI ? x : CP_R(4.0) * HALF_PI;
    q = arc_quarter(x / HALF_PI);
    phi = x - (cp_real)q * HALF_PI;
    phi = phi > CP_R(0.0) ? phi : CP_R(0.0);
    phi = phi < HALF_PI ? phi : HALF_PI;
    if (q & 1u) {
        s = (cp_real)(q + 1u) * t->lq - arc_part(t, HALF_PI - phi);
    } else {
        s = (cp_real)q * t->lq + arc_part(t, phi);
    }
    s = s / (CP_R(4.0) * t->lq);
    return th < CP_R(0.0) ? -s : s;
}

/* ---- iterator ---------------------------------------------------------------------- */


/* Section parameter of eccentric angle th: th itself (TRIG) or psi (RATIONAL). */
static CP_NOINLINE cp_real sigma_of(const struct gsr_path *it, cp_real th)
{
    return it->g.section == GSR_SECTION_TRIG ? th : gsr_psi(th);
}


/* Fixed coordinate of line j (LINES: sig of theta_j, CIRCLES: u = j (link + 1) / gsteps). */
static cp_real fixed(const struct gsr_path *it, uint32_t j)
{
    uint32_t lk = (uint32_t)it->head.link + 1u;
    return it->head.mode == RASTER_LINES
               ? sigma_of(it, it->v0 + (cp_real)j * it->dv)
               : (cp_real)(j * lk) / (cp_real)(it->head.n > 1u ? (uint32_t)(it->head.n - 1u) * lk : 1u);
}

/* Where point k is: x[0] = u, x[1] = the section parameter sig; line (-1 on a link) and
 * index (raster_locate). Both modes are one raster: line j has a FIXED coordinate and a
 * RUNNING one (LINES: u = 0..1, CIRCLES: sig = s0..s1) at i / steps; link point a runs the
 * fixed coordinate from line j's value to line j + 1's at fraction a / (link + 1), at the
 * running end where line j stopped. */
static void locate(const struct gsr_path *it, uint32_t k, cp_real *x, struct raster_at *at)
{
    uint32_t c = it->head.mode == RASTER_LINES;
    cp_real a0 = it->s0, a1 = it->s1, f;
    raster_locate(k, it->head.steps, it->head.link, at);
    f = fixed(it, at->j);
    if (at->a != 0u) { /* link point a */
        f += (fixed(it, at->j + 1u) - f) * ((cp_real)at->a / (cp_real)(it->head.link + 1u));
    }
    x[c] = f;
    x[1u - c] = a0 + (a1 - a0) * ((cp_real)at->i / (cp_real)it->head.steps);
}

/* Emitted point at x = (u, sig) (surface, tool centre G + r n, or tip) and normal, with
 * every check: C.3 on a new section, the fold at the emitted tool centre (1 - k.(P - C) >
 * 0), finiteness. The section is cached by its u and the unit-circle point by its sig
 * (bit equality: both are the same computation whenever they are equal; gsr_path_seek
 * resets the keys), so a ring costs one section and then only its unit
 * points, and a line one unit point. */
static int pt_at(struct gsr_path *it, const cp_real *x, struct raster_pt *pt)
{
    const struct gsr_sec *s = &it->sec;
    cp_real g, ax, by, r;
    int err = CP_OK;
    if (x[0] != it->su) {
        err = sec_eval(&it->g, x[0], &it->sec);
        /* key the cache only on success: a retry at the same u must evaluate again */
        it->su = err == CP_OK ? x[0] : CP_R(-1.0);
    }
    if (x[1] != it->cs) {
        if (it->g.section == GSR_SECTION_TRIG) {
            cp_sincos(x[1], &it->cc[1], &it->cc[0]);
        } else {
            gsr_unit_rational(x[1], &it->cc[0], &it->cc[1]);
        }
        it->cs = x[1];
    }
    ax = s->fn * it->cc[0]; /* the surface point's N and B coordinates (as gsr_point), mm */
    by = s->fb * it->cc[1];
    r = it->tool_r;
    point(s, it->cc[0], it->cc[1], ax, by, &pt->p, &pt->n);
    cp_v3_comb(&pt->p, CP_R(1.0), &pt->p, r, &pt->n);
    if (it->output == RASTER_OUT_TIP) {
        pt->p.z -= r;
    }
    g = CP_R(1.0) - s->k1 * (ax + r * cp_v3_dot(&pt->n, &s->n)) - s->k2 * (by + r * cp_v3_dot(&pt->n, &s->b));
    if (err == CP_OK && !cp_finite(cp_v3_dot(&pt->p, &pt->p) + g)) { /* |p|^2 <= ~1e11 mm^2 */
        err = CP_ERR_NUMERIC;
    }
    return err != CP_OK || g > CP_R(0.0) ? err : CP_ERR_FOLD;
}

/* Walk the whole stream at twice its resolution: every point and every segment midpoint
 * (in (u, sig), along which a segment runs linearly). sag[0]: max midpoint sagitta of the
 * segments within a line/ring, sag[1]: of the link segments. Work: 2 count points, fixed
 * before the loop. */
static CP_NOINLINE int walk(struct gsr_path *it, cp_real *sag)
{
    struct raster_pt a, b, m;
    cp_real x[2], px[2] = {CP_R(0.0), CP_R(0.0)};
    struct raster_at at;
    int32_t pline = -1;
    uint32_t k;
    int err = gsr_path_seek(it, 0u);
    sag[0] = sag[1] = CP_R(0.0);
    a.p = zero;
    for (k = 0; k < it->head.count && err == CP_OK; k++) {
        locate(it, k, x, &at);
        err = pt_at(it, x, &b);
        if (err == CP_OK && k > 0u) {
            unsigned c = (at.line >= 0 && at.line == pline) ? 0u : 1u;
            px[0] = CP_R(0.5) * (px[0] + x[0]);
            px[1] = CP_R(0.5) * (px[1] + x[1]);
            err = pt_at(it, px, &m);
            cp_v3_comb(&m.p, CP_R(1.0), &m.p, CP_R(-0.5), &a.p);
            cp_v3_comb(&m.p, CP_R(1.0), &m.p, CP_R(-0.5), &b.p);
            px[0] = cp_sqrt(cp_v3_dot(&m.p, &m.p));
            sag[c] = px[0] > sag[c] ? px[0] : sag[c];
        }
        a.p = b.p;
        pline = at.line;
        px[0] = x[0];
        px[1] = x[1];
    }
    return err;
}

/* The tolerance search (raster_fit): grow from 8 steps / 1 link segment, aim at and
 * verify with the midpoint sagitta <= SAG_MARGIN tol, at least + 1 per round, an estimate
 * above the maximum tried at the maximum. */
static const struct raster_rule gsr_rule = {.aim = SAG_MARGIN, .accept = SAG_MARGIN, .start = 8u,
                                            .pilot = 0u, .grow_shift = RASTER_GROW_BY_ONE, .clamp = 1u};
CP_STATIC_ASSERT(GSR_WALK_ROUNDS == RASTER_FIT_ROUNDS, gsr_walk_rounds_documented);

/* raster_overlap_check's ball of the section at u: the centre point C(f_t(u)) and the
 * larger semi-axis (the ellipse lies within it); no frame. Its u are multiples of 1/128,
 * samples of gsr_init (k / 256): every value there was checked. */
static int gsr_ball(const void *ctx, cp_real u, struct cp_vec3 *c, cp_real *r)
{
    const struct gsr *g = ctx;
    struct cp_vec3 jet[4];
    cp_real f[4][3];
    unsigned i;
    for (i = 0; i < 3u; i++) { /* f_N, f_B, f_t (f[0][i]; the derivatives unused) */
        sfun(g->cfg->r[i], u, &f[0][i]);
    }
    centre_jet(g, f[0][2], jet);
    *c = jet[0];
    *r = f[0][0] > f[0][1] ? f[0][0] : f[0][1];
    return cp_finite(c->x + c->y + c->z + *r) ? CP_OK : CP_ERR_NUMERIC;
}

int gsr_path_init(struct gsr_path *it, const struct gsr_cfg *geom, const struct raster_cfg *rc)
{
    struct raster_fit fit;
    cp_real sag[2];
    int round, err;
    if (it == NULL) {
        return CP_ERR_INVAL;
    }
    it->head.count = 0;
    it->head.overlap = 0u; /* the tool is outside: an overlap is refused */
    err = gsr_init(&it->g, geom);
    if (err == CP_OK) {
        err = raster_check(rc, CP_PI);
    }
    if (err == CP_OK && rc->tool_r > GSR_COEF_MAX) {
        err = CP_ERR_RANGE;
    }
    if (err != CP_OK) {
        return err;
    }
    it->head.mode = rc->mode;
    it->output = rc->output;
    it->head.n = rc->n;
    it->tool_r = rc->tool_r;
    it->v0 = rc->u0;
    it->dv = it->head.n > 1u ? (rc->u1 - rc->u0) / (cp_real)(it->head.n - 1u) : CP_R(0.0);
    it->s0 = CP_R(0.0); /* LINES: u runs from 0 to 1 */
    it->s1 = CP_R(1.0);
    if (it->head.mode == RASTER_CIRCLES) {
        it->s0 = sigma_of(it, rc->u0);
        it->s1 = sigma_of(it, rc->u1);
    }
    raster_fit_begin(&fit, rc, &gsr_rule);
    err = RASTER_FIT_MORE;
    for (round = 0; round <= RASTER_FIT_ROUNDS && err == RASTER_FIT_MORE; round++) {
        it->head.steps = (uint16_t)fit.m[0];
        it->head.link = (uint16_t)(fit.m[1] - 1u);
        it->head.count = raster_count(it->head.n, fit.m[0], fit.m[1] - 1u);
        err = walk(it, sag);
        if (err == CP_OK) {
            err = raster_fit_update(&fit, sag);
        }
    }
    if (err == CP_OK) { /* the tool is outside: it sweeps 2 r beyond the surface */
        struct raster_overlap o;
        err = raster_overlap_check(gsr_ball, &it->g, CP_R(2.0) * it->tool_r, &o);
    }
    if (err != CP_OK) {
        it->head.count = 0;
    }
    /* CP_OK: the last walk (its gsr_path_seek(it, 0)) left k = 0, and the caches it
     * filled are keyed by u and sig, so they stay valid (no second seek) */
    return err;
}

uint32_t gsr_path_count(const struct gsr_path *it)
{
    return it->head.count;
}

CP_NOINLINE int gsr_path_seek(struct gsr_path *it, uint32_t k)
{
    it->su = CP_R(-1.0); /* u >= 0: no section cached */
    it->cs = CP_R(8.0);  /* |sig| <= 4: no unit point cached */
    return raster_seek(&it->head, k);
}

int gsr_path_next(struct gsr_path *it, struct raster_pt *pt)
{
    cp_real x[2];
    struct raster_at at;
    int err;
    if (it->head.k >= it->head.count) {
        return CP_ERR_DONE;
    }
    locate(it, it->head.k, x, &at);
    err = pt_at(it, x, pt);
    pt->t = x[0];
    pt->line = (int16_t)at.line;
    pt->index = (uint16_t)at.index;
    if (err == CP_OK) {
        it->head.k++;
    }
    return err;
}

#if CP_REAL_DOUBLE
CP_STATIC_ASSERT(sizeof(struct gsr_path) <= 896u, gsr_path_fits_budget);
CP_STATIC_ASSERT(sizeof(struct gsr_cfg) <= 640u, gsr_cfg_fits_budget);
#else
CP_STATIC_ASSERT(sizeof(struct gsr_path) <= 448u, gsr_path_fits_budget);
CP_STATIC_ASSERT(sizeof(struct gsr_cfg) <= 320u, gsr_cfg_fits_budget);
#endif
