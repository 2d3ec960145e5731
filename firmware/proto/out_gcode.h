/* out_gcode.h - the G-code output format: one complete program per RUN, written for the
 * job's machine dialect (MACHINE, firmware/job/machines.def), paced by the machine's
 * answers with grbl's character counting.
 * SPDX-License-Identifier: MIT
 *
 * The program (docs/PROTOCOL.md "The program"), stream items numbered from 0:
 *   lead lines   [M110 N0 (checksums)] the modes "G21 G90 G17 G94 G54" (SPLIT dialects,
 *                Marlin: "G21", "G90" and, if WCS was given, "G5x", one per line),
 *                "G0 Z<safe>", [M3 S<rpm> (SPINDLE)], "G0 X<x> Y<y>" above the first point
 *   points       "G1 X.. Y.. Z.. F<plunge>" (the plunge to the first point), then one
 *                "G1 X.. Y.. Z.." per point; F only where the feed changes (the cut's after
 *                the plunge, the link feed on link points and back), 4 decimals (0.1 um),
 *                F exactly as given (fmt_real); with TOOLAXIS " A.. C.." (3 decimals,
 *                degrees) or " I.. J.. K.." (4 decimals) after Z (toolaxis.h)
 *   trail lines  "G0 Z<safe>" (retract), [M5 (SPINDLE)], the dialect's end (M2 | M400)
 * With checksums every line is "N<i> <line>*<cs>", i the stream index, cs the XOR of the
 * bytes before '*', in decimal (Marlin). The "[RUN:...]" line is for the host: it goes up
 * the host link only (out_gcode_start), never into the program.
 *
 * Flow control (dialects with ACKS): the bytes of the lines not yet answered stay <= the
 * RX buffer (RXBUF, else the dialect's); every "ok" frees the oldest line. An ERROR or
 * ALARM (grbl error:/ALARM:, Marlin Error: other than a line-number one, "!!") stops the run with
 * CP_ST_PEER_ERROR, a RESET (the machine's banner) with CP_ST_MACHINE_RESET. With
 * checksums "Resend: n" / "rs n" for a line sent makes the module send nothing until the
 * machine has been quiet OUT_GCODE_RESYNC_MS, forget its accounting and regenerate from
 * line n; a Resend of a line never sent stops with CP_ST_PEER_ERROR. No answer within
 * OUT_GCODE_PEER_TIMEOUT_MS while lines are in flight: CP_ST_TIMEOUT (ALIVE answers - Marlin's
 * busy, grbl's status report to the dialect's POLL byte - restart that clock). A dialect
 * without ACKS (LINUXCNC: a program file) is paced by the link alone. Lines are
 * regenerated from the path on a resend: no history buffer.
 */
#ifndef OUT_GCODE_H
#define OUT_GCODE_H

#include "job.h"
#include "machine.h"
#include "out.h"
#include "toolaxis.h"

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
/* With ACKS, after this long without an answer the dialect's POLL byte (grbl '?') asks
 * the machine for a status report, ms. */
#ifndef OUT_GCODE_POLL_MS
#define OUT_GCODE_POLL_MS 2000u
#endif
/* The longest stream line, bytes: "N<n> G1 X.. Y.. Z.. I.. J.. K.. F..*<cs>\n" (out_gcode.c:
 * the formal worst case; real lines are 30-60). RXBUF may not be smaller: a line must
 * fit an empty machine RX buffer. */
#define OUT_GCODE_LINE_MAX 120
/* Lines before the points and after them (enum out_gcode_item), at most. */
#define OUT_GCODE_LEAD_MAX 8u
#define OUT_GCODE_TRAIL_MAX 3u
#if OUT_GCODE_LINE_MAX > JOB_RXBUF_MIN
#error "a stream line must fit an empty machine RX buffer (JOB_RXBUF_MIN)"
#endif
/* Lines in flight are tracked in a ring of this many entries (1..255). */
#define OUT_GCODE_RING 64u

/* The program's lines other than the points. */
enum out_gcode_item {
    OUT_GCODE_M110,        /* "M110 N0": number this run's lines from N1 (checksums) */
    OUT_GCODE_MODES,       /* "G21 G90 G17 G94 G5x" */
    OUT_GCODE_G21,         /* SPLIT dialects: "G21" */
    OUT_GCODE_G90,         /*                 "G90" */
    OUT_GCODE_WCS,         /*                 "G5x" */
    OUT_GCODE_SAFE,        /* "G0 Z<safe>" (before the cut and the retract after it) */
    OUT_GCODE_SPINDLE_ON,  /* "M3 S<rpm>" (at the safe height) */
    OUT_GCODE_ABOVE,       /* "G0 X<x> Y<y>": above the first point */
    OUT_GCODE_SPINDLE_OFF, /* "M5" */
    OUT_GCODE_END          /* the dialect's program end */
};

