/* test_gsr.c - generalized surfaces of revolution (issue 7) against tests/ref_gsr.c.
 * SPDX-License-Identifier: MIT
 *
 * Acceptance of issue 7: the C.4 examples G1/G2/G3 against the independent double
 * reference (double build <= 1e-12 D, float <= 1 um), rational quarters on the ellipse and
 * in the normal plane, frames orthonormal and right-handed, the RMF tube (lines orthogonal
 * to rings, measured to be curvature lines), every C.3 rejection, the iterator (count,
 * zigzag, seek, chord tolerance) and the protocol commands.
 */
#include <string.h>

#include "gsr.h"
#include "job.h"
#include "path.h"
#include "ref_gsr.h"
#include "test.h"

#define PI_D 3.14159265358979323846

#if CP_REAL_DOUBLE
#define TOL_PT_REL 1e-12 /* x D */
#define TOL_PT_ABS 0.0
#define TOL_ORTH 1e-14
#define TOL_NRM 1e-9
#else
#define TOL_PT_REL 0.0
#define TOL_PT_ABS 1e-3 /* 1 um */
#define TOL_ORTH 1e-6
#define TOL_NRM 2e-5
#endif

/* One example: centre kind, functions (w in radians), frame, ref. */
struct ex {
    const char *name;
    int centre, frame;
    double c[3][7], r[3][7], ref[3];
};

static const struct ex ex_g[3] = {
    {"G1", 0, 0, {{0, 8, 0, 0, 0, 0, 0}, {0, 0, 0, 0, 0, 0, 0}, {0, 0, 0, 0, 2, 0, PI_D}},
     {{1.2, 0, 0, 0, 0.5, 0, PI_D}, {0.8, 0.3, 0, 0, 0, 0, 0}, {0, 1, 0, 0, 0, 0, 0}}, {0, 0, 0}},
    {"G2", 0, 1,
     {{0, 0, 0, 0, 0, 3, 2 * PI_D}, {0, 0, 0, 0, 3, 0, 2 * PI_D}, {0, 4, 0, 0, 0, 0, 0}},
     {{0.6, 0.2, 0, 0, 0, 0, 0}, {0.35, 0, 0, 0, 0.1, 0, PI_D}, {0, 0, 3, -2, 0, 0, 0}},
     {0, 0, 0}},
    {"G3", 0, 2, {{0, 6, 0, 0, 0, 0, 0}, {0, 0, 0, 0, 2, 0, PI_D}, {0, 0, 1.5, 0, 0, 0, 0}},
     {{0.9, -0.3, 0, 0, 0, 0, 0}, {0.5, 0, 0.2, 0, 0, 0, 0}, {0, 1, 0, 0, 0, 0, 0}}, {0, 0, 1}},
};

static void to_cfg(const struct ex *e, struct gsr_cfg *c)
{
    unsigned a, i;
    memset(c, 0, sizeof *c);
    c->centre = (uint8_t)e->centre;
    c->frame = (uint8_t)e->frame;
    for (a = 0; a < 3u; a++) {
        for (i = 0; i < 7u; i++) {
            c->c[a][i] = (cp_real)e->c[a][i];
            c->r[a][i] = (cp_real)e->r[a][i];
        }
    }
    c->ref.x = (cp_real)e->ref[0];
    c->ref.y = (cp_real)e->ref[1];
    c->ref.z = (cp_real)e->ref[2];
}

/* The reference uses the numbers the firmware actually holds (float build: rounded). */
static void to_ref(const struct gsr_cfg *c, int frame, struct ref_gsr *g)
{
    double cc[3][7], rr[3][7], ref[3];
    unsigned a, i;
    for (a = 0; a < 3u; a++) {
        for (i = 0; i < 7u; i++) {
            cc[a][i] = (double)c->c[a][i];
            rr[a][i] = (double)c->r[a][i];
        }
    }
    ref[0] = (double)c->ref.x;
    ref[1] = (double)c->ref.y;
    ref[2] = (double)c->ref.z;
    ref_gsr_set(g, c->centre, (const double(*)[7])cc, (const double(*)[7])rr, frame, ref);
}

static double dist(const struct cp_vec3 *p, const double *q)
{
    double dx = (double)p->x - q[0], dy = (double)p->y - q[1], dz = (double)p->z - q[2];
    return sqrt(dx * dx + dy * dy + dz * dz);
}

static double vdot(const struct cp_vec3 *a, const struct cp_vec3 *b)
{
    return (double)a->x * (double)b->x + (double)a->y * (double)b->y + (double)a->z * (double)b->z;
}

static double vdotd(const struct cp_vec3 *a, const double *b)
{
    return (double)a->x * b[0] + (double)a->y * b[1] + (double)a->z * b[2];
}

/* Largest deviation of (n, b, t) from an orthonormal right-handed frame. */
static double frame_err(const struct gsr_sec *s)
{
    double e = 0.0, d[7], det;
    unsigned i;
    d[0] = vdot(&s->n, &s->n) - 1.0;
    d[1] = vdot(&s->b, &s->b) - 1.0;
    d[2] = vdot(&s->t, &s->t) - 1.0;
    d[3] = vdot(&s->n, &s->b);
    d[4] = vdot(&s->n, &s->t);
    d[5] = vdot(&s->b, &s->t);
    det = (double)s->n.x * ((double)s->b.y * s->t.z - (double)s->b.z * s->t.y) -
          (double)s->n.y * ((double)s->b.x * s->t.z - (double)s->b.z * s->t.x) +
          (double)s->n.z * ((double)s->b.x * s->t.y - (double)s->b.y * s->t.x);
    d[6] = det - 1.0;
    for (i = 0; i < 7u; i++) {
        e = fabs(d[i]) > e ? fabs(d[i]) : e;
    }
    return e;
}

static struct ref_gsr rg; /* large (RMF table): static */
static struct gsr gm;
static struct gsr_cfg gc;

/* Acceptance 1 (C.4): trig 8 theta per u, rational 4 quarters x 5 v, u = 0 .. 1 by 1/4,
 * frames; points against the reference to 1e-12 D (double) / 1 um (float). */
