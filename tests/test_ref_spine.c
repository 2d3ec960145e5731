/* test_ref_spine.c - the SPINE reference (tests/ref_spine.c, issue 18) against closed forms
 * and against the canal reference (docs/MATH-spine.md).
 * SPDX-License-Identifier: MIT
 *
 * No firmware code is involved: these tests keep the reference honest before a firmware
 * model is judged by it. Closed forms: the helix's RMF (N1 = cos(-tau s) N + sin(-tau s) B),
 * the pipe (lines = RMF lines), the torus (lines = parallels, circles = meridians), the
 * planar spine (tan(theta/2) = tan(theta0/2) exp(-int a kappa / b ds)); the floor-fillet
 * reduction against ref_canal.c (theta0 = u0 with N1(0) = -e_z; MATH-spine section 7) and
 * the MATH-canal section 7 vectors; orthogonality and the Rodrigues formula by finite
 * differences on a Bezier spine with a CUBIC law. Everything is double precision, the same
 * in the float and the double build. Memory: a few hundred bytes of statics, stack < 2 KB.
 */
#include "ref_canal.h"
#include "ref_spine.h"
#include "test.h"

#define PI_D 3.14159265358979323846

/* ------------------------------------------------------------------ helpers */

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static double dist3(const double a[3], const double b[3])
{
    double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
    return sqrt(dot3(d, d));
}

static void cross3(const double a[3], const double b[3], double o[3])
{
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}

static void unit3(double a[3])
{
    double n = sqrt(dot3(a, a));
    a[0] /= n;
    a[1] /= n;
    a[2] /= n;
}

/* 4th-order central difference from f(-2h), f(-h), f(h), f(2h): error h^4 f^(5) / 30 */
static void cd4(double p[4][3], double h, double o[3])
{
    int i;
    for (i = 0; i < 3; i++) {
        o[i] = (p[0][i] - 8.0 * p[1][i] + 8.0 * p[2][i] - p[3][i]) / (12.0 * h);
    }
}

/* The line l walked forward through uc + k h, k = -2, -1, 0, 1, 2 (it must be at or before
 * uc - 2h): its points and normals at k != 0, and its frame vector N1 and angle at uc. */
static int line_stencil(struct ref_spine_line *l, double uc, double h, double pm[4][3],
                        double pn[4][3], double n1c[3], double *thc)
{
    static const double k[5] = {-2.0, -1.0, 0.0, 1.0, 2.0};
    int i;
    for (i = 0; i < 5; i++) {
        if (ref_spine_line_advance(l, uc + k[i] * h) != 0) {
            return -1;
        }
        if (i == 2) {
            double t[3], n2[3];
            ref_spine_line_frame(l, t, n1c, n2);
            *thc = l->y[3];
        } else {
            ref_spine_line_here(l, 0.0, pm[i - (i > 2)], pn[i - (i > 2)]);
        }
    }
    return 0;
}

/* |angle - 90 deg| between a and b, in degrees */
static double off90(const double a[3], const double b[3])
{
    double c = dot3(a, b) / sqrt(dot3(a, a) * dot3(b, b));
    return fabs(asin(c)) * 180.0 / PI_D;
}

/* |a x b| / (|a| |b|): 0 when parallel */
static double sin_ab(const double a[3], const double b[3])
{
    double x[3];
    cross3(a, b, x);
    return sqrt(dot3(x, x) / (dot3(a, a) * dot3(b, b)));
}

/* ------------------------------------------------------------- self-check */

/* The reference's jets against central differences (all spine kinds and laws), and every
 * init error code: a wrong derivative would bias every other test silently. */