/* The state of a G-code run (valid from out_gcode_start to the end of the run). */
struct out_gcode {
    uint8_t lead[OUT_GCODE_LEAD_MAX];   /* enum out_gcode_item: the lines before the points */
    uint8_t trail[OUT_GCODE_TRAIL_MAX]; /* and after them */
    uint8_t ntrail;                 /* lines in trail[] (the lead's count is run->lead) */
    uint8_t machine;                /* enum job_machine of the run */
    uint16_t rxbuf;                 /* the machine's RX buffer, bytes; 0: no acknowledgements */
    uint32_t points;                /* points of the run (from start_k) */
    uint8_t ring[OUT_GCODE_RING];   /* lengths of the unacknowledged lines, oldest first */
    uint8_t ring_head, ring_n;      /* index of the oldest, count 0..OUT_GCODE_RING */
    uint16_t inflight;              /* bytes of the unacknowledged lines, <= RXBUF */
    uint8_t resync;                 /* 1 after a Resend: wait for a quiet line, then resend */
    uint8_t pend_len;               /* bytes in pend[], 0 = none */
    uint32_t pend_idx;              /* stream index of the line in pend[] */
    char pend[OUT_GCODE_LINE_MAX];  /* the next line, built once, waiting for RXBUF room */
    uint32_t t_poll;                /* ms of the last POLL byte (or of the first line in flight) */
    /* TOOLAXIS: the angles, and the last point written (its neighbour gives the travel) */
    struct toolaxis axis;
    uint8_t prev_ok;                /* prev_p is point prev_k (placed) */
    uint8_t above_safe;             /* the run stopped at a point at or above SAFE */
    uint32_t prev_k;
    struct cp_vec3 prev_p;
};

/* Whether `job` can be written as a program (called by RUN before anything else):
 * CP_ST_OK, CP_ST_NO_FEED (FEED not set), CP_ST_NO_SAFE (SAFE not given), CP_ST_DIALECT
 * (CHECKSUM ON or a TOOLAXIS form the dialect does not take, machines.def). */
int out_gcode_check(const struct job *job);

/* Start a run of `path` for `job` (format GCODE, out_gcode_check passed): run->start_k is
 * set, the path is positioned there, run->next = 0. Sets the state, run->lead (the lines
 * before the points) and run->end (lead + points from start_k + trail), and writes the
 * "[RUN:points=..,first=..,mode=LINES|CIRCLES,n=..,steps=..,link=..]\n" line for the host
 * to out[0..cap) (at most 85 bytes). Returns the bytes written. */
size_t out_gcode_start(struct out_gcode *g, struct out_run *run, const struct job *job,
                       const struct path *path, uint8_t *out, size_t cap);

/* Emit at most one line: the next one if `sending` (the run is not held), it is below
 * run->end, fewer than OUT_GCODE_RING lines are in flight and the machine's RX buffer
 * has room for it. now: ms. Appends the line to out[0..cap) when it fits there (else it
 * waits in pend[] for a later call) and stores its length in *len (0: nothing sent).
 * Returns OUT_GOING, or the status that ends the run: CP_ST_OK (every line answered),
 * CP_ST_TIMEOUT, CP_ST_NUMERIC (a point could not be computed), CP_ST_ABOVE_SAFE (a point
 * at or above SAFE: the program's rapids there would cross the part; the line is not
 * sent). */
int out_gcode_emit(struct out_gcode *g, struct out_run *run, struct path *path,
                   const struct job *job, uint32_t now, int sending, uint8_t *out, size_t cap,
                   size_t *len);

/* Take the machine's answer `kind` (machine_reply; num: its number) during a G-code run
 * of `job`, received at now (ms). Returns OUT_GOING, or the status that ends the run:
 * CP_ST_PEER_ERROR (an ERROR or ALARM, or a Resend the run cannot honour), CP_ST_MACHINE_RESET. */
int out_gcode_answer(struct out_gcode *g, struct out_run *run, const struct job *job,
                     enum machine_reply kind, uint32_t num, uint32_t now);

/* 1 when the run waits for the machine's answer and has heard nothing for
 * OUT_GCODE_POLL_MS since the last poll or answer (the caller then sends the dialect's
 * POLL byte and calls again: the clock of the poll restarts). */
int out_gcode_poll_due(struct out_gcode *g, const struct out_run *run, uint32_t now);

#endif /* OUT_GCODE_H */
