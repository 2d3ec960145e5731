/* sim_link.h - bounded line I/O with the firmware over the pty master.
 * SPDX-License-Identifier: MIT
 *
 * Every call takes an absolute deadline (sim_link_now_ms() clock) and returns by
 * then, whatever the firmware does: it never waits without a bound, it notices a
 * dead firmware (EOF/EIO on the master, or the child exited per waitpid WNOHANG),
 * and a SIGINT/SIGTERM of host_sim (the *stop flag) within SIM_LINK_SLICE_MS.
 *
 * Replies (firmware -> host) are ASCII lines ending in '\n' ("\r\n" accepted):
 *   "ok"                   terminal reply, success
 *   "error:<code> <text>"  terminal reply, failure; <text> must be the text of
 *                          <code> in firmware/base/cp_status.def
 *   "[...]"                info line ([VER:...], [OPT:...], ...)
 *   anything else          passed to the caller's line handler (a RUN stream line)
 *                          if one is given and it accepts it, else "unknown"
 * Flood limits per reply: SIM_LINK_LINE_MAX bytes in one line, and
 * sim_link.max_lines lines / sim_link.max_bytes bytes without a terminal reply.
 */
#ifndef SIM_LINK_H
#define SIM_LINK_H

#include <signal.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "sim_pty.h"

#define SIM_LINK_LINE_MAX 1024 /* longest accepted reply line, bytes */
#define SIM_LINK_SLICE_MS 20   /* longest single poll(2) sleep, ms */

enum sim_link_rc {
    SIM_LINK_LINE = 1,     /* a line is in link->line (read_line only) */
    SIM_LINK_REPLY = 0,    /* a terminal reply arrived (await only) */
    SIM_LINK_TIMEOUT = -1, /* deadline passed */
    SIM_LINK_EOF = -2,     /* master EOF/EIO: the firmware closed the line or died */
    SIM_LINK_EXITED = -3,  /* the firmware process exited */
    SIM_LINK_LONG = -4,    /* a reply line longer than SIM_LINK_LINE_MAX */
    SIM_LINK_FLOOD = -5,   /* too many lines/bytes without a terminal reply */
    SIM_LINK_INTR = -6,    /* host_sim was asked to stop */
    SIM_LINK_IOERR = -7    /* another I/O error */
};

/* Accepts a non-info, non-terminal line (e.g. one streamed point). Returns 1 if
 * the line is valid for the current command, 0 if it is unknown. */
typedef int (*sim_link_line_fn)(void *ctx, const char *line, size_t len);

struct sim_reply {
    int error;              /* 0: "ok"; 1: "error:<code>" */
    int code;               /* the error code */
    int text_ok;            /* 1 if the error text matches cp_status.def */
    unsigned info;          /* info lines before the terminal reply */
    unsigned streamed;      /* lines accepted by the handler */
    unsigned unknown;       /* unknown lines (each one is a failed check) */
    char first_unknown[80]; /* the first of them, escaped */
    char ver[128];          /* the last [VER:...] line, if any */
    char opt[256];          /* the last [OPT:...] line, if any */
};

struct sim_link {
    struct sim_pty *pty;
    volatile sig_atomic_t *stop; /* non-zero: return SIM_LINK_INTR */
    FILE *log;                   /* transcript, or NULL */
    uint64_t t0;                 /* origin of the transcript times */
    unsigned max_lines;          /* non-terminal lines per reply (flood limit) */
    unsigned long max_bytes;     /* bytes per reply without a terminal (flood limit) */
    /* called on every wait (then each wait is at most 1 ms): host_sim's cell pumps its
     * machine link there, so passed-through lines get their machine's answers; NULL: none */
    void (*idle)(void *ctx);
    void *idle_ctx;
    /* receive state */
    unsigned char buf[4096];
    size_t len;                  /* bytes in buf */
    char line[SIM_LINK_LINE_MAX + 1];
    size_t line_len;
    /* counters */
    unsigned long long bytes_in, bytes_out;
    unsigned long lines_in;
};

/* Monotonic milliseconds (CLOCK_MONOTONIC). */
uint64_t sim_link_now_ms(void);
/* Monotonic microseconds. */
uint64_t sim_link_now_us(void);

void sim_link_init(struct sim_link *l, struct sim_pty *pty, volatile sig_atomic_t *stop,
                   FILE *log);

/* Send n bytes (the caller includes the '\n'). Returns SIM_LINK_REPLY (0) once all
 * were written, or a negative enum sim_link_rc. */
int sim_link_send(struct sim_link *l, const char *s, size_t n, uint64_t deadline_ms);

/* Read one line into l->line (NUL-terminated, without "\r\n"). Returns SIM_LINK_LINE
 * or a negative enum sim_link_rc. */
int sim_link_read_line(struct sim_link *l, uint64_t deadline_ms);

/* Read lines until a terminal reply; fills r. fn may be NULL. Returns SIM_LINK_REPLY
 * or a negative enum sim_link_rc (r then holds what arrived before). */
int sim_link_await(struct sim_link *l, uint64_t deadline_ms, struct sim_reply *r,
                   sim_link_line_fn fn, void *ctx);

/* Text of wire status `code` from firmware/base/cp_status.def, or NULL if unknown. */
const char *sim_link_status_text(int code);

/* 1 if the reply text s[0..n) is want, alone or followed by the firmware's cause
 * " (<keyword> <token>: <limit>)" (docs/PROTOCOL.md "Lines"), else 0. */
int sim_link_text_is(const char *s, size_t n, const char *want);

/* Text of an enum sim_link_rc. */
const char *sim_link_strerror(int rc);

/* Copy a line into out with non-printable bytes as \xNN (truncated to cap). */
void sim_link_escape(const char *s, size_t n, char *out, size_t cap);

/* Write a transcript line "<ms> <dir> <text>" if logging. */
void sim_link_log(struct sim_link *l, const char *dir, const char *s, size_t n);

#endif /* SIM_LINK_H */
