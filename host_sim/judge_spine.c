/* judge_spine.c - host_sim's judge of SURFACE SPINE streams (judge.h), with its own double
 * model tests/ref_spine.c (adaptive DP5(4) on the RMF ODE and on dtheta/du; no firmware
 * code).
 * SPDX-License-Identifier: MIT
 *
 * The job lines are parsed with the grammar of docs/PROTOCOL.md ("Canal surfaces along a 3D
 * spine"): SPINE LINE|ARC|HELIX|P0..P3 (ARC span in degrees), SPINEDIR, SPINEREF, and the
 * shared RADIUS (the law in u), TOOL, LINES, CIRCLES, STEPS, TOL, sent while SURFACE SPINE is
 * active (a RADIUS sent before SURFACE SPINE is not seen: send it after). The raster is
 * rebuilt from the run header (mode, n, steps, link) as firmware/models/spine.h documents it:
 *   block = steps + 1 + link, block j = k / block, r = k % block, zigzag (odd j backwards);
 *   LINES   line j: theta0 = u0 + j (u1 - u0)/(n - 1), u = i / steps; link a at the line's
 *           end u, theta0 = u0 + (j + a/(link + 1)) (u1 - u0)/(n - 1);
 *   CIRCLES circle j at u = j/(n - 1), theta0 = u0 + i (u1 - u0)/steps; link a at
 *           u = (j + a/(link + 1))/(n - 1) on the theta0 where circle j stopped.
 * Checks (max, RMS, limit; one PASS/FAIL row each):
 *   point    |received - reference| (reference: ref_spine_line_point at (theta0, u); tool:
 *            m - r n, tip: that - r z), limit 1e-3 mm
 *   normal   FRAMES: angle to the reference unit normal, limit 0.01 deg
 *   coverage every k exactly once, in order; header count = n (steps + 1) + (n - 1) link
 *   overlap  (issue 22) the run header's overlap flag against the exact spheres of the job
 *            (ref_spine_far_gap: the least |c(u) - c(u')| - R(u) - R(u') over pairs far
 *            apart along the spine; no firmware code). Per run, the miss in mm (0 if right):
 *            not reported although spheres more than pi (R_max + h) + 5 h of arc apart
 *            overlap (h the longest arc of a 1/64 of u: those pairs lie in pieces the
 *            firmware's check tests), by how much they overlap; reported although the
 *            spheres more than pi R_max apart keep a gap, by how much that gap exceeds the
 *            check's slack 4.5 h + the sampling's lip (its capsules: the largest R over a
 *            piece, twice the sagitta, 1/16 of a chord). Limit 1 um. So an accepted job
 *            whose far spheres overlap, and a report without far spheres near each other,
 *            both FAIL.
 */
#include "judge.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ref_spine.h"

#define JS_PI 3.14159265358979323846
#define JS_LIM_POINT 1e-3
#define JS_LIM_NORMAL 0.01
#define JS_LIM_OVERLAP 1e-3

static struct {
    int kind, law, mode, output, set;
    double sp[12], rp[4], ref[3], dir[3];
    unsigned n, steps;
    double v0, v1, tool;
} jb;

static struct ref_spine rs;
static int rs_ok;
static struct {
    int active;
    uint32_t points, next;
    unsigned n, steps, link;
    int mode;
} rn;

static struct judge_stat sp, sn, so;
static struct ref_spine_far rf;
static unsigned reported;   /* runs whose header reported an overlap */
static double gap_min = 1e30; /* least exact far gap over the runs, mm */
static unsigned runs, runs_complete;
static unsigned long cov_err, pts;

void judge_spine_reset(int session)
{
    if (session) {
        memset(&jb, 0, sizeof jb);
        jb.n = 1;
    }
    memset(jb.sp, 0, sizeof jb.sp);
    memset(jb.ref, 0, sizeof jb.ref);
    jb.dir[0] = 1.0;
    jb.dir[1] = jb.dir[2] = 0.0;
    jb.kind = 0;
    jb.set = 0;
    memset(&rn, 0, sizeof rn);
}

/* 1: bad arguments (the firmware answers error); 0 otherwise. */
static int nums(char **tok, unsigned nt, unsigned first, unsigned n, double *v, int span)
{
    unsigned i;
    if (nt != first + n || judge_nums(tok, first, n, v)) {
        return 1;
    }
    for (i = 0; i < n; i++) {
        if (fabs(v[i]) > (span && i == 7u ? 360.0 : 1e4)) {
            return 1;
        }
    }
    return 0;
}

