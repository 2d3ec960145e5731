/* fuzz_reply.c - libFuzzer target: whatever a machine sends back on the machine link,
 * per dialect (built once per dialect: -DFUZZ_DIALECT=grbl|marlin|generic|linuxcnc gives
 * fuzz_reply_<dialect>, mk/fuzz.mk).
 * SPDX-License-Identifier: MIT
 *
 * A two-link engine (two in-memory HALs) runs a small job with MACHINE <dialect> and LINK
 * MACHINE; the snapshot after RUN and the first program lines is the start of every input
 * (struct proto has no pointer into itself). The input is the machine's answer stream:
 * fed in pieces that end at '\n' (at most 48 bytes), with polls between. Then a good
 * machine answers "ok" to every line until the run ends. Byte 0 of the input picks the
 * snapshot: plain, or CHECKSUM ON (dialects that have checksums).
 * Invariants (abort() on violation):
 *   - the host link carries only "[MACHINE:<printable>]", "ok", or "error:<code> <text>"
 *     with a code of cp_status.def and its text, then " (machine <line>)" or nothing; one
 *     terminal reply for the run, and never a program line or the machine's own words
 *     bare (nothing of the machine's chatter is taken as a command or real-time byte);
 *   - the machine link carries only program lines the dialect takes: "G..."/"M..." (with
 *     checksums "N<n> <line>*<xor>", the XOR right), at most the dialect's LINE_MAX, and
 *     grbl's real-time '?' (the POLL byte) between lines; every G1 is the job's point
 *     (from an independent iterator) of its place in the program;
 *   - the run ends (terminal reply) within the drain budget, and the engine then answers
 *     "$I" with "[VER:" ... "ok".
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hal_mem.h"
#include "proto.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#ifndef FUZZ_DIALECT
#define FUZZ_DIALECT grbl
#endif
#define FUZZ_STR2(x) #x
#define FUZZ_STR(x) FUZZ_STR2(x)

#define FAIL(...)                                                                                 \
    do {                                                                                           \
        fprintf(stderr, "fuzz_reply_" FUZZ_STR(FUZZ_DIALECT) ": " __VA_ARGS__);                   \
        fputc('\n', stderr);                                                                       \
        abort();                                                                                   \
    } while (0)

#define PIECE_MAX 48u
#define DRAIN_POLLS 40000 /* polls for a good machine to finish the run (~20 lines) */
#define CHECK_POLLS 1000  /* polls for RUN's check of the job (a few slices) */

static const char *const job[] = {"CURVE ARC 0 0 3 0 90",  "RADIUS COS 5.5 10.5 2",
                                  "LINES 2 -25 10",        "STEPS 2",
                                  "FEED 600 150 300",      "SAFE 30",
                                  "SPINDLE 9000",          "LINK MACHINE",
                                  NULL};

static const char *const status_text[CP_ST_END_] = {
#define CP_STATUS(name, num, text, from) [num] = text,
#include "cp_status.def"
#undef CP_STATUS
};

static struct hal_mem hm, mm;
static struct hal_uart hu, mu;
static struct proto eng;
static struct {
    struct proto eng;
    uint32_t host_now;
    uint32_t g1_base;  /* G1 lines sent before the snapshot (checked in setup) */
    unsigned inflight; /* program lines in flight at the snapshot, answered by no one yet */
    int ok;
} snap[2];
static struct canal_path refit;
static unsigned dialect;
static size_t hscan, mscan; /* bytes of hm.out / mm.out already checked */
static int replies;         /* terminal replies on the host link since the snapshot */
static uint32_t g1_seen;    /* G1 lines since the snapshot (no checksums) */
static uint32_t g1_base;    /* point of the first G1 after the snapshot */

static void feed(struct hal_mem *m, const void *b, size_t n)
{
    if (m->in_pos == m->in_len) {
        m->in_pos = m->in_len = 0;
    }
    if (hal_mem_feed(m, b, n) != 0) {
        memmove(m->in, m->in + m->in_pos, m->in_len - m->in_pos);
        m->in_len -= m->in_pos;
        m->in_pos = 0;
        if (hal_mem_feed(m, b, n) != 0) {
            FAIL("input buffer full");
        }
    }
}

static int32_t q4(cp_real v)
{
    return (int32_t)cp_floor(v * CP_R(10000.0) + CP_R(0.5));
}

static long fixed4(const char *s)
{
    double v = strtod(s, NULL);
    return (long)(v * 10000.0 + (v < 0 ? -0.5 : 0.5));
}

