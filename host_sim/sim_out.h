/* sim_out.h - host_sim outputs: every received point as CSV, the G-code program,
 * an SVG of the toolpath a machinist reads: top view to scale (mm axes, origin, the part's
 * extent), isometric view (X/Y/Z axes at true length), one colour per family, link and
 * rapid moves dashed, the start point, a legend and a caption of the job's model and run.
 * SPDX-License-Identifier: MIT
 *
 * Points are kept as received: coordinates in 0.1 um (int32), the normal in
 * 1/32767 (FRAMES only), line (-1 = link move) and index. The CSV is written as the
 * points arrive (so a resumed run simply continues the same file); the SVG and the
 * G-code trailer (M2) are written by sim_out_close().
 */
#ifndef SIM_OUT_H
#define SIM_OUT_H

#include <stdint.h>

struct sim_out_pt {
    int32_t x, y, z; /* 0.1 um */
    int16_t n[3];    /* 1/32767 (valid if has_n) */
    int32_t line;    /* -1: link move */
    uint32_t index;
    int has_n;
};

/* Open the requested files (any may be NULL). Returns 0 or -1 (message on stderr). */
int sim_out_open(const char *csv, const char *gcode, const char *svg);

/* One point received intact, in stream order. */
void sim_out_point(const struct sim_out_pt *p);

/* A G-code body line without the N and * decorations (GCODE runs); the preamble is
 * written only once. FRAMES runs get G1 lines synthesised by sim_out_point. */
void sim_out_gcode(const char *body);

/* A run starts (the "[RUN:...]" header or the BEGIN frame): surface is the SURFACE word of
 * the job (sim_check_surface()), mode 0 = LINES (family 2), 1 = CIRCLES (family 1). A run
 * whose first point does not continue the previous run's last k (a new RUN, not a RESUME)
 * is reached by a rapid move in the SVG. Up to SIM_OUT_RUNS_MAX runs are drawn apart;
 * later ones join the last. */
#define SIM_OUT_RUNS_MAX 64
void sim_out_run_begin(const char *surface, uint32_t points, uint32_t first, int mode, unsigned n,
                       unsigned steps, unsigned link);

/* A job command the firmware answered ok: TOL, STEPS and TOOL are kept for the SVG's
 * caption (the last of TOL / STEPS wins, as in the firmware); other lines are ignored. */
void sim_out_job_line(const char *line);

/* Write the SVG and the trailer, close everything. Returns the points written. */
unsigned long sim_out_close(void);

/* Format v (0.1 um units) as "[-]I.FFFF" into buf; returns buf. */
const char *sim_out_fixed4(int32_t v, char *buf);

#endif /* SIM_OUT_H */
