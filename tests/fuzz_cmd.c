/* fuzz_cmd.c - libFuzzer target: the command-line path, bytes -> proto over the
 * in-memory HAL, with a fresh engine per input.
 * SPDX-License-Identifier: MIT
 *
 * The input is what the host sends: job commands, RUN/RESUME, real-time bytes,
 * binary garbage. It is fed in pieces that end at '\n' (at most 96 bytes each),
 * and between pieces the engine is polled while a minimal machine answers:
 *   - every G-code stream line (G... or N...) gets "ok";
 *   - every frame of a FRAMES run is decoded and acknowledged (cumulative ACK).
 * Invariants (abort() on violation):
 *   - every text reply is "ok", "error:<code> <text>" with a code of
 *     cp_status.def and its exact text, an info line "[...]", a report "<...>",
 *     or a stream line;
 *   - every streamed point (G1 line or POINT frame) equals the point of an
 *     independent iterator over the same job, quantised the same way;
 *   - no hang: the engine consumes its input (no POLL_STALL polls without reading
 *     a byte while input is pending), and after the input a running job ends
 *     within DRAIN_BUDGET polls, or at once after an abort (0x18 / ABORT frame);
 *   - afterwards the engine answers "$I" with "[VER:" ... "ok".
 * Each run is bounded by a poll budget per input, so a huge job (1M points) is
 * aborted rather than streamed to the end.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "frame.h"
#include "hal_mem.h"
#include "proto.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define PIECE_MAX 96u
#define POLL_STALL 4000   /* polls without consuming pending input = hang */
#define FEED_BUDGET 20000 /* polls per piece (input is fed while the machine answers) */
#define DRAIN_BUDGET 6000 /* polls after the input before the run is aborted */
#define ABORT_BUDGET 2000 /* polls for an abort to end the run */

#define FAIL(...)                                  \
    do {                                           \
        fprintf(stderr, "fuzz_cmd: " __VA_ARGS__); \
        fprintf(stderr, "\n");                     \
        abort();                                   \
    } while (0)

/* The text of each code, from cp_status.def: the harness's own table (built as the
 * firmware's), so checking an error line does not run the
 * firmware's instrumented cp_status_text - 2 % of fuzz_cmd - and its table is
 * checked too. */
static const char *const status_text[CP_ST_END_] = {
#define CP_STATUS(name, code, text, from) [code] = text,
#include "cp_status.def"
#undef CP_STATUS
};

static struct hal_mem mem;
static struct hal_uart uart;
static struct proto eng;

/* machine / host side */
static size_t scan;            /* bytes of mem.out already looked at */
static char tline[200];        /* text line being assembled from the output */
static size_t tlen;
static int tline_bin;          /* the line held a non-printable byte (frame bytes) */
static struct frame_rx frx;    /* frames from the firmware */
static int saw_ver, saw_ok;    /* for the final $I check */
static uint8_t pending[512];   /* machine answers not yet queued (in[] full) */
static size_t npending;
static size_t in_base;         /* bytes of in[] dropped by in_reset (progress counter) */

/* independent iterator of the current run's job, whatever its SURFACE (path.h): a
 * job snapshot is the raster, the other models' geometry and the kind. The iterator
 * may keep pointers into the snapshot it was initialised on (the DRC and GSR paths
 * do), so that snapshot stays put while the iterator is in use. */
struct snap {
    struct raster_cfg cfg;
    union path_geom geom;
    uint8_t kind;
};
static struct path ref;
static struct snap snap_cfg;
/* Initialised reference iterators, kept across inputs (speed, docs/HARDENING.md):
 * path_init of a model job (the DRC solve above all) cost as much as the firmware's
 * own RUN - 12 % of fuzz_cmd - and libFuzzer's mutants mostly keep the job of their
 * parent. Each entry holds a job snapshot and the iterator exactly as path_init on
 * it left it (pointers into e->snap only, path.h); taking an entry copies that
 * iterator to `ref`, which is the state a new path_init on the same job reaches
 * (path_init depends on its arguments only, the firmware has no other state). Within
 * an input nothing changes: the iterator is still set up again, from the copy,
 * whenever the job differs from the current one. Least recently used entry goes. */