/* A G1 line of the program: point k of the job. */
static void check_g1(const char *g, uint32_t k)
{
    struct raster_pt pt;
    const char *x = strstr(g, " X"), *y = strstr(g, " Y"), *z = strstr(g, " Z");
    if (x == NULL || y == NULL || z == NULL) {
        FAIL("malformed G1 \"%s\"", g);
    }
    if (canal_path_seek(&refit, k) != CP_OK || canal_path_next(&refit, &pt) != CP_OK) {
        FAIL("G1 for point %u beyond the job: \"%s\"", (unsigned)k, g);
    }
    if (fixed4(x + 2) != q4(pt.p.x) || fixed4(y + 2) != q4(pt.p.y) || fixed4(z + 2) != q4(pt.p.z)) {
        FAIL("wrong point %u: \"%s\" (want %.4f %.4f %.4f)", (unsigned)k, g, (double)pt.p.x,
             (double)pt.p.y, (double)pt.p.z);
    }
}

/* One line the firmware sent to the machine. */
static void machine_line(char *l, size_t n)
{
    const struct machine_dialect *d = machine_dialect(dialect);
    char *body = l;
    if (n > d->line_max) {
        FAIL("line of %u bytes > LINE_MAX %u: \"%s\"", (unsigned)n, (unsigned)d->line_max, l);
    }
    if (eng.job.checksum) {
        char *star = strrchr(l, '*'), *sp = strchr(l, ' ');
        unsigned cs = 0;
        const char *c;
        unsigned long num = strtoul(l + 1, NULL, 10);
        if (l[0] != 'N' || star == NULL || sp == NULL || sp > star) {
            FAIL("bad checksum line \"%s\"", l);
        }
        for (c = l; c < star; c++) {
            cs ^= (unsigned char)*c;
        }
        if (strtoul(star + 1, NULL, 10) != cs) {
            FAIL("bad checksum in \"%s\"", l);
        }
        *star = '\0';
        body = sp + 1;
        if (strncmp(body, "G1 ", 3) == 0) {
            if (num < eng.run.lead) {
                FAIL("G1 on line N%lu, before the program's lead (%u lines)", num,
                     (unsigned)eng.run.lead);
            }
            check_g1(body, (uint32_t)(num - eng.run.lead));
        }
    } else if (strncmp(body, "G1 ", 3) == 0) {
        check_g1(body, g1_base + g1_seen++);
    }
    if (body[0] != 'G' && body[0] != 'M') {
        FAIL("not a program line: \"%s\"", l);
    }
    if (strchr(body, '[') != NULL || strchr(body, '<') != NULL ||
        (!d->checksum && (strchr(l, '*') != NULL || strstr(l, "M110") != NULL))) {
        FAIL("a line the machine rejects: \"%s\"", l);
    }
}

/* One line the firmware sent to the host. */
static void host_line(const char *l, size_t n)
{
    if (strncmp(l, "[MACHINE:", 9) == 0 && l[n - 1] == ']') {
        return;
    }
    if (strncmp(l, "[RUN:", 5) == 0 || strncmp(l, "[VER:", 5) == 0 ||
        strncmp(l, "[OPT:", 5) == 0) {
        return;
    }
    if (strcmp(l, "ok") == 0) {
        replies++;
        return;
    }
    if (strncmp(l, "error:", 6) == 0) {
        char *end;
        long code = strtol(l + 6, &end, 10);
        size_t tl;
        if (code < 1 || code >= CP_ST_END_ || status_text[code] == NULL || *end != ' ') {
            FAIL("bad error line \"%s\"", l);
        }
        tl = strlen(status_text[code]);
        if (strncmp(end + 1, status_text[code], tl) != 0 ||
            (end[1 + tl] != '\0' && strncmp(end + 1 + tl, " (machine ", 10) != 0)) {
            FAIL("bad error text \"%s\"", l);
        }
        replies++;
        return;
    }
    FAIL("unexpected host line \"%s\"", l);
}

/* Check the new output of both links; with `answer`, answer each program line "ok". */
static void scan_out(int answer)
{
    char l[256];
    size_t k;
    for (k = hscan; k < hm.out_len; k++) {
        if (hm.out[k] == '\n') {
            size_t n = k - hscan < sizeof l - 1u ? k - hscan : sizeof l - 1u;
            memcpy(l, hm.out + hscan, n);
            l[n] = '\0';
            hscan = k + 1u;
            host_line(l, n);
        }
    }
    for (k = mscan; k < mm.out_len; k++) {
        if (mm.out[k] == '?' && k == mscan) { /* grbl's POLL byte, between lines */
            mscan = k + 1u;
            if (answer) {
                feed(&mm, "<Run|MPos:0.000,0.000,0.000|FS:600,0>\n", 39);
            }
            continue;
        }
        if (mm.out[k] == '\n') {
            size_t n = k - mscan < sizeof l - 1u ? k - mscan : sizeof l - 1u;
            memcpy(l, mm.out + mscan, n);
            l[n] = '\0';
            mscan = k + 1u;
            machine_line(l, n);
            if (answer && machine_dialect(dialect)->acks) {
                feed(&mm, "ok\n", 3);
            }
        }
    }
    if (hscan == hm.out_len) {
        hscan = hm.out_len = 0;
    }
    if (mscan == mm.out_len) {
        mscan = mm.out_len = 0;
    }
}

