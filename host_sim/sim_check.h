/* sim_check.h - host_sim as the judge: every received point against host_sim's own
 * independent double-precision model of the job's surface model (tests/ref_<m>.c; no
 * firmware code). This is the model-independent front: the SURFACE word picks a row of
 * the judge table (judge.h, one row per firmware/models/models.def line, judge_<m>.c).
 * SPDX-License-Identifier: MIT
 *
 * Call order, per run of host_sim:
 *   sim_check_init()
 *   sim_check_job_line(line)     for every job command line sent (SURFACE, CURVE, RADIUS,
 *                                TOOL, LINES, CIRCLES, STEPS, TOL, ...; others are ignored)
 *   per RUN / RESUME:
 *     sim_check_run_begin(...)   from the "[RUN:...]" header (GCODE) or BEGIN frame (FRAMES)
 *     sim_check_point(k, ...)    for every received point, in arrival order
 *     sim_check_run_end()        coverage of this run
 *   sim_check_report(...)        prints the table and adds its checks to the counts
 * Checks of the canal judge (judge_canal.c; the other judges' in their files), each one a
 * pass/fail line in the table, with max and RMS:
 *   surface   distance of the point (tool centre recovered for TOOL outputs) to the
 *             canal (offset) surface, i.e. | |p - rho(t)| - (R(t) - r_tool) |
 *   line      distance to the true curvature line: the reference point of the same
 *             line at the same t (family 2), or of the same circle (family 1, links)
 *   ortho     angle between the streamed line's direction and the circle, deg
 *   chord     sagitta of each streamed segment against the reference curve
 *   coverage  every point k = first .. points-1 exactly once, in order
 */
#ifndef SIM_CHECK_H
#define SIM_CHECK_H

#include <stdint.h>
#include <stdio.h>

void sim_check_init(void);

/* A job command as sent to the firmware (no newline). Returns 0; -1 if the judge
 * cannot model it (then the run is reported as unchecked: a failed check).
 * Returns 1 for a job command with bad arguments (arity, number, keyword, range, as
 * firmware/job/job.c checks them): the firmware must answer error and the model is left
 * unchanged, exactly as the firmware leaves its job. Non-job lines return 0. */
int sim_check_job_line(const char *line);

/* A run starts: the header/BEGIN values as sent by the firmware.
 * mode: 0 = LINES, 1 = CIRCLES; overlap: the header's overlap flag (judge_run_overlap). */
void sim_check_run_begin(uint32_t points, uint32_t first, int mode, unsigned n, unsigned steps,
                         unsigned link, int overlap);

/* The SURFACE word of the active row ("CANAL" until a SURFACE line selects another). */
const char *sim_check_surface(void);

/* One received point k (ordinal in the job), mm; n is the unit normal (FRAMES) or
 * NULL (GCODE). Values are as received (quantized to 0.1 um). */
void sim_check_point(uint32_t k, double x, double y, double z, const double *n);

/* The run ended (complete or not). complete = 1 if the firmware answered ok. */
void sim_check_run_end(int complete);

/* Print the table (one row per check: max, RMS, limit, pass/fail) to f and add
 * the number of passed and failed checks. Rows without samples (ortho of CIRCLES
 * span ANGLE, runs stopped before a second point) and chord of a STEPS job (no
 * limit) are printed as INFO and not counted; normal only when normals arrived
 * (FRAMES); coverage is always counted. No run at all: one line, nothing counted. */
void sim_check_report(FILE *f, int *passed, int *failed);

#endif /* SIM_CHECK_H */