int test_ref_spine_selfcheck(void)
{
    static const double sps[4][12] = {{1, 2, 3, 41, -8, 13},
                                      {10, -5, 20, 1, -2, 3, 40, 1, 1, 0, 1.5 * PI_D},
                                      {0, 0, 0, 0, 0, 1, 15, 10, 2, 1, 0, 0},
                                      {0, 0, 0, 25, 35, 15, 60, -25, 35, 90, 10, 5}};
    static const double rps[4][4] = {{4}, {3, 10}, {1.5, 4, 3}, {3, 6, 2, 5}};
    static const double zref[3] = {0, 0, 1};
    struct ref_spine rs;
    double worst = 0.0;
    int k, law, q, i;
    for (k = 0; k < 4; k++) {
        for (law = 0; law < 4; law++) {
            CHECK_EQ_INT(ref_spine_init(&rs, k, sps[k], law, rps[law], k == 0 ? zref : NULL),
                         REF_SPINE_OK);
            for (q = 1; q < 8; q++) {
                double u = q / 8.0, h = 1e-3, e = 0.0, sc = 1.0;
                struct ref_spine_jet j, a2, a1, b1, b2;
                ref_spine_jet(&rs, u, &j);
                ref_spine_jet(&rs, u - 2 * h, &a2);
                ref_spine_jet(&rs, u - h, &a1);
                ref_spine_jet(&rs, u + h, &b1);
                ref_spine_jet(&rs, u + 2 * h, &b2);
#define D4(f) ((a2.f - 8.0 * a1.f + 8.0 * b1.f - b2.f) / (12.0 * h))
                for (i = 0; i < 3; i++) {
                    e += fabs(D4(c[i]) - j.cu[i]) + fabs(D4(cu[i]) - j.cuu[i]);
                    sc += fabs(j.cu[i]) + fabs(j.cuu[i]);
                }
                e += fabs(D4(r) - j.ru) + fabs(D4(ru) - j.ruu);
                sc += fabs(j.ru) + fabs(j.ruu);
#undef D4
                CHECK(e <= 1e-7 * sc);
                worst = e / sc > worst ? e / sc : worst;
            }
        }
    }
    TEST_NOTE("ref_spine jets vs central differences: max rel %.2g\n", worst);
    /* the error codes */
    {
        static const double same[12] = {1, 2, 3, 1, 2, 3};
        static const double steep[12] = {0, 0, 0, 10, 0, 0};
        static const double lin[4] = {1, 12}, neg[4] = {-1}, ok[4] = {4};
        static const double xref[3] = {1, 0, 0};
        double nan_sp[12] = {0, 0, 0, 10, 0, 0};
        nan_sp[4] = sqrt(-1.0 + 0.0 * sps[0][0]);
        CHECK_EQ_INT(ref_spine_init(&rs, 7, sps[0], 0, ok, zref), REF_SPINE_EKIND);
        CHECK_EQ_INT(ref_spine_init(&rs, 0, sps[0], 9, ok, zref), REF_SPINE_EKIND);
        CHECK_EQ_INT(ref_spine_init(&rs, 0, nan_sp, 0, ok, zref), REF_SPINE_ENAN);
        CHECK_EQ_INT(ref_spine_init(&rs, 0, same, 0, ok, zref), REF_SPINE_EDEGEN);
        CHECK_EQ_INT(ref_spine_init(&rs, 0, steep, 1, lin, zref), REF_SPINE_ESLOPE);
        CHECK_EQ_INT(ref_spine_init(&rs, 0, steep, 0, neg, zref), REF_SPINE_ESLOPE);
        CHECK_EQ_INT(ref_spine_init(&rs, 0, steep, 0, ok, NULL), REF_SPINE_EREF);
        CHECK_EQ_INT(ref_spine_init(&rs, 0, steep, 0, ok, xref), REF_SPINE_EREF);
        CHECK_EQ_INT(ref_spine_init(&rs, 0, steep, 0, ok, zref), REF_SPINE_OK);
    }
    return 0;
}

/* ---------------------------------------------------------- helix pipe */

/* A constant-R pipe along a helix: a = 0, so every line keeps its angle (the RMF lines),
 * and the RMF is the helix's closed form N1 = cos(h p / w) N - sin(h p / w) B (p the helix
 * angle, h = pitch / 2 pi, w = sqrt(r^2 + h^2): tau s = h p / w). Points against that closed
 * form; the lines are curvature lines (Rodrigues by finite differences). */
