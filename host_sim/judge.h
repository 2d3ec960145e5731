/* judge.h - host_sim's judges of the models other than the canal (seeds 001-003).
 * SPDX-License-Identifier: MIT
 *
 * sim_check.c judges the canal itself and forwards to judge_<m>_* while the job's
 * SURFACE is <m> (SURFACE GSR | CHANNEL | DRC, docs/PROTOCOL.md). Each judge keeps
 * its own independent double-precision model (tests/ref_<m>.c, no firmware code)
 * and has the same contract as the sim_check_* function of the same suffix
 * (sim_check.h): job_line sees EVERY job line sent while its SURFACE is active
 * (its own geometry commands and the shared raster commands TOOL, LINES, CIRCLES,
 * STEPS, TOL, FEED, FORMAT, ...), returns 0 (modelled or not a job line), 1 (bad
 * arguments: the firmware must answer error, model unchanged) or -1 (cannot
 * model: the run is reported unchecked). reset is called on `SURFACE <m>` (the
 * firmware starts that model's geometry afresh); report prints its table rows and
 * adds its checks to the counts (coverage always counted, like the canal judge).
 */
#ifndef JUDGE_H
#define JUDGE_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#define JUDGE_DECLARE(m)                                                                          \
    void judge_##m##_reset(void);                                                                 \
    int judge_##m##_job_line(const char *line);                                                   \
    void judge_##m##_run_begin(uint32_t points, uint32_t first, int mode, unsigned n,             \
                               unsigned steps, unsigned link);                                    \
    void judge_##m##_point(uint32_t k, double x, double y, double z, const double *n);            \
    void judge_##m##_run_end(int complete);                                                       \
    void judge_##m##_report(FILE *f, int *passed, int *failed);

JUDGE_DECLARE(gsr)
JUDGE_DECLARE(channel)
JUDGE_DECLARE(drc)

/* Helpers shared by the judges (judge_util.c). */
#define JUDGE_MAX_TOKENS 24u
/* Split a job line into at most JUDGE_MAX_TOKENS tokens (spaces, tabs, CR, LF; a token
 * starting with '#' ends the line) in buf (>= strlen(line) + 1 bytes). Returns the
 * count, or -1 if the line does not fit buf. */
int judge_split(const char *line, char *buf, size_t bufsz, char **tok);
/* 1 if token a is keyword b (any case). */
int judge_kw(const char *a, const char *b);
/* Parse tok[first .. first+n-1] as finite numbers into v. 0 on success, 1 if one is
 * not a number or not finite. */
int judge_nums(char **tok, unsigned first, unsigned n, double *v);
/* Angle between two 3-vectors, degrees (atan2 of |a x b| and a.b: exact near 0). */
double judge_angle_deg(const double *a, const double *b);

/* One check of a judge: max (and where), RMS, samples over the limit. */
struct judge_stat {
    double max, sum2;
    unsigned long n, fails;
    uint32_t worst; /* k of the max */
};
/* Add sample v of point k; lim <= 0: no limit (an INFO row). A NaN sample fails. */
void judge_stat_add(struct judge_stat *s, double v, double lim, uint32_t k);
/* Print the row "PASS|FAIL judge <model>-<name> max .. rms .. limit .. n=.. worst k=.." and
 * count it; counted = 0 or no samples: an INFO row, not counted. */
void judge_stat_row(FILE *f, int *passed, int *failed, const char *model, const char *name,
                    const struct judge_stat *s, double lim, const char *unit, int counted);

#endif /* JUDGE_H */
