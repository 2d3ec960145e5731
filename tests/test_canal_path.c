/* test_canal_path.c - deterministic kernels, raster structure, links, tool offset.
 * SPDX-License-Identifier: MIT
 *
 * Accuracy against the independent reference lives in test_canal_ref.c; these tests
 * check the structure of the stream: zigzag order, link moves on the right circles
 * and lines, no gaps, ball-tool geometry, and the maths kernels against libm.
 */
#include "cp_math.h"
#include "test.h"
#include "canal_path.h"

#define PI_D 3.14159265358979323846

/* cp_exp, cp_expm1, cp_log against libm in double (the models of seeds 001-003 build
 * pow, Beta and the DRC segment model on them). */
int test_math_exp_log(void)
{
    double we = 0.0, wm = 0.0, wl = 0.0;
    unsigned i, st = 777u;
    for (i = 0; i < 20000u; i++) {
        double u = (double)(test_prng(&st) % 2000001u) / 1000000.0 - 1.0;
        double x = (double)(cp_real)(u * 87.0), y = (double)(cp_real)(u * 0.5);
        double z = (double)(cp_real)exp(u * 80.0), e, r;
        e = fabs((double)cp_exp((cp_real)x) - exp(x)) / exp(x);
        we = e > we ? e : we;
        r = expm1(y);
        if (r != 0.0) {
            e = fabs((double)cp_expm1((cp_real)y) - r) / fabs(r);
            wm = e > wm ? e : wm;
        }
        e = fabs((double)cp_log((cp_real)z) - log(z)) / (2.0e-7 + 4.0 * CP_REAL_EPS * fabs(log(z)));
        wl = e > wl ? e : wl;
    }
    TEST_NOTE("exp max rel %.3g, expm1 max rel %.3g, log max err / bound %.3g (%s)\n", we, wm, wl,
              CP_REAL_NAME);
    CHECK(we <= 4.0 * CP_REAL_EPS);
    CHECK(wm <= 4.0 * CP_REAL_EPS);
    CHECK(wl <= 1.0);
    CHECK(cp_finite(cp_exp(CP_R(1000.0))) && cp_exp(CP_R(-1000.0)) >= CP_R(0.0));
    CHECK(!cp_finite(cp_log(CP_R(-1.0))));
    CHECK(cp_exp(CP_R(0.0)) == CP_R(1.0) && cp_log(CP_R(1.0)) == CP_R(0.0));
    return 0;
}

/* cp_floor / cp_ceil (float build: the firmware's own cp_floorf) equal libm's floor and
 * ceil on every tested value: random floats over 2^-10 .. 2^30 of both signs, the
 * neighbours of integers (one ulp off) and the specials. */
int test_math_floor_ceil(void)
{
    static const double sp[] = {0.0, 0.5, 1.0, 8388607.5, 8388608.0, 16777217.0, 1e30};
    unsigned i, st = 4242u, bad = 0u;
    for (i = 0; i < 60000u; i++) {
        double m = (double)(test_prng(&st) % 1000000u) / 1000000.0, x;
        int e = (int)(test_prng(&st) % 41u) - 10;
        cp_real v;
        x = ldexp(1.0 + m, e) * ((i & 1u) ? -1.0 : 1.0);
        if (i % 3u == 0u) { /* an integer, or one ulp beside one */
            x = floor(x);
            v = (cp_real)x;
            v = (i % 9u == 0u) ? v : (i % 9u == 3u ? nextafterf((float)v, 1e30f) : nextafterf((float)v, -1e30f));
        } else {
            v = (cp_real)x;
        }
        bad += (double)cp_floor(v) != floor((double)v) || (double)cp_ceil(v) != ceil((double)v);
    }
    for (i = 0; i < sizeof sp / sizeof sp[0]; i++) {
        cp_real v = (cp_real)sp[i];
        bad += (double)cp_floor(v) != floor((double)v) || (double)cp_ceil(v) != ceil((double)v);
        bad += (double)cp_floor(-v) != floor(-(double)v) || (double)cp_ceil(-v) != ceil(-(double)v);
    }
    TEST_NOTE("floor/ceil: %u of %u values differ from libm (%s)\n", bad,
              60000u + 2u * (unsigned)(sizeof sp / sizeof sp[0]), CP_REAL_NAME);
    CHECK(bad == 0u);
    CHECK(!cp_finite(cp_floor((cp_real)NAN)) && cp_ceil((cp_real)INFINITY) == (cp_real)INFINITY);
    return 0;
}

