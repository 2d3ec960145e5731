/* drc.c - DRC-EXP thickening of discretely represented curves and its toolpaths (drc.h).
 * SPDX-License-Identifier: MIT
 *
 * MATH-seeds-2-3-4.md part A.2. Notation: a segment A -> B of chord c, direction d;
 * its end angles a (tangent at A to the chord) and b (chord to the tangent at B),
 * signed with the turn; E1(q) = (e^q - 1)/q, E2(q) = (e^q - 1 - q)/q^2,
 * r(q) = (E1 - E2)/E2 (increasing, r(-q) = 1/r(q), r(0) = 1).
 *
 * Layout for flash (drc.h, "Footprint"): the planar core (validation, tangent
 * assignment, planar insertion) and the iterator come first and are all the stream
 * references; the 3D extension (adjoining-plane normals, twist, A3 tilt, the twisted
 * complex model as the guess of the intrinsic arc, the osculating-plane solve) and the A.4
 * measures follow, reached only from the library entry
 * points (drc_tangents, drc_insert, drc_thicken, drc_run, drc_measure), so
 * --gc-sections drops them from the firmware image.
 */
#include "drc.h"
#include "cp_math.h"
#include "raster.h"

#define ONE CP_R(1.0)
#define TWO CP_R(2.0)
#define HALF CP_R(0.5)
#define ZERO CP_R(0.0)
#define DRC_K_INF CP_R(1.0e30) /* "unbounded" curvature of the one-zero-angle limit */

/* ---- the exponential segment model ---- */

/* Series terms: E1 = sum_{k=0}^{S} q^k/(k+1)!, E2 = sum q^k/(k+2)! on |q| <= 1.
 * Truncation <= 2/(S+3)! relative to E2 >= e^-1: float S = 9 (2/12! = 4e-9 < 2^-24),
 * double S = 16 (2/19! = 1.6e-17 < 2^-53). Outside, the closed forms lose at most
 * a factor 1/(1 - 2/e) ~ 3.8 (E2 = (E1 - 1)/q at q = 1) to cancellation. */
#if CP_REAL_DOUBLE
#define DRC_SERIES 16
#else
#define DRC_SERIES 9
#endif

/* 1/k! for k = 1 .. DRC_SERIES + 3 (index k - 1). */
static const cp_real inv_fact[DRC_SERIES + 3] = {
    CP_R(1.0),
    CP_R(0.5),
    CP_R(1.66666666666666666667e-1),
    CP_R(4.16666666666666666667e-2),
    CP_R(8.33333333333333333333e-3),
    CP_R(1.38888888888888888889e-3),
    CP_R(1.98412698412698412698e-4),
    CP_R(2.48015873015873015873e-5),
    CP_R(2.75573192239858906526e-6),
    CP_R(2.75573192239858906526e-7),
    CP_R(2.50521083854417187751e-8),
    CP_R(2.08767569878680989792e-9),
#if CP_REAL_DOUBLE /* (the float build's DRC_SERIES + 3 = 12 end here) */
    CP_R(1.60590438368216145994e-10),
    CP_R(1.14707455977297247139e-11),
    CP_R(7.64716373181981647590e-13),
    CP_R(4.77947733238738529744e-14),
    CP_R(2.81145725434552076320e-15),
    CP_R(1.56192069685862264622e-16),
    CP_R(8.22063524662432971696e-18),
#endif
};

/* E1, E2 and e^q of real q. */
static void e12(cp_real q, cp_real *e1, cp_real *e2, cp_real *eq)
{
    cp_real s1 = ZERO, s2 = ZERO, ex;
    int k;
    if (cp_fabs(q) <= ONE) {
        for (k = DRC_SERIES; k >= 0; k--) {
            s1 = s1 * q + inv_fact[k];
            s2 = s2 * q + inv_fact[k + 1];
        }
        ex = ONE + q * s1;
    } else {
        ex = cp_exp(q);
        s1 = (ex - ONE) / q;
        s2 = (s1 - ONE) / q;
    }
    *e1 = s1;
    *e2 = s2;
    *eq = ex;
}

/* r^-1(rho) for rho > 0: q in [-DRC_Q_MAX, DRC_Q_MAX] with r(q) = rho (clamped at the
 * ends), by DRC_Q_BISECT bisection steps (r is increasing; r(q) < rho <=>
 * E1 - E2 < rho E2 since E2 > 0). Error: 2 DRC_Q_MAX 2^-DRC_Q_BISECT. */
static cp_real rinv(cp_real rho)
{
    cp_real lo = -DRC_Q_MAX, hi = DRC_Q_MAX, e1, e2, eq, m;
    int i;
    for (i = 0; i < DRC_Q_BISECT; i++) {
        m = HALF * (lo + hi);
        e12(m, &e1, &e2, &eq);
        if (e1 - e2 < rho * e2) {
            lo = m;
        } else {
            hi = m;
        }
    }
    return HALF * (lo + hi);
}

static cp_real rq(cp_real q)
{
    cp_real e1, e2, eq;
    e12(q, &e1, &e2, &eq);
    return (e1 - e2) / e2;
}

/* End curvatures ka, kb (1/mm, signed with the turn) and q of the segment model with
 * end angles a, b on a chord of length len (A.2 step 1). */
static CP_NOINLINE void seg_k(cp_real a, cp_real b, cp_real len, cp_real *ka, cp_real *kb,
                              cp_real *q)
{
    cp_real th = HALF * cp_fabs(a + b), sn, cs, lt;
    cp_sincos(th, &sn, &cs);
    /* L~ = L (th/2) / sin(th/2): arc length of the circle of turning th */
    lt = th > CP_R(1e-12) ? len * th / sn : len;
    *q = ZERO;
    if (a * b > ZERO) {
        cp_real e1, e2, eq;
        *q = rinv(b / a);
        e12(*q, &e1, &e2, &eq);
        *ka = a / (e2 * lt);
        *kb = *ka * eq;
    } else if ((a == ZERO) != (b == ZERO)) {
        /* exactly one zero end angle (next to a collinear run): the limit a -> 0 of the
         * convex model, curvature 0 at that end and unbounded (k_B ~ b q / L~, q -> inf)
         * at the other, so G2 there is reachable only as that angle -> 0: the bisection
         * ends with the tangent on the chord (the "end value" of A.2; line_arc: an exact
         * curvature step at the join, no inflection) */
        cp_real k = a + b > ZERO ? DRC_K_INF : -DRC_K_INF; /* a + b: the nonzero one */
        *ka = a == ZERO ? ZERO : k;
        *kb = b == ZERO ? ZERO : k;
    } else {
        *ka = TWO * (TWO * a - b) / lt;
        *kb = TWO * (TWO * b - a) / lt;
    }
}

/* ---- steps 0 and 1 ---- */

int drc_size(uint32_t n, uint32_t passes, uint32_t *need)
{
    *need = 0;
    if (n < 3u) {
        return CP_ERR_TOO_FEW;
    }
    if (passes > CP_MAX_PASSES || n > 0x7FFFFFu) {
        return CP_ERR_TOO_MANY;
    }
    *need = (n - 1u) * ((uint32_t)1u << passes) + 1u;
    return CP_OK;
}

/* The zero of an angle measured against the chord a-b of length c (drc.h DRC_ANGLE_ZERO):
 * DRC_ANGLE_ZERO (1 + (|a| + |b|)/c), |.| the max-abs coordinate. Every decision of this
 * file that the maths takes at an exact 0 of an angle (a collinear vertex, a tangent on
 * its chord, the model of a segment) compares with it, and tests/ref_drc.c does the same. */
static cp_real max_abs(const struct cp_vec3 *v)
{
    cp_real m = cp_fabs(v->x);
    m = cp_fabs(v->y) > m ? cp_fabs(v->y) : m;
    return cp_fabs(v->z) > m ? cp_fabs(v->z) : m;
}

static cp_real angle_zero(const struct cp_vec3 *a, const struct cp_vec3 *b, cp_real c)
{
    return DRC_ANGLE_ZERO * (ONE + (max_abs(a) + max_abs(b)) / c);
}

/* Scratch of step 1 (the caller's tangent array holds the normals meanwhile). */
struct drc_scratch {
    cp_real phi[CP_MAX_DRC_POINTS]; /* signed turning at interior vertices 1..n-2; at the
                                       ends (solve) the end angles a0 (phi[0], tp[0] = 1)
                                       and b1 (phi[n-1], tp[n-1] = 0) */
    cp_real len[CP_MAX_DRC_POINTS]; /* chord lengths */
    cp_real zero[CP_MAX_DRC_POINTS]; /* angle_zero of each chord (DRC_ANGLE_ZERO) */
    cp_real tp[CP_MAX_DRC_POINTS];  /* tangent parameters t_j */
    cp_real tau[CP_MAX_DRC_POINTS]; /* AP torsion of chords 1..n-3 (3D only) */
};

/* Angles of segment i from the tangent parameters: a = t_i phi_i (a0 at i = 0: 1 a0),
 * b = (1 - t_{i+1}) phi_{i+1} (b1 at the last segment: (1 - 0) b1); exact. */
static cp_real seg_a(const struct drc_scratch *w, uint32_t i)
{
    return w->tp[i] * w->phi[i];
}

static cp_real seg_b(const struct drc_scratch *w, uint32_t i)
{
    return (ONE - w->tp[i + 1u]) * w->phi[i + 1u];
}

int drc_point_check(const struct cp_vec3 *q, int planar)
{
    cp_real v[3];
    uint32_t k;
    v[0] = q->x;
    v[1] = q->y;
    v[2] = q->z;
    for (k = 0; k < 3u; k++) {
        if (!(cp_fabs(v[k]) <= CANAL_COORD_MAX)) {
            return cp_finite(v[k]) ? CP_ERR_RANGE : CP_ERR_NONFINITE;
        }
    }
    return planar && v[2] != ZERO ? CP_ERR_OFF_PLANE : CP_OK;
}

/* Validation and step 0 (A.3), in the order: count, per coordinate non-finite or range,
 * (planar != 0) off the plane, coincident chord, turning >= 90 deg. Fills len, zero and the
 * planar signed turning phi_j = atan2((d_{j-1} x d_j).z, d_{j-1}.d_j), exactly 0 when
 * |sin turn| <= zero_{j-1} + zero_j (collinear: the turn is the angle between the two chord
 * directions, each as uncertain as an end angle on its chord; the 3D path overwrites phi). */
