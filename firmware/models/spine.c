/* spine.c - SPINE kernel: jets, init checks, the local node frame, the fixed-step march of
 * the transport M (two-point Hermite Magnus-4, increment form), its quintic interpolant and
 * the points. See spine.h and docs/MATH-spine.md sections 2-5 and 9.7.
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

/* R, R_u and (full) R_uu at u */
static void sp_law(const struct spine *s, cp_real u, int full, struct spine_jet *j)
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
        cp_sincos(w * u, &sn, &cs); /* out of line: flash; bit-identical to the kernel */
        j->r = k[0] * cs + k[1];
        j->ru = -k[0] * w * sn;
        if (full) {
            j->ruu = -k[0] * w * w * cs;
        }
        break;
    }
    default: { /* SPINE_R_CUBIC: power basis about 1/2 (sp_power), Horner in w = u - 1/2 */
        cp_real w = u - CP_R(0.5);
        j->r = ((k[3] * w + k[2]) * w + k[1]) * w + k[0];
        j->ru = (CP_R(3.0) * k[3] * w + CP_R(2.0) * k[2]) * w + k[1];
        if (full) {
            j->ruu = CP_R(6.0) * k[3] * w + CP_R(2.0) * k[2];
        }
        break;
    }
    }
}

/* ARC and HELIX: r (cos p e1 + sin p e2), p = w u, its first and (full) second and third
 * u-derivatives (c_uuu = -w^2 c_u) */
static void sp_circle(const struct spine *s, cp_real r, cp_real w, cp_real u, int full,
                      struct spine_jet *j)
{
    cp_real sn, cs, rw = r * w, rww = rw * w;
    cp_sincos(w * u, &sn, &cs); /* out of line: flash; bit-identical to the kernel */
    j->c.x = r * (cs * s->e1.x + sn * s->e2.x);
    j->c.y = r * (cs * s->e1.y + sn * s->e2.y);
    j->c.z = r * (cs * s->e1.z + sn * s->e2.z);
    j->cu.x = rw * (cs * s->e2.x - sn * s->e1.x);
    j->cu.y = rw * (cs * s->e2.y - sn * s->e1.y);
    j->cu.z = rw * (cs * s->e2.z - sn * s->e1.z);
    if (!full) {
        return;
    }
    j->cuu.x = -w * w * j->c.x;
    j->cuu.y = -w * w * j->c.y;
    j->cuu.z = -w * w * j->c.z;
    j->cuuu.x = -w * w * j->cu.x;
    j->cuuu.y = -w * w * j->cu.y;
    j->cuuu.z = -w * w * j->cu.z;
    (void)rww;
}

/* BEZIER in its power basis about 1/2 (sp_power): c = B0 + B1 w + B2 w^2 + B3 w^3, Horner in
 * w = u - 1/2, |w| <= 1/2. |B_k w^k| <= 2 max |P_i| for every k, so each coordinate is
 * rounded to a few ulp of max |P_i| (as the Bernstein sum). */
static void sp_bezier(const cp_real *b, cp_real u, int full, struct spine_jet *j)
{
    cp_real w = u - CP_R(0.5);
    j->c.x = ((b[9] * w + b[6]) * w + b[3]) * w + b[0];
    j->c.y = ((b[10] * w + b[7]) * w + b[4]) * w + b[1];
    j->c.z = ((b[11] * w + b[8]) * w + b[5]) * w + b[2];
    j->cu.x = (CP_R(3.0) * b[9] * w + CP_R(2.0) * b[6]) * w + b[3];
    j->cu.y = (CP_R(3.0) * b[10] * w + CP_R(2.0) * b[7]) * w + b[4];
    j->cu.z = (CP_R(3.0) * b[11] * w + CP_R(2.0) * b[8]) * w + b[5];
    if (!full) {
        return;
    }
    j->cuu.x = CP_R(6.0) * b[9] * w + CP_R(2.0) * b[6];
    j->cuu.y = CP_R(6.0) * b[10] * w + CP_R(2.0) * b[7];
    j->cuu.z = CP_R(6.0) * b[11] * w + CP_R(2.0) * b[8];
    j->cuuu.x = CP_R(6.0) * b[9];
    j->cuuu.y = CP_R(6.0) * b[10];
    j->cuuu.z = CP_R(6.0) * b[11];
}

/* The jet at u; full = 0: c, c_u, R and R_u only (the points' jet). */
static void sp_jet(const struct spine *s, cp_real u, int full, struct spine_jet *j)
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
        j->cuuu = j->cuu;
        break;
    case SPINE_ARC:
        sp_circle(s, p[6], p[10], u, full, j);
        j->c.x += p[0];
        j->c.y += p[1];
        j->c.z += p[2];
        break;
    case SPINE_HELIX: {
        cp_real w = CP_TWO_PI * p[8], rise = p[7] * p[8]; /* dz/du = pitch turns */
        sp_circle(s, p[6], w, u, full, j);
        j->c.x += p[0] + rise * u * s->ax.x;
        j->c.y += p[1] + rise * u * s->ax.y;
        j->c.z += p[2] + rise * u * s->ax.z;
        j->cu.x += rise * s->ax.x;
        j->cu.y += rise * s->ax.y;
        j->cu.z += rise * s->ax.z;
        break;
    }
    default:
        sp_bezier(p, u, full, j);
        break;
    }
    sp_law(s, u, full, j);
}

