/* proto.h - the protocol engine: commands in, replies and the toolpath stream out,
 * over one hal_uart. The full wire description is docs/PROTOCOL.md.
 * SPDX-License-Identifier: MIT
 *
 * grbl conventions: ASCII lines ending in '\n' or '\r' ("\r\n" counts once);
 * every command line is answered "ok" or "error:<code> <text>" (cp_status.def).
 * The firmware never transmits before the host has spoken (no boot banner):
 * bytes written to a pty or QEMU UART before the host attaches are lost.
 *
 * Commands: $I | HELLO (version and limits), the job commands of job.h, RUN,
 * RESUME k. Real-time bytes (outside FRAMES runs): '?' status report,
 * '!' feed hold, '~' resume, 0x18 abort.
 *
 * RUN validates the job (canal_path_init) and streams it:
 *   GCODE   "G21 G90 G17" then one "G1 X.. Y.. Z.. [F..]" per point, 4 decimals,
 *           optionally "N<n> ... *<cs>" (CHECKSUM ON). The firmware is the sender: it
 *           keeps the bytes of unacknowledged lines <= RXBUF (grbl character
 *           counting) and consumes one "ok" per line from the machine; "error:..." or
 *           "ALARM:..." from the machine stops the job (error:19); "Resend: n"
 *           regenerates from line n (checksum mode). Then "ok" (or "error:N").
 *   FRAMES  binary frames (frame.h): BEGIN, one POINT per point, END, with a window
 *           of PROTO_WINDOW unacknowledged frames, go-back-N on NAK or timeout; the
 *           host answers with ACK/NAK/ABORT/HOLD/GO frames. Then the text line "ok"
 *           (or an END frame with the status and the text "error:N ...").
 * Points are regenerated from the toolpath iterator on every retransmission: no
 * history buffer, and a stream is byte-identical on every target.
 */
#ifndef PROTO_H
#define PROTO_H

#include "cp_status.h"
#include "cp_types.h"
#include "frame.h"
#include "hal_uart.h"
#include "job.h"

/* Worst-case length of one reply burst (the $I answer, or one stream line), bytes. */
#define PROTO_REPLY_MAX 160

/* After a FRAMES run: a held 0x06.. prefix that gets no further byte for this long
 * is not a late host frame and is replayed as text, ms. A 6-byte frame takes 6 ms
 * at 9600 baud. */
#define PROTO_TAIL_MS 50u

/* FRAMES: unacknowledged frames in flight (1..64). */
#ifndef PROTO_WINDOW
#define PROTO_WINDOW 16u
#endif
/* FRAMES: retransmission timeout without ACK progress, ms. */
#ifndef PROTO_RTO_MS
#define PROTO_RTO_MS 250u
#endif
/* FRAMES: consecutive timeouts without progress before error:23. */
#ifndef PROTO_MAX_RETRIES
#define PROTO_MAX_RETRIES 40u
#endif
/* GCODE: the machine must answer a line within this time, ms (else error:22). */
#ifndef PROTO_PEER_TIMEOUT_MS
#define PROTO_PEER_TIMEOUT_MS 10000u
#endif
/* GCODE + CHECKSUM: after "Resend: n" the firmware sends nothing until the machine has
 * been quiet this long, ms, then forgets its in-flight accounting and resends from n.
 * (A machine answers a corrupted or merged line unpredictably - Marlin flushes its RX
 * buffer - so counting its oks cannot be trusted across a resend.) */
#ifndef PROTO_RESYNC_MS
#define PROTO_RESYNC_MS 100u
#endif
/* GCODE: the longest stream line, bytes: "N<n> G1 X.. Y.. Z.. F..*<cs>\n" with 4 decimals
 * per coordinate stays under 90. RXBUF may not be smaller (JOB_RXBUF_MIN). */
#define PROTO_GCODE_MAX 96
#if PROTO_GCODE_MAX > JOB_RXBUF_MIN
#error "a stream line must fit an empty machine RX buffer (JOB_RXBUF_MIN)"
#endif
/* GCODE: lines in flight are tracked in a ring of this many entries. */
#define PROTO_RING 64u

