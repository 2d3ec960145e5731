/* sim_check.c - host_sim as the judge (stub: replaced by the full model).
 * SPDX-License-Identifier: MIT
 */
#include "sim_check.h"

static unsigned long points_seen;

void sim_check_init(void)
{
    points_seen = 0;
}

int sim_check_job_line(const char *line)
{
    (void)line;
    return 0;
}

void sim_check_run_begin(uint32_t points, uint32_t first, int mode, unsigned n, unsigned steps,
                         unsigned link)
{
    (void)points;
    (void)first;
    (void)mode;
    (void)n;
    (void)steps;
    (void)link;
}

void sim_check_point(uint32_t k, double x, double y, double z, const double *n)
{
    (void)k;
    (void)x;
    (void)y;
    (void)z;
    (void)n;
    points_seen++;
}

void sim_check_run_end(int complete)
{
    (void)complete;
}

void sim_check_report(FILE *f, int *passed, int *failed)
{
    (void)f;
    (void)passed;
    (void)failed;
}
