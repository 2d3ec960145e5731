/* job.h - the fillet job assembled from protocol commands (docs/PROTOCOL.md).
 * SPDX-License-Identifier: MIT
 *
 * Commands (case-insensitive keywords; numbers in mm, angles in degrees; the full list,
 * with the models' own commands, is firmware/job/commands.def):
 *   CURVE LINE x0 y0 x1 y1 | ARC cx cy r a0 a1 | ELLIPSE cx cy A B a0 a1
 *         | BEZIER x0 y0 x1 y1 x2 y2 x3 y3
 *   RADIUS CONST c | LINEAR r0 r1 | COS b c k | CUBIC r0 r1 r2 r3
 *   TOOL BALL r [TIP|CENTRE|CENTER] | TOOL NONE
 *   LINES n u0 u1            family-2 lines, start angles u0..u1 (|u| <= 180) on the
 *                            first circle
 *   CIRCLES n u0 u1 [PATCH]  family-1 arcs at n evenly spaced t over contact angles
 *                            u0..u1 (PATCH: between the family-2 lines that start at u0, u1)
 *   STEPS m | TOL chord_um   fixed steps per line, or a chord tolerance (default TOL 1)
 *   FEED f [plunge [link]]   mm/min of the cut, of the plunge to the first point and of
 *                            the link points (plunge and link default to f); GCODE needs
 *                            it (0: not set, RUN answers error:40)
 *   SAFE z                   the safe height, mm in table coordinates (after PLACE/TILT):
 *                            rapids happen there; GCODE needs it (error:41)
 *   SPINDLE rpm              M3 S<rpm> before the cut, M5 after it (0: no spindle words;
 *                            else 1..100000)
 *   WCS G54..G59             the work offset of the program (default G54)
 *   MACHINE GENERIC | GRBL | MARLIN | LINUXCNC   the dialect of the program and of the
 *                            machine's answers (machines.def; default GENERIC)
 *   LINK HOST | MACHINE      where the G-code program goes: up the host link (default: a
 *                            host that takes the G-code itself) or down the machine link
 *   TOOLAXIS OFF | AC lead side | IJK lead side   5-axis words on every G1: the streamed
 *                            normal tilted lead degrees along the travel and side degrees
 *                            to its left (|.| <= 60), as A/C table angles or as the tool
 *                            vector I J K (proto's toolaxis.h; the dialect must take them)
 *   FORMAT GCODE | FRAMES
 *   RXBUF n                  the machine's RX buffer for character counting
 *                            (JOB_RXBUF_MIN..JOB_RXBUF_MAX = 120..1024, default: the dialect's)
 *   CHECKSUM ON | OFF        Marlin-style N<n> ... *<cs> lines and Resend: handling (GCODE)
 *   PLACE x y z [rz]         the part's origin on the table (mm, |.| <= 1000) and its turn
 *                            about Z (degrees, |rz| <= 360, default 0); error:6 out of range
 *   TILT axis_deg angle_deg  the base plane inclined by angle_deg (|.| <= 90) about the
 *                            table line at axis_deg (|.| <= 360) through the part's origin
 *   JOB CLEAR                the defaults (job_init), but MACHINE and LINK (the cell's
 *                            wiring) stay; $J (the protocol's) prints the job
 *   SURFACE CANAL | GSR | CHANNEL | DRC   the model RUN streams (default CANAL; the words
 *                            of models.def); a new SURFACE starts that model's geometry
 *                            afresh (path.h)
 * Every command is a row of commands.def (its keyword, argument shape, words and
 * owner). Every command validates its arguments at once, with every check of the model's
 * init that needs the command alone (CURVE: canal_curve_check, RADIUS: canal_radius_check,
 * ...: the same code as at RUN); what needs the combination is validated at RUN
 * (path_init), each failure with its own wire status (cp_status.def).
 * A model's own geometry commands (job_<m>.c) need its SURFACE first (error:24).
 */
#ifndef JOB_H
#define JOB_H

#include "cp_status.h"
#include "path.h"

/* The output formats (FORMAT), one per row of outputs.def: JOB_GCODE, JOB_FRAMES. */
enum job_format {
#define CP_OUTPUT(NAME, name, WORD) JOB_##NAME,
#include "outputs.def"
#undef CP_OUTPUT
};

/* The machine dialects (MACHINE), one per row of machines.def: JOB_MACHINE_GENERIC, ... */
enum job_machine {
#define CP_MACHINE(NAME, WORD, RXBUF, LINE_MAX, ACKS, CHECKSUM, SPLIT, POLL, END, AC, IJK) JOB_MACHINE_##NAME,
#include "machines.def"
#undef CP_MACHINE
    JOB_MACHINES
};

