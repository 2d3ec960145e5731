/* test_proto.c - fmt and the line protocol engine over the in-memory HAL.
 * SPDX-License-Identifier: MIT
 */
#include <ctype.h>
#include <stdio.h>
#include <string.h>

#include "fmt.h"
#include "hal_mem.h"
#include "proto.h"
#include "test.h"

int test_fmt_numbers(void)
{
    char b[64];
    size_t pos = 0;
    CHECK_EQ_INT(fmt_u32(b, sizeof b, &pos, 0u), CP_OK);
    CHECK_EQ_INT(fmt_str(b, sizeof b, &pos, " "), CP_OK);
    CHECK_EQ_INT(fmt_u32(b, sizeof b, &pos, 4294967295u), CP_OK);
    CHECK_EQ_INT(fmt_str(b, sizeof b, &pos, " "), CP_OK);
    CHECK_EQ_INT(fmt_i32(b, sizeof b, &pos, -2147483647 - 1), CP_OK);
    CHECK_EQ_INT(fmt_str(b, sizeof b, &pos, " "), CP_OK);
    CHECK_EQ_INT(fmt_fixed(b, sizeof b, &pos, -12345, 4), CP_OK);
    CHECK_EQ_INT(fmt_str(b, sizeof b, &pos, " "), CP_OK);
    CHECK_EQ_INT(fmt_fixed(b, sizeof b, &pos, 7, 4), CP_OK);
    CHECK_EQ_INT(fmt_str(b, sizeof b, &pos, " "), CP_OK);
    CHECK_EQ_INT(fmt_fixed(b, sizeof b, &pos, -7, 3), CP_OK);
    b[pos] = '\0';
    CHECK(strcmp(b, "0 4294967295 -2147483648 -1.2345 0.0007 -0.007") == 0);
    /* a full buffer is reported, never overrun */
    pos = 0;
    CHECK_EQ_INT(fmt_u32(b, 3, &pos, 12345u), CP_ERR_FULL);
    CHECK_EQ_INT(pos, 0);
    CHECK_EQ_INT(fmt_fixed(b, 64, &pos, 1, 10), CP_ERR_INVAL);
    return 0;
}

/* Run the engine until it is idle for a few polls (bounded). */
static void pump(struct proto *p)
{
    int idle = 0, i;
    for (i = 0; i < 100000 && idle < 4; i++) {
        idle = proto_poll(p) > 0 ? 0 : idle + 1;
    }
}

/* cp_status_of: the FROM column of cp_status.def, CP_ERR_INVAL as OUT_OF_RANGE and the
 * codes no row names as NUMERIC (the mapping job_status_of had, case by case). */
/* commands.def: every keyword names one command, and a word (or option) names one entry
 * of its command's list (job.c looks them up by text and takes the first match, so a
 * second row with the same text could never be reached). */
struct cmd_text {
    const char *text;
    int cmd; /* enum job_cmd of the command a word belongs to; -1 for a keyword */
};
static const struct cmd_text cmd_texts[] = {
#define CP_CMD(OWNER, NAME, KEYWORD, SHAPE, MIN, MAX, SURFACE) {KEYWORD, -1},
#define CP_CMD_WORD(CMD, WORD, TEXT, NUMBERS, VALUE) {TEXT, (int)(CMD)},
#define CP_CMD_OPTION(CMD, WORD, TEXT, VALUE) {TEXT, (int)(CMD)},
#include "commands.def"
#undef CP_CMD
#undef CP_CMD_WORD
#undef CP_CMD_OPTION
};

static int same_text(const char *a, const char *b)
{
    while (*a != '\0' && toupper((unsigned char)*a) == toupper((unsigned char)*b)) {
        a++;
        b++;
    }
    return *a == '\0' && *b == '\0';
}

int test_commands_distinct(void)
{
    size_t n = sizeof cmd_texts / sizeof cmd_texts[0], i, k;
    unsigned keywords = 0;
    for (i = 0; i < n; i++) {
        keywords += cmd_texts[i].cmd < 0;
        for (k = i + 1; k < n; k++) {
            if (cmd_texts[i].cmd == cmd_texts[k].cmd && same_text(cmd_texts[i].text, cmd_texts[k].text)) {
                printf("  commands.def: \"%s\" twice (%s)\n", cmd_texts[i].text,
                       cmd_texts[i].cmd < 0 ? "keywords" : "words of one command");
                CHECK(0);
            }
        }
    }
    CHECK_EQ_INT((int)keywords, (int)JOB_CMDS);
    TEST_NOTE("commands.def: %u keywords and %u words, all distinct\n", keywords,
              (unsigned)(n - keywords));
    return 0;
}

