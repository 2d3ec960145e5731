/* fw_fake.c - misbehaving fake "firmwares" for host_sim's robustness tests.
 * SPDX-License-Identifier: MIT
 *
 * Usage: fw_fake MODE [--pidfile PATH]      (serial line = fds 0 and 1, blocking)
 *   --good          a minimal correct responder: $I/HELLO -> [VER:]/[OPT:]/ok,
 *                   empty line -> ok, a line over 95 bytes -> error:2 (CP_LINE_MAX 96), else error:1
 *   --die           exits at once with status 3 (firmware crash at boot)
 *   --silent        reads everything, never answers (hung firmware)
 *   --flood         writes pseudo-random garbage forever, never reads
 *   --longline      writes 'U' forever without a newline
 *   --slow [MS]     correct replies, one byte every MS ms (default 300)
 *   --chatty        correct, but every reply starts with an unknown line
 *   --wrong         answers "ok" to everything after the handshake
 *   --die-after N   correct for N lines, then exits with status 4
 *   --hang-after N  correct for N lines, then silent
 *   --stubborn      correct, but ignores SIGTERM/SIGHUP and does not exit on
 *                   hang-up (only SIGKILL ends it)
 *   --lossy-start   correct, but the first 5 bytes of its first answer are lost (as
 *                   seen from QEMU at connect on a loaded host): a host that asks $I
 *                   again gets a complete answer and must go on normally
 * It exits 0 on end of file (hang-up) except in --stubborn mode.
 * A POSIX test tool (built with _XOPEN_SOURCE=700), never part of the firmware.
 */
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#define FAKE_LINE_MAX 95 /* like CP_LINE_MAX 96 minus the terminator */

static unsigned slow_ms;
static unsigned lossy; /* --lossy-start: bytes of the first answer still to drop */

static void fake_sleep_ms(unsigned ms)
{
    struct timespec ts;
    ts.tv_sec = (time_t)(ms / 1000u);
    ts.tv_nsec = (long)(ms % 1000u) * 1000000L;
    while (nanosleep(&ts, &ts) != 0 && errno == EINTR) {
    }
}

/* Write all of s (blocking); exit 0 when the line is gone. */
static void fake_put(const char *s)
{
    size_t n = strlen(s), i;
    while (lossy > 0u && n > 0u) { /* --lossy-start: lost on the way */
        lossy--;
        s++;
        n--;
    }
    if (slow_ms == 0u) {
        while (n > 0) {
            ssize_t w = write(1, s, n);
            if (w <= 0) {
                if (w < 0 && errno == EINTR) {
                    continue;
                }
                exit(0);
            }
            s += w;
            n -= (size_t)w;
        }
        return;
    }
    for (i = 0; i < n; i++) {
        if (write(1, s + i, 1) != 1) {
            exit(0);
        }
        fake_sleep_ms(slow_ms);
    }
}

static void fake_answer(const char *line, size_t len, int overflow, int wrong)
{
    if (overflow) {
        fake_put("error:2 line too long\n");
    } else if ((len == 2 && memcmp(line, "$I", 2) == 0) || (len == 5 && memcmp(line, "HELLO", 5) == 0)) {
        fake_put("[VER:fw_fake 0.0 proto 1]\n[OPT:real=none,line=96]\nok\n");
    } else if (len == 0 || wrong) {
        fake_put("ok\n");
    } else {
        fake_put("error:1 unknown command\n");
    }
}

int main(int argc, char **argv)
{
    static char line[FAKE_LINE_MAX];
    const char *mode = argc > 1 ? argv[1] : "--good";
    long limit = -1;
    int i, chatty = 0, wrong = 0, die = 0, overflow = 0, handshaken = 0;
    size_t len = 0;
    unsigned seed = 12345u;

    for (i = 2; i < argc; i++) {
        if (strcmp(argv[i], "--pidfile") == 0 && i + 1 < argc) {
            FILE *f = fopen(argv[++i], "w");
            if (f != NULL) {
                fprintf(f, "%ld\n", (long)getpid());
                fclose(f);
            }
        } else if (argv[i][0] >= '0' && argv[i][0] <= '9') {
            limit = strtol(argv[i], NULL, 10);
        }
    }
    if (strcmp(mode, "--die") == 0) {
        return 3;
    }
    /* the pty is the controlling terminal: see its hang-up as EOF/EIO, not SIGHUP */
    (void)signal(SIGHUP, SIG_IGN);
    if (strcmp(mode, "--flood") == 0) {
        unsigned char buf[256];
        for (;;) {
            size_t k;
            for (k = 0; k < sizeof buf; k++) {
                seed = seed * 1103515245u + 12345u;
                buf[k] = (unsigned char)(seed >> 16);
            }
            if (write(1, buf, sizeof buf) < 0 && errno != EINTR) {
                return 0;
            }
        }
    }
    if (strcmp(mode, "--longline") == 0) {
        static const char u[64] = "UUUUUUUUUUUUUUUUUUUUUUUUUUUUUUUUUUUUUUUUUUUUUUUUUUUUUUUUUUUUUUU";
        for (;;) {
            if (write(1, u, sizeof u) < 0 && errno != EINTR) {
                return 0;
            }
        }
    }
    if (strcmp(mode, "--slow") == 0) {
        slow_ms = limit > 0 ? (unsigned)limit : 300u;
    } else if (strcmp(mode, "--chatty") == 0) {
        chatty = 1;
    } else if (strcmp(mode, "--wrong") == 0) {
        wrong = 1;
    } else if (strcmp(mode, "--die-after") == 0) {
        die = 1;
    } else if (strcmp(mode, "--stubborn") == 0) {
        (void)signal(SIGTERM, SIG_IGN);
    } else if (strcmp(mode, "--lossy-start") == 0) {
        lossy = 5u;
    } else if (strcmp(mode, "--silent") != 0 && strcmp(mode, "--good") != 0 &&
               strcmp(mode, "--hang-after") != 0) {
        fprintf(stderr, "fw_fake: unknown mode %s\n", mode);
        return 2;
    }
    for (;;) {
        char c;
        ssize_t n = read(0, &c, 1);
        if (n < 0 && errno == EINTR) {
            continue;
        }
        if (n <= 0) {
            break; /* hang-up */
        }
        if (strcmp(mode, "--silent") == 0) {
            continue;
        }
        if (c != '\n' && c != '\r') {
            if (len < sizeof line) {
                line[len++] = c;
            } else {
                overflow = 1;
            }
            continue;
        }
        if (limit == 0 && !slow_ms) {
            if (die) {
                return 4;
            }
            len = 0;
            overflow = 0;
            continue; /* --hang-after: silent from now on */
        }
        if (limit > 0 && !slow_ms) {
            limit--;
        }
        if (chatty) {
            fake_put("hello from the fake\n");
        }
        fake_answer(line, len, overflow, wrong && handshaken);
        handshaken = 1;
        len = 0;
        overflow = 0;
    }
    if (strcmp(mode, "--stubborn") == 0) {
        for (;;) {
            fake_sleep_ms(1000u);
        }
    }
    return 0;
}
