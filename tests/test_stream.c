/* test_stream.c - RUN over the in-memory HAL: G-code with character counting and
 * checksums, FRAMES with acks and retransmission, real-time bytes, RESUME, and the
 * bad-input table of docs/PROTOCOL.md.
 * SPDX-License-Identifier: MIT
 *
 * A tiny machine model lives here: it reads what the firmware sent, answers "ok"
 * per G-code line after a delay, and checks that the bytes of unanswered lines never
 * exceed its RX buffer (grbl character counting).
 */
#include <stdlib.h>
#include <string.h>

#include "hal_mem.h"
#include "proto.h"
#include "test.h"

struct rig {
    struct hal_mem m;
    struct hal_uart u;
    struct proto p;
    size_t scan;      /* bytes of m.out already parsed */
    char text[16384]; /* non-G-code lines received (replies, reports) */
    size_t text_len;
};

static struct rig rig;
static int resends; /* Resend: requests the machine model sent */

static void rig_init(void)
{
    struct proto_cfg cfg = {0};
    memset(&rig, 0, sizeof rig);
    hal_mem_init(&rig.m, &rig.u);
    rig.m.tick_ms = 1;
    cfg.uart = &rig.u;
    if (proto_init(&rig.p, &cfg) != CP_OK) {
        printf("  proto_init failed\n");
    }
}

static void host_send(const char *s)
{
    if (rig.m.in_pos == rig.m.in_len) {
        rig.m.in_pos = rig.m.in_len = 0;
    }
    (void)hal_mem_feed_str(&rig.m, s);
}

/* Pump the firmware, returning the next complete line the firmware sent (without
 * '\n') in buf, or 0 if none within `polls` polls. */
static int next_line(char *buf, size_t cap, int polls)
{
    int i;
    for (i = 0; i < polls; i++) {
        size_t k;
        for (k = rig.scan; k < rig.m.out_len; k++) {
            if (rig.m.out[k] == '\n') {
                size_t n = k - rig.scan;
                if (n >= cap) {
                    n = cap - 1;
                }
                memcpy(buf, rig.m.out + rig.scan, n);
                buf[n] = '\0';
                rig.scan = k + 1;
                if (rig.scan == rig.m.out_len) {
                    rig.scan = 0;
                    rig.m.out_len = 0;
                }
                return 1;
            }
        }
        (void)proto_poll(&rig.p);
    }
    return 0;
}

/* Send a command and return its final reply ("ok" / "error:N ..."), skipping info. */
static int command(const char *cmd, char *reply, size_t cap)
{
    host_send(cmd);
    host_send("\n");
    while (next_line(reply, cap, 2000)) {
        if (reply[0] != '[' && reply[0] != '<') {
            return 1;
        }
    }
    return 0;
}

static int expect_code(const char *cmd, int code)
{
    char r[128];
    if (!command(cmd, r, sizeof r)) {
        printf("  no reply to \"%s\"\n", cmd);
        return 0;
    }
    if (code == 0 ? strcmp(r, "ok") != 0 : (strncmp(r, "error:", 6) != 0 || atoi(r + 6) != code)) {
        printf("  \"%s\" -> \"%s\", want code %d\n", cmd, r, code);
        return 0;
    }
    return 1;
}

static const char *const paper_job[] = {
    "CURVE ARC 0 0 3 0 360", "RADIUS COS 5.5 10.5 2", "LINES 3 -25 10", "STEPS 40",
    "FEED 600 100", "SAFE 20", NULL};

static int load(const char *const *cmds)
{
    int i;
    for (i = 0; cmds[i] != NULL; i++) {
        if (!expect_code(cmds[i], 0)) {
            return 0;
        }
    }
    return 1;
}

/* Reference stream: the iterator of the same job, quantized like the firmware. */
static int ref_point(uint32_t k, long q[3])
{
    static struct canal_path tp;
    struct raster_pt pt;
    if (canal_path_init(&tp, &rig.p.job.canal, &rig.p.job.cfg) != CP_OK || canal_path_seek(&tp, k) != CP_OK ||
        canal_path_next(&tp, &pt) != CP_OK) {
        return 0;
    }
    q[0] = (long)floor((double)(pt.p.x * CP_R(10000.0) + CP_R(0.5)));
    q[1] = (long)floor((double)(pt.p.y * CP_R(10000.0) + CP_R(0.5)));
    q[2] = (long)floor((double)(pt.p.z * CP_R(10000.0) + CP_R(0.5)));
    return 1;
}

static long parse_fixed4(const char *s)
{
    double v = strtod(s, NULL);
    return (long)floor(v * 10000.0 + 0.5); /* nearest: v*1e4 is within 1e-9 of an integer */
}

/* Stream a GCODE run as the machine: ok per line with `lag` lines of delay,
 * check character counting and every point. Returns 0 or the failing __LINE__. */
