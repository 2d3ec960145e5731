/* test_channel.c - channel surface (seed 002): B.3 table, Beta constants, surface against
 * the independent reference (ref_channel.c), node sections, area law, every B.4 rejection,
 * the iterator (count, zigzag, links, seek, chord tolerance) and the protocol commands.
 * SPDX-License-Identifier: MIT
 */
#include <string.h>

#include "channel.h"
#include "job.h"
#include "ref_channel.h"
#include "test.h"

#define PI_D 3.14159265358979323846

#if CP_REAL_DOUBLE
#define TOL_REL 1e-12 /* B.3 against the reference */
#else
#define TOL_REL 5e-6 /* float: the Beta constants carry ~2e-6 (lgam() in channel.c) */
#endif
/* against the published table (6-9 significant digits) */
#define TOL_PRINT (TOL_REL > 1e-6 ? TOL_REL : 1e-6)

/* The example of B.3: Table 1 (a, b, n), Table 2 (theta, phi, psi, offsets). */
static const double ex_abn[3][3] = {{5, 3.5, 2}, {4, 3, 3}, {3.5, 2.5, 6}};
static const double ex_ang[3][3] = {
    {PI_D / 17, PI_D / 6, 4 * PI_D / 3}, {PI_D / 8, PI_D / 12, 5 * PI_D / 4}, {PI_D / 7, PI_D / 18, 7 * PI_D / 6}};
static const double ex_c[3][3] = {{3, 4.5, 1}, {6, 3.5, 7}, {7, 1, 14}};

static void example(struct channel_cfg *g, struct ref_channel *r, int printed)
{
    struct ref_ch_sec rs[3];
    int i, k;
    g->count = 3;
    for (i = 0; i < 3; i++) {
        struct channel_section *s = &g->s[i];
        s->a = (cp_real)ex_abn[i][0];
        s->b = (cp_real)ex_abn[i][1];
        s->n = (cp_real)ex_abn[i][2];
        s->c.x = (cp_real)ex_c[i][0];
        s->c.y = (cp_real)ex_c[i][1];
        s->c.z = (cp_real)ex_c[i][2];
        channel_euler(s, (cp_real)ex_ang[i][2], (cp_real)ex_ang[i][0], (cp_real)ex_ang[i][1],
                      printed ? CHANNEL_ORDER_PRINTED : CHANNEL_ORDER_SPIN_FIRST);
        if (r != NULL) {
            rs[i].a = ex_abn[i][0];
            rs[i].b = ex_abn[i][1];
            rs[i].n = ex_abn[i][2];
            for (k = 0; k < 3; k++) {
                rs[i].c[k] = ex_c[i][k];
            }
            ref_channel_euler(ex_ang[i][2], ex_ang[i][0], ex_ang[i][1], printed, rs[i].x, rs[i].z);
        }
    }
    if (r != NULL) {
        (void)ref_channel_build(r, 3, rs);
    }
}

static double dist3(const struct cp_vec3 *p, const double *q)
{
    double dx = (double)p->x - q[0], dy = (double)p->y - q[1], dz = (double)p->z - q[2];
    return sqrt(dx * dx + dy * dy + dz * dz);
}

static struct ref_channel ref; /* static: kept off the (M4F) stack */

