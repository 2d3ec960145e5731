/* test_canal_ref.c - the firmware surface and toolpath against the published test
 * vectors (MATH-canal §7) and against the independent reference (ref_canal.c).
 * SPDX-License-Identifier: MIT
 *
 * Every figure is measured; nothing is hard-coded but the §7 vectors. The reference
 * integrates the orthogonal-trajectory ODE adaptively (no closed form), so agreement
 * with the firmware's one-quadrature formula is a real check of both.
 * Memory: the static data of this file is a few KB; stack per test < 4 KB.
 */
#include <string.h>

#include "ref_canal.h"
#include "test.h"
#include "canal_path.h"

#define PI_D 3.14159265358979323846

#if CP_REAL_DOUBLE
#define VEC_TOL 1e-9  /* mm, §7 vectors through the firmware API */
#define REF_TOL 1e-6  /* mm, toolpath points vs the reference */
#define NRM_TOL 1e-9  /* unit normals vs the reference */
#else
#define VEC_TOL 1e-5
#define REF_TOL 1e-3
#define NRM_TOL 1e-5
#endif

/* ------------------------------------------------------------------ shapes */

struct shape {
    const char *name;
    uint8_t curve, radius;
    double cp[8], rp[4];
    double u0, u1; /* band of start angles; (u1 - u0)/(n - 1) is dyadic, so every line's
                      start angle is exact in float and double */
    uint16_t n, steps, substeps;
};

enum { SH_PAPER, SH_ELLIPSE, SH_BEZIER, SH_LINE, SH_CWARC, SH_COUNT };

static const struct shape shapes[SH_COUNT] = {
    /* the paper's example: R = 5.5 cos 2t + 10.5 on the radius-3 circle, regular band
       (w > 10.454 or w < 0.2126, MATH-canal §7) */
    {"paper", CANAL_ARC, CANAL_R_COS, {0.0, 0.0, 3.0, 0.0, 2.0 * PI_D}, {5.5, 10.5, 2.0},
     -0.5, 0.125, 6, 128, 8},
    /* elliptic arc, COS law with k = 3 on the true angle */
    {"ellipse", CANAL_ELLIPSE, CANAL_R_COS, {1.0, -2.0, 20.0, 12.0, 0.3, 2.5}, {1.5, 6.0, 3.0},
     -0.5, 0.5, 5, 96, 8},
    /* S-shaped cubic Bezier (inflection at s = 1/2), CUBIC radius law */
    {"bezier-S", CANAL_BEZIER, CANAL_R_CUBIC, {0.0, 0.0, 10.0, 15.0, 20.0, -15.0, 30.0, 0.0},
     {3.0, 5.0, 2.0, 4.0}, -0.5, 0.5, 3, 128, 8},
    /* straight line with a non-linear (CUBIC) radius */
    {"line-cubic", CANAL_LINE, CANAL_R_CUBIC, {0.0, 0.0, 40.0, 10.0}, {2.0, 6.0, 1.0, 3.0},
     -1.0, 1.0, 5, 64, 8},
    /* clockwise arc (a1 < a0: t = -angle, left = outside), LINEAR radius */
    {"cw-arc", CANAL_ARC, CANAL_R_LINEAR, {5.0, 5.0, 15.0, 2.0, -1.0}, {3.0, 6.0}, -0.5, 0.5, 3,
     96, 8},
};

static void shape_cfg(const struct shape *s, struct canal_cfg *g, struct raster_cfg *c)
{
    static const struct raster_cfg zero;
    static const struct canal_cfg gzero;
    int i;
    *c = zero;
    *g = gzero;
    g->curve = s->curve;
    g->radius = s->radius;
    for (i = 0; i < 8; i++) {
        g->cp[i] = (cp_real)s->cp[i];
    }
    for (i = 0; i < 4; i++) {
        g->rp[i] = (cp_real)s->rp[i];
    }
    c->mode = RASTER_LINES;
    c->output = RASTER_OUT_SURFACE;
    c->labels = RASTER_LABEL_ANGLE;
    c->n = s->n;
    c->u0 = (cp_real)s->u0;
    c->u1 = (cp_real)s->u1;
    c->steps = s->steps;
    c->substeps = s->substeps;
    c->link = 3;
    c->tol = CP_R(0.0);
    c->tool_r = CP_R(0.0);
}

/* The reference built from the firmware's validated copy of the parameters (the
 * cp_real values actually used, widened to double). */
static void ref_from(struct ref_canal *rc, const struct canal *s)
{
    double cp[8], rp[4];
    int i;
    for (i = 0; i < 8; i++) {
        cp[i] = (double)s->cp[i];
    }
    for (i = 0; i < 4; i++) {
        rp[i] = (double)s->rp[i];
    }
    ref_canal_set(rc, s->curve, s->radius, cp, rp);
}

static double line_u0(const struct raster_cfg *c, int j)
{
    if (c->n < 2u) {
        return (double)c->u0;
    }
    return (double)c->u0 + (double)j * ((double)c->u1 - (double)c->u0) / (double)(c->n - 1u);
}

static double dist3d(const double a[3], const struct cp_vec3 *b)
{
    double dx = a[0] - (double)b->x, dy = a[1] - (double)b->y, dz = a[2] - (double)b->z;
    return sqrt(dx * dx + dy * dy + dz * dz);
}

static void vec_of(const struct cp_vec3 *v, double o[3])
{
    o[0] = (double)v->x;
    o[1] = (double)v->y;
    o[2] = (double)v->z;
}

/* distance of x from the segment a-b */
static double seg_dist(const double x[3], const double a[3], const double b[3])
{
    double d[3], e[3], dd = 0.0, de = 0.0, s, r = 0.0;
    int i;
    for (i = 0; i < 3; i++) {
        d[i] = b[i] - a[i];
        e[i] = x[i] - a[i];
        dd += d[i] * d[i];
        de += d[i] * e[i];
    }
    s = dd > 0.0 ? de / dd : 0.0;
    s = s < 0.0 ? 0.0 : (s > 1.0 ? 1.0 : s);
    for (i = 0; i < 3; i++) {
        double w = e[i] - s * d[i];
        r += w * w;
    }
    return sqrt(r);
}

#define MAXL 8

/* ------------------------------------------------------------ MATH-canal §7 */

/* points on the characteristic circles: t, u, x, y, z */
static const double vec_circ[12][5] = {
    {0.0, 0.0, 3.0, 0.0, 0.0},
    {0.0, PI_D / 2, -13.0, 0.0, 16.0},
    {0.0, PI_D, 3.0, 0.0, 32.0},
    {0.0, 3 * PI_D / 2, 19.0, 0.0, 16.0},
    {PI_D / 4, 0.0, 2.121320344, 2.121320344, 0.0},
    {PI_D / 4, PI_D / 2, -1.716938262, 2.052484810, 0.7269230769},
    {PI_D / 4, PI_D, -1.648102728, 5.890743416, 1.453846154},
    {PI_D / 4, 3 * PI_D / 2, 2.190155877, 5.959578949, 0.7269230769},
    {PI_D / 2, 0.0, 0.0, 3.0, 0.0},
    {PI_D / 2, PI_D / 2, 0.0, -2.0, 5.0},
    {PI_D / 2, PI_D, 0.0, 3.0, 10.0},
    {PI_D / 2, 3 * PI_D / 2, 0.0, 8.0, 5.0},
};

