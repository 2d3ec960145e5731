/* sim_machine_marlin_cmd.c - Marlin 2.x's commands: parser.cpp GCodeParser::parse (the
 * FASTER_GCODE_PARSER variant) and gcode.cpp process_parsed_command for a stock
 * configuration, with the handlers G0_G1, G2_G3, G4, G28, G92, M3-M5, M110, M114, M400,
 * M410 as far as a serial host can see them.
 * SPDX-License-Identifier: MIT
 */
#include "sim_machine_marlin.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define ML_PI 3.14159265358979323846

static const double ml_steps_mm[3] = {80.0, 80.0, 4000.0};

/* the parsed command (parser.cpp: command_letter, codenum, the seen parameters) */
struct ml_cmd {
    char letter; /* 'G', 'M', 'T' or '?' (unknown) */
    int code;
    const char *text; /* command_ptr: the command, N and checksum removed */
    int seen[26];
    const char *val[26]; /* NULL: seen without a value */
};

static int ml_numeric(char c)
{
    return c >= '0' && c <= '9';
}

/* parser.h valid_float: [-+]?.?[0-9] */
static int ml_valid_float(const char *p)
{
    if (*p == '-' || *p == '+') {
        p++;
    }
    return ml_numeric(p[0]) || (p[0] == '.' && ml_numeric(p[1]));
}

static int ml_seenval(const struct ml_cmd *c, char l)
{
    return c->seen[l - 'A'] && c->val[l - 'A'] != NULL;
}

static double ml_value(const struct ml_cmd *c, char l)
{
    return strtod(c->val[l - 'A'], NULL);
}

/* parser.cpp parse: skip "N<n> ", the command letter (G/M/T, upper case only: no
 * GCODE_CASE_INSENSITIVE) and its integer code (no subcodes in a stock build); the line is
 * cut at '*' and the spaces before it; then every A-Z letter is a parameter, with a value
 * when a number follows */
static void ml_parse(char *line, struct ml_cmd *c)
{
    char *p = line, *star;
    memset(c, 0, sizeof *c);
    c->letter = '?';
    while (*p == ' ') {
        p++;
    }
    if (p[0] == 'N' && (ml_numeric(p[1]) || p[1] == '-')) {
        p += 2;
        while (ml_numeric(*p)) {
            p++;
        }
        while (*p == ' ') {
            p++;
        }
    }
    c->text = p;
    if (*p == '\0') {
        return;
    }
    star = strchr(p + 1, '*');
    if (star != NULL) {
        --star;
        while (star > p && *star == ' ') {
            --star;
        }
        star[1] = '\0';
    }
    if ((*p != 'G' && *p != 'M' && *p != 'T') || !ml_numeric(p[1])) {
        return;
    }
    c->letter = *p++;
    while (ml_numeric(*p)) {
        c->code = c->code * 10 + (*p++ - '0');
    }
    while (*p == ' ') {
        p++;
    }
    if (c->letter == 'M' && (c->code == 23 || c->code == 28 || c->code == 30 ||
                             c->code == 117 || c->code == 118 || c->code == 928)) {
        return; /* a string argument, no parameters */
    }
    while (*p != '\0') {
        char param = *p++;
        if (param >= 'A' && param <= 'Z') {
            while (*p == ' ') {
                p++;
            }
            c->seen[param - 'A'] = 1;
            c->val[param - 'A'] = ml_valid_float(p) ? p : NULL;
        }
        if (!(*p >= 'A' && *p <= 'Z')) {
            while (*p != '\0' && (ml_numeric(*p) || *p == '.' || *p == '-' || *p == '+')) {
                p++;
            }
            while (*p == ' ') {
                p++;
            }
        }
    }
}

/* M410 (queue.cpp at read time, and the command): planner.quick_stop, then the position
 * is where the steppers stopped */
void ml_quickstop(struct sim_machine *m, int arg)
{
    struct sm_marlin *ml = m->ml;
    int i;
    (void)arg;
    sm_plan_clear(m);
    for (i = 0; i < 3; i++) {
        ml->psteps[i] = lround(m->mpos[i] * ml_steps_mm[i]);
        ml->cur[i] = m->mpos[i];
    }
}

/* one planner move to the native position dest[] from current_position (motion.cpp
 * prepare_line_to_destination: soft endstops clamp the homed axes to [0, 200]) */
