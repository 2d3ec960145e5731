/* out_frames.c - the FRAMES output format and the tail after a FRAMES run
 * (out_frames.h).
 * SPDX-License-Identifier: MIT
 */
#include "out_frames.h"

#define END_PAYLOAD 5u   /* u8 status, u32 points sent */
#define BEGIN_PAYLOAD 16u /* u32 points, u32 first, u16 n, u16 steps, u16 link, u8 mode,
                            u8 overlap */

/* The points of the run: the items between BEGIN and END. */
static uint32_t run_points(const struct out_run *run)
{
    return run->end - 2u;
}

static int encode_begin(const struct out_run *run, const struct path *path, uint8_t *out,
                        size_t cap)
{
    uint8_t pl[BEGIN_PAYLOAD];
    frame_put_u32(pl, path_count(path));
    frame_put_u32(pl + 4, run->start_k);
    frame_put_u16(pl + 8, path->info.n);
    frame_put_u16(pl + 10, path->info.steps);
    frame_put_u16(pl + 12, path->info.link);
    pl[14] = path->info.mode;
    pl[15] = path->info.overlap; /* 1: far parts meet, the tool inside (reported) */
    return frame_encode(0u, FRAME_BEGIN, pl, sizeof pl, out, cap);
}

/* POINT frame of stream item idx (1..points): position in 0.1 um, normal in 1/32767. */
static int encode_point(const struct out_run *run, struct path *path, uint32_t idx,
                        uint8_t *out, size_t cap)
{
    uint8_t pl[FRAME_POINT_PAYLOAD];
    struct raster_pt pt;
    uint32_t k = run->start_k + idx - 1u;
    int e = out_point(path, &run->place, k, &pt);
    if (e != CP_OK) {
        return e;
    }
    frame_put_u32(pl, k);
    /* position in 0.1 um (int32 x, y, z at 4, 8, 12), normal in 1/32767 (int16 at 16, 18,
     * 20), line and index (22, 24): frame.h's POINT payload */
    frame_put_u32(pl + 4, (uint32_t)out_quantize(pt.p.x, CP_R(10000.0)));
    frame_put_u32(pl + 8, (uint32_t)out_quantize(pt.p.y, CP_R(10000.0)));
    frame_put_u32(pl + 12, (uint32_t)out_quantize(pt.p.z, CP_R(10000.0)));
    frame_put_u16(pl + 16, (uint16_t)(int16_t)out_quantize(pt.n.x, CP_R(32767.0)));
    frame_put_u16(pl + 18, (uint16_t)(int16_t)out_quantize(pt.n.y, CP_R(32767.0)));
    frame_put_u16(pl + 20, (uint16_t)(int16_t)out_quantize(pt.n.z, CP_R(32767.0)));
    frame_put_u16(pl + 22, (uint16_t)pt.line);
    frame_put_u16(pl + 24, pt.index);
    return frame_encode((uint8_t)idx, FRAME_POINT, pl, sizeof pl, out, cap);
}

/* END frame numbered idx with `status`: the points sent are the items after BEGIN
 * below idx (the whole run when idx = points + 1). */
static int encode_end(const struct out_run *run, uint32_t idx, int status, uint8_t *out,
                      size_t cap)
{
    uint8_t pl[END_PAYLOAD];
    uint32_t npts = run_points(run), sent = idx > 0u ? idx - 1u : 0u;
    pl[0] = (uint8_t)status;
    frame_put_u32(pl + 1, sent < npts ? sent : npts);
    return frame_encode((uint8_t)idx, FRAME_END, pl, sizeof pl, out, cap);
}

void out_frames_start(struct out_frames *f, struct out_run *run, const struct path *path)
{
    frame_rx_init(&f->rx);
    f->retries = 0;
    run->lead = 1u;
    run->end = path_count(path) - run->start_k + 2u; /* BEGIN, the points, END */
}