/* curvature lines: w, t, u, x, y, z (rows of one w in increasing t) */
static const double vec_line[13][6] = {
    {-6, 0.0, 5.952887952, 8.189189189, 0.0, 0.8648648649},
    {-6, PI_D / 4, 5.379740691, 2.937511755, 4.374008638, 0.2770245511},
    {-6, PI_D / 2, 6.077022090, 0.0, 4.023529412, 0.1058823529},
    {-6, PI_D, 5.952887952, -8.189189189, 0.0, 0.8648648649},
    {-2, 0.0, 5.355890089, 15.8, 0.0, 6.4},
    {-2, PI_D / 4, 4.720968685, 2.206254047, 5.943336978, 0.7206863680},
    {-2, PI_D / 2, 5.933840909, 0.0, 4.711409396, 0.3020134228},
    {2, 0.0, 0.927295218, -9.8, 0.0, 6.4},
    {2, PI_D / 4, 3.053943009, -1.811876301, 5.712499889, 1.451055662},
    {2, PI_D / 2, 5.202346307, 0.0, 7.411764706, 2.647058824},
    {12, 0.0, 0.1662824638, 0.3517241379, 0.0, 0.2206896552},
    {12, PI_D / 4, 0.7154855499, 0.3776460409, 1.302003503, 0.1782598444},
    {12, PI_D / 2, 0.2388578520, 0.0, 1.817034700, 0.1419558360},
};

/* Lambda(t) = int_0^t g by composite Simpson over the firmware's own integrand
 * (canal_g of canal_jet), summed in double: 4096 panels per pi (error < 1e-12). */
static double lambda_loop(const struct canal *c, double t)
{
    int n = 2 * (int)ceil(2048.0 * t / PI_D), i;
    double h, sum = 0.0;
    struct canal_jet j;
    if (n == 0) {
        return 0.0;
    }
    h = t / n;
    for (i = 0; i <= n; i++) {
        double w = (i == 0 || i == n) ? 1.0 : ((i & 1) ? 4.0 : 2.0);
        canal_jet(c, (cp_real)(h * i), &j);
        sum += w * (double)canal_g(&j);
    }
    return sum * h / 3.0;
}

static double wrap2pi(double a)
{
    a = fmod(a, 2.0 * PI_D);
    return a < 0.0 ? a + 2.0 * PI_D : a;
}

int test_canal_vectors(void)
{
    struct raster_cfg cfg;
    struct canal_cfg surf;
    struct canal c;
    struct canal_jet j;
    struct canal_frame f, f0;
    struct canal_point pt;
    struct ref_canal rc;
    double m[3], nn[3], fw_worst = 0.0, ref_worst = 0.0, refu_worst = 0.0;
    double lam_cache[3] = {0.0, 0.0, 0.0}; /* pi/4, pi/2, pi */
    int i;
    shape_cfg(&shapes[SH_PAPER], &surf, &cfg);
    CHECK_EQ_INT(canal_init(&c, &surf), CP_OK);
    /* the reference uses the exact example (double pi), not the float copy */
    {
        static const double cp[8] = {0.0, 0.0, 3.0, 0.0, 2.0 * PI_D, 0, 0, 0};
        static const double rp[4] = {5.5, 10.5, 2.0, 0.0};
        ref_canal_set(&rc, REF_ARC, REF_R_COS, cp, rp);
    }
    /* table 1: points on circles, firmware (label of angle u on the circle at t) and reference */
    for (i = 0; i < 12; i++) {
        const double *v = vec_circ[i];
        cp_real al, b;
        double e;
        canal_jet(&c, (cp_real)v[0], &j);
        canal_frame(&j, &f);
        canal_label(&f, (cp_real)v[1], &al, &b);
        canal_point(&f, al, b, CP_R(0.0), &pt);
        CHECK_NEAR(pt.m.x, v[2], VEC_TOL, 0.0);
        CHECK_NEAR(pt.m.y, v[3], VEC_TOL, 0.0);
        CHECK_NEAR(pt.m.z, v[4], VEC_TOL, 0.0);
        e = fabs((double)pt.m.x - v[2]) + fabs((double)pt.m.y - v[3]) + fabs((double)pt.m.z - v[4]);
        fw_worst = e > fw_worst ? e : fw_worst;
        ref_point(&rc, v[0], v[1], m, nn);
        CHECK_NEAR(m[0], v[2], 1e-9, 0.0);
        CHECK_NEAR(m[1], v[3], 1e-9, 0.0);
        CHECK_NEAR(m[2], v[4], 1e-9, 0.0);
        e = fabs(m[0] - v[2]) + fabs(m[1] - v[3]) + fabs(m[2] - v[4]);
        ref_worst = e > ref_worst ? e : ref_worst;
    }
    /* table 2: curvature lines w = const, u0 = 2 atan2(1, w) at t0 = 0 (q0 = 1) */
    canal_jet(&c, CP_R(0.0), &j);
    canal_frame(&j, &f0);
    CHECK_NEAR(f0.q2, 1.0, 1e-12, 0.0);
    lam_cache[0] = lambda_loop(&c, PI_D / 4);
    lam_cache[1] = lambda_loop(&c, PI_D / 2);
    lam_cache[2] = lambda_loop(&c, PI_D);
    for (i = 0; i < 13;) {
        double w = vec_line[i][0], u0 = 2.0 * atan2(1.0, w);
        struct ref_line rl;
        cp_real al, b;
        canal_label(&f0, (cp_real)u0, &al, &b);
        ref_line_start(&rl, &rc, 0.0, u0);
        for (; i < 13 && vec_line[i][0] == w; i++) {
            const double *v = vec_line[i];
            double lam = v[1] == 0.0 ? 0.0 : (v[1] < 1.0 ? lam_cache[0] : (v[1] < 2.0 ? lam_cache[1] : lam_cache[2]));
            double e;
            canal_jet(&c, (cp_real)v[1], &j);
            canal_frame(&j, &f);
            canal_point(&f, (cp_real)((double)al + lam * (double)b), b, CP_R(0.0), &pt);
            CHECK_NEAR(pt.m.x, v[3], VEC_TOL, 0.0);
            CHECK_NEAR(pt.m.y, v[4], VEC_TOL, 0.0);
            CHECK_NEAR(pt.m.z, v[5], VEC_TOL, 0.0);
            e = fabs((double)pt.m.x - v[3]) + fabs((double)pt.m.y - v[4]) + fabs((double)pt.m.z - v[5]);
            fw_worst = e > fw_worst ? e : fw_worst;
            /* the reference: adaptive integration of the ODE, no closed form */
            CHECK_EQ_INT(ref_line_advance(&rl, v[1]), 0);
            ref_point(&rc, v[1], rl.u, m, nn);
            CHECK_NEAR(m[0], v[3], 1e-9, 0.0);
            CHECK_NEAR(m[1], v[4], 1e-9, 0.0);
            CHECK_NEAR(m[2], v[5], 1e-9, 0.0);
            CHECK_NEAR(wrap2pi(rl.u), v[2], 1e-9, 0.0);
            e = fabs(m[0] - v[3]) + fabs(m[1] - v[4]) + fabs(m[2] - v[5]);
            ref_worst = e > ref_worst ? e : ref_worst;
            e = fabs(wrap2pi(rl.u) - v[2]);
            refu_worst = e > refu_worst ? e : refu_worst;
        }
    }
    TEST_NOTE("MATH-canal sec. 7 vectors: firmware (%s) max |err|_1 %.3g mm; reference %.3g mm, "
              "u %.3g rad\n", CP_REAL_NAME, fw_worst, ref_worst, refu_worst);
    return 0;
}

/* --------------------------------------------- reference self-consistency */