int test_gsr_c4_examples(void)
{
    unsigned e;
    for (e = 0; e < 3u; e++) {
        double lo[3] = {1e30, 1e30, 1e30}, hi[3] = {-1e30, -1e30, -1e30}, D, wp = 0.0, wf = 0.0,
               wo = 0.0, wn = 0.0;
        unsigned iu, k, a;
        to_cfg(&ex_g[e], &gc);
        CHECK_EQ_INT(gsr_init(&gm, &gc), CP_OK);
        to_ref(&gc, ex_g[e].frame, &rg);
        for (iu = 0; iu <= 4u; iu++) { /* D: bounding box of the reference samples */
            for (k = 0; k < 8u; k++) {
                double P[3];
                ref_gsr_point(&rg, iu / 4.0, 2.0 * PI_D * k / 8.0, P);
                for (a = 0; a < 3u; a++) {
                    lo[a] = P[a] < lo[a] ? P[a] : lo[a];
                    hi[a] = P[a] > hi[a] ? P[a] : hi[a];
                }
            }
        }
        D = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                 (hi[2] - lo[2]) * (hi[2] - lo[2]));
        for (iu = 0; iu <= 4u; iu++) {
            struct gsr_sec s;
            double u = iu / 4.0, ft[3], T[3], N[3], B[3];
            gsr_section(&gm, (cp_real)u, &s);
            ref_gsr_fn(rg.r[2], u, ft);
            ref_gsr_frame(&rg, ft[0], T, N, B);
            wf = fmax(wf, fmax(dist(&s.t, T), fmax(dist(&s.n, N), dist(&s.b, B))));
            wo = fmax(wo, frame_err(&s));
            for (k = 0; k < 28u; k++) { /* 8 trig + 4 quarters x 5 v */
                struct cp_vec3 p, n;
                cp_real cx, cy;
                double th, P[3], nr[3];
                if (k < 8u) {
                    th = 2.0 * PI_D * k / 8.0;
                    cp_sincos((cp_real)th, &cy, &cx);
                    th = (double)(cp_real)th;
                } else {
                    double psi = -2.0 + (double)((k - 8u) / 5u) + 0.25 * (double)((k - 8u) % 5u);
                    gsr_unit_rational((cp_real)psi, &cx, &cy);
                    th = ref_gsr_theta(psi);
                }
                gsr_point(&s, cx, cy, &p, &n);
                ref_gsr_point(&rg, u, th, P);
                ref_gsr_normal(&rg, u, th, nr);
                wp = fmax(wp, dist(&p, P));
                wn = fmax(wn, dist(&n, nr));
            }
        }
        TEST_NOTE("%s (%s): points max %.3g mm = %.3g D (D = %.3f mm), frames %.3g, "
                  "orthonormality %.3g, normals %.3g rad\n",
                  ex_g[e].name, CP_REAL_NAME, wp, wp / D, D, wf, wo, wn);
        CHECK(wp <= TOL_PT_ABS + TOL_PT_REL * D);
        CHECK(wf <= (CP_REAL_DOUBLE ? 1e-12 : 2e-6));
        CHECK(wo <= TOL_ORTH);
        CHECK(wn <= TOL_NRM);
    }
    return 0;
}

/* Acceptance 2: rational quarter points on the ellipse (1e-14 rel.) and in the normal
 * plane, rational = trigonometric at the same eccentric angle, v(theta) inverts theta(v),
 * the quarter's speed ratio of C.2 (1.17157). */
int test_gsr_rational(void)
{
    double wr = 0.0, wpl = 0.0, wt = 0.0, wv = 0.0, ratio;
    unsigned e, iu, k;
    cp_real x0, y0, x1, y1, xm, ym, xm2, ym2;
    for (e = 0; e < 3u; e++) {
        to_cfg(&ex_g[e], &gc);
        CHECK_EQ_INT(gsr_init(&gm, &gc), CP_OK);
        for (iu = 0; iu <= 8u; iu++) {
            struct gsr_sec s;
            gsr_section(&gm, (cp_real)(iu / 8.0), &s);
            for (k = 0; k <= 64u; k++) {
                double psi = -2.0 + k / 16.0, x, y, r;
                struct cp_vec3 p, n, d;
                cp_real cx, cy, tx, ty;
                gsr_unit_rational((cp_real)psi, &cx, &cy);
                gsr_point(&s, cx, cy, &p, &n);
                d.x = p.x - s.c.x;
                d.y = p.y - s.c.y;
                d.z = p.z - s.c.z;
                x = vdot(&d, &s.n) / (double)s.fn;
                y = vdot(&d, &s.b) / (double)s.fb;
                r = fabs(x * x + y * y - 1.0);
                wr = fmax(wr, r);
                wpl = fmax(wpl, fabs(vdot(&d, &s.t)) / sqrt(vdot(&d, &d)));
                cp_sincos((cp_real)ref_gsr_theta(psi), &ty, &tx);
                wt = fmax(wt, fabs((double)(tx - cx)) + fabs((double)(ty - cy)));
                wv = fmax(wv, fabs((double)gsr_psi((cp_real)ref_gsr_theta(psi)) - psi));
            }
        }
    }
    gsr_unit_rational(CP_R(0.0), &x0, &y0);
    gsr_unit_rational(CP_R(1e-4), &x1, &y1);
    gsr_unit_rational(CP_R(0.5), &xm, &ym);
    gsr_unit_rational(CP_R(0.5001), &xm2, &ym2);
    ratio = hypot((double)(xm2 - xm), (double)(ym2 - ym)) / hypot((double)(x1 - x0), (double)(y1 - y0));
    TEST_NOTE("rational (%s): ellipse residual %.3g, out of the normal plane %.3g, vs trig %.3g, "
              "v(theta) round trip %.3g, speed ratio %.5f (C.2: 1.17157)\n",
              CP_REAL_NAME, wr, wpl, wt, wv, ratio);
    CHECK(wr <= (CP_REAL_DOUBLE ? 1e-14 : 4e-6));
    CHECK(wpl <= (CP_REAL_DOUBLE ? 1e-14 : 1e-6));
    CHECK(wt <= (CP_REAL_DOUBLE ? 1e-14 : 1e-6));
    CHECK(wv <= (CP_REAL_DOUBLE ? 1e-13 : 2e-6));
    CHECK(fabs(ratio - 1.1715729) <= (CP_REAL_DOUBLE ? 1e-4 : 2e-2));
    return 0;
}

/* Frames: all four orthonormal and right-handed (1e-14), the corrected eq. 7, and the RMF
 * against the reference's own double reflection. */
