/* judge_gsr.c - host_sim's judge of SURFACE GSR streams (judge.h), with its own double
 * model tests/ref_gsr.c (no firmware code).
 * SPDX-License-Identifier: MIT
 *
 * The job lines are parsed here with the grammar of docs/PROTOCOL.md ("Generalized surfaces
 * of revolution"): CENTER X|Y|Z, CENTER P0..P3, RADII N|B|T (w in degrees), FRAME, FORM,
 * and the shared TOOL, LINES, CIRCLES, STEPS, TOL. The raster is rebuilt from the run
 * header (mode, n, steps, link) as firmware/models/gsr.h documents it, in double:
 *   block = steps + 1 + link, line j = k / block, r = k % block, odd lines backwards;
 *   LINES   line j at theta_j = v0 + j (v1 - v0)/(n - 1), u = i / steps; link kk at the
 *           line's end u, section parameter from line j's to line j + 1's (fraction
 *           kk / (link + 1));
 *   CIRCLES ring j at u = j (link + 1)/gsteps, gsteps = (n - 1)(link + 1) (1 if n = 1),
 *           section parameter from v0's to v1's at i / steps; link kk at u = (j (link + 1)
 *           + kk)/gsteps on the section parameter of v1 (even j) / v0 (odd j);
 *   section parameter: theta (FORM TRIG) or psi (FORM RATIONAL, theta(psi) and psi(theta)
 *   by the closed forms of C.2).
 * Checks (max, RMS, limit; one PASS/FAIL row each):
 *   point    |received - reference point at (u, theta)| (tool: + r n; tip: - r z),
 *            limit 1e-3 mm (the wire quantization is 0.05 um per axis)
 *   chord    for every consecutive pair, the reference curve between them (7 samples,
 *            linear in (u, section parameter)) from the received chord; limit TOL
 *            (STEPS: info only)
 *   normal   FRAMES: angle to the reference unit normal, limit 0.01 deg
 *   coverage every k exactly once, in order, from the run's first point; a complete run
 *            reaches points - 1; header count = n (steps + 1) + (n - 1) link
 *   overlap  (issue 22) how deep the ball of the streamed tool centre (the surface point
 *            without a tool) enters the sweep's solid FAR from its own section: more than
 *            pi (max semi-axis + r) of centre arc away (ref_gsr_far_dist: the exact disks,
 *            independent of the firmware's capsules); limit 1e-3 mm: the tool is outside,
 *            an overlap is a gouge into another part of the pipe
 */
#include "judge.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "ref_gsr.h"

#define JG_PI 3.14159265358979323846
#define JG_LIM_POINT 1e-3
#define JG_LIM_NORMAL 0.01
#define JG_LIM_OVERLAP 1e-3

static struct {
    int centre, frame, form, mode, output;
    double c[3][7], r[3][7], ref[3];
    unsigned n, steps;
    double v0, v1, tol, tool;
} jb;

static struct ref_gsr rg;
static struct ref_gsr_far rf; /* the far-part measure of the run's sweep */
static struct {
    int active;
    uint32_t points, next;
    unsigned n, steps, link;
    int mode;
    double pu, psig, pp[3];
    int have_prev;
} rn;

static struct judge_stat sp, sc, sn, so;
static unsigned runs, runs_complete;
static unsigned long cov_err, pts;
static int chord_info;

/* session: everything afresh; SURFACE GSR: the geometry starts afresh (the raster commands
 * stay, as in the firmware). */
void judge_gsr_reset(int session)
{
    if (session) {
        memset(&jb, 0, sizeof jb);
        jb.n = 1;
        jb.tol = 1e-3;
    }
    memset(jb.c, 0, sizeof jb.c);
    memset(jb.r, 0, sizeof jb.r);
    memset(jb.ref, 0, sizeof jb.ref);
    jb.r[2][1] = 1.0;
    jb.centre = jb.frame = jb.form = 0;
    memset(&rn, 0, sizeof rn);
}