void spine_jet(const struct spine *s, cp_real u, struct spine_jet *j)
{
    sp_jet(s, u, 1, j);
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

/* BEZIER and CUBIC to their power basis about u = 1/2 (sp_bezier, sp_law): with the
 * Bernstein coefficients p0..p3 of one coordinate,
 *   B0 = (p0 + 3 p1 + 3 p2 + p3) / 8,  B1 = 3 (p3 + p2 - p1 - p0) / 4,
 *   B2 = 3 (p3 - p2 - p1 + p0) / 2,    B3 = p3 - 3 p2 + 3 p1 - p0
 * (the Taylor coefficients c, c_u, c_uu / 2, c_uuu / 6 at u = 1/2). `stride` 3 (points) or
 * 1 (scalars). */
static void sp_power(cp_real *p, int stride)
{
    int i;
    for (i = 0; i < stride; i++) {
        cp_real p0 = p[i], p1 = p[i + stride], p2 = p[i + 2 * stride], p3 = p[i + 3 * stride];
        p[i] = (p0 + CP_R(3.0) * p1 + CP_R(3.0) * p2 + p3) * CP_R(0.125);
        p[i + stride] = CP_R(0.75) * ((p3 + p2) - (p1 + p0));
        p[i + 2 * stride] = CP_R(1.5) * ((p3 - p2) - (p1 - p0));
        p[i + 3 * stride] = (p3 - p0) - CP_R(3.0) * (p2 - p1);
    }
}

/* |c_u| > 0, R > 0 and |a| < 1 on the nodes u = k / N and on u = k / SPINE_CHECK_N; the
 * largest R in *rmax, the spine's extent max |c(u) - c(0)| over the samples in *ext */
static int sp_samples(struct spine *s, cp_real scale, cp_real *rmax, cp_real *ext)
{
    uint32_t k, nn = s->nsteps, nall = nn + 1u + SPINE_CHECK_N + 1u;
    cp_real rmin = CP_R(1e30);
    struct cp_vec3 c0 = {CP_R(0.0), CP_R(0.0), CP_R(0.0)}, dc;
    int bad_r = 0, bad_a = 0;
    *rmax = CP_R(0.0);
    *ext = CP_R(0.0);
    for (k = 0; k < nall; k++) {
        struct spine_jet j;
        cp_real v, a;
        cp_real u = k <= nn ? (cp_real)k / (cp_real)nn
                            : (cp_real)(k - nn - 1u) / (cp_real)SPINE_CHECK_N;
        spine_jet(s, u, &j);
        if (k == 0u) {
            c0 = j.c;
        }
        cp_v3_sub(&j.c, &c0, &dc);
        v = cp_v3_norm(&dc);
        *ext = v > *ext ? v : *ext;
        v = cp_v3_norm(&j.cu);
        if (!(v > CP_R(1e-5) * (CP_R(1.0) + scale))) {
            return CP_ERR_DEGENERATE;
        }
        a = cp_fabs(j.ru) / v;
        bad_r |= !(j.r > CP_R(0.0));
        bad_a |= !(a < CP_R(1.0));
        rmin = j.r < rmin ? j.r : rmin;
        *rmax = j.r > *rmax ? j.r : *rmax;
    }
    s->rmin = rmin;
    return bad_r ? CP_ERR_RADIUS : (bad_a ? CP_ERR_RANGE : CP_OK);
}

/* The node frame at a jet: v = |c_u|, T, E = e.T, G = |e - E T| = sqrt(1 - E^2) (> 0: e is
 * never along T), P = (e - E T) / G, Q = T x P. ~35 flops, 2 square roots, 6 divisions;
 * each vector unit to a few ulp. */
struct sp_frame {
    struct cp_vec3 t, p, q;
    cp_real v, e, g;
};

static void sp_frame(const struct spine *s, const struct spine_jet *j, struct sp_frame *f)
{
    struct cp_vec3 w;
    f->v = cp_sqrt(cp_v3_dot(&j->cu, &j->cu));
    f->t.x = j->cu.x / f->v;
    f->t.y = j->cu.y / f->v;
    f->t.z = j->cu.z / f->v;
    f->e = cp_v3_dot(&s->ax, &f->t);
    w.x = s->ax.x - f->e * f->t.x;
    w.y = s->ax.y - f->e * f->t.y;
    w.z = s->ax.z - f->e * f->t.z;
    f->g = cp_sqrt(cp_v3_dot(&w, &w));
    f->p.x = w.x / f->g;
    f->p.y = w.y / f->g;
    f->p.z = w.z / f->g;
    cp_v3_cross(&f->t, &f->p, &f->q);
}

/* BEZIER: the frame axis e, the candidate with the largest min |e x T| over u = k /
 * SPINE_CHECK_N: the coordinate axes and the unit cross products of the hodograph's
 * control vectors D_i = P_{i+1} - P_i (p: the control points, before sp_power). A planar
 * curve gets its plane's normal (|e x T| = 1). CP_ERR_DEGENERATE below SPINE_AXIS_MIN. */
static int sp_axis_bezier(struct spine *s, const cp_real *p)
{
    struct cp_vec3 cand[6], d[3];
    cp_real best = CP_R(-1.0);
    int c, i;
    uint32_t k;
    for (i = 0; i < 3; i++) {
        d[i].x = p[3 * i + 3] - p[3 * i];
        d[i].y = p[3 * i + 4] - p[3 * i + 1];
        d[i].z = p[3 * i + 5] - p[3 * i + 2];
    }
    for (i = 0; i < 3; i++) { /* the coordinate axes */
        cand[i].x = i == 0 ? CP_R(1.0) : CP_R(0.0);
        cand[i].y = i == 1 ? CP_R(1.0) : CP_R(0.0);
        cand[i].z = i == 2 ? CP_R(1.0) : CP_R(0.0);
    }
    cp_v3_cross(&d[0], &d[1], &cand[3]);
    cp_v3_cross(&d[1], &d[2], &cand[4]);
    cp_v3_cross(&d[0], &d[2], &cand[5]);
    for (c = 0; c < 6; c++) {
        cp_real worst = CP_R(2.0);
        if (!(cp_v3_norm(&cand[c]) > CP_R(0.0))) {
            continue; /* parallel control vectors */
        }
        (void)cp_v3_unit(&cand[c]);
        for (k = 0; k <= SPINE_CHECK_N; k++) {
            struct spine_jet j;
            cp_real e, g;
            spine_jet(s, (cp_real)k / (cp_real)SPINE_CHECK_N, &j);
            (void)cp_v3_unit(&j.cu);
            e = cp_v3_dot(&cand[c], &j.cu);
            g = CP_R(1.0) - e * e; /* |e x T|^2 */
            worst = g < worst ? g : worst;
        }
        if (worst > best) {
            best = worst;
            s->ax = cand[c];
        }
    }
    return best >= SPINE_AXIS_MIN * SPINE_AXIS_MIN ? CP_OK : CP_ERR_DEGENERATE;
}

/* A closed spine (|c(1) - c(0)| <= RASTER_SEAM_GAP ext: an ARC of 2 pi, a HELIX of pitch 0
 * and whole turns, a Bezier with P3 = P0) needs R to close (raster.h): R, a = dR/ds and
 * da/ds at both ends to raster_seam_check, length scale max(ext, rmax). The RMF need not
 * close (its holonomy): the family-2 lines then meet the seam at other labels, but the
 * surface is whole. */
static CP_NOINLINE int sp_seam(const struct spine *s, cp_real ext, cp_real rmax)
{
    struct spine_jet j[2];
    cp_real a[2], as[2], v;
    struct cp_vec3 d;
    int e;
    spine_jet(s, CP_R(0.0), &j[0]);
    spine_jet(s, CP_R(1.0), &j[1]);
    cp_v3_sub(&j[1].c, &j[0].c, &d);
    if (!(cp_v3_norm(&d) <= RASTER_SEAM_GAP * ext)) {
        return CP_OK; /* open: its ends may have any R */
    }
    for (e = 0; e < 2; e++) {
        v = cp_v3_norm(&j[e].cu);
        a[e] = j[e].ru / v;
        as[e] = (j[e].ruu - a[e] * cp_v3_dot(&j[e].cu, &j[e].cuu) / v) / (v * v);
    }
    return raster_seam_check(j[0].r, a[0], as[0], j[1].r, a[1], as[1], ext > rmax ? ext : rmax);
}

/* N1(0) from ref (non-zero) or the principal normal; LINE: the axis is N1(0) itself. Then
 * z0 = (cos, sin)(phi0 / 2), phi0 the angle of N1(0) from P(0) towards Q(0). */
static int sp_frame0(struct spine *s, const cp_real ref[3])
{
    struct spine_jet j;
    struct sp_frame f;
    struct cp_vec3 t, w, n10;
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
        cp_v3_comb(&n10, CP_R(1.0), &w, -d, &t);
        if (!(cp_v3_norm(&n10) > CP_R(1e-4) * l)) {
            return CP_ERR_FRAME_REF;
        }
    } else {
        d = cp_v3_dot(&j.cuu, &t);
        cp_v3_comb(&n10, CP_R(1.0), &j.cuu, -d, &t);
        if (!(cp_v3_norm(&n10) > CP_R(1e-4) * cp_v3_dot(&j.cu, &j.cu))) {
            return CP_ERR_FRENET;
        }
    }
    (void)cp_v3_unit(&n10);
    if (s->kind == SPINE_LINE) {
        s->ax = n10; /* normal to the line's one T: P = N1(0) everywhere */
    }
    sp_frame(s, &j, &f);
    l = cp_atan2(cp_v3_dot(&n10, &f.q), cp_v3_dot(&n10, &f.p));
    cp_sincos(CP_R(0.5) * l, &s->z0[1], &s->z0[0]);
    return CP_OK;
}