static void poll_n(int n, int answer)
{
    int i;
    for (i = 0; i < n; i++) {
        (void)proto_poll(&eng);
        scan_out(answer);
    }
}

static void command(const char *c)
{
    int before = replies;
    feed(&hm, c, strlen(c));
    feed(&hm, "\n", 1);
    poll_n(50, 1);
    if (replies != before + 1) {
        FAIL("no reply to \"%s\"", c);
    }
}

/* The snapshot: the job, then RUN and its first lines (answered by nobody yet). */
static void setup(int cs)
{
    struct proto_cfg cfg = {0};
    char mline[32];
    int i;
    hal_mem_init(&hm, &hu);
    hal_mem_init(&mm, &mu);
    hm.tick_ms = 1;
    cfg.uart = &hu;
    cfg.machine = &mu;
    if (proto_init(&eng, &cfg) != CP_OK) {
        FAIL("proto_init");
    }
    hscan = mscan = 0;
    replies = 0;
    for (i = 0; job[i] != NULL; i++) {
        command(job[i]);
    }
    snprintf(mline, sizeof mline, "MACHINE %s", FUZZ_STR(FUZZ_DIALECT));
    command(mline);
    dialect = eng.job.machine;
    if (cs) {
        command("CHECKSUM ON");
    }
    if (canal_path_init(&refit, &eng.job.canal, &eng.job.cfg) != CP_OK) {
        FAIL("reference iterator");
    }
    feed(&hm, "RUN\n", 4);
    g1_seen = g1_base = 0;
    poll_n(1, 0); /* RUN: its check begins (PROTO_CHECK, one slice per poll) */
    for (i = 0; i < CHECK_POLLS && eng.state == PROTO_CHECK; i++) {
        poll_n(1, 0);
    }
    poll_n(8, 0); /* the first program lines */
    if (eng.state == PROTO_IDLE || eng.state == PROTO_CHECK) {
        FAIL("RUN did not start");
    }
    snap[cs].g1_base = g1_seen; /* the G1 lines sent so far were checked; an input's count on */
    snap[cs].inflight = eng.out.gcode.ring_n;
    snap[cs].eng = eng;
    snap[cs].host_now = hm.now;
    snap[cs].ok = 1;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    int cs, polls;
    size_t i = size > 0u ? 1u : 0u;
    if (!snap[0].ok) {
        setup(0);
    }
    cs = size > 0u && (data[0] & 1u) && machine_dialect(dialect)->checksum;
    if (!snap[cs].ok) {
        setup(cs);
    }
    eng = snap[cs].eng; /* restore: the engine, the clock, empty links */
    hm.in_pos = hm.in_len = hm.out_len = 0;
    mm.in_pos = mm.in_len = mm.out_len = 0;
    hm.now = snap[cs].host_now;
    hscan = mscan = 0;
    replies = 0;
    g1_base = snap[cs].g1_base;
    g1_seen = 0;
    while (i < size) { /* the machine's answers, piece by piece */
        size_t n = 0;
        while (i + n < size && n < PIECE_MAX && data[i + n] != '\n') {
            n++;
        }
        if (i + n < size && n < PIECE_MAX) {
            n++; /* the '\n' */
        }
        feed(&mm, data + i, n);
        i += n;
        poll_n(4, 0);
    }
    feed(&mm, "\n", 1); /* the good machine: the input's last line ends, then the answers
                           * to the lines in flight at the snapshot, then one per line */
    for (polls = 0; polls < (int)snap[cs].inflight; polls++) {
        feed(&mm, "ok\n", 3);
    }
    for (polls = 0; polls < DRAIN_POLLS && eng.state != PROTO_IDLE; polls++) {
        poll_n(1, 1); /* then a good machine */
    }
    poll_n(4, 1); /* the terminal reply leaves the engine's tx */
    if (eng.state != PROTO_IDLE) {
        FAIL("the run did not end (next %u of %u)", (unsigned)eng.run.next, (unsigned)eng.run.end);
    }
    if (replies != 1) {
        FAIL("%d terminal replies for one run", replies);
    }
    feed(&hm, "$I\n", 3);
    poll_n(10, 1);
    if (replies != 2) {
        FAIL("no answer to $I after the run");
    }
    return 0;
}
