/* test_overlap_inside.c - the overlap REPORT of the models whose ball tool is inside the
 * swept spheres or sections (issue 22: raster_overlap_report, raster.h): SPINE and the
 * channel stream such a job and set head.overlap; the channel's closed guide needs closing
 * sections (CP_ERR_SEAM).
 * SPDX-License-Identifier: MIT
 *
 * Each report is cross-checked with an independent measure of the exact geometry
 * (ref_spine_far_gap: the spheres themselves; ref_channel_far_depth: the section disks; not
 * the firmware's capsules): a reported SPINE job has far spheres within the check's slack,
 * an unreported one has none that overlap; an unreported channel has no far disks that
 * share points.
 */
#include <math.h>
#include <string.h>

#include "test.h"
#include "channel.h"
#include "ref_channel.h"
#include "ref_spine.h"
#include "spine.h"

#define OI_PI 3.14159265358979323846

#if CP_WITH_SPINE
static struct spine_path oi_sp;
static struct ref_spine oi_rs;
static struct ref_spine_far oi_rf;

/* A SPINE job (kind, sp, RADIUS CONST r) streamed as LINES 2 -60 60 with a chord
 * tolerance of 20 um and a ball of 0.5 inside (TIP); returns spine_path_init's code and,
 * in *gap, the exact least gap of spheres at least pi R + 5 pieces of arc apart (*gap_near:
 * at least pi R apart), the spine measured by ref_spine. */
static int oi_spine(int kind, const double sp[12], double r, double *gap, double *gap_near,
                    double *piece)
{
    struct spine_cfg cfg;
    struct raster_cfg rc;
    double rp[4] = {0.0, 0.0, 0.0, 0.0}, ua, ub;
    int i, err;
    rp[0] = r;
    memset(&cfg, 0, sizeof cfg);
    cfg.kind = (uint8_t)kind;
    cfg.law = SPINE_R_CONST;
    for (i = 0; i < 12; i++) {
        cfg.sp[i] = (cp_real)sp[i];
    }
    cfg.rp[0] = (cp_real)r;
    memset(&rc, 0, sizeof rc);
    rc.mode = RASTER_LINES;
    rc.n = 2;
    rc.u0 = (cp_real)(-OI_PI / 3.0);
    rc.u1 = (cp_real)(OI_PI / 3.0);
    rc.tol = CP_R(0.02);
    rc.link = RASTER_LINK_AUTO;
    rc.output = RASTER_OUT_TIP;
    rc.tool_r = CP_R(0.5);
    err = spine_path_init(&oi_sp, &cfg, &rc);
    if (ref_spine_init(&oi_rs, kind, sp, REF_SPINE_R_CONST, rp, NULL) != REF_SPINE_OK) {
        return -100;
    }
    ref_spine_far_init(&oi_rf, &oi_rs);
    *piece = oi_rf.piece;
    *gap = ref_spine_far_gap(&oi_rs, &oi_rf, OI_PI * (oi_rf.rmax + oi_rf.piece) + 5.0 * oi_rf.piece,
                             &ua, &ub);
    *gap_near = ref_spine_far_gap(&oi_rs, &oi_rf, OI_PI * oi_rf.rmax, &ua, &ub);
    return err;
}

/* The report is right: overlapping far spheres (the exact measure below -1 um) are reported;
 * a report has far spheres within the check's slack (4.5 pieces + the sampling's lip). */
static int oi_consistent(double gap, double gap_near, double piece)
{
    if (gap < -1e-3 && !oi_sp.head.overlap) {
        printf("  spheres overlap by %.4f mm, not reported\n", -gap);
        return 0;
    }
    if (oi_sp.head.overlap && !(gap_near < 4.5 * piece + oi_rf.lip)) {
        printf("  reported, but the far spheres keep %.4f mm (piece %.3f mm)\n", gap_near, piece);
        return 0;
    }
    return 1;
}

