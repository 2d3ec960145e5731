/* test_drc.c - DRC-EXP (seed 001): thickening against the independent reference,
 * the acceptance measures of issue 6, rejections, the streaming iterator.
 * SPDX-License-Identifier: MIT
 */
#include <float.h>
#include <string.h>

#include "canal.h"
#include "drc.h"
#include "job.h"
#include "path.h"
#include "ref_canal.h"
#include "ref_drc.h"
#include "test.h"

/* Heavy note-only comparisons (soft doubles) run on the host only. */
#ifdef TEST_NO_MAIN
#define DRC_HEAVY 0
#else
#define DRC_HEAVY 1
#endif

/* ---- test sets (MATH-seeds A.5 names; our own samples) ---- */
enum { SET_SPIRAL_U, SET_SPIRAL_N, SET_ELLIPSE, SET_LINE_ARC, SET_CIRCLE, SET_HELIX_FINE,
       SET_CONE_3D, SET_N };

static const char *const set_name[SET_N] = {"spiral_uniform", "spiral_nonuniform",
                                            "ellipse_quadrant", "line_arc",
                                            "circle_nonuniform", "helix_fine",
                                            "conical_spiral_3d"};

/* clothoid-like spiral k(s) = 0.2 + 0.5 s: position by composite Simpson */
static void spiral_at(double s, double p[3])
{
    int i, m = 64;
    double h = s / m, x = 0.0, y = 0.0;
    for (i = 0; i <= m; i++) {
        double u = h * i, th = 0.2 * u + 0.25 * u * u;
        double w = (i == 0 || i == m) ? 1.0 : (i & 1 ? 4.0 : 2.0);
        x += w * cos(th);
        y += w * sin(th);
    }
    p[0] = x * h / 3.0;
    p[1] = y * h / 3.0;
    p[2] = 0.0;
}

static int make_set(int id, double (*P)[3])
{
    static const double su[7] = {0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0};
    static const double sn[8] = {0.0, 0.3, 0.8, 1.2, 1.7, 2.1, 2.6, 3.0};
    static const double te[8] = {0.0, 0.15, 0.35, 0.5, 0.75, 0.95, 1.25, 1.5707963267948966};
    static const double tc[8] = {0.0, 0.2, 0.5, 0.7, 1.1, 1.3, 1.7, 2.0};
    int i;
    switch (id) {
    case SET_SPIRAL_U:
        for (i = 0; i < 7; i++) {
            spiral_at(su[i], P[i]);
        }
        return 7;
    case SET_SPIRAL_N:
        for (i = 0; i < 8; i++) {
            spiral_at(sn[i], P[i]);
        }
        return 8;
    case SET_ELLIPSE:
        for (i = 0; i < 8; i++) {
            P[i][0] = 3.0 * cos(te[i]);
            P[i][1] = sin(te[i]);
            P[i][2] = 0.0;
        }
        return 8;
    case SET_LINE_ARC:
        for (i = 0; i < 4; i++) {
            P[i][0] = -3.0 + i;
            P[i][1] = 0.0;
            P[i][2] = 0.0;
        }
        for (i = 1; i <= 4; i++) {
            double a = -1.5707963267948966 + 0.5 * i;
            P[3 + i][0] = 2.0 * cos(a);
            P[3 + i][1] = 2.0 + 2.0 * sin(a);
            P[3 + i][2] = 0.0;
        }
        return 8;
    case SET_CIRCLE:
        for (i = 0; i < 8; i++) {
            P[i][0] = 2.0 * cos(tc[i]);
            P[i][1] = 2.0 * sin(tc[i]);
            P[i][2] = 0.0;
        }
        return 8;
    case SET_HELIX_FINE: /* r = 1, c = 0.3, 22.5 deg per segment; 12 points (CP_MAX_DRC_POINTS) */
        for (i = 0; i < 12; i++) {
            double t = 0.39269908169872414 * i;
            P[i][0] = cos(t);
            P[i][1] = sin(t);
            P[i][2] = 0.3 * t;
        }
        return 12;
    default: /* conical spiral: radius 1 + 0.15 t, z = 0.3 t, 22.5 deg per segment */
        for (i = 0; i < 12; i++) {
            double t = 0.39269908169872414 * i;
            P[i][0] = (1.0 + 0.15 * t) * cos(t);
            P[i][1] = (1.0 + 0.15 * t) * sin(t);
            P[i][2] = 0.3 * t;
        }
        return 12;
    }
}

static double set_size(const double (*P)[3], int n)
{
    double lo[3], hi[3];
    int i, k;
    for (k = 0; k < 3; k++) {
        lo[k] = hi[k] = P[0][k];
    }
    for (i = 0; i < n; i++) {
        for (k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], P[i][k]);
            hi[k] = fmax(hi[k], P[i][k]);
        }
    }
    return sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

/* library buffers (K <= 5 on 12 points: 353 points) */
#define LIB_CAP (32 * 11 + 1)
static struct drc_pt lib[LIB_CAP];
static double refp[REF_DRC_MAXOUT][3], reft[REF_DRC_MAXOUT][3];
static double setp[REF_DRC_MAXN][3];

static int lib_run(const double (*P)[3], int n, int K, uint32_t *m)
{
    int i;
    for (i = 0; i < n; i++) {
        lib[i].p.x = (cp_real)P[i][0];
        lib[i].p.y = (cp_real)P[i][1];
        lib[i].p.z = (cp_real)P[i][2];
    }
    return drc_run(lib, (uint32_t)n, (uint32_t)K, LIB_CAP, m);
}

/* 1. the library against the independent reference, K = 0..4 (double: 1e-9 D). A pass
 * keeps every earlier point, so the K = 4 output holds K = 0..3 at strides 16..2: one
 * run per set covers all five K. The M4F runs the planar spiral_nonuniform only (the
 * reference is soft double; its 3D Frenet fits, issue 21, would take minutes there). */
int test_drc_ref_match(void)
{
    int id;
    double worst = 0.0, worst_t = 0.0;
    for (id = 0; id < SET_N; id++) {
        int n = make_set(id, setp), nr = 0;
        double D = set_size((const double(*)[3])setp, n), e = 0.0, et = 0.0;
        uint32_t m = 0, i;
        if (!DRC_HEAVY && id != SET_SPIRAL_N) {
            continue; /* (the M4F: the 3D reference's Frenet fits in soft double take minutes) */
        }
        CHECK_EQ_INT(lib_run((const double(*)[3])setp, n, 4, &m), CP_OK);
        CHECK_EQ_INT(ref_drc_run((const double(*)[3])setp, n, 4, refp, reft, &nr), 0);
        CHECK_EQ_INT(m, nr);
        for (i = 0; i < m; i++) {
            double dx = (double)lib[i].p.x - refp[i][0], dy = (double)lib[i].p.y - refp[i][1],
                   dz = (double)lib[i].p.z - refp[i][2];
            double tx = (double)lib[i].t.x - reft[i][0], ty = (double)lib[i].t.y - reft[i][1],
                   tz = (double)lib[i].t.z - reft[i][2];
            e = fmax(e, sqrt(dx * dx + dy * dy + dz * dz) / D);
            et = fmax(et, sqrt(tx * tx + ty * ty + tz * tz));
        }
        TEST_NOTE("drc ref %-18s max |P - ref| = %.2e D, |T - ref| = %.2e (K = 0..4, %s)\n",
                  set_name[id], e, et, CP_REAL_NAME);
        worst = fmax(worst, e);
        worst_t = fmax(worst_t, et);
    }
#if CP_REAL_DOUBLE
    CHECK(worst <= 1e-9);
    CHECK(worst_t <= 1e-8);
#else
    CHECK(worst <= 2e-5);
    CHECK(worst_t <= 1e-3);
#endif
    return 0;
}

static struct drc_cfg gcfg;
static struct drc_path it;
static struct raster_pt tpt[4];

static void set_geom(const double (*P)[3], int n, int K, int edge)
{
    int i;
    memset(&gcfg, 0, sizeof gcfg);
    for (i = 0; i < n; i++) {
        gcfg.p[i].x = (cp_real)P[i][0];
        gcfg.p[i].y = (cp_real)P[i][1];
        gcfg.p[i].z = (cp_real)P[i][2];
    }
    gcfg.n = (uint8_t)n;
    gcfg.passes = (uint8_t)K;
    gcfg.edge = (uint8_t)edge;
}

static void raster_defaults(struct raster_cfg *c)
{
    memset(c, 0, sizeof *c);
    c->mode = RASTER_LINES;
    c->n = 1;
    c->link = RASTER_LINK_AUTO;
    c->tol = CP_R(0.001);
}

static int same_bits(const struct raster_pt *a, const struct raster_pt *b)
{
    return memcmp(&a->p, &b->p, sizeof a->p) == 0 && memcmp(&a->n, &b->n, sizeof a->n) == 0 &&
           a->line == b->line && a->index == b->index;
}

/* streamed tree points (CURVE mode) = the in-place thickening, bit for bit; seek(k)
 * reproduces point k bit for bit. The stream is planar (drc.h, "Footprint"): a 3D set is
 * CP_ERR_OFF_PLANE at init (the 3D library path is checked by test_drc_ref_match and
 * test_drc_helix). */