int test_gsr_frames(void)
{
    unsigned f, k;
    for (f = 0; f < 4u; f++) {
        struct ex e = ex_g[f < 3u ? f : 2u];
        double wo = 0.0, wr = 0.0, w7 = 0.0;
        e.frame = (int)f;
        if (f == 3u) {
            e.ref[0] = 0.0;
            e.ref[1] = 0.0;
            e.ref[2] = 1.0;
        }
        to_cfg(&e, &gc);
        CHECK_EQ_INT(gsr_init(&gm, &gc), CP_OK);
        to_ref(&gc, e.frame, &rg);
        for (k = 0; k <= 64u; k++) {
            struct gsr_sec s;
            double u = k / 64.0, ft[3], T[3], N[3], B[3];
            gsr_section(&gm, (cp_real)u, &s);
            wo = fmax(wo, frame_err(&s));
            ref_gsr_fn(rg.r[2], u, ft);
            ref_gsr_frame(&rg, ft[0], T, N, B);
            wr = fmax(wr, fmax(dist(&s.n, N), dist(&s.b, B)));
            if (f == 0u) {
                w7 = fmax(w7, fabs((double)(s.n.x - s.t.z)) + fabs((double)s.n.y) +
                                  fabs((double)(s.n.z + s.t.x)) + fabs(vdot(&s.n, &s.t)));
            }
        }
        TEST_NOTE("frame %u (%s): orthonormal/right-handed %.3g, vs reference %.3g%s\n", f,
                  CP_REAL_NAME, wo, wr, f == 3u ? " (RMF table interpolation)" : "");
        CHECK(wo <= TOL_ORTH);
        /* RMF: the table's Hermite interpolation, bounded at init by GSR_RMF_TOL / rmax
         * (measured against the reference's own double reflection, nodes and between) */
        CHECK(wr <= (f == 3u ? (double)(GSR_RMF_TOL / gm.rmax) + 2e-6
                             : (CP_REAL_DOUBLE ? 1e-12 : 2e-6)));
        CHECK(w7 <= (CP_REAL_DOUBLE ? 1e-15 : 1e-7));
    }
    return 0;
}

/* ---- the raster as documented in gsr.h, in double, for the checks below ---- */
struct rast {
    int mode, form;
    unsigned n, steps, link;
    double v0, v1;
};

/* (u, theta) of point k (and its line, -1 on links). */
static int rast_at(const struct rast *r, unsigned k, double *u, double *th)
{
    unsigned block = r->steps + 1u + r->link, j = k / block, q = k % block, lk = r->link + 1u;
    unsigned i = (j & 1u) ? r->steps - q : q, back = j & 1u;
    double dv = r->n > 1u ? (r->v1 - r->v0) / (r->n - 1u) : 0.0, sig;
#define SIG(x) (r->form == GSR_SECTION_TRIG ? (x) : ref_gsr_psi(x))
    if (r->mode == RASTER_LINES) {
        double s0 = SIG(r->v0 + j * dv), s1 = SIG(r->v0 + (j + 1u) * dv);
        *u = q <= r->steps ? (double)i / r->steps : (back ? 0.0 : 1.0);
        sig = q <= r->steps ? s0 : s0 + (s1 - s0) * (double)(q - r->steps) / lk;
    } else {
        double gs = r->n > 1u ? (double)((r->n - 1u) * lk) : 1.0, s0 = SIG(r->v0), s1 = SIG(r->v1);
        *u = (j * lk + (q <= r->steps ? 0u : q - r->steps)) / gs;
        sig = q <= r->steps ? s0 + (s1 - s0) * (double)i / r->steps : (back ? s0 : s1);
    }
#undef SIG
    *th = r->form == GSR_SECTION_TRIG ? sig : ref_gsr_theta(sig);
    return q <= r->steps ? (int)j : -1;
}

/* the (u, sig) of rast_at, for interpolating along a segment */
static double sig_of(const struct rast *r, double th)
{
    return r->form == GSR_SECTION_TRIG ? th : ref_gsr_psi(th);
}

static struct raster_pt pts[6000];
static struct gsr_path gp;

/* Iterator: count, zigzag, every point on the documented raster (reference), the chord
 * tolerance against the reference curve between consecutive points, seek(k) bit for bit,
 * ball-tool centres at r along the normal. */