int test_channel_b3_table(void)
{
    /* B.3 as published (6-7 digits) */
    static const double nrm[3][3] = {
        {0.491487, -0.183750, 0.851280}, {0.239118, -0.382683, 0.892399}, {0.156452, -0.433884, 0.887281}};
    static const double xax[3][3] = {{-0.512579, -0.851280, 0.112188},
                                     {-0.753049, -0.653281, -0.078365},
                                     {-0.890540, -0.450484, -0.063262}};
    static const double kk[3] = {6.782330, 7.141165, 7.5};
    static const double acc[3][3] = {
        {1.251147, 4.450611, 0.159823}, {-3.839963, -2.492122, 2.119051}, {2.108705, -3.482123, -2.636028}};
    static const double ss[3] = {54.9778714, 42.3993300, 33.7333727};
    static const double ji[3] = {299.801205, 150, 82.346436}, jii[3] = {212.180223, 150, 114.222476},
                        j12[3] = {75.881997, 42, 27.605460}, al[3] = {-120, -135, -150};
    struct channel_cfg g;
    struct channel ch;
    int i;
    example(&g, &ref, 0);
    CHECK_EQ_INT(channel_init(&ch, &g), CP_OK);
    for (i = 0; i < 3; i++) {
        CHECK_NEAR(g.s[i].z.x, nrm[i][0], 1e-6, 0);
        CHECK_NEAR(g.s[i].z.y, nrm[i][1], 1e-6, 0);
        CHECK_NEAR(g.s[i].z.z, nrm[i][2], 1e-6, 0);
        CHECK_NEAR(g.s[i].x.x, xax[i][0], 1e-6, 0);
        CHECK_NEAR(g.s[i].x.y, xax[i][1], 1e-6, 0);
        CHECK_NEAR(g.s[i].x.z, xax[i][2], 1e-6, 0);
        CHECK_NEAR(ch.d[i], kk[i], 1e-6, 0);
        CHECK_NEAR(ch.acc[i][0], acc[i][0], 1e-6, TOL_PRINT);
        CHECK_NEAR(ch.acc[i][1], acc[i][1], 1e-6, TOL_PRINT);
        CHECK_NEAR(ch.acc[i][2], acc[i][2], 1e-6, TOL_PRINT);
        CHECK_NEAR(ch.y[0][i], ss[i], 1e-7, TOL_PRINT);
        CHECK_NEAR(ch.y[2][i], ji[i], 1e-6, TOL_PRINT);
        CHECK_NEAR(ch.y[3][i], jii[i], 1e-6, TOL_PRINT);
        CHECK_NEAR(ch.y[4][i], j12[i], 1e-6, TOL_PRINT);
        CHECK_NEAR(ch.al[i] * (180.0 / PI_D), al[i], 1e-4, 0);
        /* against the independent reference */
        CHECK_NEAR(g.s[i].z.x, ref.s[i].z[0], TOL_REL, 0);
        CHECK_NEAR(g.s[i].x.y, ref.s[i].x[1], TOL_REL, 0);
        CHECK_NEAR(ch.d[i] * g.s[i].z.x, ref.m[i][0], 0, TOL_REL);
        CHECK_NEAR(ch.d[i] * g.s[i].z.z, ref.m[i][2], 0, TOL_REL);
        CHECK_NEAR(ch.acc[i][0], ref.acc[i][0], TOL_REL * 10.0, TOL_REL);
        CHECK_NEAR(ch.acc[i][1], ref.acc[i][1], TOL_REL * 10.0, TOL_REL);
        CHECK_NEAR(ch.acc[i][2], ref.acc[i][2], TOL_REL * 10.0, TOL_REL);
        CHECK_NEAR(ch.y[0][i], ref.y[0][i], 0, TOL_REL);
        CHECK_NEAR(ch.y[2][i], ref.y[2][i], 0, TOL_REL);
        CHECK_NEAR(ch.y[3][i], ref.y[3][i], 0, TOL_REL);
        CHECK_NEAR(ch.y[4][i], ref.y[4][i], 0, TOL_REL);
        CHECK_NEAR(ch.al[i], ref.al[i], TOL_REL, 0);
    }
    /* J_x, J_y of the table: 168.369731, 343.611696 / 108, 192 / 66.4084162, 130.160496 */
    CHECK_NEAR(channel_kj(CP_R(2.0)) * 5.0 * 3.5 * 3.5 * 3.5, 168.369731, 1e-6, 1e-6);
    CHECK_NEAR(channel_kj(CP_R(3.0)) * 64.0 * 3.0, 192.0, 0, 3.0 * TOL_REL);
    CHECK_NEAR(channel_kj(CP_R(6.0)) * 3.5 * 2.5 * 2.5 * 2.5, 66.4084162, 1e-6, 1e-6);
    return 0;
}

int test_channel_beta(void)
{
    static const double ns[8] = {1.0, 1.5, 2.0, 2.5, 3.0, 6.0, 17.0, 100.0};
    int i;
#if CP_REAL_DOUBLE
    CHECK_NEAR(channel_ks(2.0), PI_D, 0, 1e-14);
    CHECK_NEAR(channel_kj(2.0), PI_D / 4.0, 0, 1e-14);
    CHECK_NEAR(channel_ks(1.0), 2.0, 0, 1e-14); /* rhombus: 2ab */
    CHECK_NEAR(channel_kj(1.0), 1.0 / 3.0, 0, 1e-14); /* J_x of the unit rhombus: 1/3 */
#else
    CHECK_NEAR(channel_ks(CP_R(2.0)), PI_D, 0, 2e-6);
    CHECK_NEAR(channel_kj(CP_R(2.0)), PI_D / 4.0, 0, 2e-6);
#endif
    for (i = 0; i < 8; i++) {
        CHECK_NEAR(channel_ks((cp_real)ns[i]), ref_channel_ks(ns[i]), 0, TOL_REL);
        CHECK_NEAR(channel_kj((cp_real)ns[i]), ref_channel_kj(ns[i]), 0, TOL_REL);
    }
    return 0;
}