/* 1: bad arguments (the firmware answers error, model unchanged); 0 otherwise. The 7th
 * number of a function (w, degrees) may reach 23040, every other 1e4. */
static int nums(char **tok, unsigned nt, unsigned first, unsigned n, double *v)
{
    unsigned i;
    if (nt != first + n) {
        return 1;
    }
    for (i = 0; i < n; i++) {
        char *e;
        v[i] = strtod(tok[first + i], &e);
        if (*e != '\0' || !isfinite(v[i]) || fabs(v[i]) > (i == 6u ? 23040.0 : 1e4)) {
            return 1;
        }
    }
    return 0;
}

int judge_gsr_job_line(const char *line)
{
    char buf[128], *tok[JUDGE_MAX_TOKENS];
    int r = judge_split(line, buf, sizeof buf, tok);
    unsigned nt = r > 0 ? (unsigned)r : 0u, k;
    double v[7];
    if (nt < 2u) {
        return 0;
    }
    if (!strcasecmp(tok[0], "CENTER") || !strcasecmp(tok[0], "RADII")) {
        static const char *const cn[7] = {"X", "Y", "Z", "P0", "P1", "P2", "P3"};
        int radii = tok[0][0] == 'R' || tok[0][0] == 'r';
        for (k = 0; k < (radii ? 3u : 7u); k++) {
            if (!strcasecmp(tok[1], radii ? (k == 0 ? "N" : k == 1 ? "B" : "T") : cn[k])) {
                break;
            }
        }
        if (k == (radii ? 3u : 7u)) {
            return 1;
        }
        if (!radii && k >= 3u) {
            if (nums(tok, nt, 2u, 3u, v)) {
                return 1;
            }
            if (jb.centre != 1) {
                memset(jb.c, 0, sizeof jb.c);
                jb.centre = 1;
            }
            jb.c[0][k - 3u] = v[0];
            jb.c[1][k - 3u] = v[1];
            jb.c[2][k - 3u] = v[2];
            return 0;
        }
        if (nums(tok, nt, 2u, 7u, v)) {
            return 1;
        }
        v[6] *= JG_PI / 180.0;
        if (radii) {
            memcpy(jb.r[k], v, sizeof v);
        } else {
            if (jb.centre != 0) {
                memset(jb.c, 0, sizeof jb.c);
                jb.centre = 0;
            }
            memcpy(jb.c[k], v, sizeof v);
        }
        return 0;
    }
    if (!strcasecmp(tok[0], "FRAME")) {
        static const char *const fn[4] = {"FIXED", "FRENET", "N0", "RMF"};
        for (k = 0; k < 4u && strcasecmp(tok[1], fn[k]); k++) {
        }
        if (k == 4u || nums(tok, nt, 2u, k >= 2u ? 3u : 0u, v)) {
            return 1;
        }
        if (k >= 2u) {
            if (v[0] == 0.0 && v[1] == 0.0 && v[2] == 0.0) {
                return 1;
            }
            memcpy(jb.ref, v, sizeof jb.ref);
        }
        jb.frame = (int)k;
        return 0;
    }
    if (!strcasecmp(tok[0], "FORM")) {
        if (nt != 2u || (strcasecmp(tok[1], "RATIONAL") && strcasecmp(tok[1], "TRIG"))) {
            return 1;
        }
        jb.form = !strcasecmp(tok[1], "TRIG");
        return 0;
    }
    if (!strcasecmp(tok[0], "LINES") || !strcasecmp(tok[0], "CIRCLES")) {
        if (nt < 4u || nt > 5u) {
            return 1;
        }
        jb.mode = tok[0][0] == 'C' || tok[0][0] == 'c';
        jb.n = (unsigned)strtoul(tok[1], NULL, 10);
        jb.v0 = strtod(tok[2], NULL) * JG_PI / 180.0;
        jb.v1 = strtod(tok[3], NULL) * JG_PI / 180.0;
        return 0;
    }
    if (!strcasecmp(tok[0], "STEPS")) {
        jb.steps = (unsigned)strtoul(tok[1], NULL, 10);
        jb.tol = 0.0;
        return 0;
    }
    if (!strcasecmp(tok[0], "TOL")) {
        jb.tol = strtod(tok[1], NULL) * 1e-3;
        jb.steps = 0;
        return 0;
    }
    if (!strcasecmp(tok[0], "TOOL")) {
        if (!strcasecmp(tok[1], "NONE")) {
            jb.output = 0;
            jb.tool = 0.0;
        } else if (nt >= 3u) {
            jb.tool = strtod(tok[2], NULL);
            jb.output = (nt == 4u && strcasecmp(tok[3], "TIP")) ? 1 : 2;
        }
        return 0;
    }
    return 0;
}