/* The reference's own derivatives against central differences (jets of C and R,
 * the analytic m_t, m_u), and the envelope conditions, on every shape: a wrong
 * derivative in the reference would otherwise silently bias every other test. */
int test_canal_ref_selfcheck(void)
{
    int si, k;
    double worst = 0.0;
    for (si = 0; si < SH_COUNT; si++) {
        struct raster_cfg cfg;
        struct canal_cfg surf;
        struct canal c;
        struct ref_canal rc;
        shape_cfg(&shapes[si], &surf, &cfg);
        CHECK_EQ_INT(canal_init(&c, &surf), CP_OK);
        ref_from(&rc, &c);
        for (k = 0; k <= 8; k++) {
            double t = rc.t0 + (rc.t1 - rc.t0) * (0.03 + 0.94 * k / 8.0);
            double hs = 1e-4 * (rc.t1 - rc.t0), hu = 1e-3, u = -0.9 + 0.3 * k;
            struct ref_jet a, b, a2, b2, j0;
            double m[3], mt[3], mu[3], pa[3], pb[3], pa2[3], pb2[3], na[3], cen[3], ax[3], r, e, sc;
            double rho[3], d2 = 0.0, dot = 0.0, dc = 0.0, da = 0.0;
            int i;
            /* 4th-order central differences: (-f(2h) + 8 f(h) - 8 f(-h) + f(-2h)) / 12h */
#define CD4(fm2, fm1, fp1, fp2, h) ((-(fp2) + 8.0 * (fp1) - 8.0 * (fm1) + (fm2)) / (12.0 * (h)))
            ref_jet(&rc, t, &j0);
            ref_jet(&rc, t - 2 * hs, &a2);
            ref_jet(&rc, t - hs, &a);
            ref_jet(&rc, t + hs, &b);
            ref_jet(&rc, t + 2 * hs, &b2);
            sc = 1.0 + fabs(j0.dx) + fabs(j0.dy) + fabs(j0.dr);
            e = fabs(CD4(a2.x, a.x, b.x, b2.x, hs) - j0.dx) + fabs(CD4(a2.y, a.y, b.y, b2.y, hs) - j0.dy) +
                fabs(CD4(a2.r, a.r, b.r, b2.r, hs) - j0.dr);
            CHECK(e <= 1e-7 * sc);
            sc = 1.0 + fabs(j0.ddx) + fabs(j0.ddy) + fabs(j0.ddr);
            e = fabs(CD4(a2.dx, a.dx, b.dx, b2.dx, hs) - j0.ddx) +
                fabs(CD4(a2.dy, a.dy, b.dy, b2.dy, hs) - j0.ddy) +
                fabs(CD4(a2.dr, a.dr, b.dr, b2.dr, hs) - j0.ddr);
            CHECK(e <= 1e-7 * sc);
            ref_partials(&rc, t, u, m, mt, mu);
            ref_point(&rc, t - 2 * hs, u, pa2, na);
            ref_point(&rc, t - hs, u, pa, na);
            ref_point(&rc, t + hs, u, pb, na);
            ref_point(&rc, t + 2 * hs, u, pb2, na);
            e = 0.0;
            sc = 1.0;
            for (i = 0; i < 3; i++) {
                e += fabs(CD4(pa2[i], pa[i], pb[i], pb2[i], hs) - mt[i]);
                sc += fabs(mt[i]);
            }
            if (!(e <= 1e-7 * sc)) {
                printf("  %s t %.6g u %.3g: m_t err %.3g of %.3g\n", shapes[si].name, t, u, e, sc);
            }
            CHECK(e <= 1e-7 * sc);
            worst = e / sc > worst ? e / sc : worst;
            ref_point(&rc, t, u - 2 * hu, pa2, na);
            ref_point(&rc, t, u - hu, pa, na);
            ref_point(&rc, t, u + hu, pb, na);
            ref_point(&rc, t, u + 2 * hu, pb2, na);
            e = 0.0;
            sc = 1.0;
            for (i = 0; i < 3; i++) {
                e += fabs(CD4(pa2[i], pa[i], pb[i], pb2[i], hu) - mu[i]);
                sc += fabs(mu[i]);
            }
            CHECK(e <= 1e-7 * sc);
#undef CD4
            /* on the sphere, on the characteristic circle */
            rho[0] = j0.x;
            rho[1] = j0.y;
            rho[2] = j0.r;
            ref_circle(&rc, t, cen, &r, ax);
            for (i = 0; i < 3; i++) {
                d2 += (m[i] - rho[i]) * (m[i] - rho[i]);
                dot += (m[i] - rho[i]) * ((i == 0) ? j0.dx : (i == 1) ? j0.dy : j0.dr);
                dc += (m[i] - cen[i]) * (m[i] - cen[i]);
                da += (m[i] - cen[i]) * ax[i];
            }
            CHECK_NEAR(sqrt(d2), j0.r, 1e-12 * j0.r, 0.0);
            CHECK_NEAR(dot, -j0.r * j0.dr, 1e-11 * (1.0 + j0.r * sc), 0.0);
            CHECK_NEAR(sqrt(dc), r, 1e-12 * j0.r, 0.0);
            CHECK(fabs(da) <= 1e-12 * j0.r);
        }
    }
    TEST_NOTE("reference m_t vs central difference: max rel %.2g\n", worst);
    return 0;
}

/* ------------------------------------------------------ toolpath vs reference */

/* Run shape si through the iterator (LINES, zigzag, links) and compare every
 * family-2 point and normal with the reference line of the same start angle at
 * the same t. */
static int ref_compare(int si, double *maxerr, double *maxnerr)
{
    static struct canal_path tp;
    struct raster_cfg cfg;
    struct canal_cfg surf;
    struct raster_pt pt;
    struct ref_canal rc;
    struct ref_line rl[MAXL];
    uint32_t fam2 = 0, links = 0;
    int j;
    shape_cfg(&shapes[si], &surf, &cfg);
    CHECK(cfg.n <= MAXL);
    CHECK_EQ_INT(canal_path_init(&tp, &surf, &cfg), CP_OK);
    ref_from(&rc, &tp.surf);
    CHECK((double)tp.surf.t0 == rc.t0 && (double)tp.surf.t1 == rc.t1);
    for (j = 0; j < cfg.n; j++) {
        ref_line_start(&rl[j], &rc, rc.t0, line_u0(&cfg, j));
    }
    *maxerr = 0.0;
    *maxnerr = 0.0;
    while (canal_path_next(&tp, &pt) == CP_OK) {
        double m[3], nn[3], e, en;
        if (pt.line < 0) {
            links++;
            continue;
        }
        CHECK(pt.line < cfg.n);
        CHECK_EQ_INT(ref_line_advance(&rl[pt.line], (double)pt.t), 0);
        ref_point(&rc, (double)pt.t, rl[pt.line].u, m, nn);
        e = dist3d(m, &pt.p);
        en = dist3d(nn, &pt.n);
        if (e > *maxerr) {
            *maxerr = e;
        }
        if (en > *maxnerr) {
            *maxnerr = en;
        }
        fam2++;
    }
    CHECK_EQ_INT(fam2, (uint32_t)cfg.n * (tp.head.steps + 1u));
    CHECK_EQ_INT(links, (uint32_t)(cfg.n - 1u) * tp.head.link);
    return 0;
}

static int ref_shape_test(int si)
{
    double e, en;
    int r = ref_compare(si, &e, &en);
    if (r != 0) {
        return r;
    }
    TEST_NOTE("%s vs reference (%s): max |dp| %.4g um, max |dn| %.3g (limits %.3g um, %.3g)\n",
              shapes[si].name, CP_REAL_NAME, e * 1e3, en, REF_TOL * 1e3, NRM_TOL);
    CHECK(e <= REF_TOL);
    CHECK(en <= NRM_TOL);
    return 0;
}