/* TOOLAXIS: the 5-axis words of the program (job.toolaxis; proto's toolaxis.h). */
enum job_toolaxis { JOB_TOOLAXIS_OFF = 0, JOB_TOOLAXIS_AC = 1, JOB_TOOLAXIS_IJK = 2 };
#define JOB_TOOLAXIS_ANGLE_MAX CP_R(60.0) /* |lead|, |side| <= 60 degrees */

/* LINK: where the G-code program goes (job.link). */
enum job_link { JOB_LINK_HOST = 0, JOB_LINK_MACHINE = 1 };

/* have bits: what the canal's and the raster's commands set (every model's, kept by
 * SURFACE). A model's own progress is in its geometry (union path_geom), which SURFACE
 * starts afresh; job_<m>_ready reads both. */
#define JOB_HAVE_CURVE 0x01u  /* CURVE */
#define JOB_HAVE_RADIUS 0x02u /* RADIUS */
#define JOB_HAVE_RASTER 0x04u /* LINES or CIRCLES */
#define JOB_HAVE_ALL 0x07u    /* what the canal needs */

/* Most tokens of one command line (keyword included). */
#define JOB_MAX_TOKENS 20u

#define JOB_RXBUF_MIN 120u /* >= the longest stream line (out_gcode.h OUT_GCODE_LINE_MAX) */
#define JOB_RXBUF_MAX 1024u
#define JOB_FEED_MAX CP_R(1.0e6)
#define JOB_FEED_MIN CP_R(0.001) /* smallest non-zero FEED, mm/min (F is printed exactly) */
#define JOB_SAFE_MAX CP_R(1000.0) /* SAFE: |z| <= 1 m (mm) */
#define JOB_SPINDLE_MAX CP_R(100000.0) /* SPINDLE: 0 or 1..100000 rpm (printed plainly) */
#define JOB_PLACE_OFF_MAX CP_R(1000.0) /* PLACE: |x|, |y|, |z| <= 1 m (mm) */
#define JOB_PLACE_RZ_MAX CP_R(360.0)   /* PLACE: |rz| <= 360 deg */
#define JOB_TILT_AXIS_MAX CP_R(360.0)  /* TILT: |axis_deg| <= 360 */
#define JOB_TILT_MAX CP_R(90.0)        /* TILT: |angle_deg| <= 90 (a vertical face at most) */

/* PLACE and TILT as given (docs/PROTOCOL.md "Placement on the part"); all 0 (job_init):
 * no placement. The model's point p (tool offset included) and normal n go to the table
 * as  p' = T Rz p + off,  n' = T Rz n,  where Rz turns by rz about Z (counter-clockwise
 * seen from +Z) and T inclines the base plane by `tilt` about the table line through
 * the part's origin at direction `axis` in XY (right hand about (cos axis, sin axis, 0)):
 * "the face is inclined 30 deg about the line at 45 deg" is TILT 45 30. proto's place.h
 * builds the matrix at RUN. */
struct job_place {
    cp_real off[3]; /* PLACE x y z: mm, |.| <= JOB_PLACE_OFF_MAX */
    cp_real rz;     /* PLACE rz: degrees, |rz| <= JOB_PLACE_RZ_MAX (default 0) */
    cp_real axis;   /* TILT axis_deg: degrees, |axis| <= JOB_TILT_AXIS_MAX */
    cp_real tilt;   /* TILT angle_deg: degrees, |tilt| <= JOB_TILT_MAX */
};

/* Returned by job_command for a line that is not a job command (e.g. RUN, $I). */
#define JOB_NOT_MINE (-1)
/* Returned by job_line for RUN (alone on its line) or RESUME k: the protocol's run. */
#define JOB_RUN (-2)
/* Returned by job_line for $J (alone on its line): the protocol prints the job (job_dump). */
#define JOB_DUMP (-3)