static CP_ALWAYS_INLINE int analyse(const struct cp_vec3 *p, unsigned ps, uint32_t n,
                                    int planar, struct drc_scratch *w)
{
    struct cp_vec3 d0, d1;
    cp_real lo[3], hi[3], dd = ZERO, cz;
    uint32_t i, k;
    if (n < 3u) {
        return CP_ERR_TOO_FEW;
    }
    if (n > CP_MAX_DRC_POINTS) {
        return CP_ERR_TOO_MANY;
    }
    /* the bounding box from P_0 (a non-finite P_0 is rejected below, unused) */
    lo[0] = hi[0] = p[0].x;
    lo[1] = hi[1] = p[0].y;
    lo[2] = hi[2] = p[0].z;
    for (i = 0; i < n; i++) {
        const struct cp_vec3 *q = &p[i * ps];
        cp_real v[3];
        int err = drc_point_check(q, planar); /* the point alone (POINT checks it too) */
        if (err != CP_OK) {
            return err;
        }
        v[0] = q->x;
        v[1] = q->y;
        v[2] = q->z;
        for (k = 0; k < 3u; k++) {
            lo[k] = v[k] < lo[k] ? v[k] : lo[k];
            hi[k] = v[k] > hi[k] ? v[k] : hi[k];
        }
    }
    for (k = 0; k < 3u; k++) {
        dd += (hi[k] - lo[k]) * (hi[k] - lo[k]);
    }
    dd = cp_sqrt(dd) * DRC_COINCIDENT_REL;
    for (i = 0; i + 1u < n; i++) {
        cp_v3_sub(&p[(i + 1u) * ps], &p[i * ps], &d1);
        w->len[i] = cp_v3_norm(&d1);
        if (!(w->len[i] > dd)) {
            return CP_ERR_COINCIDENT;
        }
        w->zero[i] = angle_zero(&p[i * ps], &p[(i + 1u) * ps], w->len[i]);
        if (i > 0u) {
            cp_real co = cp_v3_dot(&d0, &d1);
            if (!(co > ZERO)) {
                return CP_ERR_TURN;
            }
            cz = d0.x * d1.y - d0.y * d1.x; /* (d0 x d1).z = L0 L1 sin(turn) */
            w->phi[i] = cp_fabs(cz) > (w->zero[i - 1u] + w->zero[i]) * w->len[i - 1u] * w->len[i]
                            ? cp_atan2(cz, co) : ZERO;
        }
        d0 = d1;
    }
    return CP_OK;
}

/* G2 residual of vertex j at tangent parameter x (A.2 step 1), times sign(phi_j). */
static CP_ALWAYS_INLINE cp_real g2_res(const struct drc_scratch *w, uint32_t j, cp_real x)
{
    cp_real ka, kb, kl, kr, q, ph = w->phi[j];
    seg_k(x * ph, seg_b(w, j), w->len[j], &ka, &kb, &q);
    seg_k(seg_a(w, j - 1u), (ONE - x) * ph, w->len[j - 1u], &kl, &kr, &q);
    return ph > ZERO ? ka - kr : kr - ka;
}

/* Step 1 on the turning angles: tangent parameters tp and end angles a0, b1.
 * Gauss-Seidel: DRC_SWEEPS sweeps of (ends, then each vertex by DRC_T_BISECT
 * bisection steps). The residual is increasing in t_j (a larger a_j raises the
 * curvature at the start of segment j and lowers it at the end of j - 1); without
 * a sign change the bisection ends at 0 or 1 (G2 given up, tangent on a chord).
 * Error of t_j: 2^-DRC_T_BISECT. The sweeps converge geometrically (measured: G2
 * residual <= 1e-14 relative after 40 sweeps in double on every test set).
 * End angles: N = 3 the circle through the three points (chord angle asin(L k / 2));
 * N >= 4 the neighbour segment's q scaled by the length ratio (<= 1), the angle then
 * bounded by the neighbour vertex's turn: |a0| <= |phi_1|, |b1| <= |phi_{N-2}| (drc.h,
 * "End tangents": a steep curvature ratio next to a short chord would otherwise turn
 * the end tangent past 90 deg, and the thickened curve would loop behind P_0). */
static CP_ALWAYS_INLINE void solve(const struct cp_vec3 *p, unsigned ps, uint32_t n,
                                   struct drc_scratch *w)
{
    cp_real ka, kb, q, x, k;
    uint32_t i, s, e;
    for (i = 0; i < n; i++) {
        w->tp[i] = HALF;
    }
    w->tp[0] = ONE; /* the end angles a0 = phi[0], b1 = phi[n-1] (seg_a, seg_b) */
    w->tp[n - 1u] = ZERO;
    w->phi[0] = ZERO;
    w->phi[n - 1u] = ZERO;
    if (n == 3u) {
        struct cp_vec3 ch;
        cp_v3_sub(&p[2u * ps], &p[0], &ch);
        cp_sincos(w->phi[1], &x, &q);
        k = x / cp_v3_norm(&ch); /* half the signed curvature of the circle */
        for (e = 0; e < 2u; e++) {
            x = w->len[e] * k;
            w->phi[e * (n - 1u)] = cp_atan2(x, cp_sqrt(ONE - x * x));
        }
    }
    for (s = 0; s < DRC_SWEEPS; s++) {
        for (e = 0; n >= 4u && e < 2u; e++) {
            /* v the neighbour vertex (1, N - 2), j = v - e its inner segment, v - 1 + e
             * the end segment */
            uint32_t v = e ? n - 2u : 1u, j = v - e;
            cp_real lr = w->len[v - 1u + e] / w->len[j];
            seg_k(seg_a(w, j), seg_b(w, j), w->len[j], &ka, &kb, &q);
            x = rq(q * (lr < ONE ? lr : ONE));
            k = w->phi[v]; /* the neighbour vertex's turn */
            q = (e ? w->tp[v] : ONE - w->tp[v]) * k;
            x = e ? q * x : q / x;
            /* |end angle| <= |turn|: < 90 deg and convex (same sign), circles untouched;
             * within the zero of its chord the end angle is 0 (on the chord) */
            x = cp_fabs(x) > cp_fabs(k) ? k : x;
            w->phi[e * (n - 1u)] = cp_fabs(x) <= w->zero[v - 1u + e] ? ZERO : x;
        }
        for (i = 1; i + 1u < n; i++) {
            cp_real lo = ZERO, hi = ONE, m;
            uint32_t b;
            if (w->phi[i] == ZERO) {
                continue;
            }
            for (b = 0; b < DRC_T_BISECT; b++) {
                m = HALF * (lo + hi);
                if (g2_res(w, i, m) < ZERO) {
                    lo = m;
                } else {
                    hi = m;
                }
            }
            /* a tangent within the zero of a chord lies on it (drc.h DRC_ANGLE_ZERO): the
             * end value of A.2, exactly, so that seg_k's a b > 0 and a == 0 see the same
             * angle in every build (the bracket's 2^-DRC_T_BISECT |phi| < 6e-9 rad stays
             * below the zero, >= 3.8e-6 rad, so the builds decide alike) */
            m = HALF * (lo + hi);
            m = cp_fabs(m * w->phi[i]) <= w->zero[i] ? ZERO : m;
            w->tp[i] = cp_fabs((ONE - m) * w->phi[i]) <= w->zero[i - 1u] ? ONE : m;
        }
    }
}

/* Angle of the tangent at point i from chord c(i) = i (n - 2 at the last point), signed
 * about the normal: a0, t_i phi_i, -b1. */
static cp_real tan_angle(const struct drc_scratch *w, uint32_t i, uint32_t n)
{
    return i + 1u == n ? -w->phi[i] : seg_a(w, i);
}

/* o = the unit vector (dx, dy, 0) rotated by ang about +z; returns cos ang. */
static CP_NOINLINE cp_real rot_z(cp_real ang, cp_real dx, cp_real dy, struct cp_vec3 *o)
{
    cp_real sn, cs;
    cp_sincos(ang, &sn, &cs);
    o->x = cs * dx - sn * dy;
    o->y = sn * dx + cs * dy;
    o->z = ZERO;
    return cs;
}

/* Steps 0 and 1 of planar data (z == 0 required: CP_ERR_OFF_PLANE): the stream's path
 * and drc_tangents' for planar input, so both give the same bits. analyse, solve and
 * g2_res are inlined here (flash: the stream's only copy; drc_tangents, library only,
 * gets its own analyse and solve for the 3D path). The tangent at point i
 * is the unit chord c(i) rotated by -angle about +z. */
static CP_NOINLINE int tangents_planar(const struct cp_vec3 *p, unsigned ps, struct cp_vec3 *t,
                                       unsigned ts, uint32_t n)
{
    struct drc_scratch w;
    uint32_t i;
    int err = analyse(p, ps, n, 1, &w);
    if (err != CP_OK) {
        return err;
    }
    solve(p, ps, n, &w);
    for (i = 0; i < n; i++) {
        uint32_t c = i + 1u < n ? i : n - 2u;
        struct cp_vec3 d;
        cp_real l = w.len[c];
        cp_v3_sub(&p[(c + 1u) * ps], &p[c * ps], &d);
        (void)rot_z(-tan_angle(&w, i, n), d.x / l, d.y / l, &t[i * ts]);
    }
    return CP_OK;
}

/* ---- step 2, planar ---- */

/* Planar insertion (A.2 step 2, real z): signed angles about +z. */
static CP_NOINLINE void insert_planar(const struct drc_pt *a, const struct drc_pt *b,
                                      struct drc_pt *m)
{
    cp_real dx = b->p.x - a->p.x, dy = b->p.y - a->p.y, c = cp_sqrt(dx * dx + dy * dy);
    cp_real tha, thb, d1, gm, e1, e2, eq, r, zero;
    struct cp_vec3 u;
    dx /= c;
    dy /= c;
    tha = cp_atan2(dx * a->t.y - dy * a->t.x, dx * a->t.x + dy * a->t.y);
    thb = cp_atan2(dx * b->t.y - dy * b->t.x, dx * b->t.x + dy * b->t.y);
    zero = angle_zero(&a->p, &b->p, c); /* end angles at rounding level are the exact 0 */
    tha = cp_fabs(tha) <= zero ? ZERO : tha;
    thb = cp_fabs(thb) <= zero ? ZERO : thb;
    /* inflection or a zero end angle: linear curvature */
    d1 = CP_R(0.25) * (tha - thb);
    gm = CP_R(-0.25) * (tha + thb);
    if (tha * thb < ZERO) {
        /* convex (a = -tha, b = thb of one sign): k = (C/L) e^{qu}, q = r^-1(b/a);
         * children: c1 = C/2, deviations D1 = G_A + c1 E2(q/2), G_M = G_A + c1 E1(q/2) */
        cp_real q = rinv(-thb / tha), cc;
        e12(q, &e1, &e2, &eq);
        cc = -HALF * tha / e2; /* signed C/2 */
        e12(HALF * q, &e1, &e2, &eq);
        d1 = tha + cc * e2;
        gm = tha + cc * e1;
    }
    /* isosceles apex: M = A + c/(2 cos D1) rot(d, D1) */
    r = HALF * c / rot_z(d1, dx, dy, &u);
    m->p.x = a->p.x + r * u.x;
    m->p.y = a->p.y + r * u.y;
    m->p.z = ZERO;
    (void)rot_z(gm, dx, dy, &m->t);
}