static void sp_restart(struct spine *s);

int spine_init(struct spine *s, const struct spine_cfg *cfg, uint16_t nsteps)
{
    cp_real scale = CP_R(0.0), rmax, ext;
    int e, i;
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
    for (i = 0; i < 12; i++) {
        cp_real q = cp_fabs(s->sp[i]);
        scale = q > scale ? q : scale;
    }
    if (s->law == SPINE_R_CUBIC) {
        sp_power(s->rp, 1);
    }
    if (s->kind == SPINE_BEZIER) {
        cp_real ctl[12];
        memcpy(ctl, s->sp, sizeof ctl);
        sp_power(s->sp, 3);
        e = sp_samples(s, scale, &rmax, &ext);
        if (e == CP_OK) {
            e = sp_axis_bezier(s, ctl);
        }
    } else {
        e = sp_samples(s, scale, &rmax, &ext);
    }
    if (e != CP_OK) {
        return e;
    }
    e = sp_frame0(s, cfg->ref);
    if (e == CP_OK) {
        e = sp_seam(s, ext, rmax);
    }
    if (e != CP_OK) {
        return e;
    }
    sp_restart(s);
    return CP_OK;
}

/* ---------------------------------------------------------------------- march */

/* The generator A = [[-d, s + r], [s - r, d]] (as g = (d, s, r)) and its u-derivative gd at
 * a jet with frame f (MATH-spine 9.7):
 *   p = c_uu.P, q = c_uu.Q, v_u = c_uu.T, W = sqrt(v^2 - R_u^2), f = R_u / (2 v W),
 *   eta = E / (2 v G), tau = P_u.Q = -2 eta q,
 *   g = (f p, f q, eta q),
 *   p_u = c_uuu.P - p v_u / v + tau q,  q_u = c_uuu.Q - q v_u / v - tau p,
 *   f_u = (R_uu - R_u (v_u / v + W_u / W)) / (2 v W),  W_u = (v v_u - R_u R_uu) / W,
 *   eta_u = (E_u - E (v_u / v + G_u / G)) / (2 v G),  E_u = (e.c_uu - E v_u) / v,
 *   G_u = -E E_u / G,
 *   gd = (f_u p + f p_u, f_u q + f q_u, eta_u q + eta q_u).
 * Rounding: a few ulp relative each; W loses digits only as |a| -> 1 (refused at init), G
 * as e comes near T (a Bezier's axis keeps G >= SPINE_AXIS_MIN). */