static int machine_gcode(int rxbuf, int lag, uint32_t first, uint32_t *points, int corrupt_at)
{
    char l[160];
    size_t pend_len[256];
    int pend = 0, inbuf = 0, g1 = 0, preamble = 0, done = 0, expect_n = 1;
    uint32_t k = first;
    while (!done && next_line(l, sizeof l, 20000)) {
        const char *g = l;
        if (l[0] == 'N') {
            /* checksum mode: verify, maybe corrupt the line on purpose */
            const char *star = strchr(l, '*');
            unsigned cs = 0, n = (unsigned)atoi(l + 1);
            const char *q;
            CHECK(star != NULL);
            for (q = l; q < star; q++) {
                cs ^= (unsigned char)*q;
            }
            pend_len[pend++] = strlen(l) + 1;
            inbuf += (int)strlen(l) + 1;
            CHECK(inbuf <= rxbuf);
            if (corrupt_at > 0 && (int)n == corrupt_at) {
                corrupt_at = -corrupt_at; /* once */
                cs ^= 0x55u;
            }
            if ((unsigned)atoi(star + 1) == cs && strncmp(strchr(l, ' ') + 1, "M110 N", 6) == 0) {
                /* Marlin: M110 N<v> sets the line number; the next line is v + 1 */
                expect_n = atoi(strchr(l, ' ') + 7) + 1;
                host_send("ok\n");
                inbuf -= (int)pend_len[--pend];
                continue;
            }
            if ((unsigned)atoi(star + 1) != cs || (int)n != expect_n) {
                if ((int)n == expect_n || corrupt_at < 0) {
                    char rs[32];
                    if ((int)n == expect_n) {
                        snprintf(rs, sizeof rs, "Resend: %d\n", expect_n);
                        host_send(rs);
                        resends++;
                        corrupt_at = 0;
                    }
                }
                host_send("ok\n");
                inbuf -= (int)pend_len[--pend];
                continue;
            }
            expect_n++;
            g = strchr(l, ' ') + 1;
            *(char *)strchr(g, '*') = '\0';
        } else if (l[0] == 'G' || l[0] == 'M') {
            pend_len[pend++] = strlen(l) + 1;
            inbuf += (int)strlen(l) + 1;
            CHECK(inbuf <= rxbuf); /* character counting honoured */
        } else if (strcmp(l, "ok") == 0) {
            done = 1;
            break;
        } else if (strncmp(l, "[RUN:points=", 12) == 0) {
            continue; /* the run header: not a machine line */
        } else {
            printf("  unexpected line \"%s\"\n", l);
            return __LINE__;
        }
        if (strncmp(g, "G1 ", 3) != 0) {
            preamble++; /* the program around the points (test_stream_program checks it) */
        } else {
            long q[3];
            CHECK(strncmp(g, "G1 X", 4) == 0);
            CHECK(ref_point(k, q));
            CHECK_EQ_INT(parse_fixed4(strchr(g, 'X') + 1), q[0]);
            CHECK_EQ_INT(parse_fixed4(strchr(g, 'Y') + 1), q[1]);
            CHECK_EQ_INT(parse_fixed4(strchr(g, 'Z') + 1), q[2]);
            k++;
            g1++;
        }
        /* answer with a lag: the machine works through its buffer */
        while (pend > lag) {
            int i;
            host_send("ok\n");
            inbuf -= (int)pend_len[0];
            for (i = 1; i < pend; i++) {
                pend_len[i - 1] = pend_len[i];
            }
            pend--;
        }
        if (pend > 0 && rig.p.run.next >= rig.p.run.end) {
            while (pend > 0) {
                host_send("ok\n");
                inbuf -= (int)pend_len[--pend];
            }
        }
    }
    CHECK(done);
    CHECK_EQ_INT(preamble, rig.p.run.lead + rig.p.out.gcode.ntrail - rig.p.job.checksum);
    *points = (uint32_t)g1;
    return 0;
}

int test_stream_gcode(void)
{
    uint32_t pts = 0;
    int r;
    rig_init();
    CHECK(load(paper_job));
    CHECK(expect_code("RXBUF 128", 0));
    host_send("RUN\n");
    r = machine_gcode(128, 3, 0, &pts, 0);
    if (r != 0) {
        return r;
    }
    CHECK_EQ_INT(pts, path_count(&rig.p.path));
    CHECK(rig.p.state == PROTO_IDLE);
    /* the firmware is ready for the next command */
    CHECK(expect_code("$I", 0));
    /* RESUME: the tail of the same stream */
    host_send("RESUME 50\n");
    r = machine_gcode(128, 1, 50, &pts, 0);
    if (r != 0) {
        return r;
    }
    CHECK_EQ_INT(pts, path_count(&rig.p.path) - 50u);
    CHECK(expect_code("RESUME 999999", CP_ST_RESUME_RANGE));
    return 0;
}

/* A placement that is the identity (a full turn, a tilt axis without a tilt) streams
 * exactly the unplaced points (machine_gcode compares every G1 with the model's own
 * iterator): the transform is skipped, not merely close. */
int test_stream_place_identity(void)
{
    uint32_t pts = 0;
    int r;
    rig_init();
    CHECK(load(paper_job));
    CHECK(expect_code("PLACE 0 0 0 360", 0));
    CHECK(expect_code("TILT 45 0", 0));
    host_send("RUN\n");
    r = machine_gcode(128, 3, 0, &pts, 0);
    if (r != 0) {
        return r;
    }
    CHECK_EQ_INT(pts, path_count(&rig.p.path));
    CHECK(rig.p.run.place.on == 0u);
    return 0;
}

int test_stream_checksum(void)
{
    uint32_t pts = 0;
    int r;
    rig_init();
    CHECK(load(paper_job));
    CHECK(expect_code("CHECKSUM ON", 0));
    CHECK(expect_code("RXBUF 256", 0));
    host_send("RUN\n");
    resends = 0;
    r = machine_gcode(256, 4, 0, &pts, 17); /* line N17 arrives corrupted once */
    if (r != 0) {
        return r;
    }
    CHECK_EQ_INT(resends, 1);
    CHECK_EQ_INT(pts, path_count(&rig.p.path));
    return 0;
}

int test_stream_realtime(void)
{
    char l[160];
    int i, got_report = 0, got_abort = 0;
    rig_init();
    CHECK(load(paper_job));
    host_send("?");
    CHECK(next_line(l, sizeof l, 100));
    CHECK(strcmp(l, "<Idle>") == 0);
    host_send("RUN\n");
    CHECK(next_line(l, sizeof l, 100)); /* preamble */
    host_send("!");
    host_send("?");
    for (i = 0; i < 20 && next_line(l, sizeof l, 100); i++) {
        if (strncmp(l, "<Hold|L:0/3|P:", 14) == 0) {
            got_report = 1;
            break;
        }
    }
    CHECK(got_report);
    CHECK(rig.p.state == PROTO_HOLD);
    host_send("~");
    host_send("CURVE LINE 0 0 1 1\n"); /* a job command while running */
    host_send("\x18");
    for (i = 0; i < 50 && next_line(l, sizeof l, 200); i++) {
        if (strncmp(l, "error:20", 8) == 0) {
            got_abort = 1;
            break;
        }
        if (strncmp(l, "error:", 6) == 0) {
            CHECK(strncmp(l, "error:7", 7) == 0); /* busy */
        }
    }
    CHECK(got_abort);
    CHECK(rig.p.state == PROTO_IDLE);
    /* late oks from the machine are ignored when idle */
    host_send("ok\nok\n");
    CHECK(expect_code("$I", 0));
    return 0;
}

/* A job whose check takes many slices (issue 22): 64 lines of an ellipse, 2 um. */
static const char *const check_job[] = {
    "CURVE ELLIPSE 0 0 40 30 0 300", "RADIUS LINEAR 4 6", "LINES 64 -40 40", "TOL 2",
    "FEED 600 100", "SAFE 20", NULL};