#define REF_CACHE 64u
static struct ref_entry {
    struct snap snap;
    struct path init;
    uint32_t hash;   /* of snap: a lookup compares whole snapshots only on a match */
    unsigned long used; /* 0: empty */
    int ok;          /* path_init returned CP_OK */
} ref_cache[REF_CACHE];
static struct ref_entry *ref_cur; /* entry `ref` was taken from; NULL at input start */
static unsigned long ref_clock;
/* The job before each of the last PRE_HIST polls: a header staged in the engine's TX
 * buffer may reach the HAL a poll or more after the poll that started (and ended) its
 * run, when later job lines have changed the job. The job changes on few polls, so
 * it is copied only then, as version pre_ver into pre_snap[pre_ver % PRE_HIST]; the
 * poll ring pre_hist holds version numbers, newest at pre_hist[(pre_n - 1) %
 * PRE_HIST]. A version at most one higher per poll: the versions of the last PRE_HIST
 * polls span at most PRE_HIST, so none of them is overwritten. (Copying the job
 * twice on every poll was ~7 % of fuzz_cmd, mostly in the sanitizer's memcpy.) */
#define PRE_HIST 8u
static struct snap pre_snap[PRE_HIST];
static unsigned pre_hist[PRE_HIST];
static unsigned pre_n, pre_ver;
#define PRE_CFG (&pre_snap[pre_ver % PRE_HIST]) /* the job before the current poll */
static int have_snap;
static int poll_active; /* the engine was running after the current poll */
static uint32_t gk;            /* next point index expected in a G-code run (no checksum) */
static uint32_t hfirst;         /* first point of the run whose header was seen last (checksum mode) */
static uint32_t lead_n;         /* checksum mode: N of the run's first G1 line (its lead lines
                                   before it; UINT32_MAX until seen) */
static uint8_t snap_checksum;

static void flush_pending(void);

static void send_bytes(const void *b, size_t n)
{
    if (npending + n > sizeof pending) {
        flush_pending();
    }
    if (npending + n > sizeof pending) {
        FAIL("host side cannot queue %u bytes: the firmware does not read", (unsigned)n);
    }
    memcpy(pending + npending, b, n);
    npending += n;
}

/* Drop the bytes of in[] the firmware has read (compaction). */
static void in_reset(void)
{
    if (mem.in_pos > 0) {
        memmove(mem.in, mem.in + mem.in_pos, mem.in_len - mem.in_pos);
        in_base += mem.in_pos;
        mem.in_len -= mem.in_pos;
        mem.in_pos = 0;
    }
}

/* Bytes the firmware has read so far (monotonic). */
static size_t in_read(void)
{
    return in_base + mem.in_pos;
}

static void flush_pending(void)
{
    if (npending == 0) {
        return;
    }
    in_reset();
    if (hal_mem_feed(&mem, pending, npending) == 0) {
        npending = 0;
    }
}

static int32_t q(cp_real v, cp_real scale)
{
    return (int32_t)cp_floor(v * scale + CP_R(0.5));
}

static int ref_point_at(uint32_t k, struct raster_pt *pt)
{
    if (ref_cur == NULL || !ref_cur->ok) {
        return 0;
    }
    if (path_pos(&ref) != k && path_seek(&ref, k) != CP_OK) {
        return 0;
    }
    return path_next(&ref, pt) == CP_OK;
}

/* The engine's job now, padding zeroed (snapshots are compared byte by byte). */
static void snap_of(struct snap *s)
{
    static struct job j; /* the job with its model's geometry filled as RUN fills it */
    memset(s, 0, sizeof *s);
    j = eng.job;
    job_geom_fill(&j);
    memcpy(&s->cfg, &j.cfg, sizeof s->cfg);
    memcpy(&s->geom, &j.geom, sizeof s->geom);
    s->kind = j.kind;
}

