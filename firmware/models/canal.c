/* canal.c - canal surface touching z = 0 along a plane curve: jets, frame, points.
 * SPDX-License-Identifier: MIT
 *
 * Mathematics: MATH-canal §2.2 (contact frame), §5.2 (one quadrature, stereographic
 * point, homogeneous labels, regularity D), §9 (streaming algorithm).
 */
#include "canal.h"
#include "cp_math.h"
#include "raster.h" /* raster_seam_check */

/* Number of used parameters per kind. */
static const uint8_t curve_nparams[4] = {
    [CANAL_LINE] = 4u, [CANAL_ARC] = 5u, [CANAL_ELLIPSE] = 6u, [CANAL_BEZIER] = 8u};
static const uint8_t radius_nparams[4] = {
    [CANAL_R_CONST] = 1u, [CANAL_R_LINEAR] = 2u, [CANAL_R_COS] = 3u, [CANAL_R_CUBIC] = 4u};

/* Grid steps of |C'|^2 used to bracket the minimum speed of a Bezier, and the zoom
 * rounds inside the bracket (fixed counts; bezier_min_speed). */
#define BEZIER_SPEED_SAMPLES 64
#define BEZIER_SPEED_ROUNDS 10

/* Does [lo, hi] contain off + 2 pi m for some integer m? */
static int contains_phase(cp_real lo, cp_real hi, cp_real off)
{
    cp_real m = cp_ceil((lo - off) / CP_TWO_PI);
    return off + CP_TWO_PI * m <= hi;
}

/* Widen [lo[0], lo[1]] (min, max) to contain v. */
static void widen(cp_real *lo, cp_real v)
{
    lo[0] = v < lo[0] ? v : lo[0];
    lo[1] = v > lo[1] ? v : lo[1];
}

static cp_real bern3(const cp_real *r, cp_real s)
{
    cp_real u = CP_R(1.0) - s;
    return r[0] * u * u * u + CP_R(3.0) * r[1] * s * u * u + CP_R(3.0) * r[2] * s * s * u +
           r[3] * s * s * s;
}

/* Derivatives d/ds, d2/ds2 of the cubic Bernstein polynomial with coefficients c[0],
 * c[st], c[2 st], c[3 st] at s (u = 1 - s): the Bezier coordinates (stride 2) and the
 * CUBIC radius law (stride 1) share it. */
static CP_NOINLINE void bern3_d(const cp_real *c, unsigned st, cp_real s, cp_real u, cp_real *d,
                                cp_real *dd)
{
    cp_real c0 = c[0], c1 = c[st], c2 = c[2u * st], c3 = c[3u * st];
    *d = CP_R(3.0) * ((c1 - c0) * u * u + CP_R(2.0) * (c2 - c1) * s * u + (c3 - c2) * s * s);
    *dd = CP_R(6.0) * ((c2 - CP_R(2.0) * c1 + c0) * u + (c3 - CP_R(2.0) * c2 + c1) * s);
}