/* ---- the 3D extension and the library entry points (not referenced by the stream) ---- */

/* 3D step 0: oriented adjoining-plane normals n_j = unit(d_{j-1} x d_j) into t,
 * n_j . n_{j-1} >= 0 (a collinear vertex inherits the previous normal, filled back at
 * the first one; all collinear: +z), turning phi_j about them, AP-dihedral torsion
 * tau = angle / L of chords 1..n-3 (A2) and the twist rejection |angle| >= 45 deg. */
static CP_NOINLINE int shape_3d(const struct cp_vec3 *p, unsigned ps, struct cp_vec3 *t,
                                unsigned ts, uint32_t n, struct drc_scratch *w)
{
    struct cp_vec3 d0, d1, c;
    uint32_t i, k, have = 0;
    for (i = 0; i < n; i++) {
        t[i * ts].x = ZERO;
        t[i * ts].y = ZERO;
        t[i * ts].z = ONE;
        w->tau[i] = ZERO;
    }
    for (i = 1; i + 1u < n; i++) {
        cp_real cl, co;
        cp_v3_sub(&p[i * ps], &p[(i - 1u) * ps], &d0);
        cp_v3_sub(&p[(i + 1u) * ps], &p[i * ps], &d1);
        co = cp_v3_dot(&d0, &d1);
        cp_v3_cross(&d0, &d1, &c);
        cl = cp_v3_norm(&c);
        w->phi[i] = ZERO;
        if (cl > (w->zero[i - 1u] + w->zero[i]) * w->len[i - 1u] * w->len[i]) { /* analyse */
            cp_real sg = ONE;
            cp_v3_comb(&c, ONE / cl, &c, ZERO, &c);
            if (have && cp_v3_dot(&c, &t[(i - 1u) * ts]) < ZERO) {
                cp_v3_comb(&c, -ONE, &c, ZERO, &c);
                sg = -ONE;
            }
            for (k = have ? i : 0u; k <= i; k++) {
                t[k * ts] = c;
            }
            have = 1;
            /* (d_{j-1} x d_j) . n_j = sg cl */
            w->phi[i] = cp_atan2(sg * cl, co);
        } else if (have) {
            t[i * ts] = t[(i - 1u) * ts];
        }
    }
    t[(n - 1u) * ts] = t[(n - 2u) * ts];
    for (i = 1; i + 2u < n; i++) {
        cp_real ang;
        cp_v3_cross(&t[i * ts], &t[(i + 1u) * ts], &c);
        cp_v3_sub(&p[(i + 1u) * ps], &p[i * ps], &d0);
        ang = cp_atan2(cp_v3_dot(&c, &d0) / w->len[i], cp_v3_dot(&t[i * ts], &t[(i + 1u) * ts]));
        if (!(cp_fabs(ang) < CP_R(0.78539816339744830962))) {
            return CP_ERR_TWIST;
        }
        w->tau[i] = ang / w->len[i];
    }
    return CP_OK;
}

/* The A3 tilt chi_i of the tangent out of the adjoining plane (N >= 4; 0 for N = 3):
 * ends ks tau L L / 3, interior -ks tau_b L L / 6 (ks the signed 3-point curvature,
 * tau_b the mean torsion of the two chords, the one-sided value next to the ends). */
static CP_NOINLINE void tilt_3d(const struct cp_vec3 *p, unsigned ps, uint32_t n,
                                const struct drc_scratch *w, cp_real *chi)
{
    uint32_t i;
    for (i = 0; i < n; i++) {
        uint32_t v = i == 0u ? 1u : (i + 1u == n ? n - 2u : i);
        struct cp_vec3 ch2;
        cp_real sn, cs, ks, tb;
        chi[i] = ZERO;
        if (n < 4u) {
            continue;
        }
        cp_v3_sub(&p[(v + 1u) * ps], &p[(v - 1u) * ps], &ch2);
        cp_sincos(w->phi[v], &sn, &cs);
        ks = TWO * sn / cp_v3_norm(&ch2); /* signed 3-point curvature */
        if (i == 0u) {
            chi[i] = ks * w->tau[1] * w->len[0] * w->len[1] / CP_R(3.0);
        } else if (i + 1u == n) {
            chi[i] = ks * w->tau[n - 3u] * w->len[n - 2u] * w->len[n - 3u] / CP_R(3.0);
        } else {
            tb = v == 1u ? w->tau[1]
                         : (v + 2u == n ? w->tau[n - 3u] : HALF * (w->tau[v - 1u] + w->tau[v]));
            chi[i] = -ks * tb * w->len[v - 1u] * w->len[v] / CP_R(6.0);
        }
    }
}

/* The 3D tangents from the solved angles: chord c(i) rotated about the normal n_i (in t)
 * by -angle, tilted by chi_i (tilt_3d). Out of line: chi and the vectors stay off
 * drc_tangents' frame (analyse and solve are inlined there). */
static CP_NOINLINE void orient_3d(const struct cp_vec3 *p, unsigned ps, struct cp_vec3 *t,
                                  unsigned ts, uint32_t n, const struct drc_scratch *w)
{
    cp_real chi[CP_MAX_DRC_POINTS];
    uint32_t i;
    tilt_3d(p, ps, n, w, chi);
    for (i = 0; i < n; i++) {
        uint32_t c = i + 1u < n ? i : n - 2u;
        struct cp_vec3 d, nd, nrm = t[i * ts];
        cp_real sn, cs;
        cp_v3_sub(&p[(c + 1u) * ps], &p[c * ps], &d);
        cp_v3_comb(&d, ONE / cp_v3_norm(&d), &d, ZERO, &d);
        cp_v3_cross(&nrm, &d, &nd);
        cp_sincos(-tan_angle(w, i, n), &sn, &cs);
        cp_v3_comb(&t[i * ts], cs, &d, sn, &nd);
        cp_sincos(chi[i], &sn, &cs);
        cp_v3_comb(&t[i * ts], cs, &t[i * ts], sn, &nrm);
    }
}

static void kink_3d(const struct cp_vec3 *p, unsigned ps, struct cp_vec3 *t, unsigned ts,
                    uint32_t n);

int drc_tangents(const struct cp_vec3 *p, unsigned ps, struct cp_vec3 *t, unsigned ts,
                 uint32_t n)
{
    struct drc_scratch w;
    uint32_t i;
    int err = analyse(p, ps, n, 0, &w);
    if (err != CP_OK) {
        return err;
    }
    for (i = 0; i < n && p[i * ps].z == ZERO; i++) {
    }
    if (i == n) { /* analyse(planar) would pass too: the planar path */
        return tangents_planar(p, ps, t, ts, n);
    }
    err = shape_3d(p, ps, t, ts, n, &w);
    if (err != CP_OK) {
        return err;
    }
    solve(p, ps, n, &w);
    orient_3d(p, ps, t, ts, n, &w);
    kink_3d(p, ps, t, ts, n);
    return CP_OK;
}

int drc_is_planar(const struct drc_pt *buf, uint32_t n)
{
    uint32_t i;
    for (i = 0; i < n; i++) {
        if (buf[i].p.z != ZERO || buf[i].t.z != ZERO) {
            return 0;
        }
    }
    return 1;
}

/* complex numbers of the twisted model */
struct cx {
    cp_real re, im;
};

static struct cx cmul(struct cx a, struct cx b)
{
    struct cx r;
    r.re = a.re * b.re - a.im * b.im;
    r.im = a.re * b.im + a.im * b.re;
    return r;
}

static struct cx cdiv(struct cx a, struct cx b)
{
    cp_real d = b.re * b.re + b.im * b.im;
    struct cx r;
    r.re = (a.re * b.re + a.im * b.im) / d;
    r.im = (a.im * b.re - a.re * b.im) / d;
    return r;
}

/* e[0..3] = E1, E2, E1', E2' of complex z: E1' = (e^z - E1)/z,
 * E2' = (E1 - 2 E2)/z; series on |z| <= 1 (same truncation as e12). */
static void ce12(struct cx z, struct cx e[4])
{
    int k, j;
    if (z.re * z.re + z.im * z.im <= ONE) {
        for (j = 0; j < 4; j++) {
            e[j].re = ZERO;
            e[j].im = ZERO;
        }
        for (k = DRC_SERIES; k >= 0; k--) {
            e[0] = cmul(e[0], z);
            e[0].re += inv_fact[k];
            e[1] = cmul(e[1], z);
            e[1].re += inv_fact[k + 1];
        }
        /* E1' = sum (k+1) z^k/(k+2)!, E2' = sum (k+1) z^k/(k+3)! */
        for (k = DRC_SERIES; k >= 0; k--) {
            e[2] = cmul(e[2], z);
            e[2].re += (cp_real)(k + 1) * inv_fact[k + 1];
            e[3] = cmul(e[3], z);
            e[3].re += (cp_real)(k + 1) * inv_fact[k + 2];
        }
        return;
    }
    {
        struct cx ez, one;
        cp_real sn, cs, er = cp_exp(z.re);
        cp_sincos(z.im, &sn, &cs);
        ez.re = er * cs;
        ez.im = er * sn;
        one.re = ez.re - ONE;
        one.im = ez.im;
        e[0] = cdiv(one, z);
        one.re = e[0].re - ONE;
        one.im = e[0].im;
        e[1] = cdiv(one, z);
        one.re = ez.re - e[0].re;
        one.im = ez.im - e[0].im;
        e[2] = cdiv(one, z);
        one.re = e[0].re - CP_R(2.0) * e[1].re;
        one.im = e[0].im - CP_R(2.0) * e[1].im;
        e[3] = cdiv(one, z);
    }
}

/* ---- the intrinsic 3D segment model (issue 21, docs/DRC-TORSION.md) ----
 * An arc of length len with curvature k(u) = (ka/len) e^{q u} and constant torsion tb/len,
 * u = s/len in [0, 1], started at A with the tangent T_A and the principal normal
 * N(psi) = cos psi r1 + sin psi (T_A x r1). The unknowns x = (psi, len, ka, q, tb) are fitted
 * to B and T_B (5 equations) by DRC_FIT_NEWTON Newton steps. The family is closed under
 * restriction to a sub-arc (k stays exponential, tau constant), so the fit of a child
 * segment's end data returns the child half of its parent's arc: the limit curve of the
 * passes on every original segment IS the fitted arc, and the osculating plane cannot kink
 * at an inserted point (the linearised twisted model could: a kink is a Dirac in torsion,
 * whose discrete value doubles with every pass; docs/DRC-TORSION.md). */