void judge_gsr_run_begin(uint32_t points, uint32_t first, int mode, unsigned n, unsigned steps,
                         unsigned link)
{
    double cc[3][7], rr[3][7];
    unsigned a, i;
    runs++;
    rn.active = 1;
    rn.points = points;
    rn.next = first;
    rn.mode = mode;
    rn.n = n;
    rn.steps = steps;
    rn.link = link;
    rn.have_prev = 0;
    chord_info = jb.tol <= 0.0;
    if (points != n * (steps + 1u) + (n - 1u) * link || n != jb.n || mode != jb.mode ||
        steps == 0u || (jb.steps != 0u && steps != jb.steps)) {
        cov_err++;
    }
    /* the firmware holds its numbers as parsed (degrees -> radians in its own precision):
     * the reference takes the job's decimal values; differences are << 1 um */
    for (a = 0; a < 3u; a++) {
        for (i = 0; i < 7u; i++) {
            cc[a][i] = jb.c[a][i];
            rr[a][i] = jb.r[a][i];
        }
    }
    ref_gsr_set(&rg, jb.centre, (const double(*)[7])cc, (const double(*)[7])rr, jb.frame, jb.ref);
    ref_gsr_far_init(&rf, &rg);
}

/* (u, section parameter) of point k of the run's raster. */
static void where(uint32_t k, double *u, double *sig)
{
    unsigned block = rn.steps + 1u + rn.link, j = k / block, q = k % block, lk = rn.link + 1u;
    unsigned i = (j & 1u) ? rn.steps - q : q, back = j & 1u;
    double dv = rn.n > 1u ? (jb.v1 - jb.v0) / (rn.n - 1u) : 0.0;
#define SIGOF(x) (jb.form ? (x) : ref_gsr_psi(x))
    if (rn.mode == 0) {
        double s0 = SIGOF(jb.v0 + j * dv), s1 = SIGOF(jb.v0 + (j + 1u) * dv);
        *u = q <= rn.steps ? (double)i / rn.steps : (back ? 0.0 : 1.0);
        *sig = q <= rn.steps ? s0 : s0 + (s1 - s0) * (double)(q - rn.steps) / lk;
    } else {
        double gs = rn.n > 1u ? (double)((rn.n - 1u) * lk) : 1.0, s0 = SIGOF(jb.v0),
               s1 = SIGOF(jb.v1);
        *u = (j * lk + (q <= rn.steps ? 0u : q - rn.steps)) / gs;
        *sig = q <= rn.steps ? s0 + (s1 - s0) * (double)i / rn.steps : (back ? s0 : s1);
    }
#undef SIGOF
}

/* Emitted reference position at (u, sig), and its unit normal. */
static void ref_emit(double u, double sig, double P[3], double n[3])
{
    double th = jb.form ? sig : ref_gsr_theta(sig);
    int c;
    ref_gsr_point(&rg, u, th, P);
    ref_gsr_normal(&rg, u, th, n);
    for (c = 0; c < 3; c++) {
        P[c] += jb.tool * n[c];
    }
    if (jb.output == 2) {
        P[2] -= jb.tool;
    }
}