/* Exact range of R over the normalized parameter s in [0, 1]. */
static void radius_range(const struct canal *c, cp_real *range)
{
    const cp_real *rp = c->rp;
    range[0] = rp[0];
    range[1] = rp[0];
    switch (c->radius) {
    case CANAL_R_CONST:
        break;
    case CANAL_R_LINEAR:
        widen(range, rp[1]);
        break;
    case CANAL_R_COS: {
        /* b cos(phi) + c over the phase interval ph = [min, max] of phi = k theta over the
         * travelled theta interval: its values at both ends, and b + c (cos = 1) or c - b
         * (cos = -1) where the interval contains a phase 0 or pi (mod 2 pi) */
        cp_real th0 = CP_R(0.0), th1 = CP_TWO_PI, ph[2], sn, cs, b = rp[0], cc = rp[1];
        unsigned e;
        if (c->curve == CANAL_ARC || c->curve == CANAL_ELLIPSE) {
            th0 = (cp_real)c->dir * c->t0;
            th1 = (cp_real)c->dir * c->t1;
        }
        ph[0] = rp[2] * th0;
        ph[1] = ph[0];
        widen(ph, rp[2] * th1);
        range[0] = CP_R(3.0e38); /* above any candidate: the first widen sets both */
        range[1] = -CP_R(3.0e38);
        for (e = 0; e < 2u; e++) {
            cp_sincos(ph[e], &sn, &cs);
            widen(range, b * cs + cc);
            if (contains_phase(ph[0], ph[1], e ? CP_PI : CP_R(0.0))) {
                widen(range, e ? cc - b : b + cc);
            }
        }
        break;
    }
    default: { /* CANAL_R_CUBIC: endpoints and the roots of R'(s) in (0, 1) */
        cp_real d0 = rp[1] - rp[0], d1 = rp[2] - rp[1], d2 = rp[3] - rp[2];
        cp_real qa = d0 - CP_R(2.0) * d1 + d2, qb = CP_R(2.0) * (d1 - d0), qc = d0;
        cp_real roots[2];
        int nr = 0, i;
        widen(range, rp[3]);
        if (cp_fabs(qa) <= CP_R(1e-12) * (cp_fabs(qb) + cp_fabs(qc))) { /* qa = 0 included */
            if (qb != CP_R(0.0)) {
                roots[nr++] = -qc / qb;
            }
        } else {
            cp_real disc = qb * qb - CP_R(4.0) * qa * qc;
            if (disc >= CP_R(0.0)) {
                cp_real sq = cp_sqrt(disc);
                cp_real qq = qb >= CP_R(0.0) ? -CP_R(0.5) * (qb + sq) : -CP_R(0.5) * (qb - sq);
                roots[nr++] = qq / qa;
                if (qq != CP_R(0.0)) {
                    roots[nr++] = qc / qq;
                }
            }
        }
        for (i = 0; i < nr; i++) {
            if (roots[i] > CP_R(0.0) && roots[i] < CP_R(1.0)) {
                widen(range, bern3(rp, roots[i]));
            }
        }
        break;
    }
    }
}

static void jet_eval(const struct canal *restrict c, cp_real t, struct canal_jet *restrict j,
                     int second);

/* |C'(s)|^2 of a Bezier, from its jet (every field of c that jet_eval reads is set). */
static cp_real bezier_speed2(const struct canal *p, cp_real s)
{
    struct canal_jet j;
    jet_eval(p, s, &j, 0);
    return j.dx * j.dx + j.dy * j.dy;
}

/* Minimum |C'| of a Bezier over [0, 1]: sample on a grid of step w = 1/64, then zoom:
 * each round samples the bracket [s_b - w, s_b + w] around the best sample s_b so far
 * in steps of w/4 (the 7 interior points), then w /= 4. |C'|^2 is a quartic: at most
 * two local minima, each wider than the grid spacing unless it is a near-cusp, which
 * the zoom resolves: once the bracket holds one minimum, it keeps holding it (the best
 * sample is within one step of it), so after BEZIER_SPEED_ROUNDS rounds s_b is within
 * 4^-10 / 64 = 1.5e-8 of it - below the float spacing of s in [1/2, 1]. Samples are
 * clamped to [0, 1] (the polynomial beyond the ends is not the curve). Fixed counts:
 * 1 + 64 + 7 BEZIER_SPEED_ROUNDS evaluations. */
static cp_real bezier_min_speed(const struct canal *p)
{
    cp_real w = CP_R(1.0) / (cp_real)BEZIER_SPEED_SAMPLES, lo = CP_R(0.0), sb = CP_R(0.0);
    cp_real best = bezier_speed2(p, CP_R(0.0));
    unsigned r, i, n = BEZIER_SPEED_SAMPLES;
    for (r = 0; r <= BEZIER_SPEED_ROUNDS; r++) {
        for (i = 1; i <= n; i++) {
            cp_real s = lo + (cp_real)i * w, v;
            s = s < CP_R(0.0) ? CP_R(0.0) : s;
            s = s > CP_R(1.0) ? CP_R(1.0) : s;
            v = bezier_speed2(p, s);
            if (v < best) {
                best = v;
                sb = s;
            }
        }
        lo = sb - w;
        w *= CP_R(0.25);
        n = 7u;
    }
    return cp_sqrt(best);
}

/* The first of an ARC's or ELLIPSE's parameters that is an angle (its last two); 8 (none)
 * for the other kinds. */
static unsigned first_angle(uint8_t curve)
{
    return (curve == CANAL_ARC || curve == CANAL_ELLIPSE) ? curve_nparams[curve] - 2u : 8u;
}