/* n bytes at a and b equal, 8 at a time. Not memcmp: it runs before every poll, the
 * sanitizer's interceptor is slow for this, and it hands every unequal pair to
 * libFuzzer as a comparison hint, while job snapshots are no input bytes. */
static int same_bytes(const void *a, const void *b, size_t n)
{
    const uint8_t *x = a, *y = b;
    uint64_t u, v;
    size_t i;
    for (i = 0; i + 8u <= n; i += 8u) {
        memcpy(&u, x + i, 8u);
        memcpy(&v, y + i, 8u);
        if (u != v) {
            return 0;
        }
    }
    for (; i < n; i++) {
        if (x[i] != y[i]) {
            return 0;
        }
    }
    return 1;
}

/* Snapshots a and b are equal (padding is zeroed by snap_of). */
static int snap_eq(const struct snap *a, const struct snap *b)
{
    return same_bytes(a, b, sizeof *a);
}

/* snap_of would give s now. */
static int job_is(const struct snap *s)
{
    static struct snap now;
    if (s->kind != eng.job.kind || !same_bytes(&s->cfg, &eng.job.cfg, sizeof s->cfg)) {
        return 0;
    }
    snap_of(&now); /* the geometry as RUN fills it (job_geom_fill) */
    return snap_eq(s, &now);
}

/* FNV-1a of a snapshot: the cache key. */
static uint32_t snap_hash(const struct snap *c)
{
    const uint8_t *b = (const uint8_t *)c;
    uint32_t h = 2166136261u; /* FNV-1a */
    size_t i;
    for (i = 0; i < sizeof *c; i++) {
        h = (h ^ b[i]) * 16777619u;
    }
    return h;
}

/* Point `ref` at job c (a fresh iterator at point 0) unless it is on c already. */
static int ref_try(const struct snap *c)
{
    struct ref_entry *e = NULL;
    uint32_t h;
    unsigned i;
    if (ref_cur != NULL && snap_eq(&ref_cur->snap, c)) {
        return ref_cur->ok;
    }
    h = snap_hash(c);
    for (i = 0; i < REF_CACHE; i++) {
        struct ref_entry *x = &ref_cache[i];
        if (x->used != 0 && x->hash == h && snap_eq(&x->snap, c)) {
            e = x;
            break;
        }
        if (e == NULL || x->used < e->used) {
            e = x; /* the least recently used so far, if c is not found */
        }
    }
    if (i == REF_CACHE) {
        e->snap = *c;
        e->hash = h;
        e->ok = path_init(&e->init, e->snap.kind, &e->snap.cfg, &e->snap.geom) == CP_OK;
    }
    e->used = ++ref_clock;
    ref = e->init;
    ref_cur = e;
    return e->ok;
}

/* A stream header (text "[RUN:points=count" or a BEGIN frame) arrived: point the
 * reference iterator at the run's job. While the run is active after the poll that
 * sent the header, the job is the engine's (job commands are refused while running).
 * A run can also start and end within one poll ("RUN\r\x18..." in one read: the
 * header, then error:20): then the job was the engine's job before or after that
 * poll (or at the last active poll, or before one of the last PRE_HIST polls: the
 * header may leave the TX buffer polls later, after later job lines were applied),
 * and the one whose iterator gives `count` points is taken. No point of such a run
 * can follow (at most one stream item per
 * poll, and the first is the preamble / BEGIN). */