int test_channel_surface_ref(void)
{
    struct channel_cfg g;
    struct channel ch;
    struct channel_row r;
    struct cp_vec3 p, nm;
    cp_real gg;
    double emax = 0.0, nmax = 0.0, gmin = 1e30, dd = 20.0; /* D: extent of the example, mm */
    int i, k, j;
    example(&g, &ref, 0);
    CHECK_EQ_INT(channel_init(&ch, &g), CP_OK);
    for (i = 0; i <= 8; i++) { /* u = 0, 0.25, ..., 2 */
        struct ref_ch_row o;
        double u = 0.25 * i;
        channel_row(&ch, (cp_real)u, &r);
        ref_channel_row(&ref, u, &o);
        CHECK_EQ_INT(r.flags, 0);
        CHECK_NEAR(r.ab[0], o.a, 1e-9 * dd, TOL_REL);
        CHECK_NEAR(r.ab[1], o.b, 1e-9 * dd, TOL_REL);
        CHECK_NEAR(r.alpha, o.alpha, 10.0 * TOL_REL, 0);
        CHECK_NEAR(r.s, o.s, 0, TOL_REL);
        CHECK_NEAR(r.n, o.n, 0, TOL_REL);
        {
            const cp_real e1[3] = {r.e1.x, r.e1.y, r.e1.z}, e2[3] = {r.e2.x, r.e2.y, r.e2.z};
            for (j = 0; j < 3; j++) {
                CHECK_NEAR(e1[j], o.e1[j], 10.0 * TOL_REL, 0);
                CHECK_NEAR(e2[j], o.e2[j], 10.0 * TOL_REL, 0);
            }
        }
        for (k = 0; k < 8; k++) { /* w = k pi/4 */
            double pr[3], nr[3], gr, e, en;
            channel_point(&r, (cp_real)(k * PI_D / 4.0 - PI_D), &p, &nm, &gg);
            ref_channel_point(&ref, u, k * PI_D / 4.0 - PI_D, pr);
            ref_channel_normal(&ref, u, k * PI_D / 4.0 - PI_D, nr, &gr);
            e = dist3(&p, pr);
            en = sqrt((nm.x - nr[0]) * (nm.x - nr[0]) + (nm.y - nr[1]) * (nm.y - nr[1]) +
                      (nm.z - nr[2]) * (nm.z - nr[2]));
            emax = e > emax ? e : emax;
            nmax = en > nmax ? en : nmax;
            gmin = gg < gmin ? gg : gmin;
            CHECK_NEAR(gg, gr, 1e-5, 1e-5);
        }
    }
    TEST_NOTE("channel surface vs reference: %.3g mm, normal %.3g, min g %.3f\n", emax, nmax, gmin);
#if CP_REAL_DOUBLE
    CHECK(emax <= 1e-9 * dd);
    CHECK(nmax <= 1e-6);
#else
    CHECK(emax <= 1e-3); /* 1 um for this 20 mm part */
    CHECK(nmax <= 1e-4);
#endif
    CHECK(gmin > 0.3); /* B.3: sweep regularity min 0.374 over the surface */
    return 0;
}