/* Copy the n used parameters v[0..n) into out[0..cnt) (the unused ones 0) and check them:
 * every used one finite (CP_ERR_NONFINITE, which wins over a range error), then in range
 * (CP_ERR_RANGE): |v| <= CANAL_COORD_MAX, from index `special` on |v| <= smax. (Not
 * inlined: one copy serves the curve's parameters and the law's.) */
static CP_NOINLINE int copy_params(cp_real *out, unsigned cnt, const cp_real *v, unsigned n,
                                   unsigned special, cp_real smax)
{
    unsigned i;
    int err = CP_OK;
    for (i = 0; i < cnt; i++) {
        cp_real x = i < n ? v[i] : CP_R(0.0);
        out[i] = x;
        if (!cp_finite(x)) {
            return CP_ERR_NONFINITE;
        }
        if (cp_fabs(x) > (i >= special ? smax : CANAL_COORD_MAX)) {
            err = CP_ERR_RANGE;
        }
    }
    return err;
}

/* The radius law's parameters into c->rp (copy_params): |v| <= CANAL_COORD_MAX, the k of a
 * COS law |k| <= CANAL_K_MAX. canal_radius_check and canal_init. */
static int law_params(struct canal *c, const struct canal_cfg *cfg)
{
    c->radius = cfg->radius;
    return copy_params(c->rp, 4u, cfg->rp, radius_nparams[cfg->radius],
                       cfg->radius == CANAL_R_COS ? 2u : 4u, CANAL_K_MAX);
}

/* canal_init, step 2: the parameter interval [t0, t1] of the curve (and dir), its least
 * speed cmin (not for a BEZIER: bezier_min_speed, once the fields the jet reads are set)
 * and its size (the scale of the degeneracy test) in *size. Errors: CP_ERR_RANGE (ARC or
 * ELLIPSE radius <= 0, sweep above CANAL_SPAN_MAX), CP_ERR_EMPTY (equal angles). */
static int curve_interval(struct canal *c, cp_real *size)
{
    unsigned i, na = first_angle(c->curve);
    switch (c->curve) {
    case CANAL_LINE: {
        cp_real dx = c->cp[2] - c->cp[0], dy = c->cp[3] - c->cp[1];
        c->t0 = CP_R(0.0);
        c->t1 = CP_R(1.0);
        c->cmin = cp_sqrt(dx * dx + dy * dy);
        *size = c->cmin;
        break;
    }
    case CANAL_ARC:
    case CANAL_ELLIPSE: {
        /* an ARC is an ellipse with A = B = r (as in jet_eval) */
        cp_real a0 = c->cp[na], a1 = c->cp[na + 1u];
        cp_real ra = c->cp[2], rb = c->curve == CANAL_ARC ? ra : c->cp[3];
        if (ra <= CP_R(0.0) || rb <= CP_R(0.0)) {
            return CP_ERR_RANGE;
        }
        c->cmin = ra < rb ? ra : rb;
        *size = ra > rb ? ra : rb;
        if (a0 == a1) {
            return CP_ERR_EMPTY;
        }
        if (cp_fabs(a1 - a0) > CANAL_SPAN_MAX * (CP_R(1.0) + CP_R(4.0) * CP_REAL_EPS)) {
            return CP_ERR_RANGE;
        }
        c->dir = a1 > a0 ? 1 : -1;
        c->t0 = (cp_real)c->dir * a0;
        c->t1 = (cp_real)c->dir * a1;
        break;
    }
    default: { /* CANAL_BEZIER */
        /* bounding box of the control points: bx = (xmin, xmax), by = (ymin, ymax) */
        cp_real bx[2], by[2];
        bx[0] = bx[1] = c->cp[0];
        by[0] = by[1] = c->cp[1];
        for (i = 1; i < 4u; i++) {
            widen(bx, c->cp[2u * i]);
            widen(by, c->cp[2u * i + 1u]);
        }
        *size = (bx[1] - bx[0]) > (by[1] - by[0]) ? (bx[1] - bx[0]) : (by[1] - by[0]);
        c->t0 = CP_R(0.0);
        c->t1 = CP_R(1.0);
        break; /* cmin below, once the fields the jet reads are set */
    }
    }
    return c->t1 > c->t0 ? CP_OK : CP_ERR_EMPTY;
}

