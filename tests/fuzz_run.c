/* fuzz_run.c - libFuzzer target: the whole receive path during a FRAMES run.
 * SPDX-License-Identifier: MIT
 *
 * A fresh engine per input loads one of a few small jobs (byte 0), FORMAT FRAMES,
 * and RUN (or RESUME k, byte 1). The rest of the input is a program for the host
 * side while the firmware streams; each op is one byte (+ arguments):
 *   0 raw bytes (len, bytes...)         4 HOLD / GO / ABORT / STATUS / unknown type
 *   1 ACK the newest frame received     5 poll n times without answering
 *   2 NAK seq                           6 set the clock tick (0..63 ms per now_ms)
 *   3 ACK seq (any)                     7 a valid ACK/NAK with one bit flipped
 * Between ops the engine is polled 4 times. Every frame the firmware sends is
 * decoded and checked: CRC (by the decoder), seq = low 8 bits of its index in the
 * run, BEGIN fields, every POINT equal to an independent iterator of the same job
 * at k (position, normal, line, index), END status a code of cp_status.def.
 * After the program a well-behaved host (64 sync bytes, GO, then an ACK per frame,
 * clock 1 ms) must bring the run to its end - the text "ok" or "error:<code> ..."
 * - within a poll budget, else the harness abort()s (hang). Then "$I" must be answered.
 *
 * Speed (docs/HARDENING.md): the job set-up is done once per job, on the first
 * input that uses it: a fresh engine gets the job lines and FORMAT FRAMES (each
 * must be answered "ok"), and the engine and the loopback HAL are saved. Every
 * input starts from a byte copy of that state, which is exactly the state a fresh
 * set-up reaches (the firmware has no state outside struct proto and the HAL).
 * The expected POINT fields of every k are computed once per job by an
 * independent iterator (canal_path_init on the job's cfg, then canal_path_next from 0
 * to the end: no seek), and each POINT frame is compared with that table. This is
 * the same comparison as before, field by field, without recomputing the job on
 * every input. Likewise the RUN / RESUME k line and the 4 polls after it run once
 * per job and k, their frames checked then; later inputs with that job and k start
 * from a byte copy of the engine, the HAL and the receive state at that point.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "frame.h"
#include "hal_mem.h"
#include "proto.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define FAIL(...)                                  \
    do {                                           \
        fprintf(stderr, "fuzz_run: " __VA_ARGS__); \
        fprintf(stderr, "\n");                     \
        abort();                                   \
    } while (0)

/* The text of each code, from cp_status.def: the harness's own table (the firmware
 * packs the texts into one string), so checking an error line does not run the
 * firmware's instrumented cp_status_text (as in fuzz_cmd), and its table is checked
 * too. */
static const char *const status_text[CP_ST_END_] = {
#define CP_STATUS(name, code, text, from) [code] = text,
#include "cp_status.def"
#undef CP_STATUS
};

static const char *const jobs[][6] = {
    {"CURVE ARC 0 0 3 0 360", "RADIUS COS 5.5 10.5 2", "LINES 3 -25 10", "STEPS 20", NULL, NULL},
    {"CURVE LINE 0 0 40 10", "RADIUS CUBIC 2 6 1 3", "CIRCLES 3 -40 40", "STEPS 12", NULL, NULL},
    {"CURVE ELLIPSE 1 -2 20 12 20 140", "RADIUS COS 1.5 6 3", "CIRCLES 4 -20 30 PATCH",
     "STEPS 8", "TOOL BALL 0.5 CENTRE", NULL},
    {"CURVE BEZIER 0 0 10 15 20 -15 30 0", "RADIUS CUBIC 3 5 2 4", "LINES 2 -20 20", "TOL 50",
     "TOOL BALL 1", NULL},
};
#define NJOBS (sizeof jobs / sizeof jobs[0])

static struct hal_mem mem;
static struct hal_uart uart;
static struct proto eng;
static struct frame_rx frx;
static size_t scan;
static char text[128];
static size_t tlen;
static int in_frames;     /* the run's frames are still coming (text comes after END/error) */
static int begun;         /* the run's first frame (BEGIN) came: before it, RUN's check
                             answers in text ('?': <Check|..>, Ctrl-X: error:20), and a
                             text byte may look like a frame's length ('<' = 60) */