/* node sections reproduced (as point sets) and the area law */
int test_channel_nodes_area(void)
{
    static const double us[4] = {0.37, 1.0, 1.5, 1.93};
    struct channel_cfg g;
    struct channel ch;
    struct channel_row r;
    struct cp_vec3 p, nm;
    cp_real gg;
    double emax = 0.0, amax = 0.0;
    int i, k;
    example(&g, NULL, 0);
    CHECK_EQ_INT(channel_init(&ch, &g), CP_OK);
    for (i = 0; i < 3; i++) {
        const struct channel_section *s = &g.s[i];
        double ya[3];
        ya[0] = (double)s->z.y * s->x.z - (double)s->z.z * s->x.y;
        ya[1] = (double)s->z.z * s->x.x - (double)s->z.x * s->x.z;
        ya[2] = (double)s->z.x * s->x.y - (double)s->z.y * s->x.x;
        channel_row(&ch, (cp_real)i, &r);
        for (k = 0; k < 64; k++) {
            double q[3], x, y, z, rho, e;
            channel_point(&r, (cp_real)(2.0 * PI_D * k / 64.0 - PI_D), &p, &nm, &gg);
            q[0] = (double)p.x - s->c.x;
            q[1] = (double)p.y - s->c.y;
            q[2] = (double)p.z - s->c.z;
            x = q[0] * s->x.x + q[1] * s->x.y + q[2] * s->x.z;
            y = q[0] * ya[0] + q[1] * ya[1] + q[2] * ya[2];
            z = q[0] * s->z.x + q[1] * s->z.y + q[2] * s->z.z;
            rho = pow(pow(fabs(x / s->a), s->n) + pow(fabs(y / s->b), s->n), 1.0 / s->n);
            e = fabs(rho - 1.0) * s->a + fabs(z);
            emax = e > emax ? e : emax;
        }
    }
    TEST_NOTE("channel node sections reproduced to %.3g mm\n", emax);
#if CP_REAL_DOUBLE
    CHECK(emax <= 1e-12 * 20.0);
#else
    CHECK(emax <= 2e-5 * 20.0);
#endif
    for (i = 0; i < 4; i++) { /* area of a 4000-gon section = S(u) */
        double area = 0.0, x0 = 0.0, y0 = 0.0, rel;
        channel_row(&ch, (cp_real)us[i], &r);
        for (k = 0; k <= 4000; k++) {
            double x, y, q[3];
            channel_point(&r, (cp_real)(2.0 * PI_D * (k % 4000) / 4000.0 - PI_D), &p, &nm, &gg);
            q[0] = (double)p.x - r.l.x;
            q[1] = (double)p.y - r.l.y;
            q[2] = (double)p.z - r.l.z;
            x = q[0] * r.e1.x + q[1] * r.e1.y + q[2] * r.e1.z;
            y = q[0] * r.e2.x + q[1] * r.e2.y + q[2] * r.e2.z;
            if (k > 0) {
                area += x0 * y - x * y0;
            }
            x0 = x;
            y0 = y;
        }
        rel = fabs(0.5 * fabs(area) - (double)r.s) / (double)r.s;
        amax = rel > amax ? rel : amax;
    }
    TEST_NOTE("channel area law: |area(4000-gon) - S(u)|/S <= %.3g\n", amax);
#if CP_REAL_DOUBLE
    CHECK(amax <= 1e-6);
#else
    CHECK(amax <= 2e-5);
#endif
    return 0;
}

/* a straight duct along x: sections at x = 0, 10, 20 (normals +x unless changed) */
static void duct(struct channel_cfg *g)
{
    int i;
    memset(g, 0, sizeof *g);
    g->count = 3;
    for (i = 0; i < 3; i++) {
        g->s[i].a = CP_R(3.0);
        g->s[i].b = CP_R(2.0);
        g->s[i].n = CP_R(2.0);
        g->s[i].c.x = (cp_real)(10 * i);
        g->s[i].x.y = CP_R(1.0);
        g->s[i].z.x = CP_R(1.0);
    }
}

static int path_err(const struct channel_cfg *g, const struct raster_cfg *rs)
{
    static struct channel_path cp;
    return channel_path_init(&cp, g, rs);
}

static void raster(struct raster_cfg *rs)
{
    memset(rs, 0, sizeof *rs);
    rs->mode = RASTER_LINES;
    rs->n = 3;
    rs->u0 = CP_R(-1.5);
    rs->u1 = CP_R(1.5);
    rs->tol = CP_R(0.05);
    rs->link = RASTER_LINK_AUTO;
}