int test_stream_check(void)
{
    /* RUN checks the job in slices (PROTO_CHECK): '?' answers "<Check|W:w|S:i/m>" between
     * them, Ctrl-X cancels the check with error:20 and leaves the engine idle with no path,
     * and a line sent after RUN waits (in order) until the check has ended */
    char l[160];
    int i, polls, reports = 0, run_line = 0, info_after = 0;
    uint32_t last_walk = 0u;
    rig_init();
    CHECK(load(check_job));
    host_send("RUN\n");
    (void)proto_poll(&rig.p);
    CHECK(rig.p.state == PROTO_CHECK);
    for (polls = 0; polls < 100000 && rig.p.state == PROTO_CHECK; polls++) {
        if (polls % 4 == 1) {
            host_send("?");
        }
        while (next_line(l, sizeof l, 1)) {
            unsigned long w = 0, si = 0, sm = 0;
            CHECK(sscanf(l, "<Check|W:%lu|S:%lu/%lu>", &w, &si, &sm) == 3);
            CHECK(w >= last_walk && w >= 1u && si <= sm); /* walks go on, steps within */
            last_walk = (uint32_t)w;
            reports++;
        }
    }
    CHECK(polls > 8 && reports > 2); /* many slices, the '?' answered between them */
    CHECK(rig.p.state == PROTO_RUN);
    host_send("\x18");
    for (i = 0; i < 2000 && rig.p.state != PROTO_IDLE; i++) {
        (void)proto_poll(&rig.p);
    }
    CHECK(rig.p.state == PROTO_IDLE);
    /* Ctrl-X during a check */
    rig_init();
    CHECK(load(check_job));
    host_send("RUN\n");
    for (i = 0; i < 3; i++) {
        (void)proto_poll(&rig.p);
    }
    CHECK(rig.p.state == PROTO_CHECK);
    host_send("\x18");
    CHECK(next_line(l, sizeof l, 4));
    CHECK(strcmp(l, "error:20 aborted") == 0);
    CHECK(rig.p.state == PROTO_IDLE && path_count(&rig.p.path) == 0u);
    host_send("?");
    CHECK(next_line(l, sizeof l, 4));
    CHECK(strcmp(l, "<Idle>") == 0);
    /* a line after RUN: answered after the check, i.e. after the run's [RUN:...] line */
    host_send("RUN\n$I\n");
    for (i = 0; i < 200 && next_line(l, sizeof l, 5000); i++) {
        if (strncmp(l, "[RUN:", 5) == 0) {
            run_line = 1;
        }
        if (strncmp(l, "[VER:", 5) == 0) {
            info_after = run_line;
            break;
        }
    }
    CHECK(info_after);
    TEST_NOTE("check in %d polls, %d <Check|...> reports, last walk %u\n", polls, reports,
              (unsigned)last_walk);
    return 0;
}

struct bad_vec {
    const char *line;
    int code;
};

/* The bad-input table of docs/PROTOCOL.md: every row has its own test. */
static const struct bad_vec bad[] = {
    {"FOO", CP_ST_UNKNOWN_CMD},
    {"$J 1", CP_ST_UNKNOWN_CMD}, /* $J alone only (grbl's jog $J=... is not ours) */
    {"JOB", CP_ST_BAD_ARITY},
    {"JOB RESET", CP_ST_BAD_KEYWORD},
    {"CURVE", CP_ST_BAD_ARITY},
    {"CURVE SPIRAL 1 2", CP_ST_BAD_KEYWORD},
    {"CURVE LINE 0 0 1", CP_ST_BAD_ARITY},
    {"CURVE LINE 0 0 1 1 2", CP_ST_BAD_ARITY},
    {"CURVE LINE 0 0 1 x", CP_ST_BAD_NUMBER},
    {"CURVE ARC 0 0 3 0 nan", CP_ST_NONFINITE},
    {"CURVE ARC 0 0 inf 0 90", CP_ST_NONFINITE},
    {"CURVE LINE 0 0 1e12 0", CP_ST_OUT_OF_RANGE},
    /* the curve alone, at CURVE (canal_curve_check: the codes of RUN) */
    {"CURVE ELLIPSE 0 0 0 25 0 360", CP_ST_OUT_OF_RANGE},
    {"CURVE ARC 0 0 3 0 400", CP_ST_OUT_OF_RANGE},
    {"CURVE LINE 0 0 2e4 0", CP_ST_OUT_OF_RANGE},
    {"CURVE LINE 0 0 0 0", CP_ST_DEGENERATE},
    {"CURVE BEZIER 1 1 1 1 1 1 1 1", CP_ST_DEGENERATE},
    {"CURVE ARC 0 0 3 10 10", CP_ST_EMPTY},
    /* the law alone, at RADIUS (canal_radius_check) */
    {"RADIUS COS 1 2 65", CP_ST_OUT_OF_RANGE},
    {"RADIUS LINEAR 1 2e4", CP_ST_OUT_OF_RANGE},
    {"RADIUS", CP_ST_BAD_ARITY},
    {"RADIUS CONST", CP_ST_BAD_ARITY},
    {"RADIUS WAVY 1", CP_ST_BAD_KEYWORD},
    {"RADIUS COS 1 2", CP_ST_BAD_ARITY},
    {"TOOL", CP_ST_BAD_ARITY},
    {"TOOL FLAT 2", CP_ST_BAD_KEYWORD},
    {"TOOL BALL -1", CP_ST_OUT_OF_RANGE},
    {"TOOL BALL 1 SIDE", CP_ST_BAD_KEYWORD},
    {"LINES 0 -10 10", CP_ST_OUT_OF_RANGE},
    {"LINES 99999 -10 10", CP_ST_TOO_MANY},
    {"LINES 3 -10 200", CP_ST_OUT_OF_RANGE},
    {"LINES 3 5 5", CP_ST_OUT_OF_RANGE},
    {"LINES 3 -10", CP_ST_BAD_ARITY},
    {"LINES 2.5 -10 10", CP_ST_BAD_NUMBER},
    {"CIRCLES 3 -10 10 WIDE", CP_ST_BAD_KEYWORD},
    {"STEPS 0", CP_ST_OUT_OF_RANGE},
    {"STEPS 999999", CP_ST_TOO_MANY},
    {"STEPS -4", CP_ST_BAD_NUMBER},
    {"TOL 0", CP_ST_OUT_OF_RANGE},
    {"TOL 1 2", CP_ST_BAD_ARITY},
    {"FEED -5", CP_ST_OUT_OF_RANGE},
    {"FORMAT XML", CP_ST_BAD_KEYWORD},
    {"RXBUF 8", CP_ST_OUT_OF_RANGE},
    {"RXBUF 119", CP_ST_OUT_OF_RANGE}, /* smaller than the longest stream line */
    {"FEED 0.0009", CP_ST_OUT_OF_RANGE},
    {"FEED 600 0", CP_ST_OUT_OF_RANGE}, /* a plunge feed of 0 */
    {"FEED 600 100 50 7", CP_ST_BAD_ARITY},
    {"SAFE 1000.1", CP_ST_OUT_OF_RANGE},
    {"SPINDLE -1", CP_ST_OUT_OF_RANGE},
    {"WCS G60", CP_ST_BAD_KEYWORD},
    {"MACHINE HAAS", CP_ST_BAD_KEYWORD},
    {"LINK USB", CP_ST_BAD_KEYWORD},
    {"CHECKSUM MAYBE", CP_ST_BAD_KEYWORD},
    {"PLACE 1 2", CP_ST_BAD_ARITY},
    {"PLACE 1 2 3 4 5", CP_ST_BAD_ARITY},
    {"TILT 45", CP_ST_BAD_ARITY},
    {"PLACE 1 2 z", CP_ST_BAD_NUMBER},
    {"PLACE 0 nan 0", CP_ST_NONFINITE},
    {"TILT 0 inf", CP_ST_NONFINITE},
    {"PLACE 1001 0 0", CP_ST_OUT_OF_RANGE},
    {"PLACE 0 0 0 361", CP_ST_OUT_OF_RANGE},
    {"TILT 361 0", CP_ST_OUT_OF_RANGE},
    {"TILT 45 91", CP_ST_OUT_OF_RANGE},
    {"RESUME", CP_ST_BAD_ARITY},
    {"RESUME x", CP_ST_BAD_NUMBER},
    {"RUN", CP_ST_NO_JOB},
    {"LINES 1 2 3 4 5 6 7 8 9 10 11 12 13", CP_ST_BAD_ARITY},
    {"CURVE LINE 1 2 3 4 5 6 7 8 9 10 11 12", CP_ST_BAD_ARITY},
};