int test_status_of(void)
{
    static const struct {
        int err, st;
    } map[] = {
        {CP_OK, CP_ST_OK},
        {CP_ERR_INVAL, CP_ST_OUT_OF_RANGE},
        {CP_ERR_NONFINITE, CP_ST_NONFINITE},
        {CP_ERR_RANGE, CP_ST_OUT_OF_RANGE},
        {CP_ERR_RADIUS, CP_ST_RADIUS},
        {CP_ERR_DEGENERATE, CP_ST_DEGENERATE},
        {CP_ERR_EMPTY, CP_ST_EMPTY},
        {CP_ERR_TOO_MANY, CP_ST_TOO_MANY},
        {CP_ERR_TOOL, CP_ST_TOOL},
        {CP_ERR_CUSP, CP_ST_CUSP},
        {CP_ERR_NUMERIC, CP_ST_NUMERIC},
        {CP_ERR_TOL, CP_ST_TOL},
        {CP_ERR_IO, CP_ST_NUMERIC},
        {CP_ERR_FULL, CP_ST_NUMERIC},
        {CP_ERR_STATE, CP_ST_NUMERIC},
        {CP_ERR_DONE, CP_ST_NUMERIC},
        {CP_ERR_OFF_PLANE, CP_ST_OFF_PLANE},
        {CP_ERR_FRENET, CP_ST_FRENET},
        {CP_ERR_FRAME_REF, CP_ST_FRAME_REF},
        {CP_ERR_SECTION, CP_ST_SECTION},
        {CP_ERR_FT_RANGE, CP_ST_FT_RANGE},
        {CP_ERR_FOLD, CP_ST_FOLD},
        {CP_ERR_TOO_FEW, CP_ST_TOO_FEW},
        {CP_ERR_EXPONENT, CP_ST_EXPONENT},
        {CP_ERR_COINCIDENT, CP_ST_COINCIDENT},
        {CP_ERR_SECTION_PLANE, CP_ST_SECTION_PLANE},
        {CP_ERR_AREA_LAW, CP_ST_AREA_LAW},
        {CP_ERR_ISOTROPIC, CP_ST_ISOTROPIC},
        {CP_ERR_TURN, CP_ST_TURN},
        {CP_ERR_TWIST, CP_ST_TWIST},
        {CP_ERR_BUFFER, CP_ST_BUFFER},
        {CP_ERR_SEAM, CP_ST_SEAM},
        {CP_ERR_OVERLAP, CP_ST_OVERLAP},
        {-33, CP_ST_NUMERIC}, /* not (yet) an enum cp_err */
        {1, CP_ST_NUMERIC},   /* WIRE_ONLY's value is no cp_err */
    };
    unsigned i;
    for (i = 0; i < sizeof map / sizeof map[0]; i++) {
        CHECK_EQ_INT(cp_status_of(map[i].err), map[i].st);
    }
    return 0;
}

/* The check order of every argument shape (job.h enum job_shape, commands.def): arity,
 * word, unsigned number, numbers, then the hook's ranges; the option words of TOOL (after
 * the range) and CIRCLES (before everything); a model's command under another SURFACE. */
