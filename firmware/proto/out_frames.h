/* out_frames.h - the FRAMES output format: the run streamed as binary CRC frames
 * (frame.h) to a controller, with a go-back-N window; and the tail after such a run,
 * when late frames of the host may still arrive among text.
 * SPDX-License-Identifier: MIT
 *
 * The stream (docs/PROTOCOL.md "RUN with FORMAT FRAMES"): item 0 is the BEGIN frame,
 * items 1..points one POINT frame each (from run->start_k), the last item the END frame
 * (status 0); seq = the low 8 bits of the item index. The host answers with ACK (seq =
 * next expected: cumulative), NAK (seq = wanted again), ABORT, HOLD, GO frames. At most
 * OUT_FRAMES_WINDOW frames are unacknowledged; a NAK, or OUT_FRAMES_RTO_MS without ACK
 * progress, resends from the oldest unacknowledged frame, regenerated from the path bit
 * for bit (no history buffer). OUT_FRAMES_MAX_RETRIES timeouts in a row end the run
 * with CP_ST_LINK_ERROR. A run that stops early sends an END frame with its status.
 */
#ifndef OUT_FRAMES_H
#define OUT_FRAMES_H

#include "frame.h"
#include "out.h"

/* Unacknowledged frames in flight (1..64; $I reports it as window=). */
#ifndef OUT_FRAMES_WINDOW
#define OUT_FRAMES_WINDOW 16u
#endif
/* Retransmission timeout without ACK progress, ms. */
#ifndef OUT_FRAMES_RTO_MS
#define OUT_FRAMES_RTO_MS 250u
#endif
/* Consecutive timeouts without progress before CP_ST_LINK_ERROR (1..255). */
#ifndef OUT_FRAMES_MAX_RETRIES
#define OUT_FRAMES_MAX_RETRIES 40u
#endif
/* After a FRAMES run: a held prefix of a late frame that gets no further byte for this
 * long is not a frame and is replayed as text, ms. A 6-byte frame takes 6 ms at 9600
 * baud. */
#define OUT_FRAMES_TAIL_MS 50u

#if OUT_FRAMES_WINDOW < 1 || OUT_FRAMES_WINDOW > 64
#error "OUT_FRAMES_WINDOW must be in 1..64"
#endif

/* The state of a FRAMES run (valid from out_frames_start to the end of the run). */
struct out_frames {
    struct frame_rx rx; /* decoder of the host's frames */
    uint8_t retries;    /* consecutive timeouts without ACK progress */
};

/* What a host frame asks of the engine (out_frames_take). ACK and NAK are handled
 * inside; these are the run controls, the binary form of the real-time bytes. */
enum out_frames_control {
    OUT_FRAMES_NONE = 0, /* nothing (ACK, NAK, STATUS, an unknown type) */
    OUT_FRAMES_ABORT,    /* ABORT: end the run with CP_ST_ABORTED */
    OUT_FRAMES_HOLD,     /* HOLD: send no new frames */
    OUT_FRAMES_GO        /* GO: send again (run->t_last is restarted) */
};

/* Start a FRAMES run of `path`: run->start_k is set, the path is positioned there,
 * run->next = run->acked = 0. Sets the state, run->lead (1: BEGIN) and run->end
 * (BEGIN + points from start_k + END). */
void out_frames_start(struct out_frames *f, struct out_run *run, const struct path *path);

/* Emit at most one frame: after a timeout go back to the oldest unacknowledged one,
 * then send the next if `sending` (the run is not held), it is below run->end and the
 * window has room. now: ms. Appends the frame to out[0..cap) (cap >= FRAME_MAX) and
 * stores its length in *len (0 when nothing was sent). Returns OUT_GOING, or the status
 * that ends the run: CP_ST_OK (every frame acknowledged), CP_ST_LINK_ERROR,
 * CP_ST_NUMERIC (a point could not be computed). */
int out_frames_emit(struct out_frames *f, struct out_run *run, struct path *path,
                    uint32_t now, int sending, uint8_t *out, size_t cap, size_t *len);

/* Feed one byte from the host to the decoder. Returns 1 when it completes a valid frame
 * (take it with out_frames_take before the next byte), else 0. */
int out_frames_rx(struct out_frames *f, uint8_t c);

/* Take the frame just decoded, received at now (ms): ACK and NAK move run->acked and
 * run->next (and restart run->t_last); returns the control the frame asks for. */
enum out_frames_control out_frames_take(struct out_frames *f, struct out_run *run, uint32_t now);

/* The END frame of a run that stops early with `status` (not CP_ST_OK: a complete run
 * sent its END as its last item), numbered run->next, with the points sent so far.
 * Writes it to out[0..cap) (cap >= FRAME_MIN + 5); returns its length (0: no room). */
size_t out_frames_finish(const struct out_run *run, int status, uint8_t *out, size_t cap);

/* The tail after a FRAMES run. The host may still send late 6-byte ACK/NAK frames (e.g.
 * for a retransmitted END). They start with len = 6 (0x06, never valid in text). While
 * `open`, bytes from such a 0x06 on are held in buf[] and checked as they come: a
 * complete frame of a host type with a good CRC and sync is dropped whole; anything else
 * (line noise) is replayed, byte for byte, as text once it fails a check (or stalls for
 * OUT_FRAMES_TAIL_MS), so a command after a stray 0x06 is never lost (its line gets
 * error:8 for the bad byte, as any other noise would). The engine opens the tail when a
 * FRAMES run ends and closes it at the next text command. */
struct out_frames_tail {
    uint32_t t0;            /* ms when buf[] got its first byte */
    uint8_t open;           /* late frames of the last FRAMES run may still arrive */
    uint8_t len;            /* bytes held in buf[] */
    uint8_t replay;         /* bytes of buf[] still to replay as text, 0..len */
    uint8_t buf[FRAME_MIN]; /* a possible late host frame */
};

/* What the tail did with a byte (out_frames_tail_take). */
enum out_frames_tail_use {
    OUT_FRAMES_TAIL_TEXT = 0, /* not taken: the byte is text */
    OUT_FRAMES_TAIL_HELD,     /* held (or the end of a late frame, dropped) */
    OUT_FRAMES_TAIL_STARTED   /* a 0x06 started a held prefix: stamp it (tail_started) */
};

/* Offer a byte received while the tail is open. */
enum out_frames_tail_use out_frames_tail_take(struct out_frames_tail *t, uint8_t c);

/* The time (ms) of the byte that made out_frames_tail_take return STARTED. */
void out_frames_tail_started(struct out_frames_tail *t, uint32_t now);

/* 1 if a prefix is held and waits for its next byte (then out_frames_tail_stalled). */
int out_frames_tail_waiting(const struct out_frames_tail *t);

/* No byte is waiting at now (ms): a held prefix that has waited OUT_FRAMES_TAIL_MS is
 * not a frame and is to be replayed. */
void out_frames_tail_stalled(struct out_frames_tail *t, uint32_t now);

/* The next held byte to replay as text (call only while t->replay > 0). */
uint8_t out_frames_tail_next(struct out_frames_tail *t);

#endif /* OUT_FRAMES_H */