/* canal_curve_check and canal_init, the curve alone: its parameters into c (copy_params:
 * |v| <= CANAL_COORD_MAX, the angles of an ARC/ELLIPSE |v| <= 4 pi), its interval
 * (curve_interval), least speed and the degeneracy test; its size (mm: the scale of the
 * degeneracy and seam tests) in *size_out. c->radius and c->rp must be set (a BEZIER's
 * speed is read from the jet, which evaluates R too). */
static int curve_setup(struct canal *c, const struct canal_cfg *cfg, cp_real *size_out)
{
    cp_real size = CP_R(0.0);
    int err = copy_params(c->cp, 8u, cfg->cp, curve_nparams[cfg->curve], first_angle(cfg->curve),
                          CP_R(2.0) * CP_TWO_PI);
    c->curve = cfg->curve;
    c->dir = 1;
    if (err == CP_OK) {
        err = curve_interval(c, &size);
    }
    if (err != CP_OK) {
        return err;
    }
    c->inv_span = CP_R(1.0) / (c->t1 - c->t0);
    c->kappa_const = (uint8_t)(c->curve == CANAL_ARC || c->curve == CANAL_LINE);
    c->kappa_c = c->curve == CANAL_ARC ? (cp_real)c->dir / c->cp[2] : CP_R(0.0);
    c->k_int = 0;
    c->dth = (c->curve == CANAL_ARC || c->curve == CANAL_ELLIPSE) ? (cp_real)c->dir : CP_TWO_PI;
    if (c->curve == CANAL_BEZIER) {
        c->cmin = bezier_min_speed(c);
    }
    *size_out = size;
    if (!(c->cmin > CP_R(1e-5) * size) || !(c->cmin > CP_R(1e-9))) {
        return CP_ERR_DEGENERATE;
    }
    return CP_OK;
}

/* (not inlined: its struct canal stays out of the protocol's line handler frame) */
CP_NOINLINE int canal_curve_check(const struct canal_cfg *cfg)
{
    struct canal c;
    cp_real size;
    unsigned i;
    if (cfg == NULL || cfg->curve > CANAL_BEZIER) {
        return CP_ERR_INVAL;
    }
    c.radius = CANAL_R_CONST; /* R = 1: read by a BEZIER's jet, not by the checks */
    for (i = 0; i < 4u; i++) {
        c.rp[i] = i == 0u ? CP_R(1.0) : CP_R(0.0);
    }
    return curve_setup(&c, cfg, &size);
}

int canal_radius_check(const struct canal_cfg *cfg)
{
    struct canal c;
    if (cfg == NULL || cfg->radius > CANAL_R_CUBIC) {
        return CP_ERR_INVAL;
    }
    return law_params(&c, cfg);
}

/* canal_init, last step: on a closed C (end point within RASTER_SEAM_GAP x size of the
 * start) R, dR/ds and d2R/ds2 (per arc length: the frame's p and dpds) at both ends go to
 * raster_seam_check, length scale the larger of size and max R. (Not inlined: its two
 * jets and frames stay out of the frame of canal_path_init, on the worst stack path.) */
static CP_NOINLINE int seam_check(const struct canal *c, cp_real size)
{
    struct canal_jet j0, j1;
    struct canal_frame f0, f1;
    cp_real dx, dy;
    canal_jet(c, c->t0, &j0);
    canal_jet(c, c->t1, &j1);
    dx = j1.x - j0.x;
    dy = j1.y - j0.y;
    if (!(cp_sqrt(dx * dx + dy * dy) <= RASTER_SEAM_GAP * size)) {
        return CP_OK; /* open: its ends may have any R */
    }
    canal_frame(&j0, &f0);
    canal_frame(&j1, &f1);
    return raster_seam_check(f0.r, f0.p, f0.dpds, f1.r, f1.p, f1.dpds,
                             size > c->rmax ? size : c->rmax);
}

int canal_init(struct canal *c, const struct canal_cfg *cfg)
{
    cp_real size = CP_R(0.0);
    int law, err;
    if (c == NULL || cfg == NULL || cfg->curve > CANAL_BEZIER || cfg->radius > CANAL_R_CUBIC) {
        return CP_ERR_INVAL;
    }
    law = law_params(c, cfg);
    err = curve_setup(c, cfg, &size);
    if (law == CP_ERR_NONFINITE || (err == CP_OK && law != CP_OK)) {
        return law; /* NONFINITE anywhere first, then the curve's checks, then the law's */
    }
    if (err != CP_OK) {
        return err;
    }
    if (c->radius == CANAL_R_COS && (c->curve == CANAL_ARC || c->curve == CANAL_ELLIPSE)) {
        unsigned ki;
        for (ki = 1; ki <= 8u; ki++) {
            if (c->rp[2] == (cp_real)ki) {
                c->k_int = (uint8_t)ki;
            }
        }
    }
    {
        cp_real range[2];
        radius_range(c, range);
        c->rmin = range[0];
        c->rmax = range[1];
    }
    if (!(c->rmin > CP_R(0.0))) {
        return CP_ERR_RADIUS;
    }
    return seam_check(c, size);
}