int judge_spine_job_line(const char *line)
{
    char buf[160], *tok[JUDGE_MAX_TOKENS];
    int r = judge_split(line, buf, sizeof buf, tok);
    unsigned nt = r > 0 ? (unsigned)r : 0u, k;
    double v[12];
    if (nt < 2u) {
        return 0;
    }
    if (judge_kw(tok[0], "SPINE")) {
        static const char *const w[7] = {"LINE", "ARC", "HELIX", "P0", "P1", "P2", "P3"};
        static const unsigned na[7] = {6u, 8u, 9u, 3u, 3u, 3u, 3u};
        int kind;
        for (k = 0; k < 7u && !judge_kw(tok[1], w[k]); k++) {
        }
        if (k == 7u || nums(tok, nt, 2u, na[k], v, k == 1u)) {
            return 1;
        }
        kind = k < 3u ? (int)k : REF_SPINE_BEZIER;
        if (kind != jb.kind || kind != REF_SPINE_BEZIER) {
            memset(jb.sp, 0, sizeof jb.sp);
            jb.set = 0;
            jb.kind = kind;
        }
        if (kind == REF_SPINE_BEZIER) {
            memcpy(&jb.sp[3u * (k - 3u)], v, 3u * sizeof v[0]);
            jb.set |= 1 << (k - 3u);
        } else {
            memcpy(jb.sp, v, (k == 1u ? 7u : na[k]) * sizeof v[0]);
            if (k == 1u) {
                jb.sp[10] = v[7] * JS_PI / 180.0;
            }
            jb.set = 0x0F;
        }
        return 0;
    }
    if (judge_kw(tok[0], "SPINEDIR") || judge_kw(tok[0], "SPINEREF")) {
        if (nums(tok, nt, 1u, 3u, v, 0)) {
            return 1;
        }
        memcpy(judge_kw(tok[0], "SPINEDIR") ? jb.dir : jb.ref, v, 3u * sizeof v[0]);
        return 0;
    }
    if (judge_kw(tok[0], "RADIUS") && nt >= 3u) {
        static const char *const names[4] = {"CONST", "LINEAR", "COS", "CUBIC"};
        int q;
        for (q = 0; q < 4; q++) {
            if (judge_kw(tok[1], names[q])) {
                memset(jb.rp, 0, sizeof jb.rp);
                if (nt - 2u > 4u || judge_nums(tok, 2u, nt - 2u, jb.rp)) {
                    return 0; /* the canal judge reports the arity error */
                }
                jb.law = q;
            }
        }
        return 0;
    }
    if ((judge_kw(tok[0], "LINES") || judge_kw(tok[0], "CIRCLES")) && nt >= 4u &&
        !judge_nums(tok, 2u, 2u, v)) {
        jb.mode = judge_kw(tok[0], "CIRCLES");
        jb.n = (unsigned)strtoul(tok[1], NULL, 10);
        jb.v0 = v[0] * JS_PI / 180.0;
        jb.v1 = v[1] * JS_PI / 180.0;
        return 0;
    }
    if (judge_kw(tok[0], "STEPS")) {
        jb.steps = (unsigned)strtoul(tok[1], NULL, 10);
        return 0;
    }
    if (judge_kw(tok[0], "TOL")) {
        jb.steps = 0;
        return 0;
    }
    if (judge_kw(tok[0], "TOOL")) {
        if (judge_kw(tok[1], "NONE")) {
            jb.output = 0;
            jb.tool = 0.0;
        } else if (nt >= 3u && !judge_nums(tok, 2u, 1u, v)) {
            jb.tool = v[0];
            jb.output = (nt == 4u && !judge_kw(tok[3], "TIP")) ? 1 : 2;
        }
        return 0;
    }
    return 0;
}

