/* proto.h - the line protocol engine: commands in, replies out, over one hal_uart.
 * SPDX-License-Identifier: MIT
 *
 * grbl conventions: ASCII lines ending in '\n' or '\r' ("\r\n" counts once);
 * every line is answered "ok" or "error:<code> <text>" (codes: cp_status.def).
 * The firmware never transmits before the host has spoken (no boot banner):
 * bytes written to a pty or QEMU UART before the host attaches are lost.
 *
 * Commands in this version:
 *   $I | HELLO   -> "[VER:canalpath <fw> proto <n>]"
 *                   "[OPT:real=<float|double>,line=<CP_LINE_MAX>,tx=<CP_TX_BUF>,
 *                          steps=<CP_MAX_STEPS>,sub=<CP_MAX_SUBSTEPS>,lines=<CP_MAX_LINES>,
 *                          link=<CP_MAX_LINK>]"  then "ok"
 *   (empty line) -> "ok" (sync, as grbl)
 *   anything else -> error:1 unknown command
 * Errors: a line longer than CP_LINE_MAX-1 bytes -> error:2 (after its newline);
 *         a byte outside 0x20..0x7E (other than CR/LF) -> error:8 for that line.
 */
#ifndef PROTO_H
#define PROTO_H

#include "cp_types.h"
#include "cp_status.h"
#include "hal_uart.h"

/* Worst-case length of one reply burst (the $I answer), bytes. */
#define PROTO_REPLY_MAX 160

#if CP_TX_BUF < PROTO_REPLY_MAX
#error "CP_TX_BUF must hold one reply burst (PROTO_REPLY_MAX)"
#endif

struct proto_cfg {
    const struct hal_uart *uart; /* the serial port; must stay valid while in use */
};

struct proto {
    const struct hal_uart *uart;
    char line[CP_LINE_MAX];   /* the line being assembled */
    uint16_t line_len;        /* bytes in line[] */
    uint8_t line_flags;       /* PROTO_LF_* of the current line */
    uint8_t last_cr;          /* previous byte was '\r' (so a following '\n' is skipped) */
    uint8_t rx[32];           /* bytes read from the HAL, not yet consumed */
    uint8_t rx_len, rx_pos;   /* valid bytes in rx[], next to consume */
    uint8_t tx[CP_TX_BUF];    /* replies waiting for the HAL */
    uint16_t tx_len, tx_pos;  /* bytes in tx[], next to send */
    uint32_t lines_seen;      /* complete lines received (diagnostics) */
    int err;                  /* sticky fatal error (CP_ERR_IO after hang-up), else 0 */
};

/* Initialise p. Returns CP_OK, or CP_ERR_INVAL if cfg or cfg->uart (or one of
 * its three calls) is NULL. Nothing is transmitted. */
CP_MUST_CHECK int proto_init(struct proto *p, const struct proto_cfg *cfg);

/* Do one bounded slice of work: flush pending replies, then consume received
 * bytes (at most sizeof rx per call) while a full reply burst fits in tx.
 * Returns > 0 if any byte moved, 0 if idle (the caller may sleep: WFI, poll()),
 * or CP_ERR_IO (sticky) once the HAL reports that the link is gone. */
int proto_poll(struct proto *p);

#endif /* PROTO_H */