/* The jet; second = 0 skips the second derivatives where they cost (they are then
 * unspecified; BEZIER and CUBIC set them anyway): the streamed point needs only C, C',
 * R, R'. One body for both (flash over speed). */
static CP_NOINLINE void jet_eval(const struct canal *restrict c, cp_real t,
                                 struct canal_jet *restrict j, int second)
{
    const cp_real *p = c->cp;
    const cp_real *rp = c->rp;
    cp_real s, u, sn, cs, th, d = (cp_real)c->dir;
    switch (c->curve) {
    case CANAL_LINE:
        j->dx = p[2] - p[0];
        j->dy = p[3] - p[1];
        j->x = p[0] + t * j->dx;
        j->y = p[1] + t * j->dy;
        if (second) {
            j->ddx = CP_R(0.0);
            j->ddy = CP_R(0.0);
        }
        break;
    case CANAL_ARC: /* an ellipse with A = B = r */
    case CANAL_ELLIPSE: {
        cp_real ra = p[2], rb = c->curve == CANAL_ARC ? p[2] : p[3];
        cp_sincos_kernel(d * t, &sn, &cs);
        j->x = p[0] + ra * cs;
        j->y = p[1] + rb * sn;
        j->dx = -d * ra * sn;
        j->dy = d * rb * cs;
        if (second) {
            j->ddx = -ra * cs;
            j->ddy = -rb * sn;
        }
        break;
    }
    default: { /* CANAL_BEZIER, s = t */
        cp_real b0, b1, b2, b3;
        u = CP_R(1.0) - t;
        b0 = u * u * u;
        b1 = CP_R(3.0) * t * u * u;
        b2 = CP_R(3.0) * t * t * u;
        b3 = t * t * t;
        j->x = b0 * p[0] + b1 * p[2] + b2 * p[4] + b3 * p[6];
        j->y = b0 * p[1] + b1 * p[3] + b2 * p[5] + b3 * p[7];
        bern3_d(p, 2u, t, u, &j->dx, &j->ddx);     /* x: p[0], p[2], p[4], p[6] */
        bern3_d(p + 1, 2u, t, u, &j->dy, &j->ddy); /* y: p[1], p[3], p[5], p[7] */
        break;
    }
    }
    s = (t - c->t0) * c->inv_span;
    switch (c->radius) {
    case CANAL_R_CONST:
        j->r = rp[0];
        j->dr = CP_R(0.0);
        j->ddr = CP_R(0.0);
        break;
    case CANAL_R_LINEAR:
        j->r = rp[0] + (rp[1] - rp[0]) * s;
        j->dr = (rp[1] - rp[0]) * c->inv_span;
        j->ddr = CP_R(0.0);
        break;
    case CANAL_R_COS:
        if (c->k_int != 0u) {
            /* (cos k theta, sin k theta) = (cos theta, sin theta)^k as complex numbers:
             * k - 1 complex products of the curve's own sincos, still in (cs, sn) from
             * the ARC/ELLIPSE case above (error <= ~2k ulp, k <= 8) */
            cp_real c1 = cs, s1 = sn, tmp;
            uint8_t i;
            for (i = 1; i < c->k_int; i++) {
                tmp = cs * c1 - sn * s1;
                sn = sn * c1 + cs * s1;
                cs = tmp;
            }
        } else {
            th = (c->curve == CANAL_ARC || c->curve == CANAL_ELLIPSE) ? d * t : CP_TWO_PI * t;
            cp_sincos(rp[2] * th, &sn, &cs);
        }
        j->r = rp[0] * cs + rp[1];
        j->dr = -rp[0] * rp[2] * sn * c->dth;
        if (second) {
            j->ddr = -rp[0] * rp[2] * rp[2] * cs * c->dth * c->dth;
        }
        break;
    default: /* CANAL_R_CUBIC */
        u = CP_R(1.0) - s;
        j->r = bern3(rp, s);
        bern3_d(rp, 1u, s, u, &j->dr, &j->ddr); /* d/ds; ddr unused unless second */
        j->dr = j->dr * c->inv_span;
        j->ddr = j->ddr * c->inv_span * c->inv_span;
        break;
    }
}