static int finished;      /* the closing text line arrived */
static int saw_ver;       /* the $I answer's "[VER:" line arrived (finished is reset there) */
static int last_seq = -1; /* seq of the newest frame received */
static int good_host;     /* ack every frame */
static uint32_t first, npts;

/* per job, built on first use: the engine after the set-up and the expected points */
struct expect {
    int32_t x, y, z;
    int16_t nx, ny, nz, line;
    uint16_t index;
};
#define EXPECT_MAX 4096u
static struct {
    int ready;
    struct proto eng;
    struct hal_mem mem;
    struct canal_path ref; /* initialised, never advanced: BEGIN fields */
    uint32_t count;
    struct expect *pts;
} snap[NJOBS];
static const struct canal_path *ref; /* snap[j].ref of the current input */
static const struct expect *exp_pts;
/* per job and first point k (RUN: 0, RESUME k: 1..127), built on first use: the
 * engine and the harness's receive state after the RUN / RESUME line and its first 4
 * polls (the firmware's run start: canal_path_init, the BEGIN frame and the first
 * points, each checked then). The run start was ~15 % of every input and is the same
 * for every input with that job and k: the firmware is deterministic and has no
 * state outside struct proto and the HAL. */
#define FIRST_MAX 128u
static struct start {
    struct proto eng;
    struct hal_mem mem;
    struct frame_rx frx;
    char text[sizeof text];
    size_t tlen;
    int in_frames, begun, finished, last_seq;
} *starts[NJOBS][FIRST_MAX];

static void host_bytes(const void *b, size_t n)
{
    if (mem.in_pos == mem.in_len) {
        mem.in_pos = mem.in_len = 0;
    }
    if (hal_mem_feed(&mem, b, n) != 0) {
        /* the firmware reads everything eventually: make room by compaction */
        memmove(mem.in, mem.in + mem.in_pos, mem.in_len - mem.in_pos);
        mem.in_len -= mem.in_pos;
        mem.in_pos = 0;
        (void)hal_mem_feed(&mem, b, n);
    }
}

static void host_frame(uint8_t seq, uint8_t type)
{
    uint8_t f[8];
    int n = frame_encode(seq, type, NULL, 0, f, sizeof f);
    host_bytes(f, (size_t)n);
}

static int32_t q(cp_real v, cp_real scale)
{
    return (int32_t)cp_floor(v * scale + CP_R(0.5));
}

static void text_line(void)
{
    text[tlen] = '\0';
    if (strcmp(text, "ok") == 0) {
        finished = 1;
    } else if (strncmp(text, "error:", 6) == 0) {
        char *end;
        long code = strtol(text + 6, &end, 10);
        if (end == text + 6 || code < 1 || code >= CP_ST_END_ || *end != ' ' ||
            strcmp(end + 1, status_text[code]) != 0) {
            FAIL("bad error line \"%s\"", text);
        }
        finished = 1;
    } else if (in_frames && !begun && text[0] == '<' && text[tlen - 1] == '>') {
        /* '?' during RUN's check: its report; the frames still follow */
    } else if (!in_frames && (text[0] == '[' || (text[0] == '<' && text[tlen - 1] == '>'))) {
        /* $I answer, or a status report ('?' in the bytes after the run ended) */
        if (strncmp(text, "[VER:", 5) == 0) {
            saw_ver = 1;
            finished = 0; /* the "ok" of the $I answer must follow */
        }
    } else {
        FAIL("unexpected text \"%s\"", text);
    }
    tlen = 0;
}