/* The cases: a helix tube whose pitch is below 2 R (its turns' spheres meet), a
 * Bezier whose ends come closer than 2 R; each streams (the tool inside: harmless) and is
 * REPORTED; the same shapes with room are not. */
int test_overlap_spine(void)
{
    /* helix about z, radius 15, 2 turns; pitch 3 against spheres of radius 2 */
    static const double tight[12] = {0, 0, 0, 0, 0, 1, 15, 3, 2, 1, 0, 0};
    static const double loose[12] = {0, 0, 0, 0, 0, 1, 15, 6, 2, 1, 0, 0};
    /* the Bezier, its ends 4 mm apart (lifted into 3D; it also crosses itself near
     * its ends), and an arch whose ends are 60 mm apart */
    static const double close[12] = {0, 0, 0, 40, 40, 2, -40, 40, 2, 4, 0, 0};
    static const double apart[12] = {0, 0, 0, 20, 40, 2, 40, 40, 2, 60, 0, 0};
    double gap, gap_near, piece;
    CHECK_EQ_INT(oi_spine(SPINE_HELIX, tight, 2.0, &gap, &gap_near, &piece), CP_OK);
    TEST_NOTE("spine helix pitch 3, R 2: overlap %u, exact far gap %.3f mm (piece %.3f mm)\n",
              (unsigned)oi_sp.head.overlap, gap, piece);
    CHECK_EQ_INT(oi_sp.head.overlap, 1);
    CHECK(gap < -0.9); /* the turns 3 mm apart, spheres 4 mm across: -1 */
    CHECK(oi_consistent(gap, gap_near, piece));
    CHECK(spine_path_count(&oi_sp) > 0u);
    CHECK_EQ_INT(oi_spine(SPINE_HELIX, loose, 2.0, &gap, &gap_near, &piece), CP_OK);
    TEST_NOTE("spine helix pitch 6, R 2: overlap %u, exact far gap %.3f mm\n",
              (unsigned)oi_sp.head.overlap, gap);
    CHECK_EQ_INT(oi_sp.head.overlap, 0);
    CHECK(gap > 1.9);
    CHECK(oi_consistent(gap, gap_near, piece));
    CHECK_EQ_INT(oi_spine(SPINE_BEZIER, close, 3.0, &gap, &gap_near, &piece), CP_OK);
    TEST_NOTE("spine Bezier, ends 4 mm apart, R 3: overlap %u, exact far gap %.3f mm\n",
              (unsigned)oi_sp.head.overlap, gap);
    CHECK_EQ_INT(oi_sp.head.overlap, 1);
    CHECK(gap < -1.9);
    CHECK(oi_consistent(gap, gap_near, piece));
    CHECK_EQ_INT(oi_spine(SPINE_BEZIER, apart, 3.0, &gap, &gap_near, &piece), CP_OK);
    TEST_NOTE("spine Bezier arch, ends 60 mm apart, R 3: overlap %u, exact far gap %.3f mm\n",
              (unsigned)oi_sp.head.overlap, gap);
    CHECK_EQ_INT(oi_sp.head.overlap, 0);
    CHECK(oi_consistent(gap, gap_near, piece));
    return 0;
}
#else
int test_overlap_spine(void)
{
    return 0;
}
#endif

#if CP_WITH_CHANNEL
static struct channel_path oi_cp;
static struct channel_cfg oi_cc;

/* A loop in the xz plane through 4 centres on the circle of centre (20, 0, 11.786) through
 * (0, 0, 0), (40, 0, 0), (20, 0, 35): section i at angle ang[i] on it (radians from the
 * centre, clockwise seen from +y, i.e. the direction of travel), normal along the circle's
 * tangent, a axis +y; semi-axes a x b, exponent 2. */
