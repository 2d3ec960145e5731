/* main_posix.c - firmware entry of the native build (build/host/fw_native).
 * SPDX-License-Identifier: MIT
 *
 * Usage: fw_native [--tty PATH | --pty LINK] [--machine-tty PATH | --machine-fd N]
 *   default      serve the protocol on fd 0 (read and write; the pty slave that
 *                host_sim dup2()s to 0 and 1). The terminal mode is left alone:
 *                host_sim puts the pty in raw mode from the master side.
 *   --tty PATH   open PATH (O_RDWR|O_NOCTTY), put it in raw mode, serve on it.
 *   --pty LINK   create a pseudo-terminal itself (Klipper's linux MCU style), make
 *                LINK a symlink to its slave (/dev/pts/N, also printed on stderr) and
 *                serve on the master: any serial client (pyserial, a sender) opens
 *                LINK. The slave is kept open, so clients may come and go; this mode
 *                ends only on a signal.
 *   --machine-tty PATH   the machine link (proto.h "two links"): open PATH, raw mode;
 *                a grbl, Marlin or LinuxCNC serial port, or a pty a simulator serves
 *   --machine-fd N       the machine link on an inherited descriptor N (read and
 *                write; host_sim passes its second pty's slave as fd 3)
 *                Without either, the port has one link (LINK MACHINE answers error:42).
 *
 * Owns the single protocol engine (file-scope state is allowed in hal/ only).
 * Loop: proto_poll() while it makes progress; when idle, sleep in poll(2) on the
 * descriptor for at most FW_IDLE_MS (no busy loop; the timeout keeps the engine's
 * millisecond clocks - GCODE peer timeout, FRAMES retransmission - ticking).
 * The firmware sends nothing until the host speaks (proto.h).
 * Exit status: 0 after the link hangs up (message on stderr; SIGHUP is ignored so a
 * hang-up of the controlling pty ends the loop the same way), 2 on a usage or
 * set-up error. stdout is never used for messages: it may be the serial line.
 */
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "hal_uart_posix.h"
#include "proto.h"

/* Longest sleep while idle, ms. Bounds the latency of a timer-driven event. */
#define FW_IDLE_MS 50

static struct hal_uart_posix port, mport;
static struct hal_uart uart, muart;
static struct proto proto;

static int usage(void)
{
    fprintf(stderr, "usage: fw_native [--tty PATH | --pty LINK] [--machine-tty PATH | "
                    "--machine-fd N]\n");
    return 2;
}

int main(int argc, char **argv)
{
    struct proto_cfg cfg = {0};
    const char *tty = NULL, *link = NULL, *mtty = NULL;
    int fd = 0, mfd = -1, i, r;

    for (i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--tty") == 0 && i + 1 < argc) {
            tty = argv[++i];
        } else if (strcmp(argv[i], "--pty") == 0 && i + 1 < argc) {
            link = argv[++i];
        } else if (strcmp(argv[i], "--machine-tty") == 0 && i + 1 < argc) {
            mtty = argv[++i];
        } else if (strcmp(argv[i], "--machine-fd") == 0 && i + 1 < argc) {
            char *end;
            long v = strtol(argv[++i], &end, 10);
            if (*end != '\0' || v < 0 || v > 1023) {
                return usage();
            }
            mfd = (int)v;
        } else {
            return usage();
        }
    }
    (void)signal(SIGPIPE, SIG_IGN); /* a closed peer is reported as EPIPE -> CP_ERR_IO */
    /* the pty may be our controlling terminal: its hang-up is seen as EOF/EIO by the
     * HAL (exit 0 with a message), not as a fatal SIGHUP */
    (void)signal(SIGHUP, SIG_IGN);
    if (link != NULL) {
        const char *slave;
        int keep;
        fd = posix_openpt(O_RDWR | O_NOCTTY);
        if (fd < 0 || grantpt(fd) != 0 || unlockpt(fd) != 0 || (slave = ptsname(fd)) == NULL) {
            perror("fw_native: posix_openpt");
            return 2;
        }
        keep = open(slave, O_RDWR | O_NOCTTY); /* held open: clients may come and go */
        if (keep < 0 || hal_uart_posix_raw(keep) != CP_OK || hal_uart_posix_raw(fd) != CP_OK) {
            perror(slave);
            return 2;
        }
        (void)unlink(link);
        if (symlink(slave, link) != 0) {
            perror(link);
            return 2;
        }
        fprintf(stderr, "fw_native: serving on %s (%s)\n", slave, link);
    } else if (tty != NULL) {
        fd = open(tty, O_RDWR | O_NOCTTY);
        if (fd < 0) {
            perror(tty);
            return 2;
        }
        if (hal_uart_posix_raw(fd) != CP_OK) {
            fprintf(stderr, "fw_native: cannot set raw mode on %s\n", tty);
            return 2;
        }
    }
    if (hal_uart_posix_init(&port, &uart, fd, fd) != CP_OK) {
        fprintf(stderr, "fw_native: cannot use fd %d\n", fd);
        return 2;
    }
    cfg.uart = &uart;
    if (mtty != NULL) {
        mfd = open(mtty, O_RDWR | O_NOCTTY);
        if (mfd < 0 || hal_uart_posix_raw(mfd) != CP_OK) {
            perror(mtty);
            return 2;
        }
    }
    if (mfd >= 0) {
        if (hal_uart_posix_init(&mport, &muart, mfd, mfd) != CP_OK) {
            fprintf(stderr, "fw_native: cannot use machine fd %d\n", mfd);
            return 2;
        }
        cfg.machine = &muart;
    }
    if (proto_init(&proto, &cfg) != CP_OK) {
        fprintf(stderr, "fw_native: proto_init failed\n");
        return 2;
    }
    for (;;) {
        r = proto_poll(&proto);
        if (r < 0) {
            break; /* CP_ERR_IO: the link is gone */
        }
        if (r == 0 && hal_uart_posix_wait(&port, mfd >= 0 ? &mport : NULL, FW_IDLE_MS) < 0) {
            break;
        }
    }
    hal_uart_posix_close(&port);
    fprintf(stderr, "fw_native: link hung up after %lu lines, %lu bytes in, %lu out; exiting\n",
            (unsigned long)proto.lines_seen, (unsigned long)port.bytes_in,
            (unsigned long)port.bytes_out);
    return 0;
}
