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
 *   SURFACE CANAL | GSR | CHANNEL | DRC   the model RUN streams (default CANAL); a new
 *                             SURFACE starts that model's geometry afresh (path.h)
 * Every command validates its arguments at once; the geometry is validated at RUN
 * (toolpath_init), each failure with its own wire status (cp_status.def).
 * A model's own geometry commands (job_<m>.c) need its SURFACE first (error:24).
 */
#ifndef JOB_H
#define JOB_H

#include "cp_status.h"
#include "path.h"

enum job_format { JOB_GCODE = 0, JOB_FRAMES = 1 };

#define JOB_HAVE_CURVE 0x01u
#define JOB_HAVE_RADIUS 0x02u
#define JOB_HAVE_RASTER 0x04u
#define JOB_HAVE_ALL 0x07u /* what the canal needs */
/* have bits of the other models' geometry commands (their `need` in job.c) */
#define JOB_HAVE_GSR_MASK 0x0038u     /* 0x0008, 0x0010, 0x0020 */
#define JOB_HAVE_CHANNEL_MASK 0x01C0u /* 0x0040, 0x0080, 0x0100 */
#define JOB_HAVE_DRC_MASK 0x0E00u     /* 0x0200, 0x0400, 0x0800 */
#define JOB_HAVE_CHANNEL_SECTION 0x0040u /* SURFACE CHANNEL: at least one SECTION */
#define JOB_HAVE_DRC_POINTS 0x0200u      /* SURFACE DRC: at least one POINT */
#define JOB_HAVE_GSR_CENTER 0x0008u /* SURFACE GSR: CENTER X|Y|Z, or all four CENTER P<i> */
#define JOB_HAVE_GSR_RADII 0x0010u  /* SURFACE GSR: RADII N and RADII B */
#define JOB_HAVE_GSR_FRAME 0x0020u  /* SURFACE GSR: FRAME */

/* Most tokens of one command line (keyword included). */
#define JOB_MAX_TOKENS 20u

#define JOB_RXBUF_MIN 96u /* >= the longest stream line (proto.h PROTO_GCODE_MAX) */
#define JOB_RXBUF_MAX 1024u
#define JOB_FEED_MAX CP_R(1.0e6)
#define JOB_FEED_MIN CP_R(0.05) /* smallest non-zero FEED: F is printed with 1 decimal */

/* Returned by job_command for a line that is not a job command (e.g. RUN, $I). */
#define JOB_NOT_MINE (-1)
/* Returned by job_line for RUN (alone on its line) or RESUME k: the protocol's run. */
#define JOB_RUN (-2)

struct job {
    struct toolpath_cfg cfg; /* raster (every model) and canal geometry, C units (radians) */
    union path_geom geom;    /* geometry of the other models (the one of `kind`) */
    cp_real feed;            /* mm/min, 0 = omit F */
    uint16_t rxbuf;          /* machine RX buffer, bytes */
    uint16_t have;           /* JOB_HAVE_* bits */
    uint8_t kind;            /* enum path_kind (SURFACE), default PATH_CANAL */
    uint8_t format;          /* enum job_format */
    uint8_t checksum;        /* 1: N<n> ... *<cs> line numbers and checksums */
};

/* Most numbers of one command (SECTION's 9). */
#define JOB_MAX_NUMBERS 9u

/* One command line as job_command has checked it for a model's command hook: the
 * keyword, the word after it (if the command takes one), the arity and every number
 * are already valid (the wire status of the first failure is answered before the
 * hook is called). */
struct job_args {
    unsigned cmd;               /* the command: the index of its keyword in the model's list */
    unsigned sub;               /* index of the word after it in the command's word list
                                   (a number instead, THICKEN K: the list's length) */
    unsigned na;                /* numbers in v[] */
    uint32_t u;                 /* the unsigned number: THICKEN K (and the canal's STEPS,
                                   RXBUF, LINES/CIRCLES n) */
    cp_real v[JOB_MAX_NUMBERS]; /* the numbers, in line order */
};

/* A model's command hook, int job_<m>_command(struct job *j, struct job_args *a),
 * called directly from job.c when j->kind is the model's: apply the command to j->geom
 * (set its JOB_HAVE_* bits) and return a wire status (a->v may serve as scratch). The
 * keywords, their words and number counts are in job.c's table (`words`), in the order
 * of a->cmd and a->sub. */

/* SURFACE CHANNEL (job_channel.c): SECTION, AXES, SECTIONS CLEAR; defaults: no section. */
int job_channel_command(struct job *j, struct job_args *a);
void job_channel_defaults(union path_geom *g);

/* SURFACE GSR (job_gsr.c): CENTER, RADII, FRAME, FORM; defaults: centre 0, f_t(u) = u,
 * FRAME FIXED (not set), FORM RATIONAL. */
int job_gsr_command(struct job *j, struct job_args *a);
void job_gsr_defaults(union path_geom *g);

/* SURFACE DRC (job_drc.c): POINT, POINTS CLEAR, THICKEN, EDGE; defaults: no point,
 * THICKEN AUTO, EDGE OFF. */
int job_drc_command(struct job *j, struct job_args *a);
void job_drc_defaults(union path_geom *g);

/* Defaults: nothing set, TOL 1 um, FORMAT GCODE, RXBUF 128, CHECKSUM OFF, TOOL NONE. */
void job_init(struct job *j);

/* Apply one command line (trimmed, no terminator). Returns a wire status
 * (CP_ST_OK or an error; the job is unchanged on error), or JOB_NOT_MINE (also for
 * RUN and RESUME, the protocol's commands). */
int job_command(struct job *j, const char *line, size_t len);

/* job_command for the protocol: the same, except that RUN alone on its line (RUN with
 * anything after it is JOB_NOT_MINE) and RESUME k return JOB_RUN with *first = 0 or k
 * (the job is unchanged). RESUME checks as the other commands: error:3 unless exactly
 * one argument, error:4 if k is not an unsigned decimal number, error:21 above
 * 2^32 - 1 (proto.c checks k against the run's point count). */
int job_line(struct job *j, const char *line, size_t len, uint32_t *first);

/* CP_ST_OK if the job has everything its SURFACE needs, else CP_ST_NO_JOB. */
int job_ready(const struct job *j);

/* 1 if the line starts with a job command keyword (CURVE ... CHECKSUM, SURFACE, a
 * model's keyword, RUN, RESUME). */
int job_is_command(const char *line, size_t len);

/* The surface models of this build for $I: "CANAL" and, when compiled in (cp_config.h
 * CP_WITH_*), "+GSR", "+CHANNEL", "+DRC" in that order, e.g. "CANAL+GSR". */
const char *job_models(void);

#endif /* JOB_H */