int test_math_kernels(void)
{
    double worst_sc = 0.0, worst_at = 0.0;
    unsigned i, st = 12345u;
    for (i = 0; i < 20000u; i++) {
        double x = ((double)(test_prng(&st) % 2000001u) / 1000000.0 - 1.0) * 40.0;
        cp_real s, c;
        double y, e;
        cp_sincos((cp_real)x, &s, &c);
        /* compare with the double of the float argument actually used */
        x = (double)(cp_real)x;
        e = fabs((double)s - sin(x)) + fabs((double)c - cos(x));
        worst_sc = e > worst_sc ? e : worst_sc;
        y = ((double)(test_prng(&st) % 2000001u) / 1000000.0 - 1.0) * 5.0;
        x = ((double)(test_prng(&st) % 2000001u) / 1000000.0 - 1.0) * 5.0;
        y = (double)(cp_real)y;
        x = (double)(cp_real)x;
        e = fabs((double)cp_atan2((cp_real)y, (cp_real)x) - atan2(y, x));
        worst_at = e > worst_at ? e : worst_at;
    }
    TEST_NOTE("sincos max |err| %.3g, atan2 max |err| %.3g rad (%s)\n", worst_sc, worst_at,
              CP_REAL_NAME);
    CHECK(worst_sc <= 4.0e-7);
    CHECK(worst_at <= 4.0e-7);
    /* the two stages give the bits of cp_sincos (canal_path.c spreads a label's sincos
     * over two points and relies on it), over the whole kernel range and at the
     * rounding ties x 2/pi = m + 1/2 */
    for (i = 0; i < 20000u; i++) {
        double x = ((double)(test_prng(&st) % 2000001u) / 1000000.0 - 1.0) * 1.0e5;
        struct cp_sincos_st sst;
        cp_real s1, c1, s2, c2;
        if (i < 64u) {
            x = ((double)i - 31.5) * PI_D / 2.0;
        }
        cp_sincos((cp_real)x, &s1, &c1);
        cp_sincos_stage1((cp_real)x, &sst);
        cp_sincos_stage2(&sst, &s2, &c2);
        CHECK(s1 == s2 && c1 == c2);
        CHECK(fabs((double)s1 * (double)s1 + (double)c1 * (double)c1 - 1.0) < 1e-6);
    }
    {
        /* beyond the kernel range: clamped, finite; NaN stays NaN */
        cp_real s1, c1, nan_v = CP_R(0.0);
        cp_sincos(CP_R(1.0e30), &s1, &c1);
        CHECK(cp_finite(s1) && cp_finite(c1));
        cp_sincos(-CP_R(1.0e30), &s1, &c1);
        CHECK(cp_finite(s1) && cp_finite(c1));
        nan_v = nan_v / nan_v;
        cp_sincos(nan_v, &s1, &c1);
        CHECK(s1 != s1 && c1 != c1);
    }
    CHECK((double)cp_atan2(CP_R(0.0), CP_R(0.0)) == 0.0);
    CHECK(fabs((double)cp_atan2(CP_R(0.0), CP_R(-1.0)) - PI_D) < 4e-7);
    return 0;
}

static void paper_cfg(struct canal_cfg *s, struct raster_cfg *c)
{
    static const struct raster_cfg zero;
    static const struct canal_cfg szero;
    *c = zero;
    *s = szero;
    s->curve = CANAL_ARC;
    s->radius = CANAL_R_COS;
    s->cp[0] = CP_R(0.0);
    s->cp[1] = CP_R(0.0);
    s->cp[2] = CP_R(3.0);
    s->cp[3] = CP_R(0.0);
    s->cp[4] = CP_TWO_PI;
    s->rp[0] = CP_R(5.5);
    s->rp[1] = CP_R(10.5);
    s->rp[2] = CP_R(2.0);
    c->mode = RASTER_LINES;
    c->output = RASTER_OUT_SURFACE;
    c->n = 5;
    c->u0 = CP_R(-0.5);
    c->u1 = CP_R(0.18);
    c->tol = CP_R(0.002);
    c->link = RASTER_LINK_AUTO;
}

