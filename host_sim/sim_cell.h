/* sim_cell.h - the machine on the firmware's machine link: a second pty that host_sim
 * creates, with an emulated grbl 1.1h or Marlin 2.x (sim_machine.h) behind it.
 * SPDX-License-Identifier: MIT
 *
 * With --machine grbl|marlin host_sim plays a two-link cell (docs/HOST_SIM.md "Cells"):
 * the host on the firmware's host link (the first pty), the machine on its machine link
 * (this one). The firmware gets the second pty's path (fw_native --machine-tty PATH, or
 * QEMU's second -serial: UART1). Bytes the firmware writes are delivered to the emulator
 * paced like a UART (byte time T: d_i = max(a_i, d_(i-1)) + T); the emulator's replies are
 * written back as it produces them. The emulator lives as long as the session (one
 * machine, many programs, a firmware restart or two). Its moves become the run's points:
 * every feed move is one point (the program's plunge is the first), rapids are the
 * program's safe moves. The program lines are kept for --gcode (N and *cs removed).
 */
#ifndef SIM_CELL_H
#define SIM_CELL_H

#include <stddef.h>
#include <stdint.h>

#include "sim_machine.h"
#include "sim_pty.h"

#define SIM_CELL_LINE_MAX 256

struct sim_cell {
    struct sim_pty pty;      /* the machine link's pty (no process of its own) */
    struct sim_machine *m;   /* the emulated machine */
    enum sim_machine_kind kind;
    /* bytes read from the pty, waiting for their paced delivery */
    uint8_t *ib;
    double *ia;              /* arrival time of each, us */
    size_t ihead, ilen, icap;
    double dlast;            /* delivery time of the last byte, us */
    double t_last;           /* us of the last byte either way */
    unsigned long long bytes_in, bytes_out;
    size_t moves_seen;       /* moves already taken by sim_cell_next_move */
    uint8_t ob[4096];        /* the machine's replies the pty has not taken yet */
    size_t olen;
    char line[SIM_CELL_LINE_MAX]; /* the program line being split for --gcode */
    size_t line_len;
};

/* Create the pty and the machine. Returns 0, or -1 with a message in err. */
int sim_cell_open(struct sim_cell *c, const struct sim_machine_opts *o, char *err, size_t errcap);

/* The firmware has opened the slave (handshake answered): drop the parent's copy. */
void sim_cell_release(struct sim_cell *c);

/* A firmware restart: a fresh pty for the new firmware, the same machine. 0 or -1. */
int sim_cell_reopen(struct sim_cell *c, char *err, size_t errcap);

/* Close everything (idempotent). */
void sim_cell_close(struct sim_cell *c);

/* Move bytes at now_us: read the pty, deliver what is due (byte_us per byte; 0 = at
 * once), write the machine's replies. Returns 1 if anything moved, 0 if not, -1 when
 * the pty failed (the firmware closed it). */
int sim_cell_pump(struct sim_cell *c, double now_us, double byte_us);

/* The next undelivered byte's due time, us (a huge value when none). */
double sim_cell_next_due(const struct sim_cell *c, double byte_us);

/* The next move the machine accepted since the last call: 1 and *mv, or 0. */
int sim_cell_next_move(struct sim_cell *c, struct sim_machine_move *mv);

#endif /* SIM_CELL_H */
