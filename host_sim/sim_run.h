/* sim_run.h - the RUN receiver of host_sim: a grbl/Marlin-like machine for GCODE
 * streams, a Klipper-style frame receiver for FRAMES streams, UART pacing, fault
 * injection on the firmware -> host byte stream (docs/HOST_SIM.md).
 * SPDX-License-Identifier: MIT
 *
 * sim_run_stream() is called right after "RUN\n" or "RESUME k\n" was written. It owns
 * the pty master until the terminal reply of that command has been delivered (or a
 * bound is hit), feeding the judge (sim_check.h) and the writers (sim_out.h).
 *
 * Pacing (--baud N, byte time T = 10/N s, 8N1): firmware byte i, read from the pty at
 * a_i, is delivered to the machine/decoder at d_i = max(a_i, d_(i-1)) + T (a UART
 * shifting the bytes out back to back). Host replies of n bytes are written when
 * their transmission ends: max(now, line free) + n T. T = 0: no pacing.
 */
#ifndef SIM_RUN_H
#define SIM_RUN_H

#include <stdint.h>

#include "sim_link.h"

struct sim_cell;

enum sim_fault { SIM_FAULT_NONE, SIM_FAULT_DROP, SIM_FAULT_FLIP, SIM_FAULT_DUP, SIM_FAULT_HANGUP };

struct sim_run_opts {
    int frames;               /* FORMAT FRAMES */
    int checksum;             /* CHECKSUM ON (GCODE) */
    unsigned rxbuf;           /* machine RX buffer (RXBUF), bytes */
    double byte_us;           /* T in microseconds; 0 = unpaced */
    int fault;                /* enum sim_fault */
    unsigned long fault_at;   /* byte of the run's stream (0-based, from the command) */
    unsigned timeout_ms;      /* silence bound */
    FILE *raw;                /* raw firmware -> host bytes of the run, or NULL */
    int progress;             /* progress line on stderr */
    struct sim_cell *cell;    /* two links: the machine on the machine link (sim_cell.h),
                                 whose feed moves are the points; NULL: one link */
};

struct sim_run_result {
    int rc;                   /* SIM_LINK_REPLY or a negative enum sim_link_rc */
    int hung;                 /* the hang-up fault was injected */
    int error, code, text_ok; /* terminal reply */
    int header;               /* [RUN:...] header / BEGIN frame seen */
    uint32_t points, first;   /* from the header */
    int mode;
    unsigned n, steps, link;
    uint32_t got;             /* points received intact, in order */
    unsigned long long bytes_in, bytes_out;
    double dur_us;            /* command written -> terminal reply delivered */
    double stream_us;         /* first byte delivered -> terminal reply delivered */
    double first_byte_us;     /* command written -> first byte delivered */
    double util, util_stream; /* wire utilization (paced runs) */
    unsigned long rx_overflow;/* GCODE: lines that broke character counting */
    unsigned long max_inbuf;  /* GCODE: most unanswered bytes seen */
    unsigned long resends;    /* GCODE: Resend: requests sent */
    unsigned long bad_lines;  /* GCODE: lines failing N/checksum or unparsable */
    unsigned long naks, bad_frames, dup_frames, gap_frames, acks; /* FRAMES */
    unsigned long order_err;  /* FRAMES: POINT k not the expected one */
    unsigned long host_program; /* two links: program lines that came up the host link */
    unsigned long end_points; /* FRAMES: END frame's count */
    int end_status;           /* FRAMES: END frame's status (-1: none) */
    char why[200];
};

/* Stream one run. Returns r->rc. */
int sim_run_stream(struct sim_link *l, const struct sim_run_opts *o, struct sim_run_result *r);

/* Write n bytes paced at byte_us per byte (command lines). Returns like sim_link_send. */
int sim_run_send(struct sim_link *l, const char *s, size_t n, double byte_us, uint64_t deadline_ms);

#endif /* SIM_RUN_H */
