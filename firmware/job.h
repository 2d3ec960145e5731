/* job.h - the fillet job assembled from protocol commands (docs/PROTOCOL.md).
 * SPDX-License-Identifier: MIT
 *
 * Commands (case-insensitive keywords; numbers in mm, angles in degrees; the full list,
 * with the models' own commands, is firmware/commands.def):
 *   CURVE LINE x0 y0 x1 y1 | ARC cx cy r a0 a1 | ELLIPSE cx cy A B a0 a1
 *         | BEZIER x0 y0 x1 y1 x2 y2 x3 y3
 *   RADIUS CONST c | LINEAR r0 r1 | COS b c k | CUBIC r0 r1 r2 r3
 *   TOOL BALL r [TIP|CENTRE|CENTER] | TOOL NONE
 *   LINES n u0 u1            family-2 lines, start angles u0..u1 (|u| <= 180) on the
 *                            first circle
 *   CIRCLES n u0 u1 [PATCH]  family-1 arcs at n evenly spaced t over contact angles
 *                            u0..u1 (PATCH: between the family-2 lines that start at u0, u1)
 *   STEPS m | TOL chord_um   fixed steps per line, or a chord tolerance (default TOL 1)
 *   FEED f                   mm/min on every G1 (0 = no F word)
 *   FORMAT GCODE | FRAMES
 *   RXBUF n                  the machine's RX buffer for character counting
 *                            (JOB_RXBUF_MIN..JOB_RXBUF_MAX = 96..1024, default 128)
 *   CHECKSUM ON | OFF        Marlin-style N<n> ... *<cs> lines and Resend: handling (GCODE)
 *   SURFACE CANAL | GSR | CHANNEL | DRC   the model RUN streams (default CANAL; the words
 *                            of models.def); a new SURFACE starts that model's geometry
 *                            afresh (path.h)
 * Every command is a row of commands.def (its keyword, argument shape, words and
 * owner). Every command validates its arguments at once; the geometry is validated at
 * RUN (path_init), each failure with its own wire status (cp_status.def).
 * A model's own geometry commands (job_<m>.c) need its SURFACE first (error:24).
 */
#ifndef JOB_H
#define JOB_H

#include "cp_status.h"
#include "path.h"

enum job_format { JOB_GCODE = 0, JOB_FRAMES = 1 };

/* have bits: what the commands set, and what RUN needs (job_<m>_ready). The canal's and
 * the raster's (every model's, kept by SURFACE), then each model's own (cleared by
 * SURFACE, which starts a model's geometry afresh). */
#define JOB_HAVE_CURVE 0x01u
#define JOB_HAVE_RADIUS 0x02u
#define JOB_HAVE_RASTER 0x04u
#define JOB_HAVE_ALL 0x07u               /* what the canal needs; the bits SURFACE keeps */
#define JOB_HAVE_GSR_MASK 0x0038u        /* 0x0008, 0x0010, 0x0020 */
#define JOB_HAVE_CHANNEL_MASK 0x01C0u    /* 0x0040, 0x0080, 0x0100 */
#define JOB_HAVE_DRC_MASK 0x0E00u        /* 0x0200, 0x0400, 0x0800 */
#define JOB_HAVE_CHANNEL_SECTION 0x0040u /* SURFACE CHANNEL: at least one SECTION */
#define JOB_HAVE_DRC_POINTS 0x0200u      /* SURFACE DRC: at least one POINT */
#define JOB_HAVE_GSR_CENTER 0x0008u      /* SURFACE GSR: CENTER X|Y|Z, or all four CENTER P<i> */
#define JOB_HAVE_GSR_RADII 0x0010u       /* SURFACE GSR: RADII N and RADII B */
#define JOB_HAVE_GSR_FRAME 0x0020u       /* SURFACE GSR: FRAME */

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

/* The commands, one per CP_CMD row of commands.def: <OWNER>_CMD_<NAME>, e.g.
 * CANAL_CMD_CURVE, JOB_CMD_SURFACE, PROTO_CMD_RESUME, CHANNEL_CMD_SECTIONS_CLEAR. */
enum job_cmd {
#define CP_CMD(OWNER, NAME, KEYWORD, SHAPE, MIN, MAX, SURFACE) OWNER##_CMD_##NAME,
#define CP_CMD_WORD(CMD, WORD, TEXT, NUMBERS, VALUE)
#define CP_CMD_OPTION(CMD, WORD, TEXT, VALUE)
#include "commands.def"
#undef CP_CMD
#undef CP_CMD_WORD
#undef CP_CMD_OPTION
    JOB_CMDS
};

/* The words and options of the commands, one per CP_CMD_WORD / CP_CMD_OPTION row of
 * commands.def: JOB_WORD_<WORD>, e.g. JOB_WORD_CURVE_ARC, JOB_WORD_TOOL_CENTRE. */
enum job_word {
#define CP_CMD(OWNER, NAME, KEYWORD, SHAPE, MIN, MAX, SURFACE)
#define CP_CMD_WORD(CMD, WORD, TEXT, NUMBERS, VALUE) JOB_WORD_##WORD,
#define CP_CMD_OPTION(CMD, WORD, TEXT, VALUE) JOB_WORD_##WORD,
#include "commands.def"
#undef CP_CMD
#undef CP_CMD_WORD
#undef CP_CMD_OPTION
    JOB_WORDS,
    JOB_NO_WORD = JOB_WORDS, /* job_args.word: a number instead (THICKEN K); .option: none */
    JOB_BAD_WORD             /* job_args.option: a last word that is none of the command's */
};