static double dist3(const struct cp_vec3 *a, const struct cp_vec3 *b)
{
    double dx = (double)a->x - (double)b->x, dy = (double)a->y - (double)b->y,
           dz = (double)a->z - (double)b->z;
    return sqrt(dx * dx + dy * dy + dz * dz);
}

/* Distance of p from the sphere of centre (C(t), R(t)) minus R, and the angle
 * condition (p - rho).rho' = -R R' (MATH-canal §11), both at the point's own t. */
static void sphere_residual(const struct canal_path *tp, const struct raster_pt *pt,
                            double *dr, double *dang)
{
    struct canal_jet j;
    double ex, ey, ez, r;
    canal_jet(&tp->surf, pt->t, &j);
    ex = (double)pt->p.x - (double)j.x;
    ey = (double)pt->p.y - (double)j.y;
    ez = (double)pt->p.z - (double)j.r;
    r = sqrt(ex * ex + ey * ey + ez * ez);
    *dr = fabs(r - (double)j.r);
    *dang = fabs(ex * (double)j.dx + ey * (double)j.dy + ez * (double)j.dr + (double)j.r * (double)j.dr) /
            sqrt((double)j.dx * (double)j.dx + (double)j.dy * (double)j.dy + (double)j.dr * (double)j.dr);
}

int test_canal_path_zigzag(void)
{
    struct raster_cfg cfg;
    struct canal_cfg surf;
    struct canal_path tp;
    struct raster_pt pt, prev;
    uint32_t k = 0, n;
    double maxgap = 0.0, maxr = 0.0, maxa = 0.0, dr, da;
    int expect_line = 0;
    uint32_t expect_index = 0;
    paper_cfg(&surf, &cfg);
    CHECK_EQ_INT(canal_path_init(&tp, &surf, &cfg), CP_OK);
    n = canal_path_count(&tp);
    CHECK_EQ_INT(n, (uint32_t)cfg.n * (tp.head.steps + 1u) + (uint32_t)(cfg.n - 1u) * tp.head.link);
    CHECK(tp.head.link >= 1u);
    while (canal_path_next(&tp, &pt) == CP_OK) {
        if (pt.line >= 0) {
            /* order: line j, index 0..steps on even lines, steps..0 on odd lines */
            CHECK_EQ_INT(pt.line, expect_line);
            CHECK_EQ_INT(pt.index, (expect_line & 1) ? tp.head.steps - expect_index : expect_index);
            expect_index++;
            if (expect_index > tp.head.steps) {
                expect_index = 0;
                expect_line++;
            }
        } else {
            /* a link point: on the characteristic circle at the line's end t */
            CHECK(pt.t == ((expect_line & 1) ? tp.surf.t0 + (cp_real)(2u * tp.substeps * tp.head.steps) * tp.hp
                                             : tp.surf.t0));
        }
        sphere_residual(&tp, &pt, &dr, &da);
        maxr = dr > maxr ? dr : maxr;
        maxa = da > maxa ? da : maxa;
        if (k > 0u) {
            double g = dist3(&pt.p, &prev.p);
            maxgap = g > maxgap ? g : maxgap;
        }
        prev = pt;
        k++;
    }
    CHECK_EQ_INT(k, n);
    CHECK_EQ_INT(canal_path_next(&tp, &pt), CP_ERR_DONE);
    TEST_NOTE("zigzag: %u points, steps %u, substeps %u, link %u, max step %.4f mm, sphere "
              "residual %.2g mm, envelope residual %.2g mm\n",
              (unsigned)n, (unsigned)tp.head.steps, tp.substeps, tp.head.link, maxgap, maxr, maxa);
    /* no gaps: every move is short (a chord of <= 2 um sagitta on radii <= 16 mm) */
    CHECK(maxgap < 0.6);
    CHECK(maxr < 2e-5);
    CHECK(maxa < 2e-4);
    return 0;
}

