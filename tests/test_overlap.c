/* test_overlap.c - the global overlap check (issue 22): raster_overlap_check on curves with
 * known answers, then the models that refuse an overlap (GSR: the tool is outside).
 * SPDX-License-Identifier: MIT
 *
 * Each refusal below was accepted before the check (the local tests see one section and
 * its neighbours); each acceptance is a sweep whose parts are apart by a known margin.
 */
#include <math.h>
#include <string.h>

#include "test.h"
#include "gsr.h"
#include "raster.h"
#include "ref_gsr.h"

#define OV_PI 3.14159265358979323846

/* ---- curves with known answers ---- */
enum ov_kind { OV_HELIX, OV_LINE, OV_EIGHT, OV_HOOK };

struct ov_curve {
    int kind;
    double a, pitch, turns, rho; /* HELIX: radius, pitch, turns; every curve: ball radius */
};

static int ov_ball(const void *ctx, cp_real u, struct cp_vec3 *c, cp_real *r)
{
    const struct ov_curve *k = ctx;
    double x = 0.0, y = 0.0, z = 0.0, w = (double)u;
    switch (k->kind) {
    case OV_HELIX: /* axis z through 0 */
        x = k->a * cos(2.0 * OV_PI * k->turns * w);
        y = k->a * sin(2.0 * OV_PI * k->turns * w);
        z = k->pitch * k->turns * w;
        break;
    case OV_LINE:
        x = 50.0 * w;
        break;
    case OV_EIGHT: /* a figure eight of size a, crossing itself at the origin (u = 1/2) */
        x = k->a * sin(2.0 * OV_PI * w);
        y = 0.5 * k->a * sin(4.0 * OV_PI * w);
        break;
    default: /* OV_HOOK: a U of width a: its ends a apart, joined by a half circle */
        x = 0.5 * k->a * cos(OV_PI * w) + 0.0;
        y = 0.5 * k->a * sin(OV_PI * w) * 3.0;
        break;
    }
    c->x = (cp_real)x;
    c->y = (cp_real)y;
    c->z = (cp_real)z;
    *r = (cp_real)k->rho;
    return CP_OK;
}

static int ov_run(int kind, double a, double pitch, double turns, double rho, double grow,
                  struct raster_overlap *o)
{
    struct ov_curve k;
    k.kind = kind;
    k.a = a;
    k.pitch = pitch;
    k.turns = turns;
    k.rho = rho;
    return raster_overlap_check(ov_ball, &k, (cp_real)grow, o);
}

int test_overlap_check(void)
{
    struct raster_overlap o;
    /* a helix tube of radius 2: consecutive turns 2 rho = 4 mm apart at the threshold */
    CHECK_EQ_INT(ov_run(OV_HELIX, 20.0, 3.0, 3.0, 2.0, 0.0, &o), CP_ERR_OVERLAP);
    TEST_NOTE("helix r 20 pitch 3 turns 3, tube 2: overlap, gap %.3f mm at u %.3f / %.3f\n",
              (double)o.gap, (double)o.ua, (double)o.ub);
    CHECK(o.ub - o.ua > 0.2 && o.ub - o.ua < 0.45); /* about a turn (1/3) apart */
    CHECK_EQ_INT(ov_run(OV_HELIX, 20.0, 6.0, 3.0, 2.0, 0.0, &o), CP_OK);
    TEST_NOTE("helix pitch 6: no overlap, closest pair gap %.3f mm (true 2)\n", (double)o.gap);
    CHECK(o.gap > 0.5 && o.gap <= 2.0);
    /* an outside tool of radius 1 sweeps 2 mm beyond the tube: 6 - 4 - 2 = 0 left */
    CHECK_EQ_INT(ov_run(OV_HELIX, 20.0, 6.0, 3.0, 2.0, 2.0, &o), CP_ERR_OVERLAP);
    CHECK_EQ_INT(ov_run(OV_HELIX, 20.0, 8.0, 3.0, 2.0, 2.0, &o), CP_OK);
    /* a closed circle (a torus of major radius 10, minor 4): the neighbours across the
     * seam are neighbours; the far side is 20 mm away */
    CHECK_EQ_INT(ov_run(OV_HELIX, 10.0, 0.0, 1.0, 4.0, 0.0, &o), CP_OK);
    TEST_NOTE("torus 10 x 4: closest non-neighbours gap %.3f mm\n", (double)o.gap);
    /* ...and of major radius 5 with minor 4.5 (valid: curvature 1/5 < 1/4.5): the neighbour
     * arc pi 4.5 + 2 pieces covers all but the far side, 10 mm away against 9 */
    CHECK_EQ_INT(ov_run(OV_HELIX, 5.0, 0.0, 1.0, 4.5, 0.0, &o), CP_OK);
    TEST_NOTE("torus 5 x 4.5: closest non-neighbours gap %.3f mm (true 1)\n", (double)o.gap);
    CHECK(o.gap > 0.5 && o.gap <= 1.0);
    /* a straight tube never meets itself */
    CHECK_EQ_INT(ov_run(OV_LINE, 0.0, 0.0, 0.0, 5.0, 10.0, &o), CP_OK);
    /* (pairs beyond the neighbour arc pi (5 + 5) + 2 pieces = 33 mm: >= 13 mm apart) */
    CHECK(o.gap > 12.0);
    /* a figure eight crosses itself */
    CHECK_EQ_INT(ov_run(OV_EIGHT, 30.0, 0.0, 0.0, 1.0, 0.0, &o), CP_ERR_OVERLAP);
    TEST_NOTE("figure eight: overlap at u %.3f / %.3f\n", (double)o.ua, (double)o.ub);
    /* a U whose ends come 3 mm apart: fine with tube 1, not with tube 2 */
    CHECK_EQ_INT(ov_run(OV_HOOK, 3.0, 0.0, 0.0, 0.4, 0.0, &o), CP_OK);
    TEST_NOTE("U of width 3, tube 0.4: closest gap %.3f mm\n", (double)o.gap);
    CHECK_EQ_INT(ov_run(OV_HOOK, 3.0, 0.0, 0.0, 2.0, 0.0, &o), CP_ERR_OVERLAP);
    return 0;
}