int test_job_shapes(void)
{
    static const struct {
        const char *line;
        int st;
    } cases[] = {
        {"TOOL NONE x", CP_ST_BAD_KEYWORD},       /* a word without numbers takes nothing */
        {"TOOL BALL", CP_ST_BAD_ARITY},           /* BALL r */
        {"TOOL BALL x FOO", CP_ST_BAD_NUMBER},    /* numbers before the option */
        {"TOOL BALL -1 FOO", CP_ST_OUT_OF_RANGE}, /* the range before the option */
        {"TOOL BALL 1 FOO", CP_ST_BAD_KEYWORD},
        {"TOOL BALL 1 TIP X", CP_ST_BAD_ARITY},
        {"tool ball 1 centre", CP_ST_OK},
        {"CIRCLES 3 x 10 FOO", CP_ST_BAD_KEYWORD}, /* the option before the numbers */
        {"CIRCLES 3 x 10 PATCH", CP_ST_BAD_NUMBER},
        {"LINES 3 -10 10 PATCH", CP_ST_BAD_ARITY}, /* LINES has no option */
        {"CIRCLES 3 -10 10 PATCH", CP_ST_OK},
        {"FORMAT X Y", CP_ST_BAD_ARITY}, /* WORD: arity before the word */
        {"FORMAT XML", CP_ST_BAD_KEYWORD},
        {"CURVE FOO 1", CP_ST_BAD_KEYWORD}, /* WORD_THEN_NUMBERS: the word first */
        {"CURVE LINE 0 0 1", CP_ST_BAD_ARITY},
        {"CURVE LINE 0 0 1 nan", CP_ST_NONFINITE},
        {"STEPS x", CP_ST_BAD_NUMBER}, /* UINT_OR_WORD without words */
        {"STEPS 4294967296", CP_ST_OUT_OF_RANGE},
        {"STEPS 1 2", CP_ST_BAD_ARITY},
        {"POINT 1 2", CP_ST_WRONG_SURFACE}, /* before the arity */
        {"POINT 1", CP_ST_WRONG_SURFACE},
        {"SURFACE FOO", CP_ST_BAD_KEYWORD},
        {"SURFACE DRC", CP_ST_OK},
        {"POINT 1", CP_ST_BAD_ARITY}, /* NUMBERS 2..3 */
        {"POINT 1 2 3 4", CP_ST_BAD_ARITY},
        {"POINT 1e5 0", CP_ST_OUT_OF_RANGE},
        {"THICKEN x", CP_ST_BAD_NUMBER}, /* UINT_OR_WORD: not AUTO, so a number */
        {"THICKEN 99", CP_ST_TOO_MANY},
        {"THICKEN auto", CP_ST_OK},
        {"EDGE MAYBE", CP_ST_BAD_KEYWORD},
        {"SECTION 1 1 2 0 0 0 0 0 0", CP_ST_WRONG_SURFACE},
        {"RUN", JOB_NOT_MINE}, /* the protocol's */
        {"RESUME 3", JOB_NOT_MINE},
        {"FOO 1", JOB_NOT_MINE},
    };
    static struct job j;
    uint32_t k = 7u;
    unsigned i;
    job_init(&j);
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        int st = job_command(&j, cases[i].line, strlen(cases[i].line));
        if (st != cases[i].st) {
            printf("  note: %s -> %d\n", cases[i].line, st);
        }
        CHECK_EQ_INT(st, cases[i].st);
    }
    /* the protocol's entry: RUN alone and RESUME k run, RESUME's own range code */
    CHECK_EQ_INT(job_line(&j, "RUN", 3u, &k), JOB_RUN);
    CHECK_EQ_INT(k, 0);
    CHECK_EQ_INT(job_line(&j, "RUN 1", 5u, &k), JOB_NOT_MINE);
    CHECK_EQ_INT(job_line(&j, "RESUME 12", 9u, &k), JOB_RUN);
    CHECK_EQ_INT(k, 12);
    CHECK_EQ_INT(job_line(&j, "RESUME 4294967296", 17u, &k), CP_ST_RESUME_RANGE);
    CHECK_EQ_INT(job_line(&j, "RESUME", 6u, &k), CP_ST_BAD_ARITY);
    return 0;
}