int test_drc_stream_equals_thicken(void)
{
    static const int sets[3] = {SET_SPIRAL_N, SET_LINE_ARC, SET_CIRCLE};
    struct raster_cfg rc;
    int s;
    unsigned seed = 6u;
    raster_defaults(&rc);
    for (s = 0; s < (DRC_HEAVY ? 3 : 1); s++) {
        int n = make_set(sets[s], setp), K = DRC_HEAVY ? 4 : 3;
        uint32_t m = 0, k, c;
        CHECK_EQ_INT(lib_run((const double(*)[3])setp, n, K, &m), CP_OK);
        set_geom((const double(*)[3])setp, n, K, 0);
        CHECK_EQ_INT(drc_path_init(&it, &gcfg, &rc), CP_OK);
        c = drc_path_count(&it);
        CHECK_EQ_INT(c, m);
        for (k = 0; k < c; k++) {
            CHECK_EQ_INT(drc_path_next(&it, &tpt[0]), CP_OK);
            CHECK(memcmp(&tpt[0].p, &lib[k].p, sizeof tpt[0].p) == 0);
            CHECK(memcmp(&tpt[0].n, &lib[k].t, sizeof tpt[0].n) == 0);
            CHECK_EQ_INT(tpt[0].index, k);
        }
        CHECK_EQ_INT(drc_path_next(&it, &tpt[0]), CP_ERR_DONE);
        for (k = 0; k < (DRC_HEAVY ? 20u : 6u); k++) {
            uint32_t q = test_prng(&seed) % c;
            CHECK_EQ_INT(drc_path_seek(&it, q), CP_OK);
            CHECK_EQ_INT(drc_path_next(&it, &tpt[0]), CP_OK);
            CHECK(memcmp(&tpt[0].p, &lib[q].p, sizeof tpt[0].p) == 0);
            CHECK(memcmp(&tpt[0].n, &lib[q].t, sizeof tpt[0].n) == 0);
        }
    }
    set_geom((const double(*)[3])setp, make_set(SET_HELIX_FINE, setp), 3, 0);
    CHECK_EQ_INT(drc_path_init(&it, &gcfg, &rc), CP_ERR_OFF_PLANE);
    return 0;
}

/* EDGE mode: a fillet along a non-uniformly sampled circular arc (DRC reproduces the
 * circle) with a LINEAR radius law; every streamed point against the independent canal
 * reference (adaptive ODE of the curvature lines, ref_canal.c), and seek bit for bit. */
int test_drc_edge_vs_canal_ref(void)
{
    static const double ang[7] = {0.0, 0.25, 0.45, 0.8, 1.1, 1.5, 2.0};
    static const double us[3] = {-0.5, 0.2, 0.9};
    struct raster_cfg rc;
    struct ref_canal cref;
    double cp[8] = {0}, rp[4] = {0}, P[7][3], worst = 0.0, wn = 0.0;
    uint32_t c, k, steps;
    unsigned seed = 61u;
    int i;
    for (i = 0; i < 7; i++) {
        P[i][0] = 1.0 + 20.0 * cos(ang[i]);
        P[i][1] = -2.0 + 20.0 * sin(ang[i]);
        P[i][2] = 0.0;
    }
    set_geom((const double(*)[3])P, 7, DRC_HEAVY ? 4 : 3, 1);
    raster_defaults(&rc);
    gcfg.radius = CANAL_R_LINEAR;
    gcfg.rp[0] = CP_R(4.0);
    gcfg.rp[1] = CP_R(6.0);
    rc.n = 3;
    rc.u0 = (cp_real)us[0];
    rc.u1 = (cp_real)us[2];
    rc.tol = CP_R(0.002);
    CHECK_EQ_INT(drc_path_init(&it, &gcfg, &rc), CP_OK);
    c = drc_path_count(&it);
    steps = it.head.steps;
    CHECK_EQ_INT(c, 3u * (steps + 1u) + 2u * it.head.link);
    cp[0] = 1.0;
    cp[1] = -2.0;
    cp[2] = 20.0;
    cp[3] = 0.0;
    cp[4] = 2.0;
    rp[0] = 4.0;
    rp[1] = 6.0;
    ref_canal_set(&cref, REF_ARC, REF_R_LINEAR, cp, rp);
    for (k = 0; k < c; k++) {
        CHECK_EQ_INT(drc_path_next(&it, &tpt[0]), CP_OK);
        if (tpt[0].line >= 0) {
            struct ref_line l;
            double m[3], nn[3], t, d;
            /* the surface point is off C: t from the contact point of its sphere,
             * C = m - R n (n points out of the sphere, centre (C, R)) */
            {
                double sg = (double)tpt[0].t, R = 4.0 + 2.0 * sg;
                double cx = (double)tpt[0].p.x - R * (double)tpt[0].n.x;
                double cy = (double)tpt[0].p.y - R * (double)tpt[0].n.y;
                t = atan2(cy + 2.0, cx - 1.0);
            }
            ref_line_start(&l, &cref, 0.0, us[tpt[0].line]);
            CHECK_EQ_INT(ref_line_advance(&l, t), 0);
            ref_point(&cref, t, l.u, m, nn);
            d = sqrt(((double)tpt[0].p.x - m[0]) * ((double)tpt[0].p.x - m[0]) +
                     ((double)tpt[0].p.y - m[1]) * ((double)tpt[0].p.y - m[1]) +
                     ((double)tpt[0].p.z - m[2]) * ((double)tpt[0].p.z - m[2]));
            worst = fmax(worst, d);
            wn = fmax(wn, fabs((double)tpt[0].n.x * nn[0] + (double)tpt[0].n.y * nn[1] +
                               (double)tpt[0].n.z * nn[2] - 1.0));
        }
        tpt[1 + (k & 1u)] = tpt[0];
        if (k == c / 2u) {
            tpt[3] = tpt[0];
        }
    }
    TEST_NOTE("drc edge: fillet along a 7-point arc, K = %u, %u points, max |m - canal ref| = "
              "%.2e mm, max 1 - n.n_ref = %.1e (%s)\n",
              (unsigned)it.passes, (unsigned)c, worst, wn, CP_REAL_NAME);
#if CP_REAL_DOUBLE
    CHECK(worst <= 2e-6);
#else
    CHECK(worst <= 2e-4);
#endif
    CHECK(wn <= 1e-5);
    for (k = 0; k < 6u; k++) {
        uint32_t q = k == 0u ? c / 2u : test_prng(&seed) % c;
        struct raster_pt a;
        CHECK_EQ_INT(drc_path_seek(&it, q), CP_OK);
        CHECK_EQ_INT(drc_path_next(&it, &a), CP_OK);
        if (q == c / 2u) {
            CHECK(same_bits(&a, &tpt[3]));
        }
        CHECK(cp_finite(a.p.x));
    }
    return 0;
}

/* tangent-triangle containment of every inserted point of every pass (2D) */
static int triangle_violations(const struct drc_pt *b, uint32_t m)
{
    uint32_t i;
    int v = 0;
    for (i = 1; i + 1u < m; i += 2u) {
        v += !drc_in_triangle(&b[i - 1u], &b[i + 1u], &b[i].p);
    }
    return v;
}

static void to_vec(const struct drc_pt *b, uint32_t m, struct cp_vec3 *v)
{
    uint32_t i;
    for (i = 0; i < m; i++) {
        v[i] = b[i].p;
    }
}

static struct cp_vec3 vin[LIB_CAP], vout[LIB_CAP];

/* Acceptance 1-2: planar sets at K = 5: 0 extra extrema, 0 new sign changes, 0
 * between-neighbour violations, 0 tangent-triangle violations; the circle to 1e-12 R;
 * original-point curvature change decreasing K = 1..5. Double build (the measures need
 * double points: float curvature noise at K = 5 is ~1e-3 relative); the float build
 * checks the triangle and the circle to float precision. */
