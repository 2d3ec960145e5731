/* judge_gsr.c - host_sim's judge of SURFACE GSR streams (judge.h).
 * SPDX-License-Identifier: MIT
 *
 * Stub until the model lands: every job line of the model is "cannot model", so a
 * run of this SURFACE is reported unchecked (a failed check), never silently passed.
 */
#include "judge.h"

static unsigned runs;

void judge_gsr_reset(void)
{
    runs = 0;
}

int judge_gsr_job_line(const char *line)
{
    (void)line;
    return -1;
}

void judge_gsr_run_begin(uint32_t points, uint32_t first, int mode, unsigned n, unsigned steps,
                          unsigned link)
{
    (void)points;
    (void)first;
    (void)mode;
    (void)n;
    (void)steps;
    (void)link;
    runs++;
}

void judge_gsr_point(uint32_t k, double x, double y, double z, const double *n)
{
    (void)k;
    (void)x;
    (void)y;
    (void)z;
    (void)n;
}

void judge_gsr_run_end(int complete)
{
    (void)complete;
}

void judge_gsr_report(FILE *f, int *passed, int *failed)
{
    (void)passed;
    if (runs > 0u) {
        fprintf(f, "  judge gsr: not modelled, %u run(s) unchecked\n", runs);
        (*failed)++;
    }
}
