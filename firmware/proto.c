/* proto.c - the protocol engine: command lines, replies and the toolpath stream.
 * SPDX-License-Identifier: MIT
 */
#include "proto.h"
#include "fmt.h"
#include "parse.h"

#define PROTO_LF_OVERFLOW 0x01u /* the line exceeded CP_LINE_MAX-1 bytes */
#define PROTO_LF_BADCHAR 0x02u  /* the line held a byte outside 0x20..0x7E */

#define RT_STATUS '?'
#define RT_HOLD '!'
#define RT_RESUME '~'
#define RT_ABORT 0x18

/* The texts of cp_status.def packed in code order, each ended by its NUL (no pointer
 * table). The rows must number 0, 1, 2, ... in order: checked row by row below. */
enum cp_status_row {
#define CP_STATUS(name, num, text, from) CP_STATUS_ROW_##name,
#include "cp_status.def"
#undef CP_STATUS
    CP_STATUS_ROWS
};
#define CP_STATUS(name, num, text, from) CP_STATIC_ASSERT(CP_STATUS_ROW_##name == (num), row_##name);
#include "cp_status.def"
#undef CP_STATUS
static const char status_texts[] =
#define CP_STATUS(name, num, text, from) text "\0"
#include "cp_status.def"
#undef CP_STATUS
    ;

const char *cp_status_text(int code)
{
    const char *s = status_texts;
    size_t i;
    int n = 0;
    if (code < 0 || code >= CP_STATUS_ROWS) {
        return "?";
    }
    /* text number `code` starts after `code` NULs (bounded by the table) */
    for (i = 0; i < sizeof status_texts && n < code; i++) {
        if (status_texts[i] == '\0') {
            n++;
            s = status_texts + i + 1u;
        }
    }
    return s;
}

int proto_init(struct proto *p, const struct proto_cfg *cfg)
{
    if (p == NULL || cfg == NULL || cfg->uart == NULL || cfg->uart->write == NULL ||
        cfg->uart->read == NULL || cfg->uart->now_ms == NULL) {
        return CP_ERR_INVAL;
    }
    {
        /* every counter, length, flag and buffer 0: line_len, rx/tx, err = CP_OK,
         * state = PROTO_IDLE, fmt = JOB_GCODE, path.kind = PATH_CANAL, count 0, ...
         * (volatile stores, as in job_init: no library memset in the image) */
        volatile unsigned char *b = (volatile unsigned char *)p;
        size_t i;
        for (i = 0; i < sizeof *p; i++) {
            b[i] = 0u;
        }
    }
    p->uart = cfg->uart;
    job_init(&p->job);
    p->hdr = 1;
    frame_rx_init(&p->frx);
    return CP_OK;
}

/*---------------------------------------------------------------------------
 * Output staging. Callers check tx_room() >= PROTO_REPLY_MAX before a burst,
 * so the appends below cannot fail; a failure would truncate, never overrun.
 *-------------------------------------------------------------------------*/
static size_t tx_room(struct proto *p)
{
    if (p->tx_pos > 0u) { /* compact the unsent tail to the front */
        uint16_t i, k = (uint16_t)(p->tx_len - p->tx_pos);
        for (i = 0; i < k; i++) {
            p->tx[i] = p->tx[p->tx_pos + i];
        }
        p->tx_len = k;
        p->tx_pos = 0;
    }
    return (size_t)(CP_TX_BUF - p->tx_len);
}

/* Append the text s; returns the text after its NUL (the next key of a packed list:
 * tx_fields). A text that does not fit is cut at the end of tx[] (callers check
 * tx_room first, so it never is; the pointer returned then stays inside s). */
static const char *tx_text(struct proto *p, const char *s)
{
    unsigned i, n = p->tx_len, room = (unsigned)sizeof p->tx - n;
    for (i = 0; i < room && s[i] != '\0'; i++) {
        p->tx[n + i] = (uint8_t)s[i];
    }
    p->tx_len = (uint16_t)(n + i);
    return s + i + 1u;
}