int test_canal_ref_paper(void)
{
    return ref_shape_test(SH_PAPER);
}

int test_canal_ref_ellipse(void)
{
    return ref_shape_test(SH_ELLIPSE);
}

int test_canal_ref_bezier(void)
{
    return ref_shape_test(SH_BEZIER);
}

int test_canal_ref_line(void)
{
    return ref_shape_test(SH_LINE);
}

int test_canal_ref_cwarc(void)
{
    return ref_shape_test(SH_CWARC);
}

/* ------------------------------------------------------------ orthogonality */

/* Method: the line tangent is the 4th-order 5-point central difference of the
 * firmware's OWN emitted points of one line (nodes are uniform in t), so it tests
 * what the firmware emits, not the reference's ODE (which is orthogonal by
 * construction). The circle tangent at the emitted point P is axis x (P - centre)
 * of the reference's characteristic circle at the point's t. The deviation from
 * 90 degrees is measured at every interior node (index 2..steps-2). The same
 * stencil on the reference's own points gives the truncation part alone: 2.0e-3 deg
 * on the paper's example at 256 steps, < 1e-5 deg on the other shapes. */
int test_canal_ref_orthogonality(void)
{
    static struct canal_path tp;
    static double buf[CP_MAX_STEPS > 256 ? 257 : CP_MAX_STEPS + 1][3];
    struct raster_cfg cfg;
    struct canal_cfg surf;
    struct raster_pt pt;
    struct ref_canal rc;
    int si;
    for (si = 0; si < SH_COUNT; si++) {
        double worst = 0.0;
        int cur = -1;
        unsigned i;
        shape_cfg(&shapes[si], &surf, &cfg);
        cfg.link = 0;
        /* 256 steps: the stencil's truncation (h^4) is <= 2e-3 deg on the paper's example
           and the float noise of the points (~1 ulp / (12 h |m'|)) stays below 1e-3 deg */
        cfg.steps = 256;
        cfg.substeps = 2;
        CHECK_EQ_INT(canal_path_init(&tp, &surf, &cfg), CP_OK);
        ref_from(&rc, &tp.surf);
        for (;;) {
            int rcode = canal_path_next(&tp, &pt);
            if (rcode == CP_OK && pt.line < 0) {
                continue;
            }
            if (rcode != CP_OK || pt.line != cur) {
                if (cur >= 0) {
                    /* line cur complete in buf[0..steps] by index */
                    double h = ((double)tp.surf.t1 - (double)tp.surf.t0) / tp.head.steps;
                    for (i = 2; i + 2u <= tp.head.steps; i++) {
                        double d[3], cen[3], ax[3], e[3], r, dd = 0.0, ee = 0.0, de = 0.0, ang;
                        double t = (double)tp.surf.t0 + h * i;
                        int k;
                        for (k = 0; k < 3; k++) {
                            d[k] = (-buf[i + 2][k] + 8.0 * buf[i + 1][k] - 8.0 * buf[i - 1][k] + buf[i - 2][k]) /
                                   (12.0 * h);
                        }
                        ref_circle(&rc, t, cen, &r, ax);
                        e[0] = ax[1] * (buf[i][2] - cen[2]) - ax[2] * (buf[i][1] - cen[1]);
                        e[1] = ax[2] * (buf[i][0] - cen[0]) - ax[0] * (buf[i][2] - cen[2]);
                        e[2] = ax[0] * (buf[i][1] - cen[1]) - ax[1] * (buf[i][0] - cen[0]);
                        for (k = 0; k < 3; k++) {
                            dd += d[k] * d[k];
                            ee += e[k] * e[k];
                            de += d[k] * e[k];
                        }
                        ang = asin(fabs(de) / sqrt(dd * ee)) * 180.0 / PI_D;
                        worst = ang > worst ? ang : worst;
                    }
                }
                if (rcode != CP_OK) {
                    break;
                }
                cur = pt.line;
            }
            CHECK(pt.index <= tp.head.steps);
            vec_of(&pt.p, buf[pt.index]);
        }
        TEST_NOTE("%s: orthogonality line/circle max deviation %.2e deg (%s)\n", shapes[si].name,
                  worst, CP_REAL_NAME);
        CHECK(worst <= 0.01);
    }
    return 0;
}

/* ------------------------------------------------------------- contact curve */

int test_canal_contact_curve(void)
{
    static struct canal_path tp;
    struct raster_cfg cfg;
    struct canal_cfg surf;
    struct raster_pt pt;
    struct ref_canal rc;
    int si;
    for (si = 0; si < SH_COUNT; si++) {
        int j0 = -1, j;
        uint32_t seen = 0;
        double zmax = 0.0, dmax = 0.0;
        shape_cfg(&shapes[si], &surf, &cfg);
        for (j = 0; j < cfg.n; j++) {
            if (line_u0(&cfg, j) == 0.0) {
                j0 = j;
            }
        }
        CHECK(j0 >= 0); /* every shape's band contains the line u0 = 0 */
        CHECK_EQ_INT(canal_path_init(&tp, &surf, &cfg), CP_OK);
        ref_from(&rc, &tp.surf);
        while (canal_path_next(&tp, &pt) == CP_OK) {
            struct ref_jet rj;
            double dx, dy, d;
            if (pt.line != j0) {
                continue;
            }
            ref_jet(&rc, (double)pt.t, &rj);
            dx = (double)pt.p.x - rj.x;
            dy = (double)pt.p.y - rj.y;
            d = sqrt(dx * dx + dy * dy);
            zmax = fabs((double)pt.p.z) > zmax ? fabs((double)pt.p.z) : zmax;
            dmax = d > dmax ? d : dmax;
            seen++;
        }
        CHECK_EQ_INT(seen, tp.head.steps + 1u);
        TEST_NOTE("%s: contact line u0 = 0: max |z| %.2g mm, max |xy - C| %.2g mm\n",
                  shapes[si].name, zmax, dmax);
        CHECK(zmax <= 1e-4);
        CHECK(dmax <= 1e-4);
    }
    return 0;
}

/* ------------------------------------------------------------ special cases */

#if CP_REAL_DOUBLE
#define SPECIAL_TOL_TORUS 1e-10
#else
#define SPECIAL_TOL_TORUS 5e-6
#endif