static void ref_start(uint32_t count)
{
    struct snap now;
    if (poll_active) {
        if (!ref_try(&snap_cfg)) {
            FAIL("the firmware runs a job the iterator rejects");
        }
        return;
    }
    snap_of(&now);
    if ((have_snap && ref_try(&snap_cfg) && path_count(&ref) == count) ||
        (ref_try(PRE_CFG) && path_count(&ref) == count) ||
        (ref_try(&now) && path_count(&ref) == count)) {
        return;
    }
    {
        unsigned i;
        for (i = 1; i < PRE_HIST && i < pre_n; i++) {
            if (ref_try(&pre_snap[pre_hist[(pre_n - i) % PRE_HIST] % PRE_HIST]) &&
                path_count(&ref) == count) {
                return;
            }
        }
    }
    FAIL("stream header (%u points) of a run that ended in the poll that started it, for "
         "no job the iterator reproduces", (unsigned)count);
}

/* "X1.2345" style fixed-point field -> integer of 1e-4 units */
static long fixed4(const char *s, int *ok)
{
    long ip = 0, fp = 0;
    int neg = 0, nd = 0;
    if (*s == '-') {
        neg = 1;
        s++;
    }
    while (*s >= '0' && *s <= '9') {
        ip = ip * 10 + (*s++ - '0');
        nd++;
    }
    if (*s++ != '.' || nd == 0) {
        *ok = 0;
        return 0;
    }
    for (nd = 0; nd < 4; nd++) {
        if (*s < '0' || *s > '9') {
            *ok = 0;
            return 0;
        }
        fp = fp * 10 + (*s++ - '0');
    }
    return neg ? -(ip * 10000 + fp) : ip * 10000 + fp;
}

static void check_g1(const char *g, uint32_t k)
{
    struct raster_pt pt;
    const char *x = strstr(g, " X"), *y = strstr(g, " Y"), *z = strstr(g, " Z");
    int ok = 1;
    long vx, vy, vz;
    if (x == NULL || y == NULL || z == NULL) {
        FAIL("malformed G1 line \"%s\"", g);
    }
    vx = fixed4(x + 2, &ok);
    vy = fixed4(y + 2, &ok);
    vz = fixed4(z + 2, &ok);
    if (!ok) {
        FAIL("malformed number in \"%s\"", g);
    }
    if (!ref_point_at(k, &pt)) {
        FAIL("G1 line for point %u, beyond the job", (unsigned)k);
    }
    if (vx != q(pt.p.x, CP_R(10000.0)) || vy != q(pt.p.y, CP_R(10000.0)) ||
        vz != q(pt.p.z, CP_R(10000.0))) {
        FAIL("wrong point %u: \"%s\"", (unsigned)k, g);
    }
}

