/* machine.h - the machine on the other end of the G-code program: its dialect
 * (firmware/job/machines.def), its answers, and the machine link (a second hal_uart).
 * SPDX-License-Identifier: MIT
 *
 * A cell is wired with two links (docs/PROTOCOL.md "Two links"): the host link carries
 * jobs, replies, run metadata and progress; the machine link carries exactly the program
 * the machine accepts, and its answers. With LINK MACHINE the program goes down the
 * machine link; with LINK HOST (the default, and the only choice on a port without a
 * machine link) it goes up the host link to a host that takes the G-code itself.
 *
 * The machine's answers are parsed by dialect (machine_reply): nothing in them is a
 * real-time byte (a '?' in "echo:Unknown command: "M999?"" is text), lines that are not
 * answers are chatter, relayed to the host as "[MACHINE:<line>]" and never acted on.
 */
#ifndef MACHINE_H
#define MACHINE_H

#include "cp_types.h"
#include "hal_uart.h"
#include "job.h"
#include "link.h"

/* One row of machines.def (the columns are documented there). */
struct machine_dialect {
    uint16_t rxbuf;   /* RX buffer for character counting, bytes (0: no acknowledgements) */
    uint16_t line_max; /* longest line it takes, bytes before '\n' */
    uint8_t acks;     /* 1: one answer per non-empty line */
    uint8_t checksum; /* 1: CHECKSUM ON allowed */
    uint8_t split;    /* 1: one command per line */
    uint8_t poll;     /* real-time status request byte, 0 = none */
    const char *end;  /* the program end line ("M2", "M400") */
    uint8_t ac;       /* 1: takes TOOLAXIS AC's A and C words */
    uint8_t ijk;      /* 1: takes TOOLAXIS IJK's I J K words */
};

/* The row of dialect m (enum job_machine); GENERIC's for an m out of range. */
const struct machine_dialect *machine_dialect(unsigned m);

/* What one line from the machine is (machine_reply). */
enum machine_reply {
    MACHINE_OK = 0,  /* "ok" (Marlin: "ok" followed by " N.. P.. B.." or " T:..."): the
                        oldest line in flight is done */
    MACHINE_ALIVE,   /* not an answer, but proof of life: Marlin "echo:busy: processing",
                        "busy:", grbl's status report "<...>" */
    MACHINE_ERROR,   /* the machine refused a line: grbl "error:N", Marlin "Error:..." (not
                        a line-number one: kill(), MINTEMP, ...) - the answer to that line */
    MACHINE_ALARM,   /* the machine stopped: grbl "ALARM:N", Marlin "!!" (not an answer) */
    MACHINE_RETRY,   /* Marlin's "Error:... Last Line: n": a Resend follows (checksums) */
    MACHINE_RESEND,  /* "Resend: n", "rs n": *num = n */
    MACHINE_RESET,   /* the machine restarted: grbl's "Grbl 1.1h [...]" banner, Marlin's
                        "start": its planner and modes are gone */
    MACHINE_OTHER    /* chatter: "[MSG:...]", "echo:...", "//action:...", "wait", ... */
};

/* Classify the (trimmed, printable) line[0..len) from a machine of dialect m. *num is
 * the number of a RESEND (UINT32_MAX when none parses), else 0. Every dialect
 * recognises every form above (a GENERIC machine may be either kind); the dialect
 * decides only what grbl and Marlin disagree on: "ok" alone (grbl) or with Marlin's
 * suffixes. Total over any input; never reads line[len]. */
enum machine_reply machine_reply(unsigned m, const char *line, size_t len, uint32_t *num);

/* The machine link: its received bytes, the line being assembled, the bytes to send. */
#define MACHINE_RX_CHUNK 32u
#define MACHINE_LINE_MAX CP_LINE_MAX /* a longer machine line is cut (the rest dropped) */
#define MACHINE_TX_BUF 128u          /* >= one program line (OUT_GCODE_LINE_MAX) */

struct machine_link {
    const struct hal_uart *uart; /* NULL: the port has no machine link */
    uint8_t rx[MACHINE_RX_CHUNK];
    uint8_t rx_len, rx_pos;
    uint8_t last_cr;             /* previous byte was '\r' */
    uint8_t cut;                 /* the line in line[] was longer than MACHINE_LINE_MAX - 1 */
    uint8_t done;                /* line[] holds a complete line (returned last call) */
    uint16_t line_len;
    char line[MACHINE_LINE_MAX];
    uint16_t tx_len, tx_pos;
    uint8_t tx[MACHINE_TX_BUF];
};

/* Start the link on uart (NULL: no machine link). */
void machine_link_init(struct machine_link *l, const struct hal_uart *uart);

/* Send what is pending (non-blocking). Returns > 0 if bytes moved, 0 if not, CP_ERR_IO
 * when the link is gone. */
int machine_link_flush(struct machine_link *l);

/* Free bytes in the send buffer. */
size_t machine_link_room(struct machine_link *l);

/* Append s[0..n) to the send buffer (the caller checked machine_link_room). */
void machine_link_put(struct machine_link *l, const char *s, size_t n);

/* Take received bytes until a line is complete: 1 with the line (trimmed, bytes outside
 * 0x20..0x7E dropped; valid until the next call) in line[0..line_len), 0 when no complete line is there yet,
 * CP_ERR_IO when the link is gone. Reads at most MACHINE_RX_CHUNK bytes from the HAL per
 * call. */
int machine_link_line(struct machine_link *l);

#endif /* MACHINE_H */
