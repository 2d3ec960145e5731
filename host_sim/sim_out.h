/* sim_out.h - host_sim outputs: every received point as CSV, the G-code program,
 * an SVG of the toolpath (top and isometric views).
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
    int32_t x, y, z;  /* 0.1 um */
    int16_t n[3];     /* 1/32767 (valid if has_n) */
    int32_t line;     /* -1: link move */
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

/* Write the SVG and the trailer, close everything. Returns the points written. */
unsigned long sim_out_close(void);

/* Format v (0.1 um units) as "[-]I.FFFF" into buf; returns buf. */
const char *sim_out_fixed4(int32_t v, char *buf);

#endif /* SIM_OUT_H */