static void tx_str(struct proto *p, const char *s)
{
    (void)tx_text(p, s);
}

static void tx_u32(struct proto *p, uint32_t v)
{
    size_t pos = p->tx_len;
    (void)fmt_u32((char *)p->tx, sizeof p->tx, &pos, v);
    p->tx_len = (uint16_t)pos;
}

/* The texts of `keys`, packed (each ended by its NUL), with the numbers v[0..n)
 * between them: key 0, v[0], key 1, ..., v[n-1], key n. */
static void tx_fields(struct proto *p, const char *keys, const uint32_t *v, unsigned n)
{
    unsigned i;
    for (i = 0; i < n; i++) {
        keys = tx_text(p, keys);
        tx_u32(p, v[i]);
    }
    tx_str(p, keys);
}

static void reply_status(struct proto *p, int code)
{
    uint32_t v = (uint32_t)code;
    if (code == CP_ST_OK) {
        tx_str(p, "ok\n");
        return;
    }
    tx_fields(p, "error:\0 ", &v, 1u);
    tx_str(p, cp_status_text(code));
    tx_str(p, "\n");
}

static void reply_info(struct proto *p)
{
    static const uint32_t val[8] = {CP_PROTO_VERSION, CP_LINE_MAX,  CP_TX_BUF,   CP_MAX_STEPS,
                                    CP_MAX_SUBSTEPS,  CP_MAX_LINES, CP_MAX_LINK, PROTO_WINDOW};
    tx_fields(p,
              "[VER:canalpath " CP_FW_VERSION " proto \0]\n[OPT:real=" CP_REAL_NAME
              ",line=\0,tx=\0,steps=\0,sub=\0,lines=\0,link=\0,window=\0,models=",
              val, 8u);
    tx_str(p, job_models());
    tx_str(p, "]\n");
}

/* "<Idle>" or "<Run|L:j/n|P:k/m>": the line (or circle) j of n of the last point sent,
 * and k points of the job's m sent (k counts from the job's first point: RESUME). */
static void reply_report(struct proto *p)
{
    static const char names[3][6] = {"<Idle", "<Run", "<Hold"};
    uint32_t v[4];
    const char *keys = ">\n";
    unsigned n = 0;
    tx_str(p, names[p->state]);
    if (p->state != PROTO_IDLE) {
        /* the items sent after the header lines (or BEGIN) are points from start_k on,
         * up to the last one (FRAMES: then END) */
        uint32_t skip = p->fmt == JOB_GCODE ? p->hdr : 1u, m = path_count(&p->path);
        uint32_t k = p->start_k + (p->next > skip ? p->next - skip : 0u);
        uint32_t block = (uint32_t)p->path.info.steps + 1u + p->path.info.link;
        if (k > m) { /* start_k + next <= m + 2 (run_start: end): no wrap above */
            k = m;
        }
        v[0] = k > 0u ? (k - 1u) / block : 0u;
        v[1] = p->path.info.n;
        v[2] = k;
        v[3] = m;
        keys = "|L:\0/\0|P:\0/\0>\n";
        n = 4u;
    }
    tx_fields(p, keys, v, n);
}

/*---------------------------------------------------------------------------
 * Run control
 *-------------------------------------------------------------------------*/
static int frames_item(struct proto *p, uint32_t idx, int status, uint8_t *out, size_t cap);

static void run_finish(struct proto *p, int status)
{
    if (p->fmt == JOB_FRAMES && status != CP_ST_OK) {
        /* tell a binary host why the stream stopped, then the text reply */
        int n = frames_item(p, p->next, status, p->tx + p->tx_len, sizeof p->tx - p->tx_len);
        if (n > 0) {
            p->tx_len = (uint16_t)(p->tx_len + n);
        }
    }
    reply_status(p, status);
    p->frames_tail = (uint8_t)(p->fmt == JOB_FRAMES);
    p->state = PROTO_IDLE;
}