int test_proto_info(void)
{
    static struct hal_mem m;
    struct hal_uart u;
    struct proto p;
    struct proto_cfg cfg = {0};
    static char want[512];
    char line[CP_LINE_MAX + 40];
    size_t i;

    hal_mem_init(&m, &u);
    cfg.uart = &u;
    CHECK_EQ_INT(proto_init(&p, &cfg), CP_OK);
    cfg.uart = NULL;
    CHECK_EQ_INT(proto_init(&p, &cfg), CP_ERR_INVAL);
    cfg.uart = &u;
    CHECK_EQ_INT(proto_init(&p, &cfg), CP_OK);

    /* nothing is streamed before the host has spoken */
    pump(&p);
    CHECK_EQ_INT(m.out_len, 0);

    m.write_chunk = 3; /* partial writes are normal */
    hal_mem_feed_str(&m, "$I\r\nhello\n\nFOO\n");
    pump(&p);
    snprintf(want, sizeof want,
             "[VER:canalpath %s proto %d]\n[OPT:real=%s,line=%d,tx=%d,steps=%d,sub=%d,lines=%d,"
             "link=%d,window=%d,models=CANAL%s%s%s%s]\nok\n",
             CP_FW_VERSION, CP_PROTO_VERSION, CP_REAL_NAME, CP_LINE_MAX, CP_TX_BUF, CP_MAX_STEPS,
             CP_MAX_SUBSTEPS, CP_MAX_LINES, CP_MAX_LINK, (int)OUT_FRAMES_WINDOW,
             CP_WITH_GSR ? "+GSR" : "", CP_WITH_CHANNEL ? "+CHANNEL" : "",
             CP_WITH_DRC ? "+DRC" : "", CP_WITH_SPINE ? "+SPINE" : "");
    i = strlen(want);
    CHECK(m.out_len == 2 * i + strlen("ok\nerror:1 unknown command\n"));
    CHECK(memcmp(m.out, want, i) == 0);
    CHECK(memcmp(m.out + i, want, i) == 0);
    CHECK(memcmp(m.out + 2 * i, "ok\nerror:1 unknown command\n", 27) == 0);

    /* an over-long line and a line with a control byte get their codes, and the
     * engine is ready for the next line */
    hal_mem_clear_out(&m);
    memset(line, 'A', sizeof line);
    line[sizeof line - 1] = '\n';
    hal_mem_feed(&m, line, sizeof line);
    hal_mem_feed(&m, "$\x01I\n$i\n", 7);
    pump(&p);
    CHECK(m.out_len > 40);
    CHECK(memcmp(m.out, "error:2 line too long\nerror:8 invalid character in line\n[VER:", 60) ==
          0);

    /* hang-up is reported and sticky */
    hal_mem_hangup(&m);
    hal_mem_feed_str(&m, "$I\n");
    CHECK_EQ_INT(proto_poll(&p), CP_ERR_IO);
    CHECK_EQ_INT(proto_poll(&p), CP_ERR_IO);
    return 0;
}

/* Feed a host frame (seq, type) to the FRAMES decoder; returns what take asks for, or
 * -1 if the decoder did not complete it. */
static int host_frame(struct out_frames *f, struct out_run *run, uint8_t seq, uint8_t type,
                      uint32_t now)
{
    uint8_t b[FRAME_MIN];
    int i, n = frame_encode(seq, type, NULL, 0u, b, sizeof b), done = 0;
    for (i = 0; i < n; i++) {
        done = out_frames_rx(f, b[i]);
    }
    return done ? (int)out_frames_take(f, run, now) : -1;
}

/* The output modules on their own, without the engine: the machine's answers, the
 * FRAMES window's ACK/NAK arithmetic and the late-frame tail. */