int test_gsr_iterator(void)
{
    unsigned run;
    for (run = 0; run < 6u; run++) {
        struct raster_cfg rc;
        struct rast r;
        double wp = 0.0, wc = 0.0, tool = run >= 4u ? 0.4 : 0.0;
        unsigned k, cnt;
        memset(&rc, 0, sizeof rc);
        /* no tool on G2: f_t' = 0 at u = 0, 1 makes its normal +-T there, with a sign that
         * changes along the ring (f_N' > 0 > f_B' at u = 1): the tool centre would jump
         * (gsr_path_init: CP_ERR_TOL) */
        unsigned ei = run == 4u ? 0u : run % 3u;
        to_cfg(&ex_g[ei], &gc);
        gc.section = (uint8_t)(run & 1u);
        r.form = gc.section;
        r.mode = run < 2u || run == 4u ? RASTER_LINES : RASTER_CIRCLES;
        r.v0 = r.mode == RASTER_LINES ? -90.0 * PI_D / 180 : -180.0 * PI_D / 180;
        r.v1 = r.mode == RASTER_LINES ? 90.0 * PI_D / 180 : 180.0 * PI_D / 180;
        rc.mode = (uint8_t)r.mode;
        rc.n = r.mode == RASTER_LINES ? 5u : 4u;
        rc.u0 = (cp_real)r.v0;
        rc.u1 = (cp_real)r.v1;
        rc.tol = CP_R(0.004);
        rc.link = RASTER_LINK_AUTO;
        rc.output = tool > 0.0 ? RASTER_OUT_CENTRE : RASTER_OUT_SURFACE;
        rc.tool_r = (cp_real)tool;
        r.v0 = (double)rc.u0;
        r.v1 = (double)rc.u1;
        CHECK_EQ_INT(gsr_path_init(&gp, &gc, &rc), CP_OK);
        to_ref(&gc, gc.frame, &rg);
        r.n = gp.head.n;
        r.steps = gp.head.steps;
        r.link = gp.head.link;
        cnt = gsr_path_count(&gp);
        CHECK_EQ_INT(cnt, r.n * (r.steps + 1u) + (r.n - 1u) * r.link);
        CHECK(cnt <= sizeof pts / sizeof pts[0]);
        for (k = 0; k < cnt; k++) {
            double u, th, P[3], nr[3];
            int line = rast_at(&r, k, &u, &th);
            CHECK_EQ_INT(gsr_path_next(&gp, &pts[k]), CP_OK);
            CHECK_EQ_INT(pts[k].line, line);
            ref_gsr_point(&rg, u, th, P);
            if (tool > 0.0) {
                ref_gsr_normal(&rg, u, th, nr);
                P[0] += tool * nr[0];
                P[1] += tool * nr[1];
                P[2] += tool * nr[2];
            }
            wp = fmax(wp, dist(&pts[k].p, P));
            if (k > 0u) { /* chord: the reference between the two points, 7 samples */
                double u0, t0, s0, s1, a[3], b[3], ab[3], L2;
                unsigned q;
                (void)rast_at(&r, k - 1u, &u0, &t0);
                s0 = sig_of(&r, t0);
                s1 = sig_of(&r, th);
                a[0] = (double)pts[k - 1u].p.x;
                a[1] = (double)pts[k - 1u].p.y;
                a[2] = (double)pts[k - 1u].p.z;
                b[0] = (double)pts[k].p.x;
                b[1] = (double)pts[k].p.y;
                b[2] = (double)pts[k].p.z;
                for (q = 0; q < 3u; q++) {
                    ab[q] = b[q] - a[q];
                }
                L2 = ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2];
                for (q = 1; q < 8u; q++) {
                    double f = q / 8.0, uu = u0 + f * (u - u0), ss = s0 + f * (s1 - s0), Q[3], x;
                    double tt = r.form == GSR_SECTION_TRIG ? ss : ref_gsr_theta(ss), d2 = 0.0;
                    unsigned c;
                    ref_gsr_point(&rg, uu, tt, Q);
                    if (tool > 0.0) {
                        ref_gsr_normal(&rg, uu, tt, nr);
                        for (c = 0; c < 3u; c++) {
                            Q[c] += tool * nr[c];
                        }
                    }
                    x = L2 > 0.0 ? ((Q[0] - a[0]) * ab[0] + (Q[1] - a[1]) * ab[1] +
                                    (Q[2] - a[2]) * ab[2]) / L2
                                 : 0.0;
                    x = x < 0.0 ? 0.0 : (x > 1.0 ? 1.0 : x);
                    for (c = 0; c < 3u; c++) {
                        double e = Q[c] - a[c] - x * ab[c];
                        d2 += e * e;
                    }
                    wc = fmax(wc, sqrt(d2));
                }
            }
        }
        CHECK_EQ_INT(gsr_path_next(&gp, &pts[cnt]), CP_ERR_DONE);
        /* seek: every k reproduces the stream bit for bit */
        for (k = 0; k < cnt; k += 1u + cnt / 400u) {
            struct raster_pt q;
            CHECK_EQ_INT(gsr_path_seek(&gp, k), CP_OK);
            CHECK_EQ_INT(gsr_path_next(&gp, &q), CP_OK);
            CHECK(memcmp(&q.p, &pts[k].p, sizeof q.p) == 0 && memcmp(&q.n, &pts[k].n, sizeof q.n) == 0);
            CHECK(q.line == pts[k].line && q.index == pts[k].index);
        }
        CHECK_EQ_INT(gsr_path_seek(&gp, cnt + 1u), CP_ERR_RANGE);
        TEST_NOTE("%s %s %s%s: n %u steps %u link %u count %u; vs reference %.3g mm, chord %.3g "
                  "mm (tol %.3g, %.0f%%)\n",
                  ex_g[ei].name, r.mode == RASTER_LINES ? "LINES" : "CIRCLES",
                  r.form == GSR_SECTION_TRIG ? "TRIG" : "RATIONAL", tool > 0.0 ? " +tool" : "",
                  r.n, r.steps, r.link, cnt, wp, wc, (double)rc.tol, 100.0 * wc / (double)rc.tol);
        CHECK(wp <= (CP_REAL_DOUBLE ? 1e-9 : 1e-3));
        CHECK(wc <= (double)rc.tol);
    }
    /* B3: a section that failed is not cached: a retried gsr_path_next at the same k
     * evaluates it again (the failure is forced by changing the cfg under the iterator) */
    {
        struct raster_pt q0, q1;
        cp_real keep = gc.r[0][0];
        CHECK_EQ_INT(gsr_path_seek(&gp, 1u), CP_OK);
        CHECK_EQ_INT(gsr_path_next(&gp, &q0), CP_OK);
        CHECK_EQ_INT(gsr_path_seek(&gp, 1u), CP_OK);
        gc.r[0][0] = CP_R(-100.0); /* f_N < 0 */
        CHECK_EQ_INT(gsr_path_next(&gp, &q1), CP_ERR_SECTION);
        gc.r[0][0] = keep;
        CHECK_EQ_INT(gsr_path_next(&gp, &q1), CP_OK);
        CHECK(memcmp(&q1.p, &q0.p, sizeof q0.p) == 0 && memcmp(&q1.n, &q0.n, sizeof q0.n) == 0);
    }
    return 0;
}