static void oi_loop(const double *ang, const double *b)
{
    const double cx = 20.0, cz = 825.0 / 70.0, rho = sqrt(20.0 * 20.0 + cz * cz);
    unsigned i;
    memset(&oi_cc, 0, sizeof oi_cc);
    oi_cc.count = 4u;
    for (i = 0; i < 4u; i++) {
        struct channel_section *s = &oi_cc.s[i];
        s->a = CP_R(3.0);
        s->b = (cp_real)b[i];
        s->n = CP_R(2.0);
        s->c.x = (cp_real)(cx + rho * cos(ang[i]));
        s->c.z = (cp_real)(cz + rho * sin(ang[i]));
        s->z.x = (cp_real)(-sin(ang[i])); /* d/d(ang) of the point, unit */
        s->z.z = (cp_real)cos(ang[i]);
        s->x.y = CP_R(1.0);
    }
}

static int oi_channel(void)
{
    struct raster_cfg rc;
    memset(&rc, 0, sizeof rc);
    rc.mode = RASTER_LINES;
    rc.n = 3;
    rc.u0 = (cp_real)(-OI_PI / 2.0);
    rc.u1 = (cp_real)(OI_PI / 2.0);
    rc.steps = 64;
    rc.link = 4;
    rc.output = RASTER_OUT_CENTRE;
    rc.tool_r = CP_R(0.5);
    return channel_path_init(&oi_cp, &oi_cc, &rc);
}

/* The angles of the loop's 4 centres: (0,0,0) at atan2(-cz, -20), then on around through
 * (40,0,0) and (20,0,35) and back to the start (closed: the last angle is the first plus
 * 2 pi) or short of it by `short_by` radians. */
static void oi_angles(double *ang, double short_by)
{
    const double cz = 825.0 / 70.0;
    ang[0] = atan2(-cz, -20.0);
    ang[1] = atan2(-cz, 20.0);
    ang[2] = atan2(35.0 - cz, 0.0);
    if (ang[1] < ang[0]) {
        ang[1] += 2.0 * OI_PI;
    }
    if (ang[2] < ang[1]) {
        ang[2] += 2.0 * OI_PI;
    }
    ang[3] = ang[0] + 2.0 * OI_PI - short_by;
}

/* A closed duct needs closing sections: the same section all round streams; a last section
 * whose b differs (a step), one whose axes are turned by 90 degrees (a step of the turn), and
 * b laws whose values close but whose slopes do not (the natural spline of 2, 2.5, 2.5, 2
 * ends with opposite slopes) are refused with CP_ERR_SEAM; the same duct left open by 0.3
 * rad streams any of them. */
int test_seam_channel(void)
{
    static const double same[4] = {2.0, 2.0, 2.0, 2.0}, step[4] = {2.0, 2.0, 2.0, 2.5};
    static const double bump[4] = {2.0, 2.5, 2.5, 2.0};
    double ang[4];
    oi_angles(ang, 0.0);
    oi_loop(ang, same);
    CHECK_EQ_INT(oi_channel(), CP_OK);
    CHECK_EQ_INT(oi_cp.head.overlap, 0); /* the far side is 47 mm away */
    oi_loop(ang, step);
    CHECK_EQ_INT(oi_channel(), CP_ERR_SEAM);
    oi_loop(ang, bump);
    CHECK_EQ_INT(oi_channel(), CP_ERR_SEAM);
    oi_loop(ang, same);
    oi_cc.s[3].x.y = CP_R(0.0); /* the last a axis in the loop's plane: turned by 90 deg */
    oi_cc.s[3].x.x = oi_cc.s[3].z.z;
    oi_cc.s[3].x.z = -oi_cc.s[3].z.x;
    CHECK_EQ_INT(oi_channel(), CP_ERR_SEAM);
    oi_angles(ang, 0.3); /* open: the ends 7 mm apart */
    oi_loop(ang, step);
    CHECK_EQ_INT(oi_channel(), CP_OK);
    oi_loop(ang, bump);
    CHECK_EQ_INT(oi_channel(), CP_OK);
    return 0;
}

/* The exact measure of the loop in oi_cc (ref_channel_far_depth: a section's boundary
 * inside a far section's disk, > 0; no firmware code), pairs at least pi b + 5 h apart as
 * the host_sim judge takes them. */