void canal_jet(const struct canal *restrict c, cp_real t, struct canal_jet *restrict j)
{
    jet_eval(c, t, j, 1);
}

void canal_jet1(const struct canal *restrict c, cp_real t, struct canal_jet *restrict j)
{
    jet_eval(c, t, j, 0);
}

cp_real canal_frame_pt(const struct canal_jet *restrict j, struct canal_frame *restrict f)
{
    cp_real ic = CP_R(1.0) / cp_sqrt(j->dx * j->dx + j->dy * j->dy);
    f->x = j->x;
    f->y = j->y;
    f->tx = j->dx * ic;
    f->ty = j->dy * ic;
    f->r = j->r;
    f->p = j->dr * ic;
    f->q2 = CP_R(1.0) + f->p * f->p;
    return ic;
}

/* The point's part (canal_frame_pt), then the curvature fields kappa and dpds. */
void canal_frame(const struct canal_jet *restrict j, struct canal_frame *restrict f)
{
    cp_real c2 = j->dx * j->dx + j->dy * j->dy;
    cp_real ic = canal_frame_pt(j, f);
    cp_real ic2 = ic * ic;
    cp_real q = j->dx * j->ddy - j->dy * j->ddx;
    cp_real pp = j->ddr * c2 - j->dr * (j->dx * j->ddx + j->dy * j->ddy);
    f->kappa = q * ic2 * ic;
    f->dpds = pp * ic2 * ic2;
}

cp_real canal_g(const struct canal_jet *j)
{
    cp_real q = j->dx * j->ddy - j->dy * j->ddx;
    cp_real c2 = j->dx * j->dx + j->dy * j->dy;
    return j->dr * q / (c2 * cp_sqrt(c2));
}

void canal_point(const struct canal_frame *f, cp_real h, cp_real b, cp_real rad_off,
                 struct canal_point *out)
{
    canal_point_inline(f, h, b, rad_off, out);
}

cp_real canal_regularity(const struct canal_frame *f, cp_real h, cp_real b, cp_real rad_off)
{
    return f->q2 * b * b + h * h -
           CP_R(2.0) * (f->r - rad_off) * (f->kappa * h * b + f->dpds * b * b);
}

int canal_regular(const struct canal_frame *f, cp_real h, cp_real b, cp_real tool_r)
{
    cp_real den = CANAL_CUSP_EPS * (f->q2 * b * b + h * h);
    if (!(canal_regularity(f, h, b, CP_R(0.0)) > den)) {
        return 0;
    }
    return !(tool_r > CP_R(0.0)) || canal_regularity(f, h, b, tool_r) > den;
}

void canal_label(const struct canal_frame *f0, cp_real u0, cp_real *alpha, cp_real *b)
{
    cp_real sn, cs;
    cp_sincos(CP_R(0.5) * u0, &sn, &cs);
    *alpha = cp_sqrt(f0->q2) * cs;
    *b = sn;
}

cp_real canal_angle(const struct canal_frame *f, cp_real h, cp_real b)
{
    cp_real u = CP_R(2.0) * cp_atan2(cp_sqrt(f->q2) * b, h);
    if (u > CP_PI) {
        u -= CP_TWO_PI;
    } else if (u <= -CP_PI) {
        u += CP_TWO_PI;
    }
    return u;
}

void canal_circle(const struct canal_jet *j, struct cp_vec3 *centre, cp_real *radius,
                  struct cp_vec3 *axis)
{
    cp_real c2 = j->dx * j->dx + j->dy * j->dy;
    cp_real sig = cp_sqrt(c2 + j->dr * j->dr);
    cp_real is = CP_R(1.0) / sig;
    cp_real a = -j->r * j->dr * is;
    axis->x = j->dx * is;
    axis->y = j->dy * is;
    axis->z = j->dr * is;
    centre->x = j->x + a * axis->x;
    centre->y = j->y + a * axis->y;
    centre->z = j->r + a * axis->z;
    *radius = j->r * cp_sqrt(c2) * is;
}