static int run_start(struct proto *p, uint32_t first)
{
    int err;
    uint32_t npts, v[5]; /* v[0]: the points of the job; v[1..4]: the [RUN:...] line */
    if (job_ready(&p->job) != CP_ST_OK) {
        return CP_ST_NO_JOB;
    }
    err = path_init(&p->path, p->job.kind, &p->job.cfg, &p->job.geom);
    if (err != CP_OK) {
        return cp_status_of(err);
    }
    v[0] = path_count(&p->path);
    if (first >= v[0]) {
        return CP_ST_RESUME_RANGE;
    }
    if (first > 0u && path_seek(&p->path, first) != CP_OK) {
        return CP_ST_RESUME_RANGE;
    }
    npts = v[0] - first;
    p->fmt = p->job.format;
    p->start_k = first;
    p->next = 0;
    p->acked = 0;
    /* GCODE header: "G21 G90 G17", preceded by "M110 N0" with checksums so that a
     * Marlin-style machine numbers this run's lines from N1 whatever it saw before */
    p->hdr = (uint8_t)(p->job.checksum ? 2u : 1u);
    p->end = p->fmt == JOB_GCODE ? npts + p->hdr : npts + 2u;
    p->ring_head = 0;
    p->ring_n = 0;
    p->inflight = 0;
    p->resync = 0;
    p->retries = 0;
    p->pend_len = 0;
    p->t_last = hal_uart_now_ms(p->uart);
    frame_rx_init(&p->frx);
    p->state = PROTO_RUN;
    if (p->fmt == JOB_GCODE) {
        /* what the stream will hold, for hosts and judges (a G-code machine skips
         * '[' lines; this one is not counted against its RX buffer) */
        v[1] = first;
        v[2] = p->path.info.n;
        v[3] = p->path.info.steps;
        v[4] = p->path.info.link;
        tx_fields(p, "[RUN:points=\0,first=\0,mode=", v, 2u);
        tx_str(p, p->path.info.mode == RASTER_LINES ? "LINES" : "CIRCLES");
        tx_fields(p, ",n=\0,steps=\0,link=\0]\n", v + 2, 3u);
    }
    return CP_ST_OK;
}

/* Position the iterator on point k and fetch it. */
static int point_at(struct proto *p, uint32_t k, struct raster_pt *pt)
{
    if (path_pos(&p->path) != k && path_seek(&p->path, k) != CP_OK) {
        return CP_ERR_RANGE;
    }
    return path_next(&p->path, pt);
}

/* Round to an integer count of `scale` units: deterministic (floor is exact). */
static CP_NOINLINE int32_t quantize(cp_real v, cp_real scale)
{
    return (int32_t)cp_floor(v * scale + CP_R(0.5));
}

/* Build GCODE stream line `idx` into pend[]; returns its length or < 0 (the point's
 * error). The stream is hdr header lines, then one G1 per point. With checksums every
 * line is N<idx>: N0 M110 N0, N1 G21 G90 G17, N2 the first point... The longest line,
 * "N<10 digits> G1 X<12> Y<12> Z<12> F<12>*<3 digits>\n" (a coordinate or feed is an
 * int32 count with its sign and point: 12 bytes), is 75 bytes, so no append below can
 * fail (they are bounded by pend[] anyway; the single bytes are stored directly, 75 <
 * PROTO_GCODE_MAX leaves room for each). */