int test_ref_spine_helix_pipe(void)
{
    static const double sp[12] = {0, 0, 0, 0, 0, 1, 15, 10, 2, 1, 0, 0};
    static const double rp[4] = {4};
    static const double th0[3] = {0.0, 2.0, 4.5};
    const double r = 15.0, hh = 10.0 / (2.0 * PI_D), w = sqrt(r * r + hh * hh), R = 4.0;
    struct ref_spine rs;
    double worst = 0.0, frame = 0.0, rod = 0.0;
    int j, q;
    CHECK_EQ_INT(ref_spine_init(&rs, REF_SPINE_HELIX, sp, REF_SPINE_R_CONST, rp, NULL),
                 REF_SPINE_OK);
    for (j = 0; j < 3; j++) {
        struct ref_spine_line l;
        ref_spine_line_start(&l, &rs, th0[j]);
        for (q = 1; q <= 8; q++) {
            double u = q / 8.0 - 0.01, p, ang;
            double T[3], N[3], B[3], N1[3], N2[3], c[3], m[3], n[3], want[3], t[3], e1[3], e2[3];
            double pm[4][3], pn[4][3], dm[3], dn[3], n1c[3], thc;
            int i;
            CHECK_EQ_INT(line_stencil(&l, u, 1e-3, pm, pn, n1c, &thc), 0);
            cd4(pm, 1e-3, dm);
            cd4(pn, 1e-3, dn);
            rod = sin_ab(dm, dn) > rod ? sin_ab(dm, dn) : rod;
            CHECK_EQ_INT(ref_spine_line_advance(&l, u + 3e-3), 0);
            /* the closed form at the line's current u */
            p = 4.0 * PI_D * l.u;
            ang = hh * p / w;
            T[0] = -r * sin(p) / w;
            T[1] = r * cos(p) / w;
            T[2] = hh / w;
            N[0] = -cos(p);
            N[1] = -sin(p);
            N[2] = 0.0;
            cross3(T, N, B);
            for (i = 0; i < 3; i++) {
                N1[i] = cos(ang) * N[i] - sin(ang) * B[i];
            }
            cross3(T, N1, N2);
            c[0] = r * cos(p);
            c[1] = r * sin(p);
            c[2] = hh * p;
            ref_spine_line_here(&l, 0.0, m, n);
            ref_spine_line_frame(&l, t, e1, e2);
            for (i = 0; i < 3; i++) {
                want[i] = c[i] + R * (cos(th0[j]) * N1[i] + sin(th0[j]) * N2[i]);
            }
            CHECK_NEAR(l.y[3], th0[j], 1e-15, 0.0); /* a = 0: theta' = 0 exactly */
            CHECK(dist3(m, want) <= 1e-9);
            CHECK(dist3(e1, N1) <= 1e-10);
            worst = dist3(m, want) > worst ? dist3(m, want) : worst;
            frame = dist3(e1, N1) > frame ? dist3(e1, N1) : frame;
        }
    }
    CHECK(rod <= 1e-7); /* 4th-order differences at h = 1e-3: ~1e-8 of truncation */
    TEST_NOTE("helix pipe: points vs closed form %.2g mm, RMF %.2g, Rodrigues |dn x dm| %.2g\n",
              worst, frame, rod);
    return 0;
}

/* ------------------------------------------------------------------- torus */

/* An ARC spine in a tilted plane. With a constant R it is a torus: every line keeps its
 * angle and is a parallel (constant distance from the torus axis and height along it), every
 * circle a meridian (in the plane of the axis and the radial direction), and the RMF from the
 * principal normal is N1 = -radial, N2 = the plane's normal. With a LINEAR R on the same arc
 * (a and kappa constant, k2 = 0): tan(theta/2) = tan(theta0/2) exp(-a kappa s / b). */