int test_channel_rejects(void)
{
    struct channel_cfg g;
    struct channel ch;
    struct raster_cfg rs;
    raster(&rs);
    duct(&g);
    CHECK_EQ_INT(path_err(&g, &rs), CP_OK);
    g.count = 1;
    CHECK_EQ_INT(channel_init(&ch, &g), CP_ERR_TOO_FEW);
    g.count = CP_MAX_SECTIONS + 1;
    CHECK_EQ_INT(channel_init(&ch, &g), CP_ERR_TOO_MANY);
    CHECK_EQ_INT(channel_init(&ch, NULL), CP_ERR_INVAL);
    duct(&g);
    g.s[1].a = CP_R(0.0);
    CHECK_EQ_INT(channel_init(&ch, &g), CP_ERR_SECTION);
    duct(&g);
    g.s[2].b = CP_R(-1.0);
    CHECK_EQ_INT(channel_init(&ch, &g), CP_ERR_SECTION);
    duct(&g);
    g.s[0].n = CP_R(0.99);
    CHECK_EQ_INT(channel_init(&ch, &g), CP_ERR_EXPONENT);
    duct(&g);
    g.s[0].n = CP_R(101.0);
    CHECK_EQ_INT(channel_init(&ch, &g), CP_ERR_RANGE);
    duct(&g);
    g.s[1].x.y = CP_R(1.01); /* not unit */
    CHECK_EQ_INT(channel_init(&ch, &g), CP_ERR_RANGE);
    duct(&g);
    g.s[1].c.y = CP_R(1e5);
    CHECK_EQ_INT(channel_init(&ch, &g), CP_ERR_RANGE);
    duct(&g);
    g.s[1].b = CP_R(3.0); /* a = b */
    g.s[1].n = CP_R(4.0);
    CHECK_EQ_INT(channel_init(&ch, &g), CP_ERR_ISOTROPIC);
    g.s[1].n = CP_R(2.0); /* a circle is fine */
    CHECK_EQ_INT(channel_init(&ch, &g), CP_OK);
    duct(&g);
    g.s[1].c = g.s[0].c;
    CHECK_EQ_INT(channel_init(&ch, &g), CP_ERR_COINCIDENT);
    duct(&g);
    g.s[1].z.x = CP_R(0.0); /* plane z = const contains the x chords */
    g.s[1].z.z = CP_R(1.0);
    CHECK_EQ_INT(channel_init(&ch, &g), CP_ERR_SECTION_PLANE);
    duct(&g);
    {
        int i;
        for (i = 0; i < 3; i++) { /* along e_y: tau parallel to the frame reference */
            g.s[i].c.x = CP_R(0.0);
            g.s[i].c.y = (cp_real)(10 * i);
            g.s[i].x.x = CP_R(1.0);
            g.s[i].x.y = CP_R(0.0);
            g.s[i].z.x = CP_R(0.0);
            g.s[i].z.y = CP_R(1.0);
        }
    }
    CHECK_EQ_INT(channel_init(&ch, &g), CP_ERR_FRAME_REF);
    duct(&g);
    g.count = 4;
    g.s[3] = g.s[2];
    g.s[3].c.x = CP_R(30.0);
    g.s[0].n = CP_R(1.0);
    g.s[1].n = CP_R(1.0);
    g.s[2].n = CP_R(60.0);
    g.s[3].n = CP_R(60.0); /* the natural spline of n undershoots below 1 on [0, 1] */
    CHECK_EQ_INT(channel_init(&ch, &g), CP_OK);
    CHECK_EQ_INT(path_err(&g, &rs), CP_ERR_AREA_LAW);
    /* B5: the same area (S = ab K_S) everywhere, but J_I + J_II = ab (a^2 + b^2) K_J jumps 55x
     * from sections 0, 1 to 2, 3: its natural spline overshoots below 0 on [0, 1]: Q <= 0 is
     * no section (CP_ERR_AREA_LAW before anything streams, not a clamp to a circle) */
    duct(&g);
    g.count = 4;
    g.s[3] = g.s[2];
    g.s[3].c.x = CP_R(30.0);
    g.s[0].a = g.s[1].a = CP_R(1.0);
    g.s[0].b = g.s[1].b = CP_R(0.9);
    g.s[2].a = g.s[3].a = CP_R(10.0);
    g.s[2].b = g.s[3].b = CP_R(0.09);
    CHECK_EQ_INT(channel_init(&ch, &g), CP_OK);
    CHECK_EQ_INT(path_err(&g, &rs), CP_ERR_AREA_LAW);
    /* a milder jump (J ratio ~ 2): Q stays > 0, the small Q < 2P dips are clamped and counted
     * (a warning the caller reads in ch.clamps) */
    g.s[2].a = g.s[3].a = CP_R(1.8);
    g.s[2].b = g.s[3].b = CP_R(0.5);
    {
        static struct channel_path cp;
        CHECK_EQ_INT(channel_path_init(&cp, &g, &rs), CP_OK);
        TEST_NOTE("channel mild J overshoot: clamps %u\n", (unsigned)cp.ch.clamps);
        CHECK(cp.ch.clamps > 0u);
    }
    /* B6: the init walks double the step count (up to 2 x 65535 with CP_MAX_STEPS = 65535):
     * the iterator's field must hold it */
    {
        static struct channel_path cp;
        volatile uint32_t twice = 2u * 65535u;
        cp.head.steps = twice;
        CHECK(cp.head.steps == 131070u);
    }
    /* the paper's example read with the printed rotation order: the sweep folds (B5) */
    example(&g, NULL, 1);
    CHECK_EQ_INT(channel_init(&ch, &g), CP_OK);
    CHECK_EQ_INT(path_err(&g, &rs), CP_ERR_FOLD);
    example(&g, NULL, 0);
    CHECK_EQ_INT(path_err(&g, &rs), CP_OK);
    /* tool: a ball larger than the wall's curvature radius folds the centre path */
    rs.output = RASTER_OUT_CENTRE;
    rs.tool_r = CP_R(2.0);
    CHECK_EQ_INT(path_err(&g, &rs), CP_ERR_TOOL);
    rs.tool_r = CP_R(0.25);
    CHECK_EQ_INT(path_err(&g, &rs), CP_OK);
    rs.tool_r = CP_R(-1.0);
    CHECK_EQ_INT(path_err(&g, &rs), CP_ERR_TOOL);
    rs.output = RASTER_OUT_SURFACE;
    rs.tool_r = CP_R(0.5);
    CHECK_EQ_INT(path_err(&g, &rs), CP_ERR_INVAL);
    raster(&rs);
    rs.n = 2;
    rs.u0 = CP_R(-3.1);
    rs.u1 = CP_R(3.1);
    rs.tol = CP_R(1e-5); /* a whole-ring link within 0.01 um needs > CP_MAX_LINK points */
    rs.steps = 8;
    CHECK_EQ_INT(path_err(&g, &rs), CP_ERR_TOL);
    raster(&rs);
    rs.u1 = CP_R(4.0);
    CHECK_EQ_INT(path_err(&g, &rs), CP_ERR_RANGE);
    raster(&rs);
    rs.n = CP_MAX_LINES + 1;
    CHECK_EQ_INT(path_err(&g, &rs), CP_ERR_TOO_MANY);
    return 0;
}