/* Tube (R const) on a circle: every family-2 line is a circle of latitude. */
int test_canal_torus(void)
{
    static struct canal_path tp;
    struct raster_cfg cfg;
    struct canal_cfg surf;
    struct raster_pt pt;
    double zlo[MAXL], zhi[MAXL], rlo[MAXL], rhi[MAXL], worst = 0.0;
    int j;
    static const struct shape torus = {"torus", CANAL_ARC, CANAL_R_CONST,
                                       {0.0, 0.0, 12.0, 0.5, 0.5 + 2.0 * PI_D - 0.25},
                                       {3.0}, -1.5, 1.5, 4, 128, 2};
    shape_cfg(&torus, &surf, &cfg);
    CHECK_EQ_INT(canal_path_init(&tp, &surf, &cfg), CP_OK);
    for (j = 0; j < MAXL; j++) {
        zlo[j] = rlo[j] = 1e30;
        zhi[j] = rhi[j] = -1e30;
    }
    while (canal_path_next(&tp, &pt) == CP_OK) {
        double r;
        if (pt.line < 0) {
            continue;
        }
        j = pt.line;
        r = sqrt((double)pt.p.x * (double)pt.p.x + (double)pt.p.y * (double)pt.p.y);
        zlo[j] = fmin(zlo[j], (double)pt.p.z);
        zhi[j] = fmax(zhi[j], (double)pt.p.z);
        rlo[j] = fmin(rlo[j], r);
        rhi[j] = fmax(rhi[j], r);
    }
    for (j = 0; j < cfg.n; j++) {
        double u = line_u0(&cfg, j);
        worst = fmax(worst, fmax(zhi[j] - zlo[j], rhi[j] - rlo[j]));
        /* and the right latitude: z = R (1 - cos u), radius 12 - R sin u (left = inside) */
        CHECK_NEAR(zlo[j], 3.0 * (1.0 - cos(u)), 4 * SPECIAL_TOL_TORUS, 0.0);
        CHECK_NEAR(rlo[j], 12.0 - 3.0 * sin(u), 4 * SPECIAL_TOL_TORUS, 0.0);
    }
    TEST_NOTE("torus: latitude spread (z, radius) max %.2g mm (%s)\n", worst, CP_REAL_NAME);
    CHECK(worst <= SPECIAL_TOL_TORUS);
    return 0;
}

/* Cone: straight C with a LINEAR radius; every family-2 line is a straight ruling. */
int test_canal_cone(void)
{
    static struct canal_path tp;
    static double buf[65][3];
    struct raster_cfg cfg;
    struct canal_cfg surf;
    struct raster_pt pt;
    double worst = 0.0, size = 0.0, tol;
    int j;
    static const struct shape cone = {"cone", CANAL_LINE, CANAL_R_LINEAR, {-4.0, 2.0, 36.0, 12.0},
                                      {3.0, 8.0}, -1.0, 1.0, 5, 64, 2};
    shape_cfg(&cone, &surf, &cfg);
    CHECK_EQ_INT(canal_path_init(&tp, &surf, &cfg), CP_OK);
    for (j = 0; j < cfg.n; j++) {
        unsigned i;
        double a[3], b[3];
        /* collect line j in index order */
        do {
            CHECK_EQ_INT(canal_path_next(&tp, &pt), CP_OK);
            if (pt.line == j) {
                vec_of(&pt.p, buf[pt.index]);
                size = fmax(size, fmax(fabs(buf[pt.index][0]), fmax(fabs(buf[pt.index][1]), fabs(buf[pt.index][2]))));
            }
        } while (pt.line != j || pt.index != ((j & 1) ? 0u : tp.head.steps));
        for (i = 0; i < 3; i++) {
            a[i] = buf[0][i];
            b[i] = buf[tp.head.steps][i];
        }
        for (i = 1; i < tp.head.steps; i++) {
            worst = fmax(worst, seg_dist(buf[i], a, b));
        }
    }
    tol = 4.0 * (double)CP_REAL_EPS * size;
    TEST_NOTE("cone: max distance from the straight ruling %.2g mm (limit %.2g, %s)\n", worst, tol,
              CP_REAL_NAME);
    CHECK(worst <= tol);
    return 0;
}

/* ------------------------------------------------------------ chord tolerance */

#define SAG_SAMPLES 8 /* sub-intervals per half segment: samples at k/16 of the segment */

static long ref_points_eval;

/* Sagitta of one family-2 segment: the reference line between the two nodes,
 * u(t) piecewise cubic Hermite on [ta, tm], [tm, tb] with the integrated states at
 * ta, tm = (ta + tb)/2, tb; distance of the reference curve from the emitted chord. */
static double seg_sagitta(const struct ref_canal *rc, const struct ref_line *la,
                          const struct ref_line *lm, const struct ref_line *lb, const double pa[3],
                          const double pb[3])
{
    double worst = 0.0, m[3], nn[3];
    int k;
    for (k = 1; k < 2 * SAG_SAMPLES; k++) {
        double t, u;
        if (k < SAG_SAMPLES) {
            t = la->t + (lm->t - la->t) * k / SAG_SAMPLES;
            u = ref_hermite(la->t, la->u, la->f, lm->t, lm->u, lm->f, t);
        } else if (k == SAG_SAMPLES) {
            t = lm->t;
            u = lm->u;
        } else {
            t = lm->t + (lb->t - lm->t) * (k - SAG_SAMPLES) / SAG_SAMPLES;
            u = ref_hermite(lm->t, lm->u, lm->f, lb->t, lb->u, lb->f, t);
        }
        ref_point(rc, t, u, m, nn);
        ref_points_eval++;
        worst = fmax(worst, seg_dist(m, pa, pb));
    }
    return worst;
}

/* Sagitta of a link segment: both ends on the reference characteristic circle at t;
 * the arc between them (the shorter one) sampled against the chord. */
static double link_sagitta(const struct ref_canal *rc, double t, const double pa[3], const double pb[3])
{
    double cen[3], ax[3], r, e1[3], e2[3], v[3], d, phi, worst = 0.0, x[3];
    int i, k;
    ref_circle(rc, t, cen, &r, ax);
    for (i = 0; i < 3; i++) {
        e1[i] = pa[i] - cen[i];
    }
    d = e1[0] * ax[0] + e1[1] * ax[1] + e1[2] * ax[2];
    for (i = 0; i < 3; i++) {
        e1[i] -= d * ax[i];
    }
    d = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
    for (i = 0; i < 3; i++) {
        e1[i] /= d;
        v[i] = pb[i] - cen[i];
    }
    e2[0] = ax[1] * e1[2] - ax[2] * e1[1];
    e2[1] = ax[2] * e1[0] - ax[0] * e1[2];
    e2[2] = ax[0] * e1[1] - ax[1] * e1[0];
    phi = atan2(v[0] * e2[0] + v[1] * e2[1] + v[2] * e2[2], v[0] * e1[0] + v[1] * e1[1] + v[2] * e1[2]);
    for (k = 1; k < 2 * SAG_SAMPLES; k++) {
        double a = phi * k / (2 * SAG_SAMPLES);
        for (i = 0; i < 3; i++) {
            x[i] = cen[i] + r * (cos(a) * e1[i] + sin(a) * e2[i]);
        }
        worst = fmax(worst, seg_dist(x, pa, pb));
    }
    return worst;
}

static int chord_run(int si, cp_real tol, double *sag_line, double *sag_link, unsigned *steps,
                     unsigned *link)
{
    static struct canal_path tp;
    struct raster_cfg cfg;
    struct canal_cfg surf;
    struct raster_pt pt, prev;
    struct ref_canal rc;
    struct ref_line rl[2], before;
    double pa[3], pb[3];
    int j, have = 0;
    shape_cfg(&shapes[si], &surf, &cfg);
    cfg.n = 2; /* the two bounding lines of the band and the link between them */
    cfg.steps = 0;
    cfg.substeps = 0;
    cfg.link = RASTER_LINK_AUTO;
    cfg.tol = tol;
    CHECK_EQ_INT(canal_path_init(&tp, &surf, &cfg), CP_OK);
    *steps = tp.head.steps;
    *link = tp.head.link;
    ref_from(&rc, &tp.surf);
    for (j = 0; j < 2; j++) {
        ref_line_start(&rl[j], &rc, rc.t0, line_u0(&cfg, j));
    }
    *sag_line = 0.0;
    *sag_link = 0.0;
    while (canal_path_next(&tp, &pt) == CP_OK) {
        vec_of(&pt.p, pb);
        if (pt.line >= 0) {
            struct ref_line *l = &rl[pt.line];
            if (have && prev.line == pt.line) {
                struct ref_line mid;
                before = *l;
                CHECK_EQ_INT(ref_line_advance(l, 0.5 * ((double)prev.t + (double)pt.t)), 0);
                mid = *l;
                CHECK_EQ_INT(ref_line_advance(l, (double)pt.t), 0);
                *sag_line = fmax(*sag_line, seg_sagitta(&rc, &before, &mid, l, pa, pb));
            } else {
                CHECK_EQ_INT(ref_line_advance(l, (double)pt.t), 0);
            }
        }
        if (have && !(pt.line >= 0 && prev.line == pt.line)) {
            /* a link move (or the jump from a line end into the link) on the circle at t */
            CHECK(prev.t == pt.t);
            *sag_link = fmax(*sag_link, link_sagitta(&rc, (double)pt.t, pa, pb));
        }
        prev = pt;
        pa[0] = pb[0];
        pa[1] = pb[1];
        pa[2] = pb[2];
        have = 1;
    }
    return 0;
}