/* Jobs that parse but fail validation at RUN, each with its code (after the program's
 * FEED 600 and SAFE 20). */
#define GOOD_CANAL "CURVE ARC 0 0 3 0 360", "RADIUS COS 5.5 10.5 2", "LINES 2 -20 5"
static const struct {
    const char *cmds[10];
    int code;
} bad_jobs[] = {
    {{"CURVE ARC 0 0 3 0 360", "RADIUS COS 5 2 2", "LINES 1 0 0", NULL}, CP_ST_RADIUS},
    {{"CURVE ARC 0 0 3 0 360", "RADIUS COS 5.5 10.5 2", "LINES 5 -20 60", NULL}, CP_ST_CUSP},
    {{GOOD_CANAL, "TOOL BALL 6", NULL}, CP_ST_TOOL},
    {{"CURVE ARC 0 0 3 0 360", "RADIUS CONST 2", "CIRCLES 2 0 90", "TOL 0.01", NULL}, CP_ST_TOL},
    /* the program: a feed and a safe height needed, what the dialect has, a link that is there */
    {{GOOD_CANAL, "FEED 0", NULL}, CP_ST_NO_FEED},
    {{GOOD_CANAL, "JOB CLEAR", GOOD_CANAL, "FEED 600", NULL}, CP_ST_NO_SAFE},
    {{GOOD_CANAL, "MACHINE GRBL", "CHECKSUM ON", NULL}, CP_ST_DIALECT},
    {{GOOD_CANAL, "MACHINE LINUXCNC", "CHECKSUM ON", NULL}, CP_ST_DIALECT},
    {{GOOD_CANAL, "LINK MACHINE", NULL}, CP_ST_NO_MACHINE_LINK},
    /* closed curves whose law does not close (issue 22): the R = cos(2.5 theta) + 5
     * on a 360 degree arc, a LINEAR law on a closed ellipse, a closed Bezier whose CUBIC
     * law closes in value but not in slope */
    {{"CURVE ARC 0 0 3 0 360", "RADIUS COS 1 5 2.5", "LINES 2 -20 5", NULL}, CP_ST_SEAM},
    {{"CURVE ELLIPSE 0 0 4 3 0 360", "RADIUS LINEAR 1 1.5", "LINES 2 -20 5", NULL}, CP_ST_SEAM},
    {{"CURVE BEZIER 0 0 40 40 -40 40 0 0", "RADIUS CUBIC 3 4 4 3", "LINES 2 -20 5", NULL},
     CP_ST_SEAM},
#if CP_WITH_SPINE
    /* SURFACE SPINE: a cusp (an arc of radius 5 with R = 6), a straight spine without
     * SPINEREF, the tool, TOL alone beyond the march */
    {{"SURFACE SPINE", "SPINE ARC 0 0 0 0 0 1 5 60", "RADIUS CONST 6", "LINES 4 -180 90",
      "STEPS 16", NULL}, CP_ST_CUSP},
    {{"SURFACE SPINE", "SPINE LINE 0 0 0 10 0 0", "RADIUS CONST 6", "LINES 4 -180 90", "STEPS 16",
      NULL}, CP_ST_FRENET},
    {{"SURFACE SPINE", "SPINE ARC 0 0 0 0 0 1 5 60", "RADIUS CONST 4", "LINES 4 -90 90",
      "STEPS 16", "TOOL BALL 4", NULL}, CP_ST_TOOL},
    {{"SURFACE SPINE", "SPINE ARC 0 0 0 0 0 1 5 60", "RADIUS CONST 4", "LINES 4 -90 90",
      "TOL 0.01", NULL}, CP_ST_TOL},
#endif
};

/* A model's command refused on its own, under its SURFACE. */
static const struct {
    const char *surface, *line;
    int code;
} bad_model[] = {
    {"SURFACE DRC", "POINT 1 2 3", CP_ST_OFF_PLANE},     /* drc_point_check */
    {"SURFACE DRC", "POINT 1 2e4", CP_ST_OUT_OF_RANGE},
    {"SURFACE GSR", "RADII N 1 -2 0 0 0 0 0", CP_ST_SECTION}, /* gsr_fn_check */
    {"SURFACE GSR", "RADII B 0 0 0 0 0 0 0", CP_ST_SECTION},
    {"SURFACE GSR", "RADII T 0 2 0 0 0 0 0", CP_ST_FT_RANGE},
    {"SURFACE GSR", "RADII T 1 -1 0 0 0 0 0", CP_ST_FT_RANGE},
    {"SURFACE GSR", "RADII T 0.5 0 0 0 0 0 0", CP_ST_FT_RANGE},
#if CP_WITH_SPINE
    {"SURFACE SPINE", "SPINE HELIX 0 0 0 0 0 1 15 10 2 1", CP_ST_BAD_ARITY},
    {"SURFACE SPINE", "SPINE HELIX 0 0 0 0 0 1 15 10 2e4", CP_ST_OUT_OF_RANGE},
    {"SURFACE SPINE", "SPINE ARC 0 0 0 0 0 1 5 400", CP_ST_OUT_OF_RANGE},
    {"SURFACE SPINE", "SPINE KNOT 1 2 3", CP_ST_BAD_KEYWORD},
#endif
};

