/* test_seam.c - closed curves (issue 22): a law must close where its curve closes.
 * SPDX-License-Identifier: MIT
 *
 * raster_seam_check on plain numbers, then canal_init and canal_path_init on closed ARC,
 * ELLIPSE and BEZIER curves (refused with CP_ERR_SEAM, or accepted when the law closes) and
 * on open curves (never compared). Each refusal below was accepted before the check.
 */
#include <string.h>

#include "test.h"
#include "canal_path.h"
#include "raster.h"

/* ---- the shared comparison ---- */

int test_seam_check(void)
{
    const cp_real len = CP_R(10.0);
    cp_real nan = CP_R(0.0) / CP_R(0.0);
    CHECK_EQ_INT(raster_seam_check(CP_R(5.0), CP_R(0.2), CP_R(0.0), CP_R(5.0), CP_R(0.2),
                                   CP_R(0.0), len), CP_OK);
    /* value: tolerance 1e-5 len (1 + |d0| + |d1|) = 1e-4 (1.4) here */
    CHECK_EQ_INT(raster_seam_check(CP_R(5.0), CP_R(0.2), CP_R(0.0), CP_R(5.0001), CP_R(0.2),
                                   CP_R(0.0), len), CP_OK);
    CHECK_EQ_INT(raster_seam_check(CP_R(5.0), CP_R(0.2), CP_R(0.0), CP_R(5.0002), CP_R(0.2),
                                   CP_R(0.0), len), CP_ERR_SEAM);
    CHECK_EQ_INT(raster_seam_check(CP_R(7.0), CP_R(0.0), CP_R(0.0), CP_R(5.0), CP_R(0.0),
                                   CP_R(0.0), len), CP_ERR_SEAM);
    /* slope: tolerance 1e-4 (1 + |d0| + |d1|) (+ 1e-5 len (|dd0| + |dd1|)) */
    CHECK_EQ_INT(raster_seam_check(CP_R(5.0), CP_R(0.0), CP_R(0.0), CP_R(5.0), CP_R(0.00009),
                                   CP_R(0.0), len), CP_OK);
    CHECK_EQ_INT(raster_seam_check(CP_R(5.0), CP_R(0.0), CP_R(0.0), CP_R(5.0), CP_R(0.0002),
                                   CP_R(0.0), len), CP_ERR_SEAM);
    CHECK_EQ_INT(raster_seam_check(CP_R(5.0), CP_R(0.3), CP_R(0.0), CP_R(5.0), CP_R(-0.3),
                                   CP_R(0.0), len), CP_ERR_SEAM);
    /* the second derivatives widen the slope test by the ends' rounding: 1e-4 x 2 = 2e-4 */
    CHECK_EQ_INT(raster_seam_check(CP_R(5.0), CP_R(0.0), CP_R(1.0), CP_R(5.0), CP_R(0.0002),
                                   CP_R(1.0), len), CP_OK);
    /* NaN anywhere */
    CHECK_EQ_INT(raster_seam_check(nan, CP_R(0.0), CP_R(0.0), CP_R(5.0), CP_R(0.0), CP_R(0.0),
                                   len), CP_ERR_SEAM);
    CHECK_EQ_INT(raster_seam_check(CP_R(5.0), CP_R(0.0), CP_R(0.0), CP_R(5.0), nan, CP_R(0.0),
                                   len), CP_ERR_SEAM);
    return 0;
}

/* ---- the canal ---- */

/* The curve of s (its law stays) */
static void arc_cfg(struct canal_cfg *s, uint8_t curve, double a0, double a1)
{
    memset(s->cp, 0, sizeof s->cp);
    s->curve = curve;
    s->cp[0] = CP_R(1.0);
    s->cp[1] = CP_R(-2.0);
    s->cp[2] = CP_R(3.0);
    if (curve == CANAL_ARC) {
        s->cp[3] = (cp_real)a0 * CP_DEG2RAD; /* as the protocol converts degrees */
        s->cp[4] = (cp_real)a1 * CP_DEG2RAD;
    } else {
        s->cp[3] = CP_R(2.0);
        s->cp[4] = (cp_real)a0 * CP_DEG2RAD;
        s->cp[5] = (cp_real)a1 * CP_DEG2RAD;
    }
}

static void law(struct canal_cfg *s, uint8_t kind, double r0, double r1, double r2, double r3)
{
    s->radius = kind;
    s->rp[0] = (cp_real)r0;
    s->rp[1] = (cp_real)r1;
    s->rp[2] = (cp_real)r2;
    s->rp[3] = (cp_real)r3;
}

/* canal_init's verdict, which canal_path_init must give too (a LINES raster near C) */
static int both(const struct canal_cfg *s)
{
    static struct canal c;
    static struct canal_path tp;
    struct raster_cfg r;
    int e = canal_init(&c, s);
    memset(&r, 0, sizeof r);
    r.mode = RASTER_LINES;
    r.n = 2u;
    r.u0 = CP_R(-0.1);
    r.u1 = CP_R(0.1);
    r.steps = 64u;
    r.link = 2u;
    if (canal_path_init(&tp, s, &r) != e) {
        printf("  canal_path_init differs from canal_init (%d)\n", e);
        return 99;
    }
    return e;
}

