/* judge_channel.c - host_sim's judge of SURFACE CHANNEL streams (judge.h).
 * SPDX-License-Identifier: MIT
 *
 * The independent model is tests/ref_channel.c (double, no firmware code). From the job
 * lines (SECTION, AXES, SECTIONS CLEAR and the shared LINES, CIRCLES, TOL, STEPS, TOOL) and
 * the run header (mode, n, steps, link) the judge places every point k at its (u, w) itself
 * (docs/PROTOCOL.md, Channel: lines at w_j, points at u_i = i (N-1)/steps, zigzag, links)
 * and checks:
 *   surface   the surface point (the received point with the tool offset removed along the
 *             reference normal) lies on the reference section at its u: <= 1 um
 *   line      |point - reference P(u, w) (+ tool offset)|: the point is on its line or
 *             ring at the right place: <= 1 um
 *   normal    FRAMES: angle(n, reference normal by central differences) <= 0.01 deg
 *   chord     consecutive points of one line/ring: distance of the reference point at the
 *             middle parameter from the chord <= TOL + 0.1 um (wire quantization)
 *   coverage  every point k exactly once, in order; complete runs reach the end.
 *   overlap   (issue 22) the run header's overlap flag against the job's exact section disks
 *             (ref_channel_far_depth: how deep a section's boundary lies inside a disk more
 *             than pi (b_max + h) + 5 h of guide arc away, b_max the largest bounding ball,
 *             h the longest arc of a 1/64 of the guide: pairs the firmware's check tests).
 *             Per run, the miss in mm (0 if right): not reported although far disks share
 *             points, by the depth; reported although the far sections' bounding balls
 *             (the bound raster.h documents: the firmware reports on balls) more than
 *             pi b_max apart keep a gap above the check's slack 4.5 h + the sampling's lip,
 *             by the excess. Limit 1 um.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "judge.h"
#include "ref_channel.h"

#define JC_LIM_MM 1e-3
#define JC_LIM_DEG 0.01
#define JC_PI 3.14159265358979323846
#define JC_MAXSEC 4 /* CP_MAX_SECTIONS of the firmware build */

static struct {
    struct ref_ch_sec s[JC_MAXSEC];
    int ns, mode, n;
    double w0, w1, tol, tool;
    int tool_mode; /* 0 none, 1 tip, 2 centre */
} jb;

static struct ref_channel model;

static struct judge_stat st[4], so;
static struct ref_channel_far far;
static unsigned reported;           /* runs whose header reported an overlap */
static double depth_max = -1e30;    /* greatest far depth over the runs, mm */
static const char *const st_name[4] = {"surface", "line", "normal", "chord"};
static unsigned runs, unchecked;
static unsigned long cov_err, seen_pts;
static struct {
    int active, ok, have_prev;
    uint32_t points, next, steps, link, n, mode;
    double prev[3], pu, pw;
    int prev_line;
} run;

void judge_channel_reset(int session)
{
    (void)session; /* the whole model afresh, both at session start and on SURFACE CHANNEL */
    memset(&jb, 0, sizeof jb);
    jb.n = 1;
    jb.tol = 0.001;
}