#if CP_TX_BUF < PROTO_REPLY_MAX
#error "CP_TX_BUF must hold one reply burst (PROTO_REPLY_MAX)"
#endif
#if PROTO_WINDOW < 1 || PROTO_WINDOW > 64
#error "PROTO_WINDOW must be in 1..64"
#endif

enum proto_state { PROTO_IDLE = 0, PROTO_RUN = 1, PROTO_HOLD = 2 };

struct proto_cfg {
    const struct hal_uart *uart; /* the serial port; must stay valid while in use */
};

struct proto {
    /* Layout (flash, not behaviour): the scalars the engine uses most come first -
     * bytes, halfwords, words - because Thumb's 16-bit loads and stores reach only
     * byte offsets below 32, halfword offsets below 64 and word offsets below 128;
     * the path follows them, so the iterators' fields stay near the start of the
     * (single, static) engine too; then the job, the rarely used scalars and the
     * buffers. Measured on the all-models LTO image: about -490 B against the plain order. */
    uint8_t state;           /* enum proto_state */
    uint8_t fmt;             /* enum job_format of the current run */
    uint8_t ring_head, ring_n; /* GCODE: lengths of unacknowledged lines */
    uint8_t retries;         /* FRAMES: consecutive timeouts */
    uint8_t pend_len;        /* GCODE: bytes of the built line in pend[], waiting for RXBUF room */
    uint8_t hdr;             /* GCODE: header lines before the points (1, or 2 with CHECKSUM) */
    uint8_t frames_tail;     /* the last run was FRAMES: late ACK/NAK frames may still arrive */
    uint8_t tail_len;        /* bytes of a possible late frame held in tail[] */
    uint8_t tail_rep;        /* bytes of tail[] still to replay as text (not a frame after all) */
    uint8_t rx_len, rx_pos;  /* valid bytes in rx[], next to consume */
    uint8_t line_flags;      /* PROTO_LF_* of the current line */
    uint8_t last_cr;         /* previous byte was '\r' (so a following '\n' is skipped) */
    uint16_t line_len;       /* bytes in line[] */
    uint16_t tx_len, tx_pos; /* bytes in tx[], next to send */
    uint16_t inflight;       /* GCODE: bytes of unacknowledged lines */
    uint16_t resync;         /* GCODE: 1 after a Resend: wait for a quiet line, then restart */
    const struct hal_uart *uart;
    uint32_t start_k;        /* first point of the run (RESUME k) */
    uint32_t next;           /* next stream item to send (GCODE line / FRAMES frame index) */
    uint32_t acked;          /* FRAMES: items below are acknowledged; GCODE: lines acked */
    uint32_t end;            /* stream items of the run */
    uint32_t t_last;         /* ms of the last progress from the peer */
    struct path path;        /* the validated toolpath of the current run (any model) */
    struct job job;          /* the job being assembled / run */
    int err;                 /* sticky fatal error (CP_ERR_IO after hang-up), else 0 */
    uint32_t lines_seen;     /* complete lines received (diagnostics) */
    uint32_t tail_t;         /* ms when tail[] got its first byte (a stalled prefix is replayed) */
    uint32_t pend_idx;       /* GCODE: stream index of that line */
    uint8_t tail[FRAME_MIN]; /* a possible late 6-byte host frame, checked before it is dropped */
    uint8_t ring[PROTO_RING];
    char line[CP_LINE_MAX];  /* the line being assembled */
    uint8_t rx[32];          /* bytes read from the HAL, not yet consumed */
    uint8_t tx[CP_TX_BUF];   /* bytes waiting for the HAL */
    char pend[PROTO_GCODE_MAX]; /* GCODE: the next stream line, built once */
    struct frame_rx frx;     /* FRAMES: decoder of the host's frames */
};

/* Initialise p (and an empty job). Returns CP_OK, or CP_ERR_INVAL if cfg or
 * cfg->uart (or one of its three calls) is NULL. Nothing is transmitted. */
CP_MUST_CHECK int proto_init(struct proto *p, const struct proto_cfg *cfg);

/* Do one bounded slice of work: flush pending output, consume received bytes (at
 * most sizeof rx per call), emit at most one stream item. Returns > 0 if anything
 * moved, 0 if idle (the caller may sleep: WFI, poll()), or CP_ERR_IO (sticky) once
 * the HAL reports that the link is gone. */
int proto_poll(struct proto *p);

#endif /* PROTO_H */