int test_canal_path_circles(void)
{
    struct raster_cfg cfg;
    struct canal_cfg surf;
    struct canal_path tp;
    struct raster_pt pt, prev;
    uint32_t k = 0;
    double maxgap = 0.0, maxr = 0.0, dr, da;
    paper_cfg(&surf, &cfg);
    cfg.mode = RASTER_CIRCLES;
    cfg.n = 48;
    CHECK_EQ_INT(canal_path_init(&tp, &surf, &cfg), CP_OK);
    while (canal_path_next(&tp, &pt) == CP_OK) {
        if (pt.line >= 0) {
            /* circle j sits on node j (link + 1) */
            CHECK(pt.t == tp.surf.t0 + (cp_real)((uint32_t)pt.line * (tp.head.link + 1u) * 2u * tp.substeps) * tp.hp);
        }
        sphere_residual(&tp, &pt, &dr, &da);
        maxr = dr > maxr ? dr : maxr;
        if (k > 0u) {
            double g = dist3(&pt.p, &prev.p);
            maxgap = g > maxgap ? g : maxgap;
        }
        prev = pt;
        k++;
    }
    CHECK_EQ_INT(k, canal_path_count(&tp));
    TEST_NOTE("circles: %u points, steps %u, link %u, max step %.4f mm\n", (unsigned)k, (unsigned)tp.head.steps,
              tp.head.link, maxgap);
    CHECK(maxgap < 0.6);
    CHECK(maxr < 2e-5);
    return 0;
}

int test_canal_path_tool(void)
{
    struct raster_cfg cfg;
    struct canal_cfg surf;
    struct canal_path tps, tpc, tpt;
    struct raster_pt ps, pc, pq;
    const cp_real rt = CP_R(2.0);
    double worst = 0.0;
    paper_cfg(&surf, &cfg);
    cfg.steps = 200;
    cfg.tol = CP_R(0.0);
    cfg.link = 4;
    CHECK_EQ_INT(canal_path_init(&tps, &surf, &cfg), CP_OK);
    cfg.output = RASTER_OUT_CENTRE;
    cfg.tool_r = rt;
    CHECK_EQ_INT(canal_path_init(&tpc, &surf, &cfg), CP_OK);
    cfg.output = RASTER_OUT_TIP;
    CHECK_EQ_INT(canal_path_init(&tpt, &surf, &cfg), CP_OK);
    CHECK_EQ_INT(canal_path_count(&tps), canal_path_count(&tpc));
    while (canal_path_next(&tps, &ps) == CP_OK) {
        double e;
        CHECK_EQ_INT(canal_path_next(&tpc, &pc), CP_OK);
        CHECK_EQ_INT(canal_path_next(&tpt, &pq), CP_OK);
        /* centre = surface point - r n; tip = centre - r z; |n| = 1 */
        e = fabs((double)pc.p.x - ((double)ps.p.x - (double)rt * (double)ps.n.x)) +
            fabs((double)pc.p.y - ((double)ps.p.y - (double)rt * (double)ps.n.y)) +
            fabs((double)pc.p.z - ((double)ps.p.z - (double)rt * (double)ps.n.z)) +
            fabs((double)pq.p.z - ((double)pc.p.z - (double)rt)) +
            fabs(sqrt((double)ps.n.x * (double)ps.n.x + (double)ps.n.y * (double)ps.n.y +
                      (double)ps.n.z * (double)ps.n.z) - 1.0);
        worst = e > worst ? e : worst;
    }
    TEST_NOTE("tool offset consistency %.2g mm\n", worst);
    CHECK(worst < 2e-5);
    /* a tool that does not fit is rejected; so is a tool without a tool output */
    cfg.tool_r = CP_R(5.0);
    CHECK_EQ_INT(canal_path_init(&tpc, &surf, &cfg), CP_ERR_TOOL);
    cfg.tool_r = CP_R(-1.0);
    CHECK_EQ_INT(canal_path_init(&tpc, &surf, &cfg), CP_ERR_TOOL);
    cfg.output = RASTER_OUT_SURFACE;
    cfg.tool_r = CP_R(1.0);
    CHECK_EQ_INT(canal_path_init(&tpc, &surf, &cfg), CP_ERR_INVAL);
    return 0;
}