/* ---- GSR: the tool is outside the pipe, an overlap is refused ---- */
#if CP_WITH_GSR
static struct gsr_path ov_gp;
static struct gsr_cfg ov_gc;

/* A pipe along a helix (axis z, radius a, `pitch` mm per turn, `turns`) with elliptic
 * sections fn x fb, N0 frame (N0 = +z); LINES 4 from -90 to 90 degrees, TOL 20 um, a
 * ball of radius tool outside (CENTRE). */
/* ov_gc's centre: a helix about z of radius a turning w radians over u, rising `rise` mm,
 * with the N0 frame N0 = +z (the rest of ov_gc zero) */
static void ov_helix_centre(double a, double w, double rise)
{
    memset(&ov_gc, 0, sizeof ov_gc);
    ov_gc.centre = GSR_CENTRE_POLY;
    ov_gc.frame = GSR_FRAME_N0;
    ov_gc.c[0][GSR_C] = (cp_real)a;
    ov_gc.c[0][GSR_W] = (cp_real)w;
    ov_gc.c[1][GSR_B] = (cp_real)a;
    ov_gc.c[1][GSR_W] = (cp_real)w;
    ov_gc.c[2][1] = (cp_real)rise;
    ov_gc.ref.z = CP_R(1.0);
}

static int ov_gsr_helix(double a, double pitch, double turns, double fn, double fb,
                        double tool, struct raster_overlap *o)
{
    struct raster_cfg rc;
    ov_helix_centre(a, turns * 2.0 * OV_PI, pitch * turns);
    ov_gc.section = GSR_SECTION_RATIONAL;
    ov_gc.r[0][0] = (cp_real)fn;
    ov_gc.r[1][0] = (cp_real)fb;
    ov_gc.r[2][1] = CP_R(1.0);
    memset(&rc, 0, sizeof rc);
    rc.mode = RASTER_LINES;
    rc.n = 4;
    rc.u0 = (cp_real)(-OV_PI / 2.0);
    rc.u1 = (cp_real)(OV_PI / 2.0);
    rc.tol = CP_R(0.02);
    rc.link = RASTER_LINK_AUTO;
    rc.output = tool > 0.0 ? RASTER_OUT_CENTRE : RASTER_OUT_SURFACE;
    rc.tool_r = (cp_real)tool;
    (void)o;
    return gsr_path_init(&ov_gp, &ov_gc, &rc);
}

