/* judge.h - host_sim's judges: one per surface model, one row each in sim_check.c's table.
 * SPDX-License-Identifier: MIT
 *
 * The rows come from firmware/models/models.def (CP_MODEL(NAME, name, WITH, "WORD")): model
 * <name> is judged by host_sim/judge_<name>.c, which defines the judge_<name>_* hooks
 * below, and its row is { "WORD", judge_<name>_reset, ..., judge_<name>_report }. Every
 * row is compiled in whatever WITH says (host_sim judges any firmware image; an image
 * without the model answers SURFACE <WORD> with an error). Each judge keeps its own
 * independent double-precision model (tests/ref_<name>.c, no firmware code).
 *
 * sim_check.c (sim_check.h) owns what is model-independent: the SURFACE word picks the
 * row; runs, points and run ends go to that row only; the report asks every row.
 * Row 0 (the canal) is the firmware's base job: the raster commands (TOOL, LINES,
 * CIRCLES, STEPS, TOL, ...) stay in it whatever the SURFACE, so it also sees every job
 * line while another model is active.
 *
 * The hooks, with the contract of the sim_check_* function of the same suffix:
 *   reset(session)  session = 1: once, before anything (the whole judge afresh);
 *                   session = 0: on `SURFACE <WORD>` (the firmware starts that model's
 *                   geometry afresh; the raster commands stay)
 *   job_line(line)  EVERY job line sent while its SURFACE is active (its own geometry
 *                   commands and the shared raster commands); 0 (modelled or not a job
 *                   line), 1 (bad arguments: the firmware must answer error, model
 *                   unchanged) or -1 (cannot model: the run is reported unchecked)
 *   run_begin, point, run_end   the runs of its SURFACE only
 *   report(f, passed, failed)   its table rows, its checks added to the counts; nothing
 *                   when it judged no run (sim_check.c prints the "no run" line)
 */
#ifndef JUDGE_H
#define JUDGE_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

struct judge {
    const char *word; /* SURFACE keyword, models.def "WORD" */
    void (*reset)(int session);
    int (*job_line)(const char *line);
    void (*run_begin)(uint32_t points, uint32_t first, int mode, unsigned n, unsigned steps,
                      unsigned link);
    void (*point)(uint32_t k, double x, double y, double z, const double *n);
    void (*run_end)(int complete);
    void (*report)(FILE *f, int *passed, int *failed);
};

#define JUDGE_DECLARE(m)                                                                          \
    void judge_##m##_reset(int session);                                                          \
    int judge_##m##_job_line(const char *line);                                                   \
    void judge_##m##_run_begin(uint32_t points, uint32_t first, int mode, unsigned n,             \
                               unsigned steps, unsigned link);                                    \
    void judge_##m##_point(uint32_t k, double x, double y, double z, const double *n);            \
    void judge_##m##_run_end(int complete);                                                       \
    void judge_##m##_report(FILE *f, int *passed, int *failed);

#define CP_MODEL(NAME, name, WITH, WORD) JUDGE_DECLARE(name)
#include "models.def"
#undef CP_MODEL

/* The canal's surface for sim_out.c's SVG (no tool offset) at normalized parameter tf in
 * [0, 1] and contact-frame angle u (radians), mm. 0 if CURVE/RADIUS are not modelled. */
int judge_canal_surface(double tf, double u, double p[3]);
/* The canal raster's angle range u0 <= u1 (radians, as in LINES/CIRCLES). 0 if none. */
int judge_canal_urange(double *u0, double *u1);

/* The overlap flag of the run being begun (issue 22): 1 when its "[RUN:...]" header ended
 * with ",overlap=1" or its BEGIN frame's byte 15 was 1 (the firmware reported far parts of
 * the sweep that meet, the tool inside), else 0. Valid in run_begin and until the next run
 * (sim_check.c). */
int judge_run_overlap(void);

/* Helpers shared by the judges (judge_util.c). */
#define JUDGE_MAX_TOKENS 24u
/* Split buf in place at spaces, tabs, CR and LF. Returns the number of tokens; the first
 * max + 1 of them are stored in tok (which holds max + 1 pointers). */
unsigned judge_words(char *buf, char **tok, unsigned max);
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