static int same_pt(const struct raster_pt *a, const struct raster_pt *b)
{
    return a->p.x == b->p.x && a->p.y == b->p.y && a->p.z == b->p.z && a->n.x == b->n.x &&
           a->n.y == b->n.y && a->n.z == b->n.z && a->t == b->t && a->line == b->line &&
           a->index == b->index;
}

static struct channel_path it;

int test_channel_iter(void)
{
    struct channel_cfg g;
    struct raster_cfg rs;
    struct raster_pt pt, prev, keep[4];
    uint32_t k, cnt, marks[4];
    int mode;
    double smax = 0.0, emax = 0.0;
    example(&g, &ref, 0);
    for (mode = 0; mode < 2; mode++) {
        raster(&rs);
        rs.mode = (uint8_t)mode;
        rs.tol = CP_R(0.01); /* 10 um */
        if (mode == 1) {
            rs.u0 = CP_R(-3.14159);
            rs.u1 = CP_R(3.14159);
        }
        CHECK_EQ_INT(channel_path_init(&it, &g, &rs), CP_OK);
        cnt = channel_path_count(&it);
        CHECK_EQ_INT(cnt, 3u * (it.head.steps + 1u) + 2u * it.head.link);
        CHECK(it.head.steps >= 8u);
        marks[0] = 0u;
        marks[1] = it.head.steps;
        marks[2] = it.head.steps + 1u;
        marks[3] = cnt - 1u;
        memset(&prev, 0, sizeof prev);
        for (k = 0; k < cnt; k++) {
            uint32_t block = it.head.steps + 1u + it.head.link, j = k / block, r = k % block;
            int m;
            CHECK_EQ_INT(channel_path_next(&it, &pt), CP_OK);
            if (r <= it.head.steps) {
                CHECK_EQ_INT(pt.line, (int)j);
                CHECK_EQ_INT(pt.index, (j & 1u) ? it.head.steps - r : r);
            } else {
                CHECK_EQ_INT(pt.line, -1);
                CHECK_EQ_INT(pt.index, r - it.head.steps);
            }
            for (m = 0; m < 4; m++) {
                if (marks[m] == k) {
                    keep[m] = pt;
                }
            }
            if (k > 0u) {
                /* chord sagitta of this segment: distance of the reference surface point at
                 * the middle parameter from the chord line */
                double mid[3], pr[3], ch[3], dm[3], cx[3], s, e, w, lc;
                w = -1.5 + 1.5 * pt.line;
                mid[0] = 0.5 * ((double)prev.p.x + pt.p.x);
                mid[1] = 0.5 * ((double)prev.p.y + pt.p.y);
                mid[2] = 0.5 * ((double)prev.p.z + pt.p.z);
                if (mode == 0 && pt.line >= 0 && prev.line == pt.line) {
                    ref_channel_point(&ref, 0.5 * ((double)prev.t + pt.t), w, pr);
                    ch[0] = (double)pt.p.x - prev.p.x;
                    ch[1] = (double)pt.p.y - prev.p.y;
                    ch[2] = (double)pt.p.z - prev.p.z;
                    dm[0] = pr[0] - prev.p.x;
                    dm[1] = pr[1] - prev.p.y;
                    dm[2] = pr[2] - prev.p.z;
                    cx[0] = dm[1] * ch[2] - dm[2] * ch[1];
                    cx[1] = dm[2] * ch[0] - dm[0] * ch[2];
                    cx[2] = dm[0] * ch[1] - dm[1] * ch[0];
                    lc = sqrt(ch[0] * ch[0] + ch[1] * ch[1] + ch[2] * ch[2]);
                    s = sqrt(cx[0] * cx[0] + cx[1] * cx[1] + cx[2] * cx[2]) / lc;
                    smax = s > smax ? s : smax;
                    ref_channel_point(&ref, pt.t, w, pr);
                    e = dist3(&pt.p, pr);
                    emax = e > emax ? e : emax;
                }
                /* zigzag and links: the stream never jumps */
                CHECK(sqrt((mid[0] - pt.p.x) * (mid[0] - pt.p.x) + (mid[1] - pt.p.y) * (mid[1] - pt.p.y) +
                           (mid[2] - pt.p.z) * (mid[2] - pt.p.z)) < 2.0);
            }
            prev = pt;
        }
        CHECK_EQ_INT(channel_path_next(&it, &pt), CP_ERR_DONE);
        for (k = 4; k > 0u; k--) { /* seek reproduces point k bit for bit, any order */
            CHECK_EQ_INT(channel_path_seek(&it, marks[k - 1u]), CP_OK);
            CHECK_EQ_INT(channel_path_next(&it, &pt), CP_OK);
            CHECK(same_pt(&pt, &keep[k - 1u]));
        }
        CHECK_EQ_INT(channel_path_seek(&it, cnt + 1u), CP_ERR_RANGE);
        TEST_NOTE("channel %s: steps %u link %u count %u clamps %u\n", mode ? "CIRCLES" : "LINES",
                  (unsigned)it.head.steps, (unsigned)it.head.link, (unsigned)cnt, (unsigned)it.ch.clamps);
    }
    TEST_NOTE("channel LINES: chord sagitta %.3g mm (tol 0.01), points vs reference %.3g mm\n", smax,
              emax);
    CHECK(smax <= 0.01);
#if CP_REAL_DOUBLE
    CHECK(emax <= 1e-9 * 20.0);
#else
    CHECK(emax <= 1e-3);
#endif
    return 0;
}

