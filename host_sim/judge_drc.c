/* judge_drc.c - host_sim's judge of SURFACE DRC streams (judge.h).
 * SPDX-License-Identifier: MIT
 *
 * Stub until the model lands: every job line of the model is "cannot model", so a
 * run of this SURFACE is reported unchecked (a failed check), never silently passed.
 */
#include "judge.h"

static unsigned runs;

void judge_drc_reset(void)
{
    runs = 0;
}

int judge_drc_job_line(const char *line)
{
    (void)line;
    return -1;
}

void judge_drc_run_begin(uint32_t points, uint32_t first, int mode, unsigned n, unsigned steps,
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

void judge_drc_point(uint32_t k, double x, double y, double z, const double *n)
{
    (void)k;
    (void)x;
    (void)y;
    (void)z;
    (void)n;
}

void judge_drc_run_end(int complete)
{
    (void)complete;
}

void judge_drc_report(FILE *f, int *passed, int *failed)
{
    (void)passed;
    if (runs > 0u) {
        fprintf(f, "  judge drc: not modelled, %u run(s) unchecked\n", runs);
        (*failed)++;
    }
}