int test_drc_planar_acceptance(void)
{
    static const int sets[5] = {SET_SPIRAL_U, SET_SPIRAL_N, SET_ELLIPSE, SET_LINE_ARC,
                                SET_CIRCLE};
    int s, tri_total = 0, ins_total = 0;
    for (s = 0; s < 5; s++) {
        int id = sets[s], n = make_set(id, setp), K, i;
        uint32_t m = 0;
        struct drc_measures mi, mo;
        double kprev[REF_DRC_MAXN], conv[6] = {0}, circ = 0.0;
        (void)kprev;
        (void)circ;
        /* one run at K = 5; pass K's points are every 2^(5-K)-th (passes keep points) */
        CHECK_EQ_INT(lib_run((const double(*)[3])setp, n, 5, &m), CP_OK);
        for (K = 1; K <= 5; K++) {
            uint32_t sd = (uint32_t)1u << (5 - K), j, mk = ((uint32_t)(n - 1) << K) + 1u;
            for (j = 1; j + 1u < mk; j += 2u) { /* pass K inserted the odd points */
                tri_total += !drc_in_triangle(&lib[(j - 1u) * sd], &lib[(j + 1u) * sd],
                                              &lib[j * sd].p);
            }
            ins_total += (int)(mk - 1u) / 2;
#if CP_REAL_DOUBLE
            {
                double mx = 0.0;
                uint32_t st = (uint32_t)1u << K;
                for (i = 1; i + 1 < n; i++) {
                    uint32_t c = (uint32_t)i * st;
                    double k = (double)drc_kappa3(&lib[(c - 1u) * sd].p, &lib[c * sd].p,
                                                  &lib[(c + 1u) * sd].p, 1);
                    if (K > 1) {
                        mx = fmax(mx, fabs(k - kprev[i]));
                    }
                    kprev[i] = k;
                }
                conv[K] = mx;
            }
#endif
        }
        if (id == SET_CIRCLE) {
            uint32_t j;
            for (j = 0; j < m; j++) {
                double r = sqrt((double)lib[j].p.x * (double)lib[j].p.x +
                                (double)lib[j].p.y * (double)lib[j].p.y);
                circ = fmax(circ, fabs(r - 2.0));
            }
            TEST_NOTE("drc circle_nonuniform K = 5: max |r - 2| = %.2e (%s)\n", circ,
                      CP_REAL_NAME);
#if CP_REAL_DOUBLE
            CHECK(circ <= 1e-12 * 2.0);
#else
            CHECK(circ <= 2e-6 * 2.0);
#endif
        }
        for (i = 0; i < n; i++) {
            vin[i].x = (cp_real)setp[i][0];
            vin[i].y = (cp_real)setp[i][1];
            vin[i].z = (cp_real)setp[i][2];
        }
        CHECK_EQ_INT(drc_measure(vin, (uint32_t)n, 1, &mi), CP_OK);
        CHECK_EQ_INT(triangle_violations(lib, m), 0);
        to_vec(lib, m, vout);
        CHECK_EQ_INT(drc_measure(vout, m, 1, &mo), CP_OK);
        TEST_NOTE("drc %-18s K=5 DRC (%s): extra extrema %d, new sign changes %d, between %u, k %.3f..%.3f "
                  "(in %.3f..%.3f); convergence %.1e %.1e %.1e %.1e\n",
                  set_name[id], CP_REAL_NAME, (int)mo.extrema - (int)mi.extrema,
                  (int)mo.signs - (int)mi.signs, (unsigned)mo.between, (double)mo.kmin,
                  (double)mo.kmax, (double)mi.kmin, (double)mi.kmax, conv[2], conv[3], conv[4],
                  conv[5]);
#if CP_REAL_DOUBLE
        CHECK(mo.extrema <= mi.extrema);
        CHECK(mo.signs <= mi.signs);
        CHECK_EQ_INT(mo.between, 0);
        for (K = 3; K <= 5; K++) {
            CHECK(conv[K] <= conv[K - 1] || conv[K] <= 1e-12);
        }
#endif
    }
    TEST_NOTE("drc tangent-triangle violations: %d of %d inserted points (5 planar sets, K = 1..5)\n",
              tri_total, ins_total);
    CHECK_EQ_INT(tri_total, 0);
    return 0;
}

/* Acceptance 3: the same measures for DD4, CCR and CSPLINE (notes for the README
 * table), and DRC's measured by the reference's own measure function; both measure
 * functions must agree on every polyline. Host only (soft doubles on the M4F). */
int test_drc_comparison(void)
{
#if DRC_HEAVY
    static double out[REF_DRC_MAXOUT][3], pin[REF_DRC_MAXN][3];
    static const char *const mname[4] = {"DRC", "DD4", "CCR", "CSPLINE"};
    int id;
    for (id = 0; id < SET_N; id++) {
        int n = make_set(id, pin), meth, m = 0, planar = id < SET_HELIX_FINE;
        struct ref_measures ri, ro;
        ref_measure((const double(*)[3])pin, n, planar, &ri);
        for (meth = 0; meth < 4; meth++) {
            if (meth == 0) {
                CHECK_EQ_INT(ref_drc_run((const double(*)[3])pin, n, 5, out, NULL, &m), 0);
            } else if (meth == 1) {
                m = ref_dd4((const double(*)[3])pin, n, 5, out);
            } else if (meth == 2) {
                m = ref_ccr((const double(*)[3])pin, n, 5, out);
            } else {
                m = ref_cspline((const double(*)[3])pin, n, 5, out);
            }
            CHECK_EQ_INT(m, ((n - 1) << 5) + 1);
            ref_measure((const double(*)[3])out, m, planar, &ro);
#if CP_REAL_DOUBLE
            {
                struct drc_measures lm;
                int i;
                for (i = 0; i < m; i++) {
                    vout[i].x = out[i][0];
                    vout[i].y = out[i][1];
                    vout[i].z = out[i][2];
                }
                CHECK_EQ_INT(drc_measure(vout, (uint32_t)m, planar, &lm), CP_OK);
                CHECK_EQ_INT(lm.extrema, ro.extrema);
                CHECK_EQ_INT(lm.signs, ro.signs);
                CHECK_EQ_INT(lm.between, ro.between);
            }
#endif
            if (planar) {
                TEST_NOTE("drc table %-18s %-7s extra extrema %3d  new signs %2d  between %3d  k %.3f..%.3f\n",
                          set_name[id], mname[meth], ro.extrema - ri.extrema,
                          ro.signs - ri.signs, ro.between, ro.kmin, ro.kmax);
            } else {
                TEST_NOTE("drc table %-18s %-7s extra extrema %3d  new signs %2d  between %3d  k %.6f..%.6f  tau %.4f..%.4f\n",
                          set_name[id], mname[meth], ro.extrema - ri.extrema,
                          ro.signs - ri.signs, ro.between, ro.kmin, ro.kmax, ro.tmin, ro.tmax);
            }
            if (meth == 0 && planar) {
                CHECK(ro.extrema <= ri.extrema && ro.signs <= ri.signs && ro.between == 0);
            }
        }
    }
#endif
    return 0;
}

/* Acceptance 4: 3D helix_fine: curvature regularity in the interior (the exact helix
 * curvature r/(r^2 + c^2) = 0.917431), and the torsion ripple per K (A.6's open problem:
 * issue 21's intrinsic arc keeps it at ~1e-4, test_drc_torsion checks it). */
int test_drc_helix(void)
{
    int n = make_set(SET_HELIX_FINE, setp), K;
    double kex = 1.0 / 1.09, tex = 0.3 / 1.09;
    for (K = 1; K <= (DRC_HEAVY ? 5 : 3); K++) {
        uint32_t m = 0, i, st = (uint32_t)1u << K, lo, hi;
        double kmin = 1e9, kmax = -1e9, tmin = 1e9, tmax = -1e9;
        CHECK_EQ_INT(lib_run((const double(*)[3])setp, n, K, &m), CP_OK);
        /* interior: skip the first and last 2 original segments */
        lo = 2u * st;
        hi = m - 1u - 2u * st;
        for (i = lo; i <= hi; i++) {
            double k = (double)drc_kappa3(&lib[i - 1u].p, &lib[i].p, &lib[i + 1u].p, 0);
            double t = (double)drc_tau4(&lib[i - 1u].p, &lib[i].p, &lib[i + 1u].p, &lib[i + 2u].p);
            kmin = fmin(kmin, k);
            kmax = fmax(kmax, k);
            tmin = fmin(tmin, t);
            tmax = fmax(tmax, t);
        }
        TEST_NOTE("drc helix_fine K=%d interior k %.6f..%.6f (exact %.6f, spread %.1e rel), tau "
                  "%.4f..%.4f (exact %.4f, ripple %.1e) (%s)\n",
                  K, kmin, kmax, kex, (kmax - kmin) / kex, tmin, tmax, tex, tmax - tmin,
                  CP_REAL_NAME);
#if CP_REAL_DOUBLE
        CHECK((kmax - kmin) / kex <= 1e-4);
        CHECK(fabs(0.5 * (kmin + kmax) - kex) / kex <= 1e-3);
#else
        if (K <= 3) {
            CHECK((kmax - kmin) / kex <= 2e-2);
        }
#endif
    }
    return 0;
}

/* Exact curvature and torsion of the 3D sets at the parameter t (z = 0.3 t on both):
 * helix r = 1, c = 0.3; conical spiral radius a = 1 + 0.15 t. */
static void set3d_kt(int id, double t, double *k, double *tau)
{
    double a = id == SET_HELIX_FINE ? 1.0 : 1.0 + 0.15 * t, da = id == SET_HELIX_FINE ? 0.0 : 0.15;
    double d1[3], d2[3], d3[3], c[3], cn, n1;
    d1[0] = da * cos(t) - a * sin(t);
    d1[1] = da * sin(t) + a * cos(t);
    d1[2] = 0.3;
    d2[0] = -2.0 * da * sin(t) - a * cos(t);
    d2[1] = 2.0 * da * cos(t) - a * sin(t);
    d2[2] = 0.0;
    d3[0] = -3.0 * da * cos(t) + a * sin(t);
    d3[1] = -3.0 * da * sin(t) - a * cos(t);
    d3[2] = 0.0;
    c[0] = d1[1] * d2[2] - d1[2] * d2[1];
    c[1] = d1[2] * d2[0] - d1[0] * d2[2];
    c[2] = d1[0] * d2[1] - d1[1] * d2[0];
    cn = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    n1 = sqrt(d1[0] * d1[0] + d1[1] * d1[1] + d1[2] * d1[2]);
    *k = cn / (n1 * n1 * n1);
    *tau = (c[0] * d3[0] + c[1] * d3[1] + c[2] * d3[2]) / (cn * cn);
}