/* the protocol commands (docs/PROTOCOL.md, Channel) */
static int cmd(struct job *j, const char *s)
{
    return job_command(j, s, strlen(s));
}

int test_channel_job(void)
{
    static struct job j;
    static struct path p;
    job_init(&j);
    CHECK_EQ_INT(cmd(&j, "SECTION 5 3.5 2 3 4.5 1 240 10.5882352941 30"), CP_ST_WRONG_SURFACE);
    CHECK_EQ_INT(cmd(&j, "SURFACE CHANNEL"), CP_ST_OK);
    CHECK_EQ_INT(job_ready(&j), CP_ST_NO_JOB);
    CHECK_EQ_INT(cmd(&j, "AXES 1 0 0 0 0 1"), CP_ST_TOO_FEW);
    CHECK_EQ_INT(cmd(&j, "SECTION 5 3.5 2 3 4.5 1 240 10.5882352941"), CP_ST_BAD_ARITY);
    CHECK_EQ_INT(cmd(&j, "SECTION 5 3.5 2 3 4.5 1 240 10.5882352941 x"), CP_ST_BAD_NUMBER);
    CHECK_EQ_INT(cmd(&j, "SECTION 5 3.5 nan 3 4.5 1 240 10.5882352941 30"), CP_ST_NONFINITE);
    CHECK_EQ_INT(cmd(&j, "SECTION 0 3.5 2 3 4.5 1 240 10.5882352941 30"), CP_ST_SECTION);
    CHECK_EQ_INT(cmd(&j, "SECTION 5 3.5 0.5 3 4.5 1 240 10.5882352941 30"), CP_ST_EXPONENT);
    CHECK_EQ_INT(cmd(&j, "SECTION 5 5 3 3 4.5 1 240 10.5882352941 30"), CP_ST_ISOTROPIC);
    CHECK_EQ_INT(cmd(&j, "SECTION 5 3.5 2 3 4.5 1 400 0 0"), CP_ST_OUT_OF_RANGE);
    CHECK_EQ_INT(cmd(&j, "SECTION 5 3.5 2 3 4.5 1e5 0 0 0"), CP_ST_OUT_OF_RANGE);
    CHECK_EQ_INT(cmd(&j, "SECTIONS"), CP_ST_BAD_ARITY);
    CHECK_EQ_INT(cmd(&j, "SECTIONS MAYBE"), CP_ST_BAD_KEYWORD);
    CHECK_EQ_INT(cmd(&j, "SECTION 5 3.5 2 3 4.5 1 240 10.5882352941 30"), CP_ST_OK);
    CHECK_EQ_INT(cmd(&j, "AXES 1 0 0 0.5 0 1"), CP_ST_OUT_OF_RANGE);
    CHECK_EQ_INT(cmd(&j, "AXES -0.512579 -0.851280 0.112188 0.491487 -0.183750 0.851280"), CP_ST_OK);
    CHECK_EQ_INT(cmd(&j, "SECTION 4 3 3 6 3.5 7 225 22.5 15"), CP_ST_OK);
    CHECK_EQ_INT(cmd(&j, "SECTION 3.5 2.5 6 7 1 14 210 25.7142857143 10"), CP_ST_OK);
    CHECK_EQ_INT(j.geom.channel.count, 3);
    CHECK_EQ_INT(job_ready(&j), CP_ST_NO_JOB); /* no raster yet */
    CHECK_EQ_INT(cmd(&j, "LINES 3 -90 90"), CP_ST_OK);
    CHECK_EQ_INT(cmd(&j, "TOL 20"), CP_ST_OK);
    CHECK_EQ_INT(job_ready(&j), CP_ST_OK);
    CHECK_EQ_INT(path_init(&p, j.kind, &j.cfg, &j.geom), CP_OK);
    CHECK(path_count(&p) == p.info.n * (p.info.steps + 1u) + (p.info.n - 1u) * p.info.link);
    CHECK_EQ_INT(p.info.n, 3);
    CHECK_NEAR(j.geom.channel.s[1].z.x, 0.239118, 2e-6, 0);
    CHECK_NEAR(j.geom.channel.s[0].x.x, -0.512579, 2e-6, 0);
    CHECK_EQ_INT(cmd(&j, "SECTION 4 3 3 6 3.5 8 225 22.5 15"), CP_ST_OK);
#if CP_MAX_SECTIONS == 4
    CHECK_EQ_INT(cmd(&j, "SECTION 4 3 3 6 3.5 9 225 22.5 15"), CP_ST_TOO_MANY);
#endif
    CHECK_EQ_INT(cmd(&j, "SECTIONS CLEAR"), CP_ST_OK);
    CHECK_EQ_INT(j.geom.channel.count, 0);
    CHECK_EQ_INT(job_ready(&j), CP_ST_NO_JOB);
    CHECK_EQ_INT(cmd(&j, "SECTION 4 3 3 6 3.5 8 225 22.5 15"), CP_ST_OK);
    CHECK_EQ_INT(path_init(&p, j.kind, &j.cfg, &j.geom), CP_ERR_TOO_FEW);
    CHECK_EQ_INT(cp_status_of(CP_ERR_TOO_FEW), CP_ST_TOO_FEW);
    CHECK_EQ_INT(cmd(&j, "SURFACE CANAL"), CP_ST_OK);
    CHECK_EQ_INT(cmd(&j, "SECTIONS CLEAR"), CP_ST_WRONG_SURFACE);
    return 0;
}

