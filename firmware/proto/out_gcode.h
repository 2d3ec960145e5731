/* out_gcode.h - the G-code output format: the run streamed as G-code lines to a machine
 * that paces them with grbl's character counting and answers each line.
 * SPDX-License-Identifier: MIT
 *
 * The stream (docs/PROTOCOL.md "RUN with FORMAT GCODE"): a "[RUN:...]" line for hosts
 * and judges (not counted, a machine skips '[' lines), then run->lead header lines -
 * with CHECKSUM ON "N0 M110 N0" and "N1 G21 G90 G17", else "G21 G90 G17" - then one
 * "G1 X.. Y.. Z.. [F..]" per point, 4 decimals (0.1 um), F with 1 decimal when FEED > 0.
 * With checksums every line is "N<i> <line>*<cs>", i the stream index, cs the XOR of
 * the bytes before '*', in decimal (Marlin).
 *
 * Flow control: the bytes of the lines not yet answered stay <= the job's RXBUF; every
 * "ok" frees the oldest line. "error:..." or "ALARM:..." stops the run with
 * CP_ST_PEER_ERROR (with checksums only ALARM: an error then precedes a Resend). With
 * checksums "Resend: n" / "rs n" for a line sent makes the module send nothing until the
 * machine has been quiet OUT_GCODE_RESYNC_MS, forget its accounting and regenerate from
 * line n; a Resend of a line never sent stops with CP_ST_PEER_ERROR. No answer within
 * OUT_GCODE_PEER_TIMEOUT_MS while lines are in flight: CP_ST_TIMEOUT. Lines are
 * regenerated from the path on a resend: no history buffer.
 */
#ifndef OUT_GCODE_H
#define OUT_GCODE_H

#include "job.h"
#include "out.h"

/* The machine must answer a line within this time, ms (else CP_ST_TIMEOUT). */
#ifndef OUT_GCODE_PEER_TIMEOUT_MS
#define OUT_GCODE_PEER_TIMEOUT_MS 10000u
#endif
/* With checksums, after "Resend: n" nothing is sent until the machine has been quiet
 * this long, ms; then the in-flight accounting is forgotten and line n is resent. (A
 * machine answers a corrupted or merged line unpredictably - Marlin flushes its RX
 * buffer - so counting its oks cannot be trusted across a resend.) */
#ifndef OUT_GCODE_RESYNC_MS
#define OUT_GCODE_RESYNC_MS 100u
#endif
/* The longest stream line, bytes: "N<n> G1 X.. Y.. Z.. F..*<cs>\n" stays under 80
 * (out_gcode.c). RXBUF may not be smaller: a line must fit an empty machine buffer. */
#define OUT_GCODE_LINE_MAX 96
#if OUT_GCODE_LINE_MAX > JOB_RXBUF_MIN
#error "a stream line must fit an empty machine RX buffer (JOB_RXBUF_MIN)"
#endif
/* Lines in flight are tracked in a ring of this many entries (1..255). */
#define OUT_GCODE_RING 64u

/* The state of a G-code run (valid from out_gcode_start to the end of the run). */
struct out_gcode {
    uint8_t ring[OUT_GCODE_RING];   /* lengths of the unacknowledged lines, oldest first */
    uint8_t ring_head, ring_n;      /* index of the oldest, count 0..OUT_GCODE_RING */
    uint16_t inflight;              /* bytes of the unacknowledged lines, <= RXBUF */
    uint8_t resync;                 /* 1 after a Resend: wait for a quiet line, then resend */
    uint8_t pend_len;               /* bytes in pend[], 0 = none */
    uint32_t pend_idx;              /* stream index of the line in pend[] */
    char pend[OUT_GCODE_LINE_MAX];  /* the next line, built once, waiting for RXBUF room */
};

/* The machine's answers, in the order they are recognised (out_gcode_answer_kind). */
enum out_gcode_answer {
    OUT_GCODE_OK = 0,     /* "ok", the whole line */
    OUT_GCODE_ERROR,      /* "error:..." (grbl) */
    OUT_GCODE_ALARM,      /* "ALARM:..." */
    OUT_GCODE_MARLIN_ERR, /* "Error:..." (Marlin) */
    OUT_GCODE_RS,         /* "rs n" */
    OUT_GCODE_RESEND,     /* "Resend: n" */
    OUT_GCODE_NOT_ANSWER  /* any other line */
};

/* Start a run of `path` for `job` (format GCODE): run->start_k is set, the path is
 * positioned there, run->next = 0. Sets the state, run->lead (1, or 2 with checksums)
 * and run->end (lead + points from start_k), and writes the "[RUN:points=..,first=..,
 * mode=LINES|CIRCLES,n=..,steps=..,link=..]\n" line to out[0..cap) (at most 85 bytes).
 * Returns the bytes written. */
size_t out_gcode_start(struct out_gcode *g, struct out_run *run, const struct job *job,
                       const struct path *path, uint8_t *out, size_t cap);

/* Emit at most one line: the next one if `sending` (the run is not held), it is below
 * run->end, fewer than OUT_GCODE_RING lines are in flight and the machine's RX buffer
 * (job->rxbuf) has room for it. now: ms. Appends the line to out[0..cap) (cap >=
 * OUT_GCODE_LINE_MAX) and stores its length in *len (0 when nothing was sent).
 * Returns OUT_GOING, or the status that ends the run: CP_ST_OK (every line answered),
 * CP_ST_TIMEOUT, CP_ST_NUMERIC (a point could not be computed). */
int out_gcode_emit(struct out_gcode *g, struct out_run *run, struct path *path,
                   const struct job *job, uint32_t now, int sending, uint8_t *out, size_t cap,
                   size_t *len);

/* Which machine answer the (trimmed) line[0..len) is; *arg = the offset after its
 * prefix. Used in every state: when idle such lines are swallowed without a reply. */
enum out_gcode_answer out_gcode_answer_kind(const char *line, size_t len, size_t *arg);

/* Take the machine's answer `kind` (arg[0..arg_len): the text after its prefix) during
 * a G-code run of `job`, received at now (ms). Returns OUT_GOING, or CP_ST_PEER_ERROR
 * when the run must stop. */
int out_gcode_answer(struct out_gcode *g, struct out_run *run, const struct job *job,
                     enum out_gcode_answer kind, const char *arg, size_t arg_len, uint32_t now);

#endif /* OUT_GCODE_H */