int test_canal_chord_tol(void)
{
    static const double tols[2] = {1e-3, 1e-2};
    int si, ti;
    long p0 = ref_points_eval, s0 = ref_total_steps();
    for (si = 0; si < SH_COUNT; si++) {
        for (ti = 0; ti < 2; ti++) {
            double sl, sk;
            unsigned steps, link;
            int r = chord_run(si, (cp_real)tols[ti], &sl, &sk, &steps, &link);
            if (r != 0) {
                printf("  (shape %s, tol %g)\n", shapes[si].name, tols[ti]);
                return r;
            }
            TEST_NOTE("%s tol %g mm: steps %u link %u, max sagitta lines %.4g mm (%.0f%%), links %.4g mm\n",
                      shapes[si].name, tols[ti], steps, link, sl, 100.0 * sl / tols[ti], sk);
            CHECK(sl <= tols[ti]);
            CHECK(sk <= tols[ti]);
        }
    }
    TEST_NOTE("chord test cost: %ld RK steps, %ld sample points\n", ref_total_steps() - s0,
              ref_points_eval - p0);
    return 0;
}

/* ------------------------------------------------- circle, angle, regularity */

/* canal_circle against the reference circle on every shape; canal_angle inverts
 * canal_label; canal_regularity changes sign at the cuspidal edges that MATH-canal §7
 * publishes for the paper's example (t = pi/2: lambda+ = 6.787, lambda- = -3.45;
 * fixed-angle band regular for all t: -0.5636 < u < 0.2926). */
int test_canal_api_misc(void)
{
    struct raster_cfg cfg;
    struct canal_cfg surf;
    struct canal c;
    struct canal_jet j;
    struct canal_frame f;
    struct ref_canal rc;
    double worst_c = 0.0, worst_a = 0.0;
    int si, k;
    for (si = 0; si < SH_COUNT; si++) {
        shape_cfg(&shapes[si], &surf, &cfg);
        CHECK_EQ_INT(canal_init(&c, &surf), CP_OK);
        ref_from(&rc, &c);
        for (k = 0; k <= 6; k++) {
            double t = rc.t0 + (rc.t1 - rc.t0) * k / 6.0, cen[3], ax[3], r, e;
            struct cp_vec3 fc, fa;
            cp_real fr;
            canal_jet(&c, (cp_real)t, &j);
            canal_circle(&j, &fc, &fr, &fa);
            ref_circle(&rc, (double)(cp_real)t, cen, &r, ax);
            e = dist3d(cen, &fc) + fabs((double)fr - r) + dist3d(ax, &fa) * r;
            worst_c = e > worst_c ? e : worst_c;
            canal_frame(&j, &f);
            for (r = -3.0; r <= 3.01; r += 0.5) {
                cp_real al, b;
                double d;
                canal_label(&f, (cp_real)r, &al, &b);
                d = fabs((double)canal_angle(&f, al, b) - r);
                worst_a = d > worst_a ? d : worst_a;
            }
        }
    }
    TEST_NOTE("canal_circle vs reference %.2g mm; canal_angle(canal_label(u)) - u %.2g rad (%s)\n",
              worst_c, worst_a, CP_REAL_NAME);
    CHECK(worst_c <= 200.0 * (double)CP_REAL_EPS * 32.0);
    CHECK(worst_a <= 20.0 * (double)CP_REAL_EPS);
    /* regularity on the paper's example */
    shape_cfg(&shapes[SH_PAPER], &surf, &cfg);
    CHECK_EQ_INT(canal_init(&c, &surf), CP_OK);
    canal_jet(&c, (cp_real)(PI_D / 2), &j);
    canal_frame(&j, &f);
    CHECK(canal_regularity(&f, CP_R(6.70), CP_R(1.0), CP_R(0.0)) <= CP_R(0.0));
    CHECK(canal_regularity(&f, CP_R(6.87), CP_R(1.0), CP_R(0.0)) > CP_R(0.0));
    CHECK(canal_regularity(&f, CP_R(-3.40), CP_R(1.0), CP_R(0.0)) <= CP_R(0.0));
    CHECK(canal_regularity(&f, CP_R(-3.50), CP_R(1.0), CP_R(0.0)) > CP_R(0.0));
    CHECK(canal_regularity(&f, CP_R(1.0), CP_R(0.0), CP_R(0.0)) > CP_R(0.0)); /* C itself */
    for (k = 0; k <= 720; k++) {
        double t = 2.0 * PI_D * k / 720.0;
        cp_real al, b, d1, d2;
        canal_jet(&c, (cp_real)t, &j);
        canal_frame(&j, &f);
        canal_label(&f, CP_R(-0.55), &al, &b);
        d1 = canal_regularity(&f, al, b, CP_R(0.0));
        canal_label(&f, CP_R(0.28), &al, &b);
        d2 = canal_regularity(&f, al, b, CP_R(0.0));
        CHECK(d1 > CP_R(0.0) && d2 > CP_R(0.0));
    }
    /* ... and the band edges are reached: just outside, some t is singular */
    {
        int hit_lo = 0, hit_hi = 0;
        for (k = 0; k <= 720; k++) {
            double t = 2.0 * PI_D * k / 720.0;
            cp_real al, b;
            canal_jet(&c, (cp_real)t, &j);
            canal_frame(&j, &f);
            canal_label(&f, CP_R(-0.58), &al, &b);
            hit_lo |= canal_regularity(&f, al, b, CP_R(0.0)) <= CP_R(0.0);
            canal_label(&f, CP_R(0.31), &al, &b);
            hit_hi |= canal_regularity(&f, al, b, CP_R(0.0)) <= CP_R(0.0);
        }
        CHECK(hit_lo && hit_hi);
    }
    return 0;
}

/* ------------------------------------------------------------------ rejects */

