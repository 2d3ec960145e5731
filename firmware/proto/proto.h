/* proto.h - the protocol engine: commands in, replies and the toolpath stream out,
 * over a host link and, where the port has one, a machine link (two hal_uarts). The full
 * wire description is docs/PROTOCOL.md.
 * SPDX-License-Identifier: MIT
 *
 * grbl conventions on the host link: ASCII lines ending in '\n' or '\r' ("\r\n" counts
 * once); every command line is answered "ok" or "error:<code> <text> (<cause>)"
 * (cp_status.def). The firmware never transmits before the host has spoken (no boot
 * banner): bytes written to a pty or QEMU UART before the host attaches are lost.
 *
 * Commands: $I | HELLO (version and limits), $J (the job), the job commands of job.h,
 * RUN, RESUME k. Real-time bytes on the host link (outside FRAMES runs; during a G-code
 * run on the host link only between lines, so that machine chatter cannot carry one):
 * '?' status report, '!' feed hold, '~' resume, 0x18 abort ('!', '~', 0x18 also go to a
 * grbl on the machine link, whose own real-time bytes they are).
 *
 * RUN validates the job and streams it. The validation (path_check_begin, then one
 * path_check_step per proto_poll: state PROTO_CHECK) runs in slices so that the link is
 * read between them: '?' answers "<Check|W:w|S:i/m>", 0x18 cancels it (error:20); only
 * real-time bytes at the head of the host's bytes are read meanwhile (the next lines wait
 * in order). Then the stream:
 *   GCODE   a complete program for the job's MACHINE dialect (out_gcode.h) down the
 *           LINK: the machine link (two links: "[RUN:...]" and the final reply go to
 *           the host, the program and nothing else to the machine) or the host link (a
 *           host that takes the G-code itself: "[RUN:...]", the program, then the reply,
 *           on one line). The firmware is the sender: it keeps the bytes of unanswered
 *           lines <= the machine's RX buffer (grbl character counting) and takes one
 *           answer per line, parsed by dialect (machine.h); an error or alarm from the
 *           machine stops the job: "error:19 machine reported an error (machine
 *           ALARM:9)". Then "ok" (or "error:N").
 *   FRAMES  binary frames (frame.h) on the host link: BEGIN, one POINT per point, END,
 *           with a window of OUT_FRAMES_WINDOW unacknowledged frames, go-back-N on NAK or
 *           timeout; the host answers with ACK/NAK/ABORT/HOLD/GO frames. Then the text
 *           line "ok" (or an END frame with the status and the text "error:N ...").
 * Points are regenerated from the toolpath iterator on every retransmission: no
 * history buffer, and a stream is byte-identical on every target.
 *
 * Pass-through (two links, idle): a host line that is not one of the firmware's commands
 * goes to the machine as it is ($H, $X, a jog, M3 S1000); the machine's lines come back up
 * as they are until its answer (ok, error:, Error:), and host bytes wait meanwhile (but
 * for real-time bytes: 0x18 cancels the wait with error:20); no answer within
 * PROTO_PASS_TIMEOUT_MS: error:22. Other machine lines reach the host as
 * "[MACHINE:<line>]" once the host has spoken. Pass-through needs LINK MACHINE.
 *
 * proto.c keeps the links, the line assembly, the commands, the real-time bytes and the
 * replies; each output format is its own module (out_gcode.h, out_frames.h; out.h has
 * what they share), called directly at one switch on the format per seam: start a run,
 * emit the next item, take what the peer sends, finish the run.
 */
#ifndef PROTO_H
#define PROTO_H

#include "cp_status.h"
#include "cp_types.h"
#include "hal_uart.h"
#include "job.h"
#include "machine.h"
#include "out.h"
#include "out_frames.h"
#include "out_gcode.h"

/* Worst-case length of one reply burst (the $I answer, or one stream item), bytes. */
#define PROTO_REPLY_MAX 160
/* Bytes read from the HAL at once (proto_poll consumes at most these per call). */
#define PROTO_RX_CHUNK 32u

#if CP_TX_BUF < PROTO_REPLY_MAX
#error "CP_TX_BUF must hold one reply burst (PROTO_REPLY_MAX)"
#endif
#if OUT_GCODE_LINE_MAX > PROTO_REPLY_MAX || FRAME_MAX > PROTO_REPLY_MAX
#error "a stream item must fit one reply burst"
#endif