static void sp_gen(const struct spine *s, const struct spine_jet *j, const struct sp_frame *fr,
                   cp_real g[3], cp_real gd[3])
{
    cp_real v = fr->v, p = cp_v3_dot(&j->cuu, &fr->p), q = cp_v3_dot(&j->cuu, &fr->q);
    cp_real vu = cp_v3_dot(&j->cuu, &fr->t) , lv = vu / v;
    cp_real w = cp_sqrt((v - j->ru) * (v + j->ru));
    cp_real f = j->ru / (CP_R(2.0) * v * w);
    cp_real eta = fr->e / (CP_R(2.0) * v * fr->g);
    cp_real tau = CP_R(-2.0) * eta * q;
    cp_real pu = cp_v3_dot(&j->cuuu, &fr->p) - p * lv + tau * q;
    cp_real qu = cp_v3_dot(&j->cuuu, &fr->q) - q * lv - tau * p;
    cp_real wu = (v * vu - j->ru * j->ruu) / w;
    cp_real fu = (j->ruu - j->ru * (lv + wu / w)) / (CP_R(2.0) * v * w);
    cp_real eu = (cp_v3_dot(&s->ax, &j->cuu) - fr->e * vu) / v;
    cp_real gu = -fr->e * eu / fr->g;
    cp_real etau = (eu - fr->e * (lv + gu / fr->g)) / (CP_R(2.0) * v * fr->g);
    g[0] = f * p;
    g[1] = f * q;
    g[2] = eta * q;
    gd[0] = fu * p + f * pu;
    gd[1] = fu * q + f * qu;
    gd[2] = etau * q + eta * qu;
}

/* o = X M for X = [[-x0, x1 + x2], [x1 - x2, x0]] */
static void sp_xm(const cp_real x[3], const cp_real m[4], cp_real o[4])
{
    cp_real a = x[1] + x[2], b = x[1] - x[2];
    o[0] = -x[0] * m[0] + a * m[2];
    o[1] = -x[0] * m[1] + a * m[3];
    o[2] = b * m[0] + x[0] * m[2];
    o[3] = b * m[1] + x[0] * m[3];
}

/* One Magnus-4 step over [u, u + h] (h = +-1/N) from the node values (g0, gd0) to (g1, gd1),
 * on M in place. The two-point Hermite rule with the commutator term:
 *   Omega = (h/2)(A0 + A1) + (h^2/12)(A0' - A1') - (h^2/12)[A0, A1],
 * with [X, Y] = (2(s1 r2 - r1 s2), -2(d1 r2 - r1 d2), -2(d1 s2 - s1 d2)) in (d, s, r) (X = d Z
 * + s S + r J, Z = diag(-1, 1), S = [[0, 1], [1, 0]], J = [[0, 1], [-1, 0]]; [Z, S] = -2J,
 * [Z, J] = -2S, [S, J] = 2Z). Expanded about the midpoint, the first term with the second
 * is h a0 + h^3 a2 / 12 + O(h^5) (Omega1 to local order 5: error h^5 A''''/720), and the
 * third is Omega2 = -(h^3/12)[a0, a1] + O(h^5): order 4 globally, like Simpson's nodes but
 * with one jet per step instead of two.
 * exp: Omega^2 = d2 I, d2 = d^2 + s^2 - r^2 (Z S J anticommute, Z^2 = S^2 = I, J^2 = -I), so
 * exp(Omega) = C I + S Omega with C - 1 = d2 (1/2 + d2 (1/24 + d2/720)), S = 1 + d2 (1/6 +
 * d2 (1/120 + d2/5040)) for either sign of d2: truncation <= d2^4/8! relative. The iterator
 * keeps (|d| + |s| + |r|) |h| <= SPINE_STEP_MAX = 1/4 at the nodes and midpoints, so
 * |d2| <~ 1/16 and the truncation is below 4e-10.
 * Increment form M += (C - 1) M + S Omega M: the O(1) part of exp(Omega) is never rounded.
 * Inverse: the step from node 1 back to node 0 (the same call with the node values swapped
 * and -h) computes exactly -Omega (every term changes sign, IEEE sums and products are
 * commutative), whose exponential is the inverse of the forward step's: a backward pass
 * makes the forward truncation error, node by node; only the rounding differs. */
static void sp_magnus(cp_real m[4], const cp_real g0[3], const cp_real gd0[3],
                      const cp_real g1[3], const cp_real gd1[3], cp_real h)
{
    cp_real h2 = h / CP_R(2.0), hh = h * h / CP_R(12.0), om[3], dm[4], cm1, sh, d2;
    int i;
    cp_real cd = CP_R(2.0) * (g0[1] * g1[2] - g0[2] * g1[1]);
    cp_real cs = CP_R(-2.0) * (g0[0] * g1[2] - g0[2] * g1[0]);
    cp_real cr = CP_R(-2.0) * (g0[0] * g1[1] - g0[1] * g1[0]);
    om[0] = h2 * (g0[0] + g1[0]) + hh * (gd0[0] - gd1[0]) - hh * cd;
    om[1] = h2 * (g0[1] + g1[1]) + hh * (gd0[1] - gd1[1]) - hh * cs;
    om[2] = h2 * (g0[2] + g1[2]) + hh * (gd0[2] - gd1[2]) - hh * cr;
    d2 = om[0] * om[0] + om[1] * om[1] - om[2] * om[2];
    cm1 = d2 * (CP_R(0.5) + d2 * (CP_R(1.0) / CP_R(24.0) + d2 / CP_R(720.0)));
    sh = CP_R(1.0) + d2 * (CP_R(1.0) / CP_R(6.0) + d2 * (CP_R(1.0) / CP_R(120.0) +
                                                         d2 / CP_R(5040.0)));
    sp_xm(om, m, dm);
    for (i = 0; i < 4; i++) {
        m[i] += cm1 * m[i] + sh * dm[i];
    }
}