int test_stream_bad_input(void)
{
    size_t i;
    rig_init();
    for (i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        if (!expect_code(bad[i].line, bad[i].code)) {
            printf("  bad-input row %u\n", (unsigned)i);
            return __LINE__;
        }
    }
    for (i = 0; i < sizeof bad_jobs / sizeof bad_jobs[0]; i++) {
        int c;
        rig_init();
        CHECK(expect_code("FEED 600", 0));
        CHECK(expect_code("SAFE 20", 0));
        for (c = 0; bad_jobs[i].cmds[c] != NULL; c++) {
            CHECK(expect_code(bad_jobs[i].cmds[c], 0));
        }
        if (!expect_code("RUN", bad_jobs[i].code)) {
            printf("  bad-job row %u\n", (unsigned)i);
            return __LINE__;
        }
    }
    /* the models' own commands check what needs the command alone, as their RUN would */
    for (i = 0; i < sizeof bad_model / sizeof bad_model[0]; i++) {
        rig_init();
        CHECK(expect_code(bad_model[i].surface, 0));
        if (!expect_code(bad_model[i].line, bad_model[i].code)) {
            printf("  bad-model row %u\n", (unsigned)i);
            return __LINE__;
        }
    }
    /* binary garbage and line noise never wedge it */
    {
        unsigned st = 7u;
        char junk[200];
        rig_init();
        for (i = 0; i < sizeof junk - 1; i++) {
            junk[i] = (char)(test_prng(&st) & 0xFFu);
            if (junk[i] == 0x18 || junk[i] == '!' || junk[i] == '\0') {
                junk[i] = 'x';
            }
        }
        junk[sizeof junk - 1] = '\0';
        host_send(junk);
        host_send("\n");
        for (i = 0; i < 400; i++) {
            (void)proto_poll(&rig.p);
        }
        rig.scan = 0;
        rig.m.out_len = 0;
        CHECK(expect_code("$I", 0));
        CHECK(load(paper_job));
    }
    return 0;
}

/* A closed curve whose law does not close: RUN's whole answer is the one error line, before
 * any program line or frame (G-code and FRAMES); with a closing law the same job streams. */
int test_stream_seam(void)
{
    static const char want[] = "error:46 radius or section law jumps at the seam\n";
    static const char *const job[] = {"CURVE ARC 0 0 3 0 360", "RADIUS COS 1 5 2.5",
                                      "LINES 2 -20 5", "STEPS 40", "FEED 600", "SAFE 20", NULL};
    unsigned f;
    int i;
    for (f = 0; f < 2u; f++) {
        rig_init();
        CHECK(load(job));
        CHECK(expect_code(f ? "FORMAT FRAMES" : "FORMAT GCODE", 0));
        rig.scan = 0;
        rig.m.out_len = 0;
        host_send("RUN\n");
        for (i = 0; i < 200; i++) {
            (void)proto_poll(&rig.p);
        }
        if (rig.m.out_len != sizeof want - 1u || memcmp(rig.m.out, want, sizeof want - 1u) != 0) {
            printf("  RUN answered %u bytes: \"%.*s\"\n", (unsigned)rig.m.out_len,
                   (int)(rig.m.out_len < 80u ? rig.m.out_len : 80u), (const char *)rig.m.out);
            return __LINE__;
        }
        CHECK_EQ_INT(rig.p.state, PROTO_IDLE);
        rig.m.out_len = 0;
        CHECK(expect_code("RADIUS COS 1 5 3", 0)); /* k = 3 closes */
        CHECK(expect_code("FORMAT GCODE", 0));
        CHECK(expect_code("LINES 1 0 0", 0));
        {
            char r[128];
            CHECK(command("RUN", r, sizeof r)); /* the program's first line: it streams */
            CHECK(strncmp(r, "G21", 3) == 0);
        }
    }
    return 0;
}

#if CP_WITH_SPINE
/* RUN a SPINE helix tube (radius 15, 2 turns, RADIUS CONST 2, a ball of 0.5 inside) of
 * pitch `pitch` with FORMAT GCODE on the host link: the [RUN:...] header and the status
 * report that a '?' gets during the run into hdr and rep; then 0x18 ends the run. */
static int overlap_run(const char *pitch, char *hdr, char *rep, size_t cap)
{
    static const char *const job[] = {"SURFACE SPINE", "RADIUS CONST 2", "LINES 2 -60 60",
                                      "STEPS 24", "TOOL BALL 0.5 TIP", "FEED 600", "SAFE 50",
                                      NULL};
    char line[128];
    int i;
    rig_init();
    hdr[0] = rep[0] = '\0';
    if (!load(job)) {
        return 0;
    }
    snprintf(line, sizeof line, "SPINE HELIX 0 0 0 0 0 1 15 %s 2", pitch);
    if (!expect_code(line, 0)) {
        return 0;
    }
    host_send("RUN\n");
    for (i = 0; i < 100 && next_line(line, sizeof line, 4000); i++) {
        if (strncmp(line, "[RUN:", 5) == 0) {
            snprintf(hdr, cap, "%s", line);
            break;
        }
    }
    host_send("?");
    for (i = 0; i < 100 && next_line(line, sizeof line, 4000); i++) {
        if (line[0] == '<') {
            snprintf(rep, cap, "%s", line);
            break;
        }
    }
    host_send("\x18");
    for (i = 0; i < 100 && next_line(line, sizeof line, 4000); i++) {
        if (strncmp(line, "error:20", 8) == 0) {
            return hdr[0] != '\0' && rep[0] != '\0';
        }
    }
    return 0;
}

/* Issue 22: an overlap that the model's init reports (the tool inside the spheres: SPINE's
 * helix tube of pitch 3 against spheres 4 mm across) is in the run's header and in every
 * status report of the run; a tube with room (pitch 6) has neither. */
int test_stream_overlap_report(void)
{
    char hdr[128], rep[128];
    size_t n;
    CHECK(overlap_run("3", hdr, rep, sizeof hdr));
    n = strlen(hdr);
    CHECK(n > 11u && strcmp(hdr + n - 11u, ",overlap=1]") == 0);
    CHECK(strncmp(rep, "<Run|", 5) == 0);
    n = strlen(rep);
    CHECK(n > 11u && strcmp(rep + n - 11u, "|Overlap:1>") == 0);
    CHECK(overlap_run("6", hdr, rep, sizeof hdr));
    CHECK(strstr(hdr, "overlap") == NULL && strstr(rep, "Overlap") == NULL);
    CHECK(strncmp(hdr, "[RUN:points=", 12) == 0 && strncmp(rep, "<Run|", 5) == 0);
    return 0;
}
#else
int test_stream_overlap_report(void)
{
    return 0;
}
#endif