int test_canal_rejects(void)
{
    static struct canal_path tp;
    struct raster_cfg cfg, base;
    struct canal_cfg surf, surf_base;
    struct canal c;
    shape_cfg(&shapes[SH_PAPER], &surf_base, &base);
    base.steps = 64;
    base.substeps = 4;
    cfg = base;
    surf = surf_base;
    CHECK_EQ_INT(canal_path_init(&tp, &surf, &cfg), CP_OK);
    /* CP_ERR_INVAL: kinds out of range, tool radius with a surface output */
    cfg = base;
    surf = surf_base;
    surf.curve = 9;
    CHECK_EQ_INT(canal_init(&c, &surf), CP_ERR_INVAL);
    CHECK_EQ_INT(canal_path_init(&tp, &surf, &cfg), CP_ERR_INVAL);
    cfg = base;
    surf = surf_base;
    surf.radius = 4;
    CHECK_EQ_INT(canal_path_init(&tp, &surf, &cfg), CP_ERR_INVAL);
    cfg = base;
    surf = surf_base;
    cfg.mode = 2;
    CHECK_EQ_INT(canal_path_init(&tp, &surf, &cfg), CP_ERR_INVAL);
    /* CP_ERR_NONFINITE: NaN / Inf in a curve, radius or path parameter */
    cfg = base;
    surf = surf_base;
    surf.cp[2] = (cp_real)NAN;
    CHECK_EQ_INT(canal_init(&c, &surf), CP_ERR_NONFINITE);
    CHECK_EQ_INT(canal_path_init(&tp, &surf, &cfg), CP_ERR_NONFINITE);
    cfg = base;
    surf = surf_base;
    surf.rp[1] = (cp_real)INFINITY;
    CHECK_EQ_INT(canal_path_init(&tp, &surf, &cfg), CP_ERR_NONFINITE);
    cfg = base;
    surf = surf_base;
    cfg.u1 = (cp_real)NAN;
    CHECK_EQ_INT(canal_path_init(&tp, &surf, &cfg), CP_ERR_NONFINITE);
    cfg = base;
    surf = surf_base;
    cfg.tol = (cp_real)NAN;
    CHECK_EQ_INT(canal_path_init(&tp, &surf, &cfg), CP_ERR_NONFINITE);
    cfg = base;
    surf = surf_base;
    cfg.output = RASTER_OUT_CENTRE;
    cfg.tool_r = (cp_real)NAN;
    CHECK_EQ_INT(canal_path_init(&tp, &surf, &cfg), CP_ERR_NONFINITE);
    /* parameters the kinds do not use are ignored ("any USED parameter") */
    cfg = base;
    surf = surf_base;
    surf.cp[5] = (cp_real)NAN; /* ARC uses cp[0..4] */
    surf.rp[3] = (cp_real)NAN; /* COS uses rp[0..2] */
    CHECK_EQ_INT(canal_init(&c, &surf), CP_OK);
    /* CP_ERR_RANGE: coordinate too large, |u| > pi */
    cfg = base;
    surf = surf_base;
    surf.cp[2] = CP_R(2.0e4);
    CHECK_EQ_INT(canal_path_init(&tp, &surf, &cfg), CP_ERR_RANGE);
    cfg = base;
    surf = surf_base;
    cfg.u1 = CP_R(3.5);
    CHECK_EQ_INT(canal_path_init(&tp, &surf, &cfg), CP_ERR_RANGE);
    cfg = base;
    surf = surf_base;
    surf.cp[4] = CP_R(6.5); /* sweep > 2 pi */
    CHECK_EQ_INT(canal_init(&c, &surf), CP_ERR_RANGE);
    cfg = base;
    surf = surf_base;
    surf.cp[2] = CP_R(-3.0); /* ARC r < 0 (r == 0: test_canal_rejects_zero_size) */
    CHECK_EQ_INT(canal_init(&c, &surf), CP_ERR_RANGE);
    cfg = base;
    surf = surf_base;
    surf.rp[2] = CP_R(65.0); /* |k| > 64 */
    CHECK_EQ_INT(canal_init(&c, &surf), CP_ERR_RANGE);
    shape_cfg(&shapes[SH_ELLIPSE], &surf, &cfg);
    surf.cp[3] = CP_R(-12.0); /* B < 0 */
    CHECK_EQ_INT(canal_init(&c, &surf), CP_ERR_RANGE);
    cfg = base;
    surf = surf_base;
    cfg.n = 0;
    CHECK_EQ_INT(canal_path_init(&tp, &surf, &cfg), CP_ERR_RANGE);
    cfg = base;
    surf = surf_base;
    cfg.u1 = cfg.u0; /* u0 == u1 with n > 1 */
    CHECK_EQ_INT(canal_path_init(&tp, &surf, &cfg), CP_ERR_RANGE);
    cfg = base;
    surf = surf_base;
    cfg.steps = 0; /* derive from tol, but tol == 0 */
    CHECK_EQ_INT(canal_path_init(&tp, &surf, &cfg), CP_ERR_RANGE);
    cfg.tol = CP_R(20.0); /* tol > 10 mm */
    CHECK_EQ_INT(canal_path_init(&tp, &surf, &cfg), CP_ERR_RANGE);
    cfg = base;
    surf = surf_base;
    cfg.link = CP_MAX_LINK + 1;
    CHECK_EQ_INT(canal_path_init(&tp, &surf, &cfg), CP_ERR_RANGE);
    /* CP_ERR_EMPTY: a0 == a1 */
    cfg = base;
    surf = surf_base;
    surf.cp[4] = surf.cp[3];
    CHECK_EQ_INT(canal_init(&c, &surf), CP_ERR_EMPTY);
    CHECK_EQ_INT(canal_path_init(&tp, &surf, &cfg), CP_ERR_EMPTY);
    /* CP_ERR_DEGENERATE: LINE with P0 == P1; Bezier with P0 == P1 (C'(0) = 0) */
    shape_cfg(&shapes[SH_LINE], &surf, &cfg);
    surf.cp[2] = surf.cp[0];
    surf.cp[3] = surf.cp[1];
    CHECK_EQ_INT(canal_init(&c, &surf), CP_ERR_DEGENERATE);
    CHECK_EQ_INT(canal_path_init(&tp, &surf, &cfg), CP_ERR_DEGENERATE);
    shape_cfg(&shapes[SH_BEZIER], &surf, &cfg);
    CHECK_EQ_INT(canal_init(&c, &surf), CP_OK);
    surf.cp[2] = surf.cp[0];
    surf.cp[3] = surf.cp[1];
    CHECK_EQ_INT(canal_init(&c, &surf), CP_ERR_DEGENERATE);
    CHECK_EQ_INT(canal_path_init(&tp, &surf, &cfg), CP_ERR_DEGENERATE);
    /* ... and an interior cusp: P1 = P2 on a symmetric "hairpin" gives C'(1/2) = 0 */
    shape_cfg(&shapes[SH_BEZIER], &surf, &cfg);
    surf.cp[0] = CP_R(0.0);
    surf.cp[1] = CP_R(0.0);
    surf.cp[2] = CP_R(20.0);
    surf.cp[3] = CP_R(10.0);
    surf.cp[4] = CP_R(0.0);
    surf.cp[5] = CP_R(10.0);
    surf.cp[6] = CP_R(20.0);
    surf.cp[7] = CP_R(0.0);
    CHECK_EQ_INT(canal_init(&c, &surf), CP_ERR_DEGENERATE);
    /* CP_ERR_RADIUS: COS law with c < |b|; c == |b| (R = 0 at a point); a dip too narrow
       for any coarse sampling (k = 37: R < 0 only within ~3e-4 rad); a CUBIC dip */
    cfg = base;
    surf = surf_base;
    surf.rp[0] = CP_R(5.5);
    surf.rp[1] = CP_R(5.0);
    CHECK_EQ_INT(canal_init(&c, &surf), CP_ERR_RADIUS);
    CHECK_EQ_INT(canal_path_init(&tp, &surf, &cfg), CP_ERR_RADIUS);
    surf.rp[1] = CP_R(5.5);
    CHECK_EQ_INT(canal_init(&c, &surf), CP_ERR_RADIUS);
    cfg = base;
    surf = surf_base;
    surf.cp[3] = CP_R(0.2);
    surf.cp[4] = CP_R(0.3); /* 37 theta = 3 pi at theta = 0.25472: one trough inside */
    surf.rp[0] = CP_R(5.0);
    surf.rp[1] = CP_R(4.999);
    surf.rp[2] = CP_R(37.0);
    CHECK_EQ_INT(canal_init(&c, &surf), CP_ERR_RADIUS);
    surf.rp[1] = CP_R(5.001);
    CHECK_EQ_INT(canal_init(&c, &surf), CP_OK);
    shape_cfg(&shapes[SH_LINE], &surf, &cfg);
    surf.rp[0] = CP_R(1.0);
    surf.rp[1] = CP_R(-0.5);
    surf.rp[2] = CP_R(-0.5);
    surf.rp[3] = CP_R(1.0); /* min R(1/2) = -1/8 */
    CHECK_EQ_INT(canal_init(&c, &surf), CP_ERR_RADIUS);
    /* CP_ERR_TOO_MANY: steps, lines */
    cfg = base;
    surf = surf_base;
    cfg.steps = (uint16_t)(CP_MAX_STEPS + 1);
    CHECK_EQ_INT(canal_path_init(&tp, &surf, &cfg), CP_ERR_TOO_MANY);
    cfg = base;
    surf = surf_base;
    cfg.n = (uint16_t)(CP_MAX_LINES + 1);
    CHECK_EQ_INT(canal_path_init(&tp, &surf, &cfg), CP_ERR_TOO_MANY);
    cfg = base;
    surf = surf_base;
    cfg.substeps = (uint16_t)(CP_MAX_SUBSTEPS + 1);
    CHECK_EQ_INT(canal_path_init(&tp, &surf, &cfg), CP_ERR_TOO_MANY);
    /* CP_ERR_TOOL: tool radius >= min R (= 5 on the paper's example) */
    cfg = base;
    surf = surf_base;
    cfg.output = RASTER_OUT_CENTRE;
    cfg.tool_r = CP_R(5.0);
    CHECK_EQ_INT(canal_path_init(&tp, &surf, &cfg), CP_ERR_TOOL);
    cfg.tool_r = CP_R(1.0);
    CHECK(canal_path_init(&tp, &surf, &cfg) != CP_ERR_TOOL);
    /* CP_ERR_TOL: 1e-5 mm chords on a 5 m circle need ~5e4 steps > CP_MAX_STEPS */
    cfg = base;
    surf = surf_base;
    surf.radius = CANAL_R_CONST;
    surf.cp[2] = CP_R(5000.0);
    surf.rp[0] = CP_R(10.0);
    cfg.n = 1;
    cfg.u0 = cfg.u1 = CP_R(0.0);
    cfg.steps = 0;
    cfg.substeps = 0;
    cfg.tol = CP_R(1e-5);
    CHECK_EQ_INT(canal_path_init(&tp, &surf, &cfg), CP_ERR_TOL);
    /* CP_ERR_CUSP: the paper's band stretched over u = 1.0 (lines cross the cuspidal edges),
       and one line just inside the crossing range (w = 8 < 10.454) */
    cfg = base;
    surf = surf_base;
    cfg.u1 = CP_R(1.0);
    CHECK_EQ_INT(canal_path_init(&tp, &surf, &cfg), CP_ERR_CUSP);
    cfg = base;
    surf = surf_base;
    cfg.n = 1;
    cfg.u0 = cfg.u1 = (cp_real)(2.0 * atan2(1.0, 8.0));
    CHECK_EQ_INT(canal_path_init(&tp, &surf, &cfg), CP_ERR_CUSP);
    cfg.u0 = cfg.u1 = (cp_real)(2.0 * atan2(1.0, 11.0));
    CHECK_EQ_INT(canal_path_init(&tp, &surf, &cfg), CP_OK);
    return 0;
}