static double oi_depth(void)
{
    static struct ref_channel rm;
    static struct ref_channel_far rf;
    struct ref_ch_sec rs[4];
    double ua, ub;
    unsigned i;
    for (i = 0; i < 4u; i++) {
        const struct channel_section *s = &oi_cc.s[i];
        rs[i].a = (double)s->a;
        rs[i].b = (double)s->b;
        rs[i].n = (double)s->n;
        rs[i].c[0] = (double)s->c.x;
        rs[i].c[1] = (double)s->c.y;
        rs[i].c[2] = (double)s->c.z;
        rs[i].x[0] = (double)s->x.x;
        rs[i].x[1] = (double)s->x.y;
        rs[i].x[2] = (double)s->x.z;
        rs[i].z[0] = (double)s->z.x;
        rs[i].z[1] = (double)s->z.y;
        rs[i].z[2] = (double)s->z.z;
    }
    (void)ref_channel_build(&rm, 4, rs);
    ref_channel_far_init(&rf, &rm);
    return ref_channel_far_depth(&rm, &rf, OI_PI * (rf.rbmax + rf.piece) + 5.0 * rf.piece, &ua,
                                 &ub);
}

/* The exact depth (ref_channel_far_depth: 129 sections x 48 boundary points against every
 * far disk) takes about 30 s per duct in QEMU's soft double: the M4F build checks the
 * firmware's flags and counts only; the host builds (float and double) also measure the
 * depths and check them. */
#ifdef __arm__
#define OI_EXACT 0
#else
#define OI_EXACT 1
#endif

/* Far parts of a duct that meet, the tool inside: the loop carried on 0.5 rad past its
 * start (its last part runs through its first: their disks share points, the exact measure
 * finds a section's boundary inside a far disk) streams and is REPORTED; the loop left open
 * by 0.5 rad (ends 11.5 mm apart) is not. Left open by 0.12 rad (ends 2.8 mm apart, the end
 * sections face each other across the gap) it is reported although the disks are apart:
 * the documented looseness at an open end (a section is flat, its ball reaches a = 3 mm
 * past it). */
int test_overlap_channel(void)
{
    static const double same[4] = {2.0, 2.0, 2.0, 2.0};
    double ang[4], depth;
    oi_angles(ang, -0.5);
    oi_loop(ang, same);
    CHECK_EQ_INT(oi_channel(), CP_OK);
    depth = OI_EXACT ? oi_depth() : 0.0;
    TEST_NOTE("channel loop 0.5 rad past its start: overlap %u, exact far depth %.3f mm\n",
              (unsigned)oi_cp.head.overlap, depth);
    CHECK(!OI_EXACT || depth > 1.0);
    CHECK_EQ_INT(oi_cp.head.overlap, 1);
    CHECK(channel_path_count(&oi_cp) > 0u);
    oi_angles(ang, 0.5);
    oi_loop(ang, same);
    CHECK_EQ_INT(oi_channel(), CP_OK);
    depth = OI_EXACT ? oi_depth() : 0.0;
    TEST_NOTE("channel loop open by 0.5 rad: overlap %u, exact far depth %.3f mm\n",
              (unsigned)oi_cp.head.overlap, depth);
    CHECK(!OI_EXACT || depth < 0.0);
    CHECK_EQ_INT(oi_cp.head.overlap, 0);
    oi_angles(ang, 0.12);
    oi_loop(ang, same);
    CHECK_EQ_INT(oi_channel(), CP_OK);
    depth = OI_EXACT ? oi_depth() : 0.0;
    TEST_NOTE("channel loop open by 0.12 rad: overlap %u (the ends' balls), exact far depth "
              "%.3f mm\n", (unsigned)oi_cp.head.overlap, depth);
    CHECK(!OI_EXACT || depth < 0.0);
    CHECK_EQ_INT(oi_cp.head.overlap, 1);
    return 0;
}
#else
int test_seam_channel(void)
{
    return 0;
}
int test_overlap_channel(void)
{
    return 0;
}
#endif