static void text_line(char *l)
{
    if (strcmp(l, "ok") == 0) {
        saw_ok = 1;
        return;
    }
    if (strncmp(l, "error:", 6) == 0) {
        char *end;
        long code = strtol(l + 6, &end, 10);
        size_t tl = code >= 1 && code < CP_ST_END_ ? strlen(status_text[code]) : 0u;
        /* the text, alone or followed by the cause " (...)" (PROTOCOL.md "Lines") */
        if (end == l + 6 || code < 1 || code >= CP_ST_END_ || *end != ' ' ||
            strncmp(end + 1, status_text[code], tl) != 0 ||
            (end[1 + tl] != '\0' &&
             (strncmp(end + 1 + tl, " (", 2) != 0 || l[strlen(l) - 1] != ')'))) {
            FAIL("bad error line \"%s\"", l);
        }
        saw_ok = 1;
        return;
    }
    if (l[0] == '[') {
        if (strncmp(l, "[VER:", 5) == 0) {
            saw_ver = 1;
        }
        if (strncmp(l, "[RUN:points=", 12) == 0) {
            const char *f = strstr(l, ",first=");
            ref_start((uint32_t)strtoul(l + 12, NULL, 10));
            if (f == NULL) {
                FAIL("bad run header \"%s\"", l);
            }
            gk = (uint32_t)strtoul(f + 7, NULL, 10);
            lead_n = UINT32_MAX;
            hfirst = gk; /* lines until the next header belong to this run, even when
                          * they arrive after the host has already sent a new RESUME */
            if (strtoul(l + 12, NULL, 10) != path_count(&ref)) {
                FAIL("run header count differs: \"%s\"", l);
            }
        }
        return;
    }
    if (l[0] == '<' && l[strlen(l) - 1] == '>') {
        return;
    }
    if (l[0] == 'N') { /* checksum mode: N<n> <line>*<cs> */
        unsigned cs = 0;
        char *star = strrchr(l, '*'), *sp = strchr(l, ' ');
        const char *c;
        unsigned long n = strtoul(l + 1, NULL, 10);
        if (star == NULL || sp == NULL || sp > star) {
            FAIL("bad checksum line \"%s\"", l);
        }
        for (c = l; c < star; c++) {
            cs ^= (unsigned char)*c;
        }
        if (strtoul(star + 1, NULL, 10) != cs) {
            FAIL("bad checksum in \"%s\"", l);
        }
        *star = '\0';
        if (strncmp(sp + 1, "G1 ", 3) == 0) {
            /* lines are sent in order and a Resend rewinds to lines sent: the first G1
             * line after the header is the first point's, numbered after the lead */
            if (lead_n == UINT32_MAX) {
                lead_n = (uint32_t)n;
            }
            if (n < lead_n || n < 3u) {
                FAIL("point on line N%lu", n);
            }
            check_g1(sp + 1, hfirst + (uint32_t)(n - lead_n));
        } else if (strchr("GM", sp[1]) == NULL || sp[1] == '\0') {
            FAIL("unexpected program line \"%s\"", sp + 1);
        }
        send_bytes("ok\n", 3);
        return;
    }
    if ((l[0] == 'G' && strncmp(l, "G1 ", 3) != 0) || l[0] == 'M') {
        send_bytes("ok\n", 3); /* the program around the points */
        return;
    }
    if (strncmp(l, "G1 X", 4) == 0) {
        check_g1(l, gk++);
        send_bytes("ok\n", 3);
        return;
    }
    FAIL("unexpected output line \"%s\"", l);
}

static void frame_in(const uint8_t *f)
{
    uint8_t ack[8];
    int n;
    if (f[2] == FRAME_BEGIN) {
        ref_start(frame_get_u32(f + 3));
        if (f[0] != 16u + FRAME_OVERHEAD || frame_get_u32(f + 3) != path_count(&ref)) {
            FAIL("bad BEGIN frame");
        }
    } else if (f[2] == FRAME_POINT) {
        struct raster_pt pt;
        uint32_t k = frame_get_u32(f + 3);
        if (f[0] != FRAME_POINT_LEN || !ref_point_at(k, &pt)) {
            FAIL("bad POINT frame (k %u)", (unsigned)k);
        }
        if ((int32_t)frame_get_u32(f + 7) != q(pt.p.x, CP_R(10000.0)) ||
            (int32_t)frame_get_u32(f + 11) != q(pt.p.y, CP_R(10000.0)) ||
            (int32_t)frame_get_u32(f + 15) != q(pt.p.z, CP_R(10000.0)) ||
            (int16_t)frame_get_u16(f + 25) != pt.line || frame_get_u16(f + 27) != pt.index) {
            FAIL("wrong point in frame k %u", (unsigned)k);
        }
    } else if (f[2] == FRAME_END) {
        if (f[0] != 5u + FRAME_OVERHEAD || f[3] >= CP_ST_END_) {
            FAIL("bad END frame");
        }
    } else {
        FAIL("unknown frame type 0x%02x from the firmware", f[2]);
    }
    n = frame_encode((uint8_t)(f[1] + 1u), FRAME_ACK, NULL, 0, ack, sizeof ack);
    send_bytes(ack, (size_t)n);
}

/* Look at everything the firmware sent since the last call. Text and frames share
 * the line: a '\n' ends a text line only when the frame decoder is not inside a
 * frame (or the line is a "<...>" report, whose '<' = 60 looks like a frame length);
 * after a text line the decoder is reset, since the firmware never puts text
 * inside a frame and sends no sync byte before its first frame. */