int test_ref_spine_torus(void)
{
    static const double sp[12] = {10, -5, 20, 1, -2, 3, 40, 1, 1, 0, 1.5 * PI_D};
    static const double rc[4] = {6}, rl[4] = {3, 10};
    static const double th0[4] = {0.4, 1.3, 2.9, -2.0};
    double nrm[3] = {1, -2, 3}, e1[3] = {1, 1, 0}, e2[3], d, worst = 0.0, wang = 0.0;
    struct ref_spine rs, rs2;
    int j, q, i;
    unit3(nrm);
    d = dot3(e1, nrm);
    for (i = 0; i < 3; i++) {
        e1[i] -= d * nrm[i];
    }
    unit3(e1);
    cross3(nrm, e1, e2);
    CHECK_EQ_INT(ref_spine_init(&rs, REF_SPINE_ARC, sp, REF_SPINE_R_CONST, rc, NULL), REF_SPINE_OK);
    CHECK_EQ_INT(ref_spine_init(&rs2, REF_SPINE_ARC, sp, REF_SPINE_R_LINEAR, rl, NULL),
                 REF_SPINE_OK);
    for (j = 0; j < 4; j++) {
        struct ref_spine_line l, l2;
        ref_spine_line_start(&l, &rs, th0[j]);
        ref_spine_line_start(&l2, &rs2, th0[j]);
        for (q = 0; q <= 6; q++) {
            double u = q / 6.0, p = 1.5 * PI_D * u, rad[3], want[3], m[3], n[3], c[3], mc[3];
            double a, b, kap = 1.0 / 40.0, w;
            for (i = 0; i < 3; i++) {
                rad[i] = cos(p) * e1[i] + sin(p) * e2[i];
                c[i] = sp[i] + 40.0 * rad[i];
                want[i] = c[i] + 6.0 * (-cos(th0[j]) * rad[i] + sin(th0[j]) * nrm[i]);
            }
            CHECK_EQ_INT(ref_spine_line_advance(&l, u), 0);
            ref_spine_line_here(&l, 0.0, m, n);
            CHECK(dist3(m, want) <= 1e-9);
            worst = dist3(m, want) > worst ? dist3(m, want) : worst;
            /* a parallel: distance from the axis 40 - 6 cos(theta0), height 6 sin(theta0) */
            for (i = 0; i < 3; i++) {
                mc[i] = m[i] - sp[i];
            }
            d = dot3(mc, nrm);
            CHECK_NEAR(d, 6.0 * sin(th0[j]), 1e-9, 0.0);
            CHECK_NEAR(sqrt(dot3(mc, mc) - d * d), 40.0 - 6.0 * cos(th0[j]), 1e-9, 0.0);
            /* the circle at u through this point is a meridian (ref_spine_circle_point for
               the first line, which integrates from 0; the line's own frame after that) */
            if (j == 0) {
                CHECK_EQ_INT(ref_spine_circle_point(&rs, u, th0[j] + 1.0, m, n), 0);
            } else {
                struct ref_spine_jet jt;
                double t[3], n1[3], n2[3];
                ref_spine_line_frame(&l, t, n1, n2);
                ref_spine_jet(&rs, u, &jt);
                ref_spine_surface(&jt, n1, th0[j] + 1.0, 0.0, m, n);
            }
            for (i = 0; i < 3; i++) {
                mc[i] = m[i] - sp[i];
            }
            cross3(nrm, rad, c);
            CHECK(fabs(dot3(mc, c)) <= 1e-9);
            /* the LINEAR law: the planar closed form */
            CHECK_EQ_INT(ref_spine_line_advance(&l2, u), 0);
            a = 7.0 / (40.0 * 1.5 * PI_D);
            b = sqrt(1.0 - a * a);
            w = tan(th0[j] / 2.0) * exp(-a * kap / b * 40.0 * p);
            d = remainder(l2.y[3] - 2.0 * atan(w), 2.0 * PI_D);
            CHECK(fabs(d) <= 1e-10);
            wang = fabs(d) > wang ? fabs(d) : wang;
        }
    }
    TEST_NOTE("torus: lines vs closed form %.2g mm; planar LINEAR-law closed form %.2g rad\n",
              worst, wang);
    return 0;
}

/* --------------------------------------------------------- floor fillet */

/* The canal model's sphere centres as a USER spine: c = (C(t), R(t)), t = t0 + u (t1 - t0),
 * from ref_canal.c's own jet (MATH-spine section 7). */
static void floor_jet(const void *ctx, double u, struct ref_spine_jet *j)
{
    const struct ref_canal *rc = (const struct ref_canal *)ctx;
    double L = rc->t1 - rc->t0;
    struct ref_jet q;
    ref_jet(rc, rc->t0 + u * L, &q);
    j->c[0] = q.x;
    j->c[1] = q.y;
    j->c[2] = q.r;
    j->cu[0] = q.dx * L;
    j->cu[1] = q.dy * L;
    j->cu[2] = q.dr * L;
    j->cuu[0] = q.ddx * L * L;
    j->cuu[1] = q.ddy * L * L;
    j->cuu[2] = q.ddr * L * L;
    j->r = q.r;
    j->ru = q.dr * L;
    j->ruu = q.ddr * L * L;
}

