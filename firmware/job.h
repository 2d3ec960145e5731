/* job.h - the fillet job assembled from protocol commands (docs/PROTOCOL.md).
 * SPDX-License-Identifier: MIT
 *
 * Commands (case-insensitive keywords; numbers in mm, angles in degrees):
 *   CURVE LINE x0 y0 x1 y1 | CURVE ARC cx cy r a0 a1 | CURVE ELLIPSE cx cy A B a0 a1
 *   CURVE BEZIER x0 y0 x1 y1 x2 y2 x3 y3
 *   RADIUS CONST c | RADIUS LINEAR r0 r1 | RADIUS COS b c k | RADIUS CUBIC r0 r1 r2 r3
 *   TOOL BALL r [TIP|CENTRE] | TOOL NONE
 *   LINES n u0 u1             family-2 lines, start angles u0..u1 (deg, |u| <= 180) on the first
 * circle CIRCLES n u0 u1 [PATCH]   family-1 arcs at n evenly spaced t over contact angles u0..u1
 *                             (PATCH: between the family-2 lines that start at u0 and u1)
 *   STEPS m | TOL chord_um    fixed steps per line, or a chord tolerance (default TOL 1)
 *   FEED f                    mm/min on every G1 (0 = no F word)
 *   FORMAT GCODE | FRAMES
 *   RXBUF n                   the machine's RX buffer for character counting (32..1024, default
 * 128) CHECKSUM ON | OFF         Marlin-style N<n> ... *<cs> lines and Resend: handling (GCODE)
 * Every command validates its arguments at once; the geometry is validated at RUN
 * (toolpath_init), each failure with its own wire status (cp_status.def).
 */
#ifndef JOB_H
#define JOB_H

#include "cp_status.h"
#include "toolpath.h"

enum job_format { JOB_GCODE = 0, JOB_FRAMES = 1 };

#define JOB_HAVE_CURVE 0x01u
#define JOB_HAVE_RADIUS 0x02u
#define JOB_HAVE_RASTER 0x04u
#define JOB_HAVE_ALL 0x07u

#define JOB_RXBUF_MIN 96u /* >= the longest stream line (proto.h PROTO_GCODE_MAX) */
#define JOB_RXBUF_MAX 1024u
#define JOB_FEED_MAX CP_R(1.0e6)
#define JOB_FEED_MIN CP_R(0.05) /* smallest non-zero FEED: F is printed with 1 decimal */

/* Returned by job_command for a line that is not a job command (e.g. RUN, $I). */
#define JOB_NOT_MINE (-1)

struct job {
    struct toolpath_cfg cfg; /* geometry and raster, C units (radians) */
    cp_real feed;            /* mm/min, 0 = omit F */
    uint16_t rxbuf;          /* machine RX buffer, bytes */
    uint8_t have;            /* JOB_HAVE_* bits */
    uint8_t format;          /* enum job_format */
    uint8_t checksum;        /* 1: N<n> ... *<cs> line numbers and checksums */
};

/* Defaults: nothing set, TOL 1 um, FORMAT GCODE, RXBUF 128, CHECKSUM OFF, TOOL NONE. */
void job_init(struct job *j);

/* Apply one command line (trimmed, no terminator). Returns a wire status
 * (CP_ST_OK or an error; the job is unchanged on error), or JOB_NOT_MINE. */
int job_command(struct job *j, const char *line, size_t len);

/* 1 if the line starts with a job command keyword (CURVE ... CHECKSUM, RUN, RESUME). */
int job_is_command(const char *line, size_t len);

/* Wire status of an enum cp_err returned by toolpath_init. */
int job_status_of(int cp_err);

#endif /* JOB_H */