/* ARC and ELLIPSE of 360 degrees: closed by construction, either direction, any start */
int test_seam_canal_arc(void)
{
    static const double starts[3] = {0.0, -90.0, 300.0};
    struct canal_cfg s;
    unsigned i, curve;
    memset(&s, 0, sizeof s);
    for (curve = CANAL_ARC; curve <= CANAL_ELLIPSE; curve++) {
        for (i = 0; i < 3u; i++) {
            double a0 = starts[i];
            /* the example: R = cos(2.5 theta) + 5 steps by 2 mm at the seam */
            arc_cfg(&s, (uint8_t)curve, a0, a0 + 360.0);
            law(&s, CANAL_R_COS, 1.0, 5.0, 2.5, 0.0);
            CHECK_EQ_INT(both(&s), CP_ERR_SEAM);
            arc_cfg(&s, (uint8_t)curve, a0, a0 - 360.0); /* clockwise */
            CHECK_EQ_INT(both(&s), CP_ERR_SEAM);
            /* an integer k closes (value and slope); k = 2 (complex powers), 11 (cp_sincos) */
            law(&s, CANAL_R_COS, 1.0, 5.0, 2.0, 0.0);
            CHECK_EQ_INT(both(&s), CP_OK);
            law(&s, CANAL_R_COS, 0.5, 5.0, 11.0, 0.0);
            CHECK_EQ_INT(both(&s), CP_OK);
            arc_cfg(&s, (uint8_t)curve, a0, a0 + 360.0);
            CHECK_EQ_INT(both(&s), CP_OK);
            /* a k just off an integer: the slope jumps (the value only to second order) */
            law(&s, CANAL_R_COS, 1.0, 5.0, 2.001, 0.0);
            CHECK_EQ_INT(canal_init(&(struct canal){0}, &s), CP_ERR_SEAM);
            /* LINEAR: R runs 4 -> 6 and jumps back */
            law(&s, CANAL_R_LINEAR, 4.0, 6.0, 0.0, 0.0);
            CHECK_EQ_INT(both(&s), CP_ERR_SEAM);
            law(&s, CANAL_R_LINEAR, 4.0, 4.0, 0.0, 0.0);
            CHECK_EQ_INT(both(&s), CP_OK);
            /* CUBIC: equal ends but different slopes (a crease), then a closing one */
            law(&s, CANAL_R_CUBIC, 4.0, 5.0, 5.0, 4.0);
            CHECK_EQ_INT(both(&s), CP_ERR_SEAM);
            law(&s, CANAL_R_CUBIC, 4.0, 5.0, 3.0, 4.0);
            CHECK_EQ_INT(both(&s), CP_OK); /* the same point: the same speed at both ends */
            law(&s, CANAL_R_CONST, 4.0, 0.0, 0.0, 0.0);
            CHECK_EQ_INT(both(&s), CP_OK);
        }
    }
    return 0;
}

/* A Bezier with P3 = P0 (a teardrop: its ends meet at a corner, which is allowed) */
int test_seam_canal_bezier(void)
{
    static const cp_real drop[8] = {CP_R(0.0),   CP_R(0.0),  CP_R(40.0), CP_R(40.0),
                                    CP_R(-40.0), CP_R(40.0), CP_R(0.0),  CP_R(0.0)};
    struct canal_cfg s;
    struct canal c;
    memset(&s, 0, sizeof s);
    s.curve = CANAL_BEZIER;
    memcpy(s.cp, drop, sizeof drop);
    /* R(s) Bernstein: value closes when r0 = r3; dR/ds = 3 (r1 - r0)/|C'(0)| at the start,
     * 3 (r3 - r2)/|C'(1)| at the end, and |C'(0)| = |C'(1)| here */
    law(&s, CANAL_R_CUBIC, 3.0, 4.0, 2.0, 3.0);
    CHECK_EQ_INT(both(&s), CP_OK);
    law(&s, CANAL_R_CUBIC, 3.0, 4.0, 4.0, 3.0); /* closes in value, its slope flips */
    CHECK_EQ_INT(both(&s), CP_ERR_SEAM);
    law(&s, CANAL_R_CUBIC, 3.0, 4.0, 2.0, 3.5); /* a 0.5 mm step */
    CHECK_EQ_INT(both(&s), CP_ERR_SEAM);
    law(&s, CANAL_R_LINEAR, 3.0, 3.5, 0.0, 0.0);
    CHECK_EQ_INT(both(&s), CP_ERR_SEAM);
    law(&s, CANAL_R_COS, 0.5, 3.0, 1.0, 0.0); /* theta = 2 pi s, k = 1: closes */
    CHECK_EQ_INT(both(&s), CP_OK);
    law(&s, CANAL_R_COS, 0.5, 3.0, 1.5, 0.0);
    CHECK_EQ_INT(both(&s), CP_ERR_SEAM);
    /* the end moved by 1e-4 of the size: open, any law */
    s.cp[6] = CP_R(0.008);
    law(&s, CANAL_R_CUBIC, 3.0, 4.0, 2.0, 3.5);
    CHECK_EQ_INT(canal_init(&c, &s), CP_OK);
    /* the order of the checks: R <= 0 comes before the seam */
    s.cp[6] = CP_R(0.0);
    law(&s, CANAL_R_LINEAR, 3.0, -1.0, 0.0, 0.0);
    CHECK_EQ_INT(canal_init(&c, &s), CP_ERR_RADIUS);
    return 0;
}

