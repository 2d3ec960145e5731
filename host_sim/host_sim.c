/* host_sim.c - the host simulator: runs a firmware on a pty it creates, does the
 * $I handshake, plays a job file and checks the replies (docs/HOST_SIM.md).
 * SPDX-License-Identifier: MIT
 *
 * Usage: host_sim --target native|qemu --job FILE [--fw PATH] [--timeout-ms N]
 *                 [--log FILE] [--qemu PROGRAM] [--baud N] [--fault drop|flip|dup|hangup@N]
 *                 [--resume] [--csv FILE] [--gcode FILE] [--svg FILE] [--raw FILE]
 *                 [--min-util PCT] [--machine grbl|marlin] [--advanced-ok] [--homing]
 *                 [--machine-time SCALE]
 *                 [--cmd PROGRAM [ARGS...]]
 * Exit status: 0 iff every check passed; 1 if a check failed; 2 on a usage or
 * set-up error; 130 after SIGINT (the firmware is always killed and reaped).
 * The last line of stdout is always "sim: N passed, N failed" (also on exit 2).
 */
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "sim_cell.h"
#include "sim_check.h"
#include "sim_job.h"
#include "sim_link.h"
#include "sim_out.h"
#include "sim_pty.h"
#include "sim_run.h"

#define SIM_DEFAULT_NATIVE "build/host/fw_native"
#define SIM_DEFAULT_QEMU_FW "build/m4f/fw.elf"
#define SIM_HS_RETRY_MS 200u    /* $I is re-sent this often until answered */
#define SIM_HS_MAX_SENDS 50u    /* and at most this many times */
#define SIM_HS_REDO 3u          /* an incomplete answer: $I again, at most this often */
#define SIM_DRAIN_MS 500u       /* time allowed for answers to extra $I sends */
#define SIM_SHUTDOWN_MS 1000    /* the firmware must exit this soon after hang-up */
#define SIM_KILL_GRACE_MS 500   /* SIGTERM -> SIGKILL */

enum sim_target { SIM_NATIVE, SIM_QEMU, SIM_CMD };

static volatile sig_atomic_t sim_stop;

static struct {
    int passed, failed;
} checks;

static struct {
    unsigned long sent, ok, error, info, unknown, streamed;
    double rtt_min, rtt_max;
} stats;

static double *rtts; /* one per command, ms */

static void sim_on_signal(int sig)
{
    sim_stop = sig;
}

static void check(int ok, const char *what, const char *detail)
{
    if (ok) {
        checks.passed++;
        printf("  PASS %s\n", what);
    } else {
        checks.failed++;
        printf("  FAIL %s%s%s\n", what, detail[0] ? ": " : "", detail);
    }
}

static void finish_line(void)
{
    printf("sim: %d passed, %d failed\n", checks.passed, checks.failed);
    fflush(stdout);
}

