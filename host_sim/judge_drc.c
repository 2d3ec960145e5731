/* judge_drc.c - host_sim's judge of SURFACE DRC streams (judge.h).
 * SPDX-License-Identifier: MIT
 *
 * The independent model is tests/ref_drc.c (double DRC-EXP, no firmware code). From the
 * job lines (POINT, POINTS CLEAR, THICKEN, EDGE and the shared RADIUS, LINES, TOL, TOOL)
 * and the run header (steps = 2^K (N - 1) gives K) the judge thickens the points itself
 * and checks every received point:
 *   curve     EDGE OFF: |point - reference DRC point k| <= 1 um
 *   tangent   EDGE OFF, FRAMES: angle(n, reference tangent) <= 0.01 deg
 *   sphere    EDGE ON: the point lies on the sphere (C_i, R(sigma_i)) of its reference
 *             contact point, and on its characteristic circle ((m - rho).(t, p) = -R p),
 *             both <= 1 um (link points: the end circle)
 *   line      EDGE ON: distance to the reference point of the same line: the canal
 *             contact-frame formula (MATH-canal) with the judge's own Lambda, summed by
 *             the trapezoid rule over the reference points (3-point curvature times dR),
 *             <= 1 um
 *   normal    EDGE ON, FRAMES: angle(n, (m - rho)/R) <= 0.01 deg
 *   coverage  every point k exactly once, in order, complete runs reach the end.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "judge.h"
#include "ref_drc.h"

#define JD_LIM_MM 1e-3
#define JD_LIM_DEG 0.01

static struct {
    double p[REF_DRC_MAXN][3];
    int n, k, edge, radius, lines;
    double rp[4], u0, u1, tool;
    int tool_mode; /* 0 none, 1 tip, 2 centre */
    int bad;       /* cannot model (too many points, ...) */
} jb;

static double rpts[REF_DRC_MAXOUT][3], rtan[REF_DRC_MAXOUT][3], rsig[REF_DRC_MAXOUT],
    rlam[REF_DRC_MAXOUT];

static struct judge_stat st[5]; /* curve, tangent, sphere, line, normal */
static const char *const st_name[5] = {"curve", "tangent", "sphere", "line", "normal"};
static unsigned runs, unchecked;
static unsigned long cov_err, seen_pts;
static struct {
    int active, ok;
    uint32_t points, next, steps, link, n, m;
    double stot;
} run;

void judge_drc_reset(int session)
{
    (void)session; /* the whole model afresh, both at session start and on SURFACE DRC */
    memset(&jb, 0, sizeof jb);
    jb.k = -1;
    jb.lines = 1;
}