/* $J into out (the "[JOB:...]" lines' commands, '\n'-separated); 0 unless it ends "ok". */
static int dump_job(char *out, size_t cap)
{
    char r[200];
    size_t n = 0;
    host_send("$J\n");
    while (next_line(r, sizeof r, 2000)) {
        size_t len = strlen(r);
        if (strcmp(r, "ok") == 0) {
            out[n] = '\0';
            return 1;
        }
        if (strncmp(r, "[JOB:", 5) != 0 || r[len - 1] != ']' || n + len >= cap ||
            len - 6 >= CP_LINE_MAX) {
            printf("  $J: unexpected or overlong \"%s\"\n", r);
            return 0;
        }
        memcpy(out + n, r + 5, len - 6);
        n += len - 6;
        out[n++] = '\n';
    }
    return 0;
}

/* Every line of the dump d replayed: each answered ok. */
static int replay_dump(const char *d)
{
    char line[CP_LINE_MAX + 1];
    while (*d != '\0') {
        size_t k = strcspn(d, "\n");
        memcpy(line, d, k);
        line[k] = '\0';
        if (!expect_code(line, 0)) {
            return 0;
        }
        d += k + (d[k] != '\0');
    }
    return 1;
}

/* $J prints the job as the commands that rebuild it, JOB CLEAR resets it: for jobs of
 * every model, dump, clear, replay, dump again: identical; after JOB CLEAR the dump is
 * empty and RUN is error:10; $J with anything after it is not a command. */
int test_stream_job_dump(void)
{
    static const char *const jobs[][16] = {
        {"CURVE ARC 0 0 3 0 360", "RADIUS COS 5.5 10.5 2", "LINES 3 -25 10", "STEPS 40", NULL},
        {"CURVE ELLIPSE 1.5 -2 25 12.345678 -33.3 291.7", "RADIUS CUBIC 1 2.5 0.3 7",
         "CIRCLES 5 -170.1 90 PATCH", "TOL 2.5", "FEED 0.05", "TOOL BALL 0.3 CENTRE",
         "FORMAT FRAMES", "RXBUF 200", "CHECKSUM ON", NULL},
        {"CURVE BEZIER 0 0 3.3 1e-3 7 -2.123456 10 0.1", "RADIUS LINEAR 4 7", "TOOL BALL 2",
         "LINES 1 0 0", "FEED 1234.5", "PLACE 12.5 -40 3.25 -33.3", "TILT 45 30", NULL},
        /* the program's commands (issue 17) */
        {"CURVE ARC 0 0 3 0 360", "RADIUS COS 5.5 10.5 2", "LINES 3 -25 10", "FEED 600 150 400",
         "SAFE 25.5", "SPINDLE 12000", "WCS G57", "TOOLAXIS AC 12.5 -3", NULL},
        {"SURFACE DRC", "POINT 0 0", "POINT 10 0.5", "POINT 15.79 1.7395", "THICKEN 4",
         "EDGE ON", "RADIUS LINEAR 4 7", "LINES 5 -40 40", NULL},
        {"SURFACE GSR", "CENTER P0 0 0 0", "CENTER P1 4 0 2", "CENTER P2 8 3 2",
         "CENTER P3 12 3 0", "RADII N 0.9 -0.3 0 0 0 0 0", "RADII B 0.5 0.2 0 0 0 0 0",
         "RADII T 0.1 0.8 0 0 0 0.01 33.3", "FRAME N0 1 0 0", "FRAME FIXED", "FORM TRIG",
         "LINES 7 -90 90", NULL},
        {"SURFACE GSR", "CENTER X 0 8 0 0 0 0 0", "CENTER Z 0 0 0 0 2 0 180",
         "RADII N 1.2 0 0 0 0.5 0 180", "RADII B 0.8 0.3 0 0 0 0 0", "FRAME RMF 0 0 1", NULL},
#if CP_WITH_SPINE
        {"SURFACE SPINE", "SPINE P0 0 0 0", "SPINE P1 25 35 15", "SPINE P2 60 -25 35",
         "SPINE P3 90 10 5", "RADIUS CUBIC 3 6 2 5", "SPINEREF 0 0 1", "LINES 6 -150 150", NULL},
        {"SURFACE SPINE", "SPINE ARC 10 -5 20 1 -2 3 40 270", "SPINEDIR 1 1 0",
         "RADIUS LINEAR 3 10", "CIRCLES 7 -170 170 PATCH", "TOL 10", NULL},
        {"SURFACE SPINE", "SPINE HELIX 0 0 0 0 0 1 15 10 2", "RADIUS COS 1.5 4 3",
         "LINES 5 -140 140", "STEPS 40", NULL},
#endif
        /* SECTION's rows are computed from its angles: in the double build they need
         * 17 digits each, and AXES with six of them exceeds the line (PROTOCOL.md, $J) */
#if CP_REAL_DOUBLE
        {"SURFACE CHANNEL", "SECTION 4 3 3 6 3.5 7 0 0 0",
#else
        {"SURFACE CHANNEL", "SECTION 4 3 3 6 3.5 7 225 22.5 15",
#endif
         "SECTION 3.5 2.5 6 7 1 14 210 25.7142857143 10",
         "AXES -0.890540 -0.450484 -0.063262 0.156452 -0.433884 0.887281", "CIRCLES 5 -180 180",
         NULL},
    };
    static char d1[4096], d2[4096];
    size_t i;
    for (i = 0; i < sizeof jobs / sizeof jobs[0]; i++) {
        rig_init();
        CHECK(load(jobs[i]));
        CHECK(dump_job(d1, sizeof d1));
        CHECK(expect_code("JOB CLEAR", 0));
        CHECK(dump_job(d2, sizeof d2));
        CHECK(d2[0] == '\0');
        CHECK(expect_code("RUN", CP_ST_NO_JOB));
        CHECK(replay_dump(d1));
        CHECK(dump_job(d2, sizeof d2));
        if (strcmp(d1, d2) != 0) { /* (the same after the replay) */
            printf("  job %u: dump\n%s  replayed dump\n%s", (unsigned)i, d1, d2);
            return __LINE__;
        }
        if (i == 1u || i == 4u) {
            TEST_NOTE("$J of job %u:\n%s", (unsigned)i, d1);
        }
    }
    /* the cell's wiring (MACHINE, LINK) is dumped and outlives JOB CLEAR */
    rig_init();
    CHECK(expect_code("MACHINE MARLIN", 0));
    CHECK(expect_code("LINK MACHINE", 0));
    CHECK(expect_code("JOB CLEAR", 0));
    CHECK(dump_job(d1, sizeof d1));
    CHECK(strcmp(d1, "MACHINE MARLIN\nLINK MACHINE\n") == 0);
    CHECK(expect_code("$J 1", CP_ST_UNKNOWN_CMD));
    CHECK(expect_code("JOB", CP_ST_BAD_ARITY));
    CHECK(expect_code("JOB RESET", CP_ST_BAD_KEYWORD));
    return 0;
}

/* An error reply names its cause where the firmware knows it: "error:<code> <text>" first,
 * unchanged, then " (<keyword> <token>: <limit>)". */
int test_stream_error_cause(void)
{
    static const char *const cases[][2] = {
        {"FEED 0.0009", "error:6 value out of range (FEED 0.0009: 0 or 0.001..1e6)"},
        {"FEED 600 100 1e7", "error:6 value out of range (FEED 1e7: 0.001..1e6)"},
        {"RXBUF 119", "error:6 value out of range (RXBUF 119: 120..1024)"},
        {"LINES 3 -10 200", "error:6 value out of range (LINES 200: |u| <= 180)"},
        {"LINES 3 5 5", "error:6 value out of range (LINES 5: u0 != u1 for n > 1)"},
        {"TOL 0", "error:6 value out of range (TOL 0: 0.01..10000)"},
        {"TOOL BALL -1", "error:6 value out of range (TOOL -1: 0 < r <= 1e4)"},
        {"TOOL BALL 1 SIDE", "error:9 unknown keyword (TOOL SIDE)"},
        {"CURVE LINE 0 0 1 x", "error:4 not a number (CURVE x)"},
        {"CURVE LINE 0 0 1e12 0", "error:6 value out of range (CURVE 1e12: |x| <= 1e9)"},
        {"CURVE ARC 0 0 3 0 nan", "error:5 non-finite number (CURVE nan)"},
        {"CURVE SPIRAL 1 2", "error:9 unknown keyword (CURVE SPIRAL)"},
        {"STEPS -4", "error:4 not a number (STEPS -4)"},
        {"CURVE ELLIPSE 0 0 0 25 0 360", "error:6 value out of range"}, /* no cause known */
        {"CURVE LINE 0 0 1", "error:3 wrong number of arguments (CURVE: 5 arguments)"},
        {"PLACE 1 2", "error:3 wrong number of arguments (PLACE: 3..4 arguments)"},
        {"LINES 3 -10", "error:3 wrong number of arguments (LINES: 3 arguments)"},
        {"CIRCLES 3 -10", "error:3 wrong number of arguments (CIRCLES: 3..4 arguments)"},
        {"FORMAT", "error:3 wrong number of arguments (FORMAT: 1 argument)"},
        {"FOO", "error:1 unknown command"},
    };
    char r[160];
    size_t i;
    rig_init();
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        CHECK(command(cases[i][0], r, sizeof r));
        if (strcmp(r, cases[i][1]) != 0) {
            printf("  \"%s\" -> \"%s\", want \"%s\"\n", cases[i][0], r, cases[i][1]);
            return __LINE__;
        }
    }
    return 0;
}