void judge_gsr_point(uint32_t k, double x, double y, double z, const double *n)
{
    double u, sig, P[3], nr[3], d;
    pts++;
    if (!rn.active || k != rn.next || k >= rn.points) {
        cov_err++;
        rn.have_prev = 0;
        rn.next = k + 1u;
        return;
    }
    rn.next = k + 1u;
    where(k, &u, &sig);
    ref_emit(u, sig, P, nr);
    d = sqrt((x - P[0]) * (x - P[0]) + (y - P[1]) * (y - P[1]) + (z - P[2]) * (z - P[2]));
    judge_stat_add(&sp, d, JG_LIM_POINT, k);
    if (n != NULL) {
        double c = (n[0] * nr[0] + n[1] * nr[1] + n[2] * nr[2]) /
                   sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        judge_stat_add(&sn, acos(c > 1.0 ? 1.0 : c) * 180.0 / JG_PI, JG_LIM_NORMAL, k);
    }
    if (rn.have_prev) { /* chord: 7 reference samples between the two points */
        double ab[3] = {x - rn.pp[0], y - rn.pp[1], z - rn.pp[2]}, L2, worst = 0.0;
        int q, c;
        L2 = ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2];
        for (q = 1; q < 8; q++) {
            double f = q / 8.0, Q[3], nq[3], t, e2 = 0.0;
            ref_emit(rn.pu + f * (u - rn.pu), rn.psig + f * (sig - rn.psig), Q, nq);
            t = L2 > 0.0 ? ((Q[0] - rn.pp[0]) * ab[0] + (Q[1] - rn.pp[1]) * ab[1] +
                            (Q[2] - rn.pp[2]) * ab[2]) / L2
                         : 0.0;
            t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
            for (c = 0; c < 3; c++) {
                double e = Q[c] - rn.pp[c] - t * ab[c];
                e2 += e * e;
            }
            worst = sqrt(e2) > worst ? sqrt(e2) : worst;
        }
        /* the wire rounds each end by <= 0.05 um per axis */
        judge_stat_add(&sc, worst, chord_info ? 0.0 : jb.tol + 1e-4, k);
    }
    { /* overlap: the ball at the tool centre (TIP: back up by r) against the far sweep */
        double q[3] = {x, y, jb.output == 2 ? z + jb.tool : z}, r = jb.output ? jb.tool : 0.0, ua;
        double far = ref_gsr_far_dist(&rg, &rf, q, u, JG_PI * (rf.rmax + r), r, &ua);
        judge_stat_add(&so, far < r ? r - far : 0.0, JG_LIM_OVERLAP, k);
    }
    rn.pu = u;
    rn.psig = sig;
    rn.pp[0] = x;
    rn.pp[1] = y;
    rn.pp[2] = z;
    rn.have_prev = 1;
}

void judge_gsr_run_end(int complete)
{
    if (complete) {
        runs_complete++;
        if (rn.next != rn.points) {
            cov_err++;
        }
    }
    rn.active = 0;
}

void judge_gsr_report(FILE *f, int *passed, int *failed)
{
    if (runs == 0u) {
        return;
    }
    fprintf(f, "  judge gsr: %u run(s), %u complete, %lu points (reference: tests/ref_gsr.c)\n",
            runs, runs_complete, pts);
    judge_stat_row(f, passed, failed, "gsr", "point", &sp, JG_LIM_POINT, "mm", 1);
    judge_stat_row(f, passed, failed, "gsr", "chord", &sc, jb.tol + 1e-4, "mm", !chord_info);
    if (sn.n > 0ul) {
        judge_stat_row(f, passed, failed, "gsr", "normal", &sn, JG_LIM_NORMAL, "deg", 1);
    }
    judge_stat_row(f, passed, failed, "gsr", "overlap", &so, JG_LIM_OVERLAP, "mm", 1);
    (*(cov_err == 0ul ? passed : failed))++;
    fprintf(f, "  %s judge gsr-coverage %lu point(s) in %u run(s), %lu coverage/header error(s)\n",
            cov_err == 0ul ? "PASS" : "FAIL", pts, runs, cov_err);
}