int test_overlap_gsr(void)
{
    struct raster_overlap o;
    /* a helix pipe of radius 2 around r = 20: its turns meet below a pitch of 4 */
    CHECK_EQ_INT(ov_gsr_helix(20.0, 3.0, 2.0, 2.0, 2.0, 0.0, &o), CP_ERR_OVERLAP);
    CHECK_EQ_INT(ov_gsr_helix(20.0, 6.0, 2.0, 2.0, 2.0, 0.0, &o), CP_OK);
    /* a ball of radius 1 outside sweeps 2 mm more: pitch 6 leaves it no room, 8 does */
    CHECK_EQ_INT(ov_gsr_helix(20.0, 6.0, 2.0, 2.0, 2.0, 1.0, &o), CP_ERR_OVERLAP);
    CHECK_EQ_INT(ov_gsr_helix(20.0, 8.0, 2.0, 2.0, 2.0, 1.0, &o), CP_OK);
    /* a flat section 2 x 0.5 is bounded by its larger semi-axis: pitch 3 refused (a valid
     * pipe when the flat side faces the next turn: the documented false refusal) */
    CHECK_EQ_INT(ov_gsr_helix(20.0, 3.0, 2.0, 0.5, 2.0, 0.0, &o), CP_ERR_OVERLAP);
    /* one turn, no neighbour but itself across 2 pi: accepted at any pitch >= 0 */
    CHECK_EQ_INT(ov_gsr_helix(20.0, 0.5, 0.9, 2.0, 2.0, 0.0, &o), CP_OK);
    /* the judge's measure sees what the firmware refused: on the pitch-3 pipe the surface
     * facing the next turn lies inside it (distance 0); on the pitch-8 pipe the surface is
     * about 4 mm from the next turn */
    {
        static struct ref_gsr rg;
        static struct ref_gsr_far rf;
        double cc[3][7] = {{0}}, rr[3][7] = {{0}}, ref[3] = {0.0, 0.0, 1.0}, P[3], ua, d;
        double w = 4.0 * OV_PI, pitch, worst;
        int th;
        for (pitch = 3.0; pitch < 9.0; pitch += 5.0) {
            cc[0][5] = 20.0;
            cc[0][6] = w;
            cc[1][4] = 20.0;
            cc[1][6] = w;
            cc[2][1] = 2.0 * pitch;
            rr[0][0] = rr[1][0] = 2.0;
            rr[2][1] = 1.0;
            ref_gsr_set(&rg, 0, (const double(*)[7])cc, (const double(*)[7])rr, 2, ref);
            ref_gsr_far_init(&rf, &rg);
            worst = 1e30;
            for (th = 0; th < 16; th++) {
                ref_gsr_point(&rg, 0.3, th * OV_PI / 8.0, P);
                d = ref_gsr_far_dist(&rg, &rf, P, 0.3, OV_PI * 2.0, 5.0, &ua);
                worst = d < worst ? d : worst;
            }
            TEST_NOTE("ref far measure, helix pipe pitch %.0f: closest far part %.4f mm\n", pitch,
                      worst);
            if (pitch < 5.0) {
                CHECK(worst < 1e-9);
            } else {
                CHECK_NEAR(worst, 4.0, 0.05, 0.0); /* the disks tilt with the helix: 3.98 */
            }
        }
    }
    return 0;
}

/* ---- the property: no accepted GSR job whose streamed tool overlaps a far part ----
 * OV_JOBS random pipes (seeded): helices of every pitch against their sections, Bezier
 * centres with loops and close ends, elliptic sections, tools of 0 (surface), 0.3 and
 * 1 mm outside. Each is refused with a documented code, or streamed: every point's tool
 * ball is measured against the exact far sweep (ref_gsr_far_dist, the judge's measure)
 * and must not enter it by more than 1 um. The refusals are counted per code; the test
 * also needs overlaps among the refusals (else it proves nothing) and accepted jobs
 * whose closest far part is within 2 mm of the tool (else it tests only easy cases). */
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define OV_SANITIZED 1 /* unit-asan: the same jobs' first tenth */
#endif
#endif
#ifdef __arm__
#define OV_JOBS 12u /* QEMU: soft double reference */
#elif CP_REAL_DOUBLE || defined(OV_SANITIZED)
#define OV_JOBS 1000u
#else
#define OV_JOBS 10000u /* the float host build: the 10 000 */
#endif
static struct ref_gsr ov_rg;
static struct ref_gsr_far ov_rf;

static double ov_uni(unsigned *s, double a, double b)
{
    return a + (b - a) * (double)(test_prng(s) >> 8) * (1.0 / 16777216.0);
}