/* Acceptance 4: every C.3 rejection with its own code (and the basic argument errors). */
int test_gsr_rejects(void)
{
    struct rej {
        int code;
        int centre, frame;
        double c[3][7], r[3][7], ref[3];
    };
    static const struct rej rj[] = {
        /* |C'| = 0 at t = 0 (x = t^3) */
        {CP_ERR_DEGENERATE, 0, 2, {{0, 0, 0, 1, 0, 0, 0}, {0}, {0}},
         {{0.1, 0, 0, 0, 0, 0, 0}, {0.1, 0, 0, 0, 0, 0, 0}, {0, 1, 0, 0, 0, 0, 0}}, {0, 0, 1}},
        /* fixed B with y(t) = 0.1 t */
        {CP_ERR_OFF_PLANE, 0, 0, {{0, 8, 0, 0, 0, 0, 0}, {0, 0.1, 0, 0, 0, 0, 0}, {0, 0, 0, 0, 2, 0, PI_D}},
         {{0.5, 0, 0, 0, 0, 0, 0}, {0.5, 0, 0, 0, 0, 0, 0}, {0, 1, 0, 0, 0, 0, 0}}, {0, 0, 0}},
        /* Frenet on a straight line */
        {CP_ERR_FRENET, 0, 1, {{0, 1, 0, 0, 0, 0, 0}, {0, 2, 0, 0, 0, 0, 0}, {0}},
         {{0.1, 0, 0, 0, 0, 0, 0}, {0.1, 0, 0, 0, 0, 0, 0}, {0, 1, 0, 0, 0, 0, 0}}, {0, 0, 0}},
        /* Frenet through an inflection: y = (t - 1/2)^3 */
        {CP_ERR_FRENET, 0, 1, {{0, 1, 0, 0, 0, 0, 0}, {-0.125, 0.75, -1.5, 1, 0, 0, 0}, {0}},
         {{0.01, 0, 0, 0, 0, 0, 0}, {0.01, 0, 0, 0, 0, 0, 0}, {0, 1, 0, 0, 0, 0, 0}}, {0, 0, 0}},
        /* N0 parallel to T */
        {CP_ERR_FRAME_REF, 0, 2, {{0, 1, 0, 0, 0, 0, 0}, {0}, {0}},
         {{0.1, 0, 0, 0, 0, 0, 0}, {0.1, 0, 0, 0, 0, 0, 0}, {0, 1, 0, 0, 0, 0, 0}}, {2, 0, 0}},
        /* RMF with ref parallel to T(t0) */
        {CP_ERR_FRAME_REF, 0, 3, {{0, 1, 0, 0, 0, 0, 0}, {0, 0, 1, 0, 0, 0, 0}, {0}},
         {{0.1, 0, 0, 0, 0, 0, 0}, {0.1, 0, 0, 0, 0, 0, 0}, {0, 1, 0, 0, 0, 0, 0}}, {1, 0, 0}},
        /* f_N <= 0 at u = 0 */
        {CP_ERR_SECTION, 0, 2, {{0, 1, 0, 0, 0, 0, 0}, {0}, {0}},
         {{-0.1, 1, 0, 0, 0, 0, 0}, {0.1, 0, 0, 0, 0, 0, 0}, {0, 1, 0, 0, 0, 0, 0}}, {0, 0, 1}},
        /* f_B = 0 */
        {CP_ERR_SECTION, 0, 2, {{0, 1, 0, 0, 0, 0, 0}, {0}, {0}},
         {{0.1, 0, 0, 0, 0, 0, 0}, {0, 0, 0, 0, 0, 0, 0}, {0, 1, 0, 0, 0, 0, 0}}, {0, 0, 1}},
        /* f_t = 2 u leaves [0, 1] */
        {CP_ERR_FT_RANGE, 0, 2, {{0, 1, 0, 0, 0, 0, 0}, {0}, {0}},
         {{0.1, 0, 0, 0, 0, 0, 0}, {0.1, 0, 0, 0, 0, 0, 0}, {0, 2, 0, 0, 0, 0, 0}}, {0, 0, 1}},
        /* f_t = 1/2 + sin(4 pi u)/4: in [0, 1] but not increasing */
        {CP_ERR_FT_RANGE, 0, 2, {{0, 1, 0, 0, 0, 0, 0}, {0}, {0}},
         {{0.1, 0, 0, 0, 0, 0, 0}, {0.1, 0, 0, 0, 0, 0, 0}, {0.5, 0, 0, 0, 0.25, 0, 4 * PI_D}}, {0, 0, 1}},
        /* the sweep folds: section 1.5 on a circle of radius 1 */
        {CP_ERR_FOLD, 0, 0, {{0, 0, 0, 0, 0, 1, 2 * PI_D}, {0}, {0, 0, 0, 0, 1, 0, 2 * PI_D}},
         {{1.5, 0, 0, 0, 0, 0, 0}, {0.5, 0, 0, 0, 0, 0, 0}, {0, 1, 0, 0, 0, 0, 0}}, {0, 0, 0}},
        /* argument errors */
        {CP_ERR_RANGE, 0, 2, {{0, 1e5, 0, 0, 0, 0, 0}, {0}, {0}},
         {{0.1, 0, 0, 0, 0, 0, 0}, {0.1, 0, 0, 0, 0, 0, 0}, {0, 1, 0, 0, 0, 0, 0}}, {0, 0, 1}},
        {CP_ERR_RANGE, 0, 2, {{0, 1, 0, 0, 0, 0, 0}, {0}, {0}},
         {{0.1, 0, 0, 0, 0, 0, 0}, {0.1, 0, 0, 0, 0, 0, 0}, {0, 1, 0, 0, 0, 0, 0}}, {0, 0, 0}},
    };
    struct raster_cfg rc;
    unsigned i;
    for (i = 0; i < sizeof rj / sizeof rj[0]; i++) {
        struct ex e;
        memset(&e, 0, sizeof e);
        e.centre = rj[i].centre;
        e.frame = rj[i].frame;
        memcpy(e.c, rj[i].c, sizeof e.c);
        memcpy(e.r, rj[i].r, sizeof e.r);
        memcpy(e.ref, rj[i].ref, sizeof e.ref);
        to_cfg(&e, &gc);
        if (gsr_init(&gm, &gc) != rj[i].code) {
            printf("  reject case %u: got %d, want %d\n", i, gsr_init(&gm, &gc), rj[i].code);
            CHECK(0);
        }
    }
    to_cfg(&ex_g[0], &gc);
    gc.c[0][0] = (cp_real)NAN;
    CHECK_EQ_INT(gsr_init(&gm, &gc), CP_ERR_NONFINITE);
    to_cfg(&ex_g[0], &gc);
    gc.frame = 4u;
    CHECK_EQ_INT(gsr_init(&gm, &gc), CP_ERR_INVAL);
    /* the tool centre folds although the surface does not: section 0.5 on radius 1, tool 0.6 */
    {
        struct ex e;
        memset(&e, 0, sizeof e);
        memcpy(e.c, rj[10].c, sizeof e.c);
        memcpy(e.r, rj[10].r, sizeof e.r);
        e.r[0][0] = 0.5;
        to_cfg(&e, &gc);
        CHECK_EQ_INT(gsr_init(&gm, &gc), CP_OK);
        memset(&rc, 0, sizeof rc);
        rc.mode = RASTER_LINES;
        rc.n = 8u;
        rc.u0 = -CP_PI;
        rc.u1 = CP_R(0.75) * CP_PI;
        rc.steps = 16u;
        rc.link = 2u;
        rc.output = RASTER_OUT_CENTRE;
        rc.tool_r = CP_R(0.6);
        CHECK_EQ_INT(gsr_path_init(&gp, &gc, &rc), CP_ERR_FOLD);
        CHECK_EQ_INT(gsr_path_count(&gp), 0);
        rc.tool_r = CP_R(0.3);
        CHECK_EQ_INT(gsr_path_init(&gp, &gc, &rc), CP_OK);
        rc.tool_r = CP_R(-0.3);
        CHECK_EQ_INT(gsr_path_init(&gp, &gc, &rc), CP_ERR_TOOL);
        rc.tool_r = CP_R(0.3);
        rc.u1 = CP_R(4.0);
        CHECK_EQ_INT(gsr_path_init(&gp, &gc, &rc), CP_ERR_RANGE);
        rc.u1 = CP_R(1.0);
        rc.n = CP_MAX_LINES + 1u;
        CHECK_EQ_INT(gsr_path_init(&gp, &gc, &rc), CP_ERR_TOO_MANY);
        rc.n = 2u;
        rc.steps = 0u;
        rc.tol = CP_R(1e-5);
        rc.link = RASTER_LINK_AUTO;
        CHECK_EQ_INT(gsr_path_init(&gp, &gc, &rc), CP_ERR_TOL);
    }
    return 0;
}