static int usage(const char *msg)
{
    fprintf(stderr,
            "host_sim: %s\n"
            "usage: host_sim --target native|qemu --job FILE [--fw PATH] [--timeout-ms N]\n"
            "                [--log FILE] [--qemu PROGRAM] [--baud N] [--fault KIND@N]\n"
            "                [--resume] [--csv FILE] [--gcode FILE] [--svg FILE] [--raw FILE]\n"
            "                [--min-util PCT] [--machine grbl|marlin] [--advanced-ok] [--homing]\n"
            "                [--machine-time SCALE]\n"
            "                [--cmd PROGRAM [ARGS...]]\n"
            "  KIND: drop | flip | dup | hangup (byte N of the RUN stream, 0-based)\n",
            msg);
    checks.failed++;
    finish_line();
    return 2;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Print the [OPT:k=v,...] line as "k=v k=v ..." */
static void print_limits(const char *opt)
{
    size_t n = strlen(opt), i;
    printf("sim: firmware limits ");
    for (i = 5; i + 1 < n; i++) {
        putchar(opt[i] == ',' ? ' ' : opt[i]);
    }
    putchar('\n');
}

struct hs_result {
    int ok;
    unsigned sends;
    char ver[128], opt[256];
    char why[200];
};

/* Send $I every SIM_HS_RETRY_MS until "[VER:" and "ok" arrive or timeout_ms pass; an
 * "ok" that came without a clean "[VER:" line before it is asked again (SIM_HS_REDO). */
static int handshake(struct sim_link *l, unsigned timeout_ms, struct hs_result *h)
{
    uint64_t end = sim_link_now_ms() + timeout_ms;
    struct sim_reply r;
    int rc = SIM_LINK_TIMEOUT;
    unsigned unknown = 0, redo = 0;
    memset(h, 0, sizeof *h);
    while (h->sends < SIM_HS_MAX_SENDS) {
        uint64_t now = sim_link_now_ms(), d = now + SIM_HS_RETRY_MS;
        if (now >= end) {
            break;
        }
        rc = sim_link_send(l, "$I\n", 3, end);
        if (rc < 0) {
            break;
        }
        h->sends++;
        rc = sim_link_await(l, d < end ? d : end, &r, NULL, NULL);
        if (r.ver[0]) {
            memcpy(h->ver, r.ver, sizeof h->ver);
        }
        if (r.opt[0]) {
            memcpy(h->opt, r.opt, sizeof h->opt);
        }
        unknown += r.unknown;
        if (r.unknown) {
            printf("  handshake: unknown reply line \"%s\"\n", r.first_unknown);
        }
        if (rc == SIM_LINK_REPLY && !r.error && (!h->ver[0] || unknown) && redo < SIM_HS_REDO) {
            /* "ok" without a clean [VER:...] before it: the start of the answer was lost
             * (seen under QEMU on a heavily loaded host, a few bytes at connect time).
             * Ask again: a later answer must be complete; nothing of this one counts. */
            redo++;
            printf("  handshake: incomplete answer, $I again (%u of %u)\n", redo, SIM_HS_REDO);
            h->ver[0] = h->opt[0] = '\0';
            unknown = 0;
            continue;
        }
        if (rc != SIM_LINK_TIMEOUT) {
            break;
        }
    }
    if (rc == SIM_LINK_REPLY && r.error) {
        snprintf(h->why, sizeof h->why, "$I answered error:%d", r.code);
    } else if (rc == SIM_LINK_REPLY && !h->ver[0]) {
        snprintf(h->why, sizeof h->why, "no [VER:...] line before ok");
    } else if (rc == SIM_LINK_REPLY && unknown) {
        snprintf(h->why, sizeof h->why, "%u unknown line(s)", unknown);
    } else if (rc == SIM_LINK_REPLY) {
        h->ok = 1;
    } else {
        snprintf(h->why, sizeof h->why, "%s", sim_link_strerror(rc));
    }
    if (h->ok && h->sends > 1) {
        /* answers to the extra $I sends may still be on their way */
        unsigned k;
        uint64_t dend = sim_link_now_ms() + SIM_DRAIN_MS;
        for (k = 1; k < h->sends; k++) {
            if (sim_link_await(l, dend, &r, NULL, NULL) != SIM_LINK_REPLY) {
                break;
            }
        }
    }
    return rc;
}

/* The command line (sim_parse_args) */
struct sim_opts {
    enum sim_target target;
    const char *target_name; /* --target as given, or NULL */
    const char *job_path, *fw, *log_path, *qemu;
    char **cmd; /* --cmd PROGRAM [ARGS...], or NULL */
    unsigned timeout_ms;
    /* the RUN receiver and the writers */
    double baud;
    int fault;
    unsigned long fault_at;
    int resume;
    const char *csv, *gcode, *svg, *raw;
    double min_util; /* percent; < 0: not checked */
    /* --machine: a two-link cell, the emulated machine on the machine link (sim_cell.h) */
    const char *machine; /* "grbl", "marlin" or NULL (one link) */
    int advanced_ok, homing;
    double machine_time; /* --machine-time: the emulated motion's time scale (0: instant) */
};

static struct sim_opts opt;

/* One session: the job, the firmware behind its pty, the link to it */
struct sim_session {
    struct sim_job job;
    struct sim_pty pty;
    struct sim_link link;
    FILE *log;
    char **cmd;       /* the firmware's argv (cmd[8] is the pty path under QEMU) */
    char *qargv[20];  /* cmd for native and QEMU */
    uint64_t t_start; /* us */
    uint64_t t_hs;    /* us, the first handshake done (0: none) */
    int interrupted;  /* a wait returned SIM_LINK_INTR */
};

/* Job state as sent (and answered ok): what the RUN receiver must expect */
static struct {
    int frames, checksum;
    unsigned rxbuf;
    int rxbuf_set; /* RXBUF given (else the dialect's: MACHINE) */
    int acks;      /* 0: MACHINE LINUXCNC, a program file (no character counting) */
} js = {0, 0, 128, 0, 1};

/* Totals over the RUN commands of the session */
static struct {
    unsigned long runs, points;
    unsigned long long bytes_in, bytes_out;
    double run_us, wire_us;
    unsigned long resends, naks, bad, dups, gaps, hangups, resumes;
} rt;

static FILE *raw_file;

/* --machine: the cell's machine link and its emulated machine (one per session) */
static struct sim_cell cell;
static int cell_on, cell_started;

/* Case-insensitive: does text start with the keyword kw as a whole token? */
static int kw_is(const char *text, const char *kw)
{
    size_t i;
    for (i = 0; kw[i] != '\0'; i++) {
        char c = text[i];
        if (c >= 'a' && c <= 'z') {
            c = (char)(c - 'a' + 'A');
        }
        if (c != kw[i]) {
            return 0;
        }
    }
    return text[i] == '\0' || text[i] == ' ' || text[i] == '\t';
}

static const char *arg1(const char *text)
{
    while (*text != '\0' && *text != ' ' && *text != '\t') {
        text++;
    }
    while (*text == ' ' || *text == '\t') {
        text++;
    }
    return text;
}

/* A job command was answered ok: track FORMAT, CHECKSUM, RXBUF */
static void job_state(const char *text)
{
    const char *a = arg1(text);
    if (kw_is(text, "FORMAT")) {
        js.frames = kw_is(a, "FRAMES");
    } else if (kw_is(text, "CHECKSUM")) {
        js.checksum = kw_is(a, "ON");
    } else if (kw_is(text, "RXBUF")) {
        js.rxbuf = (unsigned)strtoul(a, NULL, 10);
        js.rxbuf_set = 1;
    } else if (kw_is(text, "MACHINE")) { /* machines.def: RXBUF, ACKS */
        js.acks = !kw_is(a, "LINUXCNC");
        if (!js.rxbuf_set) {
            js.rxbuf = kw_is(a, "MARLIN") ? 127u : 128u;
        }
    }
}

static int parse_fault(struct sim_opts *o, const char *v)
{
    static const char *const names[] = {"drop", "flip", "dup", "hangup"};
    static const int kinds[] = {SIM_FAULT_DROP, SIM_FAULT_FLIP, SIM_FAULT_DUP, SIM_FAULT_HANGUP};
    const char *at = strchr(v, '@');
    size_t i;
    char *e;
    if (at == NULL || at[1] < '0' || at[1] > '9') {
        return -1;
    }
    for (i = 0; i < 4; i++) {
        if (strlen(names[i]) == (size_t)(at - v) && strncmp(v, names[i], (size_t)(at - v)) == 0) {
            o->fault = kinds[i];
            o->fault_at = strtoul(at + 1, &e, 10);
            return *e == '\0' ? 0 : -1;
        }
    }
    return -1;
}

static double byte_us(void)
{
    return opt.baud > 0.0 ? 1e7 / opt.baud : 0.0;
}

/* ---- the cell (--machine) ------------------------------------------------------------- */

/* Pump the cell for ms (the machine's banner reaches the firmware while it is idle). */
static void cell_idle(unsigned ms)
{
    uint64_t end = sim_link_now_us() + (uint64_t)ms * 1000u;
    while (cell_on && sim_link_now_us() < end) {
        if (sim_cell_pump(&cell, (double)sim_link_now_us(), byte_us()) <= 0) {
            struct timespec ts = {0, 1000000L};
            (void)nanosleep(&ts, NULL);
        }
    }
}

/* The link's idle hook: the cell's machine link moves while host_sim waits for a reply. */
static void cell_link_idle(void *ctx)
{
    (void)ctx;
    (void)sim_cell_pump(&cell, (double)sim_link_now_us(), byte_us());
}

/* After the handshake: the firmware's program goes to the cell's machine in its dialect
 * (MACHINE GRBL|MARLIN, LINK MACHINE; one check). 0, or -1. */
static int cell_setup(struct sim_session *s)
{
    static const char *const lines[2][2] = {{"MACHINE GRBL\n", "LINK MACHINE\n"},
                                            {"MACHINE MARLIN\n", "LINK MACHINE\n"}};
    const char *const *l = lines[cell.kind == SIM_MACHINE_MARLIN];
    struct sim_reply r;
    int i, rc = 0, ok = 1;
    sim_cell_release(&cell);
    s->link.idle = cell_link_idle;
    cell_idle(100);
    for (i = 0; i < 2 && rc == 0; i++) {
        rc = sim_run_send(&s->link, l[i], strlen(l[i]), byte_us(),
                          sim_link_now_ms() + opt.timeout_ms);
        if (rc == SIM_LINK_REPLY) {
            rc = sim_link_await(&s->link, sim_link_now_ms() + opt.timeout_ms, &r, NULL, NULL);
        }
        ok = ok && rc == SIM_LINK_REPLY && !r.error;
        rc = rc == SIM_LINK_REPLY ? 0 : rc;
    }
    check(ok, cell.kind == SIM_MACHINE_MARLIN ? "cell: MACHINE MARLIN, LINK MACHINE accepted"
                                              : "cell: MACHINE GRBL, LINK MACHINE accepted",
          "");
    return ok ? 0 : -1;
}

/* --machine: "FORMAT FRAMES" lines of the job become "FORMAT GCODE" (FRAMES is a host-link
 * format; the cell runs every job as a program on its machine). */
static void cell_job(struct sim_job *j)
{
    size_t i;
    for (i = 0; i < j->n; i++) {
        if (kw_is(j->cmd[i].text, "FORMAT") && kw_is(arg1(j->cmd[i].text), "FRAMES")) {
            strcpy(j->cmd[i].text, "FORMAT GCODE"); /* shorter than the line it replaces */
            j->cmd[i].len = strlen(j->cmd[i].text);
        }
    }
}

/* The checks of one RUN on the cell: the machine accepted every line of it (no error, no
 * alarm, no unknown command, no RX overflow, no feed move without F, no ignored word) and
 * nothing of the program came up the host link. b: the verdict before the run. */
static void cell_run_checks(const struct sim_job_cmd *c, const struct sim_machine_verdict *b,
                            const struct sim_run_result *r)
{
    static char what[256];
    struct sim_machine_verdict v;
    sim_machine_verdict(cell.m, &v);
    snprintf(what, sizeof what,
             "line %d %s took the program: %lu lines, errors %lu, alarms %lu, unknown %lu, "
             "RX overflows %lu, G1 without F %lu, ignored words %lu",
             c->lineno, opt.machine, v.lines - b->lines, v.errors - b->errors, v.alarms - b->alarms,
             v.unknown - b->unknown, v.rx_overflows - b->rx_overflows,
             v.g1_without_feed - b->g1_without_feed, v.ignored_words - b->ignored_words);
    check(v.errors == b->errors && v.alarms == b->alarms && v.unknown == b->unknown &&
              v.rx_overflows == b->rx_overflows && v.g1_without_feed == b->g1_without_feed &&
              v.ignored_words == b->ignored_words && (r->error || v.lines > b->lines),
          what, v.first_problem);
    snprintf(what, sizeof what, "line %d nothing of the program on the host link", c->lineno);
    check(r->host_program == 0, what, r->why);
}

/* The verdict on the whole conversation with the cell's machine (summary rows, checks). */
static void cell_report(void)
{
    struct sim_machine_verdict v;
    sim_machine_verdict(cell.m, &v);
    printf("sim: cell machine %s: %lu lines, errors %lu, alarms %lu, unknown %lu, RX overflows "
           "%lu, resends %lu, safe Z %.4f; machine link in %llu B, out %llu B\n",
           opt.machine, v.lines, v.errors, v.alarms, v.unknown, v.rx_overflows, v.resends,
           v.safe_z, cell.bytes_in, cell.bytes_out);
    check(v.started_safe && v.units_mm && v.absolute,
          "cell: the program starts safe (G21 G90 before any motion, a rapid to the safe "
          "height first, no feed move above it)",
          v.first_problem);
    check(v.feed_before_safe == 0 && v.rapid_below_safe == 0 && v.feed_above_safe == 0,
          "cell: no feed move before the safe height, no rapid across below it", v.first_problem);
    check(v.ended_safe && v.program_end && v.spindle_off_at_end,
          "cell: the program ends safe (retract to the safe height, M5 if on, program end)",
          v.first_problem);
    check(v.feed_spindle_off == 0, "cell: no feed move with the spindle off (when it is used)",
          v.first_problem);
}

/* Create the pty, start the firmware and do the handshake (one check). */
static int fw_start(struct sim_session *s)
{
    struct sim_pty *pty = &s->pty;
    static char err[512], what[256];
    struct hs_result hs;
    uint64_t t0 = sim_link_now_us();
    int rc;
    if (sim_pty_open(pty, err, sizeof err) != 0) {
        fprintf(stderr, "host_sim: %s\n", err);
        return -2;
    }
    if (cell_on && cell_started && sim_cell_reopen(&cell, err, sizeof err) != 0) {
        fprintf(stderr, "host_sim: %s\n", err); /* a restart: a fresh pty, the same machine */
        return -2;
    }
    cell_started = 1;
    if (opt.target == SIM_QEMU) {
        s->cmd[8] = pty->path; /* -serial /dev/pts/N */
    }
    if (sim_pty_spawn(pty, s->cmd, opt.target != SIM_QEMU, err, sizeof err) != 0) {
        fprintf(stderr, "host_sim: %s%s\n", err,
                opt.target == SIM_QEMU && strstr(err, opt.qemu) != NULL
                    ? " (install qemu-system-arm: apt-get install qemu-system-arm)"
                    : "");
        sim_pty_hangup(pty);
        return -2;
    }
    sim_link_init(&s->link, pty, &sim_stop, s->log);
    rc = handshake(&s->link, opt.timeout_ms, &hs);
    snprintf(what, sizeof what, "handshake ($I x%u, %.2f ms)", hs.sends,
             (double)(sim_link_now_us() - t0) / 1000.0);
    check(hs.ok, what, hs.why);
    if (!hs.ok) {
        s->interrupted = rc == SIM_LINK_INTR;
        return -1;
    }
    printf("sim: firmware %s\n", hs.ver);
    if (hs.opt[0]) {
        print_limits(hs.opt);
    }
    sim_pty_release(pty); /* the firmware has the slave: a death now gives EIO */
    if (cell_on && cell_setup(s) != 0) {
        return -1;
    }
    return 0;
}

/* End the firmware after a hang-up (before a restart). */
static void fw_reap(struct sim_pty *pty)
{
    sim_pty_hangup(pty);
    if (opt.target == SIM_QEMU || !sim_pty_wait(pty, SIM_SHUTDOWN_MS)) {
        (void)sim_pty_stop(pty, SIM_KILL_GRACE_MS);
    }
}

static void run_opts(struct sim_run_opts *o, int first_stream)
{
    memset(o, 0, sizeof *o);
    o->frames = js.frames;
    o->checksum = js.checksum;
    o->cell = cell_on ? &cell : NULL;
    o->rxbuf = js.rxbuf;
    o->byte_us = opt.baud > 0.0 ? 1e7 / opt.baud : 0.0;
    o->fault = first_stream ? opt.fault : SIM_FAULT_NONE;
    o->fault_at = opt.fault_at;
    o->timeout_ms = opt.timeout_ms;
    o->raw = raw_file;
    o->progress = isatty(2);
}

static void run_account(const struct sim_run_result *r, double byte_us)
{
    rt.runs++;
    rt.points += r->got;
    rt.bytes_in += r->bytes_in;
    rt.bytes_out += r->bytes_out;
    rt.run_us += r->dur_us;
    rt.wire_us += (double)r->bytes_in * byte_us;
    rt.resends += r->resends;
    rt.naks += r->naks;
    rt.bad += r->bad_frames + r->bad_lines;
    rt.dups += r->dup_frames;
    rt.gaps += r->gap_frames;
}

static void run_row(int lineno, const char *cmd, const struct sim_run_result *r)
{
    double us = r->dur_us > 0.0 ? r->dur_us : 1.0;
    printf("  run   line %d \"%s\": %s%s, %lu points (k %lu..), %llu bytes in, %.1f B/point, "
           "%.0f points/s, %.1f ms (first byte after %.1f ms)",
           lineno, cmd, r->rc == SIM_LINK_REPLY ? (r->error ? "error" : "ok") : "no reply",
           r->hung ? " (hang-up injected)" : "", (unsigned long)r->got, (unsigned long)r->first,
           r->bytes_in, r->got ? (double)r->bytes_in / r->got : 0.0, r->got / (us / 1e6), us / 1000.0,
           r->first_byte_us / 1000.0);
    if (opt.baud > 0.0) {
        printf(", wire %.1f%% (%.1f%% from the first byte)", 100.0 * r->util,
               100.0 * r->util_stream);
    }
    if (r->resends || r->bad_lines) {
        printf(", resends %lu, bad lines %lu", r->resends, r->bad_lines);
    }
    if (r->naks || r->bad_frames || r->dup_frames || r->gap_frames) {
        printf(", NAKs %lu, bad frames %lu, dup %lu, gap %lu", r->naks, r->bad_frames,
               r->dup_frames, r->gap_frames);
    }
    if (!js.frames) {
        printf(", max RX %lu/%u", r->max_inbuf, js.rxbuf);
    }
    printf("\n");
}

/* Checks of one finished RUN/RESUME stream (r2: the resumed part, or NULL). */
static void run_checks(const struct sim_job_cmd *c, const struct sim_run_result *r,
                       const struct sim_run_result *r2, uint32_t start_k)
{
    static char what[256], detail[256];
    const struct sim_run_result *e = r2 != NULL ? r2 : r; /* the one that ended */
    int want_err = c->expect == SIM_JOB_EXPECT_ERROR;
    int pass;
    if (e->rc != SIM_LINK_REPLY) {
        snprintf(what, sizeof what, "line %d RUN reply", c->lineno);
        snprintf(detail, sizeof detail, "%s%s%s", sim_link_strerror(e->rc),
                 e->why[0] ? "; " : "", e->why);
        check(0, what, detail);
        return;
    }
    pass = want_err ? (e->error && e->code == c->code) : !e->error;
    char rep[24];
    if (e->error) {
        snprintf(rep, sizeof rep, "error:%d", e->code);
    } else {
        snprintf(rep, sizeof rep, "ok");
    }
    snprintf(what, sizeof what, "line %d RUN reply %s (want %s)", c->lineno, rep,
             want_err ? "error" : "ok");
    check(pass, what, e->why);
    if (e->error && !e->text_ok) {
        snprintf(what, sizeof what, "line %d: error:%d text does not match cp_status.def",
                 c->lineno, e->code);
        check(0, what, "");
    }
    if (!js.frames) {
        unsigned long ov = r->rx_overflow + (r2 ? r2->rx_overflow : 0);
        snprintf(what, sizeof what, "line %d character counting (max %lu of RXBUF %u)", c->lineno,
                 r2 && r2->max_inbuf > r->max_inbuf ? r2->max_inbuf : r->max_inbuf, js.rxbuf);
        if (js.acks && !cell_on) { /* the cell's machine counts its own RX overflows */
            check(ov == 0, what, r->rx_overflow ? r->why : r2 ? r2->why : "");
        }
        if (!js.checksum) {
            unsigned long bl = r->bad_lines + (r2 ? r2->bad_lines : 0);
            snprintf(what, sizeof what, "line %d every machine line parsed", c->lineno);
            snprintf(detail, sizeof detail, "%lu bad: %s", bl, r->why[0] ? r->why : r2 ? r2->why : "");
            check(bl == 0, what, detail);
        }
    } else {
        unsigned long oe = r->order_err + (r2 ? r2->order_err : 0);
        snprintf(what, sizeof what, "line %d frames in order", c->lineno);
        check(oe == 0, what, oe ? (r->order_err ? r->why : r2->why) : "");
    }
    if (!e->error && e->header) {
        uint32_t got = r->got + (r2 ? r2->got : 0);
        uint32_t want = e->points - start_k;
        snprintf(what, sizeof what, "line %d points intact: %lu of %lu (k %lu..%lu)%s", c->lineno,
                 (unsigned long)got, (unsigned long)want, (unsigned long)start_k,
                 (unsigned long)e->points - 1ul, r2 ? " across the resume" : "");
        pass = got == want && (!js.frames || e->end_points == e->got);
        snprintf(detail, sizeof detail, "END frame says %lu", e->end_points);
        check(pass, what, js.frames ? detail : "");
    }
    if (opt.min_util >= 0.0 && r2 == NULL && opt.fault == SIM_FAULT_NONE) {
        snprintf(what, sizeof what, "line %d wire utilization %.1f%% >= %.1f%% at %.0f baud",
                 c->lineno, 100.0 * r->util, opt.min_util, opt.baud);
        check(100.0 * r->util >= opt.min_util, what, "");
    }
}

/* ---- the command line ------------------------------------------------------------------ */

/* One option a with its value v. NULL, or the usage message. */
static const char *parse_value(struct sim_opts *o, const char *a, const char *v)
{
    char *e;
    if (strcmp(a, "--target") == 0) {
        o->target_name = v;
    } else if (strcmp(a, "--job") == 0) {
        o->job_path = v;
    } else if (strcmp(a, "--fw") == 0) {
        o->fw = v;
    } else if (strcmp(a, "--log") == 0) {
        o->log_path = v;
    } else if (strcmp(a, "--qemu") == 0) {
        o->qemu = v;
    } else if (strcmp(a, "--csv") == 0) {
        o->csv = v;
    } else if (strcmp(a, "--gcode") == 0) {
        o->gcode = v;
    } else if (strcmp(a, "--svg") == 0) {
        o->svg = v;
    } else if (strcmp(a, "--raw") == 0) {
        o->raw = v;
    } else if (strcmp(a, "--baud") == 0) {
        o->baud = strtod(v, &e);
        if (*e != '\0' || o->baud < 300.0 || o->baud > 1e8) {
            return "--baud must be 300..100000000";
        }
    } else if (strcmp(a, "--min-util") == 0) {
        o->min_util = strtod(v, &e);
        if (*e != '\0' || o->min_util < 0.0 || o->min_util > 100.0) {
            return "--min-util must be 0..100 (percent)";
        }
    } else if (strcmp(a, "--fault") == 0) {
        if (parse_fault(o, v) != 0) {
            return "--fault must be drop|flip|dup|hangup@N";
        }
    } else if (strcmp(a, "--machine-time") == 0) {
        o->machine_time = strtod(v, &e);
        if (*e != '\0' || o->machine_time < 0.0 || o->machine_time > 10.0) {
            return "--machine-time must be 0..10 (1: motion in real time)";
        }
    } else if (strcmp(a, "--machine") == 0) {
        if (strcmp(v, "grbl") != 0 && strcmp(v, "marlin") != 0) {
            return "--machine must be grbl or marlin";
        }
        o->machine = v;
    } else if (strcmp(a, "--timeout-ms") == 0) {
        unsigned long ms = strtoul(v, &e, 10);
        if (*e != '\0' || ms < 50 || ms > 600000) {
            return "--timeout-ms must be 50..600000";
        }
        o->timeout_ms = (unsigned)ms;
    } else {
        return "unknown option";
    }
    return NULL;
}

/* Fill o from the command line. NULL, or the usage message of the first error. */
static const char *sim_parse_args(int argc, char **argv, struct sim_opts *o)
{
    const char *msg;
    size_t i;
    memset(o, 0, sizeof *o);
    o->target = SIM_NATIVE;
    o->qemu = "qemu-system-arm";
    o->timeout_ms = 2000;
    o->fault = SIM_FAULT_NONE;
    o->min_util = -1.0;
    for (i = 1; i < (size_t)argc; i += 2) { /* every option but --resume takes one value */
        const char *a = argv[i];
        const char *v = i + 1 < (size_t)argc ? argv[i + 1] : NULL;
        if (strcmp(a, "--cmd") == 0) {
            if (v == NULL) {
                return "--cmd needs a program";
            }
            o->cmd = argv + i + 1;
            o->target = SIM_CMD;
            break;
        }
        if (strcmp(a, "--resume") == 0 || strcmp(a, "--advanced-ok") == 0 ||
            strcmp(a, "--homing") == 0) { /* the flags without a value */
            o->resume |= strcmp(a, "--resume") == 0;
            o->advanced_ok |= strcmp(a, "--advanced-ok") == 0;
            o->homing |= strcmp(a, "--homing") == 0;
            i--;
            continue;
        }
        if (v == NULL) {
            return "missing value after an option";
        }
        if ((msg = parse_value(o, a, v)) != NULL) {
            return msg;
        }
    }
    if (o->target != SIM_CMD) {
        if (o->target_name == NULL || strcmp(o->target_name, "native") == 0) {
            o->target = SIM_NATIVE;
        } else if (strcmp(o->target_name, "qemu") == 0) {
            o->target = SIM_QEMU;
        } else {
            return "--target must be native or qemu";
        }
    } else if (o->target_name != NULL && strcmp(o->target_name, "native") != 0) {
        return "--cmd runs the program like --target native";
    }
    if (o->job_path == NULL) {
        return "--job FILE is required";
    }
    if (o->min_util >= 0.0 && o->baud <= 0.0) {
        return "--min-util needs --baud";
    }
    if (o->fw == NULL) {
        o->fw = o->target == SIM_QEMU ? SIM_DEFAULT_QEMU_FW : SIM_DEFAULT_NATIVE;
    }
    return NULL;
}

/* ---- set-up ---------------------------------------------------------------------------- */

/* Load the job and open the outputs. 0; -1 if the job did not load (nothing to close);
 * -2 on any other set-up error (sim_setup_fail closes what is open). Reported on stderr. */
static int sim_setup(struct sim_session *s)
{
    static char err[512];
    if (sim_job_load(&s->job, opt.job_path, err, sizeof err) != 0) {
        fprintf(stderr, "host_sim: %s\n", err);
        return -1;
    }
    if (opt.target != SIM_CMD && access(opt.fw, R_OK) != 0) {
        fprintf(stderr, "host_sim: firmware %s: %s%s\n", opt.fw, strerror(errno),
                opt.target == SIM_QEMU ? " (build it with make m4f-fw)" : " (make fw-native)");
        return -2;
    }
    rtts = calloc(s->job.n + 1u, sizeof *rtts);
    if (rtts == NULL) {
        fprintf(stderr, "host_sim: out of memory\n");
        return -2;
    }
    if (opt.log_path != NULL) {
        s->log = fopen(opt.log_path, "w");
        if (s->log == NULL) {
            fprintf(stderr, "host_sim: %s: %s\n", opt.log_path, strerror(errno));
            return -2;
        }
        setvbuf(s->log, NULL, _IOLBF, 0);
    }
    if (opt.raw != NULL && (raw_file = fopen(opt.raw, "wb")) == NULL) {
        fprintf(stderr, "host_sim: %s: %s\n", opt.raw, strerror(errno));
        return -2;
    }
    if (opt.machine != NULL) {
        struct sim_machine_opts mo;
        memset(&mo, 0, sizeof mo);
        mo.kind = strcmp(opt.machine, "marlin") == 0 ? SIM_MACHINE_MARLIN : SIM_MACHINE_GRBL;
        mo.advanced_ok = opt.advanced_ok;
        mo.time_scale = opt.machine_time;
        mo.homing = opt.homing;
        if (sim_cell_open(&cell, &mo, err, sizeof err) != 0) {
            fprintf(stderr, "host_sim: %s\n", err);
            return -2;
        }
        cell_on = 1;
        cell_job(&s->job);
    }
    if (sim_out_open(opt.csv, opt.gcode, opt.svg) != 0) {
        return -2;
    }
    sim_check_init();
    return 0;
}

/* A set-up error: nothing was spawned, or the child is already gone. Exit status 2. */
static int sim_setup_fail(struct sim_session *s)
{
    if (s->log != NULL) {
        fclose(s->log);
    }
    if (raw_file != NULL) {
        fclose(raw_file);
    }
    (void)sim_out_close();
    sim_job_free(&s->job);
    free(rtts);
    checks.failed++;
    finish_line();
    return 2;
}

static void sim_signals(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = sim_on_signal;
    sigemptyset(&sa.sa_mask);
    (void)sigaction(SIGINT, &sa, NULL);
    (void)sigaction(SIGTERM, &sa, NULL);
    (void)sigaction(SIGHUP, &sa, NULL);
    sa.sa_handler = SIG_IGN;
    (void)sigaction(SIGPIPE, &sa, NULL);
}

/* The firmware's argv: QEMU's command line, the native firmware, or --cmd's. */
static void sim_command(struct sim_session *s)
{
    char **q = s->qargv;
    size_t k = 0;
    s->cmd = opt.cmd;
    if (opt.target == SIM_QEMU) {
        q[k++] = (char *)opt.qemu;
        q[k++] = "-M";
        q[k++] = "mps2-an386";
        q[k++] = "-display";
        q[k++] = "none";
        q[k++] = "-monitor";
        q[k++] = "none";
        q[k++] = "-serial";
        q[k++] = "/dev/null"; /* [8]: the pty path, set by fw_start */
        q[k++] = "-semihosting-config";
        q[k++] = "enable=on,target=native";
        q[k++] = "-icount";
        q[k++] = "shift=7";
        q[k++] = "-kernel";
        q[k++] = (char *)opt.fw;
        if (cell_on) { /* the second -serial is UART1: the machine link */
            q[k++] = "-serial";
            q[k++] = cell.pty.path;
        }
        q[k] = NULL;
        s->cmd = q;
    } else if (opt.target == SIM_NATIVE) {
        q[k++] = (char *)opt.fw;
        if (cell_on) {
            q[k++] = "--machine-tty";
            q[k++] = cell.pty.path;
        }
        q[k] = NULL;
        s->cmd = q;
    }
}

/* ---- the session ----------------------------------------------------------------------- */


/* After a hang-up in the first stream of job line i: a new firmware, the job's lines before
 * it again, then RESUME k with k = the first point not received intact. 1: resumed (r2
 * holds the resumed stream), 0: not resumed, -1: the session cannot go on. */
static int run_resume(struct sim_session *s, size_t i, const struct sim_run_result *r1,
                      uint32_t start_k, struct sim_run_result *r2)
{
    static char out[SIM_JOB_LINE_MAX + 2], what[256], esc[31];
    const struct sim_job_cmd *c = &s->job.cmd[i];
    struct sim_run_opts o;
    struct sim_reply r;
    size_t j;
    uint32_t k = r1->header ? r1->first + r1->got : start_k;
    char rs[40];
    int rc;
    printf("  resume: link hung up at byte %lu after %lu points; restarting the "
           "firmware, RESUME %lu\n",
           opt.fault_at, (unsigned long)r1->got, (unsigned long)k);
    fw_reap(&s->pty);
    rc = fw_start(s);
    if (rc == -2) {
        check(0, "restart after the hang-up", "");
        return -1;
    }
    for (j = 0; rc == 0 && j < i; j++) {
        const struct sim_job_cmd *cj = &s->job.cmd[j];
        if (kw_is(cj->text, "RUN") || kw_is(cj->text, "RESUME")) {
            continue;
        }
        memcpy(out, cj->text, cj->len);
        out[cj->len] = '\n';
        rc = sim_run_send(&s->link, out, cj->len + 1u, byte_us(),
                          sim_link_now_ms() + opt.timeout_ms);
        if (rc == SIM_LINK_REPLY) {
            rc = sim_link_await(&s->link, sim_link_now_ms() + opt.timeout_ms, &r, NULL, NULL);
        }
    }
    if (rc != 0) {
        check(0, "job sent again after the restart", sim_link_strerror(rc));
        s->interrupted = rc == SIM_LINK_INTR;
        return -1;
    }
    snprintf(rs, sizeof rs, "RESUME %lu\n", (unsigned long)k);
    rc = sim_run_send(&s->link, rs, strlen(rs), byte_us(), sim_link_now_ms() + opt.timeout_ms);
    if (rc != SIM_LINK_REPLY) {
        return 0;
    }
    run_opts(&o, 0);
    rc = sim_run_stream(&s->link, &o, r2);
    run_account(r2, byte_us());
    sim_link_escape(rs, strlen(rs) - 1u, esc, sizeof esc);
    run_row(c->lineno, esc, r2);
    rt.resumes++;
    snprintf(what, sizeof what, "line %d resumed at point %lu", c->lineno, (unsigned long)k);
    check(r2->header && r2->first == k, what, r2->header ? "header first differs" : "no header");
    return 1;
}

/* Job line i, a RUN or RESUME that was sent at t0 (us): its stream, a resume after a
 * hang-up (--resume), its checks. 0, or 1 when the session cannot go on. */
static int job_run(struct sim_session *s, size_t i, uint64_t t0, const char *esc)
{
    static struct sim_run_result r1, r2;
    static char what[256];
    const struct sim_job_cmd *c = &s->job.cmd[i];
    const struct sim_run_result *e;
    struct sim_run_opts o;
    int resumed = 0;
    uint32_t start_k =
        kw_is(c->text, "RESUME") ? (uint32_t)strtoul(arg1(c->text), NULL, 10) : 0u;
    struct sim_machine_verdict before;
    if (cell_on) {
        sim_machine_verdict(cell.m, &before);
    }
    run_opts(&o, 1);
    (void)sim_run_stream(&s->link, &o, &r1);
    run_account(&r1, byte_us());
    run_row(c->lineno, esc, &r1);
    if (r1.hung) {
        rt.hangups++;
    }
    if (r1.hung && opt.resume && !sim_stop) {
        resumed = run_resume(s, i, &r1, start_k, &r2);
        if (resumed < 0) {
            return 1;
        }
    }
    if (r1.hung && !resumed) {
        snprintf(what, sizeof what, "line %d RUN: link hung up at byte %lu", c->lineno,
                 opt.fault_at);
        check(0, what, opt.resume ? "resume failed" : "no --resume");
        return 1;
    }
    run_checks(c, &r1, resumed ? &r2 : NULL, start_k);
    if (cell_on) {
        cell_run_checks(c, &before, resumed ? &r2 : &r1);
    }
    e = resumed ? &r2 : &r1;
    if (e->rc != SIM_LINK_REPLY) {
        s->interrupted = e->rc == SIM_LINK_INTR;
        return 1;
    }
    stats.ok += !e->error;
    stats.error += e->error;
    rtts[stats.ok + stats.error - 1u] = (double)(sim_link_now_us() - t0) / 1000.0;
    return 0;
}

/* The table row and the checks of job line c, answered r after ms. */
static void reply_row(const struct sim_job_cmd *c, const struct sim_reply *r, double ms,
                      const char *esc)
{
    static char reply[64], expect[24], what[256];
    int pass = 1;
    rtts[stats.ok + stats.error] = ms;
    if (r->error) {
        stats.error++;
        snprintf(reply, sizeof reply, "error:%d", r->code);
    } else {
        stats.ok++;
        snprintf(reply, sizeof reply, "ok");
        job_state(c->text);
    }
    if (r->info) {
        size_t L = strlen(reply);
        snprintf(reply + L, sizeof reply - L, " +%u info", r->info);
    }
    stats.info += r->info;
    stats.unknown += r->unknown;
    stats.streamed += r->streamed;
    if (c->expect == SIM_JOB_EXPECT_OK) {
        snprintf(expect, sizeof expect, "ok");
        pass = !r->error;
    } else if (c->expect == SIM_JOB_EXPECT_ERROR) {
        snprintf(expect, sizeof expect, "error:%d", c->code);
        pass = r->error && r->code == c->code;
    } else {
        snprintf(expect, sizeof expect, "-");
    }
    printf("  %4d  %-30s %-26s %-10s %9.3f  %s\n", c->lineno, esc, reply, expect, ms,
           c->expect == SIM_JOB_EXPECT_NONE ? "-" : pass ? "pass" : "FAIL");
    if (c->expect != SIM_JOB_EXPECT_NONE && pass) {
        checks.passed++;
    } else if (c->expect != SIM_JOB_EXPECT_NONE) {
        checks.failed++;
    }
    if (r->unknown) {
        snprintf(what, sizeof what, "line %d: %u unknown reply line(s), first \"%s\"", c->lineno,
                 r->unknown, r->first_unknown);
        check(0, what, "");
    }
    if (r->error && !r->text_ok) {
        snprintf(what, sizeof what, "line %d: error:%d text does not match cp_status.def",
                 c->lineno, r->code);
        check(0, what, "");
    }
}

/* Job line i: sent, answered (or streamed), checked. 0, or 1 when the session cannot go on. */
static int job_command(struct sim_session *s, size_t i)
{
    static char out[SIM_JOB_LINE_MAX + 2], esc[31], detail[512], what[256];
    const struct sim_job_cmd *c = &s->job.cmd[i];
    struct sim_reply r;
    uint64_t t0;
    double ms;
    int rc, is_run = kw_is(c->text, "RUN") || kw_is(c->text, "RESUME");
    if (!is_run && !kw_is(c->text, "$I")) {
        (void)sim_check_job_line(c->text);
    }
    memcpy(out, c->text, c->len);
    out[c->len] = '\n';
    sim_link_escape(c->text, c->len, esc, sizeof esc);
    t0 = sim_link_now_us();
    rc = sim_run_send(&s->link, out, c->len + 1u, byte_us(), sim_link_now_ms() + opt.timeout_ms);
    if (rc == SIM_LINK_REPLY) {
        stats.sent++;
    }
    if (rc == SIM_LINK_REPLY && is_run) {
        return job_run(s, i, t0, esc);
    }
    if (rc == SIM_LINK_REPLY) {
        rc = sim_link_await(&s->link, sim_link_now_ms() + opt.timeout_ms, &r, NULL, NULL);
    }
    ms = (double)(sim_link_now_us() - t0) / 1000.0;
    if (rc != SIM_LINK_REPLY) {
        snprintf(detail, sizeof detail, "%s after %.1f ms", sim_link_strerror(rc), ms);
        snprintf(what, sizeof what, "line %d \"%s\"", c->lineno, esc);
        check(0, what, detail);
        s->interrupted = rc == SIM_LINK_INTR;
        return 1;
    }
    reply_row(c, &r, ms, esc);
    if (!r.error) {
        sim_out_job_line(c->text); /* TOL, STEPS, TOOL for the SVG's caption */
    }
    return 0;
}

/* The firmware, the handshake and the job. 0, or -2 on a set-up error (nothing spawned). */
static int sim_session(struct sim_session *s)
{
    size_t i;
    int rc;
    printf("sim: target %s, %s, job %s (%lu commands), timeout %u ms%s\n",
           opt.target == SIM_QEMU ? "qemu" : opt.target == SIM_NATIVE ? "native" : "cmd",
           opt.target == SIM_QEMU ? opt.fw : s->cmd[0], opt.job_path, (unsigned long)s->job.n,
           opt.timeout_ms, opt.baud > 0.0 ? ", paced" : "");
    if (opt.baud > 0.0) {
        printf("sim: UART pacing %.0f baud 8N1 (%.2f us/byte) both directions\n", opt.baud,
               1e7 / opt.baud);
    }
    /* 1. firmware and handshake */
    rc = fw_start(s);
    if (rc == -2) {
        return -2;
    }
    s->t_hs = sim_link_now_us();
    if (rc != 0) {
        return 0;
    }
    /* 2. the job */
    printf("  %4s  %-30s %-26s %-10s %9s  %s\n", "line", "command", "reply", "expect", "rtt ms",
           "check");
    for (i = 0; i < s->job.n; i++) {
        if (job_command(s, i) != 0) {
            break;
        }
    }
    return 0;
}

/* 3. shutdown: every path ends here, the child is always reaped */
static void sim_shutdown(struct sim_session *s)
{
    static char detail[512];
    char st[32];
    struct sim_pty *pty = &s->pty;
    if (s->interrupted || sim_stop) {
        (void)sim_pty_stop(pty, SIM_KILL_GRACE_MS);
        sim_pty_hangup(pty);
        check(0, "interrupted", "firmware stopped and reaped");
    } else if (opt.target == SIM_QEMU) {
        int alive = !sim_pty_exited(pty), how;
        how = sim_pty_stop(pty, SIM_KILL_GRACE_MS); /* QEMU never exits on a hang-up */
        sim_pty_hangup(pty);
        if (!alive) {
            snprintf(detail, sizeof detail, "QEMU exited during the session (%s)",
                     sim_pty_describe(pty->status, st, sizeof st));
        } else {
            snprintf(detail, sizeof detail, "QEMU needed SIGKILL");
        }
        check(alive && how == 1, "clean shutdown (QEMU alive, ends on SIGTERM)", detail);
    } else {
        int early = sim_pty_exited(pty), exited, how = 0;
        sim_pty_hangup(pty);
        exited = early || sim_pty_wait(pty, SIM_SHUTDOWN_MS);
        if (!exited) {
            how = sim_pty_stop(pty, SIM_KILL_GRACE_MS);
        }
        if (early) {
            snprintf(detail, sizeof detail, "firmware exited before the hang-up (%s)",
                     sim_pty_describe(pty->status, st, sizeof st));
        } else if (!exited) {
            snprintf(detail, sizeof detail, "no exit within %d ms of the hang-up; %s",
                     SIM_SHUTDOWN_MS, how == 2 ? "needed SIGKILL" : "ended by SIGTERM");
        } else {
            snprintf(detail, sizeof detail, "%s", sim_pty_describe(pty->status, st, sizeof st));
        }
        check(!early && exited && WIFEXITED(pty->status) && WEXITSTATUS(pty->status) == 0,
              "clean shutdown (exit 0 on hang-up)", detail);
    }
}

/* The totals over the RUN/RESUME streams (summary rows). */
static void report_runs(unsigned long written)
{
    printf("  %-18s %lu (%s%s), hang-ups %lu, resumes %lu\n", "runs", rt.runs,
           js.frames ? "FRAMES" : "GCODE", !js.frames && js.checksum ? "+CHECKSUM" : "",
           rt.hangups, rt.resumes);
    printf("  %-18s %lu\n", "points", rt.points);
    printf("  %-18s in %llu, out %llu\n", "run bytes", rt.bytes_in, rt.bytes_out);
    printf("  %-18s %.2f\n", "bytes/point", rt.points ? (double)rt.bytes_in / rt.points : 0.0);
    printf("  %-18s %.0f\n", "points/s", rt.run_us > 0.0 ? rt.points / (rt.run_us / 1e6) : 0.0);
    if (opt.baud > 0.0) {
        printf("  %-18s %.1f%% at %.0f baud\n", "wire utilization",
               rt.run_us > 0.0 ? 100.0 * rt.wire_us / rt.run_us : 0.0, opt.baud);
    } else {
        printf("  %-18s - (unpaced; use --baud N)\n", "wire utilization");
    }
    printf("  %-18s resends %lu, NAKs %lu, bad lines/frames %lu, dup frames %lu, "
           "gap frames %lu\n",
           "retransmits", rt.resends, rt.naks, rt.bad, rt.dups, rt.gaps);
    printf("  %-18s %.2f\n", "run ms", rt.run_us / 1000.0);
    if (opt.csv || opt.gcode || opt.svg) {
        printf("  %-18s %lu points%s%s%s%s%s%s\n", "written", written, opt.csv ? ", csv " : "",
               opt.csv ? opt.csv : "", opt.gcode ? ", gcode " : "", opt.gcode ? opt.gcode : "",
               opt.svg ? ", svg " : "", opt.svg ? opt.svg : "");
    }
}

/* 4. summary, then the judge's table */
static void sim_report(struct sim_session *s)
{
    unsigned long n = stats.ok + stats.error;
    double med = 0.0;
    unsigned long written = sim_out_close();
    if (n > 0) {
        qsort(rtts, n, sizeof *rtts, cmp_double);
        med = n % 2u ? rtts[n / 2u] : (rtts[n / 2u - 1u] + rtts[n / 2u]) / 2.0;
    }
    printf("sim: summary\n");
    printf("  %-18s %lu of %lu\n", "commands sent", stats.sent, (unsigned long)s->job.n);
    printf("  %-18s ok %lu, error %lu, info lines %lu, unknown %lu\n", "replies", stats.ok,
           stats.error, stats.info, stats.unknown);
    printf("  %-18s out %llu, in %llu\n", "bytes", s->link.bytes_out, s->link.bytes_in);
    if (n > 0) {
        printf("  %-18s min %.3f, median %.3f, max %.3f\n", "round trip ms", rtts[0], med,
               rtts[n - 1u]);
    }
    if (rt.runs > 0) {
        report_runs(written);
    }
    if (cell_on) {
        cell_report();
    }
    printf("  %-18s %.2f\n", "handshake ms", (double)(s->t_hs - s->t_start) / 1000.0);
    printf("  %-18s %.2f\n", "elapsed ms", (double)(sim_link_now_us() - s->t_start) / 1000.0);
    sim_check_report(stdout, &checks.passed, &checks.failed);
}

int main(int argc, char **argv)
{
    static struct sim_session s;
    const char *msg;
    int rc;
    setvbuf(stdout, NULL, _IOLBF, 0);
    if ((msg = sim_parse_args(argc, argv, &opt)) != NULL) {
        return usage(msg);
    }
    rc = sim_setup(&s);
    if (rc == -1) {
        checks.failed++;
        finish_line();
        return 2;
    }
    if (rc != 0) {
        return sim_setup_fail(&s);
    }
    sim_signals();
    s.t_start = sim_link_now_us();
    sim_command(&s);
    if (sim_session(&s) == -2) {
        return sim_setup_fail(&s);
    }
    sim_shutdown(&s);
    sim_report(&s);
    if (raw_file != NULL) {
        fclose(raw_file);
    }
    if (s.log != NULL) {
        fclose(s.log);
    }
    sim_job_free(&s.job);
    free(rtts);
    if (cell_on) {
        sim_cell_close(&cell);
    }
    finish_line();
    if (s.interrupted || sim_stop) {
        return 130;
    }
    return checks.failed == 0 ? 0 : 1;
}
