/* pollgap_m4f.c - the worst gap between two reads of the host link while RUN checks a job
 * (issue 22: a controller that always answers), on QEMU mps2-an386 -icount shift=7.
 * SPDX-License-Identifier: MIT
 *
 * Build and run: make pollgap (mk/hardening.mk). The engine (proto.c) runs over the
 * in-memory HAL (tests/hal_mem.c) behind a thin port whose read() and write() note the
 * instruction clock: TIMER0 as in bench/bench_m4f.c (with -icount shift=7 one instruction
 * is 128 ns of virtual time and TIMER0 ticks every 40 ns, so a span of `ticks` is
 * round(ticks * 40 / 128) instructions, exact). The main loop is the firmware's:
 * proto_poll, again and again; proto_poll reads the link once per call while nothing is
 * pending. Per job (its command lines, then RUN):
 *
 *   gap     the largest span between two consecutive read() calls, from the read that
 *           brought RUN up to POLLGAP_AFTER polls after the check ended (the stream's
 *           first items, or RUN's error): every slice of the check, the parsing, the
 *           check's begin (canal_init) and RESUME's first point included. Limit:
 *           POLLGAP_LIMIT instructions.
 *   answer  '?' fed in the middle of the check (after POLLGAP_ASK_AT polls): the span from
 *           the read() that took it to the write() that sent "<Check|...>" (which must
 *           come, and within the gap's limit).
 *   cancel  the same job again, Ctrl-X fed in the middle of the check: "error:20 aborted"
 *           is sent within the limit, then '?' answers "<Idle>".
 *
 * The closing line is "pollgap: N passed, N failed"; the exit status is the failure
 * count. Counts are identical from run to run (make pollgap runs it twice).
 */
#include <string.h>

#include "bench_print.h"
#include "fmt.h"
#include "hal_mem.h"
#include "mps2.h"
#include "proto.h"
#include "semihost.h"

/* 1 M instructions: about 6 ms at 168 MHz (issue 22's acceptance). */
#ifndef POLLGAP_LIMIT
#define POLLGAP_LIMIT 1000000u
#endif
/* '?' or Ctrl-X is fed after this many polls of the check. */
#define POLLGAP_ASK_AT 3u
/* Polls measured after the check (the start of the stream: its lead items and first
 * points, RESUME's march to its first point included). */
#define POLLGAP_AFTER 8u
/* Polls of one RUN at most (a check of the largest job below takes a few thousand). */
#define POLLGAP_POLLS_MAX 2000000u

struct pg_job {
    const char *name;
    const char *const *lines; /* protocol command lines, NULL-terminated */
    const char *run;          /* the run command: "RUN" or "RESUME k" */
    int held;                 /* 1: held to POLLGAP_LIMIT; 0: measured and reported only */
};

/* The paper's example as host_sim judges it: 8 lines, 2 um. */
static const char *const job_paper[] = {"CURVE ARC 0 0 3 0 360", "RADIUS COS 5.5 10.5 2",
                                        "LINES 8 -25 10", "TOL 2", "FORMAT FRAMES", NULL};
/* The most lines, an ellipse (Lambda by Simpson: 2 jets per panel), steps derived. */
static const char *const job_ellipse[] = {"CURVE ELLIPSE 0 0 40 30 0 300", "RADIUS LINEAR 4 6",
                                          "LINES 256 -40 40", "TOL 1", "FORMAT FRAMES", NULL};
/* The most lines and the most steps, given: one walk of 256 x 4096. */
static const char *const job_max[] = {"CURVE ARC 0 0 30 0 300", "RADIUS COS 1 8 2",
                                      "LINES 256 -60 60", "STEPS 4096", "FORMAT FRAMES", NULL};
/* An ellipse's line of the most steps, given, resumed near its end: RESUME's first point
 * marches Lambda from t0 to the point at once, in one poll after the check (up to steps x
 * substeps panels). Not sliced: the canal image has no flash room for it (issue 22's
 * note in README.md), so this row is measured and reported, not held to the limit. */
static const char *const job_resume[] = {"CURVE ELLIPSE 0 0 40 30 0 300", "RADIUS LINEAR 4 6",
                                         "LINES 2 -40 40", "STEPS 4096", "FORMAT FRAMES", NULL};
/* A Bezier with a ball tool, characteristic circles between two lines, 256 circles. */
static const char *const job_circles[] = {"CURVE BEZIER 0 0 20 40 60 -40 80 0",
                                          "RADIUS CUBIC 3 4 4 3", "TOOL BALL 1",
                                          "CIRCLES 256 -40 40 PATCH", "TOL 1", "FORMAT FRAMES",
                                          NULL};