/* IDLE; CHECK: RUN validates the job in slices (path_check_step), reading only real-time
 * bytes meanwhile; RUN, HOLD: the stream runs or holds. */
enum proto_state { PROTO_IDLE = 0, PROTO_RUN = 1, PROTO_HOLD = 2, PROTO_CHECK = 3 };

struct proto_cfg {
    const struct hal_uart *uart;    /* the host link; must stay valid while in use */
    const struct hal_uart *machine; /* the machine link (LINK MACHINE), NULL: the port has
                                       one link only */
};

/* A passed-through line must be answered within this time, ms (else error:22); status
 * reports to the POLL byte do not extend it (a grbl homing cycle is well within it). */
#ifndef PROTO_PASS_TIMEOUT_MS
#define PROTO_PASS_TIMEOUT_MS 60000u
#endif

/* Bytes of a machine's error or alarm line quoted in the host's reply. */
#define PROTO_FAULT_MAX 32u

/* The engine. No pointer into itself (a copy is a snapshot: tests/fuzz_run.c). */
struct proto {
    /* the link: received bytes, the command line being assembled, bytes to send */
    const struct hal_uart *uart;
    int err;                 /* sticky fatal error (CP_ERR_IO after hang-up), else 0 */
    uint32_t lines_seen;     /* complete lines received (diagnostics) */
    uint8_t rx[PROTO_RX_CHUNK]; /* bytes read from the HAL, not yet consumed */
    uint8_t rx_len, rx_pos;  /* valid bytes in rx[], next to consume */
    uint8_t last_cr;         /* previous byte was '\r' (so a following '\n' is skipped) */
    uint8_t line_flags;      /* PROTO_LF_* of the current line (proto.c) */
    uint16_t line_len;       /* bytes in line[] */
    char line[CP_LINE_MAX];  /* the line being assembled */
    uint16_t tx_len, tx_pos; /* bytes in tx[], next to send */
    uint8_t tx[CP_TX_BUF];   /* bytes waiting for the HAL */

    /* the job being assembled, and the validated toolpath of the current run */
    struct job job;
    struct path path;

    /* the run, whatever its format */
    uint8_t state;           /* enum proto_state */
    uint8_t fmt;             /* enum job_format of the current (or last) run */
    uint16_t dump;           /* $J: the next job_dump item + 1; 0 when not dumping (while
                                dumping no byte is consumed: the lines come out whole) */
    struct out_run run;      /* stream position, acknowledgements, peer clock */
    union {                  /* the state of the run's output format (fmt), set up by its
                              * start call, while state is PROTO_RUN or PROTO_HOLD; before,
                              * while PROTO_CHECK, the state of RUN's check */
#define CP_OUTPUT(NAME, name, WORD) struct out_##name name;
#include "outputs.def"
#undef CP_OUTPUT
        struct path_check check;
    } out;

    /* after a FRAMES run (outlives it): late host frames among the next text */
    struct out_frames_tail tail;

    /* the machine link: the program of a LINK MACHINE run and the machine's answers; while
     * idle, a host line that is not a command passes through to the machine */
    struct machine_link mach;
    uint8_t prog_link;       /* enum job_link of the current (or last) run */
    uint8_t pass;            /* 1: a passed-through host line waits for the machine's answer
                                (no host byte is consumed meanwhile) */
    uint8_t fault_len;       /* bytes in fault[] */
    char fault[PROTO_FAULT_MAX]; /* the machine's line that stopped the last run */
    uint32_t t_pass;         /* ms of the pass-through line, or of the machine's last line
                                other than a status report */
    uint32_t t_mpoll;        /* ms of the last POLL byte during a pass-through */
};

/* Initialise p (and an empty job). Returns CP_OK, or CP_ERR_INVAL if cfg or
 * cfg->uart (or one of its three calls) is NULL, or cfg->machine is given with a NULL
 * call. Nothing is transmitted. */
CP_MUST_CHECK int proto_init(struct proto *p, const struct proto_cfg *cfg);

/* Do one bounded slice of work: flush pending output, consume received bytes (at
 * most PROTO_RX_CHUNK per call), emit at most one stream item. Returns > 0 if anything
 * moved, 0 if idle (the caller may sleep: WFI, poll()), or CP_ERR_IO (sticky) once
 * the HAL reports that the link is gone. */
int proto_poll(struct proto *p);

#endif /* PROTO_H */