static void ml_line_to(struct sim_machine *m, double dest[3], int rapid, int has_a, int has_c,
                       double a, double c)
{
    struct sm_marlin *ml = m->ml;
    struct sm_motion mo;
    struct sm_block b;
    int i;
    memset(&mo, 0, sizeof mo);
    memset(&b, 0, sizeof b);
    for (i = 0; i < 3; i++) {
        if (ml->homed[i]) {
            dest[i] = dest[i] < 0.0 ? 0.0 : (dest[i] > ML_BED ? ML_BED : dest[i]);
        }
        mo.w0[i] = ml->cur[i] + ml->shift[i];
        mo.w1[i] = dest[i] + ml->shift[i];
        b.p1[i] = dest[i];
    }
    mo.rapid = rapid;
    mo.has_a = has_a;
    mo.has_c = has_c;
    mo.a = a;
    mo.c = c;
    mo.feed = m->r.feed_ever ? ml->feed_mms * 60.0 : 0.0;
    sm_motion(m, &mo);
    b.rapid = rapid;
    b.rate = ml->feed_mms * 60.0; /* G0 too: no G0_FEEDRATE in a stock build */
    sm_step_block(m, &b);
    memcpy(ml->cur, dest, sizeof ml->cur);
}

/* gcode.cpp get_destination_from_command: X Y Z (G91: relative), F when > 0; A and C are
 * no axes of a stock (XYZE) machine and are ignored */
static void ml_destination(struct sim_machine *m, const struct ml_cmd *c, double dest[3])
{
    struct sm_marlin *ml = m->ml;
    int i;
    for (i = 0; i < 3; i++) {
        char l = (char)('X' + i);
        if (ml_seenval(c, l)) {
            double v = ml_value(c, l);
            dest[i] = ml->relative ? ml->cur[i] + v : v - ml->shift[i];
        } else {
            dest[i] = ml->cur[i];
        }
    }
    if (ml_seenval(c, 'F') && ml_value(c, 'F') > 0.0) {
        ml->feed_mms = ml_value(c, 'F') / 60.0;
        sm_rule_feed_given(m);
    }
}

static void ml_g0_g1(struct sim_machine *m, const struct ml_cmd *c)
{
    double dest[3];
    ml_destination(m, c, dest);
    if (!ml_seenval(c, 'X') && !ml_seenval(c, 'Y') && !ml_seenval(c, 'Z')) {
        return; /* no axis word: a zero-length move the planner drops (F still set) */
    }
    ml_line_to(m, dest, c->code == 0, c->seen['A' - 'A'], c->seen['C' - 'A'],
               ml_seenval(c, 'A') ? ml_value(c, 'A') : 0.0,
               ml_seenval(c, 'C') ? ml_value(c, 'C') : 0.0);
}

/* G2_G3.cpp: R (radius) or I/J (center offset), XY plane (no CNC_WORKSPACE_PLANES);
 * neither: "Error:G2/G3 bad parameters". plan_arc: segments of MAX_ARC_SEGMENT_MM (1 mm),
 * at least MIN_CIRCLE_SEGMENTS (72) per full turn */
static void ml_g2_g3(struct sim_machine *m, const struct ml_cmd *c)
{
    struct sm_marlin *ml = m->ml;
    double dest[3], off[2] = {0.0, 0.0}, ctr[2], r0[2], ang, rad, lin, mm, p[3], z0;
    unsigned seg, minseg, i;
    int cw = c->code == 2;
    ml_destination(m, c, dest);
    if (ml_seenval(c, 'R')) {
        double r = ml_value(c, 'R'), d2[2], len, h2, e;
        if (r != 0.0 && (dest[0] != ml->cur[0] || dest[1] != ml->cur[1])) {
            d2[0] = (dest[0] - ml->cur[0]) * 0.5;
            d2[1] = (dest[1] - ml->cur[1]) * 0.5;
            e = (cw ^ (r < 0.0)) ? -1.0 : 1.0;
            len = hypot(d2[0], d2[1]);
            h2 = (r - len) * (r + len);
            off[0] = d2[0] - d2[1] / len * e * (h2 >= 0.0 ? sqrt(h2) : 0.0);
            off[1] = d2[1] + d2[0] / len * e * (h2 >= 0.0 ? sqrt(h2) : 0.0);
        }
    } else {
        off[0] = ml_seenval(c, 'I') ? ml_value(c, 'I') : 0.0;
        off[1] = ml_seenval(c, 'J') ? ml_value(c, 'J') : 0.0;
    }
    if (off[0] == 0.0 && off[1] == 0.0) {
        sm_step_text(m, "Error:G2/G3 bad parameters\n");
        m->r.v.errors++;
        return;
    }
    ctr[0] = ml->cur[0] + off[0];
    ctr[1] = ml->cur[1] + off[1];
    r0[0] = -off[0];
    r0[1] = -off[1];
    rad = hypot(r0[0], r0[1]);
    if (fabs(dest[0] - ml->cur[0]) < 1e-6 && fabs(dest[1] - ml->cur[1]) < 1e-6) {
        ang = cw ? -2.0 * ML_PI : 2.0 * ML_PI;
        minseg = 72;
    } else {
        double rt0 = dest[0] - ctr[0], rt1 = dest[1] - ctr[1];
        ang = atan2(r0[0] * rt1 - r0[1] * rt0, r0[0] * rt0 + r0[1] * rt1);
        ang += ang < 0.0 ? 2.0 * ML_PI : 0.0;
        ang -= cw ? 2.0 * ML_PI : 0.0;
        minseg = (unsigned)ceil(72.0 * fabs(ang) / (2.0 * ML_PI));
        minseg = minseg ? minseg : 1u;
    }
    z0 = ml->cur[2];
    lin = dest[2] - z0;
    mm = hypot(rad * fabs(ang), lin);
    if (mm < 0.001) {
        return;
    }
    seg = (unsigned)floor(mm / 1.0);
    seg = seg < minseg ? minseg : seg;
    for (i = 1; i < seg; i++) {
        double t = ang * (double)i / (double)seg;
        p[0] = ctr[0] + r0[0] * cos(t) - r0[1] * sin(t);
        p[1] = ctr[1] + r0[0] * sin(t) + r0[1] * cos(t);
        p[2] = z0 + lin * (double)i / (double)seg;
        ml_line_to(m, p, 0, 0, 0, 0.0, 0.0);
    }
    ml_line_to(m, dest, 0, 0, 0, 0.0, 0.0);
}