/* Issue 21 (docs/DRC-TORSION.md): the interior torsion of the 3D sets no longer grows with
 * the passes. Interior = without the first and last 2 original segments (as test_drc_helix);
 * errors relative to the exact curve's curvature at the point and torsion at the chord's
 * middle (z = 0.3 t). Double build: helix_fine at K = 5 within 1e-3 relative (the old
 * twisted model: 1.4e-1; now 2.6e-4, the AP-dihedral measure's own O(h^2) bias included),
 * curvature within 4e-6 (old 3.2e-6, now 1.9e-6), no new extrema (3 and 2 between-neighbour
 * at the end segments, as before; conical 0 / 0); the conical spiral's error converges (its
 * torsion is one constant per original segment: the K = 4 -> 5 change is at most half the
 * K = 2 -> 3 change; old: growing, 0.13 -> 0.43). The float build's torsion at K = 5 is
 * below float resolution: the exact helix's points rounded to float already spread its
 * discrete torsion by the floor printed here; float checks curvature and extrema only. */
int test_drc_torsion(void)
{
    static struct cp_vec3 v[LIB_CAP];
    int sets[2] = {SET_HELIX_FINE, SET_CONE_3D}, s, K;
    for (s = 0; s < (DRC_HEAVY ? 2 : 1); s++) {
        int id = sets[s], n = make_set(id, setp);
        double terr[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0}, floor_t = 0.0;
        double tsame[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
        for (K = 1; K <= (DRC_HEAVY ? 5 : 3); K++) {
            uint32_t m = 0, i, st = (uint32_t)1u << K, lo, hi;
            double kerr = 0.0, ke, te, kd, td = 0.0;
            struct drc_measures dm;
            CHECK_EQ_INT(lib_run((const double(*)[3])setp, n, K, &m), CP_OK);
            lo = 2u * st;
            hi = m - 1u - 2u * st;
            for (i = lo; i <= hi; i++) {
                double k = (double)drc_kappa3(&lib[i - 1u].p, &lib[i].p, &lib[i + 1u].p, 0);
                double t = (double)drc_tau4(&lib[i - 1u].p, &lib[i].p, &lib[i + 1u].p,
                                            &lib[i + 2u].p);
                set3d_kt(id, (double)lib[i].p.z / 0.3, &ke, &kd);
                set3d_kt(id, 0.5 * ((double)lib[i].p.z + (double)lib[i + 1u].p.z) / 0.3, &kd,
                         &te);
                kerr = fmax(kerr, fabs(k / ke - 1.0));
                terr[K] = fmax(terr[K], fabs(t / te - 1.0));
                {
                    /* the exact curve at the same parameters t = z / 0.3, in double: the
                     * AP-dihedral measure depends on the spacing (its bias for unequal chords
                     * is O(1) in the ratio), so the scheme's torsion is also compared with the
                     * exact curve's discrete torsion at the points' own spacing */
                    double q[4][3], n1[3], n2[3], x[3], dd[3], l1, l2, ld;
                    uint32_t j;
                    int c;
                    for (j = 0; j < 4u; j++) {
                        double tt = (double)lib[i - 1u + j].p.z / 0.3;
                        double a = id == SET_HELIX_FINE ? 1.0 : 1.0 + 0.15 * tt;
                        q[j][0] = a * cos(tt);
                        q[j][1] = a * sin(tt);
                        q[j][2] = 0.3 * tt;
                    }
                    for (c = 0; c < 3; c++) {
                        dd[c] = q[2][c] - q[1][c];
                    }
                    n1[0] = (q[1][1] - q[0][1]) * dd[2] - (q[1][2] - q[0][2]) * dd[1];
                    n1[1] = (q[1][2] - q[0][2]) * dd[0] - (q[1][0] - q[0][0]) * dd[2];
                    n1[2] = (q[1][0] - q[0][0]) * dd[1] - (q[1][1] - q[0][1]) * dd[0];
                    n2[0] = dd[1] * (q[3][2] - q[2][2]) - dd[2] * (q[3][1] - q[2][1]);
                    n2[1] = dd[2] * (q[3][0] - q[2][0]) - dd[0] * (q[3][2] - q[2][2]);
                    n2[2] = dd[0] * (q[3][1] - q[2][1]) - dd[1] * (q[3][0] - q[2][0]);
                    l1 = sqrt(n1[0] * n1[0] + n1[1] * n1[1] + n1[2] * n1[2]);
                    l2 = sqrt(n2[0] * n2[0] + n2[1] * n2[1] + n2[2] * n2[2]);
                    ld = sqrt(dd[0] * dd[0] + dd[1] * dd[1] + dd[2] * dd[2]);
                    x[0] = n1[1] * n2[2] - n1[2] * n2[1];
                    x[1] = n1[2] * n2[0] - n1[0] * n2[2];
                    x[2] = n1[0] * n2[1] - n1[1] * n2[0];
                    td = atan2((x[0] * dd[0] + x[1] * dd[1] + x[2] * dd[2]) / (l1 * l2 * ld),
                               (n1[0] * n2[0] + n1[1] * n2[1] + n1[2] * n2[2]) / (l1 * l2)) / ld;
                    tsame[K] = fmax(tsame[K], fabs(t - td) / te);
                }
                if (K == (DRC_HEAVY ? 5 : 3)) {
                    /* the float floor: the exact curve at the same points, stored in cp_real */
                    struct cp_vec3 q[4];
                    uint32_t j;
                    for (j = 0; j < 4u; j++) {
                        double tt = (double)lib[i - 1u + j].p.z / 0.3;
                        double a = id == SET_HELIX_FINE ? 1.0 : 1.0 + 0.15 * tt;
                        q[j].x = (cp_real)(a * cos(tt));
                        q[j].y = (cp_real)(a * sin(tt));
                        q[j].z = (cp_real)(0.3 * tt);
                    }
                    floor_t = fmax(floor_t,
                                   fabs((double)drc_tau4(&q[0], &q[1], &q[2], &q[3]) - td) / te);
                }
            }
            for (i = 0; i < m; i++) {
                v[i] = lib[i].p;
            }
            CHECK_EQ_INT(drc_measure(v, m, 0, &dm), CP_OK);
            TEST_NOTE("drc torsion %-18s K=%d interior |k/k_ex - 1| <= %.2e, |tau/tau_ex - 1| <= "
                      "%.2e, vs the exact curve's discrete torsion at the same spacing %.2e, "
                      "extrema %u, between %u (%s)\n",
                      set_name[id], K, kerr, terr[K], tsame[K], (unsigned)dm.extrema,
                      (unsigned)dm.between, CP_REAL_NAME);
            if (id == SET_HELIX_FINE) {
#if CP_REAL_DOUBLE
                CHECK(kerr <= 4e-6 || K < 5);
                CHECK(dm.extrema <= 3u && dm.between <= 2u);
#else
                CHECK(kerr <= 1e-3);
#endif
            } else {
                CHECK(kerr <= 1e-3);
                CHECK(dm.extrema == 0u && dm.between == 0u);
            }
        }
        TEST_NOTE("drc torsion %-18s float floor of the measure at K=%d: the exact curve's points "
                  "in cp_real give |tau/tau_ex - 1| <= %.2e (%s)\n",
                  set_name[id], DRC_HEAVY ? 5 : 3, floor_t, CP_REAL_NAME);
#if CP_REAL_DOUBLE
        if (id == SET_HELIX_FINE) {
            CHECK(terr[DRC_HEAVY ? 5 : 3] <= 1e-3);
        } else if (DRC_HEAVY) {
            CHECK(terr[5] <= 6e-2);
            CHECK(fabs(terr[5] - terr[4]) <= 0.5 * fabs(terr[3] - terr[2]));
        }
#endif
    }
    return 0;
}

/* Acceptance 6: every rejection of A.3 returns its own code. */
int test_drc_rejects(void)
{
    static double P[5][3];
    struct raster_cfg rc;
    uint32_t need = 0;
    int i;
    for (i = 0; i < 5; i++) {
        P[i][0] = i;
        P[i][1] = 0.1 * i * i;
        P[i][2] = 0.0;
    }
    CHECK_EQ_INT(lib_run((const double(*)[3])P, 2, 1, &need), CP_ERR_TOO_FEW);
    CHECK_EQ_INT(drc_size(12, CP_MAX_PASSES + 1u, &need), CP_ERR_TOO_MANY);
    CHECK_EQ_INT(drc_size(2, 1, &need), CP_ERR_TOO_FEW);
    /* buffer too small: the size needed is reported, nothing written */
    for (i = 0; i < 5; i++) {
        lib[i].p.x = (cp_real)P[i][0];
        lib[i].p.y = (cp_real)P[i][1];
        lib[i].p.z = CP_R(0.0);
    }
    CHECK_EQ_INT(drc_run(lib, 5, 3, 32, &need), CP_ERR_BUFFER);
    CHECK_EQ_INT(need, 33);
    CHECK_EQ_INT(drc_thicken(lib, 5, 8, &need), CP_ERR_BUFFER);
    CHECK_EQ_INT(need, 9);
    CHECK_EQ_INT(drc_run(lib, 5, 3, 33, &need), CP_OK);
    P[2][0] = P[1][0];
    P[2][1] = P[1][1];
    CHECK_EQ_INT(lib_run((const double(*)[3])P, 5, 1, &need), CP_ERR_COINCIDENT);
    P[2][0] = 0.5; /* a reversal: turn >= 90 deg */
    P[2][1] = 0.1;
    CHECK_EQ_INT(lib_run((const double(*)[3])P, 5, 1, &need), CP_ERR_TURN);
    P[2][0] = 2.0;
    P[2][1] = 0.4;
    P[3][1] = NAN;
    CHECK_EQ_INT(lib_run((const double(*)[3])P, 5, 1, &need), CP_ERR_NONFINITE);
    P[3][1] = 0.9;
    /* twist: adjoining planes 60 deg apart */
    P[0][0] = 0.0; P[0][1] = 0.0; P[0][2] = 0.0;
    P[1][0] = 1.0; P[1][1] = 0.0; P[1][2] = 0.0;
    P[2][0] = 2.0; P[2][1] = 0.3; P[2][2] = 0.0;
    P[3][0] = 3.0; P[3][1] = 0.6 + 0.15; P[3][2] = 0.26;
    P[4][0] = 4.0; P[4][1] = 1.2; P[4][2] = 0.9;
    CHECK_EQ_INT(lib_run((const double(*)[3])P, 5, 1, &need), CP_ERR_TWIST);
    /* all collinear is not an error: the subdivided straight line */
    for (i = 0; i < 5; i++) {
        P[i][0] = i * 1.5;
        P[i][1] = i * 0.5;
        P[i][2] = 0.0;
    }
    CHECK_EQ_INT(lib_run((const double(*)[3])P, 5, 2, &need), CP_OK);
    CHECK_NEAR(lib[3].p.y, 0.375, 1e-6, 0); /* point 3 of 4 per segment: y(0.75) */
    /* the iterator: too many passes, EDGE off the plane, TOL unreachable */
    raster_defaults(&rc);
    P[1][2] = 0.5;
    set_geom((const double(*)[3])P, 5, CP_MAX_PASSES + 1, 0);
    CHECK_EQ_INT(drc_path_init(&it, &gcfg, &rc), CP_ERR_TOO_MANY);
    CHECK_EQ_INT(drc_path_count(&it), 0);
    set_geom((const double(*)[3])P, 5, 2, 1);
    gcfg.rp[0] = CP_R(1.0);
    CHECK_EQ_INT(drc_path_init(&it, &gcfg, &rc), CP_ERR_OFF_PLANE);
    make_set(SET_SPIRAL_U, setp);
    for (i = 0; i < 7; i++) { /* x100: 10 nm needs more than CP_MAX_PASSES passes */
        setp[i][0] *= 100.0;
        setp[i][1] *= 100.0;
    }
    set_geom((const double(*)[3])setp, 7, DRC_PASSES_AUTO, 0);
    rc.tol = CP_R(1e-5);
    CHECK_EQ_INT(drc_path_init(&it, &gcfg, &rc), CP_ERR_TOL);
    rc.tol = CP_R(0.001);
    CHECK_EQ_INT(drc_path_init(&it, &gcfg, &rc), CP_OK);
    TEST_NOTE("drc TOL 1 um on spiral_uniform x100 (7 points): K = %u, %u points\n",
              (unsigned)it.passes, (unsigned)drc_path_count(&it));
    set_geom((const double(*)[3])setp, 2, 1, 0);
    CHECK_EQ_INT(drc_path_init(&it, &gcfg, &rc), CP_ERR_TOO_FEW);
    return 0;
}

/* The A.4 measure function on hand-made sequences with known counts. */
int test_drc_measures(void)
{
    static const double ys[9] = {0.0, 0.1, 0.4, 0.8, 1.1, 1.3, 1.6, 2.1, 2.4};
    struct drc_measures m;
    int i;
    for (i = 0; i < 9; i++) {
        vin[i].x = (cp_real)i;
        vin[i].y = (cp_real)(0.05 * i * i);
        vin[i].z = CP_R(0.0);
    }
    CHECK_EQ_INT(drc_measure(vin, 9, 1, &m), CP_OK); /* a parabola: k decreasing */
    CHECK_EQ_INT(m.extrema, 0);
    CHECK_EQ_INT(m.signs, 0);
    CHECK(m.kmin > CP_R(0.0));
    for (i = 0; i < 9; i++) {
        vin[i].y = (cp_real)ys[i];
    }
    CHECK_EQ_INT(drc_measure(vin, 9, 1, &m), CP_OK);
    /* second differences + + - - + + - : k changes sign 3 times */
    CHECK_EQ_INT(m.signs, 3);
    CHECK(m.extrema >= 2u);
    CHECK_EQ_INT(drc_measure(vin, 2, 1, &m), CP_ERR_TOO_FEW);
    return 0;
}

/* ---- issue 6 regressions ---- */

/* B1: the end angle a_0 = b_0 / r(q*) of A.2 was unbounded: next to a short chord with
 * a steep curvature ratio the tangent at P_0 pointed backwards (98 deg from chord 0) and
 * the first segment's points looped behind P_0 (x = -0.40 on a 1.29 mm chord), with no
 * error. Now |a_0| <= |phi_1|: the tangent is < 90 deg from the chord, every point of
 * the segment projects into the chord, and the reference (same rule) agrees. */
int test_drc_end_tangent_bound(void)
{
    static const double P[4][3] = {{0.0, 0.0, 0.0},
                                   {0.555650651, 1.16622233, 0.0},
                                   {0.594727933, 1.15016341, 0.0},
                                   {1.47392833, 0.459962815, 0.0}};
    double dx = P[1][0], dy = P[1][1], L = sqrt(dx * dx + dy * dy), c;
    uint32_t m = 0, i;
    int nr = 0;
    CHECK_EQ_INT(lib_run(P, 4, 3, &m), CP_OK);
    CHECK_EQ_INT(m, 25u);
    c = ((double)lib[0].t.x * dx + (double)lib[0].t.y * dy) / L; /* cos(tangent, chord 0) */
    TEST_NOTE("drc B1 set: tangent at P0 %.1f deg from chord 0 (%s)\n", acos(c) * 57.29578,
              CP_REAL_NAME);
    CHECK(c > 0.0);
    for (i = 0; i <= 8u; i++) { /* segment 0: points 0..8 at K = 3 */
        double s = ((double)lib[i].p.x * dx + (double)lib[i].p.y * dy) / L;
        CHECK(s >= -1e-6 * L && s <= L * (1.0 + 1e-6));
    }
    CHECK_EQ_INT(triangle_violations(lib, m), 0);
#if CP_REAL_DOUBLE
    CHECK_EQ_INT(ref_drc_run(P, 4, 3, refp, reft, &nr), 0);
    CHECK_EQ_INT(nr, 25);
    for (i = 0; i < m; i++) {
        CHECK_NEAR(lib[i].p.x, refp[i][0], 1e-9, 0);
        CHECK_NEAR(lib[i].p.y, refp[i][1], 1e-9, 0);
    }
#else
    (void)nr;
#endif
    return 0;
}

/* B1 property: random planar sets (3..12 points, chords 1:150, turns < 89 deg, either
 * sign, so inflections and steep ratios), K = 4: every tangent of every pass within
 * 90 deg of both its chords (no rejection is expected: the sets satisfy A.3); every
 * point inserted into a convex segment (end angles of one turn, ratio <= 40, inside the
 * unclamped q range) lies in its tangent triangle (double build: float leaves at K = 4
 * are below the containment slack). Linear-model segments (an inflection, or one end
 * angle on the chord) are S-curves by A.2 and are only counted (drc.h, drc_insert). */
#define PROP_K 4

/* max |v_k| (the coordinate scale of DRC_ANGLE_ZERO) */
static double max_abs3(const struct cp_vec3 *v)
{
    return fmax(fmax(fabs((double)v->x), fabs((double)v->y)), fabs((double)v->z));
}

int test_drc_random_planar(void)
{
    static struct drc_pt b[((uint32_t)(CP_MAX_DRC_POINTS - 1) << PROP_K) + 1u];
    unsigned seed = 20240606u;
    int set, sets = DRC_HEAVY ? 400 : 40, tan_bad = 0, tri_bad = 0, convex = 0, linear = 0;
    for (set = 0; set < sets; set++) {
        int n = 3 + (int)(test_prng(&seed) % (CP_MAX_DRC_POINTS - 2)), i, k;
        double x = 0.0, y = 0.0, h = (double)(test_prng(&seed) % 6283u) * 1e-3;
        uint32_t m = 0;
        for (i = 0; i < n; i++) {
            double u = (double)(test_prng(&seed) % 20001u) * 1e-4 - 1.0; /* -1..1 */
            double v = (double)(test_prng(&seed) % 20001u) * 1e-4 - 1.0;
            double len = exp(2.5 * u);
            b[i].p.x = (cp_real)x;
            b[i].p.y = (cp_real)y;
            b[i].p.z = CP_R(0.0);
            h += i > 0 ? v * 89.0 * 0.017453292519943295 : 0.0;
            x += len * cos(h);
            y += len * sin(h);
        }
        CHECK_EQ_INT(drc_run(b, (uint32_t)n, PROP_K, sizeof b / sizeof b[0], &m), CP_OK);
        for (k = 0; k <= PROP_K; k++) {
            uint32_t sd = (uint32_t)1u << (PROP_K - k), mk = ((uint32_t)(n - 1) << k) + 1u, j;
            for (j = 0; j + 1u < mk; j++) {
                const struct drc_pt *a = &b[j * sd], *e = &b[(j + 1u) * sd];
                double dx = (double)e->p.x - (double)a->p.x, dy = (double)e->p.y - (double)a->p.y;
                double ta = atan2(dx * (double)a->t.y - dy * (double)a->t.x,
                                  dx * (double)a->t.x + dy * (double)a->t.y);
                double tb = atan2(dx * (double)e->t.y - dy * (double)e->t.x,
                                  dx * (double)e->t.x + dy * (double)e->t.y);
                double zero = (double)DRC_ANGLE_ZERO *
                              (1.0 + (max_abs3(&a->p) + max_abs3(&e->p)) / sqrt(dx * dx + dy * dy));
                tan_bad += !(fabs(ta) < 1.5707963267948966 && fabs(tb) < 1.5707963267948966);
                if (k == PROP_K) {
                    continue;
                }
                /* convex as drc.c decides it: both end angles above the zero (DRC_ANGLE_ZERO) */
                if (ta * tb < 0.0 && fabs(ta) > zero && fabs(tb) > zero &&
                    fabs(tb) <= 40.0 * fabs(ta) && fabs(ta) <= 40.0 * fabs(tb)) {
                    convex++;
#if CP_REAL_DOUBLE
                    tri_bad += !drc_in_triangle(a, e, &b[j * sd + sd / 2u].p);
#endif
                } else {
                    linear++;
                }
            }
        }
    }
    TEST_NOTE("drc random planar: %d sets, K = %d: tangents >= 90 deg from a chord %d, "
              "triangle violations %d of %d convex inserts (%d linear-model inserts) (%s)\n",
              sets, PROP_K, tan_bad, tri_bad, convex, linear, CP_REAL_NAME);
    CHECK_EQ_INT(tan_bad, 0);
    CHECK_EQ_INT(tri_bad, 0);
    return 0;
}

/* B2: EDGE mode regularity at every point. A fillet R = 30 along a circle of radius 20
 * (R kappa = 1.5: lines with cot(u/2) in 0.38..2.62, u = 42..138 deg, cross the
 * cuspidal edge). (a) Lines at u = 20 and 170 deg are regular, but their link on the end
 * circle passes u = 90 deg: it was checked with kappa = 0 (always regular for constant
 * R) and streamed; now CP_ERR_CUSP. (b) R LINEAR 40 -> 4 along a 120 deg arc, K = 0,
 * one line at u = 90 deg: only its first point is beyond the edge (D < 0 there, checked
 * below independently with the exact curvature), and the first point of a line was
 * exempt; now CP_ERR_CUSP. */
int test_drc_edge_cusp_ends(void)
{
    struct raster_cfg rc;
    struct canal_frame f;
    double P[7][3];
    cp_real q, cs, sn;
    int i;
    for (i = 0; i < 5; i++) {
        double a = 0.25 * i;
        P[i][0] = 20.0 * sin(a);
        P[i][1] = 20.0 * (1.0 - cos(a));
        P[i][2] = 0.0;
    }
    set_geom((const double(*)[3])P, 5, 2, 1);
    raster_defaults(&rc);
    rc.tol = CP_R(0.01);
    gcfg.radius = CANAL_R_CONST;
    gcfg.rp[0] = CP_R(30.0);
    rc.u0 = CP_R(20.0) * CP_DEG2RAD;
    rc.u1 = rc.u0;
    CHECK_EQ_INT(drc_path_init(&it, &gcfg, &rc), CP_OK);
    rc.u0 = CP_R(170.0) * CP_DEG2RAD;
    rc.u1 = rc.u0;
    CHECK_EQ_INT(drc_path_init(&it, &gcfg, &rc), CP_OK);
    rc.n = 2;
    rc.u0 = CP_R(20.0) * CP_DEG2RAD;
    CHECK_EQ_INT(drc_path_init(&it, &gcfg, &rc), CP_ERR_CUSP); /* the link */
    rc.u0 = CP_R(-20.0) * CP_DEG2RAD; /* the convex side: no edge */
    rc.u1 = CP_R(-170.0) * CP_DEG2RAD;
    CHECK_EQ_INT(drc_path_init(&it, &gcfg, &rc), CP_OK);
    /* (b) */
    for (i = 0; i < 3; i++) {
        double a = 1.0471975511965976 * i;
        P[i][0] = 20.0 * sin(a);
        P[i][1] = 20.0 * (1.0 - cos(a));
    }
    set_geom((const double(*)[3])P, 3, 0, 1);
    rc.n = 1;
    gcfg.radius = CANAL_R_LINEAR;
    gcfg.rp[0] = CP_R(40.0);
    gcfg.rp[1] = CP_R(4.0);
    rc.u0 = CP_R(90.0) * CP_DEG2RAD;
    rc.u1 = rc.u0;
    /* D at the first point: R = 40, p = dR/ds = -36 / arc, kappa = 1/20, Lambda = 0,
     * label (q cos 45, sin 45) */
    memset(&f, 0, sizeof f);
    f.r = CP_R(40.0);
    f.p = CP_R(-36.0) / CP_R(41.887902047863905);
    f.q2 = CP_R(1.0) + f.p * f.p;
    f.kappa = CP_R(0.05);
    f.tx = CP_R(1.0);
    q = cp_sqrt(f.q2);
    cp_sincos(CP_R(45.0) * CP_DEG2RAD, &sn, &cs);
    CHECK(canal_regularity(&f, q * cs, sn, CP_R(0.0)) < CP_R(0.0));
    CHECK_EQ_INT(drc_path_init(&it, &gcfg, &rc), CP_ERR_CUSP);
    rc.u0 = CP_R(20.0) * CP_DEG2RAD; /* away from the edge */
    rc.u1 = rc.u0;
    CHECK_EQ_INT(drc_path_init(&it, &gcfg, &rc), CP_OK);
    return 0;
}

/* B4: THICKEN AUTO measured the sagitta |pt - q0|-normalised; a line point equal to the
 * one two steps back gave NaN, which was ignored, so AUTO accepted K = 2 on a curve at
 * the float resolution (chords of two ulps at 9000 mm). Now CP_ERR_NUMERIC. (The double
 * build resolves these points: no coincidence, AUTO finds a K.) */
int test_drc_sagitta_nan(void)
{
    static const double P[4][3] = {{9000.81152, 9000.4541, 0.0},
                                   {9000.8125, 9000.45215, 0.0},
                                   {9000.81348, 9000.4502, 0.0},
                                   {9000.81445, 9000.44824, 0.0}};
    struct raster_cfg rc;
    int err;
    set_geom(P, 4, DRC_PASSES_AUTO, 0);
    raster_defaults(&rc);
    rc.tol = CP_R(1e-5);
    err = drc_path_init(&it, &gcfg, &rc);
    TEST_NOTE("drc B4 set: AUTO init %d, K = %u (%s)\n", err, (unsigned)it.passes, CP_REAL_NAME);
#if CP_REAL_DOUBLE
    CHECK(err == CP_OK || err == CP_ERR_TOL);
#else
    CHECK_EQ_INT(err, CP_ERR_NUMERIC);
#endif
    return 0;
}

/* Readiness: SURFACE DRC with EDGE ON needs RADIUS (was error:11 at RUN from R = 0, now
 * an incomplete job, error:10, before the geometry is touched); EDGE OFF does not. */
static int drc_cmd(struct job *j, const char *s)
{
    return job_command(j, s, strlen(s));
}

int test_drc_job_ready(void)
{
    static struct job j;
    job_init(&j);
    CHECK_EQ_INT(drc_cmd(&j, "SURFACE DRC"), CP_ST_OK);
    CHECK_EQ_INT(drc_cmd(&j, "POINT 0 0"), CP_ST_OK);
    CHECK_EQ_INT(drc_cmd(&j, "POINT 10 1"), CP_ST_OK);
    CHECK_EQ_INT(drc_cmd(&j, "POINT 19 4"), CP_ST_OK);
    CHECK_EQ_INT(job_ready(&j), CP_ST_OK);
    CHECK_EQ_INT(drc_cmd(&j, "EDGE ON"), CP_ST_OK);
    CHECK_EQ_INT(job_ready(&j), CP_ST_NO_JOB);
    CHECK_EQ_INT(drc_cmd(&j, "RADIUS CONST 3"), CP_ST_OK);
    CHECK_EQ_INT(job_ready(&j), CP_ST_OK);
    CHECK_EQ_INT(drc_cmd(&j, "EDGE OFF"), CP_ST_OK);
    CHECK_EQ_INT(job_ready(&j), CP_ST_OK);
    return 0;
}

/* The judge's verdict on correct streams (issue 21). Random planar sets with an inflection
 * (a cubic S through the middle), a third of them with a collinear run (two points put on
 * the chord of their neighbours: collinear in exact arithmetic, at rounding level in
 * double) and a third on an exact circle; K = 1..5. Three computations of each set:
 *   the stream     drc_run of this build (float or double), the points host_sim receives
 *   the judge      tests/ref_drc.c in double, what host_sim/judge_drc.c compares with
 *   the truth      the same source in long double (ref_drc_run_ld, 64-bit mantissa)
 * host_sim's verdict is PASS iff every point is within JD_LIM_MM = 1 um and every tangent
 * within JD_LIM_DEG = 0.01 deg of its reference (judge_drc.c). Asserted on every set: the
 * judge's verdict equals the verdict against the truth (a set whose deviation from the truth
 * is within the judge reference's own error of a limit would be ambiguous; counted, none
 * expected), the judge's reference is within 1e-4 of the limits of the truth, and the stream
 * is right: within 1 um, tangents within PROP_TAN_DEG (below); the double build's stream
 * passes the judge on every set and is within 1e-9 mm of the truth. With the tolerance of
 * issue 21's first round alone (2^-18 at the end angles of step 2), the float stream of 3
 * sets in 1000 was up to 0.099 mm off: a tangent given up on its chord left step 1's
 * bisection at t = 2^-29 (float) or 2^-61 (double), not at the exact 0 of A.2, and seg_k's
 * branches (a b > 0, exactly one zero) then saw different angles in each build; the
 * neighbouring vertex's G2 solution moved by 3 deg (drc.c solve now takes the end value
 * exactly, within the zero). */
#define JD_LIM_MM 1e-3  /* host_sim/judge_drc.c */
#define JD_LIM_DEG 0.01 /* host_sim/judge_drc.c */
/* The float build's tangent floor at K = 5: a leaf's chord direction is read from points
 * stored in float with absolute coordinates, (|A| + |B|)/c ~ 1e3 here (offsets up to 50 mm,
 * leaves 0.05 mm long), so every level adds ~eps (|A| + |B|)/c ~ 6e-5 rad; 2 sets in 1000
 * are measured at 0.0108 and 0.0109 deg (positions within 28 nm), beyond host_sim's 0.01 deg,
 * and the judge says FAIL on them, rightly. Asserted: 0.02 deg (float), the limit (double). */
#if CP_REAL_DOUBLE
#define PROP_TAN_DEG JD_LIM_DEG
#else
#define PROP_TAN_DEG 0.02
#endif

/* max over the points of |p - ref| (mm) and of the tangent angle (deg), x-y plane */
static void prop_dev(const double (*p)[3], const double (*t)[3], const long double (*rp)[3],
                     const long double (*rt)[3], uint32_t cnt, double dev[2])
{
    uint32_t k;
    dev[0] = 0.0;
    dev[1] = 0.0;
    for (k = 0; k < cnt; k++) {
        double ex = (double)((long double)p[k][0] - rp[k][0]);
        double ey = (double)((long double)p[k][1] - rp[k][1]);
        double dot = (double)((long double)t[k][0] * rt[k][0] + (long double)t[k][1] * rt[k][1]);
        double crs = (double)((long double)t[k][0] * rt[k][1] - (long double)t[k][1] * rt[k][0]);
        dev[0] = fmax(dev[0], sqrt(ex * ex + ey * ey));
        dev[1] = fmax(dev[1], fabs(atan2(crs, dot)) * 57.29577951308232);
    }
}

/* the stream's points and tangents in double */
static void prop_stream(const struct drc_pt *b, uint32_t cnt, double (*S)[3], double (*ST)[3])
{
    uint32_t k;
    for (k = 0; k < cnt; k++) {
        S[k][0] = (double)b[k].p.x;
        S[k][1] = (double)b[k].p.y;
        ST[k][0] = (double)b[k].t.x;
        ST[k][1] = (double)b[k].t.y;
    }
}

/* DRC_PROP_SETS random sets: the 1 000 in the float host build (the firmware's own
 * arithmetic); the first 100 of the same sets in the double and sanitizer builds, where
 * the long double recomputation (A.2's 64 bisections of expm1l per convex segment, about
 * a quarter second per set) would take most of CI's time for no new case; 10 on QEMU (the
 * M4F's float firmware against its soft double references: 2 s a set).
 * `make unit-double CP_DEFS=-DDRC_PROP_SETS=1000` runs the double build's full count
 * (docs/DRC-ZERO.md's double column). */
#ifndef DRC_PROP_SETS
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define DRC_PROP_SANITIZED 1
#endif
#endif
#if !DRC_HEAVY
#define DRC_PROP_SETS 10
#elif CP_REAL_DOUBLE || defined(DRC_PROP_SANITIZED)
#define DRC_PROP_SETS 100
#else
#define DRC_PROP_SETS 1000
#endif
#endif
#define PROP_OUT (((CP_MAX_DRC_POINTS - 1) << 5) + 1)
int test_drc_judge_property(void)
{
    static struct drc_pt b[PROP_OUT];
    static double P[CP_MAX_DRC_POINTS][3], R[PROP_OUT][3], RT[PROP_OUT][3], S[PROP_OUT][3],
        ST[PROP_OUT][3];
    static long double PL[CP_MAX_DRC_POINTS][3], RL[PROP_OUT][3], RTL[PROP_OUT][3],
        RD[PROP_OUT][3], RTD[PROP_OUT][3];
    unsigned seed = 20261126u;
    int want = DRC_PROP_SETS, done = 0, tries = 0, runs[3] = {0, 0, 0};
    int fail_judge = 0, fail_true = 0, ambiguous = 0, collinear = 0;
    double w_str = 0.0, w_str_t = 0.0, w_ref = 0.0, w_ref_t = 0.0;
    while (done < want && tries < 4 * want) {
        int n = 5 + (int)(test_prng(&seed) % (CP_MAX_DRC_POINTS - 4)), kind = tries % 3, i, m, K;
        double a3 = 0.002 + 1e-4 * (double)(test_prng(&seed) % 600u);
        double a1 = 1e-3 * (double)(test_prng(&seed) % 1000u) - 0.5, x0, hx;
        double off = 1e-2 * (double)(test_prng(&seed) % 5001u), sd[2], tr[2], rf[2];
        uint32_t cnt = 0, k;
        int run0 = 1 + (int)(test_prng(&seed) % (unsigned)(n - 3)), v_judge, v_true;
        tries++;
        K = 1 + (int)(test_prng(&seed) % 5u);
        hx = 1.5 + 1e-3 * (double)(test_prng(&seed) % 2000u);
        x0 = 0.5 * hx * (n - 1) + 1e-3 * (double)(test_prng(&seed) % 2001u) - 1.0;
        for (i = 0; i < n; i++) {
            double x = hx * i + 0.3 * hx * (1e-3 * (double)(test_prng(&seed) % 1001u) - 0.5);
            double y = a3 * (x - x0) * (x - x0) * (x - x0) + a1 * (x - x0);
            if (kind == 2) { /* an exact circle of radius 3 n, a quarter turn */
                double t = 1.5707963267948966 * i / (n - 1);
                x = 3.0 * n * cos(t);
                y = 3.0 * n * sin(t);
            }
            P[i][0] = x + off;
            P[i][1] = y - off;
            P[i][2] = 0.0;
        }
        if (kind == 1) { /* a collinear run: P[run0] on the chord P[run0 - 1] .. P[run0 + 1] */
            double f = (double)(test_prng(&seed) % 1001u) * 1e-3 * 0.6 + 0.2;
            for (i = 0; i < 2; i++) {
                P[run0][i] = P[run0 - 1][i] + f * (P[run0 + 1][i] - P[run0 - 1][i]);
            }
        }
        for (i = 0; i < n; i++) {
            b[i].p.x = (cp_real)P[i][0];
            b[i].p.y = (cp_real)P[i][1];
            b[i].p.z = CP_R(0.0);
        }
        if (drc_run(b, (uint32_t)n, (uint32_t)K, sizeof b / sizeof b[0], &cnt) != CP_OK) {
            continue; /* a set drc_tangents refuses (turn >= 90 deg, coincident) */
        }
        /* the points the firmware holds (POINT parses into cp_real; drc_run keeps them at
         * i 2^K): every model starts from them. (Read back after the call: GCC 12.2 -O2
         * vectorizes P = (double)(float)P into a copy that drops the float rounding.) */
        for (i = 0; i < n; i++) {
            P[i][0] = (double)b[(uint32_t)i << K].p.x;
            P[i][1] = (double)b[(uint32_t)i << K].p.y;
            PL[i][0] = (long double)P[i][0];
            PL[i][1] = (long double)P[i][1];
            PL[i][2] = 0.0L;
        }
        CHECK_EQ_INT(ref_drc_run((const double(*)[3])P, n, K, R, RT, &m), 0);
        CHECK_EQ_INT((int)cnt, m);
        CHECK_EQ_INT(ref_drc_run_ld((const long double(*)[3])PL, n, K, RL, RTL, &m), 0);
        CHECK_EQ_INT((int)cnt, m);
        prop_stream(b, cnt, S, ST);
        for (k = 0; k < cnt; k++) {
            for (i = 0; i < 2; i++) {
                RD[k][i] = (long double)R[k][i];
                RTD[k][i] = (long double)RT[k][i];
            }
        }
        prop_dev((const double(*)[3])S, (const double(*)[3])ST, (const long double(*)[3])RD,
                 (const long double(*)[3])RTD, cnt, sd); /* what host_sim measures */
        prop_dev((const double(*)[3])S, (const double(*)[3])ST, (const long double(*)[3])RL,
                 (const long double(*)[3])RTL, cnt, tr);
        prop_dev((const double(*)[3])R, (const double(*)[3])RT, (const long double(*)[3])RL,
                 (const long double(*)[3])RTL, cnt, rf);
        v_judge = sd[0] <= JD_LIM_MM && sd[1] <= JD_LIM_DEG;
        v_true = tr[0] <= JD_LIM_MM && tr[1] <= JD_LIM_DEG;
        if (fabs(tr[0] - JD_LIM_MM) <= rf[0] || fabs(tr[1] - JD_LIM_DEG) <= rf[1]) {
            ambiguous++;
        } else if (v_judge != v_true || !v_true || rf[0] > 1e-4 * JD_LIM_MM ||
                   rf[1] > 1e-4 * JD_LIM_DEG) {
            TEST_NOTE("drc judge property: set %d (kind %d, n %d, K %d): stream %.3g mm %.3g deg "
                      "(judge %s), vs truth %.3g mm %.3g deg, judge's ref vs truth %.3g mm %.3g "
                      "deg\n",
                      tries, kind, n, K, sd[0], sd[1], v_judge ? "PASS" : "FAIL", tr[0], tr[1],
                      rf[0], rf[1]);
        }
        fail_judge += !v_judge;
        fail_true += !v_true;
        CHECK(v_judge == v_true);
        CHECK(tr[0] <= JD_LIM_MM && tr[1] <= PROP_TAN_DEG); /* the stream is right */
        /* the judge's reference: 4 orders below the judge's limits (its own error, mostly
         * E2's cancellation just above the series threshold, is ~1e-9 mm, 1e-7 deg) */
        CHECK(rf[0] <= 1e-4 * JD_LIM_MM && rf[1] <= 1e-4 * JD_LIM_DEG);
#if CP_REAL_DOUBLE
        CHECK(tr[0] <= 1e-9 && tr[1] <= 1e-7);
#endif
        for (i = 1; i + 1 < n; i++) { /* collinear vertices the scheme sees (turn 0) */
            double cz = (P[i][0] - P[i - 1][0]) * (P[i + 1][1] - P[i][1]) -
                        (P[i][1] - P[i - 1][1]) * (P[i + 1][0] - P[i][0]);
            collinear += fabs(cz) < 1e-3;
        }
        w_str = fmax(w_str, tr[0]);
        w_str_t = fmax(w_str_t, tr[1]);
        w_ref = fmax(w_ref, rf[0]);
        w_ref_t = fmax(w_ref_t, rf[1]);
        runs[kind]++;
        done++;
    }
    TEST_NOTE("drc judge property: %d sets (S-curves %d, with a collinear run %d (%d collinear "
              "vertices), circles %d; K = 1..5), %s stream vs the long double scheme: max %.3g mm, "
              "%.3g deg; the judge's double reference vs it: %.3g mm, %.3g deg\n", done, runs[0],
              runs[1], collinear, runs[2], CP_REAL_NAME, w_str, w_str_t, w_ref, w_ref_t);
    TEST_NOTE("drc judge property: verdicts FAIL %d (judge) / %d (truth) of %d, ambiguous %d "
              "(long double: %d-bit mantissa)\n", fail_judge, fail_true, done, ambiguous,
              LDBL_MANT_DIG);
    CHECK(done >= want);
    CHECK_EQ_INT(ambiguous, 0);
#if CP_REAL_DOUBLE
    CHECK_EQ_INT(fail_true, 0);
#endif
    return 0;
}

/* The boundaries of issue 21, one set each, K = 5, against the long double scheme:
 *   S-curve  tests/jobs/model_drc_scurve.job's points: step 1 gives G2 up at P2 (its tangent
 *            on chord 2, exactly: A.2's end value) next to P3's 1.3 mrad turn;
 *   run      tests/jobs/model_drc_collinear.job's points: P2 .. P5 on one line in decimal,
 *            at rounding level in float and double: P3 and P4 are collinear vertices (turn 0)
 *            and every point inserted between P3 and P4 stays on that line;
 *   circle   a quarter of a circle of radius 20 around (60, -45): the points inserted stay
 *            on it (1e-12 R double; float: the coordinates' rounding, 4 ulp of 80 mm).
 * Asserted: the stream within host_sim's limits of the truth (1e-9 mm and 1e-7 deg in
 * double), the tangent at P2 on chord 2 within the angle zero, the run and the circle. */
int test_drc_zero_boundaries(void)
{
    static const double sets[3][8][2] = {
        {{19.8689137, -33.5898323}, {22.6500759, -23.3537064}, {24.705719, -20.6245651},
         {27.5781174, -20.1285591}, {29.8249931, -19.7376232}, {32.606884, -15.6355782},
         {35.0136108, -5.82091808}},
        {{0, 0}, {4.1, 2.3}, {8.6, 3.65}, {13.7, 4.67}, {18.8, 5.69}, {23.9, 6.71}, {28.7, 8.4},
         {33.1, 11.2}},
        {{80, -45}, {79.02113, -38.81966}, {76.18034, -33.24429}, {71.75571, -28.81966},
         {66.18034, -25.97887}, {60, -25}}};
    static const int count[3] = {7, 8, 6};
    static struct drc_pt b[((uint32_t)(CP_MAX_DRC_POINTS - 1) << 5) + 1u];
    static double S[PROP_OUT][3], ST[PROP_OUT][3];
    static long double PL[CP_MAX_DRC_POINTS][3], RL[PROP_OUT][3], RTL[PROP_OUT][3];
    const uint32_t K = 5u;
    int s, i, m;
    for (s = 0; s < 3; s++) {
        int n = count[s];
        uint32_t cnt = 0, k;
        double dev[2], worst = 0.0;
        for (i = 0; i < n; i++) {
            if (s == 2) { /* on the circle in double, then in this build's precision */
                double t = 1.5707963267948966 * i / (n - 1);
                b[i].p.x = (cp_real)(60.0 + 20.0 * cos(t));
                b[i].p.y = (cp_real)(-45.0 + 20.0 * sin(t));
            } else {
                b[i].p.x = (cp_real)sets[s][i][0];
                b[i].p.y = (cp_real)sets[s][i][1];
            }
            b[i].p.z = CP_R(0.0);
        }
        CHECK_EQ_INT(drc_run(b, (uint32_t)n, K, sizeof b / sizeof b[0], &cnt), CP_OK);
        for (i = 0; i < n; i++) {
            PL[i][0] = (long double)b[i << K].p.x;
            PL[i][1] = (long double)b[i << K].p.y;
            PL[i][2] = 0.0L;
        }
        CHECK_EQ_INT(ref_drc_run_ld((const long double(*)[3])PL, n, (int)K, RL, RTL, &m), 0);
        CHECK_EQ_INT((int)cnt, m);
        prop_stream(b, cnt, S, ST);
        prop_dev((const double(*)[3])S, (const double(*)[3])ST, (const long double(*)[3])RL,
                 (const long double(*)[3])RTL, cnt, dev);
        if (s == 0) { /* the tangent at P2 on chord 2 */
            const struct drc_pt *p2 = &b[2u << K], *p3 = &b[3u << K];
            double cx = (double)(p3->p.x - p2->p.x), cy = (double)(p3->p.y - p2->p.y);
            worst = fabs(atan2(cx * (double)p2->t.y - cy * (double)p2->t.x,
                               cx * (double)p2->t.x + cy * (double)p2->t.y));
            CHECK(worst <= (double)DRC_ANGLE_ZERO * (1.0 + 2.0 * 36.0 / sqrt(cx * cx + cy * cy)));
        }
        if (s == 1) { /* the run P3 .. P4: every point between on the line through them */
            const struct cp_vec3 *a = &b[3u << K].p, *e = &b[4u << K].p;
            double lx = (double)(e->x - a->x), ly = (double)(e->y - a->y);
            double l = sqrt(lx * lx + ly * ly);
            for (k = 3u << K; k <= 4u << K; k++) {
                double px = (double)b[k].p.x - (double)a->x, py = (double)b[k].p.y - (double)a->y;
                worst = fmax(worst, fabs(px * ly - py * lx) / l);
            }
            CHECK(worst <= (CP_REAL_DOUBLE ? 1e-12 : 1e-5));
        }
        if (s == 2) { /* every point on the circle */
            for (k = 0; k < cnt; k++) {
                double dx = S[k][0] - 60.0, dy = S[k][1] + 45.0;
                worst = fmax(worst, fabs(sqrt(dx * dx + dy * dy) - 20.0));
            }
            CHECK(worst <= (CP_REAL_DOUBLE ? 1e-12 * 20.0 : 4.0 * 80.0 * 5.96e-8));
        }
        TEST_NOTE("drc zero boundary %s: %u points, vs the long double scheme %.3g mm, %.3g deg; "
                  "%s %.3g (%s)\n", s == 0 ? "S-curve" : (s == 1 ? "run" : "circle"),
                  (unsigned)cnt, dev[0], dev[1], s == 0 ? "tangent at P2 off chord 2 (rad)"
                                 : (s == 1 ? "off the run's line (mm)" : "off the circle (mm)"),
                  worst, CP_REAL_NAME);
        CHECK(dev[0] <= (CP_REAL_DOUBLE ? 1e-9 : JD_LIM_MM));
        CHECK(dev[1] <= (CP_REAL_DOUBLE ? 1e-7 : JD_LIM_DEG));
    }
    return 0;
}