/* The interval interpolant: M on [lo, lo + 1/N] as sum_i pc[i] t^i (t in [0, 1]), the
 * quintic Hermite polynomial of (M, H M', H^2 M'') at both ends (H = 1/N, M' = A M,
 * M'' = A' M + A^2 M = A' M + (d^2 + s^2 - r^2) M). With D = M1 - c0 - c1 - c2, D' = H M1' -
 * c1 - 2 c2, D'' = H^2 M1'' - 2 c2: c3 = 10 D - 4 D' + D''/2, c4 = -15 D + 7 D' - D'',
 * c5 = 6 D - 3 D' + D''/2. Error H^6 |M^(6)| / 46080 (MATH-spine 9.7: ~1e-9 relative on the
 * helix tube at N = 32). Rounding: D carries a few ulp of |M| into c3..c5 with the weights
 * of the Hermite basis H5(t) = 10 t^3 - 15 t^4 + 6 t^5 in [0, 1], so the sum keeps a few
 * ulp of |M|; at t = 0 it is c0 = M(lo) exactly. */
static void sp_interval(struct spine *s, const cp_real m0[4], const cp_real g0[3],
                        const cp_real gd0[3], const cp_real m1[4], const cp_real g1[3],
                        const cp_real gd1[3])
{
    /* pc[] holds the end data first (no scratch arrays on the stack): pc[1] = H A0 M0,
     * pc[2] = A0' M0, pc[3] = H A1 M1, pc[4] = A1' M1; then each entry's coefficients */
    cp_real hs = CP_R(1.0) / (cp_real)s->nsteps, h2 = hs * hs;
    cp_real qa = g0[0] * g0[0] + g0[1] * g0[1] - g0[2] * g0[2];
    cp_real qb = g1[0] * g1[0] + g1[1] * g1[1] - g1[2] * g1[2];
    int i;
    sp_xm(g0, m0, s->pc[1]);
    sp_xm(gd0, m0, s->pc[2]);
    sp_xm(g1, m1, s->pc[3]);
    sp_xm(gd1, m1, s->pc[4]);
    for (i = 0; i < 4; i++) {
        cp_real d1a = hs * s->pc[1][i], d2a = h2 * (s->pc[2][i] + qa * m0[i]);
        cp_real d1b = hs * s->pc[3][i], d2b = h2 * (s->pc[4][i] + qb * m1[i]);
        cp_real c2 = CP_R(0.5) * d2a;
        cp_real dd = ((m1[i] - m0[i]) - d1a) - c2, dd1 = (d1b - d1a) - d2a, dd2 = d2b - d2a;
        s->pc[0][i] = m0[i];
        s->pc[1][i] = d1a;
        s->pc[2][i] = c2;
        s->pc[3][i] = CP_R(10.0) * dd - CP_R(4.0) * dd1 + CP_R(0.5) * dd2;
        s->pc[4][i] = CP_R(-15.0) * dd + CP_R(7.0) * dd1 - dd2;
        s->pc[5][i] = CP_R(6.0) * dd - CP_R(3.0) * dd1 + CP_R(0.5) * dd2;
    }
}

/* The march at node 0: M = M(0) (the rotation by phi0/2), A and A' there. */
static void sp_restart(struct spine *s)
{
    struct spine_jet j;
    struct sp_frame f;
    spine_jet(s, CP_R(0.0), &j);
    sp_frame(s, &j, &f);
    sp_gen(s, &j, &f, s->g, s->gd);
    s->m[0] = s->z0[0];
    s->m[1] = s->z0[1];
    s->m[2] = -s->z0[1];
    s->m[3] = s->z0[0];
    s->node = 0u;
    s->back = 0u;
}

/* One march step from node k to k + dir (dir = +1 forward, -1 back): the jet, frame and
 * generator at the new node, the Magnus step, the interval's interpolant (from the lower
 * node). The new node's u is k1 / N with an integer k1: 0 and 1 exactly at the ends. */
static void sp_step(struct spine *s, int dir)
{
    struct spine_jet j;
    struct sp_frame f;
    cp_real g[3], gd[3], m0[4];
    uint32_t k1 = dir > 0 ? s->node + 1u : s->node - 1u;
    int i;
    spine_jet(s, (cp_real)k1 / (cp_real)s->nsteps, &j);
    sp_frame(s, &j, &f);
    sp_gen(s, &j, &f, g, gd);
    for (i = 0; i < 4; i++) {
        m0[i] = s->m[i];
    }
    sp_magnus(s->m, s->g, s->gd, g, gd, dir > 0 ? CP_R(1.0) / (cp_real)s->nsteps
                                                : CP_R(-1.0) / (cp_real)s->nsteps);
    if (dir > 0) {
        sp_interval(s, m0, s->g, s->gd, s->m, g, gd);
    } else {
        sp_interval(s, s->m, g, gd, m0, s->g, s->gd);
    }
    for (i = 0; i < 3; i++) {
        s->g[i] = g[i];
        s->gd[i] = gd[i];
    }
    s->node = (uint16_t)k1;
    s->back = dir < 0 ? 1u : 0u;
}

/* Bring the march to node k on the forward (back = 0) or backward pass. Forward: on from
 * the current node, or restart when the state is backward or ahead of k. Backward: a
 * forward state first goes on to N (once per pass); a backward state behind k restarts. */
static void sp_march(struct spine *s, uint32_t k, uint8_t back)
{
    if (!back) {
        if (s->back || k < s->node) {
            sp_restart(s);
        }
        while (s->node < k) { /* at most N steps: node rises by one each */
            sp_step(s, 1);
        }
        return;
    }
    if (s->back && k > s->node) {
        sp_restart(s);
    }
    if (!s->back) {
        while (s->node < s->nsteps) { /* at most N steps */
            sp_step(s, 1);
        }
    }
    while (s->node > k) { /* at most N steps: node falls by one each */
        sp_step(s, -1);
    }
}

/* o = k a */
static void sp_scale(struct cp_vec3 *o, cp_real k, const struct cp_vec3 *a)
{
    o->x = k * a->x;
    o->y = k * a->y;
    o->z = k * a->z;
}

/* Entry i of the interval's interpolant at t (Horner). */
static CP_ALWAYS_INLINE cp_real sp_horner5(const struct spine *s, int i, cp_real t)
{
    return ((((s->pc[5][i] * t + s->pc[4][i]) * t + s->pc[3][i]) * t + s->pc[2][i]) * t +
            s->pc[1][i]) * t + s->pc[0][i];
}