static void observe(void)
{
    while (scan < mem.out_len) {
        uint8_t c = mem.out[scan++];
        if (c == '\n') {
            int report = tlen > 1 && tline[0] == '<' && tline[tlen - 1] == '>' &&
                         (strncmp(tline, "<Idle", 5) == 0 || strncmp(tline, "<Run", 4) == 0 ||
                          strncmp(tline, "<Hold", 5) == 0);
            if (frx.len == 0u || frx.len == 0xFFu || report) {
                if (tline_bin || tlen >= sizeof tline - 1) {
                    FAIL("binary or over-long text line");
                }
                tline[tlen] = '\0';
                text_line(tline);
                frame_rx_init(&frx);
                tlen = 0;
                tline_bin = 0;
                continue;
            }
        }
        if (frame_rx_feed(&frx, c)) {
            frame_in(frx.buf);
            tlen = 0; /* a frame is not text */
            tline_bin = 0;
            continue;
        }
        if (c == '\n') {
            tlen = 0; /* a '\n' inside a frame: not text */
            tline_bin = 0;
        } else if (tlen < sizeof tline - 1) {
            tline[tlen++] = (char)c;
            if (c < 0x20 || c > 0x7E) {
                tline_bin = 1;
            }
        } else {
            tline_bin = 1;
        }
    }
    if (scan == mem.out_len) {
        scan = 0;
        mem.out_len = 0;
    }
}

static int trace = -1; /* FUZZ_TRACE=1 in the environment: dump the traffic to stderr */

static void trace_bytes(const char *dir, const uint8_t *b, size_t n)
{
    size_t i;
    if (n == 0) {
        return;
    }
    fprintf(stderr, "%s ", dir);
    for (i = 0; i < n; i++) {
        if (b[i] >= 0x20 && b[i] < 0x7F && b[i] != '\\') {
            fputc(b[i], stderr);
        } else {
            fprintf(stderr, "\\x%02x", b[i]);
        }
    }
    fputc('\n', stderr);
}

static int poll_once(void)
{
    size_t in0 = in_read(), out0 = mem.out_len;
    int r;
    if (pre_n == 0 || !job_is(PRE_CFG)) {
        pre_ver++;
        snap_of(PRE_CFG);
    }
    pre_hist[pre_n % PRE_HIST] = pre_ver;
    pre_n++;
    r = proto_poll(&eng);
    if (trace < 0) {
        trace = getenv("FUZZ_TRACE") != NULL;
    }
    if (trace) {
        trace_bytes("fw<", mem.in + mem.in_pos - (in_read() - in0), in_read() - in0);
        trace_bytes("fw>", mem.out + out0, mem.out_len - out0);
    }
    if (r < 0) {
        FAIL("proto_poll = %d", r);
    }
    poll_active = eng.state != PROTO_IDLE;
    if (poll_active) {
        if (!have_snap || !job_is(&snap_cfg)) {
            snap_of(&snap_cfg);
        }
        snap_checksum = eng.job.checksum;
        have_snap = 1;
    }
    observe();
    flush_pending();
    return r;
}