#if CP_REAL_DOUBLE
#define DRC_FIT_NEWTON 8           /* Newton steps of the 5-unknown fit */
#define DRC_FD CP_R(1.0e-7)         /* forward-difference step of the Jacobian */
#else
#define DRC_FIT_NEWTON 6
#define DRC_FD CP_R(2.0e-3)
#endif
#define DRC_FRENET_STEPS 16u      /* exact helical sub-steps per arc (even: M at the half) */
#define DRC_KINK_SWEEPS 8u        /* step 1: Gauss-Seidel sweeps of the osculating-plane fit */
#define DRC_KINK_SECANT 4u        /* secant steps per vertex and sweep */

struct frm {
    struct cp_vec3 p, t, n; /* position, unit tangent, principal normal (b = t x n) */
};

/* Rotate v about the unit axis w by the angle with sine sn and 1 - cosine oc (Rodrigues;
 * oc = 2 sin^2(half angle), no cancellation). */
static void rot_axis(struct cp_vec3 *v, const struct cp_vec3 *w, cp_real sn, cp_real oc)
{
    struct cp_vec3 x;
    cp_real wd = cp_v3_dot(w, v);
    cp_v3_cross(w, v, &x);
    cp_v3_comb(v, ONE - oc, v, sn, &x);
    cp_v3_comb(v, ONE, v, oc * wd, w);
}

/* Walk the model x from the frame f (in place) over `steps` of the DRC_FRENET_STEPS
 * sub-steps. Each sub-step freezes the curvature at its midpoint and moves exactly along
 * the helix of that curvature and the torsion (a rotation of the frame about the Darboux
 * vector w = tau T + k B by |w| h, position = the integral of the rotating tangent): exact
 * for helices (q = 0); otherwise second order in the sub-step, error
 * <= ka (q / DRC_FRENET_STEPS)^2 / 24 rad (docs/DRC-TORSION.md). */
static void frn_walk(struct frm *f, const cp_real *x, uint32_t steps)
{
    cp_real h = x[1] / (cp_real)DRC_FRENET_STEPS, tau = x[4] / x[1];
    cp_real k = x[2] / x[1] * cp_exp(x[3] * HALF / (cp_real)DRC_FRENET_STEPS);
    cp_real g = cp_exp(x[3] / (cp_real)DRC_FRENET_STEPS);
    uint32_t i;
    for (i = 0; i < steps; i++) {
        struct cp_vec3 b, w, x1, tp;
        cp_real wn, ph, sn, cs, oc, si, ci, td;
        cp_v3_cross(&f->t, &f->n, &b);
        cp_v3_comb(&w, tau, &f->t, k, &b);
        wn = cp_v3_norm(&w);
        ph = wn * h;
        cp_sincos(HALF * ph, &sn, &cs); /* half angle: 1 - cos ph = 2 sin^2(ph/2) */
        oc = TWO * sn * sn;
        sn = TWO * sn * cs;
        if (ph > CP_R(1e-3)) {
            si = sn / ph; /* sin(ph)/ph */
            ci = oc / ph; /* (1 - cos ph)/ph */
        } else {          /* (truncation ph^4/120, ph^5/720: below 2^-53 relative) */
            si = ONE - ph * ph / CP_R(6.0);
            ci = ph * (HALF - ph * ph / CP_R(24.0));
        }
        if (wn > ZERO) {
            cp_v3_comb(&w, ONE / wn, &w, ZERO, &w);
        }
        td = cp_v3_dot(&f->t, &w);
        cp_v3_comb(&tp, ONE, &f->t, -td, &w); /* T perpendicular to the axis */
        cp_v3_cross(&w, &f->t, &x1);
        cp_v3_comb(&b, td * h, &w, si * h, &tp);
        cp_v3_comb(&b, ONE, &b, ci * h, &x1);
        cp_v3_comb(&f->p, ONE, &f->p, ONE, &b);
        rot_axis(&f->t, &w, sn, oc);
        rot_axis(&f->n, &w, sn, oc);
        k *= g;
    }
}

/* The start frame of the model: P = 0 (positions relative to A), T = T_A,
 * N = cos psi r1 + sin psi (T_A x r1). */
static void frn_start(const struct drc_pt *a, const struct cp_vec3 *r1, cp_real psi,
                      struct frm *f)
{
    struct cp_vec3 r2;
    cp_real sn, cs;
    cp_v3_cross(&a->t, r1, &r2);
    cp_sincos(psi, &sn, &cs);
    f->p.x = ZERO; /* relative to A: rounding scales with the arc, not with |A| */
    f->p.y = ZERO;
    f->p.z = ZERO;
    f->t = a->t;
    cp_v3_comb(&f->n, cs, r1, sn, &r2);
}

/* Residual of x: (P(1) - B)/c and (T(1) - T_B) on ea, eb (both perpendicular to T_B). */
static void frn_res(const struct drc_pt *a, const struct drc_pt *b, const struct cp_vec3 *r1,
                    const struct cp_vec3 *ea, const struct cp_vec3 *eb, cp_real ic,
                    const cp_real *x, cp_real *r)
{
    struct frm f;
    struct cp_vec3 dp, dt;
    frn_start(a, r1, x[0], &f);
    frn_walk(&f, x, DRC_FRENET_STEPS);
    cp_v3_sub(&b->p, &a->p, &dp);
    cp_v3_sub(&f.p, &dp, &dp);
    cp_v3_sub(&f.t, &b->t, &dt);
    r[0] = dp.x * ic;
    r[1] = dp.y * ic;
    r[2] = dp.z * ic;
    r[3] = cp_v3_dot(&dt, ea);
    r[4] = cp_v3_dot(&dt, eb);
}

/* Fit the model to the segment a -> b from the initial guess x (the twisted model's) and
 * the reference normal r1 (unit, perpendicular to T_A): DRC_FIT_NEWTON Newton steps, the
 * Jacobian by forward differences (steps DRC_FD x the unknown's scale), a 5 x 5 Gaussian
 * elimination with partial pivoting; a step with a pivot below 1e-30 is skipped. */
static CP_NOINLINE void frn_fit(const struct drc_pt *a, const struct drc_pt *b,
                                const struct cp_vec3 *r1, cp_real c, cp_real *x)
{
    cp_real jac[5][6], r0[5], r[5], xs[5], ic = ONE / c;
    struct cp_vec3 ea, eb;
    uint32_t it, i, j, k;
    cp_v3_comb(&ea, ONE, r1, -cp_v3_dot(r1, &b->t), &b->t);
    cp_v3_comb(&ea, ONE / cp_v3_norm(&ea), &ea, ZERO, &ea);
    cp_v3_cross(&b->t, &ea, &eb);
    for (it = 0; it < DRC_FIT_NEWTON; it++) {
        int ok = 1;
        frn_res(a, b, r1, &ea, &eb, ic, x, r0);
        for (j = 0; j < 5u; j++) {
            cp_real hj = DRC_FD * (j == 1u ? c : ONE);
            for (i = 0; i < 5u; i++) {
                xs[i] = x[i];
            }
            xs[j] += hj;
            frn_res(a, b, r1, &ea, &eb, ic, xs, r);
            for (i = 0; i < 5u; i++) {
                jac[i][j] = (r[i] - r0[i]) / hj;
            }
        }
        for (i = 0; i < 5u; i++) {
            jac[i][5] = r0[i];
        }
        for (k = 0; k < 5u; k++) { /* elimination with partial pivoting */
            uint32_t pv = k;
            for (i = k + 1u; i < 5u; i++) {
                pv = cp_fabs(jac[i][k]) > cp_fabs(jac[pv][k]) ? i : pv;
            }
            if (!(cp_fabs(jac[pv][k]) > CP_R(1e-30))) {
                ok = 0;
                break;
            }
            for (j = 0; j < 6u; j++) {
                cp_real t = jac[k][j];
                jac[k][j] = jac[pv][j];
                jac[pv][j] = t;
            }
            for (i = k + 1u; i < 5u; i++) {
                cp_real f = jac[i][k] / jac[k][k];
                for (j = k; j < 6u; j++) {
                    jac[i][j] -= f * jac[k][j];
                }
            }
        }
        if (!ok) {
            break;
        }
        for (k = 5u; k-- > 0u;) { /* back substitution: the step in jac[k][5] */
            for (j = k + 1u; j < 5u; j++) {
                jac[k][5] -= jac[k][j] * jac[j][5];
            }
            jac[k][5] /= jac[k][k];
        }
        for (i = 0; i < 5u; i++) {
            x[i] -= jac[i][5];
        }
    }
}

/* The twisted small-angle model of A.2 (deviation vectors g = angle(T, d) unit(T - (T.d) d),
 * complex in e1 = unit(g_A), e2 = d x e1; g(u) = G_A + C (e^{zu} - 1)/z with r(z) = rho =
 * -G_B/G_A by DRC_NEWTON damped Newton steps, step clipped to 1, Re z clamped to
 * +-DRC_Q_MAX, from z0 = r^-1(|rho|) + 3i arg(rho)), used as the initial guess of the
 * intrinsic model when both end angles are non-zero and Re rho > 0: x = (0, c, |C|, Re z,
 * Im z) and r1 = the direction of C (the curvature at A) perpendicular to T_A. Returns 1
 * then; else 0 with ga, gb the deviation vectors (the linear model's input). */