static void ml_set_home(struct sim_machine *m, int axes)
{
    struct sm_marlin *ml = m->ml;
    double dest[3];
    struct sm_motion mo;
    int i;
    memset(&mo, 0, sizeof mo);
    for (i = 0; i < 3; i++) {
        mo.w0[i] = ml->cur[i] + ml->shift[i];
        dest[i] = ml->cur[i];
        if (axes & (1 << i)) {
            ml->shift[i] = 0.0; /* set_axis_is_at_home: position_shift = 0 */
            dest[i] = 0.0;      /* X/Y/Z_HOME_DIR -1: the MIN_POS, 0 */
            ml->homed[i] = 1;
        }
        mo.w1[i] = dest[i] + ml->shift[i];
    }
    mo.rapid = 1;
    sm_motion(m, &mo);
    memcpy(ml->cur, dest, sizeof ml->cur);
}

/* G28: wait for the planner, home the named axes (none: all) at once here */
static void ml_g28_done(struct sim_machine *m, int axes)
{
    struct sm_marlin *ml = m->ml;
    int i;
    for (i = 0; i < 3; i++) {
        if (axes & (1 << i)) {
            m->mpos[i] = 0.0;
            ml->psteps[i] = 0;
        }
    }
}

static void ml_g28(struct sim_machine *m, const struct ml_cmd *c)
{
    int axes = (c->seen['X' - 'A'] ? 1 : 0) | (c->seen['Y' - 'A'] ? 2 : 0) |
               (c->seen['Z' - 'A'] ? 4 : 0);
    axes = axes ? axes : 7;
    sm_step_sync(m);
    ml_set_home(m, axes);
    sm_step_call(m, ml_g28_done, axes);
}

/* G92 (workspace offsets on): the logical position of each named axis becomes its value */
static void ml_g92(struct sim_machine *m, const struct ml_cmd *c)
{
    struct sm_marlin *ml = m->ml;
    int i;
    for (i = 0; i < 3; i++) {
        if (ml_seenval(c, (char)('X' + i))) {
            ml->shift[i] = ml_value(c, (char)('X' + i)) - ml->cur[i];
        }
    }
}

static void ml_spindle_set(struct sim_machine *m, int on)
{
    m->ml->sp_on = on;
}

/* M3-M5.cpp (SPINDLE_FEATURE): planner.synchronize(), then the power; switching on waits
 * SPINDLE_LASER_POWERUP_DELAY, switching off SPINDLE_LASER_POWERDOWN_DELAY (5000 ms each
 * in Configuration_adv.h); M3 without S uses SPEED_POWER_STARTUP (on) */
static void ml_spindle(struct sim_machine *m, const struct ml_cmd *c)
{
    struct sm_marlin *ml = m->ml;
    int on = c->code != 5, was = ml->sp_on;
    if (on && ml_seenval(c, 'S')) {
        ml->sp_power = ml_value(c, 'S');
        on = ml->sp_power > 0.0;
    } else if (on) {
        ml->sp_power = 25000.0;
    }
    sm_step_sync(m);
    sm_step_call(m, ml_spindle_set, on);
    if (on != was) {
        sm_step_delay(m, 5000.0);
    }
    ml->sp_on = on;
    sm_rule_spindle(m, on, c->code == 5);
}

/* motion.cpp report_current_position_projected: logical position, E, then the planner's
 * step counts (stepper.cpp report_a_position) */