int judge_channel_job_line(const char *line)
{
    char buf[128], *tok[JUDGE_MAX_TOKENS];
    int r = judge_split(line, buf, sizeof buf, tok);
    unsigned nt = r > 0 ? (unsigned)r : 0u;
    double v[9];
    if (nt == 0u) {
        return 0;
    }
    if (judge_kw(tok[0], "SECTION")) {
        struct ref_ch_sec *s;
        if (nt != 10u || judge_nums(tok, 1u, 9u, v) || jb.ns >= JC_MAXSEC || !(v[0] > 0.0) ||
            !(v[1] > 0.0) || !(v[2] >= 1.0)) {
            return 1;
        }
        s = &jb.s[jb.ns++];
        s->a = v[0];
        s->b = v[1];
        s->n = v[2];
        s->c[0] = v[3];
        s->c[1] = v[4];
        s->c[2] = v[5];
        ref_channel_euler(v[6] * JC_PI / 180.0, v[7] * JC_PI / 180.0, v[8] * JC_PI / 180.0, 0, s->x,
                          s->z);
        return 0;
    }
    if (judge_kw(tok[0], "AXES")) {
        struct ref_ch_sec *s;
        int k;
        if (nt != 7u || judge_nums(tok, 1u, 6u, v) || jb.ns == 0) {
            return 1;
        }
        s = &jb.s[jb.ns - 1];
        for (k = 0; k < 3; k++) {
            s->x[k] = v[k];
            s->z[k] = v[3 + k];
        }
        return 0;
    }
    if (judge_kw(tok[0], "SECTIONS")) {
        if (nt != 2u || !judge_kw(tok[1], "CLEAR")) {
            return 1;
        }
        jb.ns = 0;
        return 0;
    }
    if ((judge_kw(tok[0], "LINES") || judge_kw(tok[0], "CIRCLES")) && (nt == 4u || nt == 5u) &&
        !judge_nums(tok, 2u, 2u, v)) {
        jb.mode = judge_kw(tok[0], "CIRCLES");
        jb.n = atoi(tok[1]);
        jb.w0 = v[0] * JC_PI / 180.0;
        jb.w1 = v[1] * JC_PI / 180.0;
        return 0;
    }
    if (judge_kw(tok[0], "TOL") && nt == 2u && !judge_nums(tok, 1u, 1u, v)) {
        jb.tol = v[0] * 1e-3;
        return 0;
    }
    if (judge_kw(tok[0], "STEPS")) {
        jb.tol = 0.0; /* fixed steps: no chord check */
        return 0;
    }
    if (judge_kw(tok[0], "TOOL")) {
        if (nt >= 2u && judge_kw(tok[1], "NONE")) {
            jb.tool_mode = 0;
            jb.tool = 0.0;
        } else if (nt >= 3u && judge_kw(tok[1], "BALL") && !judge_nums(tok, 2u, 1u, v)) {
            jb.tool = v[0];
            jb.tool_mode = (nt == 4u && !judge_kw(tok[3], "TIP")) ? 2 : 1;
        }
        return 0;
    }
    return 0;
}

void judge_channel_run_begin(uint32_t points, uint32_t first, int mode, unsigned n, unsigned steps,
                             unsigned link)
{
    runs++;
    memset(&run, 0, sizeof run);
    run.active = 1;
    run.points = points;
    run.next = first;
    run.steps = steps;
    run.link = link;
    run.n = n;
    run.mode = (uint32_t)mode;
    if (jb.ns < 2 || steps == 0u) {
        unchecked++;
        return;
    }
    if (points != n * (steps + 1u) + (n - 1u) * link || (int)n != jb.n || mode != jb.mode) {
        cov_err++;
        unchecked++;
        return;
    }
    (void)ref_channel_build(&model, jb.ns, jb.s);
    run.ok = 1;
    { /* the overlap flag against the exact far disks */
        int flag = judge_run_overlap();
        double ua, ub, h, depth, gap, miss = 0.0;
        ref_channel_far_init(&far, &model);
        h = far.piece;
        depth = ref_channel_far_depth(&model, &far, JC_PI * (far.rbmax + h) + 5.0 * h, &ua, &ub);
        gap = ref_channel_far_ballgap(&far, JC_PI * far.rbmax);
        if (!flag && depth > 0.0) {
            miss = depth;
        } else if (flag && gap > 4.5 * h + far.lip) {
            miss = gap - (4.5 * h + far.lip);
        }
        judge_stat_add(&so, miss, JC_LIM_MM, first);
        reported += flag != 0;
        depth_max = depth > depth_max ? depth : depth_max;
    }
}

static void stat_add(int c, double v, uint32_t k, double lim)
{
    judge_stat_add(&st[c], v, lim, k);
}

static double frac(double lo, double hi, uint32_t num, uint32_t den)
{
    return den == 0u ? lo : lo + (hi - lo) * (double)num / (double)den;
}

/* (u, w) of point k and its line/ring (-1: link) */
static void place(uint32_t k, double *u, double *w, int *line)
{
    uint32_t block = run.steps + 1u + run.link, j = k / block, r = k % block, i, den, nm = run.n - 1u;
    double top = model.ns - 1.0, ua, ub, wa, wb;
    int link = r > run.steps;
    i = link ? r - run.steps : ((j & 1u) ? run.steps - r : r);
    den = link ? run.link + 1u : run.steps;
    if (run.mode == 0u) {
        wa = frac(jb.w0, jb.w1, j, nm);
        ua = link ? ((j & 1u) ? 0.0 : top) : 0.0;
        ub = link ? ua : top;
        wb = link ? frac(jb.w0, jb.w1, j + 1u, nm) : wa;
    } else {
        ua = frac(0.0, top, j, nm);
        wa = link ? ((j & 1u) ? jb.w0 : jb.w1) : jb.w0;
        wb = link ? wa : jb.w1;
        ub = link ? frac(0.0, top, j + 1u, nm) : ua;
    }
    *u = frac(ua, ub, i, den);
    *w = frac(wa, wb, i, den);
    *line = link ? -1 : (int)j;
}