/* Acceptance 3: an RMF tube (constant circular section on the helix of G2). Measured on
 * the streamed points only (finite differences on the (line, index) grid, no firmware
 * formula): the longitudinal lines are orthogonal to the rings (F = G_u.G_theta = 0) and
 * are curvature lines: the second fundamental form is diagonal too (M = G_u theta . n = 0),
 * i.e. the principal directions are along the lines (angle alpha = 1/2 atan2(2 M',
 * L/E - N/G), M' = M / sqrt(E G)). The same tube in the Frenet frame is the control: its
 * lines twist around the tube and alpha is degrees there, so the measure can fail. */
#define TUBE_L 24u
#define TUBE_S 400u
static double tube[TUBE_L][TUBE_S + 1u][3];

static int tube_run(int frame, double *ortho, double *alpha, double *nrm)
{
    static const struct ex helix = {
        "tube", 0, 3,
        {{0, 0, 0, 0, 0, 3, 2 * PI_D}, {0, 0, 0, 0, 3, 0, 2 * PI_D}, {0, 4, 0, 0, 0, 0, 0}},
        {{0.5, 0, 0, 0, 0, 0, 0}, {0.5, 0, 0, 0, 0, 0, 0}, {0, 1, 0, 0, 0, 0, 0}},
        {0, 0, 1}};
    struct ex e = helix;
    struct raster_cfg rc;
    struct raster_pt pt;
    double hu = 1.0 / TUBE_S, ht = 2.0 * PI_D / TUBE_L, wo = 0.0, wa = 0.0, wn = 0.0;
    unsigned k, j, i, c;
    e.frame = frame;
    to_cfg(&e, &gc);
    gc.section = GSR_SECTION_TRIG;
    memset(&rc, 0, sizeof rc);
    rc.mode = RASTER_LINES;
    rc.n = TUBE_L;
    rc.u0 = -CP_PI;
    rc.u1 = (cp_real)(PI_D - ht);
    rc.steps = TUBE_S;
    rc.link = 0u;
    CHECK_EQ_INT(gsr_path_init(&gp, &gc, &rc), CP_OK);
    for (k = 0; k < gsr_path_count(&gp); k++) {
        CHECK_EQ_INT(gsr_path_next(&gp, &pt), CP_OK);
        tube[pt.line][pt.index][0] = (double)pt.p.x;
        tube[pt.line][pt.index][1] = (double)pt.p.y;
        tube[pt.line][pt.index][2] = (double)pt.p.z;
        if (pt.index > 0u && pt.index < TUBE_S) { /* normal vs the finite-difference one below */
            continue;
        }
    }
    for (j = 0; j < TUBE_L; j++) {
        unsigned jp = (j + 1u) % TUBE_L, jm = (j + TUBE_L - 1u) % TUBE_L;
        for (i = 1; i < TUBE_S; i++) {
            double gu[3], gt[3], guu[3], gtt[3], gut[3], n[3], E, F, G, L, M, N, l, a;
            for (c = 0; c < 3u; c++) {
                gu[c] = (tube[j][i + 1u][c] - tube[j][i - 1u][c]) / (2.0 * hu);
                gt[c] = (tube[jp][i][c] - tube[jm][i][c]) / (2.0 * ht);
                guu[c] = (tube[j][i + 1u][c] - 2.0 * tube[j][i][c] + tube[j][i - 1u][c]) / (hu * hu);
                gtt[c] = (tube[jp][i][c] - 2.0 * tube[j][i][c] + tube[jm][i][c]) / (ht * ht);
                gut[c] = (tube[jp][i + 1u][c] - tube[jp][i - 1u][c] - tube[jm][i + 1u][c] +
                          tube[jm][i - 1u][c]) / (4.0 * hu * ht);
            }
            n[0] = gt[1] * gu[2] - gt[2] * gu[1];
            n[1] = gt[2] * gu[0] - gt[0] * gu[2];
            n[2] = gt[0] * gu[1] - gt[1] * gu[0];
            l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            E = gu[0] * gu[0] + gu[1] * gu[1] + gu[2] * gu[2];
            F = gu[0] * gt[0] + gu[1] * gt[1] + gu[2] * gt[2];
            G = gt[0] * gt[0] + gt[1] * gt[1] + gt[2] * gt[2];
            L = (guu[0] * n[0] + guu[1] * n[1] + guu[2] * n[2]) / l;
            M = (gut[0] * n[0] + gut[1] * n[1] + gut[2] * n[2]) / l;
            N = (gtt[0] * n[0] + gtt[1] * n[1] + gtt[2] * n[2]) / l;
            wo = fmax(wo, fabs(asin(F / sqrt(E * G))) * 180.0 / PI_D);
            a = 0.5 * atan2(2.0 * M / sqrt(E * G), L / E - N / G) * 180.0 / PI_D;
            a = fabs(a) > 45.0 ? 90.0 - fabs(a) : fabs(a);
            wa = fmax(wa, a);
            if (i == TUBE_S / 2u) { /* the streamed normal against the grid's own */
                CHECK_EQ_INT(gsr_path_seek(&gp, j * (TUBE_S + 1u) + ((j & 1u) ? TUBE_S - i : i)),
                             CP_OK);
                CHECK_EQ_INT(gsr_path_next(&gp, &pt), CP_OK);
                wn = fmax(wn, fabs(1.0 - vdotd(&pt.n, n) / l));
            }
        }
    }
    *ortho = wo;
    *alpha = wa;
    *nrm = wn;
    return 0;
}

int test_gsr_rmf_tube(void)
{
    double o, a, n, fo, fa, fn;
    int r = tube_run(GSR_FRAME_RMF, &o, &a, &n);
    if (r != 0) {
        return r;
    }
    r = tube_run(GSR_FRAME_FRENET, &fo, &fa, &fn);
    if (r != 0) {
        return r;
    }
    TEST_NOTE("RMF tube (%s): lines vs rings max %.2e deg off 90, principal directions max "
              "%.2e deg off the lines, streamed normal 1 - cos %.1e; Frenet control: %.2f deg, "
              "%.2f deg\n",
              CP_REAL_NAME, o, a, n, fo, fa);
    CHECK(o <= 0.01);
    CHECK(a <= 0.01);
    CHECK(n <= 1e-6);
    CHECK(fa > 1.0); /* the measure sees a frame whose lines are not curvature lines */
    return 0;
}

/* The protocol commands: argument errors, the have bits, and a job streamed through
 * struct path equals the iterator on the same geometry. */