/* How job_line checks a command's arguments, in this order: token count (error:3), words
 * (error:9), the count (parse_uint: error:4, above 2^32 - 1 error:6), the numbers
 * (parse_real: error:4/5/6), then the owner's hook checks ranges (error:6, 14, ...).
 * MIN, MAX: the CP_CMD row's columns. */
enum job_shape {
    JOB_ARGS_NUMBERS,              /* MIN..MAX numbers (TOL, FEED, SECTION, AXES, POINT) */
    JOB_ARGS_WORD,                 /* exactly one word of the list: arity first, then the
                                      word (FORMAT, CHECKSUM, SURFACE, SECTIONS, EDGE) */
    JOB_ARGS_WORD_THEN_NUMBERS,    /* a word of the list, then the numbers of its row
                                      (CURVE, RADIUS, CENTER, RADII, FRAME, FORM) */
    JOB_ARGS_WORD_NUMBERS_OPTION,  /* as WORD_THEN_NUMBERS, but a word without numbers takes
                                      nothing more (error:9), and one with numbers may end
                                      with an option word, which the hook checks after its
                                      ranges (JOB_BAD_WORD: error:9) (TOOL) */
    JOB_ARGS_COUNT_NUMBERS_OPTION, /* an unsigned count, MIN numbers, then, if the command
                                      has options, an optional option word, checked before
                                      the arity and the numbers (error:9) (LINES, CIRCLES) */
    JOB_ARGS_COUNT_OR_WORD,        /* exactly one token: a word of the list, or an unsigned
                                      count (STEPS, RXBUF, RESUME, THICKEN) */
    JOB_ARGS_ALONE                 /* nothing after the keyword; with anything after it the
                                      line is not a command (RUN) */
};

/* One command line as job_line has checked it for its owner's hook: the keyword, the
 * words, the arity and every number are valid (the wire status of the first failure is
 * answered before the hook is called). */
struct job_args {
    enum job_cmd cmd;           /* the command */
    enum job_word word;         /* the word after the keyword, JOB_NO_WORD if none (or a
                                   count instead: THICKEN K) */
    unsigned value;             /* VALUE of the word's row (0 without a word) */
    enum job_word option;       /* the option word: JOB_NO_WORD when absent, JOB_BAD_WORD
                                   when it is none of the command's (TOOL) */
    unsigned option_value;      /* VALUE of the option's row (0 without one) */
    unsigned na;                /* numbers in v[] */
    uint32_t u;                 /* the count (COUNT_* shapes), 0 without one */
    cp_real v[JOB_MAX_NUMBERS]; /* the numbers, in line order */
};

/* A model's hooks, one set per row of models.def (job_<name>.c), called directly from
 * job.c (no function pointers: the static stack analysis sees every edge):
 *   int  job_<m>_command(struct job *j, struct job_args *a)  a command of the model's
 *        (commands.def OWNER): apply it to the job (set its JOB_HAVE_* bits) and return
 *        a wire status; switch on a->cmd (<M>_CMD_*); a->v may serve as scratch
 *   void job_<m>_defaults(union path_geom *g)   SURFACE <m>: its geometry afresh
 *   int  job_<m>_ready(const struct job *j)     1 when the job has all RUN needs */

/* the canal (job_canal.c): CURVE, RADIUS (under every SURFACE); SURFACE CANAL keeps
 * everything; ready with CURVE, RADIUS and LINES or CIRCLES. */
int job_canal_command(struct job *j, struct job_args *a);
void job_canal_defaults(union path_geom *g);
int job_canal_ready(const struct job *j);

/* SURFACE CHANNEL (job_channel.c): SECTION, AXES, SECTIONS CLEAR; defaults: no section;
 * ready with a SECTION and LINES or CIRCLES. */
int job_channel_command(struct job *j, struct job_args *a);
void job_channel_defaults(union path_geom *g);
int job_channel_ready(const struct job *j);

/* SURFACE GSR (job_gsr.c): CENTER, RADII, FRAME, FORM; defaults: centre 0, f_t(u) = u,
 * FRAME FIXED (not set), FORM RATIONAL; ready with CENTER, RADII N and B, FRAME and
 * LINES or CIRCLES. */
int job_gsr_command(struct job *j, struct job_args *a);
void job_gsr_defaults(union path_geom *g);
int job_gsr_ready(const struct job *j);

/* SURFACE DRC (job_drc.c): POINT, POINTS CLEAR, THICKEN, EDGE; defaults: no point,
 * THICKEN AUTO, EDGE OFF; ready with a POINT (EDGE ON: and RADIUS). */
int job_drc_command(struct job *j, struct job_args *a);
void job_drc_defaults(union path_geom *g);
int job_drc_ready(const struct job *j);

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

/* 1 if the line starts with a job command keyword (a KEYWORD of commands.def whose
 * owner is compiled in: CURVE ... CHECKSUM, SURFACE, a model's keyword, RUN, RESUME). */
int job_is_command(const char *line, size_t len);

/* The surface models of this build for $I: the words of models.def's rows that are
 * compiled in (cp_config.h CP_WITH_*), in row order, joined by "+", e.g. "CANAL+GSR". */
const char *job_models(void);

#endif /* JOB_H */