/* FRAMES: decode, ack every frame; drop one ack and NAK one frame on purpose. */
static int frames_run(void)
{
    struct frame_rx fr;
    uint32_t expect = 0, pts = 0, k = 0;
    int done = 0, i, naked = 0;
    char l[64];
    rig_init();
    CHECK(load(paper_job));
    CHECK(expect_code("FORMAT FRAMES", 0));
    host_send("RUN\n");
    frame_rx_init(&fr);
    for (i = 0; i < 200000 && !done; i++) {
        (void)proto_poll(&rig.p);
        while (rig.scan < rig.m.out_len) {
            uint8_t c = rig.m.out[rig.scan++];
            if (frame_rx_feed(&fr, c)) {
                const uint8_t *f = fr.buf;
                uint8_t ack[8];
                int n;
                if (f[1] != (uint8_t)expect) {
                    continue; /* a retransmitted duplicate */
                }
                if (f[2] == FRAME_POINT) {
                    long q[3];
                    if (expect == 20u && !naked) {
                        naked = 1; /* pretend it was corrupted: NAK it */
                        n = frame_encode((uint8_t)expect, FRAME_NAK, NULL, 0, ack, sizeof ack);
                        hal_mem_feed(&rig.m, ack, (size_t)n);
                        continue;
                    }
                    CHECK_EQ_INT(frame_get_u32(f + 3), k);
                    CHECK(ref_point(k, q));
                    CHECK_EQ_INT((int32_t)frame_get_u32(f + 7), q[0]);
                    CHECK_EQ_INT((int32_t)frame_get_u32(f + 11), q[1]);
                    CHECK_EQ_INT((int32_t)frame_get_u32(f + 15), q[2]);
                    k++;
                    pts++;
                } else if (f[2] == FRAME_END) {
                    CHECK_EQ_INT(f[3], 0);
                }
                expect++;
                if (expect % 5u != 3u) { /* some acks are simply not sent (cumulative) */
                    n = frame_encode((uint8_t)expect, FRAME_ACK, NULL, 0, ack, sizeof ack);
                    hal_mem_feed(&rig.m, ack, (size_t)n);
                }
                if (f[2] == FRAME_END) {
                    n = frame_encode((uint8_t)expect, FRAME_ACK, NULL, 0, ack, sizeof ack);
                    hal_mem_feed(&rig.m, ack, (size_t)n);
                    done = 1;
                    break;
                }
            }
        }
    }
    CHECK(done);
    CHECK(naked);
    CHECK_EQ_INT(pts, path_count(&rig.p.path));
    /* the final text reply */
    rig.m.out_len = rig.scan = 0;
    CHECK(next_line(l, sizeof l, 2000));
    CHECK(strcmp(l, "ok") == 0);
    CHECK(rig.p.tail.open);
    return 0;
}

int test_stream_frames(void)
{
    char l[64];
    CHECK(frames_run() == 0);
    /* a late duplicate ACK whose seq is '\n' arrives after the run: skipped whole, so
     * the next command is answered exactly once, normally */
    {
        uint8_t ack[8];
        int n = frame_encode((uint8_t)'\n', FRAME_ACK, NULL, 0, ack, sizeof ack);
        hal_mem_feed(&rig.m, ack, (size_t)n);
    }
    CHECK(expect_code("FORMAT GCODE", 0));
    CHECK(!next_line(l, sizeof l, 50)); /* and nothing else */
    return 0;
}

/* After a FRAMES run a stray 0x06 that is not a late host frame is line noise: the
 * held bytes are replayed as text, so no command after it is lost (finding F5 of
 * docs/HARDENING.md: the firmware once dropped 0x06 and the next five bytes). */