void judge_channel_point(uint32_t k, double x, double y, double z, const double *n)
{
    double u, w, pr[3], nr[3], g, surf[3], d[3], off;
    int line, i;
    seen_pts++;
    if (!run.active) {
        cov_err++;
        return;
    }
    if (k != run.next || k >= run.points) {
        cov_err++;
    }
    run.next = k + 1u;
    if (!run.ok) {
        return;
    }
    place(k, &u, &w, &line);
    ref_channel_point(&model, u, w, pr);
    ref_channel_normal(&model, u, w, nr, &g);
    off = jb.tool_mode ? jb.tool : 0.0;
    surf[0] = x + off * nr[0];
    surf[1] = y + off * nr[1];
    surf[2] = z + off * nr[2] + (jb.tool_mode == 1 ? jb.tool : 0.0);
    stat_add(0, ref_channel_off_section(&model, u, surf), k, JC_LIM_MM);
    for (i = 0; i < 3; i++) {
        d[i] = surf[i] - pr[i];
    }
    stat_add(1, sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]), k, JC_LIM_MM);
    if (n) {
        stat_add(2, judge_angle_deg(n, nr), k, JC_LIM_DEG);
    }
    if (jb.tol > 0.0 && run.have_prev && line >= 0 && run.prev_line == line) {
        /* reference point at the middle parameter (tool offset along its normal) vs chord */
        double pm[3], nm[3], gm, ch[3], dm[3], cx[3], lc, cur[3] = {x, y, z};
        ref_channel_point(&model, 0.5 * (u + run.pu), 0.5 * (w + run.pw), pm);
        ref_channel_normal(&model, 0.5 * (u + run.pu), 0.5 * (w + run.pw), nm, &gm);
        for (i = 0; i < 3; i++) {
            pm[i] -= off * nm[i];
        }
        pm[2] -= jb.tool_mode == 1 ? jb.tool : 0.0;
        for (i = 0; i < 3; i++) {
            ch[i] = cur[i] - run.prev[i];
            dm[i] = pm[i] - run.prev[i];
        }
        cx[0] = dm[1] * ch[2] - dm[2] * ch[1];
        cx[1] = dm[2] * ch[0] - dm[0] * ch[2];
        cx[2] = dm[0] * ch[1] - dm[1] * ch[0];
        lc = sqrt(ch[0] * ch[0] + ch[1] * ch[1] + ch[2] * ch[2]);
        if (lc > 0.0) {
            stat_add(3, sqrt(cx[0] * cx[0] + cx[1] * cx[1] + cx[2] * cx[2]) / lc, k,
                     jb.tol + 1e-4);
        }
    }
    run.have_prev = 1;
    run.prev[0] = x;
    run.prev[1] = y;
    run.prev[2] = z;
    run.pu = u;
    run.pw = w;
    run.prev_line = line;
}

void judge_channel_run_end(int complete)
{
    if (run.active && complete && run.next != run.points) {
        cov_err++;
    }
    run.active = 0;
}

void judge_channel_report(FILE *f, int *passed, int *failed)
{
    char d[200];
    int c;
    if (runs == 0u) {
        return;
    }
    fprintf(f, "  judge channel: %u run(s), %lu points, reference tests/ref_channel.c\n", runs,
            seen_pts);
    for (c = 0; c < 4; c++) {
        judge_stat_row(f, passed, failed, "channel", st_name[c], &st[c],
                       c == 3 ? jb.tol + 1e-4 : (c != 2 ? JC_LIM_MM : JC_LIM_DEG),
                       c != 2 ? "mm" : "deg", 1);
    }
    if (so.n > 0ul) {
        if (depth_max > -1e29) {
            fprintf(f, "  judge channel: %u of %lu run(s) reported an overlap; deepest far-disk "
                    "point %.4f mm (< 0: none inside)\n", reported, so.n, depth_max);
        } else {
            fprintf(f, "  judge channel: %u of %lu run(s) reported an overlap; no boundary "
                    "point crosses a far section's plane\n", reported, so.n);
        }
        judge_stat_row(f, passed, failed, "channel", "overlap", &so, JC_LIM_MM, "mm", 1);
    }
    snprintf(d, sizeof d, "%lu point(s) in %u run(s): %lu order/coverage errors, %u unchecked",
             seen_pts, runs, cov_err, unchecked);
    fprintf(f, "  %s judge channel-coverage %s\n",
            cov_err == 0ul && unchecked == 0u ? "PASS" : "FAIL", d);
    if (cov_err == 0ul && unchecked == 0u) {
        (*passed)++;
    } else {
        (*failed)++;
    }
}