int test_out_modules(void)
{
    /* the answers by dialect (machine.h): what grbl and Marlin really send */
    static const struct {
        unsigned m;
        const char *line;
        enum machine_reply kind;
        uint32_t num;
    } ans[] = {
        {JOB_MACHINE_GRBL, "ok", MACHINE_OK, 0u},
        {JOB_MACHINE_GRBL, "okay", MACHINE_OTHER, 0u},
        {JOB_MACHINE_GRBL, "ok N2 P15 B3", MACHINE_OTHER, 0u}, /* not grbl's */
        {JOB_MACHINE_MARLIN, "ok N2 P15 B3", MACHINE_OK, 0u},   /* ADVANCED_OK */
        {JOB_MACHINE_MARLIN, "ok T:21.3 /0.0", MACHINE_OK, 0u},
        {JOB_MACHINE_GRBL, "error:22", MACHINE_ERROR, 0u},
        {JOB_MACHINE_GRBL, "ALARM:9", MACHINE_ALARM, 0u},
        {JOB_MACHINE_GRBL, "<Run|MPos:1.000,2.000,0.000|FS:500,0>", MACHINE_ALIVE, 0u},
        {JOB_MACHINE_GRBL, "[MSG:Caution: Unlocked]", MACHINE_OTHER, 0u},
        {JOB_MACHINE_GRBL, "Grbl 1.1h ['$' for help]", MACHINE_RESET, 0u},
        {JOB_MACHINE_MARLIN, "echo:busy: processing", MACHINE_ALIVE, 0u},
        {JOB_MACHINE_MARLIN, "echo:Unknown command: \"M999?\"", MACHINE_OTHER, 0u},
        {JOB_MACHINE_MARLIN, "Error:checksum mismatch, Last Line: 4", MACHINE_RETRY, 0u},
        {JOB_MACHINE_MARLIN, "Error:Printer halted. kill() called!", MACHINE_ERROR, 0u},
        {JOB_MACHINE_MARLIN, "Resend: 7", MACHINE_RESEND, 7u},
        {JOB_MACHINE_MARLIN, "Resend:8", MACHINE_RESEND, 8u},
        {JOB_MACHINE_MARLIN, "rs N12", MACHINE_RESEND, 12u},
        {JOB_MACHINE_MARLIN, "Resend: x", MACHINE_RESEND, UINT32_MAX},
        {JOB_MACHINE_MARLIN, "start", MACHINE_RESET, 0u},
        {JOB_MACHINE_MARLIN, "!!", MACHINE_ALARM, 0u},
        {JOB_MACHINE_GENERIC, "o", MACHINE_OTHER, 0u},
        {JOB_MACHINE_GENERIC, "", MACHINE_OTHER, 0u},
        {JOB_MACHINE_GENERIC, "Resend", MACHINE_OTHER, 0u},
    };
    static struct job job;
    struct out_gcode g;
    struct out_frames f;
    struct out_frames_tail t;
    struct out_run run;
    uint8_t late[FRAME_MIN];
    size_t i;
    uint32_t num;
    int n;
    for (i = 0; i < sizeof ans / sizeof ans[0]; i++) {
        CHECK_EQ_INT(machine_reply(ans[i].m, ans[i].line, strlen(ans[i].line), &num), ans[i].kind);
        CHECK(num == ans[i].num);
    }
    /* with checksums: a line-number error waits for its Resend, a Resend of a line sent
     * rewinds (oks are then ignored until the resync), one never sent stops the run */
    job_init(&job);
    job.checksum = 1;
    memset(&g, 0, sizeof g);
    memset(&run, 0, sizeof run);
    g.ring_n = 2;
    g.inflight = 40;
    g.ring[0] = 20;
    g.ring[1] = 20;
    run.next = 5;
    CHECK_EQ_INT(out_gcode_answer(&g, &run, &job, MACHINE_RETRY, 0u, 10u), OUT_GOING);
    CHECK_EQ_INT(out_gcode_answer(&g, &run, &job, MACHINE_RESEND, 3u, 11u), OUT_GOING);
    CHECK(run.next == 3u && g.resync == 1u && run.t_last == 11u);
    CHECK_EQ_INT(out_gcode_answer(&g, &run, &job, MACHINE_OK, 0u, 12u), OUT_GOING);
    CHECK(g.ring_n == 2u && run.acked == 0u);
    g.resync = 0;
    CHECK_EQ_INT(out_gcode_answer(&g, &run, &job, MACHINE_OK, 0u, 13u), OUT_GOING);
    CHECK(g.ring_n == 1u && g.inflight == 20u && run.acked == 1u);
    CHECK_EQ_INT(out_gcode_answer(&g, &run, &job, MACHINE_ALIVE, 0u, 14u), OUT_GOING);
    CHECK(g.ring_n == 1u && run.t_last == 14u);
    CHECK_EQ_INT(out_gcode_answer(&g, &run, &job, MACHINE_OTHER, 0u, 15u), OUT_GOING);
    CHECK(run.t_last == 14u); /* chatter is no sign of progress */
    CHECK_EQ_INT(out_gcode_answer(&g, &run, &job, MACHINE_RESEND, 3u, 16u), CP_ST_PEER_ERROR);
    CHECK_EQ_INT(out_gcode_answer(&g, &run, &job, MACHINE_ALARM, 0u, 17u), CP_ST_PEER_ERROR);
    CHECK_EQ_INT(out_gcode_answer(&g, &run, &job, MACHINE_RESET, 0u, 18u), CP_ST_MACHINE_RESET);
    job.checksum = 0;
    CHECK_EQ_INT(out_gcode_answer(&g, &run, &job, MACHINE_ERROR, 0u, 19u), CP_ST_PEER_ERROR);
    CHECK_EQ_INT(out_gcode_answer(&g, &run, &job, MACHINE_RETRY, 0u, 20u), CP_ST_PEER_ERROR);

    /* FRAMES: a cumulative ACK moves acked, an ACK beyond next is ignored, a NAK rewinds */
    memset(&f, 0, sizeof f);
    memset(&run, 0, sizeof run);
    frame_rx_init(&f.rx);
    run.next = 5;
    run.end = 10;
    f.retries = 3;
    CHECK_EQ_INT(host_frame(&f, &run, 3u, FRAME_ACK, 100u), OUT_FRAMES_NONE);
    CHECK(run.acked == 3u && run.t_last == 100u && f.retries == 0u);
    CHECK_EQ_INT(host_frame(&f, &run, 9u, FRAME_ACK, 101u), OUT_FRAMES_NONE);
    CHECK(run.acked == 3u && run.t_last == 100u);
    CHECK_EQ_INT(host_frame(&f, &run, 4u, FRAME_NAK, 102u), OUT_FRAMES_NONE);
    CHECK(run.acked == 4u && run.next == 4u && run.t_last == 102u);
    CHECK_EQ_INT(host_frame(&f, &run, 0u, FRAME_HOLD, 103u), OUT_FRAMES_HOLD);
    CHECK_EQ_INT(host_frame(&f, &run, 0u, FRAME_GO, 104u), OUT_FRAMES_GO);
    CHECK(run.t_last == 104u);
    CHECK_EQ_INT(host_frame(&f, &run, 0u, FRAME_ABORT, 105u), OUT_FRAMES_ABORT);

    /* the tail: text passes, a late ACK is dropped whole, a 0x06 prefix that fails its
     * type check or stalls is replayed byte for byte */
    memset(&t, 0, sizeof t);
    t.open = 1;
    CHECK_EQ_INT(out_frames_tail_take(&t, 'A'), OUT_FRAMES_TAIL_TEXT);
    n = frame_encode(7u, FRAME_ACK, NULL, 0u, late, sizeof late);
    CHECK_EQ_INT(n, FRAME_MIN);
    CHECK_EQ_INT(out_frames_tail_take(&t, late[0]), OUT_FRAMES_TAIL_STARTED);
    for (i = 1; i < FRAME_MIN; i++) {
        CHECK_EQ_INT(out_frames_tail_take(&t, late[i]), OUT_FRAMES_TAIL_HELD);
    }
    CHECK(t.len == 0u && t.replay == 0u);
    CHECK_EQ_INT(out_frames_tail_take(&t, FRAME_MIN), OUT_FRAMES_TAIL_STARTED);
    CHECK_EQ_INT(out_frames_tail_take(&t, 0u), OUT_FRAMES_TAIL_HELD);
    CHECK_EQ_INT(out_frames_tail_take(&t, FRAME_POINT), OUT_FRAMES_TAIL_HELD);
    CHECK(t.replay == 3u && !out_frames_tail_waiting(&t));
    CHECK_EQ_INT(out_frames_tail_next(&t), FRAME_MIN);
    CHECK_EQ_INT(out_frames_tail_next(&t), 0);
    CHECK_EQ_INT(out_frames_tail_next(&t), FRAME_POINT);
    CHECK(t.len == 0u && t.replay == 0u);
    CHECK_EQ_INT(out_frames_tail_take(&t, FRAME_MIN), OUT_FRAMES_TAIL_STARTED);
    out_frames_tail_started(&t, 200u);
    CHECK(out_frames_tail_waiting(&t));
    out_frames_tail_stalled(&t, 200u + OUT_FRAMES_TAIL_MS - 1u);
    CHECK(t.replay == 0u);
    out_frames_tail_stalled(&t, 200u + OUT_FRAMES_TAIL_MS);
    CHECK(t.replay == 1u);
    return 0;
}