static CP_NOINLINE int twist_guess(const struct drc_pt *a, const struct drc_pt *b,
                                   struct cp_vec3 *d, cp_real *cl, struct cp_vec3 *ga,
                                   struct cp_vec3 *gb, cp_real *x, struct cp_vec3 *r1)
{
    struct cp_vec3 e1, e2;
    cp_real c, w, td, ang, zero, na, nb;
    struct cx gA, gB, rho, z, e[4], r, dr, st, cc;
    int i;
    cp_v3_sub(&b->p, &a->p, d);
    c = cp_v3_norm(d);
    *cl = c;
    zero = angle_zero(&a->p, &b->p, c); /* end angles at rounding level are the exact 0 */
    cp_v3_comb(d, ONE / c, d, ZERO, d);
    td = cp_v3_dot(&a->t, d);
    cp_v3_comb(ga, ONE, &a->t, -td, d);
    w = cp_v3_norm(ga);
    ang = cp_atan2(w, td);
    cp_v3_comb(ga, ang > zero ? ang / w : ZERO, ga, ZERO, ga);
    td = cp_v3_dot(&b->t, d);
    cp_v3_comb(gb, ONE, &b->t, -td, d);
    w = cp_v3_norm(gb);
    ang = cp_atan2(w, td);
    cp_v3_comb(gb, ang > zero ? ang / w : ZERO, gb, ZERO, gb);
    na = cp_v3_norm(ga);
    nb = cp_v3_norm(gb);
    if (!(na > ZERO && nb > ZERO)) {
        return 0;
    }
    cp_v3_comb(&e1, ONE / na, ga, ZERO, ga);
    cp_v3_cross(d, &e1, &e2);
    gA.re = na;
    gA.im = ZERO;
    gB.re = cp_v3_dot(gb, &e1);
    gB.im = cp_v3_dot(gb, &e2);
    rho = cdiv(gB, gA);
    rho.re = -rho.re;
    rho.im = -rho.im;
    if (!(rho.re > ZERO)) {
        return 0;
    }
    z.re = rinv(cp_sqrt(rho.re * rho.re + rho.im * rho.im));
    z.im = CP_R(3.0) * cp_atan2(rho.im, rho.re);
    for (i = 0; i < DRC_NEWTON; i++) {
        cp_real sl;
        ce12(z, e);
        /* r = E1/E2 - 1, r' = (E1' E2 - E1 E2') / E2^2 */
        r = cdiv(e[0], e[1]);
        r.re -= ONE + rho.re;
        r.im -= rho.im;
        dr = cmul(e[2], e[1]);
        st = cmul(e[0], e[3]);
        dr.re -= st.re;
        dr.im -= st.im;
        dr = cdiv(dr, cmul(e[1], e[1]));
        st = cdiv(r, dr);
        sl = st.re * st.re + st.im * st.im;
        if (sl > ONE) {
            sl = ONE / cp_sqrt(sl);
            st.re *= sl;
            st.im *= sl;
        }
        z.re -= st.re;
        z.im -= st.im;
        z.re = z.re > DRC_Q_MAX ? DRC_Q_MAX : (z.re < -DRC_Q_MAX ? -DRC_Q_MAX : z.re);
    }
    ce12(z, e);
    cc = cdiv(gA, e[1]); /* -C */
    cp_v3_comb(r1, -cc.re, &e1, -cc.im, &e2);
    cp_v3_comb(r1, ONE, r1, -cp_v3_dot(r1, &a->t), &a->t);
    w = cp_v3_norm(r1);
    cp_v3_comb(r1, ONE / w, r1, ZERO, r1);
    x[0] = ZERO;
    x[1] = c;
    x[2] = cp_sqrt(cc.re * cc.re + cc.im * cc.im);
    x[3] = z.re;
    x[4] = z.im;
    return 1;
}

/* 3D insertion: the intrinsic model (above) fitted to the segment, M and T_M its point
 * and tangent at the half arc; where A.2 takes the linear model (an end angle zero, or
 * Re rho <= 0: an inflection) the linear model of A.2: D1 = (G_A - G_B)/4,
 * G_M = -(G_A + G_B)/4, M = A + c/(2 cos al) (cos al d + sin al unit(D1)), al = |D1|. */
static CP_NOINLINE void insert_3d(const struct drc_pt *a, const struct drc_pt *b,
                                  struct drc_pt *m)
{
    struct cp_vec3 d, ga, gb, v1, vm, r1;
    cp_real c, w, al, sn, cs, x[5];
    if (twist_guess(a, b, &d, &c, &ga, &gb, x, &r1)) {
        struct frm f;
        frn_fit(a, b, &r1, c, x);
        frn_start(a, &r1, x[0], &f);
        frn_walk(&f, x, DRC_FRENET_STEPS / 2u);
        cp_v3_comb(&m->p, ONE, &a->p, ONE, &f.p);
        m->t = f.t;
        return;
    }
    cp_v3_comb(&v1, CP_R(0.25), &ga, CP_R(-0.25), &gb);
    cp_v3_comb(&vm, CP_R(-0.25), &ga, CP_R(-0.25), &gb);
    al = cp_v3_norm(&v1);
    cp_sincos(al, &sn, &cs);
    w = HALF * c / cs;
    cp_v3_comb(&v1, w * cs, &d, al > ZERO ? w * sn / al : ZERO, &v1);
    cp_v3_comb(&m->p, ONE, &a->p, ONE, &v1);
    al = cp_v3_norm(&vm);
    cp_sincos(al, &sn, &cs);
    cp_v3_comb(&m->t, cs, &d, al > ZERO ? sn / al : ZERO, &vm);
}

/* Kink of the osculating plane at the vertex b of the segments a -> b -> c: the signed
 * angle about T_b from the binormal of the left arc at its end to the right arc's at its
 * start (both the intrinsic model). Returns 0 with *k = 0 when a segment takes the linear
 * model (no osculating plane to match). */
static int kink_at(const struct drc_pt *a, const struct drc_pt *b, const struct drc_pt *c,
                   cp_real *k)
{
    struct cp_vec3 d, ga, gb, r1, bl, br, x1;
    struct frm f;
    cp_real cl, x[5];
    *k = ZERO;
    if (!twist_guess(a, b, &d, &cl, &ga, &gb, x, &r1)) {
        return 0;
    }
    frn_fit(a, b, &r1, cl, x);
    frn_start(a, &r1, x[0], &f);
    frn_walk(&f, x, DRC_FRENET_STEPS);
    cp_v3_cross(&f.t, &f.n, &bl);
    if (!twist_guess(b, c, &d, &cl, &ga, &gb, x, &r1)) {
        return 0;
    }
    frn_fit(b, c, &r1, cl, x);
    frn_start(b, &r1, x[0], &f);
    cp_v3_cross(&f.t, &f.n, &br);
    cp_v3_cross(&bl, &br, &x1);
    *k = cp_atan2(cp_v3_dot(&x1, &b->t), cp_v3_dot(&bl, &br));
    return 1;
}

/* Step 1, 3D (issue 21): the tangent at every interior vertex is tilted out of its
 * adjoining plane (about the principal normal) until the osculating planes of the two
 * intrinsic arcs meet there without a kink: DRC_KINK_SWEEPS Gauss-Seidel sweeps, each vertex
 * DRC_KINK_SECANT secant steps on the tilt from 0 and DRC_FD. The A3 tilt (orient_3d) is
 * the start value and the end tangents keep it. A kink left at an original vertex is a
 * Dirac in torsion: its discrete value doubles with every pass (docs/DRC-TORSION.md). */
static CP_NOINLINE void kink_3d(const struct cp_vec3 *p, unsigned ps, struct cp_vec3 *t,
                                unsigned ts, uint32_t n)
{
    uint32_t s, j, i;
    for (s = 0; s < DRC_KINK_SWEEPS; s++) {
        for (j = 1; j + 1u < n; j++) {
            struct drc_pt a, b, c;
            struct cp_vec3 t0, u, d0, d1;
            cp_real b0 = ZERO, b1 = DRC_FD, k0, k1, sn, cs, un;
            a.p = p[(j - 1u) * ps];
            a.t = t[(j - 1u) * ts];
            b.p = p[j * ps];
            b.t = t[j * ts];
            c.p = p[(j + 1u) * ps];
            c.t = t[(j + 1u) * ts];
            t0 = b.t;
            cp_v3_sub(&b.p, &a.p, &d0);
            cp_v3_sub(&c.p, &b.p, &d1);
            cp_v3_cross(&d0, &d1, &u);
            cp_v3_comb(&u, ONE, &u, -cp_v3_dot(&u, &t0), &t0);
            un = cp_v3_norm(&u);
            if (!(un > ZERO) || !kink_at(&a, &b, &c, &k0)) {
                continue;
            }
            cp_v3_comb(&u, ONE / un, &u, ZERO, &u);
            for (i = 0; i < DRC_KINK_SECANT; i++) {
                cp_real b2;
                cp_sincos(b1, &sn, &cs);
                cp_v3_comb(&b.t, cs, &t0, sn, &u);
                (void)kink_at(&a, &b, &c, &k1);
                if (!(cp_fabs(k1 - k0) > ZERO)) {
                    break;
                }
                b2 = b1 - k1 * (b1 - b0) / (k1 - k0);
                b0 = b1;
                k0 = k1;
                b1 = b2;
            }
            cp_sincos(b1, &sn, &cs);
            cp_v3_comb(&t[j * ts], cs, &t0, sn, &u);
        }
    }
}

void drc_insert(const struct drc_pt *a, const struct drc_pt *b, int planar, struct drc_pt *m)
{
    if (planar) {
        insert_planar(a, b, m);
    } else {
        insert_3d(a, b, m);
    }
}

int drc_thicken(struct drc_pt *buf, uint32_t n, uint32_t cap, uint32_t *n_out)
{
    uint32_t i;
    int planar;
    *n_out = n >= 1u ? 2u * n - 1u : 0u;
    if (n < 2u) {
        return CP_ERR_TOO_FEW;
    }
    if (cap < 2u * n - 1u) {
        return CP_ERR_BUFFER;
    }
    planar = drc_is_planar(buf, n);
    /* from the back: A, B read before indices 2i..2i+2 are written (2i >= i + 1 for
     * i >= 1, so no unread entry is overwritten) */
    for (i = n - 1u; i-- > 0u;) {
        struct drc_pt a = buf[i], b = buf[i + 1u];
        buf[2u * i + 2u] = b;
        drc_insert(&a, &b, planar, &buf[2u * i + 1u]);
        buf[2u * i] = a;
    }
    return CP_OK;
}

int drc_run(struct drc_pt *buf, uint32_t n, uint32_t passes, uint32_t cap, uint32_t *n_out)
{
    uint32_t k, m = n;
    int err = drc_size(n, passes, n_out);
    if (err != CP_OK) {
        return err;
    }
    if (cap < *n_out) {
        return CP_ERR_BUFFER;
    }
    err = drc_tangents(&buf[0].p, 2u, &buf[0].t, 2u, n);
    if (err != CP_OK) {
        return err;
    }
    for (k = 0; k < passes; k++) {
        err = drc_thicken(buf, m, cap, &m);
        if (err != CP_OK) {
            return err;
        }
    }
    return CP_OK;
}

/* ---- discrete characteristics and measures (A.4); host/test use ---- */