/* a random job into ov_gc and rc; returns the tool radius (0: SURFACE) */
static double ov_random_job(unsigned *s, struct raster_cfg *rc)
{
    static const double tools[3] = {0.0, 0.3, 1.0};
    unsigned a, kind = test_prng(s) % 5u;
    double tool = tools[test_prng(s) % 3u];
    uint8_t section = (uint8_t)(test_prng(s) % 2u);
    if (kind < 3u) { /* a helix about z: radius, turns, pitch */
        double A = ov_uni(s, 3.0, 30.0), w = 2.0 * OV_PI * ov_uni(s, 0.2, 3.0);
        ov_helix_centre(A, w, ov_uni(s, 0.0, 12.0) * w / (2.0 * OV_PI));
    } else { /* a Bezier in a 40 mm box, RMF from a random reference */
        memset(&ov_gc, 0, sizeof ov_gc);
        ov_gc.centre = GSR_CENTRE_BEZIER;
        ov_gc.frame = GSR_FRAME_RMF;
        for (a = 0; a < 3u; a++) {
            unsigned i;
            for (i = 0; i < 4u; i++) {
                ov_gc.c[a][i] = (cp_real)ov_uni(s, -20.0, 20.0);
            }
        }
        ov_gc.ref.x = (cp_real)ov_uni(s, -1.0, 1.0);
        ov_gc.ref.y = (cp_real)ov_uni(s, -1.0, 1.0);
        ov_gc.ref.z = (cp_real)ov_uni(s, -1.0, 1.0);
    }
    ov_gc.section = section;
    ov_gc.r[0][0] = (cp_real)ov_uni(s, 0.3, 5.0);
    ov_gc.r[1][0] = (cp_real)ov_uni(s, 0.3, 5.0);
    ov_gc.r[0][1] = (cp_real)ov_uni(s, -0.2, 0.2);
    ov_gc.r[2][1] = CP_R(1.0);
    memset(rc, 0, sizeof *rc);
    rc->mode = RASTER_LINES;
    rc->n = (uint16_t)(2u + test_prng(s) % 2u);
    rc->u0 = (cp_real)(-OV_PI);
    rc->u1 = (cp_real)(OV_PI * 0.75);
    rc->tol = CP_R(0.05);
    rc->link = RASTER_LINK_AUTO;
    rc->output = tool > 0.0 ? RASTER_OUT_CENTRE : RASTER_OUT_SURFACE;
    rc->tool_r = (cp_real)tool;
    return tool;
}

int test_overlap_gsr_property(void)
{
    unsigned seed = 0x0e7a9u, i, codes[40] = {0}, accepted = 0, close = 0;
    unsigned long points = 0;
    double worst = 0.0, closest = 1e30;
    for (i = 0; i < OV_JOBS; i++) {
        struct raster_cfg rc;
        double tool = ov_random_job(&seed, &rc), cc[3][7], rr[3][7], ref[3], near, jclose = 1e30;
        struct raster_pt pt;
        unsigned a, k;
        int err = gsr_path_init(&ov_gp, &ov_gc, &rc);
        if (err != CP_OK) {
            codes[-err < 40 ? -err : 0]++;
            continue;
        }
        accepted++;
        for (a = 0; a < 3u; a++) {
            for (k = 0; k < 7u; k++) {
                cc[a][k] = (double)ov_gc.c[a][k];
                rr[a][k] = (double)ov_gc.r[a][k];
            }
        }
        ref[0] = (double)ov_gc.ref.x;
        ref[1] = (double)ov_gc.ref.y;
        ref[2] = (double)ov_gc.ref.z;
        ref_gsr_set(&ov_rg, ov_gc.centre, (const double(*)[7])cc, (const double(*)[7])rr,
                    ov_gc.frame, ref);
        ref_gsr_far_init(&ov_rf, &ov_rg);
        near = OV_PI * (ov_rf.rmax + tool);
        for (k = 0; gsr_path_next(&ov_gp, &pt) == CP_OK; k++) {
            double q[3] = {(double)pt.p.x, (double)pt.p.y, (double)pt.p.z}, ua;
            double far = ref_gsr_far_dist(&ov_rg, &ov_rf, q, (double)pt.t, near, tool + 2.0, &ua);
            points++;
            jclose = far - tool < jclose ? far - tool : jclose;
            if (tool - far > worst) {
                worst = tool - far;
            }
            if (tool - far > 1e-3) {
                printf("  job %u point %u (u %.4f): the tool enters the sweep at u %.4f by "
                       "%.4f mm\n", i, k, (double)pt.t, ua, tool - far);
                CHECK(0);
            }
        }
        close += jclose < 2.0;
        closest = jclose < closest ? jclose : closest;
    }
    TEST_NOTE("GSR overlap property (%s): %u jobs, %u accepted (%lu points; %u with a far part "
              "within 2 mm of the tool, closest %.3f mm), worst entry %.2g mm; refused:",
              CP_REAL_NAME, OV_JOBS, accepted, points, close, closest, worst);
    for (i = 0; i < 40u; i++) {
        if (codes[i] != 0u) {
            printf(" %d:%u", -(int)i, codes[i]);
        }
    }
    printf("\n");
#if !defined(__arm__) /* 12 jobs on QEMU: too few for the counts */
    CHECK(codes[-CP_ERR_OVERLAP] > OV_JOBS / 20u);
    CHECK(close > OV_JOBS / 100u);
#endif
    return 0;
}
#else
int test_overlap_gsr(void)
{
    return 0;
}
int test_overlap_gsr_property(void)
{
    return 0;
}
#endif