int test_channel_wire(void)
{
    static const double lam[3][3] = {{179.210340, 307.060729, 486.271069},
                                     {129.587046, 197.272784, 326.859830},
                                     {93.460667, 152.801846, 246.262513}};
    static const double len[3] = {26.911845, 23.681044, 21.995547};
    struct channel_cfg g;
    int i, k;
#if CP_REAL_DOUBLE
    const uint32_t m = 40000u;
    const double tl = 1e-7;
#else
    const uint32_t m = 2000u;
    const double tl = 2e-4;
#endif
    example(&g, &ref, 0);
    for (i = 0; i < 3; i++) {
        cp_real l, lm[3];
        struct cp_vec3 cen, ax;
        double rl, rlam[3], rax[3];
        CHECK_EQ_INT(channel_wire_inertia(&g.s[i], m, &l, &cen, lm, &ax), CP_OK);
        ref_channel_wire(&ref.s[i], (int)m, &rl, rlam, rax);
        CHECK_NEAR(l, len[i], 0, tl);
        CHECK_NEAR(l, rl, 0, tl);
        for (k = 0; k < 3; k++) {
            CHECK_NEAR(lm[k], lam[i][k], 0, tl);
            CHECK_NEAR(lm[k], rlam[k], 0, tl);
        }
        /* B2: wire centroid = section centre; B4: axis of the largest moment = normal */
        CHECK_NEAR(cen.x, g.s[i].c.x, 1e-9 + tl, 0);
        CHECK_NEAR(cen.z, g.s[i].c.z, 1e-9 + tl, 0);
        CHECK_NEAR(ax.x * g.s[i].z.x + ax.y * g.s[i].z.y + ax.z * g.s[i].z.z, 1.0, tl, 0);
        CHECK_NEAR(ax.y, rax[1], tl, 0);
        CHECK_NEAR(1.0 / sqrt(lm[2]), i == 0 ? 0.045348 : (i == 1 ? 0.055312 : 0.063724), 1e-6, 0);
    }
    {
        cp_real l, lm[3];
        struct cp_vec3 cen, ax;
        CHECK_EQ_INT(channel_wire_inertia(&g.s[0], 4u, &l, &cen, lm, &ax), CP_ERR_RANGE);
    }
    return 0;
}