cp_real drc_kappa3(const struct cp_vec3 *a, const struct cp_vec3 *b, const struct cp_vec3 *c,
                   int sgn)
{
    struct cp_vec3 u, v, w, x;
    cp_real lu, lv, lw, s;
    cp_v3_sub(b, a, &u);
    cp_v3_sub(c, b, &v);
    cp_v3_sub(c, a, &w);
    lu = cp_v3_norm(&u);
    lv = cp_v3_norm(&v);
    lw = cp_v3_norm(&w);
    if (!(lu > ZERO && lv > ZERO && lw > ZERO)) {
        return ZERO;
    }
    cp_v3_cross(&u, &v, &x);
    s = cp_v3_norm(&x) / (lu * lv);
    if (sgn && x.z < ZERO) {
        s = -s;
    }
    return CP_R(2.0) * s / lw;
}

cp_real drc_tau4(const struct cp_vec3 *a, const struct cp_vec3 *b, const struct cp_vec3 *c,
                 const struct cp_vec3 *d)
{
    struct cp_vec3 u0, u1, u2, n1, n2, x;
    cp_real l1, l2, l;
    cp_v3_sub(b, a, &u0);
    cp_v3_sub(c, b, &u1);
    cp_v3_sub(d, c, &u2);
    cp_v3_cross(&u0, &u1, &n1);
    cp_v3_cross(&u1, &u2, &n2);
    l1 = cp_v3_norm(&n1);
    l2 = cp_v3_norm(&n2);
    l = cp_v3_norm(&u1);
    if (!(l1 > ZERO && l2 > ZERO && l > ZERO)) {
        return ZERO;
    }
    cp_v3_cross(&n1, &n2, &x);
    return cp_atan2(cp_v3_dot(&x, &u1) / (l * l1 * l2), cp_v3_dot(&n1, &n2) / (l1 * l2)) / l;
}

/* One step of the extremum count: differences below thr are flat. */
static void ext_step(cp_real dk, cp_real thr, int *last, uint32_t *count)
{
    int sg = dk > thr ? 1 : (dk < -thr ? -1 : 0);
    if (sg != 0) {
        if (*last != 0 && sg != *last) {
            (*count)++;
        }
        *last = sg;
    }
}

int drc_measure(const struct cp_vec3 *p, uint32_t n, int sgn, struct drc_measures *m)
{
    cp_real kmax = ZERO, thr, tm = ZERO, kp = ZERO, kpp = ZERO, tp = ZERO;
    uint32_t i;
    int last = 0, lsg = 0, tl = 0;
    m->extrema = m->signs = m->between = m->t_extrema = 0;
    m->kmin = m->kmax = m->tmin = m->tmax = ZERO;
    if (n < 3u) {
        return CP_ERR_TOO_FEW;
    }
    /* pass 1: ranges (the threshold 1e-6 max|k| needs max|k| first) */
    for (i = 1; i + 1u < n; i++) {
        cp_real k = drc_kappa3(&p[i - 1u], &p[i], &p[i + 1u], sgn);
        kmax = cp_fabs(k) > kmax ? cp_fabs(k) : kmax;
        m->kmin = (i == 1u || k < m->kmin) ? k : m->kmin;
        m->kmax = (i == 1u || k > m->kmax) ? k : m->kmax;
    }
    for (i = 1; i + 2u < n; i++) {
        cp_real t = drc_tau4(&p[i - 1u], &p[i], &p[i + 1u], &p[i + 2u]);
        tm = cp_fabs(t) > tm ? cp_fabs(t) : tm;
        m->tmin = (i == 1u || t < m->tmin) ? t : m->tmin;
        m->tmax = (i == 1u || t > m->tmax) ? t : m->tmax;
    }
    thr = CP_R(1e-6) * kmax;
    /* pass 2: extrema, sign changes, between-neighbour violations of odd points */
    for (i = 1; i + 1u < n; i++) {
        cp_real k = drc_kappa3(&p[i - 1u], &p[i], &p[i + 1u], sgn);
        int sg = k > thr ? 1 : (k < -thr ? -1 : 0); /* |k| <= thr counts as 0 */
        if (i >= 2u) {
            ext_step(k - kp, thr, &last, &m->extrema);
        }
        if (sg != 0) {
            m->signs += (lsg != 0 && sg != lsg) ? 1u : 0u;
            lsg = sg;
        }
        if (i >= 3u && ((i - 1u) & 1u)) { /* point i - 1 (odd) between i - 2 and i */
            cp_real lo = kpp < k ? kpp : k, hi = kpp < k ? k : kpp;
            m->between += (kp < lo - thr || kp > hi + thr) ? 1u : 0u;
        }
        kpp = kp;
        kp = k;
    }
    thr = CP_R(1e-6) * tm;
    for (i = 1; i + 2u < n; i++) {
        cp_real t = drc_tau4(&p[i - 1u], &p[i], &p[i + 1u], &p[i + 2u]);
        if (i >= 2u) {
            ext_step(t - tp, thr, &tl, &m->t_extrema);
        }
        tp = t;
    }
    return CP_OK;
}

int drc_in_triangle(const struct drc_pt *a, const struct drc_pt *b, const struct cp_vec3 *m)
{
    /* in the frame of the chord: x along d, y to the side of the turn. The triangle is
     * A, B and X = the tangent lines' intersection; M inside <=> M is on the X side of
     * the chord, on the inner side of both tangent lines. */
    cp_real dx = b->p.x - a->p.x, dy = b->p.y - a->p.y, c = cp_sqrt(dx * dx + dy * dy);
    cp_real mx = m->x - a->p.x, my = m->y - a->p.y, nx = m->x - b->p.x, ny = m->y - b->p.y;
    cp_real ca, cb, cm, sl;
#if CP_REAL_DOUBLE
    sl = CP_R(1e-9) * c;
#else
    sl = CP_R(1e-5) * c;
#endif
    ca = a->t.x * my - a->t.y * mx; /* side of M w.r.t. the tangent line at A */
    cb = b->t.x * ny - b->t.y * nx; /* ... at B */
    cm = dx * my - dy * mx;         /* ... w.r.t. the chord */
    (void)c;
    /* left turn (T_A right of the chord, T_B left of it): the arc bulges to the right of
     * the chord, B and A lie on the positive side of the other end's tangent line, so M
     * is inside iff ca >= 0, cb >= 0 and cm <= 0 (mirrored for a right turn) */
    {
        cp_real sa = dx * a->t.y - dy * a->t.x; /* < 0: T_A right of the chord */
        cp_real sb = dx * b->t.y - dy * b->t.x; /* > 0: T_B left of the chord */
        if (cp_fabs(sa) <= sl * CP_R(1e-3) && cp_fabs(sb) <= sl * CP_R(1e-3)) {
            return cp_fabs(cm) <= sl * c; /* straight: M on the chord */
        }
        if (sa * sb > ZERO) {
            return 1; /* inflection segment: no triangle (not counted) */
        }
        if (sb > ZERO || sa < ZERO) {
            return ca >= -sl && cb >= -sl && cm <= sl * c;
        }
        return ca <= sl && cb <= sl && cm >= -sl * c;
    }
}

/* ---- the streaming iterator (planar) ---- */


#define DRC_SAG_MARGIN CP_R(0.9) /* measured sagitta must be <= 0.9 tol (canal: same) */

/* Radius law over sigma in [0, 1] with derivatives in the arc length s = sigma s_tot:
 * r[0] = R, r[1] = dR/ds, r[2] = d2R/ds2. COS: R = b cos(2 pi k sigma) + c; the others
 * (CONST, LINEAR, the Bernstein CUBIC) as the power-basis cubic rp[] that
 * drc_path_init converts them to, by Horner's rule with derivatives. */
static void rlaw(const struct drc_path *it, cp_real sg, cp_real r[3])
{
    const cp_real *c = it->rp;
    cp_real is = ONE / it->s_tot, r0 = ZERO, r1 = ZERO, r2 = ZERO;
    int i;
    if (it->g->radius == CANAL_R_COS) {
        cp_real w = CP_TWO_PI * c[2], sn, cs;
        cp_sincos(w * sg, &sn, &cs);
        r0 = c[0] * cs + c[1];
        r1 = -c[0] * w * sn;
        r2 = -c[0] * w * w * cs;
    } else {
        for (i = 3; i >= 0; i--) {
            r2 = r2 * sg + TWO * r1;
            r1 = r1 * sg + r0;
            r0 = r0 * sg + c[i];
        }
    }
    r[0] = r0;
    r[1] = r1 * is;
    r[2] = r2 * (is * is);
}

static void orig(const struct drc_path *it, uint32_t i, struct drc_pt *o)
{
    o->p = it->g->p[i];
    o->t = it->tan[i];
}

/* Put the walk at position pos (travel order, 0..steps): cur = the point at pos,
 * stk[d - 1] = the far end (in travel) of the depth-d interval holding the leaf
 * [pos, pos + 1] of its segment's subdivision tree. From pos - 1 (same segment) only the
 * levels below the node of pos are new: ctz(leaf index) inserts, one per point on
 * average; otherwise the descent along the bits of the leaf index (K inserts). Same
 * nodes, same operands (an insert reads only its interval's ends): same bits, so
 * seek(k) reproduces the streamed point exactly. A backward line (dir) inserts with
 * the ends swapped back into curve order. The depth-0 interval is the original segment:
 * its far end is loaded into stk[0] when level 1 is (re)built (there it stays stk[0], or
 * the level-1 midpoint replaces it). pos == steps is the line's last original point: no
 * levels (its segment js = N - 1 is past the last; the point is P_{N-1} forward, P_0
 * backward). */
static void walk_to(struct drc_path *it, uint32_t pos)
{
    uint32_t kk = it->passes, m = pos & ((((uint32_t)1u) << kk) - 1u), z = m, d = 1u, dn = 0u;
    uint32_t js = pos >> kk, top = pos < it->head.steps ? kk : 0u;
    /* the original points at the ends of segment js (travel order, js <= nseg): p0 where
     * travel enters it (curve index js forward, nseg - js backward), p1 = p0 + 1 or
     * p0 - 1 where it leaves (read only with a level, pos < steps: then js < nseg, so
     * p0 >= 1 backward) */
    uint32_t p0 = it->dir ? it->nseg - js : js;
    struct drc_pt tmp;
    if (m != 0u && pos == it->pos + 1u) {
        tmp = it->stk[kk - 1u]; /* the point at pos: the old leaf's far end */
        dn = kk;                /* depth of node pos: K - ctz(m); m has a set bit below K */
        while ((z & 1u) == 0u && dn > 1u) {
            z >>= 1;
            dn--;
        }
        d = dn;
    } else {
        orig(it, p0, &it->cur);
    }
    for (; d <= top; d++) {
        const struct drc_pt *pf = &it->stk[d == 1u ? 0u : d - 2u];
        if (d == 1u) {
            orig(it, it->dir ? p0 - 1u : p0 + 1u, &it->stk[0]);
        }
        if (d != dn) {
            insert_planar(it->dir ? pf : &it->cur, it->dir ? &it->cur : pf, &tmp);
        }
        if ((m >> (kk - d)) & 1u) {
            it->stk[d - 1u] = *pf; /* (d = 1: stk[0] itself, exact overlap) */
            it->cur = tmp;
        } else {
            it->stk[d - 1u] = tmp;
        }
    }
    it->pos = pos;
}