CP_STATIC_ASSERT(12 + 4 + 12 + 3 * (2 + 12) + 4 + 1 <= PROTO_GCODE_MAX, gcode_line_fits);
static int gcode_line(struct proto *p, uint32_t idx)
{
    char *out = p->pend;
    const size_t cap = sizeof p->pend;
    size_t pos = 0;
    if (p->job.checksum) {
        out[pos++] = 'N';
        (void)fmt_u32(out, cap, &pos, idx);
        out[pos++] = ' ';
    }
    if (idx < p->hdr) { /* idx + 2 == hdr: M110 (checksums only); idx + 1 == hdr: G21 */
        (void)fmt_str(out, cap, &pos, idx + 2u == p->hdr ? "M110 N0" : "G21 G90 G17");
    } else {
        static const char word[4][5] = {"G1 X", " Y", " Z", " F"};
        struct raster_pt pt;
        cp_real v[4];
        unsigned i, nw = p->job.feed > CP_R(0.0) ? 4u : 3u;
        int e = point_at(p, p->start_k + idx - p->hdr, &pt);
        if (e != CP_OK) {
            return e;
        }
        v[0] = pt.p.x;
        v[1] = pt.p.y;
        v[2] = pt.p.z;
        v[3] = p->job.feed;
        /* X Y Z with 4 decimals, then F (1 decimal) unless the feed is 0 */
        for (i = 0; i < nw; i++) {
            (void)fmt_str(out, cap, &pos, word[i]);
            (void)fmt_fixed(out, cap, &pos, quantize(v[i], i < 3u ? CP_R(10000.0) : CP_R(10.0)),
                            i < 3u ? 4u : 1u);
        }
    }
    if (p->job.checksum) {
        uint8_t cs = 0;
        size_t i;
        for (i = 0; i < pos; i++) {
            cs ^= (uint8_t)out[i];
        }
        out[pos++] = '*';
        (void)fmt_u32(out, cap, &pos, cs);
    }
    out[pos++] = '\n';
    return (int)pos;
}

/* Build FRAMES stream item `idx` into out; returns its length or < 0. With a status
 * other than CP_ST_OK: the END frame of a stopped run (idx = next; the points are
 * the frames sent after BEGIN). */
static int frames_item(struct proto *p, uint32_t idx, int status, uint8_t *out, size_t cap)
{
    uint8_t pl[FRAME_POINT_PAYLOAD];
    uint32_t npts = p->end - 2u, sent = idx > 0u ? idx - 1u : 0u;
    uint8_t type = FRAME_END;
    size_t plen = 5u;
    if (status != CP_ST_OK) {
        /* END below */
    } else if (idx == 0u) {
        frame_put_u32(pl, path_count(&p->path));
        frame_put_u32(pl + 4, p->start_k);
        frame_put_u16(pl + 8, p->path.info.n);
        frame_put_u16(pl + 10, p->path.info.steps);
        frame_put_u16(pl + 12, p->path.info.link);
        pl[14] = p->path.info.mode;
        type = FRAME_BEGIN;
        plen = 15u;
    } else if (idx <= npts) {
        struct raster_pt pt;
        uint32_t k = p->start_k + idx - 1u;
        int e = point_at(p, k, &pt);
        cp_real v[6];
        unsigned i;
        if (e != CP_OK) {
            return e;
        }
        v[0] = pt.p.x;
        v[1] = pt.p.y;
        v[2] = pt.p.z;
        v[3] = pt.n.x;
        v[4] = pt.n.y;
        v[5] = pt.n.z;
        frame_put_u32(pl, k);
        for (i = 0; i < 3u; i++) { /* position in 0.1 um, normal in 1/32767 */
            frame_put_u32(pl + 4u + 4u * i, (uint32_t)quantize(v[i], CP_R(10000.0)));
            frame_put_u16(pl + 16u + 2u * i, (uint16_t)(int16_t)quantize(v[3u + i], CP_R(32767.0)));
        }
        frame_put_u16(pl + 22, (uint16_t)pt.line);
        frame_put_u16(pl + 24, pt.index);
        type = FRAME_POINT;
        plen = FRAME_POINT_PAYLOAD;
    }
    if (type == FRAME_END) {
        pl[0] = (uint8_t)status;
        frame_put_u32(pl + 1, sent < npts ? sent : npts); /* the whole run: idx = npts + 1 */
    }
    return frame_encode((uint8_t)idx, type, pl, plen, out, cap);
}