/* MATH-canal section 7 vectors (w, t, x, y, z; u0 = 2 atan2(1, w)), rows of one w in
 * increasing t */
static const double floor_vec[6][5] = {
    {2, PI_D / 4, -1.811876301, 5.712499889, 1.451055662},
    {2, PI_D / 2, 0.0, 7.411764706, 2.647058824},
    {12, PI_D / 4, 0.3776460409, 1.302003503, 0.1782598444},
    {12, PI_D / 2, 0.0, 1.817034700, 0.1419558360},
    {-6, PI_D / 4, 2.937511755, 4.374008638, 0.2770245511},
    {-6, PI_D, -8.189189189, 0.0, 0.8648648649},
};

/* SPINE on c = C + R e_z against the canal reference (paper example): theta0 = u0 with the
 * start vector -e_z, theta0 = u0 + atan2(-3, 22) with the principal normal; u0 = 0 is C. */
int test_ref_spine_floor(void)
{
    static const double cp[8] = {0.0, 0.0, 3.0, 0.0, 2.0 * PI_D, 0, 0, 0};
    static const double rp[4] = {5.5, 10.5, 2.0, 0.0};
    static const double mz[3] = {0.0, 0.0, -1.0};
    static const double u0s[4] = {-0.5, 0.0, 0.125, 1.5}; /* 1.5 crosses the cusps */
    const double phi0 = atan2(-3.0, 22.0);
    struct ref_canal rc;
    struct ref_spine rs, rp_s;
    double worst = 0.0, wn = 0.0, wpn = 0.0, wvec = 0.0;
    int j, q;
    ref_canal_set(&rc, REF_ARC, REF_R_COS, cp, rp);
    CHECK_EQ_INT(ref_spine_init_user(&rs, floor_jet, &rc, mz), REF_SPINE_OK);
    CHECK_EQ_INT(ref_spine_init_user(&rp_s, floor_jet, &rc, NULL), REF_SPINE_OK);
    for (j = 0; j < 4; j++) {
        struct ref_line cl;
        struct ref_spine_line sl, pl;
        ref_line_start(&cl, &rc, 0.0, u0s[j]);
        ref_spine_line_start(&sl, &rs, u0s[j]);
        ref_spine_line_start(&pl, &rp_s, u0s[j] + phi0);
        for (q = 1; q <= 16; q++) {
            double t = q * PI_D / 8.0, mc[3], nc[3], ms[3], ns[3];
            CHECK_EQ_INT(ref_line_advance(&cl, t), 0);
            ref_point(&rc, t, cl.u, mc, nc);
            CHECK_EQ_INT(ref_spine_line_advance(&sl, q / 16.0), 0);
            ref_spine_line_here(&sl, 0.0, ms, ns);
            worst = dist3(ms, mc) > worst ? dist3(ms, mc) : worst;
            wn = dist3(ns, nc) > wn ? dist3(ns, nc) : wn;
            if (u0s[j] == 0.0) {
                CHECK(fabs(ms[2]) <= 1e-9); /* the contact curve C stays on the floor */
            }
            if (j % 2 == 0) {
                CHECK_EQ_INT(ref_spine_line_advance(&pl, q / 16.0), 0);
                ref_spine_line_here(&pl, 0.0, ms, ns);
                wpn = dist3(ms, mc) > wpn ? dist3(ms, mc) : wpn;
            }
        }
    }
    CHECK(worst <= 1e-8);
    CHECK(wn <= 1e-9);
    CHECK(wpn <= 1e-8);
    for (j = 0; j < 6; j += 2) { /* one line per w, walked through its rows */
        struct ref_spine_line vl;
        ref_spine_line_start(&vl, &rs, 2.0 * atan2(1.0, floor_vec[j][0]));
        for (q = j; q < j + 2; q++) {
            const double *v = floor_vec[q];
            double m[3], n[3];
            CHECK_EQ_INT(ref_spine_line_advance(&vl, v[1] / (2.0 * PI_D)), 0);
            ref_spine_line_here(&vl, 0.0, m, n);
            CHECK(dist3(m, v + 2) <= 2e-9);
            wvec = dist3(m, v + 2) > wvec ? dist3(m, v + 2) : wvec;
        }
    }
    TEST_NOTE("floor fillet vs ref_canal: points %.2g mm, normals %.2g (theta0 = u0, N1(0) = "
              "-e_z); principal normal (theta0 = u0 %+.6f) %.2g mm; MATH-canal vectors %.2g mm\n",
              worst, wn, phi0, wpn, wvec);
    return 0;
}

