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
 * Test hook: env SIM_JUDGE_PERTURB_K=k moves point k 5 um in x before any judge sees it,
 * so a suite can prove that every judge fails on a wrong point (sim_suite.sh models).
 */
#include "sim_check.h"
#include "judge.h"

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

void sim_check_init(void)
{
    const char *pk = getenv("SIM_JUDGE_PERTURB_K");
    unsigned i;
    perturb_k = pk != NULL ? strtol(pk, NULL, 10) : -1;
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
    rm = surface != 0u ? judges[surface].job_line(line) : 0;
    rb = judges[0].job_line(line);
    return rm != 0 ? rm : rb;
}

void sim_check_run_begin(uint32_t points, uint32_t first, int mode, unsigned n, unsigned steps,
                         unsigned link)
{
    runs++;
    judges[surface].run_begin(points, first, mode, n, steps, link);
}

const char *sim_check_surface(void)
{
    return judges[surface].word;
}

void sim_check_point(uint32_t k, double x, double y, double z, const double *n)
{
    if (perturb_k >= 0 && (long)k == perturb_k) {
        x += 0.005;
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