/* Emit at most one stream item if flow control allows. Returns 1 if one was sent. */
static int run_emit(struct proto *p)
{
    uint32_t now = hal_uart_now_ms(p->uart);
    int n;
    if (tx_room(p) < PROTO_REPLY_MAX) {
        return 0; /* every path below may append a whole burst */
    }
    if (p->fmt == JOB_GCODE) {
        if (p->next >= p->end) {
            if (p->ring_n == 0u) {
                run_finish(p, CP_ST_OK);
                return 1;
            }
        } else if (p->resync) {
            /* after a Resend: the line must be quiet, then start afresh from n */
            if ((uint32_t)(now - p->t_last) >= PROTO_RESYNC_MS) {
                p->resync = 0;
                p->ring_n = 0;
                p->inflight = 0;
                p->t_last = now;
            }
            return 0;
        } else if (p->state == PROTO_RUN && p->ring_n < PROTO_RING) {
            /* the line is built once into pend[] and waits there until the machine's
             * RX buffer has room for it (text replies meanwhile do not disturb it) */
            if (p->pend_len == 0u || p->pend_idx != p->next) {
                n = gcode_line(p, p->next);
                if (n < 0) {
                    run_finish(p, CP_ST_NUMERIC);
                    return 1;
                }
                p->pend_len = (uint8_t)n;
                p->pend_idx = p->next;
            }
            n = p->pend_len;
            if ((uint32_t)p->inflight + (uint32_t)n <= p->job.rxbuf) {
                int i;
                for (i = 0; i < n; i++) {
                    p->tx[p->tx_len + i] = (uint8_t)p->pend[i];
                }
                p->pend_len = 0;
                p->tx_len = (uint16_t)(p->tx_len + n);
                p->ring[(p->ring_head + p->ring_n) % PROTO_RING] = (uint8_t)n;
                p->ring_n++;
                p->inflight = (uint16_t)(p->inflight + n);
                if (p->ring_n == 1u) {
                    p->t_last = now; /* the answer clock starts with the first line in flight */
                }
                p->next++;
                return 1;
            }
        }
        if (p->ring_n > 0u && (uint32_t)(now - p->t_last) > PROTO_PEER_TIMEOUT_MS) {
            run_finish(p, CP_ST_TIMEOUT);
            return 1;
        }
        return 0;
    }
    /* FRAMES */
    if (p->acked >= p->end) {
        run_finish(p, CP_ST_OK);
        return 1;
    }
    if (p->state == PROTO_RUN && p->acked < p->next && (uint32_t)(now - p->t_last) > PROTO_RTO_MS) {
        /* go-back-N: resend everything from the oldest unacknowledged frame */
        if (++p->retries >= PROTO_MAX_RETRIES) {
            run_finish(p, CP_ST_LINK_ERROR);
            return 1;
        }
        p->next = p->acked;
        p->t_last = now;
    }
    if (p->state == PROTO_RUN && p->next < p->end && p->next - p->acked < PROTO_WINDOW) {
        n = frames_item(p, p->next, CP_ST_OK, p->tx + p->tx_len, FRAME_MAX);
        if (n < 0) {
            run_finish(p, CP_ST_NUMERIC);
            return 1;
        }
        if (p->next == p->acked) {
            p->t_last = now; /* the retransmission clock runs from the oldest frame */
        }
        p->tx_len = (uint16_t)(p->tx_len + n);
        p->next++;
        return 1;
    }
    return 0;
}

static void frames_rx(struct proto *p, const uint8_t *f)
{
    /* the full sequence number of the received 8-bit seq, counted from acked; it is
     * one of ours only if it is <= next */
    uint32_t full = p->acked + (uint8_t)(f[1] - (uint8_t)p->acked);
    uint32_t now = hal_uart_now_ms(p->uart);
    switch (f[2]) {
    case FRAME_ACK:
        if (full <= p->next && full > p->acked) {
            p->acked = full;
            p->t_last = now;
            p->retries = 0;
        }
        break;
    case FRAME_NAK:
        if (full >= p->acked && full < p->next) {
            p->acked = full; /* everything before it arrived */
            p->next = full;
            p->t_last = now;
        }
        break;
    case FRAME_ABORT:
        run_finish(p, CP_ST_ABORTED);
        break;
    case FRAME_HOLD:
        p->state = PROTO_HOLD;
        break;
    case FRAME_GO:
        p->state = PROTO_RUN;
        p->t_last = now;
        break;
    default:
        break; /* STATUS and unknown types: ignored in this version */
    }
}

