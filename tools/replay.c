/* replay.c - a transcript of the protocol engine for the differential check
 * (tools/stream_diff.sh): every line of stdin is sent to a fresh-per-process proto
 * over the in-memory HAL, and everything the firmware answers is printed, byte for
 * byte (non-printable bytes as \xNN). The host side is scripted and clocked:
 *   - a G-code stream line from the firmware (it starts with G, M or N) is answered
 *     "ok" at once, as a machine would;
 *   - the clock advances 10 ms only when the engine is idle, so timeouts, retries and
 *     their replies depend on the engine's own decisions, not on how often it reads
 *     the clock;
 *   - a line ends when the firmware's final reply ("ok" or "error:...") is out, or
 *     after REPLAY_POLLS polls.
 * FRAMES runs get no ACK: they end with the engine's own link-error status, which is
 * as deterministic as the rest. The same source is built against two trees; the two
 * transcripts must be identical.
 * SPDX-License-Identifier: MIT
 */
#include <stdio.h>
#include <string.h>

#include "hal_mem.h"
#include "proto.h"

#define REPLAY_POLLS 3000000L

static struct proto eng;
static struct hal_mem mem;
static struct hal_uart uart;

static size_t shown;     /* bytes of mem.out already printed */
static char cur[512];    /* the firmware line being collected */
static size_t cur_len;

static void put_byte(uint8_t c)
{
    if (c == '\n') {
        fputs("\\n\n", stdout);
    } else if (c < 32u || c > 126u || c == '\\') {
        printf("\\x%02X", c);
    } else {
        putchar(c);
    }
}

/* Print new output; answer stream lines; returns 1 when a final reply line was seen. */
static int drain(void)
{
    int final = 0;
    while (shown < mem.out_len) {
        uint8_t c = mem.out[shown++];
        put_byte(c);
        if (c == '\n' || c == '\r') {
            cur[cur_len] = '\0';
            if (cur_len > 0 && (cur[0] == 'G' || cur[0] == 'M' || cur[0] == 'N')) {
                (void)hal_mem_feed_str(&mem, "ok\n");
            } else if (strcmp(cur, "ok") == 0 || strncmp(cur, "error:", 6) == 0) {
                final = 1;
            }
            cur_len = 0;
        } else if (cur_len + 1 < sizeof cur) {
            cur[cur_len++] = (char)c;
        }
    }
    if (mem.out_len > HAL_MEM_OUT / 2 && shown == mem.out_len) {
        hal_mem_clear_out(&mem);
        shown = 0;
    }
    return final;
}

int main(void)
{
    struct proto_cfg cfg = {0};
    char line[1024];
    hal_mem_init(&mem, &uart);
    mem.tick_ms = 0;
    cfg.uart = &uart;
    if (proto_init(&eng, &cfg) != CP_OK) {
        puts("replay: proto_init failed");
        return 1;
    }
    while (fgets(line, sizeof line, stdin) != NULL) {
        long i;
        printf(">> %s", line);
        if (strchr(line, '\n') == NULL) {
            putchar('\n');
        }
        if (hal_mem_feed_str(&mem, line) != 0) {
            puts("replay: input does not fit");
            continue;
        }
        for (i = 0; i < REPLAY_POLLS; i++) {
            int r = proto_poll(&eng);
            if (drain()) {
                /* let the engine finish what it queued after the reply */
                int k;
                for (k = 0; k < 64; k++) {
                    (void)proto_poll(&eng);
                }
                (void)drain();
                break;
            }
            if (r == 0) {
                mem.now += 10u;
            } else if (r < 0) {
                printf("<< proto_poll %d\n", r);
                return 0;
            }
        }
        if (i == REPLAY_POLLS) {
            puts("<< (no final reply)");
        }
    }
    return 0;
}