struct job {
    struct raster_cfg cfg;  /* raster (every model), C units (radians) */
    struct canal_cfg canal; /* CURVE and RADIUS (the canal's geometry, kept by SURFACE; RADIUS
                               is also the radius law of SURFACE DRC's EDGE fillet), C units */
    union path_geom geom;   /* geometry of the model of `kind` (job_geom_fill: the canal's
                               and DRC's radius law from `canal`, before path_init) */
    struct job_place place;  /* PLACE, TILT (all 0: none) */
    cp_real feed[3];         /* FEED cut, plunge, link: mm/min (0: not set) */
    cp_real safe;            /* SAFE z, mm (valid when safe_set) */
    cp_real spindle;         /* SPINDLE rpm, 0 = no spindle words */
    uint16_t rxbuf;          /* RXBUF: the machine's RX buffer, bytes; 0 = the dialect's */
    uint8_t machine;         /* enum job_machine (MACHINE) */
    uint8_t link;            /* enum job_link (LINK) */
    uint8_t wcs;             /* WCS: 0..5 for G54..G59 */
    uint8_t safe_set;        /* 1 once SAFE was given */
    uint8_t toolaxis;        /* enum job_toolaxis (TOOLAXIS) */
    cp_real lead, side;      /* TOOLAXIS lead side, degrees as given */
    uint16_t have;           /* JOB_HAVE_* bits */
    uint8_t kind;            /* enum path_kind (SURFACE), default PATH_CANAL */
    uint8_t format;          /* enum job_format */
    uint8_t checksum;        /* 1: N<n> ... *<cs> line numbers and checksums */
    /* the cause of the last refused command (job_line), for the protocol's error reply;
     * not a setting (not dumped): the failing token line[cause_st .. + cause_len) of that
     * line (cause_len 0: none known) and the limit it broke (NULL: none given) */
    uint8_t cause_st, cause_len;
    uint8_t cause_args_min, cause_args_max; /* error:3: the arguments after the keyword the
                                               command takes (max 0: not an arity error) */
    const char *cause_limit;
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
 * (error:9), the unsigned number (parse_uint: error:4, above 2^32 - 1 error:6), the numbers
 * (parse_real: error:4/5/6), then the owner's hook checks ranges (error:6, 14, ...).
 * MIN, MAX: the CP_CMD row's columns. */
enum job_shape {
    JOB_ARGS_NUMBERS,             /* MIN..MAX numbers (TOL, FEED, SECTION, AXES, POINT) */
    JOB_ARGS_WORD,                /* exactly one word of the list: arity first, then the
                                     word (FORMAT, CHECKSUM, SURFACE, SECTIONS, EDGE) */
    JOB_ARGS_WORD_THEN_NUMBERS,   /* a word of the list, then the numbers of its row
                                     (CURVE, RADIUS, CENTER, RADII, FRAME, FORM) */
    JOB_ARGS_WORD_NUMBERS_OPTION, /* as WORD_THEN_NUMBERS, but a word without numbers takes
                                     nothing more (error:9), and one with numbers may end
                                     with an option word, which the hook checks after its
                                     ranges: its hook MUST answer error:9 for
                                     option == JOB_BAD_WORD (TOOL) */
    JOB_ARGS_UINT_NUMBERS_OPTION, /* an unsigned number, MIN numbers, then, if the command
                                      has options, an optional option word, checked before
                                      the arity and the numbers (error:9) (LINES, CIRCLES) */
    JOB_ARGS_UINT_OR_WORD,        /* exactly one token: a word of the list, or an unsigned
                                      number (STEPS, RXBUF, RESUME, THICKEN) */
    JOB_ARGS_ALONE                /* nothing after the keyword; with anything after it the
                                     line is not a command (RUN) */
};

/* One command line as job_line has checked it for its owner's hook: the keyword, the
 * words, the arity and every number are valid (the wire status of the first failure is
 * answered before the hook is called). */
struct job_args {
    enum job_cmd cmd;           /* the command */
    enum job_word word;         /* the word after the keyword, JOB_NO_WORD if none (or a
                                   number instead: THICKEN K) */
    unsigned value;             /* VALUE of the word's row (0 without a word) */
    enum job_word option;       /* the option word: JOB_NO_WORD when absent, JOB_BAD_WORD
                                   when it is none of the command's (TOOL) */
    unsigned option_value;      /* VALUE of the option's row (0 without one) */
    unsigned na;                /* numbers in v[] */
    uint32_t u;                 /* the unsigned number (UINT_* shapes), 0 without one */
    cp_real v[JOB_MAX_NUMBERS]; /* the numbers, in line order */
    uint8_t scale[JOB_MAX_NUMBERS]; /* job_dump only: enum job_scale of v[i] */
    /* the cause of a refusal: which argument failed (JOB_ARG_*: job_line's checks set it,
     * a hook sets it with its error) and the limit it broke (a hook's, NULL if none) */
    uint8_t bad;
    uint8_t tok_v, tok_u; /* (job_line's) token index of v[0] and of the unsigned number */
    uint8_t args_min, args_max; /* an arity error: the arguments the command takes */
    const char *limit;
};

/* job_args.bad: no argument named, the number v[k] (JOB_ARG_V + k), the unsigned
 * number, the word, the option word. */
#define JOB_ARG_NONE 0u
#define JOB_ARG_U 1u
#define JOB_ARG_WORD 2u
#define JOB_ARG_OPTION 3u
#define JOB_ARG_V 4u

/* How a dumped number (job_dump) is stored: the job holds scale * (the wire's number). */
enum job_scale {
    JOB_SCALE_ONE = 0, /* as on the wire */
    JOB_SCALE_DEG,     /* degrees on the wire, radians in the job (CP_DEG2RAD) */
    JOB_SCALE_MILLI    /* TOL: um on the wire, mm in the job (0.001) */
};
/* The wire factor of enum job_scale s (the job holds factor * the wire's number). */
#define JOB_SCALE_FACTOR(s)                                                                        \
    ((s) == JOB_SCALE_DEG ? CP_DEG2RAD : (s) == JOB_SCALE_MILLI ? CP_R(0.001) : CP_R(1.0))

/* job_dump's and the models' job_<m>_dump answers for item i. */
#define JOB_DUMP_LINE 1  /* *a is the command line of item i */
#define JOB_DUMP_SKIP 0  /* item i is at its default: no line */
#define JOB_DUMP_END (-1) /* no item i or later */

/* A model's hooks, one set per row of models.def (firmware/job/job_<name>.c, declared here
 * from the rows), called directly from job.c (no function pointers: the static stack
 * analysis sees every edge):
 *   int  job_<m>_command(struct job *j, struct job_args *a)
 *        a command of the model's (commands.def OWNER <M>, switch on a->cmd: <M>_CMD_*):
 *        apply it to the job and return a wire status (the job unchanged on error);
 *        a->v may serve as scratch
 *   void job_<m>_defaults(union path_geom *g)
 *        SURFACE <m>: the model's geometry afresh
 *   int  job_<m>_ready(const struct job *j)
 *        1 when the job has all RUN needs for the model, else 0 (job_ready: error:10)
 *   int  job_<m>_dump(const struct job *j, unsigned i, struct job_args *a)
 *        the model's geometry as commands, item i = 0, 1, ...: JOB_DUMP_LINE with the
 *        command in *a (cmd, word, option, u, na, v[] as the job holds them and scale[]),
 *        JOB_DUMP_SKIP, or JOB_DUMP_END; replayed in item order after SURFACE <m>, they
 *        rebuild the geometry
 * The models' commands, defaults and needs (the header of each job_<m>.c):
 *   canal    CURVE, RADIUS (under every SURFACE); SURFACE CANAL keeps everything;
 *            ready with CURVE, RADIUS and LINES or CIRCLES
 *   gsr      CENTER, RADII, FRAME, FORM; defaults: centre 0, f_t(u) = u, FRAME FIXED
 *            (not set), FORM RATIONAL; ready with CENTER (X|Y|Z, or all four P<i>),
 *            RADII N and B, FRAME, and LINES or CIRCLES
 *   channel  SECTION, AXES, SECTIONS CLEAR; defaults: no section; ready with a SECTION
 *            and LINES or CIRCLES
 *   drc      POINT, POINTS CLEAR, THICKEN, EDGE; defaults: no point, THICKEN AUTO,
 *            EDGE OFF; ready with a POINT (EDGE ON: and RADIUS)
 *   plane    STRIP (the example model, test builds only); defaults: no strip; ready
 *            with STRIP and LINES */
#define CP_MODEL(NAME, name, WITH, WORD)                                                           \
    int job_##name##_command(struct job *j, struct job_args *a);                                   \
    void job_##name##_defaults(union path_geom *g);                                                \
    int job_##name##_ready(const struct job *j);                                                   \
    int job_##name##_dump(const struct job *j, unsigned i, struct job_args *a);
#include "models.def"
#undef CP_MODEL
/* SURFACE SPINE: SPINEDIR into the spine kind's sp[] slots (job_geom_fill, at RUN). */
void job_spine_fill(struct spine_cfg *c);

/* Defaults: nothing set, TOL 1 um, FORMAT GCODE, RXBUF 128, CHECKSUM OFF, TOOL NONE,
 * no placement (PLACE 0 0 0 0, TILT 0 0). */
void job_init(struct job *j);

/* Apply one command line (trimmed, no terminator). Returns a wire status
 * (CP_ST_OK or an error; the job is unchanged on error), or JOB_NOT_MINE (also for
 * RUN, RESUME and $J, the protocol's commands). */
int job_command(struct job *j, const char *line, size_t len);

/* job_command for the protocol: the same, except that RUN alone on its line (RUN with
 * anything after it is JOB_NOT_MINE) and RESUME k return JOB_RUN with *first = 0 or k
 * (the job is unchanged), and $J alone on its line JOB_DUMP (the protocol prints
 * job_dump's lines). On an error it sets j->cause_* (the failing token and limit, when
 * known) for the reply; every other line clears them. RESUME checks as the other commands: error:3 unless exactly
 * one argument, error:4 if k is not an unsigned decimal number, error:21 above
 * 2^32 - 1 (proto.c checks k against the run's point count). */
int job_line(struct job *j, const char *line, size_t len, uint32_t *first);

/* The job as command lines ($J), item i = 0, 1, ... (fixed order: CURVE, RADIUS, TOOL,
 * LINES or CIRCLES, STEPS or TOL, FEED, FORMAT, RXBUF, CHECKSUM, SURFACE, PLACE, TILT, SAFE,
 * SPINDLE, WCS, MACHINE, LINK, TOOLAXIS, then the model's job_<m>_dump items): JOB_DUMP_LINE with the command in *a, JOB_DUMP_SKIP (not set: the
 * default), JOB_DUMP_END. Replayed in order after JOB CLEAR they rebuild the job
 * (tests: dump, clear, replay, dump again: identical). */
int job_dump(const struct job *j, unsigned i, struct job_args *a);

/* The keyword of command c, the text of word w (commands.def: upper case; "" if none). */
const char *job_keyword(enum job_cmd c);
const char *job_word_text(enum job_word w);

/* The word (option 0) or option word (option 1) of command c whose VALUE is value (the
 * first such row), JOB_NO_WORD if none. For the dump hooks. */
enum job_word job_word_of(enum job_cmd c, unsigned value, unsigned option);

/* *a afresh for a dumped command c with word w (JOB_NO_WORD: none): no option, u = 0,
 * na = the word's numbers (0 without a word), v[] 0, every scale JOB_SCALE_ONE. */
void job_dump_args(struct job_args *a, enum job_cmd c, enum job_word w);

/* job_dump_args for command c with its word (option 0) whose VALUE is value (job_word_of):
 * the dump of a job field that a word sets. */
void job_dump_word(struct job_args *a, enum job_cmd c, unsigned value);

/* The dumped line's numbers: a->v[0..a->na) = v[0..a->na) (a->na as set above). */
void job_dump_numbers(struct job_args *a, const cp_real *v);

/* A command's range check: every number a->v[first..end) within |x| <= max, else
 * CP_ST_OUT_OF_RANGE naming the first one that is not (a->bad) and `limit` (the cause's
 * text, "|x| <= 1e4"). Returns CP_ST_OK or CP_ST_OUT_OF_RANGE. */
int job_limit_abs(struct job_args *a, unsigned first, unsigned end, cp_real max,
                  const char *limit);

/* The dumped line's numbers k, k + 1, k + 2: the point or vector p's x, y, z. */
void job_dump_vec3(struct job_args *a, unsigned k, const struct cp_vec3 *p);

/* The enum job_shape of command c (commands.def's SHAPE). */
unsigned job_shape_of(enum job_cmd c);

/* The canal's dump items (job_canal_dump, under every SURFACE): CURVE, RADIUS. */
#define JOB_CANAL_ITEMS 2u

/* CP_ST_OK if the job has everything its SURFACE needs, else CP_ST_NO_JOB. */
int job_ready(const struct job *j);

/* Before path_init (proto.c run_start): copy what the model of j->kind takes from the
 * canal's commands into j->geom: SURFACE CANAL the whole j->canal (CURVE, RADIUS),
 * SURFACE DRC the radius law (j->canal.radius, rp) of its EDGE fillet. Cannot fail. */
void job_geom_fill(struct job *j);

/* 1 if the line starts with a job command keyword (a KEYWORD of commands.def whose
 * owner is compiled in: CURVE ... CHECKSUM, SURFACE, a model's keyword, RUN, RESUME). */
int job_is_command(const char *line, size_t len);

/* The surface models of this build for $I: the words of models.def's rows that are
 * compiled in (cp_config.h CP_WITH_*), in row order, joined by "+", e.g. "CANAL+GSR". */
const char *job_models(void);

#endif /* JOB_H */