/*---------------------------------------------------------------------------
 * Lines
 *-------------------------------------------------------------------------*/
/* The machine's responses, in the order they are tried: "ok" (the whole line), the
 * errors "error:", "ALARM:", "Error:", the resend requests "rs ", "Resend:". */
enum { M_OK, M_ERROR, M_ALARM, M_ERROR2, M_RS, M_RESEND, M_NONE };
static const char machine_pre[] = "ok\0error:\0ALARM:\0Error:\0rs \0Resend:";

/* A line from the machine during a GCODE run (or a stray one when idle).
 * Returns 1 if it was a machine response (consumed), else 0. */
static int machine_line(struct proto *p)
{
    /* the machine's lines act only on a GCODE run (when idle they are just consumed) */
    int gc = p->state != PROTO_IDLE && p->fmt == JOB_GCODE;
    const char *kw = machine_pre;
    unsigned m, a = 0;
    for (m = 0; m < M_NONE; m++) { /* the first prefix the line starts with */
        for (a = 0; kw[a] != '\0' && a < p->line_len && p->line[a] == kw[a]; a++) {
        }
        if (kw[a] == '\0' && (m != M_OK || p->line_len == 2u)) {
            break;
        }
        while (a < 8u && kw[a] != '\0') { /* to the next prefix (all shorter than 8) */
            a++;
        }
        kw += a + 1u;
    }
    if (m == M_NONE) {
        return 0;
    }
    if (gc) {
        p->t_last = hal_uart_now_ms(p->uart);
    }
    if (m == M_OK) {
        if (gc && !p->resync && p->ring_n > 0u) {
            p->inflight = (uint16_t)(p->inflight - p->ring[p->ring_head]);
            p->ring_head = (uint8_t)((p->ring_head + 1u) % PROTO_RING);
            p->ring_n--;
            p->acked++;
        }
    } else if (m < M_RS) {
        /* with checksums a machine error precedes its Resend: request */
        if (gc && (!p->job.checksum || m == M_ALARM)) {
            run_finish(p, CP_ST_PEER_ERROR);
        }
    } else {
        uint32_t n;
        while (a < p->line_len && p->line[a] == ' ') { /* a: after the prefix */
            a++;
        }
        if (gc && p->job.checksum && !p->resync) {
            if (parse_uint(p->line + a, (size_t)(p->line_len - a), 0xFFFFFFFFu, &n) == CP_ST_OK &&
                n < p->next) {
                /* regenerate from line Nn (stream index n) once the machine has gone
                 * quiet (run_emit); later Resend: requests for lines already in flight
                 * are ignored */
                p->next = n;
                p->resync = 1;
                p->pend_len = 0;
            } else {
                /* a line we never sent: the machine counts differently (no M110, or a
                 * garbled request); its oks cannot be trusted - stop */
                run_finish(p, CP_ST_PEER_ERROR);
            }
        }
    }
    return 1;
}