static const struct pg_job jobs[] = {
    {"paper_lines8_tol2", job_paper, "RUN", 1},
    {"ellipse_lines256_tol1", job_ellipse, "RUN", 1},
    {"arc_lines256_steps4096", job_max, "RUN", 1},
    {"bezier_tool_circles256", job_circles, "RUN", 1},
    {"ellipse_steps4096_resume", job_resume, "RESUME 4000", 0},
};
#define N_JOBS (sizeof jobs / sizeof jobs[0])

/* ---- the timed port: hal_mem behind read/write that note the instruction clock ---- */
static struct hal_mem mem;
static struct hal_uart mem_uart; /* hal_mem's own calls */
static struct hal_uart port;     /* what the engine sees */
static struct proto engine;

static uint32_t t_read;      /* TIMER0 at the last read() */
static uint32_t gap_max;     /* largest read-to-read span, instructions */
static int measuring;        /* 1: spans count towards gap_max */
static uint32_t t_asked;     /* TIMER0 at the read() that took the real-time byte */
static uint8_t asked;        /* the real-time byte fed (0: none) */
static int ask_read;         /* 1: the byte has been read */
static uint32_t answer_insns;/* read of the byte -> write() of its answer */
static const char *answer;   /* the answer's start ("<Check|", "error:20") */
static int answered;

static int port_read(void *ctx, uint8_t *buf, size_t cap)
{
    uint32_t t = MPS2_TIMER0_VALUE, gap = ticks_to_insns(t_read, t);
    int n;
    (void)ctx;
    if (measuring && gap > gap_max) {
        gap_max = gap;
    }
    t_read = t;
    n = hal_uart_read(&mem_uart, buf, cap);
    if (asked != 0u && !ask_read && n > 0 && memchr(buf, asked, (size_t)n) != NULL) {
        ask_read = 1;
        t_asked = t;
    }
    return n;
}

static int port_write(void *ctx, const uint8_t *buf, size_t len)
{
    uint32_t t = MPS2_TIMER0_VALUE;
    size_t a = answer != NULL ? strlen(answer) : 0u;
    (void)ctx;
    if (ask_read && !answered && a > 0u && len >= a && memcmp(buf, answer, a) == 0) {
        answered = 1;
        answer_insns = ticks_to_insns(t_asked, t);
    }
    return hal_uart_write(&mem_uart, buf, len);
}

static uint32_t port_now(void *ctx)
{
    (void)ctx;
    return hal_uart_now_ms(&mem_uart);
}

/* v instructions as ms at 168 MHz, 2 decimals */
static void print_ms168(uint32_t v)
{
    char b[16];
    size_t pos = 0;
    (void)fmt_fixed(b, sizeof b - 1u, &pos, (int32_t)(((uint64_t)v * 100u + 84000u) / 168000u), 2);
    b[pos] = '\0';
    print(b);
}

/* Up to the first newline of what the engine sent from offset `from`. */
static void print_reply(size_t from)
{
    char b[96];
    size_t i;
    for (i = 0; i + 1u < sizeof b && from + i < mem.out_len && mem.out[from + i] != '\n'; i++) {
        b[i] = (char)mem.out[from + i];
    }
    b[i] = '\0';
    print(b);
}

/* Fresh engine, the job's lines each answered "ok". 0 on success. */
static int load(const struct pg_job *pj)
{
    struct proto_cfg cfg = {0};
    size_t l;
    uint32_t i;
    hal_mem_init(&mem, &mem_uart);
    port.ctx = NULL;
    port.read = port_read;
    port.write = port_write;
    port.now_ms = port_now;
    cfg.uart = &port;
    if (proto_init(&engine, &cfg) != CP_OK) {
        return -1;
    }
    for (l = 0; pj->lines[l] != NULL; l++) {
        hal_mem_clear_out(&mem);
        (void)hal_mem_feed_str(&mem, pj->lines[l]);
        (void)hal_mem_feed_str(&mem, "\n");
        for (i = 0; i < 64u && proto_poll(&engine) > 0; i++) {
        }
        if (mem.out_len != 3u || memcmp(mem.out, "ok\n", 3u) != 0) {
            print("  job line not ok: ");
            print(pj->lines[l]);
            print("\n");
            return -1;
        }
    }
    hal_mem_clear_out(&mem);
    return 0;
}

/* RUN the loaded job; feed `byte` (0: none) after POLLGAP_ASK_AT polls of the check and
 * expect an answer starting with `expect`. Polls until the check is over and one more
 * poll has run (the first stream item, or the reply, is then written). Returns the
 * polls of the check (0: it never started). */
