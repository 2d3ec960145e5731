/* sim_check.c - host_sim as the judge: the model-independent part. The job's SURFACE picks
 * one row of the judge table (one row per line of firmware/models/models.def, judge.h); the
 * judges themselves are host_sim/judge_<name>.c, each with its own independent
 * double-precision model (tests/ref_<name>.c).
 * SPDX-License-Identifier: MIT
 *
 * Routing (sim_check.h call order):
 *   init         every row's reset(1); SURFACE is row 0 (the canal, the firmware's default)
 *   job_line     "SURFACE <WORD>" selects the row of WORD and calls its reset(0) (1: no such
 *                word or not one argument: the firmware answers error); any other line
 *                goes to the active row and to row 0 (the base job: the raster commands
 *                stay in the canal job whatever the SURFACE); the first nonzero answer wins
 *   run_begin, point, run_end   the active row
 *   report       rows 1.. in table order, then row 0, then "judge: no run" if no row had one
 * Placement (PLACE x y z [rz], TILT axis_deg angle_deg: docs/PROTOCOL.md "Placement on the
 * part"): this router keeps them (checked here, independently: a line out of range leaves
 * them unchanged, as the firmware answers error:6; SURFACE keeps them, as the firmware does)
 * and takes every received point and normal back to the part's frame before the model's
 * judge sees it, p = Rz(-rz) T(a, -tilt) (p' - off), n likewise without off, in double
 * with its own code (Rodrigues' vector form, libm): every judge works unchanged on placed
 * jobs.
 * Test hooks: env SIM_JUDGE_PERTURB_K=k moves point k 5 um in x before any judge sees it,
 * so a suite can prove that every judge fails on a wrong point (sim_suite.sh models);
 * env SIM_PLACE_SKEW_DEG=d turns the judge's inverse by d degrees more about Z (a wrong
 * rz), so a suite can prove that a wrong placement in the firmware fails the judge.
 */