static void frame_in(const uint8_t *f)
{
    uint32_t idx;
    if (!in_frames) {
        FAIL("frame after the run ended");
    }
    switch (f[2]) {
    case FRAME_BEGIN:
        if (f[1] != 0u || f[0] != 22u || frame_get_u32(f + 3) != canal_path_count(ref) ||
            frame_get_u32(f + 7) != first || frame_get_u16(f + 11) != ref->head.n ||
            frame_get_u16(f + 13) != ref->head.steps || frame_get_u16(f + 15) != ref->head.link ||
            f[17] != ref->head.mode || f[18] != 0u) { /* the canal reports no overlap */
            FAIL("bad BEGIN frame");
        }
        break;
    case FRAME_POINT: {
        const struct expect *e;
        uint32_t k = frame_get_u32(f + 3);
        if (f[0] != FRAME_POINT_LEN || k < first || k >= first + npts) {
            FAIL("POINT frame k %u outside [%u, %u)", (unsigned)k, (unsigned)first,
                 (unsigned)(first + npts));
        }
        idx = k - first + 1u;
        if (f[1] != (uint8_t)idx) {
            FAIL("POINT k %u with seq %u", (unsigned)k, f[1]);
        }
        e = &exp_pts[k];
        if ((int32_t)frame_get_u32(f + 7) != e->x || (int32_t)frame_get_u32(f + 11) != e->y ||
            (int32_t)frame_get_u32(f + 15) != e->z || (int16_t)frame_get_u16(f + 19) != e->nx ||
            (int16_t)frame_get_u16(f + 21) != e->ny || (int16_t)frame_get_u16(f + 23) != e->nz ||
            (int16_t)frame_get_u16(f + 25) != e->line || frame_get_u16(f + 27) != e->index) {
            FAIL("wrong POINT frame k %u", (unsigned)k);
        }
        break;
    }
    case FRAME_END:
        /* Known firmware issue (docs/HARDENING.md, finding F2): an error END sent after
         * the complete END frame was already sent reports points = npts + 1 (it counts
         * the END frame). Tolerated unless built with -DFUZZ_STRICT. */
#ifdef FUZZ_STRICT
        if (f[0] != 11u || f[3] >= CP_ST_END_ || frame_get_u32(f + 4) > npts) {
#else
        if (f[0] != 11u || f[3] >= CP_ST_END_ || frame_get_u32(f + 4) > npts + 1u) {
#endif
            FAIL("bad END frame (status %u, points %u)", f[3], (unsigned)frame_get_u32(f + 4));
        }
        if (f[3] == CP_ST_OK) {
            if (f[1] != (uint8_t)(npts + 1u) || frame_get_u32(f + 4) != npts) {
                FAIL("complete END frame with seq %u points %u", f[1],
                     (unsigned)frame_get_u32(f + 4));
            }
        } else {
            in_frames = 0; /* an error END is followed by the text at once */
        }
        break;
    default:
        FAIL("unknown frame type 0x%02x", f[2]);
    }
    last_seq = f[1];
    if (good_host) {
        host_frame((uint8_t)(f[1] + 1u), FRAME_ACK);
    }
}

static void observe(void)
{
    while (scan < mem.out_len) {
        uint8_t c = mem.out[scan++];
        if (in_frames && !begun && (c == '\n' || (c >= 0x20u && c <= 0x7Eu && c != FRAME_SYNC))) {
            /* RUN's check answers in text before the first frame */
            if (c == '\n') {
                text_line();
                in_frames = !finished; /* an error: no frames come */
            } else if (tlen < sizeof text - 1) {
                text[tlen++] = (char)c;
            }
            continue;
        }
        if (in_frames) {
            begun = 1;
            if (frame_rx_feed(&frx, c)) {
                frame_in(frx.buf);
                tlen = 0;
            } else if (frx.len == 0xFFu || frx.len == 0u) {
                /* only text can be here: the text reply after the END frame */
                if (c == '\n') {
                    in_frames = 0;
                    text_line();
                } else if (c != FRAME_SYNC && tlen < sizeof text - 1) {
                    text[tlen++] = (char)c;
                }
            } else {
                tlen = 0;
            }
            if (!in_frames && eng.state == PROTO_IDLE) {
                /* frames ended (an error END); the text line follows */
            }
            continue;
        }
        if (c == '\n') {
            text_line();
        } else if (tlen < sizeof text - 1) {
            if (c < 0x20 || c > 0x7E) {
                FAIL("binary byte 0x%02x in text after the run", c);
            }
            text[tlen++] = (char)c;
        }
    }
    scan = 0;
    mem.out_len = 0;
}

static void poll_n(int n)
{
    int i;
    for (i = 0; i < n; i++) {
        int r = proto_poll(&eng);
        if (r < 0) {
            FAIL("proto_poll = %d", r);
        }
        observe();
    }
}

static void command(const char *cmd)
{
    host_bytes(cmd, strlen(cmd));
    host_bytes("\n", 1);
    finished = 0;
    poll_n(50);
    if (!finished) {
        FAIL("no reply to \"%s\"", cmd);
    }
}

/* The engine after the set-up of job j, and the expected points of the job. */
static void job_setup(unsigned j)
{
    struct proto_cfg cfg = {0};
    struct canal_path it;
    struct raster_pt pt;
    uint32_t k;
    int i;
    hal_mem_init(&mem, &uart);
    mem.tick_ms = 1;
    cfg.uart = &uart;
    if (proto_init(&eng, &cfg) != CP_OK) {
        FAIL("proto_init");
    }
    scan = tlen = 0;
    in_frames = finished = good_host = 0;
    for (i = 0; jobs[j][i] != NULL; i++) {
        command(jobs[j][i]);
    }
    command("FORMAT FRAMES");
    /* the reference: a separate iterator over a copy of the job's cfg */
    if (canal_path_init(&snap[j].ref, &eng.job.canal, &eng.job.cfg) != CP_OK ||
        canal_path_init(&it, &eng.job.canal, &eng.job.cfg) != CP_OK) {
        FAIL("job %u rejected", j);
    }
    snap[j].count = canal_path_count(&it);
    if (snap[j].count == 0u || snap[j].count > EXPECT_MAX) {
        FAIL("job %u has %u points", j, (unsigned)snap[j].count);
    }
    snap[j].pts = calloc(snap[j].count, sizeof *snap[j].pts);
    if (snap[j].pts == NULL) {
        FAIL("out of memory");
    }
    for (k = 0; k < snap[j].count; k++) {
        struct expect *e = &snap[j].pts[k];
        if (canal_path_next(&it, &pt) != CP_OK) {
            FAIL("reference iterator failed at %u", (unsigned)k);
        }
        e->x = q(pt.p.x, CP_R(10000.0));
        e->y = q(pt.p.y, CP_R(10000.0));
        e->z = q(pt.p.z, CP_R(10000.0));
        e->nx = (int16_t)q(pt.n.x, CP_R(32767.0));
        e->ny = (int16_t)q(pt.n.y, CP_R(32767.0));
        e->nz = (int16_t)q(pt.n.z, CP_R(32767.0));
        e->line = pt.line;
        e->index = pt.index;
    }
    snap[j].eng = eng;
    snap[j].mem = mem;
    snap[j].ready = 1;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    size_t a = 2, c;
    unsigned j;
    int i, polls;
    char cmd[32];
    struct start *st;
    if (size < 2) {
        return 0;
    }
    j = data[0] % NJOBS;
    if (!snap[j].ready) {
        job_setup(j);
    }
    ref = &snap[j].ref;
    exp_pts = snap[j].pts;
    scan = 0;
    good_host = 0;
    first = (data[1] & 0x80u) ? (uint32_t)(data[1] & 0x7Fu) % snap[j].count : 0u;
    npts = snap[j].count - first;
    st = starts[j][first];
    if (st == NULL) {
        eng = snap[j].eng; /* struct proto holds no pointer into itself (uart -> &uart) */
        mem = snap[j].mem;
        tlen = 0;
        last_seq = -1;
        frame_rx_init(&frx);
        in_frames = 1;
        begun = 0;
        finished = 0;
        if (first == 0u) {
            host_bytes("RUN\n", 4);
        } else {
            snprintf(cmd, sizeof cmd, "RESUME %u\n", (unsigned)first);
            host_bytes(cmd, strlen(cmd));
        }
        poll_n(4);
        st = malloc(sizeof *st);
        if (st == NULL) {
            FAIL("out of memory");
        }
        st->eng = eng;
        st->mem = mem;
        st->frx = frx;
        memcpy(st->text, text, sizeof text);
        st->tlen = tlen;
        st->in_frames = in_frames;
        st->begun = begun;
        st->finished = finished;
        st->last_seq = last_seq;
        starts[j][first] = st;
    } else {
        eng = st->eng;
        mem = st->mem;
        frx = st->frx;
        memcpy(text, st->text, sizeof text);
        tlen = st->tlen;
        in_frames = st->in_frames;
        begun = st->begun;
        finished = st->finished;
        last_seq = st->last_seq;
    }
    while (a < size && !finished) {
        uint8_t op = data[a++] % 8u;
        uint8_t arg = a < size ? data[a] : 0u;
        switch (op) {
        case 0:
            a++;
            c = arg % 32u;
            if (c > size - a) {
                c = size - a;
            }
            host_bytes(data + a, c);
            a += c;
            break;
        case 1:
            if (last_seq >= 0) {
                host_frame((uint8_t)(last_seq + 1), FRAME_ACK);
            }
            break;
        case 2:
            a++;
            host_frame(arg, FRAME_NAK);
            break;
        case 3:
            a++;
            host_frame(arg, FRAME_ACK);
            break;
        case 4: {
            static const uint8_t types[8] = {FRAME_HOLD, FRAME_GO, FRAME_STATUS, FRAME_HOLD,
                                             FRAME_GO, 0x7Fu, FRAME_POINT, FRAME_ABORT};
            a++;
            /* ABORT only on 1 of 32 values: the fuzzer should mostly stay in the run */
            host_frame(arg, (arg % 32u) == 31u ? FRAME_ABORT : types[arg % 7u]);
            break;
        }
        case 5:
            a++;
            poll_n(arg);
            break;
        case 6:
            a++;
            mem.tick_ms = arg % 64u;
            break;
        default: {
            uint8_t f[8];
            int n;
            uint8_t bit = a + 1 < size ? data[a + 1] : 0u;
            a += 2;
            n = frame_encode(arg, (bit & 0x80u) ? FRAME_NAK : FRAME_ACK, NULL, 0, f, sizeof f);
            f[(bit >> 3) % (unsigned)n] ^= (uint8_t)(1u << (bit & 7u));
            host_bytes(f, (size_t)n);
            break;
        }
        }
        poll_n(4);
    }
    /* a well-behaved host takes over */
    good_host = 1;
    mem.tick_ms = 1;
    if (!finished) {
        uint8_t sync[FRAME_MAX];
        memset(sync, FRAME_SYNC, sizeof sync);
        host_bytes(sync, sizeof sync);
        host_frame(0, FRAME_GO);
        if (last_seq >= 0) {
            host_frame((uint8_t)(last_seq + 1), FRAME_ACK);
        }
    }
    /* budget: every point a few polls, plus the go-back-N timeouts (250 ms each at
     * 1 ms per now_ms call, a few now_ms calls per poll) */
    for (polls = 0; polls < 40 * (int)npts + 4000 && !finished; polls++) {
        poll_n(1);
    }
    if (!finished || eng.state != PROTO_IDLE) {
        FAIL("hang: run of job %u not finished after %d polls with a good host (state %d, "
             "acked %u next %u end %u)",
             j, polls, eng.state, (unsigned)eng.run.acked, (unsigned)eng.run.next, (unsigned)eng.run.end);
    }
    finished = 0;
    in_frames = 0;
    tlen = 0;
    saw_ver = 0;
    /* a newline first, as a sender does after line noise: it ends a partial line of
     * the program's raw bytes, and a held 0x06.. prefix (a possible late frame) fails
     * its check at or before this byte or at one of "$I" (at most 5 bytes are held),
     * so "$I\n" is a line of its own */
    host_bytes("\n$I\n", 4);
    for (i = 0; i < 50 && !(saw_ver && finished); i++) {
        poll_n(1);
    }
    if (!saw_ver || !finished) {
        FAIL("no answer to $I after the run");
    }
    return 0;
}