/* The point part of spine_eval: the jet's T, a, b and the frame terms in closed form,
 * P = (e - E T) / G, Q = (T x e) / G, G = sqrt(1 - E^2) (sp_frame's frame to a few ulp),
 * bn1 = b P and bn2 = b Q with b / G formed once. Inlined: the streaming path's only user. */
static CP_ALWAYS_INLINE void sp_state(const struct spine *s, const struct spine_jet *j,
                                      struct spine_state *st, struct cp_vec3 *tx, cp_real *g)
{
    const struct cp_vec3 *x = &s->ax;
    cp_real v = cp_sqrt(j->cu.x * j->cu.x + j->cu.y * j->cu.y + j->cu.z * j->cu.z), e, bg;
    struct cp_vec3 t;
    t.x = j->cu.x / v;
    t.y = j->cu.y / v;
    t.z = j->cu.z / v;
    st->t = t;
    st->c = j->c;
    st->r = j->r;
    st->a = j->ru / v;
    st->b = cp_sqrt((CP_R(1.0) - st->a) * (CP_R(1.0) + st->a));
    e = x->x * t.x + x->y * t.y + x->z * t.z;
    *g = cp_sqrt((CP_R(1.0) - e) * (CP_R(1.0) + e));
    bg = st->b / *g;
    tx->x = t.y * x->z - t.z * x->y;
    tx->y = t.z * x->x - t.x * x->z;
    tx->z = t.x * x->y - t.y * x->x;
    st->bn1.x = bg * (x->x - e * t.x);
    st->bn1.y = bg * (x->y - e * t.y);
    st->bn1.z = bg * (x->z - e * t.z);
    st->bn2.x = bg * tx->x;
    st->bn2.y = bg * tx->y;
    st->bn2.z = bg * tx->z;
    st->at.x = -st->a * t.x;
    st->at.y = -st->a * t.y;
    st->at.z = -st->a * t.z;
}

int spine_eval(struct spine *s, uint32_t num, uint32_t den, uint8_t back, uint8_t full,
               struct spine_state *st)
{
    struct spine_jet j;
    struct cp_vec3 tx;
    uint32_t k, rem;
    cp_real u, g;
    if (s == NULL || st == NULL || den == 0u || den > 65535u || num > den) {
        return CP_ERR_RANGE;
    }
    k = (num * (uint32_t)s->nsteps) / den; /* <= 65535 * 1024 < 2^32 */
    rem = (num * (uint32_t)s->nsteps) % den;
    u = (cp_real)num / (cp_real)den;
    if (rem == 0u) { /* a node: its own M */
        sp_march(s, k, back);
        st->m[0] = s->m[0];
        st->m[1] = s->m[1];
        st->m[2] = s->m[2];
        st->m[3] = s->m[3];
    } else { /* inside [k, k + 1]: the interpolant, Horner in t */
        cp_real t = (cp_real)rem / (cp_real)den;
        sp_march(s, back ? k : k + 1u, back);
        st->m[0] = sp_horner5(s, 0, t);
        st->m[1] = sp_horner5(s, 1, t);
        st->m[2] = sp_horner5(s, 2, t);
        st->m[3] = sp_horner5(s, 3, t);
    }
    sp_jet(s, u, full, &j);
    st->u = u;
    st->node = (uint16_t)k;
    sp_state(s, &j, st, &tx, &g);
    if (full) {
        cp_real v2 = cp_v3_dot(&j.cu, &j.cu);
        sp_scale(&st->n1, CP_R(1.0) / st->b, &st->bn1);
        sp_scale(&st->n2, CP_R(1.0) / g, &tx);
        st->as = (j.ruu - st->a * cp_v3_dot(&j.cuu, &st->t)) / v2;
        st->k1 = cp_v3_dot(&j.cuu, &st->n1) / v2;
        st->k2 = cp_v3_dot(&j.cuu, &st->n2) / v2;
    }
    if (!cp_finite(st->m[0] + st->m[1] + st->m[2] + st->m[3]) ||
        !cp_finite(st->c.x + st->c.y + st->c.z + st->b)) {
        return CP_ERR_NUMERIC;
    }
    return CP_OK;
}

int spine_node(struct spine *s, uint16_t i, struct spine_state *st)
{
    if (s == NULL || i > s->nsteps) {
        return CP_ERR_RANGE;
    }
    return spine_eval(s, i, s->nsteps, 0u, 1u, st);
}