static void exec_line(struct proto *p)
{
    uint16_t a = 0, b = p->line_len;
    uint32_t k = 0;
    int st;
    p->lines_seen++;
    if (p->line_flags != 0u) { /* PROTO_LF_OVERFLOW and/or PROTO_LF_BADCHAR */
        if (p->state == PROTO_IDLE) { /* (machine chatter during a run: no reply into the stream) */
            reply_status(p, (p->line_flags & PROTO_LF_OVERFLOW) ? CP_ST_LINE_TOO_LONG
                                                                : CP_ST_BAD_CHAR);
        }
        return;
    }
    /* trim spaces at both ends */
    while (a < b && p->line[a] == ' ') {
        a++;
    }
    while (b > a && p->line[b - 1u] == ' ') {
        b--;
    }
    if (a > 0u) {
        uint16_t i;
        for (i = a; i < b; i++) {
            p->line[i - a] = p->line[i];
        }
    }
    p->line_len = (uint16_t)(b - a);
    if (machine_line(p)) {
        return;
    }
    if (p->line_len == 0u) {
        if (p->state == PROTO_IDLE) {
            reply_status(p, CP_ST_OK); /* sync, as grbl */
        }
        return;
    }
    if (parse_kw(p->line, p->line_len, "$I\0HELLO", 2u) < 2u) {
        reply_info(p);
        reply_status(p, CP_ST_OK);
        return;
    }
    if (p->state != PROTO_IDLE) {
        /* during a run the peer is the machine: a job command gets error:7, any other
         * line (echo:, busy:, [MSG:...]) is chatter and gets no reply in the stream */
        if (job_is_command(p->line, p->line_len)) {
            reply_status(p, CP_ST_BUSY);
        }
        return;
    }
    p->frames_tail = 0; /* a text command: late frames of the last run are over */
    st = job_line(&p->job, p->line, p->line_len, &k);
    if (st == JOB_RUN) { /* RUN or RESUME k: a run from point 0 or k ("ok" at its end) */
        st = run_start(p, k);
        if (st == CP_ST_OK) {
            return;
        }
    }
    reply_status(p, st == JOB_NOT_MINE ? CP_ST_UNKNOWN_CMD : st);
}

/* Real-time bytes act at once, outside the line assembly (grbl). */
static int realtime(struct proto *p, uint8_t c)
{
    switch (c) {
    case RT_STATUS:
        reply_report(p);
        return 1;
    case RT_HOLD:
        if (p->state == PROTO_RUN) {
            p->state = PROTO_HOLD;
        }
        return 1;
    case RT_RESUME:
        if (p->state == PROTO_HOLD) {
            p->state = PROTO_RUN;
            p->t_last = hal_uart_now_ms(p->uart);
        }
        return 1;
    case RT_ABORT:
        p->line_len = 0;
        p->line_flags = 0;
        if (p->state != PROTO_IDLE) {
            run_finish(p, CP_ST_ABORTED);
        }
        return 1;
    default:
        return 0;
    }
}

/* Text path: real-time bytes, then line assembly. */
static void feed_text(struct proto *p, uint8_t c)
{
    if (realtime(p, c)) {
        return;
    }
    if (c == '\n' || c == '\r') {
        int skip = (c == '\n' && p->last_cr);
        p->last_cr = (uint8_t)(c == '\r');
        if (skip) {
            return;
        }
        exec_line(p);
        p->line_len = 0;
        p->line_flags = 0;
        return;
    }
    p->last_cr = 0;
    if (c == '\t') {
        c = ' ';
    }
    if (c < 0x20u || c > 0x7Eu) {
        p->line_flags |= PROTO_LF_BADCHAR;
        return;
    }
    if (p->line_len >= CP_LINE_MAX - 1) {
        p->line_flags |= PROTO_LF_OVERFLOW;
        return;
    }
    p->line[p->line_len++] = (char)c;
}

/* After a FRAMES run the host may still send late 6-byte ACK/NAK frames. They start
 * with len = 6 (0x06, never valid in text). Bytes from such a 0x06 on are held in
 * tail[] and checked as they come: a complete frame of a host type with a good CRC
 * and sync is dropped whole; anything else (line noise) is replayed, byte for byte,
 * as text once it fails a check, so a command after a stray 0x06 is never lost (its
 * line gets error:8 for the bad byte, as any other noise would). Returns 1 if c was
 * taken here. */