/* Open curves are never compared: every law passes the seam test */
int test_seam_canal_open(void)
{
    struct canal_cfg s;
    struct canal c;
    memset(&s, 0, sizeof s);
    arc_cfg(&s, CANAL_ARC, 0.0, 359.0);
    law(&s, CANAL_R_COS, 1.0, 5.0, 2.5, 0.0);
    CHECK_EQ_INT(both(&s), CP_OK);
    arc_cfg(&s, CANAL_ARC, 0.0, 359.99); /* 1.7e-4 rad short of closing: open */
    law(&s, CANAL_R_LINEAR, 4.0, 6.0, 0.0, 0.0);
    CHECK_EQ_INT(canal_init(&c, &s), CP_OK);
    arc_cfg(&s, CANAL_ELLIPSE, 30.0, 200.0);
    CHECK_EQ_INT(both(&s), CP_OK);
    memset(&s, 0, sizeof s);
    s.curve = CANAL_LINE;
    s.cp[2] = CP_R(10.0);
    s.cp[3] = CP_R(5.0);
    law(&s, CANAL_R_LINEAR, 2.0, 6.0, 0.0, 0.0);
    CHECK_EQ_INT(both(&s), CP_OK);
    memset(&s, 0, sizeof s);
    s.curve = CANAL_BEZIER;
    s.cp[2] = CP_R(10.0);
    s.cp[3] = CP_R(20.0);
    s.cp[4] = CP_R(30.0);
    s.cp[5] = CP_R(-20.0);
    s.cp[6] = CP_R(40.0);
    law(&s, CANAL_R_CUBIC, 3.0, 4.0, 4.0, 3.5);
    CHECK_EQ_INT(both(&s), CP_OK);
    return 0;
}

/* ---- GSR: a ring of elliptic sections around a closed circle ---- */
#if CP_WITH_GSR
#include "gsr.h"

/* centre: a circle of radius 10 in z = 0 (w = turns x 2 pi), N0 frame with N = +z; f_t = u;
 * f_N = fn0 + a u + b sin(wb u), f_B = 2 */
static int gsr_try(double turns, double a, double b, double wb)
{
    static struct gsr_cfg cf;
    static struct gsr g;
    memset(&cf, 0, sizeof cf);
    cf.centre = GSR_CENTRE_POLY;
    cf.frame = GSR_FRAME_N0;
    cf.section = GSR_SECTION_RATIONAL;
    cf.c[0][GSR_C] = CP_R(10.0);
    cf.c[0][GSR_W] = (cp_real)(turns * 6.283185307179586);
    cf.c[1][GSR_B] = CP_R(10.0);
    cf.c[1][GSR_W] = (cp_real)(turns * 6.283185307179586);
    cf.r[0][0] = CP_R(2.5);
    cf.r[0][1] = (cp_real)a;
    cf.r[0][GSR_B] = (cp_real)b;
    cf.r[0][GSR_W] = (cp_real)wb;
    cf.r[1][0] = CP_R(2.0);
    cf.r[2][1] = CP_R(1.0);
    cf.ref.z = CP_R(1.0);
    return gsr_init(&g, &cf);
}

int test_seam_gsr(void)
{
    const double pi = 3.141592653589793;
    CHECK_EQ_INT(gsr_try(1.0, 0.0, 0.0, 0.0), CP_OK);           /* constant sections */
    CHECK_EQ_INT(gsr_try(1.0, 0.5, 0.0, 0.0), CP_ERR_SEAM);     /* f_N 2.5 -> 3 */
    CHECK_EQ_INT(gsr_try(1.0, 0.0, 0.5, 2.0 * pi), CP_OK);      /* one full sine: closes */
    CHECK_EQ_INT(gsr_try(1.0, 0.0, 0.5, pi), CP_ERR_SEAM);      /* half a sine: a crease */
    CHECK_EQ_INT(gsr_try(0.75, 0.5, 0.0, 0.0), CP_OK);          /* open: any law */
    CHECK_EQ_INT(gsr_try(0.75, 0.0, 0.5, pi), CP_OK);
    return 0;
}
#else
int test_seam_gsr(void)
{
    return 0;
}
#endif