int test_gsr_job(void)
{
    static const struct {
        const char *line;
        int st;
    } cmds[] = {
        {"CENTER X 0 8 0 0 0 0 0", CP_ST_WRONG_SURFACE},
        {"SURFACE GSR", CP_ST_OK},
        {"CENTER X 0 8 0 0", CP_ST_BAD_ARITY},
        {"CENTER Q 0 8 0 0 0 0 0", CP_ST_BAD_KEYWORD},
        {"CENTER X 0 8 zz 0 0 0 0", CP_ST_BAD_NUMBER},
        {"CENTER X 0 8 nan 0 0 0 0", CP_ST_NONFINITE},
        {"CENTER X 0 2e4 0 0 0 0 0", CP_ST_OUT_OF_RANGE},
        {"CENTER X 0 8 0 0 0 0 0", CP_ST_OK},
        {"CENTER Z 0 0 0 0 2 0 180", CP_ST_OK},
        {"RADII N 1.2 0 0 0 0.5 0 180", CP_ST_OK},
        {"RADII N 1.2 0 0 0 0.5 0 30000", CP_ST_OUT_OF_RANGE},
        {"FRAME N0 0 0 0", CP_ST_OUT_OF_RANGE},
        {"FRAME SIDEWAYS", CP_ST_BAD_KEYWORD},
        {"FRAME FIXED 1", CP_ST_BAD_ARITY},
        {"FORM ODD", CP_ST_BAD_KEYWORD},
        {"FORM TRIG", CP_ST_OK},
        {"LINES 5 -90 90", CP_ST_OK},
        {"TOL 4", CP_ST_OK},
        {"FRAME FIXED", CP_ST_OK},
        {"RADII B 0.8 0.3 0 0 0 0 0", CP_ST_OK},
    };
    static struct job j;
    static struct path p;
    struct raster_pt a, b;
    struct raster_cfg rc;
    unsigned i;
    job_init(&j);
    for (i = 0; i < sizeof cmds / sizeof cmds[0]; i++) {
        int st = job_command(&j, cmds[i].line, strlen(cmds[i].line));
        if (st != cmds[i].st) {
            printf("  '%s': %d, want %d\n", cmds[i].line, st, cmds[i].st);
            CHECK(0);
        }
        CHECK_EQ_INT(job_ready(&j), i + 1u == sizeof cmds / sizeof cmds[0] ? CP_ST_OK : CP_ST_NO_JOB);
    }
    CHECK_EQ_INT(path_init(&p, j.kind, &j.cfg, &j.geom), CP_OK);
    to_cfg(&ex_g[0], &gc);
    gc.section = GSR_SECTION_TRIG;
    memset(&rc, 0, sizeof rc);
    rc.mode = RASTER_LINES;
    rc.n = 5u;
    rc.u0 = CP_R(-90.0) * CP_DEG2RAD;
    rc.u1 = CP_R(90.0) * CP_DEG2RAD;
    rc.tol = CP_R(0.004);
    rc.link = RASTER_LINK_AUTO;
    CHECK_EQ_INT(gsr_path_init(&gp, &gc, &rc), CP_OK);
    CHECK_EQ_INT(path_count(&p), gsr_path_count(&gp));
    for (i = 0; i < path_count(&p); i++) {
        CHECK_EQ_INT(path_next(&p, &a), CP_OK);
        CHECK_EQ_INT(gsr_path_next(&gp, &b), CP_OK);
        /* w = 180 deg * CP_DEG2RAD may differ from pi in the last bit: 1e-5 mm */
        CHECK(fabs((double)(a.p.x - b.p.x)) + fabs((double)(a.p.z - b.p.z)) <= 1e-5);
    }
    /* Bezier centre from four points; RMF; the have bit only with all four */
    CHECK_EQ_INT(job_command(&j, "CENTER P0 0 0 0", 15u), CP_ST_OK);
    CHECK_EQ_INT(job_ready(&j), CP_ST_NO_JOB);
    CHECK_EQ_INT(job_command(&j, "CENTER P1 3 0 1", 15u), CP_ST_OK);
    CHECK_EQ_INT(job_command(&j, "CENTER P2 6 2 1", 15u), CP_ST_OK);
    CHECK_EQ_INT(job_command(&j, "CENTER P3 9 2 0", 15u), CP_ST_OK);
    CHECK_EQ_INT(job_command(&j, "FRAME RMF 0 0 1", 15u), CP_ST_OK);
    CHECK_EQ_INT(job_ready(&j), CP_ST_OK);
    CHECK_EQ_INT(path_init(&p, j.kind, &j.cfg, &j.geom), CP_OK);
    to_ref(&j.geom.gsr, GSR_FRAME_RMF, &rg);
    {
        double w = 0.0;
        for (i = 0; i < path_count(&p); i++) {
            double u, th, P[3];
            struct rast r;
            r.mode = RASTER_LINES;
            r.form = GSR_SECTION_TRIG;
            r.n = p.info.n;
            r.steps = p.info.steps;
            r.link = p.info.link;
            r.v0 = (double)j.cfg.u0;
            r.v1 = (double)j.cfg.u1;
            (void)rast_at(&r, i, &u, &th);
            CHECK_EQ_INT(path_next(&p, &a), CP_OK);
            ref_gsr_point(&rg, u, th, P);
            w = fmax(w, dist(&a.p, P));
        }
        TEST_NOTE("job: Bezier centre + RMF through the protocol, %u points, vs reference %.3g mm\n",
                  (unsigned)path_count(&p), w);
        CHECK(w <= (CP_REAL_DOUBLE ? 2e-4 : 1e-3)); /* RMF table: GSR_RMF_TOL */
    }
    return 0;
}

/* ---- even arc length on a section (gsr_arclen_*, C.2 "Speed") ---- */

#ifdef __arm__ /* the M4F runs the float build with soft doubles: a lighter reference */
#define ARC_M 16
#define ARC_REF_TOL 1e-11
#else
#define ARC_M 40
#define ARC_REF_TOL 1e-15
#endif
#if CP_REAL_DOUBLE
#define ARC_TOL 1e-9 /* x perimeter */
#else
#define ARC_TOL 4e-6
#endif

/* Chord ratio max/min of the polyline through n points (a cos th_j, b sin th_j). */
static double chord_ratio(double a, double b, const double *th, unsigned n)
{
    double lo = 1e300, hi = 0.0;
    unsigned j;
    for (j = 1; j < n; j++) {
        double dx = a * (cos(th[j]) - cos(th[j - 1u])), dy = b * (sin(th[j]) - sin(th[j - 1u]));
        double c = sqrt(dx * dx + dy * dy);
        lo = c < lo ? c : lo;
        hi = c > hi ? c : hi;
    }
    return hi / lo;
}

/* Worst |s(theta(f)) - f P| / P over f = j / ARC_M (and the round trip of gsr_arclen_frac)
 * of one section, against adaptive Simpson and the AGM perimeter. */