int test_stream_frames_tail_noise(void)
{
    static const uint8_t noise[] = {0x06, '\n', '$', 'I', '\n', 'H', 'E', 'L', 'L', 'O', '\n'};
    uint8_t ack[8];
    char l[160];
    int n, i, ver = 0, oks = 0;
    CHECK(frames_run() == 0); /* leaves a finished FRAMES run behind */
    rig.m.out_len = rig.scan = 0;
    hal_mem_feed(&rig.m, noise, sizeof noise);
    CHECK(next_line(l, sizeof l, 200));
    CHECK(strncmp(l, "error:8 ", 8) == 0); /* the line "\x06" */
    for (i = 0; i < 8 && next_line(l, sizeof l, 200); i++) {
        ver += strncmp(l, "[VER:", 5) == 0;
        oks += strcmp(l, "ok") == 0;
    }
    CHECK_EQ_INT(ver, 2); /* $I and HELLO both answered */
    CHECK_EQ_INT(oks, 2);
    CHECK(rig.p.tail.open); /* neither ends the tail: late frames may still come */
    /* a frame with a bad CRC is noise too (its bytes join the next line) */
    n = frame_encode((uint8_t)' ', FRAME_NAK, NULL, 0, ack, sizeof ack);
    ack[3] ^= 1u;
    hal_mem_feed(&rig.m, ack, (size_t)n);
    host_send("\n");
    CHECK(next_line(l, sizeof l, 200));
    CHECK(strncmp(l, "error:8 ", 8) == 0);
    /* a stalled prefix (0x06 then '\n', nothing more) is replayed after OUT_FRAMES_TAIL_MS */
    hal_mem_feed(&rig.m, noise, 2);
    CHECK(next_line(l, sizeof l, 2 * (int)OUT_FRAMES_TAIL_MS));
    CHECK(strncmp(l, "error:8 ", 8) == 0);
    /* a valid late frame is still dropped whole, even split across polls */
    n = frame_encode((uint8_t)'\n', FRAME_NAK, NULL, 0, ack, sizeof ack);
    for (i = 0; i < n; i++) {
        hal_mem_feed(&rig.m, ack + i, 1);
        (void)proto_poll(&rig.p);
    }
    CHECK(rig.p.tail.open);
    CHECK(expect_code("FORMAT GCODE", 0));
    CHECK(!next_line(l, sizeof l, 50));
    CHECK(!rig.p.tail.open);
    /* once a text command ran, 0x06 is plain noise at once */
    hal_mem_feed(&rig.m, noise, 2);
    CHECK(next_line(l, sizeof l, 5));
    CHECK(strncmp(l, "error:8 ", 8) == 0);
    CHECK(!next_line(l, sizeof l, 50));
    return 0;
}

/* A machine that numbers lines differently (its Resend: asks for a line never sent)
 * cannot be trusted: the run stops with error:19. Machine chatter gets no reply. */
int test_stream_resend_out_of_sync(void)
{
    char l[160];
    int i, got = 0;
    rig_init();
    CHECK(load(paper_job));
    CHECK(expect_code("CHECKSUM ON", 0));
    host_send("RUN\n");
    for (i = 0; i < 10 && next_line(l, sizeof l, 200); i++) {
        if (strncmp(l, "N0 M110 N0*", 11) == 0) {
            host_send("echo:busy: processing\n"); /* chatter: ignored */
            host_send("Resend: 151\n");          /* never sent: out of sync */
            host_send("ok\n");
        }
        if (strncmp(l, "error:", 6) == 0) {
            CHECK(strncmp(l, "error:19 ", 9) == 0);
            got = 1;
            break;
        }
    }
    CHECK(got);
    CHECK(rig.p.state == PROTO_IDLE);
    CHECK(expect_code("$I", 0));
    return 0;
}

/* SURFACE selects the model RUN streams; a model not compiled in is refused; the
 * canal is the default and SURFACE CANAL keeps its geometry. */
int test_stream_surface(void)
{
    static const char *const kinds[3] = {"GSR", "CHANNEL", "DRC"};
    static const int have[3] = {CP_WITH_GSR, CP_WITH_CHANNEL, CP_WITH_DRC};
    char l[160];
    unsigned i;
    rig_init();
    CHECK(rig.p.job.kind == PATH_CANAL);
    CHECK(expect_code("SURFACE", CP_ST_BAD_ARITY));
    CHECK(expect_code("SURFACE CANAL EXTRA", CP_ST_BAD_ARITY));
    CHECK(expect_code("SURFACE TORUS", CP_ST_BAD_KEYWORD));
    CHECK(load(paper_job));
    for (i = 0; i < 3u; i++) {
        char cmd[32];
        snprintf(cmd, sizeof cmd, "SURFACE %s", kinds[i]);
        CHECK(expect_code(cmd, have[i] ? CP_ST_OK : CP_ST_BAD_KEYWORD));
        if (have[i]) {
            CHECK(rig.p.job.kind == i + 1u);
            CHECK(expect_code("RUN", CP_ST_NO_JOB)); /* its geometry starts empty */
        }
    }
    CHECK(expect_code("surface canal", CP_ST_OK));
    CHECK(rig.p.job.kind == PATH_CANAL);
    CHECK(expect_code("STEPS 4", CP_ST_OK));
    host_send("RUN\n");
    CHECK(next_line(l, sizeof l, 200));
    CHECK(strncmp(l, "[RUN:points=", 12) == 0);
    return 0;
}

/* A machine that never answers during a GCODE run: the firmware sends what fits its
 * RX buffer, then stops with error:22 once nothing was acknowledged for
 * OUT_GCODE_PEER_TIMEOUT_MS, and answers commands again. */
int test_stream_silent_machine(void)
{
    char l[160];
    int i, g1 = 0, got = 0;
    size_t bytes = 0;
    rig_init();
    rig.m.tick_ms = 7; /* a few now_ms calls per poll: the timeout passes in ~1000 polls */
    CHECK(load(paper_job));
    CHECK(expect_code("RXBUF 128", 0));
    host_send("RUN\n");
    for (i = 0; i < 200 && next_line(l, sizeof l, 4000); i++) {
        if (l[0] == 'G' || l[0] == 'M') { /* the program's lines */
            g1++;
            bytes += strlen(l) + 1u;
            continue;
        }
        if (l[0] == '[') {
            continue;
        }
        CHECK(strncmp(l, "error:22 ", 9) == 0);
        got = 1;
        break;
    }
    CHECK(got);
    CHECK(g1 > 0);
    CHECK(bytes <= 128u); /* never more than the machine's RX buffer unacknowledged */
    CHECK(rig.p.state == PROTO_IDLE);
    CHECK(rig.m.now >= OUT_GCODE_PEER_TIMEOUT_MS);
    printf("  note: silent machine: %d lines (%u bytes) in flight, error:22 at %u ms\n", g1,
           (unsigned)bytes, (unsigned)rig.m.now);
    CHECK(expect_code("$I", 0));
    return 0;
}