void judge_spine_run_begin(uint32_t points, uint32_t first, int mode, unsigned n, unsigned steps,
                           unsigned link)
{
    double s[12];
    unsigned slot = jb.kind == REF_SPINE_ARC ? 7u : jb.kind == REF_SPINE_HELIX ? 9u : 12u, i;
    int zero = jb.ref[0] == 0.0 && jb.ref[1] == 0.0 && jb.ref[2] == 0.0;
    runs++;
    rn.active = 1;
    rn.points = points;
    rn.next = first;
    rn.mode = mode;
    rn.n = n;
    rn.steps = steps;
    rn.link = link;
    if (points != n * (steps + 1u) + (n - 1u) * link || n != jb.n || mode != jb.mode ||
        steps == 0u || (jb.steps != 0u && steps != jb.steps)) {
        cov_err++;
    }
    memcpy(s, jb.sp, sizeof s);
    for (i = 0; slot < 12u && i < 3u; i++) {
        s[slot + i] = jb.dir[i];
    }
    rs_ok = ref_spine_init(&rs, jb.kind, s, jb.law, jb.rp, zero ? NULL : jb.ref) == REF_SPINE_OK;
    if (rs_ok) { /* the overlap flag against the exact spheres */
        int flag = judge_run_overlap();
        double ua, ub, h, far, near, miss = 0.0;
        ref_spine_far_init(&rf, &rs);
        h = rf.piece;
        far = ref_spine_far_gap(&rs, &rf, JS_PI * (rf.rmax + h) + 5.0 * h, &ua, &ub);
        near = ref_spine_far_gap(&rs, &rf, JS_PI * rf.rmax, &ua, &ub);
        if (!flag && far < 0.0) {
            miss = -far;
        } else if (flag && near > 4.5 * h + rf.lip) {
            miss = near - (4.5 * h + rf.lip);
        }
        judge_stat_add(&so, miss, JS_LIM_OVERLAP, first);
        reported += flag != 0;
        gap_min = far < gap_min ? far : gap_min;
    }
}

/* (theta0, u) of point k of the run's raster. */
static void where(uint32_t k, double *th, double *u)
{
    unsigned block = rn.steps + 1u + rn.link, j = k / block, q = k % block;
    double lk = rn.link + 1.0, du = jb.v1 - jb.v0, fj, run;
    if (q <= rn.steps) {
        unsigned i = (j & 1u) ? rn.steps - q : q;
        fj = j;
        run = (double)i / rn.steps;
    } else {
        fj = j + (q - rn.steps) / lk;
        run = (j & 1u) ? 0.0 : 1.0;
    }
    if (rn.mode == 0) {
        *th = rn.n > 1u ? jb.v0 + du * fj / (rn.n - 1.0) : jb.v0;
        *u = run;
    } else {
        *th = jb.v0 + du * run;
        *u = rn.n > 1u ? fj / (rn.n - 1.0) : 0.0;
    }
}

void judge_spine_point(uint32_t k, double x, double y, double z, const double *n)
{
    double th, u, m[3], nr[3], d;
    int c;
    pts++;
    if (!rn.active || k != rn.next || k >= rn.points) {
        cov_err++;
        rn.next = k + 1u;
        return;
    }
    rn.next = k + 1u;
    where(k, &th, &u);
    if (!rs_ok || ref_spine_line_point(&rs, th, u, m, nr) != 0) {
        judge_stat_add(&sp, NAN, JS_LIM_POINT, k);
        return;
    }
    for (c = 0; c < 3; c++) {
        m[c] -= jb.tool * nr[c];
    }
    if (jb.output == 2) {
        m[2] -= jb.tool;
    }
    d = sqrt((x - m[0]) * (x - m[0]) + (y - m[1]) * (y - m[1]) + (z - m[2]) * (z - m[2]));
    judge_stat_add(&sp, d, JS_LIM_POINT, k);
    if (n != NULL) {
        judge_stat_add(&sn, judge_angle_deg(n, nr), JS_LIM_NORMAL, k);
    }
}

void judge_spine_run_end(int complete)
{
    if (complete) {
        runs_complete++;
        if (rn.next != rn.points) {
            cov_err++;
        }
    }
    rn.active = 0;
}

void judge_spine_report(FILE *f, int *passed, int *failed)
{
    if (runs == 0u) {
        return;
    }
    fprintf(f, "  judge spine: %u run(s), %u complete, %lu points (reference: tests/ref_spine.c)\n",
            runs, runs_complete, pts);
    judge_stat_row(f, passed, failed, "spine", "point", &sp, JS_LIM_POINT, "mm", 1);
    if (sn.n > 0ul) {
        judge_stat_row(f, passed, failed, "spine", "normal", &sn, JS_LIM_NORMAL, "deg", 1);
    }
    if (so.n > 0ul) {
        fprintf(f, "  judge spine: %u of %lu run(s) reported an overlap; least exact far-sphere "
                "gap %.4f mm\n", reported, so.n, gap_min);
        judge_stat_row(f, passed, failed, "spine", "overlap", &so, JS_LIM_OVERLAP, "mm", 1);
    }
    (*(cov_err == 0ul ? passed : failed))++;
    fprintf(f, "  %s judge spine-coverage %lu point(s) in %u run(s), %lu coverage/header error(s)\n",
            cov_err == 0ul ? "PASS" : "FAIL", pts, runs, cov_err);
}