int out_frames_emit(struct out_frames *f, struct out_run *run, struct path *path,
                    uint32_t now, int sending, uint8_t *out, size_t cap, size_t *len)
{
    uint32_t idx = run->next;
    int n;
    *len = 0;
    if (run->acked >= run->end) {
        return CP_ST_OK; /* every frame acknowledged */
    }
    if (sending && run->acked < run->next && (uint32_t)(now - run->t_last) > OUT_FRAMES_RTO_MS) {
        /* go-back-N: resend everything from the oldest unacknowledged frame */
        if (++f->retries >= OUT_FRAMES_MAX_RETRIES) {
            return CP_ST_LINK_ERROR;
        }
        run->next = run->acked;
        run->t_last = now;
        idx = run->next;
    }
    if (!sending || idx >= run->end || idx - run->acked >= OUT_FRAMES_WINDOW) {
        return OUT_GOING;
    }
    if (idx == 0u) {
        n = encode_begin(run, path, out, cap);
    } else if (idx <= run_points(run)) {
        n = encode_point(run, path, idx, out, cap);
    } else {
        n = encode_end(run, idx, CP_ST_OK, out, cap);
    }
    if (n < 0) {
        return CP_ST_NUMERIC;
    }
    if (idx == run->acked) {
        run->t_last = now; /* the retransmission clock runs from the oldest frame */
    }
    run->next = idx + 1u;
    *len = (size_t)n;
    return OUT_GOING;
}

int out_frames_rx(struct out_frames *f, uint8_t c)
{
    return frame_rx_feed(&f->rx, c);
}

enum out_frames_control out_frames_take(struct out_frames *f, struct out_run *run, uint32_t now)
{
    const uint8_t *fr = f->rx.buf;
    /* the full sequence number of the 8-bit seq, counted from acked; it is one of ours
     * only if it is <= next */
    uint32_t full = run->acked + (uint8_t)(fr[1] - (uint8_t)run->acked);
    switch (fr[2]) {
    case FRAME_ACK:
        if (full <= run->next && full > run->acked) {
            run->acked = full;
            run->t_last = now;
            f->retries = 0;
        }
        return OUT_FRAMES_NONE;
    case FRAME_NAK:
        if (full >= run->acked && full < run->next) {
            run->acked = full; /* everything before it arrived */
            run->next = full;
            run->t_last = now;
        }
        return OUT_FRAMES_NONE;
    case FRAME_ABORT:
        return OUT_FRAMES_ABORT;
    case FRAME_HOLD:
        return OUT_FRAMES_HOLD;
    case FRAME_GO:
        run->t_last = now;
        return OUT_FRAMES_GO;
    default:
        return OUT_FRAMES_NONE; /* STATUS and unknown types: ignored in this version */
    }
}

size_t out_frames_finish(const struct out_run *run, int status, uint8_t *out, size_t cap)
{
    int n;
    if (status == CP_ST_OK) {
        return 0;
    }
    n = encode_end(run, run->next, status, out, cap);
    return n > 0 ? (size_t)n : 0u;
}

/*---------------------------------------------------------------------------
 * The tail after a FRAMES run
 *-------------------------------------------------------------------------*/
enum out_frames_tail_use out_frames_tail_take(struct out_frames_tail *t, uint8_t c)
{
    uint8_t n = t->len;
    int ok = 1;
    if (n == 0u && c != FRAME_MIN) {
        return OUT_FRAMES_TAIL_TEXT;
    }
    t->buf[n++] = c;
    t->len = n;
    if (n == 3u) { /* type: a host -> firmware frame */
        ok = c >= FRAME_ACK && c <= FRAME_STATUS;
    } else if (n == FRAME_MIN) {
        /* sync, and the CRC over len..type and the CRC itself is 0 (frame.c) */
        ok = c == FRAME_SYNC && frame_crc16(0xFFFFu, t->buf, FRAME_MIN - 1u) == 0u;
        if (ok) {
            t->len = 0; /* a late frame: dropped */
            return OUT_FRAMES_TAIL_HELD;
        }
    }
    if (!ok) {
        t->replay = n; /* not a frame: the engine replays the held bytes as text */
    }
    return n == 1u ? OUT_FRAMES_TAIL_STARTED : OUT_FRAMES_TAIL_HELD;
}

void out_frames_tail_started(struct out_frames_tail *t, uint32_t now)
{
    t->t0 = now;
}

int out_frames_tail_waiting(const struct out_frames_tail *t)
{
    return t->len > 0u && t->replay == 0u;
}

void out_frames_tail_stalled(struct out_frames_tail *t, uint32_t now)
{
    if (out_frames_tail_waiting(t) && (uint32_t)(now - t->t0) >= OUT_FRAMES_TAIL_MS) {
        t->replay = t->len;
    }
}

uint8_t out_frames_tail_next(struct out_frames_tail *t)
{
    uint8_t c = t->buf[t->len - t->replay];
    if (--t->replay == 0u) {
        t->len = 0;
    }
    return c;
}