int test_canal_path_deterministic(void)
{
    /* two inits of the same job give bit-identical streams; a second iterator
     * seeked into the middle of a backward line agrees bit for bit */
    struct raster_cfg cfg;
    struct canal_cfg surf;
    static struct canal_path a, b;
    struct raster_pt pa, pb;
    uint32_t k, start;
    paper_cfg(&surf, &cfg);
    cfg.n = 4;
    CHECK_EQ_INT(canal_path_init(&a, &surf, &cfg), CP_OK);
    CHECK_EQ_INT(canal_path_init(&b, &surf, &cfg), CP_OK);
    start = (uint32_t)(a.head.steps + 1u + a.head.link) + a.head.steps / 3u; /* inside line 1 (backward) */
    for (k = 0; k < start; k++) {
        CHECK_EQ_INT(canal_path_next(&a, &pa), CP_OK);
    }
    CHECK_EQ_INT(canal_path_seek(&b, start), CP_OK);
    for (k = start; k < canal_path_count(&a); k++) {
        CHECK_EQ_INT(canal_path_next(&a, &pa), CP_OK);
        CHECK_EQ_INT(canal_path_next(&b, &pb), CP_OK);
        CHECK(pa.p.x == pb.p.x && pa.p.y == pb.p.y && pa.p.z == pb.p.z);
        CHECK(pa.line == pb.line && pa.index == pb.index);
    }
    CHECK_EQ_INT(canal_path_seek(&b, canal_path_count(&b) + 1u), CP_ERR_RANGE);
    return 0;
}

int test_canal_path_seek_stages(void)
{
    /* LINES labels are made in halves over the last two points of a line; seek makes
     * them whole. Seek to EVERY k of short-line jobs (steps 1, 2, 3; links on and off;
     * both label kinds) and compare the rest of the stream bit for bit with the
     * uninterrupted one: a stage done twice, skipped or made for the wrong line shows */
    static const uint16_t steps_v[3] = {1u, 2u, 3u};
    static struct canal_path a, b;
    static struct raster_pt ref[64];
    struct raster_cfg cfg;
    struct canal_cfg surf;
    struct raster_pt pb;
    unsigned sv, lk, lab, checked = 0u;
    uint32_t k, m, cnt;
    for (sv = 0; sv < 3u; sv++) {
        for (lk = 0; lk < 2u; lk++) {
            for (lab = 0; lab < 2u; lab++) {
                paper_cfg(&surf, &cfg);
                cfg.n = 5;
                cfg.steps = steps_v[sv];
                cfg.link = lk ? 2u : 0u;
                cfg.tol = CP_R(0.0);
                if (lab) {
                    cfg.labels = RASTER_LABEL_LAMBDA; /* w = 12..40: u = 9.5..2.9 deg */
                    cfg.u0 = CP_R(12.0);
                    cfg.u1 = CP_R(40.0);
                }
                CHECK_EQ_INT(canal_path_init(&a, &surf, &cfg), CP_OK);
                cnt = canal_path_count(&a);
                CHECK(cnt > 0u && cnt <= 64u);
                for (k = 0; k < cnt; k++) {
                    CHECK_EQ_INT(canal_path_next(&a, &ref[k]), CP_OK);
                }
                CHECK_EQ_INT(canal_path_next(&a, &pb), CP_ERR_DONE);
                CHECK_EQ_INT(canal_path_init(&b, &surf, &cfg), CP_OK);
                for (k = 0; k < cnt; k++) {
                    CHECK_EQ_INT(canal_path_seek(&b, k), CP_OK);
                    for (m = k; m < cnt; m++) {
                        CHECK_EQ_INT(canal_path_next(&b, &pb), CP_OK);
                        CHECK(pb.p.x == ref[m].p.x && pb.p.y == ref[m].p.y &&
                              pb.p.z == ref[m].p.z && pb.n.x == ref[m].n.x &&
                              pb.n.y == ref[m].n.y && pb.n.z == ref[m].n.z);
                        CHECK(pb.line == ref[m].line && pb.index == ref[m].index);
                        checked++;
                    }
                    CHECK_EQ_INT(canal_path_next(&b, &pb), CP_ERR_DONE);
                }
            }
        }
    }
    TEST_NOTE("seek at every k of 12 short-line jobs: %u points bit-identical\n", checked);
    return 0;
}