#include "sim_check.h"
#include "judge.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define CP_MODEL(NAME, name, WITH, WORD)                                                           \
    {.word = WORD,                                                                                 \
     .reset = judge_##name##_reset,                                                                \
     .job_line = judge_##name##_job_line,                                                          \
     .run_begin = judge_##name##_run_begin,                                                        \
     .point = judge_##name##_point,                                                                \
     .run_end = judge_##name##_run_end,                                                            \
     .report = judge_##name##_report},
static const struct judge judges[] = {
#include "models.def"
};
#undef CP_MODEL

#define N_JUDGES (sizeof judges / sizeof judges[0])
#define SC_LINE_MAX 128u /* longer than any command the firmware accepts (error:2) */

static unsigned surface; /* the active row */
static unsigned runs;    /* runs of every row */
/* Test hook (env SIM_JUDGE_PERTURB_K=k): point k is judged 5 um off in x. -1: off. */
static long perturb_k = -1;

/* PLACE and TILT as the firmware holds them (degrees as given); all 0: no placement */
static struct {
    double off[3], rz, axis, tilt;
    double skew; /* test hook SIM_PLACE_SKEW_DEG: added to rz in the inverse */
} place;

#define SC_PI 3.14159265358979323846

/* v <- v rotated by ang (radians) about the unit axis a (right hand): Rodrigues, the
 * vector form v cos + (a x v) sin + a (a . v)(1 - cos). */
static void rot_about(double *v, const double *a, double ang)
{
    double c = cos(ang), s = sin(ang), d = a[0] * v[0] + a[1] * v[1] + a[2] * v[2];
    double x[3] = {a[1] * v[2] - a[2] * v[1], a[2] * v[0] - a[0] * v[2], a[0] * v[1] - a[1] * v[0]};
    int i;
    for (i = 0; i < 3; i++) {
        v[i] = v[i] * c + x[i] * s + a[i] * d * (1.0 - c);
    }
}

/* The inverse placement of a received vector (with_off: a point, else a normal). */
static void place_inverse(double *v, int with_off)
{
    const double d = SC_PI / 180.0;
    const double z[3] = {0.0, 0.0, 1.0};
    double a[3];
    int i;
    a[0] = cos(place.axis * d);
    a[1] = sin(place.axis * d);
    a[2] = 0.0;
    for (i = 0; with_off && i < 3; i++) {
        v[i] -= place.off[i];
    }
    rot_about(v, a, -place.tilt * d);
    rot_about(v, z, -(place.rz + place.skew) * d);
}

/* PLACE x y z [rz] | TILT axis_deg angle_deg (the firmware's ranges, docs/PROTOCOL.md):
 * 0 when kept, 1 when the firmware must answer error (placement unchanged). */
static int place_line(const char *line)
{
    char buf[SC_LINE_MAX], *tok[JUDGE_MAX_TOKENS + 1u];
    double v[4];
    int nt = judge_split(line, buf, sizeof buf, tok), i;
    if (nt < 1) {
        return 1;
    }
    if (judge_kw(tok[0], "TILT")) {
        if (nt != 3 || judge_nums(tok, 1u, 2u, v) || fabs(v[0]) > 360.0 || fabs(v[1]) > 90.0) {
            return 1;
        }
        place.axis = v[0];
        place.tilt = v[1];
        return 0;
    }
    if (nt < 4 || nt > 5 || judge_nums(tok, 1u, (unsigned)nt - 1u, v)) {
        return 1;
    }
    for (i = 0; i < 3; i++) {
        if (fabs(v[i]) > 1000.0) {
            return 1;
        }
    }
    if (nt == 5 && fabs(v[3]) > 360.0) {
        return 1;
    }
    for (i = 0; i < 3; i++) {
        place.off[i] = v[i];
    }
    place.rz = nt == 5 ? v[3] : 0.0;
    return 0;
}

void sim_check_init(void)
{
    const char *pk = getenv("SIM_JUDGE_PERTURB_K"), *sk = getenv("SIM_PLACE_SKEW_DEG");
    unsigned i;
    perturb_k = pk != NULL ? strtol(pk, NULL, 10) : -1;
    memset(&place, 0, sizeof place);
    place.skew = sk != NULL ? strtod(sk, NULL) : 0.0;
    surface = 0;
    runs = 0;
    for (i = 0; i < N_JUDGES; i++) {
        judges[i].reset(1);
    }
}

/* SURFACE tok[1] (nt tokens): 0, or 1 when the firmware must answer error. */
static int select_surface(char **tok, unsigned nt)
{
    unsigned i;
    if (nt != 2u) {
        return 1;
    }
    for (i = 0; i < N_JUDGES; i++) {
        if (judge_kw(tok[1], judges[i].word)) {
            surface = i;
            judges[i].reset(0);
            return 0;
        }
    }
    return 1;
}

int sim_check_job_line(const char *line)
{
    char buf[SC_LINE_MAX], *tok[3];
    unsigned nt;
    int rm, rb;
    size_t L = strlen(line);
    if (L >= sizeof buf) {
        return 0;
    }
    memcpy(buf, line, L + 1u);
    nt = judge_words(buf, tok, 2u);
    if (nt == 0u) {
        return 0;
    }
    if (judge_kw(tok[0], "SURFACE")) {
        return select_surface(tok, nt);
    }
    if (judge_kw(tok[0], "PLACE") || judge_kw(tok[0], "TILT")) {
        return place_line(line); /* the router's own: no judge sees it */
    }
    rm = surface != 0u ? judges[surface].job_line(line) : 0;
    rb = judges[0].job_line(line);
    return rm != 0 ? rm : rb;
}

static int run_overlap; /* the header's overlap flag of the current run */

int judge_run_overlap(void)
{
    return run_overlap;
}

void sim_check_run_begin(uint32_t points, uint32_t first, int mode, unsigned n, unsigned steps,
                         unsigned link, int overlap)
{
    runs++;
    run_overlap = overlap != 0;
    judges[surface].run_begin(points, first, mode, n, steps, link);
}

const char *sim_check_surface(void)
{
    return judges[surface].word;
}

void sim_check_point(uint32_t k, double x, double y, double z, const double *n)
{
    double p[3], nv[3];
    if (perturb_k >= 0 && (long)k == perturb_k) {
        x += 0.005;
    }
    if (place.off[0] != 0.0 || place.off[1] != 0.0 || place.off[2] != 0.0 || place.rz != 0.0 ||
        place.tilt != 0.0 || place.skew != 0.0) {
        p[0] = x, p[1] = y, p[2] = z;
        place_inverse(p, 1);
        x = p[0], y = p[1], z = p[2];
        if (n != NULL) {
            memcpy(nv, n, sizeof nv);
            place_inverse(nv, 0);
            n = nv;
        }
    }
    judges[surface].point(k, x, y, z, n);
}

void sim_check_run_end(int complete)
{
    judges[surface].run_end(complete);
}

void sim_check_report(FILE *f, int *passed, int *failed)
{
    unsigned i;
    for (i = 1; i < N_JUDGES; i++) {
        judges[i].report(f, passed, failed);
    }
    judges[0].report(f, passed, failed); /* the base job's table closes the report */
    if (runs == 0u) {
        fprintf(f, "  judge: no run, nothing judged\n");
    }
}