static uint32_t run(const char *cmd, uint8_t byte, const char *expect)
{
    uint32_t polls = 0, i;
    gap_max = 0u;
    asked = 0u;
    ask_read = 0;
    answered = 0;
    answer = expect;
    answer_insns = 0u;
    (void)hal_mem_feed_str(&mem, cmd);
    (void)hal_mem_feed_str(&mem, "\n");
    t_read = MPS2_TIMER0_VALUE;
    measuring = 0;
    (void)proto_poll(&engine); /* reads RUN: the first span counted starts here */
    measuring = 1;
    for (i = 0; i < POLLGAP_POLLS_MAX && engine.state == PROTO_CHECK; i++) {
        if (byte != 0u && i == POLLGAP_ASK_AT) {
            uint8_t b[1];
            b[0] = byte;
            asked = byte;
            (void)hal_mem_feed(&mem, b, 1u);
        }
        (void)proto_poll(&engine);
        polls++;
    }
    for (i = 0; i < POLLGAP_AFTER; i++) { /* the check's end, the stream's first items */
        (void)proto_poll(&engine);
    }
    measuring = 0;
    return polls;
}

int main(void)
{
    size_t i;
    int passed = 0, failed = 0;
    uint32_t worst = 0u;
    MPS2_TIMER0_CTRL = 0u;
    MPS2_TIMER0_RELOAD = 0xFFFFFFFFu;
    MPS2_TIMER0_VALUE = 0xFFFFFFFFu;
    MPS2_TIMER0_CTRL = MPS2_TIMER_CTRL_EN;
    print("pollgap: largest span between two reads of the host link during RUN's check, "
          "instructions (QEMU -icount shift=7; ms at 168 MHz); limit ");
    print_u32(POLLGAP_LIMIT);
    print("\n");
    for (i = 0; i < N_JOBS; i++) {
        uint32_t polls, gap;
        size_t l;
        int ok;
        print("job ");
        print(jobs[i].name);
        print(":");
        for (l = 0; jobs[i].lines[l] != NULL; l++) {
            print(l ? " | " : " ");
            print(jobs[i].lines[l]);
        }
        print(" | ");
        print(jobs[i].run);
        print("\n");
        /* 1. the gap, and '?' answered in the middle of the check */
        if (load(&jobs[i]) != 0) {
            failed++;
            continue;
        }
        polls = run(jobs[i].run, '?', "<Check|");
        gap = gap_max;
        ok = polls > POLLGAP_ASK_AT && (gap <= POLLGAP_LIMIT || !jobs[i].held) && answered &&
             answer_insns <= POLLGAP_LIMIT && engine.path.info.count > 0u;
        print("  check: ");
        print_u32(polls);
        print(" polls, ");
        print_u32(engine.path.info.count);
        print(" points (n ");
        print_u32(engine.path.info.n);
        print(", steps ");
        print_u32(engine.path.info.steps);
        print(", link ");
        print_u32(engine.path.info.link);
        print(")\n  gap max ");
        print_u32(gap);
        print(" (");
        print_ms168(gap);
        print(jobs[i].held ? " ms)" : " ms; not held to the limit: RESUME's first point)");
        print("\n  '?' answered after ");
        print_u32(answer_insns);
        print(" (");
        print_ms168(answer_insns);
        print(" ms): ");
        {
            size_t at = 0;
            while (at + 7u <= mem.out_len && memcmp(mem.out + at, "<Check|", 7u) != 0) {
                at++;
            }
            if (answered) {
                print_reply(at);
            } else {
                print("(no answer)");
            }
        }
        print("\n");
        worst = jobs[i].held && gap > worst ? gap : worst;
        /* 2. Ctrl-X cancels the check; then the engine is idle */
        if (load(&jobs[i]) != 0) {
            failed++;
            continue;
        }
        (void)run(jobs[i].run, 0x18u, "error:20");
        {
            uint32_t cancel = answer_insns;
            int cancelled = answered && engine.state == PROTO_IDLE;
            hal_mem_clear_out(&mem);
            (void)hal_mem_feed_str(&mem, "?");
            (void)proto_poll(&engine);
            (void)proto_poll(&engine);
            cancelled = cancelled && mem.out_len == 7u && memcmp(mem.out, "<Idle>\n", 7u) == 0;
            print("  Ctrl-X: error:20 after ");
            print_u32(cancel);
            print(cancelled ? ", then <Idle>\n" : ": NOT cancelled\n");
            ok = ok && cancelled && cancel <= POLLGAP_LIMIT;
        }
        print(ok ? "  PASS " : "  FAIL ");
        print(jobs[i].name);
        print("\n");
        passed += ok;
        failed += !ok;
    }
    print("pollgap: worst gap of the held jobs ");
    print_u32(worst);
    print(" instructions (");
    print_ms168(worst);
    print(" ms at 168 MHz)\n");
    print("pollgap: ");
    print_u32((uint32_t)passed);
    print(" passed, ");
    print_u32((uint32_t)failed);
    print(" failed\n");
    semihost_exit(failed);
    return failed;
}