/* canal.h: "CP_ERR_RANGE ... r <= 0 (ARC), A <= 0 or B <= 0": the boundary value 0
 * itself is a range error, not a degenerate curve. */
int test_canal_rejects_zero_size(void)
{
    struct raster_cfg cfg;
    struct canal_cfg surf;
    struct canal c;
    shape_cfg(&shapes[SH_PAPER], &surf, &cfg);
    surf.cp[2] = CP_R(0.0);
    CHECK_EQ_INT(canal_init(&c, &surf), CP_ERR_RANGE);
    shape_cfg(&shapes[SH_ELLIPSE], &surf, &cfg);
    surf.cp[2] = CP_R(0.0);
    CHECK_EQ_INT(canal_init(&c, &surf), CP_ERR_RANGE);
    shape_cfg(&shapes[SH_ELLIPSE], &surf, &cfg);
    surf.cp[3] = CP_R(0.0);
    CHECK_EQ_INT(canal_init(&c, &surf), CP_ERR_RANGE);
    return 0;
}

/* ------------------------------------------------------------- count / seek */

int test_canal_count_exact(void)
{
    static struct canal_path tp;
    struct raster_cfg cfg;
    struct canal_cfg surf;
    struct raster_pt pt, rec[6];
    uint32_t pos[6], n, k = 0;
    int i, r;
    shape_cfg(&shapes[SH_BEZIER], &surf, &cfg);
    cfg.steps = 50;
    cfg.substeps = 3;
    cfg.link = 5;
    CHECK_EQ_INT(canal_path_init(&tp, &surf, &cfg), CP_OK);
    n = canal_path_count(&tp);
    CHECK_EQ_INT(n, 3u * 51u + 2u * 5u);
    /* positions: first, inside line 0, a link point, inside the backward line 1, last */
    pos[0] = 0;
    pos[1] = 17;
    pos[2] = 51 + 2;
    pos[3] = 51 + 5 + 30;
    pos[4] = 51 + 5 + 51 + 5;
    pos[5] = n - 1u;
    while ((r = canal_path_next(&tp, &pt)) == CP_OK) {
        for (i = 0; i < 6; i++) {
            if (pos[i] == k) {
                rec[i] = pt;
            }
        }
        k++;
        CHECK(k <= n);
    }
    CHECK_EQ_INT(r, CP_ERR_DONE);
    CHECK_EQ_INT(k, n);
    CHECK_EQ_INT(canal_path_next(&tp, &pt), CP_ERR_DONE);
    CHECK_EQ_INT(rec[2].line, -1);
    CHECK_EQ_INT(rec[3].line, 1);
    /* seek in a scrambled order, compare bit for bit, and check that the stream goes on */
    for (i = 5; i >= 0; i--) {
        int q = (i * 4) % 6;
        struct raster_pt a;
        CHECK_EQ_INT(canal_path_seek(&tp, pos[q]), CP_OK);
        CHECK_EQ_INT(canal_path_next(&tp, &a), CP_OK);
        CHECK(memcmp(&a.p, &rec[q].p, sizeof a.p) == 0);
        CHECK(memcmp(&a.n, &rec[q].n, sizeof a.n) == 0);
        CHECK(memcmp(&a.t, &rec[q].t, sizeof a.t) == 0);
        CHECK_EQ_INT(a.line, rec[q].line);
        CHECK_EQ_INT(a.index, rec[q].index);
        k = pos[q] + 1u;
        while (canal_path_next(&tp, &a) == CP_OK) {
            k++;
        }
        CHECK_EQ_INT(k, n);
    }
    CHECK_EQ_INT(canal_path_seek(&tp, n), CP_OK);
    CHECK_EQ_INT(canal_path_next(&tp, &pt), CP_ERR_DONE);
    CHECK(canal_path_seek(&tp, n + 1u) != CP_OK);
    return 0;
}