int spine_node_back(struct spine *s, uint16_t i, struct spine_state *st)
{
    if (s == NULL || i > s->nsteps) {
        return CP_ERR_RANGE;
    }
    return spine_eval(s, i, s->nsteps, 1u, 1u, st);
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

/* The label theta0 of label index l (0..nl). (Not inlined: LTO had copied it into
 * sp_emit and into sp_check_at's label loop.) */
static CP_NOINLINE cp_real sp_lab(const struct spine_path *it, uint32_t l)
{
    if (it->nl == 0u) {
        return it->u0;
    }
    return it->u0 + (it->u1 - it->u0) * ((cp_real)l / (cp_real)it->nl);
}

/* Point k as (u = num / den, label index l); line and index for raster_pt. The pass of a
 * point (*back): the odd lines of LINES and their links are on the backward pass. */
static void sp_where(const struct spine_path *it, uint32_t k, uint32_t *num, uint32_t *l,
                     uint8_t *back, struct raster_at *at)
{
    uint32_t lk = (uint32_t)it->head.link + 1u;
    raster_locate(k, it->head.steps, it->head.link, at);
    if (it->head.mode == RASTER_LINES) {
        *num = at->i;
        *l = at->j * lk + at->a;
        *back = (uint8_t)(at->j & 1u);
    } else {
        *num = at->j * lk + at->a;
        *l = at->i;
        *back = 0u;
    }
}

/* The emitted point at (u = num / den, label l) on the forward or backward pass: the tool
 * centre c + (R - r) n (CENTRE), the surface (r = 0: SURFACE), the tip (TIP). */
static int sp_emit(struct spine_path *it, uint32_t num, uint32_t l, uint8_t back,
                   struct raster_pt *pt)
{
    struct spine_state st;
    int err = spine_eval(&it->s, num, it->den, back, 0u, &st);
    if (err != CP_OK) {
        return err;
    }
    if (l != it->lab_l) { /* the label is a function of l alone: caching keeps seeks exact */
        spine_label(sp_lab(it, l), &it->lab);
        it->lab_l = l;
    }
    spine_point_label(&st, &it->lab, -it->tool_r, pt);
    if (it->output == RASTER_OUT_TIP) {
        pt->p.z -= it->tool_r;
    }
    return cp_finite(pt->p.x + pt->p.y + pt->p.z) ? CP_OK : CP_ERR_NUMERIC;
}

/* D > 0 at (num / den, every label of the patch) on the surface and the tool-centre
 * surface. */
static int sp_check_at(struct spine_path *it, uint32_t num, uint32_t den)
{
    struct spine_state st;
    uint32_t l;
    int err = spine_eval(&it->s, num, den, 0u, 1u, &st);
    for (l = 0; l <= it->nl && err == CP_OK; l++) {
        struct spine_label lab;
        cp_real ct, sn, d0, d1;
        spine_label(sp_lab(it, l), &lab);
        spine_angle(&st, &lab, &ct, &sn);
        d0 = spine_regularity(&st, ct, sn, CP_R(0.0));
        d1 = spine_regularity(&st, ct, sn, -it->tool_r);
        if (!cp_finite(d0 + d1)) {
            err = CP_ERR_NUMERIC;
        } else if (!(d0 > CP_R(0.0)) || !(d1 > CP_R(0.0))) {
            err = CP_ERR_CUSP;
        }
    }
    return err;
}

/* D > 0 at every streamed u and every march node (two forward sweeps). */
static CP_NOINLINE int sp_check_patch(struct spine_path *it)
{
    uint32_t i;
    int err = CP_OK;
    for (i = 0; i <= it->den && err == CP_OK; i++) {
        err = sp_check_at(it, i, it->den);
    }
    for (i = 0; i <= it->s.nsteps && err == CP_OK; i++) {
        err = sp_check_at(it, i, it->s.nsteps);
    }
    return err;
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

/* The raster's counts: steps per line (LINES) or circle (CIRCLES) and link; den, the
 * denominator of every streamed u. CP_ERR_TOO_MANY when den would exceed 65535. */
static int sp_setup(struct spine_path *it, uint32_t steps, uint32_t link)
{
    uint32_t den = it->head.mode == RASTER_LINES
                       ? steps
                       : (it->head.n > 1u ? (uint32_t)(it->head.n - 1u) : 1u) * (link + 1u);
    if (den > 32767u) { /* sp_walk_links evaluates at u = num / (2 den) */
        return CP_ERR_TOO_MANY;
    }
    it->head.steps = steps;
    it->head.link = (uint16_t)link;
    it->den = (uint16_t)den;
    return CP_OK;
}

/* The march's N by step doubling (spine.h): from SPINE_PATH_NMIN, each step of the march at
 * N against two half steps from the same M (the midpoint's A and A' from one more jet):
 * their difference is 15/16 of the full step's local error (order 4: local h^5). The
 * estimate is 2 (R_max + tool_r) sum_k (|dM_k| - 8 eps |M|)+ |M_{k+1}| / 15 (max norms: an
 * error dM in M turns a line's angle by at most 2 |dM| |M^-1| and |M^-1| = |M| in SL(2);
 * the 8 eps |M| take out the two schemes' rounding, which is not truncation). Accepted at
 * <= SPINE_MARCH_TOL with every step's (|d| + |s| + |r|) |h| <= SPINE_STEP_MAX; else N
 * doubles; CP_ERR_TOL past SPINE_NSTEPS_MAX. Leaves the march initialized at the chosen N. */
static CP_NOINLINE int sp_pick_n(struct spine_path *it, const struct spine_cfg *cfg)
{
    uint32_t n, k;
    int err, i;
    for (n = SPINE_PATH_NMIN; n <= SPINE_NSTEPS_MAX; n *= 2u) {
        struct spine *s = &it->s;
        cp_real h = CP_R(1.0) / (cp_real)n, sum = CP_R(0.0), wide = CP_R(0.0), rmax = s->rmin;
        err = spine_init(s, cfg, (uint16_t)n);
        if (err != CP_OK) {
            return err;
        }
        for (k = 0; k < n; k++) {
            struct spine_jet j;
            struct sp_frame f;
            cp_real gh[3], gdh[3], mh[4], dm = CP_R(0.0), mm = CP_R(0.0), w;
            spine_jet(s, ((cp_real)k + CP_R(0.5)) * h, &j);
            sp_frame(s, &j, &f);
            sp_gen(s, &j, &f, gh, gdh);
            rmax = j.r > rmax ? j.r : rmax;
            for (i = 0; i < 4; i++) {
                mh[i] = s->m[i];
            }
            sp_magnus(mh, s->g, s->gd, gh, gdh, CP_R(0.5) * h);
            sp_step(s, 1);
            sp_magnus(mh, gh, gdh, s->g, s->gd, CP_R(0.5) * h);
            for (i = 0; i < 4; i++) {
                cp_real e = cp_fabs(s->m[i] - mh[i]), a = cp_fabs(s->m[i]);
                dm = e > dm ? e : dm;
                mm = a > mm ? a : mm;
            }
            dm -= CP_R(8.0) * CP_REAL_EPS * mm;
            sum += dm > CP_R(0.0) ? dm * mm : CP_R(0.0);
            w = (cp_fabs(s->g[0]) + cp_fabs(s->g[1]) + cp_fabs(s->g[2])) * h;
            wide = w > wide ? w : wide;
            w = (cp_fabs(gh[0]) + cp_fabs(gh[1]) + cp_fabs(gh[2])) * h;
            wide = w > wide ? w : wide;
        }
        if (!cp_finite(sum + wide)) {
            return CP_ERR_NUMERIC;
        }
        if (CP_R(2.0) * (rmax + it->tool_r) * sum / CP_R(15.0) <= SPINE_MARCH_TOL &&
            wide <= SPINE_STEP_MAX) {
            sp_restart(s);
            return CP_OK;
        }
    }
    return CP_ERR_TOL;
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

/* The step sagitta of the raster (head.steps): the largest second difference / 8 along
 * every line (LINES: one forward sweep per line) or circle (CIRCLES), on the emitted
 * ball-centre (or surface) points. */
static CP_NOINLINE int sp_walk_steps(struct spine_path *it, cp_real *sag)
{
    uint32_t j, i, steps = it->head.steps, lk = (uint32_t)it->head.link + 1u;
    cp_real dv = it->u1 - it->u0;
    *sag = CP_R(0.0);
    for (j = 0; j < it->head.n; j++) {
        struct raster_pt pt;
        struct cp_vec3 p[3]; /* the last three points; p[0], p[1] are read from i = 2 on */
        struct spine_state st;
        cp_real fj = it->head.n > 1u ? (cp_real)j / (cp_real)(it->head.n - 1u) : CP_R(0.0);
        for (i = 0; i < 3u; i++) {
            p[i].x = p[i].y = p[i].z = CP_R(0.0);
        }
        for (i = 0; i <= steps; i++) {
            cp_real th;
            int err = CP_OK;
            if (it->head.mode == RASTER_LINES) {
                err = spine_eval(&it->s, i, it->den, 0u, 0u, &st);
                th = it->u0 + dv * fj;
            } else {
                if (i == 0u) {
                    err = spine_eval(&it->s, it->head.n > 1u ? j * lk : 0u, it->den, 0u, 0u, &st);
                }
                th = it->u0 + dv * ((cp_real)i / (cp_real)steps);
            }
            if (err != CP_OK) {
                return err;
            }
            spine_point(&st, th, -it->tool_r, &pt);
            p[0] = p[1];
            p[1] = p[2];
            p[2] = pt.p;
            if (i >= 2u) {
                cp_real e = sp_sag3(&p[0], &p[1], &p[2]);
                if (!cp_finite(e)) {
                    return CP_ERR_NUMERIC;
                }
                *sag = e > *sag ? e : *sag;
            }
        }
    }
    return CP_OK;
}

/* CIRCLES: the link sagitta, |P(mid) - (P(a) + P(b))/2| of every link segment (u = a / den,
 * (2a + 1) / (2 den), (a + 1) / den) on the lines theta0 = u0 and u1 (where the circles
 * stop), one forward sweep each. */
static CP_NOINLINE int sp_walk_links(struct spine_path *it, cp_real *sag)
{
    uint32_t e, a, den = it->den;
    *sag = CP_R(0.0);
    for (e = 0; e < 2u; e++) {
        cp_real th = e ? it->u1 : it->u0;
        struct raster_pt pa, pm, pb;
        struct spine_state st;
        int err = spine_eval(&it->s, 0u, den, 0u, 0u, &st);
        if (err != CP_OK) {
            return err;
        }
        spine_point(&st, th, -it->tool_r, &pa);
        for (a = 0; a < den; a++) {
            struct cp_vec3 d;
            cp_real x;
            err = spine_eval(&it->s, 2u * a + 1u, 2u * den, 0u, 0u, &st);
            if (err == CP_OK) {
                spine_point(&st, th, -it->tool_r, &pm);
                err = spine_eval(&it->s, a + 1u, den, 0u, 0u, &st);
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
static CP_NOINLINE int sp_fit(struct spine_path *it, const struct raster_cfg *rc, uint32_t *link)
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
        err = sp_setup(it, fit.m[0], fit.m[1] - 1u);
        if (err == CP_ERR_TOO_MANY) {
            err = CP_ERR_TOL;
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

/* raster_overlap_check's ball at u: the sphere of the spine itself, centre c(u), radius
 * R(u) (the surface is its envelope; the inside tool's ball lies in it). */
static int sp_ball(const void *ctx, cp_real u, struct cp_vec3 *c, cp_real *r)
{
    struct spine_jet j;
    spine_jet(ctx, u, &j);
    *c = j.c;
    *r = j.r;
    return CP_OK; /* (finite: spine_init's samples bound every parameter) */
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
    it->head.overlap = 0u;
    err = spine_init(&it->s, cfg, 1u); /* the geometry's checks first (N set below) */
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
    if (!(it->tool_r < it->s.rmin)) {
        return CP_ERR_TOOL;
    }
    err = sp_pick_n(it, cfg);
    if (err != CP_OK) {
        return err;
    }
    if (!(it->tool_r < it->s.rmin)) { /* the finer samples of the chosen N */
        return CP_ERR_TOOL;
    }
    link = rc->link == RASTER_LINK_AUTO ? 0u : rc->link; /* LINES AUTO: derived below */
    if (rc->steps == 0u || (rc->mode == RASTER_CIRCLES && rc->link == RASTER_LINK_AUTO)) {
        err = sp_fit(it, rc, &link);
    } else {
        err = sp_setup(it, rc->steps, link);
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
    err = sp_setup(it, it->head.steps, link); /* the final link (and CIRCLES: its den) */
    if (err != CP_OK) {
        return err;
    }
    it->nl = (uint16_t)(rc->mode == RASTER_LINES ? (uint32_t)(rc->n - 1u) * (link + 1u)
                                                 : it->head.steps);
    err = sp_check_patch(it);
    if (err == CP_OK) { /* last: far parts whose spheres meet (reported: the tool inside) */
        err = raster_overlap_report(sp_ball, &it->s, &it->head);
    }
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
    uint32_t num, l;
    uint8_t back;
    int err;
    if (it->head.k >= it->head.count) {
        return CP_ERR_DONE;
    }
    sp_where(it, it->head.k, &num, &l, &back, &at);
    err = sp_emit(it, num, l, back, pt);
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