/* Label of line j (contact-frame start angle u_j = u0 + j (u1 - u0)/(n - 1) on the first
 * circle): alpha = q0 cos(u_j/2), b = sin(u_j/2) (canal.h). */
static void label(const struct drc_path *it, uint32_t j, cp_real *a, cp_real *b)
{
    const struct raster_cfg *rc = it->rc;
    cp_real cs, du = it->head.n > 1u ? (rc->u1 - rc->u0) / (cp_real)(it->head.n - 1u) : ZERO;
    cp_sincos(HALF * (rc->u0 + (cp_real)j * du), b, &cs);
    *a = it->q0 * cs;
}

/* Start line jl at its first point: direction, walk, arc length, Lambda, R, label. */
static void line_start(struct drc_path *it, uint32_t jl)
{
    cp_real r[3];
    it->line = (int32_t)jl;
    it->dir = (uint8_t)(jl & 1u); /* (CURVE mode and the curve walk: line 0 only) */
    walk_to(it, 0u);
    it->s = it->dir ? it->s_tot : ZERO;
    it->lam = it->dir ? it->lam_tot : ZERO;
    it->kap = it->kend[it->dir]; /* the end leaf's curvature: the start point is checked */
    rlaw(it, (cp_real)it->dir, r); /* sigma 1 or 0 */
    it->r_cur = r[0];
    label(it, jl, &it->lab_a, &it->lab_b);
}

static CP_NOINLINE cp_real walk_sigma(const struct drc_path *it)
{
    cp_real sg = it->s / it->s_tot;
    return sg < ZERO ? ZERO : (sg > ONE ? ONE : sg);
}

/* One step along the line (pos -> pos + 1) with the sums over the leaf a -> b (curve
 * order) of chord h and turn th (of the end tangents): s += the leaf's arc length, h times
 * the arc/chord ratio of a circle of that turn, (th/2)/sin(th/2) = 1 + (1 - cos th)/12 +
 * O(th^4) (relative error < th^4/300 <= 1e-9 for the leaf turns here; a backward line
 * subtracts, s runs from s_tot down), and Lambda = integral kappa dR over the leaf as
 * kap dR with kap = kappa_leaf = 2 sin(th/2)/h (the circle through the leaf's ends with
 * those tangents; exact for circles). Error per leaf: arc cov(kappa, p) <= arc^3
 * max|kappa'| max|p'| / 12 (p = dR/ds): O(h^2) over the curve, 4x smaller per pass;
 * exact when C is a circle (Lambda = kappa (R - R0), MATH-canal). A backward line
 * subtracts the same leaf terms (Lambda_i = Lambda_{i+1} - kappa (R_{i+1} - R_i)), so
 * every line's Lambda at a point is the same sum. In CURVE mode Lambda is unused. */
static void line_step(struct drc_path *it)
{
    const struct drc_pt a = it->cur, *b = &it->cur; /* a -> b in travel order */
    cp_real r[3], dx, dy, h, c, kap;
    walk_to(it, it->pos + 1u);
    dx = b->p.x - a.p.x;
    dy = b->p.y - a.p.y;
    h = cp_sqrt(dx * dx + dy * dy);
    c = a.t.x * b->t.x + a.t.y * b->t.y;
    /* 2 sin(th/2) = 2 sin th / sqrt(2 (1 + cos th)); |th| < 90 deg so 1 + c > 1 */
    kap = TWO * (a.t.x * b->t.y - a.t.y * b->t.x) / (cp_sqrt(TWO * (ONE + c)) * h);
    h *= ONE + (ONE - c) / CP_R(12.0);
    if (it->dir) { /* curve order b -> a: the cross product and the arc-length step change
                      sign, exactly (h and c are symmetric in a, b; 0 - kap keeps a zero
                      curvature +0, as the cross product in curve order gives) */
        kap = ZERO - kap;
        h = -h;
    }
    it->kap = kap;
    if (it->pos == 1u) {
        it->kend[it->dir] = kap; /* the end leaf of the line's start (init: kend[1]) */
    }
    it->s += h;
    rlaw(it, walk_sigma(it), r);
    it->lam += kap * (r[0] - it->r_cur); /* the same in both directions */
    it->r_cur = r[0];
}

/* Frame of the canal surface at point q, sigma sg, curvature kap. */
static CP_NOINLINE void frame_at(const struct drc_path *it, const struct drc_pt *q, cp_real sg,
                     cp_real kap, struct canal_frame *f)
{
    cp_real r[3];
    rlaw(it, sg, r);
    f->x = q->p.x;
    f->y = q->p.y;
    f->tx = q->t.x;
    f->ty = q->t.y;
    f->r = r[0];
    f->p = r[1];
    f->q2 = ONE + r[1] * r[1];
    f->kappa = kap;
    f->dpds = r[2];
}

/* Link jl -> jl + 1 at fraction fr: it runs on the end circle of line jl (its last
 * point for even jl, its first for odd jl) from line jl's point to line jl + 1's, at
 * uniform contact-frame angle u = ua + fr d (d = the signed gap, the short way); the
 * family-1 label there is (q cos(u/2), sin(u/2)) (canal.h), computed here in half
 * angles. Returns the gap |d|. */
static CP_NOINLINE cp_real link_at(const struct drc_path *it, uint32_t jl, cp_real fr,
                       struct canal_frame *f, cp_real *h, cp_real *b)
{
    struct drc_pt q;
    int end = (jl & 1u) == 0u;
    cp_real lam = end ? it->lam_tot : ZERO, qq, ha, ba, hb, bb, d;
    orig(it, (uint32_t)end * it->nseg, &q);
    frame_at(it, &q, (cp_real)end, it->kend[end], f); /* sigma 1 or 0 */
    qq = cp_sqrt(f->q2);
    label(it, jl, &ha, &ba);
    label(it, jl + 1u, &hb, &bb);
    ha += lam * ba;
    hb += lam * bb;
    d = cp_atan2(ha * qq * bb - qq * ba * hb, ha * hb + qq * qq * ba * bb);
    cp_sincos(cp_atan2(qq * ba, ha) + fr * d, b, &ha);
    *h = qq * ha;
    return TWO * cp_fabs(d);
}

/* Point r of block jl (line jl: r = 0..steps in travel order; r > steps: point r - steps
 * of the link jl -> jl + 1) into pt. Positions the walk: CURVE mode by the tree descent
 * (or one step), EDGE mode by re-walking the line from its start when it is not ahead
 * (Lambda and s are sequential sums, so a seek re-walks, same bits). EDGE: the canal
 * point (surface, tool centre or tip). Checks (init; next() ignores them): R > 0, tool
 * radius < R, and regularity of the surface and of the tool's offset surface,
 * D b^2 > eps (q^2 b^2 + h^2), at every point (issue 6, B2): kappa is the curvature of
 * the leaf walked into the point; at a line's first point and on the links (the end
 * circles) the end leaf's, kend[], recorded by the forward walks. */
static CP_NOINLINE int point_at(struct drc_path *it, uint32_t jl, uint32_t r,
                                struct raster_pt *pt)
{
    const struct raster_cfg *rc = it->rc;
    struct canal_frame f;
    struct canal_point cp;
    /* the radius offset: 0 for OUT_SURFACE, else tool_r; EDGE mode (the only user) has
     * tool_r == 0 exactly with OUT_SURFACE (init), and + ZERO turns a -0 into +0 */
    cp_real h, b, off = rc->tool_r + ZERO;
    pt->line = -1;
    pt->t = (jl & 1u) ? ZERO : ONE;
    if (r > it->head.steps) {
        pt->index = (uint16_t)(r - it->head.steps);
        (void)link_at(it, jl, (cp_real)(r - it->head.steps) / (cp_real)(it->head.link + 1u), &f, &h, &b);
    } else {
        if (it->line != (int32_t)jl || it->pos > r) {
            line_start(it, jl);
        }
        if (!it->edge && it->pos + 1u < r) {
            walk_to(it, r);
        }
        while (it->pos < r) {
            line_step(it);
        }
        if (!it->dir && r == it->head.steps) {
            it->lam_tot = it->lam; /* a forward line's sum: backward lines start here */
        }
        pt->line = (int16_t)jl;
        pt->index = (uint16_t)(it->dir ? it->head.steps - r : r);
        pt->p = it->cur.p;
        pt->n = it->cur.t;
        pt->t = (cp_real)r / (cp_real)it->head.steps;
        if (!it->edge) {
            return CP_OK;
        }
        pt->t = walk_sigma(it);
        frame_at(it, &it->cur, pt->t, it->kap, &f);
        h = it->lab_a + it->lam * it->lab_b;
        b = it->lab_b;
        if (!(f.r > ZERO)) {
            return CP_ERR_RADIUS;
        }
        if (!(f.r > rc->tool_r)) { /* (init: 0 <= tool_r, so here tool_r >= R > 0) */
            return CP_ERR_TOOL;
        }
    }
    canal_point(&f, h, b, off, &cp);
    pt->p = cp.m;
    pt->n = cp.n;
    if (rc->output == RASTER_OUT_TIP) {
        pt->p.z -= off;
    }
    return canal_regular(&f, h, b, rc->tool_r) ? CP_OK : CP_ERR_CUSP;
}

/* 1 if the point's position is finite (finite coordinates, |p| <= ~1e5 mm, cannot
 * overflow the sum; a NaN or Inf makes it non-finite). */
static CP_NOINLINE int pt_finite(const struct raster_pt *pt)
{
    return cp_finite(pt->p.x + pt->p.y + pt->p.z);
}

/* Walk the points r = lo..hi of blocks 0..nb-1 (the curve: 1; the lines: n; the links:
 * n - 1, none after the last line): the checks of point_at, finite points, and the
 * largest sagitta of the lines (deviation of each point from its neighbours' chord / 4:
 * exact for circular arcs of equal steps) into *sag. A point equal to the one two steps
 * back (zero chord, NaN sagitta) is CP_ERR_NUMERIC, not skipped: AUTO must not stop on
 * an unmeasured line. */