/* ---------------------------------------------------------- orthogonality */

/* A 3D Bezier spine with a CUBIC law: the lines meet the circles at 90 degrees, and both
 * families are curvature lines (Rodrigues: dn parallel to dm), by finite differences of the
 * reference's own points (lines: 4th-order differences along the integrated line; circles:
 * in theta); kappa2 = g / D of ref_spine_regularity against the measured dn / dm. */
int test_ref_spine_orthogonality(void)
{
    static const double sp[12] = {0, 0, 0, 25, 35, 15, 60, -25, 35, 90, 10, 5};
    static const double rp[4] = {3, 6, 2, 5};
    static const double th0[5] = {0.3, 1.5, 2.7, 4.0, 5.2};
    const double h = 1e-3, ht = 1e-4;
    struct ref_spine rs;
    double worst = 0.0, rod = 0.0, rodc = 0.0, kap = 0.0;
    int j, q, i;
    CHECK_EQ_INT(ref_spine_init(&rs, REF_SPINE_BEZIER, sp, REF_SPINE_R_CUBIC, rp, NULL),
                 REF_SPINE_OK);
    for (j = 0; j < 5; j++) {
        struct ref_spine_line l;
        ref_spine_line_start(&l, &rs, th0[j]);
        for (q = 1; q <= 9; q++) {
            double u = q / 10.0, pm[4][3], pn[4][3], dm[3], dn[3], mt[3], nt[3], n1[3], th;
            double ma[3], na[3], mb[3], nb[3], a, g, dd;
            struct ref_spine_jet jt;
            CHECK_EQ_INT(line_stencil(&l, u, h, pm, pn, n1, &th), 0);
            cd4(pm, h, dm);
            cd4(pn, h, dn);
            /* the circle at u through the line's point: m_theta, n_theta (central, O(ht^2)) */
            ref_spine_jet(&rs, u, &jt);
            ref_spine_surface(&jt, n1, th + ht, 0.0, mb, nb);
            ref_spine_surface(&jt, n1, th - ht, 0.0, ma, na);
            for (i = 0; i < 3; i++) {
                mt[i] = (mb[i] - ma[i]) / (2.0 * ht);
                nt[i] = (nb[i] - na[i]) / (2.0 * ht);
            }
            worst = off90(dm, mt) > worst ? off90(dm, mt) : worst;
            rod = sin_ab(dm, dn) > rod ? sin_ab(dm, dn) : rod;
            rodc = sin_ab(mt, nt) > rodc ? sin_ab(mt, nt) : rodc;
            /* dn = -kappa2 dm, kappa2 = g / D, g = (b^2 - D) / R (MATH-spine 3.4) */
            dd = ref_spine_regularity(&jt, n1, th, 0.0);
            CHECK(dd > 0.0);
            a = jt.ru / sqrt(dot3(jt.cu, jt.cu));
            g = ((1.0 - a * a) - dd) / jt.r;
            for (i = 0; i < 3; i++) {
                double e = fabs(dn[i] + g / dd * dm[i]) / sqrt(dot3(dn, dn));
                kap = e > kap ? e : kap;
            }
        }
    }
    CHECK(worst <= 1e-6); /* degrees; the acceptance is 0.01 */
    CHECK(rod <= 1e-7);
    CHECK(rodc <= 1e-7);
    CHECK(kap <= 1e-6);
    TEST_NOTE("Bezier + CUBIC: lines vs circles %.2g deg off 90; Rodrigues: lines %.2g, circles "
              "%.2g; dn = -kappa2 dm %.2g\n",
              worst, rod, rodc, kap);
    return 0;
}