int judge_drc_job_line(const char *line)
{
    char buf[128], *tok[JUDGE_MAX_TOKENS];
    int r = judge_split(line, buf, sizeof buf, tok);
    unsigned nt = r > 0 ? (unsigned)r : 0u;
    double v[4];
    if (nt == 0u) {
        return 0;
    }
    if (judge_kw(tok[0], "POINT")) {
        if ((nt != 3u && nt != 4u) || judge_nums(tok, 1u, nt - 1u, v)) {
            return 1;
        }
        if (jb.n >= 12) {
            return 1; /* CP_MAX_DRC_POINTS: error:14 */
        }
        jb.p[jb.n][0] = v[0];
        jb.p[jb.n][1] = v[1];
        jb.p[jb.n][2] = nt == 4u ? v[2] : 0.0;
        jb.n++;
        return 0;
    }
    if (judge_kw(tok[0], "POINTS")) {
        if (nt != 2u || !judge_kw(tok[1], "CLEAR")) {
            return 1;
        }
        jb.n = 0;
        return 0;
    }
    if (judge_kw(tok[0], "THICKEN")) {
        if (nt != 2u) {
            return 1;
        }
        jb.k = judge_kw(tok[1], "AUTO") ? -1 : atoi(tok[1]);
        return 0;
    }
    if (judge_kw(tok[0], "EDGE")) {
        if (nt != 2u || (!judge_kw(tok[1], "ON") && !judge_kw(tok[1], "OFF"))) {
            return 1;
        }
        jb.edge = judge_kw(tok[1], "ON");
        return 0;
    }
    if (judge_kw(tok[0], "RADIUS") && nt >= 3u) {
        static const char *const names[4] = {"CONST", "LINEAR", "COS", "CUBIC"};
        int k;
        for (k = 0; k < 4; k++) {
            if (judge_kw(tok[1], names[k])) {
                memset(jb.rp, 0, sizeof jb.rp);
                if (nt - 2u > 4u || judge_nums(tok, 2u, nt - 2u, jb.rp)) {
                    return 0; /* the canal judge reports the arity error */
                }
                jb.radius = k;
            }
        }
        return 0;
    }
    if (judge_kw(tok[0], "LINES") && nt == 4u && !judge_nums(tok, 2u, 2u, v)) {
        jb.lines = atoi(tok[1]);
        jb.u0 = v[0] * M_PI / 180.0;
        jb.u1 = v[1] * M_PI / 180.0;
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
    if (judge_kw(tok[0], "CIRCLES")) {
        return -1; /* DRC streams LINES only */
    }
    return 0;
}

/* radius law over sigma (canal.h kinds; COS with theta = 2 pi sigma): R and dR/dsigma */
static void rad(double s, double *r, double *dr)
{
    const double *c = jb.rp;
    double u = 1.0 - s;
    switch (jb.radius) {
    case 0:
        *r = c[0];
        *dr = 0.0;
        break;
    case 1:
        *r = c[0] + (c[1] - c[0]) * s;
        *dr = c[1] - c[0];
        break;
    case 2:
        *r = c[0] * cos(2.0 * M_PI * c[2] * s) + c[1];
        *dr = -c[0] * 2.0 * M_PI * c[2] * sin(2.0 * M_PI * c[2] * s);
        break;
    default:
        *r = u * u * u * c[0] + 3.0 * u * u * s * c[1] + 3.0 * u * s * s * c[2] + s * s * s * c[3];
        *dr = 3.0 * (u * u * (c[1] - c[0]) + 2.0 * u * s * (c[2] - c[1]) + s * s * (c[3] - c[2]));
        break;
    }
}

void judge_drc_run_begin(uint32_t points, uint32_t first, int mode, unsigned n, unsigned steps,
                         unsigned link)
{
    int K = 0, m = 0, i;
    runs++;
    memset(&run, 0, sizeof run);
    run.active = 1;
    run.points = points;
    run.next = first;
    run.steps = steps;
    run.link = link;
    run.n = n;
    if (jb.n < 3 || mode != 0) {
        unchecked++;
        return;
    }
    while (K < 8 && ((unsigned)(jb.n - 1) << K) < steps) {
        K++;
    }
    if (((unsigned)(jb.n - 1) << K) != steps || (jb.k >= 0 && jb.k != K) ||
        points != n * (steps + 1u) + (n - 1u) * link || (!jb.edge && n != 1u) ||
        (jb.edge && (int)n != jb.lines)) {
        cov_err++;
        unchecked++;
        return;
    }
    if (ref_drc_run((const double(*)[3])jb.p, jb.n, K, rpts, rtan, &m) != REF_DRC_OK) {
        unchecked++;
        return;
    }
    run.m = (uint32_t)m;
    /* arc length (chords) and Lambda by the trapezoid rule on kappa dR */
    rsig[0] = 0.0;
    for (i = 1; i < m; i++) {
        double dx = rpts[i][0] - rpts[i - 1][0], dy = rpts[i][1] - rpts[i - 1][1];
        rsig[i] = rsig[i - 1] + sqrt(dx * dx + dy * dy);
    }
    run.stot = rsig[m - 1];
    for (i = 0; i < m; i++) {
        rsig[i] /= run.stot;
    }
    rlam[0] = 0.0;
    for (i = 1; i < m; i++) {
        int a = i - 1 > 0 ? i - 1 : 1, b = i < m - 1 ? i : m - 2;
        double ka = ref_kappa3(rpts[a - 1], rpts[a], rpts[a + 1], 1);
        double kb = ref_kappa3(rpts[b - 1], rpts[b], rpts[b + 1], 1), ra, rb, d;
        rad(rsig[i - 1], &ra, &d);
        rad(rsig[i], &rb, &d);
        rlam[i] = rlam[i - 1] + 0.5 * (ka + kb) * (rb - ra);
    }
    run.ok = 1;
}

static void stat_add(int c, double v, uint32_t k, double lim)
{
    judge_stat_add(&st[c], v, lim, k);
}

void judge_drc_point(uint32_t k, double x, double y, double z, const double *n)
{
    uint32_t block, jl, r, i;
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
    block = run.steps + 1u + run.link;
    jl = k / block;
    r = k % block;
    if (!jb.edge) {
        double d[3];
        d[0] = x - rpts[r][0];
        d[1] = y - rpts[r][1];
        d[2] = z - rpts[r][2];
        stat_add(0, sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]), k, JD_LIM_MM);
        if (n) {
            stat_add(1, judge_angle_deg(n, rtan[r]), k, JD_LIM_DEG);
        }
        return;
    }
    {
        double R, dR, p, rho[3], v[3], dist, circ, off, nn[3];
        int back = (int)(jl & 1u), link = r > run.steps;
        i = link ? (back ? 0u : run.steps) : (back ? run.steps - r : r);
        rad(rsig[i], &R, &dR);
        p = dR / run.stot;
        off = jb.tool_mode ? jb.tool : 0.0;
        rho[0] = rpts[i][0];
        rho[1] = rpts[i][1];
        rho[2] = R;
        v[0] = x - rho[0];
        v[1] = y - rho[1];
        v[2] = z + (jb.tool_mode == 1 ? jb.tool : 0.0) - rho[2];
        dist = fabs(sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) - (R - off));
        /* characteristic circle: (m - rho).(t, p) = -(R - off) p (scaled by |(t, p)|) */
        circ = fabs(v[0] * rtan[i][0] + v[1] * rtan[i][1] + v[2] * p + (R - off) * p) /
               sqrt(1.0 + p * p);
        stat_add(2, fmax(dist, circ), k, JD_LIM_MM);
        if (n) {
            double l = R - off;
            nn[0] = v[0] / l;
            nn[1] = v[1] / l;
            nn[2] = v[2] / l;
            stat_add(4, judge_angle_deg(n, nn), k, JD_LIM_DEG);
        }
        if (!link) {
            /* the contact-frame formula with the judge's Lambda */
            double u = run.n > 1u ? jb.u0 + (jb.u1 - jb.u0) * (double)jl / (double)(run.n - 1u)
                                  : jb.u0;
            double rr, dr0, q0, al, b, h, q2 = 1.0 + p * p, w, nx, ny, nz, ref[3], d[3];
            rad(0.0, &rr, &dr0);
            q0 = sqrt(1.0 + (dr0 / run.stot) * (dr0 / run.stot));
            al = q0 * cos(0.5 * u);
            b = sin(0.5 * u);
            h = al + rlam[i] * b;
            w = 2.0 * b / (q2 * b * b + h * h);
            nx = w * (-p * b * rtan[i][0] - h * rtan[i][1]);
            ny = w * (-p * b * rtan[i][1] + h * rtan[i][0]);
            nz = w * b - 1.0;
            ref[0] = rho[0] + (R - off) * nx;
            ref[1] = rho[1] + (R - off) * ny;
            ref[2] = off + (R - off) * (nz + 1.0) - (jb.tool_mode == 1 ? jb.tool : 0.0);
            d[0] = x - ref[0];
            d[1] = y - ref[1];
            d[2] = z - ref[2];
            stat_add(3, sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]), k, JD_LIM_MM);
        }
    }
}

void judge_drc_run_end(int complete)
{
    if (run.active && complete && run.next != run.points) {
        cov_err++;
    }
    run.active = 0;
}

void judge_drc_report(FILE *f, int *passed, int *failed)
{
    char d[200];
    int c;
    if (runs == 0u) {
        return;
    }
    fprintf(f, "  judge drc: %u run(s), %lu points, reference DRC-EXP (tests/ref_drc.c)\n", runs,
            seen_pts);
    for (c = 0; c < 5; c++) {
        int mm = c != 1 && c != 4;
        judge_stat_row(f, passed, failed, "drc", st_name[c], &st[c], mm ? JD_LIM_MM : JD_LIM_DEG,
                       mm ? "mm" : "deg", 1);
    }
    snprintf(d, sizeof d, "%lu point(s) in %u run(s): %lu order/coverage errors, %u unchecked",
             seen_pts, runs, cov_err, unchecked);
    fprintf(f, "  %s judge drc-coverage %s\n", cov_err == 0ul && unchecked == 0u ? "PASS" : "FAIL",
            d);
    if (cov_err == 0ul && unchecked == 0u) {
        (*passed)++;
    } else {
        (*failed)++;
    }
}