static int arc_case(double a, double b, double *err, double *rt)
{
    struct gsr_arclen t;
    double pr = ref_gsr_perimeter(a, b), s = 0.0, thp = 0.0;
    int j;
    CHECK_EQ_INT(gsr_arclen_init(&t, (cp_real)a, (cp_real)b), CP_OK);
    CHECK_NEAR(4.0 * (double)t.lq, pr, 0.0, ARC_TOL);
    *err = fabs(4.0 * (double)t.lq - pr) / pr;
    *rt = 0.0;
    for (j = 0; j <= ARC_M; j++) {
        double f = (double)j / ARC_M, th = (double)gsr_arclen_angle(&t, (cp_real)f), e, fr;
        CHECK(th >= thp);                                              /* monotone */
        CHECK(gsr_arclen_angle(&t, (cp_real)-f) == (cp_real)-th);      /* odd, bit for bit */
        s += ref_gsr_arc(a, b, thp, th, ARC_REF_TOL * pr);
        e = fabs(s - f * pr) / pr;
        *err = e > *err ? e : *err;
        fr = (double)gsr_arclen_frac(&t, (cp_real)th);
        e = fabs(fr - s / pr);
        *rt = e > *rt ? e : *rt;
        CHECK_NEAR(s, f * pr, ARC_TOL * pr, 0.0);
        CHECK_NEAR(fr, s / pr, ARC_TOL, 0.0);
        thp = th;
    }
    CHECK_NEAR(thp, 2.0 * PI_D, 4.0 * CP_REAL_EPS, 0.0);
    return 0;
}

int test_gsr_arclen(void)
{
    static const double ab[][2] = {{1.7, 0.95}, {0.95, 1.7}, {1.0, 1.0}, {4.0, 1.0}, {1.0, 16.0}};
    struct gsr_arclen t;
    double th[17], err, rt, worst = 0.0, r;
    unsigned i, j;
    int rc;
    /* rejections */
    CHECK_EQ_INT(gsr_arclen_init(NULL, CP_R(1.0), CP_R(1.0)), CP_ERR_INVAL);
    CHECK_EQ_INT(gsr_arclen_init(&t, (cp_real)NAN, CP_R(1.0)), CP_ERR_NONFINITE);
    CHECK_EQ_INT(gsr_arclen_init(&t, CP_R(1.0), (cp_real)INFINITY), CP_ERR_NONFINITE);
    CHECK_EQ_INT(gsr_arclen_init(&t, CP_R(0.0), CP_R(1.0)), CP_ERR_SECTION);
    CHECK_EQ_INT(gsr_arclen_init(&t, CP_R(1.0), CP_R(-1.0)), CP_ERR_SECTION);
    CHECK_EQ_INT(gsr_arclen_init(&t, CP_R(2.0e4), CP_R(2.0e4)), CP_ERR_RANGE);
    CHECK_EQ_INT(gsr_arclen_init(&t, CP_R(1.0), CP_R(16.5)), CP_ERR_RANGE);
    CHECK_EQ_INT(gsr_arclen_init(&t, CP_R(16.0), CP_R(1.0)), CP_OK);
    CHECK(sizeof t <= (CP_REAL_DOUBLE ? 600u : 300u));
    /* accuracy against the independent double reference */
    for (i = 0; i < sizeof ab / sizeof ab[0]; i++) {
        rc = arc_case(ab[i][0], ab[i][1], &err, &rt);
        if (rc != 0) {
            printf("  section %g x %g\n", ab[i][0], ab[i][1]);
            return rc;
        }
        TEST_NOTE("arclen %g x %g: |s(theta(f)) - f P| / P <= %.2g, frac round trip %.2g\n",
                  ab[i][0], ab[i][1], err, rt);
        worst = err > worst ? err : worst;
    }
    /* the clamps, NaN, quarter angles */
    CHECK_EQ_INT(gsr_arclen_init(&t, CP_R(1.7), CP_R(0.95)), CP_OK);
    CHECK(gsr_arclen_angle(&t, CP_R(2.0)) == gsr_arclen_angle(&t, CP_R(1.0)));
    CHECK(gsr_arclen_angle(&t, CP_R(-3.0)) == gsr_arclen_angle(&t, CP_R(-1.0)));
    CHECK(gsr_arclen_angle(&t, (cp_real)NAN) != gsr_arclen_angle(&t, (cp_real)NAN));
    CHECK(gsr_arclen_frac(&t, (cp_real)NAN) != gsr_arclen_frac(&t, (cp_real)NAN));
    CHECK(gsr_arclen_frac(&t, CP_R(9.0)) == gsr_arclen_frac(&t, CP_R(2.0) * CP_PI));
    for (j = 0; j <= 4u; j++) {
        CHECK_NEAR(gsr_arclen_angle(&t, (cp_real)j / CP_R(4.0)), j * PI_D / 2.0,
                   8.0 * CP_REAL_EPS, 0.0);
    }
    /* C.2: 16 steps on the quarter of the G1 section 1.7 x 0.95 */
    for (j = 0; j <= 16u; j++) {
        th[j] = j * PI_D / 32.0;
    }
    r = chord_ratio(1.7, 0.95, th, 17u);
    TEST_NOTE("quarter 1.7 x 0.95, 16 steps, chord max/min: trig uniform %.4f\n", r);
    CHECK_NEAR(r, 1.783, 1e-3, 0.0);
    for (j = 0; j <= 16u; j++) {
        cp_real cx, cy;
        gsr_unit_rational((cp_real)j / CP_R(16.0), &cx, &cy);
        th[j] = atan2((double)cy, (double)cx); /* eccentric angle of the unit-circle point */
    }
    r = chord_ratio(1.7, 0.95, th, 17u);
    TEST_NOTE("  rational uniform %.4f\n", r);
    CHECK_NEAR(r, 1.878, 1e-3, 0.0);
    for (j = 0; j <= 16u; j++) {
        th[j] = (double)gsr_arclen_angle(&t, (cp_real)j / CP_R(64.0));
    }
    r = chord_ratio(1.7, 0.95, th, 17u);
    TEST_NOTE("  arc-length table %.6f (16 equal arcs; the rest is chord vs arc)\n", r);
    CHECK(r < 1.003);
    for (j = 0; j <= 16u; j++) {
        th[j] = (double)gsr_arclen_angle(&t, (cp_real)j / CP_R(16.0));
    }
    TEST_NOTE("  full ellipse, 16 equal arcs: chord max/min %.6f\n", chord_ratio(1.7, 0.95, th, 17u));
    TEST_NOTE("arclen worst %.2g of the perimeter (%s)\n", worst, CP_REAL_NAME);
    return 0;
}