static int tail_take(struct proto *p, uint8_t c)
{
    uint8_t n = p->tail_len;
    int ok;
    if (n == 0u) {
        if (c != FRAME_MIN) {
            return 0;
        }
        p->tail_t = hal_uart_now_ms(p->uart);
    }
    p->tail[n++] = c;
    p->tail_len = n;
    switch (n) {
    case 3u: /* type: a host -> firmware frame */
        ok = c >= FRAME_ACK && c <= FRAME_STATUS;
        break;
    case 6u: /* sync, and the CRC over len..type and the CRC itself is 0 (frame.c) */
        ok = c == FRAME_SYNC && frame_crc16(0xFFFFu, p->tail, 5u) == 0u;
        if (ok) {
            p->tail_len = 0; /* a late frame: dropped */
            return 1;
        }
        break;
    default:
        ok = 1;
        break;
    }
    if (!ok) {
        p->tail_rep = n; /* not a frame: proto_poll replays the held bytes as text */
    }
    return 1;
}

static void feed(struct proto *p, uint8_t c)
{
    if (p->state != PROTO_IDLE && p->fmt == JOB_FRAMES) {
        if (frame_rx_feed(&p->frx, c)) {
            frames_rx(p, p->frx.buf);
        }
        return;
    }
    if (p->frames_tail && tail_take(p, c)) {
        return;
    }
    feed_text(p, c);
}

/* The next held byte of a failed late-frame check, as text (it never starts another
 * check: a 0x06 among them is noise and makes its line error:8). */
static void tail_replay(struct proto *p)
{
    uint8_t c = p->tail[p->tail_len - p->tail_rep];
    if (--p->tail_rep == 0u) {
        p->tail_len = 0;
    }
    if (p->state != PROTO_IDLE && p->fmt == JOB_FRAMES) {
        feed(p, c); /* a replayed RUN started a FRAMES run: the rest are its bytes */
    } else {
        feed_text(p, c);
    }
}

int proto_poll(struct proto *p)
{
    int moved = 0;
    int n;
    if (p->err != CP_OK) {
        return p->err;
    }
    /* 1. flush (non-blocking, partial writes are normal) */
    if (p->tx_pos < p->tx_len) {
        n = hal_uart_write(p->uart, p->tx + p->tx_pos, (size_t)(p->tx_len - p->tx_pos));
        if (n < 0) {
            p->err = CP_ERR_IO;
            return p->err;
        }
        p->tx_pos = (uint16_t)(p->tx_pos + (uint16_t)n);
        moved |= (n > 0);
        if (p->tx_pos == p->tx_len) {
            p->tx_pos = 0;
            p->tx_len = 0;
        }
    }
    /* 2. refill the receive chunk */
    if (p->rx_pos == p->rx_len) {
        n = hal_uart_read(p->uart, p->rx, sizeof p->rx);
        if (n < 0) {
            p->err = CP_ERR_IO;
            return p->err;
        }
        p->rx_len = (uint8_t)n;
        p->rx_pos = 0;
        moved |= (n > 0);
    }
    /* 3. consume bytes while a whole reply burst still fits (back-pressure:
     *    unread bytes stay in the HAL/kernel buffer, nothing is dropped) */
    if (p->tail_len > 0u && p->tail_rep == 0u && p->rx_pos == p->rx_len &&
        (uint32_t)(hal_uart_now_ms(p->uart) - p->tail_t) >= PROTO_TAIL_MS) {
        p->tail_rep = p->tail_len; /* a stalled prefix is not a frame: replay it */
    }
    while (p->tail_rep > 0u && tx_room(p) >= PROTO_REPLY_MAX) { /* <= FRAME_MIN */
        tail_replay(p);
        moved = 1;
    }
    while (p->tail_rep == 0u && p->rx_pos < p->rx_len &&
           tx_room(p) >= PROTO_REPLY_MAX) { /* <= sizeof rx */
        feed(p, p->rx[p->rx_pos++]);
        moved = 1;
    }
    /* 4. one stream item */
    if (p->state != PROTO_IDLE) {
        moved |= run_emit(p);
    }
    return moved;
}
