/* judge_plane.c - host_sim's judge of the example model (SURFACE PLANE): every streamed
 * point against tests/ref_plane.c. judge.h has the hooks' contract.
 * SPDX-License-Identifier: MIT
 *
 * Modelled job lines: STRIP len width (mm, (0, 10000] each), LINES n u0 u1 (degrees),
 * STEPS m (1..4096), TOL (back to derived steps). STRIP belongs to the geometry (reset on
 * SURFACE PLANE); LINES, STEPS and TOL are raster commands and stay. Checks:
 *   point   |p - reference point k|, mm; limit 1e-3 (1 um)
 *   normal  angle between the streamed normal and (0, 0, 1), degrees; limit 0.01
 *   coverage every point once, in order, the count of the header; the header agrees with
 *            the job: mode LINES, n of LINES, steps of STEPS (RASTER_MIN_STEPS = 8 when
 *            derived: a straight line has no sagitta, plane.h), link 0 (derived links of
 *            a straight strip)
 */
#include "judge.h"
#include "ref_plane.h"

#include <math.h>
#include <string.h>

#define JP_LIM_MM 1e-3
#define JP_LIM_DEG 0.01
#define JP_DEG 0.017453292519943295
#define JP_SIZE_MAX 10000.0 /* plane.h PLANE_SIZE_MAX, mm */
#define JP_MAX_STEPS 4096ul /* cp_config.h CP_MAX_STEPS */
#define JP_MAX_LINES 256ul  /* cp_config.h CP_MAX_LINES */
#define JP_DERIVED_STEPS 8u /* raster.h RASTER_MIN_STEPS: derived steps of a straight line */

static struct ref_plane job; /* what the job lines said (steps 0: derived) */
static int have_strip, have_lines;
static struct ref_plane run; /* the run's raster (header counts) */
static int run_on, run_ok;
static uint32_t run_next, run_points;
static unsigned runs;
static unsigned long seen, cov_err;
static struct judge_stat st_point, st_normal;

void judge_plane_reset(int session)
{
    job.len = job.width = 0.0; /* SURFACE PLANE: the strip afresh, the raster stays */
    have_strip = 0;
    if (session) {
        memset(&job, 0, sizeof job);
        have_lines = 0;
        runs = 0u;
        seen = cov_err = 0ul;
        memset(&st_point, 0, sizeof st_point);
        memset(&st_normal, 0, sizeof st_normal);
    }
}

/* An unsigned decimal token (optional '+'), as the firmware's unsigned numbers. */
static int uint_arg(const char *s, unsigned long *v)
{
    unsigned long x = 0ul;
    if (*s == '+') {
        s++;
    }
    if (*s < '0' || *s > '9') {
        return 1;
    }
    for (; *s >= '0' && *s <= '9'; s++) {
        if (x < 100000000ul) {
            x = x * 10ul + (unsigned long)(*s - '0');
        }
    }
    *v = x;
    return *s != '\0';
}

int judge_plane_job_line(const char *line)
{
    unsigned long u;
    char buf[256], *tok[JUDGE_MAX_TOKENS + 1];
    double v[3];
    int nt = judge_split(line, buf, sizeof buf, tok);
    if (nt <= 0) {
        return 0;
    }
    if (judge_kw(tok[0], "STRIP")) {
        if (nt != 3 || judge_nums(tok, 1u, 2u, v) || !(v[0] > 0.0) || v[0] > JP_SIZE_MAX ||
            !(v[1] > 0.0) || v[1] > JP_SIZE_MAX) {
            return 1;
        }
        job.len = v[0];
        job.width = v[1];
        have_strip = 1;
    } else if (judge_kw(tok[0], "LINES")) {
        if (nt != 4 || uint_arg(tok[1], &u) || u == 0ul || u > JP_MAX_LINES ||
            judge_nums(tok, 1u, 3u, v) || fabs(v[1]) > 180.0 || fabs(v[2]) > 180.0 ||
            (v[1] == v[2] && u > 1ul)) {
            return 1; /* as the firmware (and judge_canal.c's cmd_raster): model unchanged */
        }
        job.n = (unsigned)u;
        job.u0 = v[1] * JP_DEG;
        job.u1 = v[2] * JP_DEG;
        have_lines = 1;
    } else if (judge_kw(tok[0], "STEPS")) {
        if (nt != 2 || uint_arg(tok[1], &u) || u == 0ul || u > JP_MAX_STEPS) {
            return 1;
        }
        job.steps = (unsigned)u;
    } else if (judge_kw(tok[0], "TOL")) {
        if (nt != 2 || judge_nums(tok, 1u, 1u, v) || v[0] < 0.01 || v[0] > 10000.0) {
            return 1;
        }
        job.steps = 0u; /* derived again */
    }
    return 0;
}

void judge_plane_run_begin(uint32_t points, uint32_t first, int mode, unsigned n, unsigned steps,
                           unsigned link)
{
    runs++;
    run = job;
    run.n = n;
    run.steps = steps;
    run.link = link;
    run_on = 1;
    run_next = first;
    run_points = points;
    /* the header against the job: n of LINES, STEPS m (or the derived count), no link */
    run_ok = have_strip && have_lines && mode == 0 && n == job.n &&
             steps == (job.steps != 0u ? job.steps : JP_DERIVED_STEPS) && link == 0u &&
             points == n * (steps + 1u) + (n - 1u) * link;
    if (!run_ok) {
        cov_err++;
    }
}

void judge_plane_point(uint32_t k, double x, double y, double z, const double *n)
{
    double p[3], nr[3];
    seen++;
    if (!run_on || k != run_next || k >= run_points) {
        cov_err++;
    }
    run_next = k + 1u;
    if (!run_ok || ref_plane_point(&run, k, p, nr) != 0) {
        return;
    }
    judge_stat_add(
        &st_point,
        sqrt((x - p[0]) * (x - p[0]) + (y - p[1]) * (y - p[1]) + (z - p[2]) * (z - p[2])),
        JP_LIM_MM, k);
    if (n != NULL) {
        judge_stat_add(&st_normal, judge_angle_deg(n, nr), JP_LIM_DEG, k);
    }
}

void judge_plane_run_end(int complete)
{
    if (run_on && complete && run_next != run_points) {
        cov_err++;
    }
    run_on = 0;
}

void judge_plane_report(FILE *f, int *passed, int *failed)
{
    if (runs == 0u) {
        return;
    }
    fprintf(f, "  judge plane: %u run(s), %lu points, reference tests/ref_plane.c\n", runs, seen);
    judge_stat_row(f, passed, failed, "plane", "point", &st_point, JP_LIM_MM, "mm", 1);
    judge_stat_row(f, passed, failed, "plane", "normal", &st_normal, JP_LIM_DEG, "deg", 1);
    fprintf(f, "  %s judge plane-coverage %lu point(s), %lu order/coverage errors\n",
            cov_err == 0ul ? "PASS" : "FAIL", seen, cov_err);
    if (cov_err == 0ul) {
        (*passed)++;
    } else {
        (*failed)++;
    }
}