static void ml_m114(struct sim_machine *m)
{
    struct sm_marlin *ml = m->ml;
    char v[3][32];
    int i;
    for (i = 0; i < 3; i++) {
        sm_fixed(v[i], sizeof v[i], ml->cur[i] + ml->shift[i], 2);
    }
    sm_step_text(m, "X:%s Y:%s Z:%s E:0.00 Count X:%ld Y:%ld Z:%ld\n", v[0], v[1], v[2],
                 ml->psteps[0], ml->psteps[1], ml->psteps[2]);
}

static void ml_m400_done(struct sim_machine *m, int arg)
{
    (void)arg;
    m->ml->last_m400 = 1;
    sm_rule_program_end(m);
}

/* codes a stock build has and whose effect a serial host does not see (they answer ok) */
static int ml_quiet_code(const struct ml_cmd *c)
{
    static const int mcodes[] = {17, 18, 31,  75,  76,  77,  81,  82,  83,  84,  85,  104, 106,
                                 107, 111, 115, 117, 118, 119, 120, 121, 140, 155, 201, 203, 204,
                                 205, 206, 211, 220, 221, 500, 501, 502, 503, 999};
    size_t i;
    if (c->letter == 'T') {
        return 1;
    }
    for (i = 0; c->letter == 'M' && i < sizeof mcodes / sizeof mcodes[0]; i++) {
        if (mcodes[i] == c->code) {
            return 1;
        }
    }
    return 0;
}

/* gcode.cpp process_parsed_command: G codes of a stock configuration */
static int ml_gcode(struct sim_machine *m, const struct ml_cmd *c)
{
    struct sm_marlin *ml = m->ml;
    switch (c->code) {
    case 0: case 1:
        ml_g0_g1(m, c);
        return 1;
    case 2: case 3: /* ARC_SUPPORT is on in a stock build */
        ml_g2_g3(m, c);
        return 1;
    case 4: { /* G4: P milliseconds, S seconds; after a planner sync */
        double ms = ml_seenval(c, 'P') ? (double)(long)ml_value(c, 'P') : 0.0;
        if (ml_seenval(c, 'S')) {
            ms = (double)(long)(ml_value(c, 'S') * 1000.0);
        }
        sm_step_sync(m);
        sm_step_delay(m, ms);
        return 1;
    }
    case 21: /* no INCH_MODE_SUPPORT: "No error on unknown G21" */
        sm_rule_units(m, 1);
        return 1;
    case 28:
        ml_g28(m, c);
        return 1;
    case 90: case 91:
        ml->relative = c->code == 91;
        sm_rule_distance(m, c->code == 90);
        return 1;
    case 92:
        ml_g92(m, c);
        return 1;
    default:
        return 0;
    }
}

/* gcode.cpp process_parsed_command: M codes of a stock configuration */
static int ml_mcode(struct sim_machine *m, const struct ml_cmd *c)
{
    switch (c->code) {
    case 3: case 4: case 5:
        if (m->o.marlin_no_spindle) {
            return 0; /* no HAS_CUTTER: unknown */
        }
        ml_spindle(m, c);
        return 1;
    case 105: /* M105 prints its own "ok" line and skips ok_to_send (temperatures here
                 are invented: 25 C hotend, no bed) */
        sm_step_text(m, "ok T:25.00 /0.00 @:0\n");
        return 2;
    case 110:
        if (ml_seenval(c, 'N')) {
            m->ml->last_n = strtol(c->val['N' - 'A'], NULL, 10);
        }
        return 1;
    case 114:
        ml_m114(m);
        return 1;
    case 400:
        sm_step_sync(m);
        sm_step_call(m, ml_m400_done, 0);
        return 1;
    case 410:
        sm_step_call(m, ml_quickstop, 0);
        return 1;
    default:
        return ml_quiet_code(c);
    }
}

/* GcodeSuite::process_next_command for the queued line (the queue keeps it until the
 * command has run: queue.cpp advance) */
void ml_process(struct sim_machine *m, char *line)
{
    struct ml_cmd c;
    int done = 0;
    ml_parse(line, &c);
    if (c.letter == 'G') {
        done = ml_gcode(m, &c);
    } else if (c.letter == 'M' || c.letter == 'T') {
        done = ml_mcode(m, &c);
    }
    if (c.letter != '?' && (c.seen['G' - 'A'] || c.seen['M' - 'A'])) {
        char esc[96];
        unsigned long ln = m->ml->qline[m->ml->qhead];
        m->r.v.ignored_words++;
        sm_esc(esc, sizeof esc, c.text);
        sm_problem(m, ln, "line %lu: \"%s\": words after the command ignored (Marlin runs only "
                          "the first command of a line)", ln, esc);
    }
    if (!done) {
        ml_unknown(m, c.text);
    }
    if (done != 2) {
        sm_step_call(m, ml_ok, 0);
    }
}