static CP_NOINLINE int walk(struct drc_path *it, uint32_t nb, uint32_t lo, uint32_t hi,
                            cp_real *sag)
{
    struct raster_pt pt;
    struct cp_vec3 q0, q1, u, v;
    cp_real x;
    uint32_t jl, r;
    int err;
    q0 = q1 = it->cur.p; /* (set by r = 0 and 1 before use) */
    for (jl = 0; jl < nb; jl++) {
        for (r = lo; r <= hi; r++) {
            err = point_at(it, jl, r, &pt);
            if (err != CP_OK) {
                return err;
            }
            if (!pt_finite(&pt)) {
                return CP_ERR_NUMERIC;
            }
            if (r >= 2u && r <= it->head.steps) { /* distance of q1 from the chord q0 pt.p */
                cp_v3_sub(&pt.p, &q0, &u);
                cp_v3_sub(&q1, &q0, &v);
                x = -cp_v3_dot(&u, &v) / cp_v3_dot(&u, &u); /* v -= (u.v / u.u) u (x u + v: the sum
                                                     v + x u, bit for bit) */
                cp_v3_comb(&v, x, &u, ONE, &v);
                x = CP_R(0.25) * cp_v3_norm(&v);
                if (!(x >= ZERO)) { /* NaN: pt == q0 (a zero chord), no sagitta (B4) */
                    return CP_ERR_NUMERIC;
                }
                *sag = x > *sag ? x : *sag;
            }
            q0 = q1;
            q1 = pt.p;
        }
    }
    return CP_OK;
}

/* drc_path_init, step 1: the checks that need no geometry, in the order of drc.h (g and
 * edge, raster_check, passes, the radius parameters: a non-finite sum is one
 * CP_ERR_NONFINITE, huge finite values that overflow included; the EDGE extras), and the
 * radius law in the power basis (COS kept as b, c, k) into it->rp. */
static int init_checks(struct drc_path *it, const struct drc_cfg *g, const struct raster_cfg *rc)
{
    cp_real *c = it->rp, x;
    uint32_t i;
    int err;
    if (g == NULL || g->edge > 1u) {
        return CP_ERR_INVAL;
    }
    /* the raster, checked as for every model (raster_check; in CURVE mode too, although
     * it uses only tol) */
    err = raster_check(rc, CP_PI);
    if (err != CP_OK) {
        return err;
    }
    if (g->passes != DRC_PASSES_AUTO && g->passes > CP_MAX_PASSES) {
        return CP_ERR_TOO_MANY;
    }
    /* (the sum is checked in CURVE mode too, the parameters are used in EDGE mode only) */
    x = g->rp[0] + g->rp[1] + g->rp[2] + g->rp[3];
    if (!cp_finite(x)) {
        return CP_ERR_NONFINITE;
    }
    /* AUTO needs the tolerance (raster_check: 0 or in [1e-5, 10]) */
    if (g->passes == DRC_PASSES_AUTO && rc->tol == ZERO) {
        return CP_ERR_RANGE;
    }
    for (i = 0; i < 4u; i++) {
        c[i] = g->rp[i];
        if (g->edge && cp_fabs(c[i]) > CANAL_COORD_MAX) {
            return CP_ERR_RADIUS;
        }
    }
    if (!g->edge) {
        return CP_OK;
    }
    /* EDGE extras: angle labels, LINES, a canal radius law, and a tool radius exactly
     * with a tool output (raster_check: none with OUT_SURFACE) */
    if (rc->labels != RASTER_LABEL_ANGLE || rc->mode != RASTER_LINES ||
        g->radius > CANAL_R_CUBIC || (rc->output != RASTER_OUT_SURFACE && rc->tool_r == ZERO)) {
        return CP_ERR_INVAL;
    }
    if (g->radius == CANAL_R_CUBIC) { /* Bernstein -> power basis */
        x = c[1] - c[2];
        c[3] += CP_R(3.0) * x - c[0];
        c[2] = CP_R(3.0) * (c[0] - c[1] - x);
        c[1] = CP_R(3.0) * (c[1] - c[0]);
    } else if (g->radius != CANAL_R_COS) { /* CONST, LINEAR */
        c[1] = g->radius == CANAL_R_LINEAR ? c[1] - c[0] : ZERO;
        c[2] = ZERO;
        c[3] = ZERO;
    }
    return CP_OK;
}

/* drc_path_init, step 3: the passes K. AUTO: K = 1, 2, ... until the sagitta fits
 * (CP_ERR_TOL when even CP_MAX_PASSES does not); else the one K (g->passes is at most
 * CP_MAX_PASSES here, and that iteration ends the loop). Each K walks the curve (its
 * sagitta, the arc length that scales sigma) and in EDGE mode every line (R, tool, cusp,
 * sagitta; Lambda on the way). */
static int init_passes(struct drc_path *it, const struct drc_cfg *g, cp_real tol)
{
    uint32_t kk;
    uint8_t edge = it->edge;
    int au = g->passes == DRC_PASSES_AUTO, err;
    for (kk = au ? 1u : g->passes; kk <= CP_MAX_PASSES; kk++) {
        cp_real sag = ZERO;
#if ((CP_MAX_DRC_POINTS - 1) << CP_MAX_PASSES) > CP_MAX_STEPS /* (else it cannot fail) */
        if (((uint32_t)it->nseg << kk) > CP_MAX_STEPS) {
            return au ? CP_ERR_TOL : CP_ERR_TOO_MANY;
        }
#endif
        it->passes = (uint8_t)kk;
        it->head.steps = (uint16_t)(it->nseg << kk);
        /* the curve itself: its sagitta, and the arc length (sigma's scale) */
        it->edge = 0u;
        err = walk(it, 1u, 0u, it->head.steps, &sag);
        it->s_tot = it->s;
        it->kend[1] = it->kap; /* the last leaf's curvature (P_{N-1} end circle) */
        it->edge = edge;
        if (err == CP_OK && edge) {
            cp_real r[3];
            rlaw(it, ZERO, r);
            it->q0 = cp_sqrt(ONE + r[1] * r[1]);
            err = walk(it, it->head.n, 0u, it->head.steps, &sag);
        }
        if (err != CP_OK) {
            return err;
        }
        if (!au || sag <= DRC_SAG_MARGIN * tol) {
            return CP_OK;
        }
    }
    return CP_ERR_TOL;
}

/* drc_path_init, step 4 (EDGE mode): the link points, uniform angle steps on the end
 * circle (radius (R - off)/q), so the chord tolerance fixes them: step 4 x sqrt(tol /
 * 2 rad) DRC_SAG_MARGIN (x <= asin x: the sagitta of that step is <= 0.81 tol); then
 * every link point is checked (regularity, finite). */
static int init_links(struct drc_path *it, const struct raster_cfg *rc)
{
    cp_real worst = ONE, h, b, x, t = rc->tol, sag = ZERO;
    struct canal_frame f;
    uint32_t i;
    for (i = 0; i + 1u < it->head.n; i++) {
        x = link_at(it, i, ZERO, &f, &h, &b);
        h = (f.r - rc->tool_r) / cp_sqrt(f.q2); /* (R - off)/q, off as point_at's */
        if (h > t && t > ZERO) {
            x = cp_ceil(x / (CP_R(4.0) * DRC_SAG_MARGIN * cp_sqrt(t / (TWO * h))));
            worst = x > worst ? x : worst;
        }
    }
    if (!(worst - ONE <= (cp_real)CP_MAX_LINK)) {
        return CP_ERR_TOL;
    }
    it->head.link = rc->link != RASTER_LINK_AUTO ? rc->link : (uint16_t)(worst - ONE);
    return walk(it, it->head.n - 1u, it->head.steps + 1u,
                (uint32_t)it->head.steps + it->head.link, &sag);
}

int drc_path_init(struct drc_path *it, const struct drc_cfg *g, const struct raster_cfg *rc)
{
    int err;
    it->head.count = 0;
    it->head.k = 0;
    it->head.overlap = 0u; /* not checked (raster.h) */
    it->line = -1;
    it->g = g;
    it->rc = rc;
    /* step 1: the checks without geometry, the radius law */
    err = init_checks(it, g, rc);
    if (err != CP_OK) {
        return err;
    }
    it->edge = g->edge;
    it->head.n = it->edge ? rc->n : 1u;
    it->head.link = 0u;
    it->s_tot = ONE;
    it->lam_tot = ZERO;
    it->kend[0] = ZERO;
    it->kend[1] = ZERO;
    it->q0 = ONE;
    /* step 2: the points and their tangents */
    err = tangents_planar(g->p, 1u, it->tan, 1u, g->n);
    if (err != CP_OK) {
        return err;
    }
    it->nseg = (uint8_t)(g->n - 1u);
    /* step 3: the passes (every line walked); step 4: the links (every link walked) */
    err = init_passes(it, g, rc->tol);
    if (err == CP_OK && it->edge) {
        err = init_links(it, rc);
    }
    if (err != CP_OK) {
        return err;
    }
    it->head.mode = RASTER_LINES;
    it->head.count = raster_count(it->head.n, it->head.steps, it->head.link);
    it->line = -1;
    return CP_OK;
}

uint32_t drc_path_count(const struct drc_path *it)
{
    return it->head.count;
}

int drc_path_seek(struct drc_path *it, uint32_t k)
{
    it->line = -1; /* next() re-positions (descent or re-walk of the line) */
    return raster_seek(&it->head, k);
}

int drc_path_next(struct drc_path *it, struct raster_pt *pt)
{
    uint32_t block = (uint32_t)it->head.steps + 1u + it->head.link;
    struct raster_pt q;
    if (it->head.k >= it->head.count) {
        return CP_ERR_DONE;
    }
    (void)point_at(it, it->head.k / block, it->head.k % block, &q);
    /* as the other models: a non-finite point is not written, k unchanged (n is
     * finite with p: EDGE p = C + (R - off) n, CURVE p and t from the same angles) */
    if (!pt_finite(&q)) {
        return CP_ERR_NUMERIC;
    }
    *pt = q;
    it->head.k++;
    return CP_OK;
}

#if CP_REAL_DOUBLE
CP_STATIC_ASSERT(sizeof(struct drc_path) <= 2u * 480u, drc_path_fits);
CP_STATIC_ASSERT(sizeof(struct drc_cfg) <= 2u * 320u, drc_cfg_fits);
#else
CP_STATIC_ASSERT(sizeof(struct drc_path) <= 480u, drc_path_fits);
CP_STATIC_ASSERT(sizeof(struct drc_cfg) <= 320u, drc_cfg_fits);
#endif
CP_STATIC_ASSERT(sizeof(struct drc_pt) == 2u * sizeof(struct cp_vec3), drc_pt_packed);