/* Feed one piece of host input and poll until it is consumed. */
static void feed_piece(const uint8_t *b, size_t n)
{
    int polls = 0, stall = 0;
    size_t last;
    in_reset();
    while (hal_mem_feed(&mem, b, n) != 0) {
        poll_once();
        in_reset();
        if (++polls > FEED_BUDGET) {
            FAIL("input buffer never drains");
        }
    }
    last = in_read();
    while (mem.in_pos < mem.in_len && polls < FEED_BUDGET) {
        poll_once();
        polls++;
        if (in_read() == last) {
            if (++stall > POLL_STALL) {
                FAIL("hang: %d polls without reading input (state %d, in %u/%u, rx %u/%u, "
                     "tx %u/%u, pend %u, ring %u, inflight %u, line_len %u)",
                     stall, eng.state, (unsigned)mem.in_pos, (unsigned)mem.in_len, eng.rx_pos,
                     eng.rx_len, eng.tx_pos, eng.tx_len, eng.out.gcode.pend_len,
                     eng.out.gcode.ring_n, eng.out.gcode.inflight, eng.line_len);
            }
        } else {
            stall = 0;
            last = in_read();
        }
    }
    /* let the stream run a little with the machine answering. An idle engine (no
     * run, nothing to read, nothing queued, and proto_poll reports that nothing
     * moved) does nothing on further polls - proto.h: the caller may sleep until
     * the next byte - so the remaining polls are skipped. */
    for (polls = 0; polls < 64; polls++) {
        if (poll_once() == 0 && eng.state == PROTO_IDLE && mem.in_pos == mem.in_len &&
            npending == 0) {
            break;
        }
    }
}

static void wait_idle(int budget, const char *what)
{
    int i;
    for (i = 0; i < budget && (eng.state != PROTO_IDLE || mem.in_pos < mem.in_len); i++) {
        poll_once();
    }
    if (eng.state != PROTO_IDLE) {
        FAIL("hang: run still active %d polls after %s", budget, what);
    }
}

/* After the input: let a running job go on with the machine answering, abort it
 * after the budget, and require the abort to end it. */
static void drain_run(void)
{
    int i;
    for (i = 0; i < POLL_STALL && (mem.in_pos < mem.in_len || npending > 0); i++) {
        poll_once(); /* first the bytes still queued (they may start a run) */
    }
    for (i = 0; i < DRAIN_BUDGET && eng.state != PROTO_IDLE; i++) {
        poll_once();
    }
    if (eng.state != PROTO_IDLE) {
        if (eng.fmt == JOB_FRAMES) {
            uint8_t f[8];
            uint8_t sync[FRAME_MAX];
            int n = frame_encode(0, FRAME_ABORT, NULL, 0, f, sizeof f);
            memset(sync, FRAME_SYNC, sizeof sync);
            send_bytes(sync, sizeof sync);
            send_bytes(f, (size_t)n);
        } else {
            send_bytes("\x18", 1);
        }
        flush_pending();
        wait_idle(ABORT_BUDGET, "an abort");
    }
    for (i = 0; i < 64 && mem.in_pos < mem.in_len; i++) {
        poll_once();
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    size_t a = 0;
    int i;
    struct proto_cfg cfg = {0};
    hal_mem_init(&mem, &uart);
    mem.tick_ms = 1;
    cfg.uart = &uart;
    if (proto_init(&eng, &cfg) != CP_OK) {
        FAIL("proto_init");
    }
    scan = tlen = npending = in_base = 0;
    tline_bin = 0;
    frame_rx_init(&frx);
    ref_cur = NULL;
    have_snap = poll_active = 0;
    pre_n = 0;
    gk = 0;
    hfirst = 0;
    lead_n = UINT32_MAX;
    while (a < size) {
        size_t b = a;
        while (b < size && b - a < PIECE_MAX && data[b] != '\n') {
            b++;
        }
        if (b < size && data[b] == '\n') {
            b++;
        }
        feed_piece(data + a, b - a);
        a = b;
    }
    /* a partial last line is ended first: it may itself be RUN */
    send_bytes("\n", 1);
    flush_pending();
    drain_run();
    /* the engine still answers */
    saw_ver = saw_ok = 0;
    send_bytes("$I\n", 3);
    flush_pending();
    for (i = 0; i < 2000 && !(saw_ver && saw_ok && mem.in_pos == mem.in_len); i++) {
        poll_once();
    }
    if (!saw_ver || !saw_ok) {
        FAIL("no answer to $I after the input (state %d, in %u/%u, pending %u, line_len %u, "
             "flags %u)", eng.state, (unsigned)mem.in_pos, (unsigned)mem.in_len,
             (unsigned)npending, eng.line_len, eng.line_flags);
    }
    return 0;
}