int test_canal_path_labels_span(void)
{
    /* lambda labels: the line w is the line that starts at u0 = 2 atan2(q0, w) */
    struct raster_cfg cfg;
    struct canal_cfg surf;
    static struct canal_path ta, tb;
    struct raster_pt pa, pb;
    double worst = 0.0;
    uint32_t k;
    paper_cfg(&surf, &cfg);
    cfg.n = 2;
    cfg.steps = 100;
    cfg.tol = CP_R(0.0);
    cfg.link = 0;
    cfg.labels = RASTER_LABEL_LAMBDA;
    cfg.u0 = CP_R(-6.0);
    cfg.u1 = CP_R(12.0);
    CHECK_EQ_INT(canal_path_init(&ta, &surf, &cfg), CP_OK);
    cfg.labels = RASTER_LABEL_ANGLE;
    cfg.u0 = (cp_real)(2.0 * atan2(1.0, -6.0)) - CP_TWO_PI; /* q0 = 1 at t = 0; fold to (-pi, pi] */
    cfg.u1 = (cp_real)(2.0 * atan2(1.0, 12.0));
    CHECK_EQ_INT(canal_path_init(&tb, &surf, &cfg), CP_OK);
    for (k = 0; k < canal_path_count(&ta); k++) {
        CHECK_EQ_INT(canal_path_next(&ta, &pa), CP_OK);
        CHECK_EQ_INT(canal_path_next(&tb, &pb), CP_OK);
        worst = fmax(worst, fabs((double)pa.p.x - (double)pb.p.x) + fabs((double)pa.p.y - (double)pb.p.y) +
                                fabs((double)pa.p.z - (double)pb.p.z));
    }
    TEST_NOTE("lambda vs angle labels: %.2g mm\n", worst);
    CHECK(worst < 2e-5);
    /* span ANGLE: every circle starts at contact angle u0 and ends at u1 */
    paper_cfg(&surf, &cfg);
    cfg.mode = RASTER_CIRCLES;
    cfg.span = RASTER_SPAN_ANGLE;
    cfg.n = 40;
    cfg.u0 = CP_R(-0.4);
    cfg.u1 = CP_R(0.2);
    CHECK_EQ_INT(canal_path_init(&ta, &surf, &cfg), CP_OK);
    worst = 0.0;
    while (canal_path_next(&ta, &pa) == CP_OK) {
        if (pa.line >= 0 && (pa.index == 0u || pa.index == ta.head.steps)) {
            struct canal_jet j;
            struct canal_frame f;
            struct canal_point m;
            cp_real u = pa.index == 0u ? cfg.u0 : cfg.u1;
            canal_jet(&ta.surf, pa.t, &j);
            canal_frame(&j, &f);
            canal_point(&f, (cp_real)sqrt((double)f.q2) * (cp_real)cos(0.5 * (double)u),
                        (cp_real)sin(0.5 * (double)u), CP_R(0.0), &m);
            worst = fmax(worst, fabs((double)pa.p.x - (double)m.m.x) + fabs((double)pa.p.y - (double)m.m.y) +
                                    fabs((double)pa.p.z - (double)m.m.z));
        }
    }
    TEST_NOTE("span ANGLE circle ends: %.2g mm\n", worst);
    CHECK(worst < 2e-5);
    /* span ANGLE needs CIRCLES mode and angle labels */
    cfg.mode = RASTER_LINES;
    CHECK_EQ_INT(canal_path_init(&ta, &surf, &cfg), CP_ERR_INVAL);
    return 0;
}
