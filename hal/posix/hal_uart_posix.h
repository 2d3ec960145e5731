/* hal_uart_posix.h - struct hal_uart over POSIX file descriptors (native firmware).
 * SPDX-License-Identifier: MIT
 *
 * The port of the native firmware build (build/host/fw_native): the serial line
 * is a file descriptor, normally the slave side of a pseudo-tty that host_sim
 * created (or fd 0 for both directions). Compile with _XOPEN_SOURCE=700; this
 * directory is the only part of the firmware build that uses POSIX.
 *
 * Behaviour of the three hal_uart calls (hal_uart.h):
 *   read   non-blocking read(2): bytes read (>= 0); EAGAIN/EINTR -> 0; end of file
 *          (read returns 0 on a non-tty, or 0 with POLLHUP on a tty), EIO, or any
 *          other error -> CP_ERR_IO, sticky.
 *   write  non-blocking write(2): bytes accepted (a short write is normal);
 *          EAGAIN/EINTR -> 0; EPIPE, EIO or any other error -> CP_ERR_IO, sticky.
 *          SIGPIPE must be ignored by the program (main_posix.c does).
 *   now_ms CLOCK_MONOTONIC in milliseconds, truncated to 32 bits (wraps after
 *          49.7 days; compare with (uint32_t)(a - b)).
 */
#ifndef HAL_UART_POSIX_H
#define HAL_UART_POSIX_H

#include "hal_uart.h"

struct hal_uart_posix {
    int rfd, wfd;          /* descriptors read from / written to (may be equal) */
    int rfl, wfl;          /* fcntl F_GETFL flags before init, restored by _close */
    int hup;               /* 1 once the link is gone (every call then fails) */
    int tx_short;          /* 1 if the last write accepted fewer bytes than offered */
    uint32_t bytes_in;     /* bytes read, total (wraps) */
    uint32_t bytes_out;    /* bytes written, total (wraps) */
};

/* Wire u to p over rfd (read) and wfd (write), which may be the same descriptor.
 * Sets O_NONBLOCK on both. Returns CP_OK, CP_ERR_INVAL (NULL or negative fd), or
 * CP_ERR_IO if fcntl fails. */
int hal_uart_posix_init(struct hal_uart_posix *p, struct hal_uart *u, int rfd, int wfd);

/* Put a terminal descriptor in raw mode (no echo, no line editing, no CR/LF
 * translation, 8 bits, VMIN=1 VTIME=0). Returns CP_OK (also for a non-tty,
 * which is left unchanged) or CP_ERR_IO. */
int hal_uart_posix_raw(int fd);

/* Sleep until a link is likely to make progress, at most timeout_ms (0..60000): for p
 * and for q (a second port, the machine link; NULL or hung up: none) the write side
 * becomes writable if its last write was short (the engine cannot consume input before
 * its output drains), else the read side becomes readable or hangs up. Returns 1 if a
 * descriptor is ready, 0 on timeout or signal, CP_ERR_IO if poll(2) fails. Never
 * busy-waits. */
int hal_uart_posix_wait(struct hal_uart_posix *p, struct hal_uart_posix *q, int timeout_ms);

/* Restore the descriptors' original file status flags (does not close them). */
void hal_uart_posix_close(struct hal_uart_posix *p);

#endif /* HAL_UART_POSIX_H */
