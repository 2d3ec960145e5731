/* test_fault_sweep.c - exhaustive fault sweep of a short FRAMES session (nanopb
 * io_errors style): for EVERY byte index of the session, in both directions, drop,
 * flip or duplicate that byte, or hang the link up there. The session must either
 * deliver every point intact, in order, exactly once, or end with the injected
 * error (hang-up). Never a wrong, missing or duplicated point.
 * SPDX-License-Identifier: MIT
 */
#include <string.h>

#include "hal_mem.h"
#include "proto.h"
#include "test.h"

enum fault { F_NONE, F_DROP, F_FLIP, F_DUP, F_HANGUP };

struct sweep {
    struct hal_mem m;
    struct hal_uart u;
    struct proto p;
    struct frame_rx fr;
    uint32_t expect;     /* next frame index the host wants */
    uint32_t k;          /* points accepted */
    int32_t ref[16][3];  /* reference points, quantized */
    uint32_t npts;
    int end_ok, bad_point, ended_text;
};

static struct sweep sw;

static void host_frame(uint8_t type, uint32_t seq)
{
    uint8_t b[8];
    int n = frame_encode((uint8_t)seq, type, NULL, 0, b, sizeof b);
    if (sw.m.in_pos == sw.m.in_len) {
        sw.m.in_pos = sw.m.in_len = 0;
    }
    (void)hal_mem_feed(&sw.m, b, (size_t)n);
}

/* Host side: one byte from the firmware (after fault injection). */
static void host_byte(uint8_t c)
{
    uint32_t bad = sw.fr.bad;
    if (sw.end_ok) {
        if (c == '\n') {
            sw.ended_text = 1;
        }
        return;
    }
    if (frame_rx_feed(&sw.fr, c)) {
        const uint8_t *f = sw.fr.buf;
        if (f[1] != (uint8_t)sw.expect) {
            /* a gap (lost frame) or a duplicate: ask for what we need */
            host_frame(f[1] > (uint8_t)sw.expect ? FRAME_NAK : FRAME_ACK, sw.expect);
            return;
        }
        if (f[2] == FRAME_POINT) {
            uint32_t k = frame_get_u32(f + 3);
            if (k != sw.k || k >= sw.npts ||
                (int32_t)frame_get_u32(f + 7) != sw.ref[k][0] ||
                (int32_t)frame_get_u32(f + 11) != sw.ref[k][1] ||
                (int32_t)frame_get_u32(f + 15) != sw.ref[k][2]) {
                sw.bad_point = 1;
            }
            sw.k++;
        } else if (f[2] == FRAME_END) {
            if (f[3] == 0u) {
                sw.end_ok = 1;
            }
        }
        sw.expect++;
        host_frame(FRAME_ACK, sw.expect);
    } else if (sw.fr.bad != bad) {
        host_frame(FRAME_NAK, sw.expect); /* garbage: ask again (once per bad frame) */
    }
}

static const char *const job[] = {"CURVE LINE 0 0 20 5", "RADIUS LINEAR 3 5", "LINES 1 30 30",
                                  "STEPS 8", "FORMAT FRAMES", NULL};

/* Run one session with fault f at byte index at of direction dir (0: firmware ->
 * host, 1: host -> firmware). Returns 1 = all points intact, 2 = ended by the
 * injected hang-up, 0 = failure (wrong/missing/duplicated point or a hang). */
static int session(enum fault f, int dir, uint32_t at, uint32_t *bytes_out)
{
    struct proto_cfg cfg = {0};
    uint32_t out_idx = 0, in_idx = 0;
    size_t scan = 0;
    int i, r = 0;
    memset(&sw.m, 0, sizeof sw.m);
    hal_mem_init(&sw.m, &sw.u);
    sw.m.tick_ms = 1;
    cfg.uart = &sw.u;
    if (proto_init(&sw.p, &cfg) != CP_OK) {
        return 0;
    }
    for (i = 0; job[i] != NULL; i++) {
        (void)hal_mem_feed_str(&sw.m, job[i]);
        (void)hal_mem_feed_str(&sw.m, "\n");
    }
    (void)hal_mem_feed_str(&sw.m, "RUN\n");
    /* let the job commands through and drop their "ok" replies */
    for (i = 0; i < 200; i++) {
        (void)proto_poll(&sw.p);
    }
    {
        size_t k, oks = 0;
        for (k = 0; k < sw.m.out_len; k++) {
            if (sw.m.out[k] == '\n') {
                oks++;
                scan = k + 1;
                if (oks == 5u) {
                    break;
                }
            }
        }
    }
    frame_rx_init(&sw.fr);
    sw.expect = 0;
    sw.k = 0;
    sw.end_ok = 0;
    sw.bad_point = 0;
    sw.ended_text = 0;
    in_idx = 0;
    /* host -> firmware faults act on the ack bytes as they are fed */
    for (i = 0; i < 200000; i++) {
        size_t before_in = sw.m.in_len;
        int rc = proto_poll(&sw.p);
        if (rc < 0) {
            r = 2; /* the injected hang-up */
            break;
        }
        while (scan < sw.m.out_len) {
            uint8_t c = sw.m.out[scan++];
            if (dir == 0 && out_idx == at) {
                if (f == F_HANGUP) {
                    hal_mem_hangup(&sw.m);
                    out_idx++;
                    break;
                }
                if (f == F_DROP) {
                    out_idx++;
                    continue;
                }
                if (f == F_FLIP) {
                    c ^= 0x10u;
                }
                if (f == F_DUP) {
                    host_byte(c);
                }
            }
            out_idx++;
            host_byte(c);
        }
        if (dir == 1 && sw.m.in_len > before_in) {
            /* fault on one of the bytes just queued by the host */
            size_t k;
            for (k = before_in; k < sw.m.in_len; k++, in_idx++) {
                if (in_idx == at) {
                    if (f == F_HANGUP) {
                        hal_mem_hangup(&sw.m);
                    } else if (f == F_FLIP) {
                        sw.m.in[k] ^= 0x10u;
                    } else if (f == F_DROP) {
                        memmove(sw.m.in + k, sw.m.in + k + 1, sw.m.in_len - k - 1);
                        sw.m.in_len--;
                        k--;
                    } else if (f == F_DUP && sw.m.in_len < HAL_MEM_IN) {
                        memmove(sw.m.in + k + 1, sw.m.in + k, sw.m.in_len - k);
                        sw.m.in_len++;
                        k++;
                    }
                }
            }
        }
        /* complete: END received and the firmware back to idle (the trailing text
         * "ok" is a courtesy: a fault in it is not a data fault) */
        if (sw.end_ok && sw.p.state == PROTO_IDLE) {
            r = 1;
            break;
        }
        if (scan == sw.m.out_len) {
            scan = 0;
            sw.m.out_len = 0;
        }
    }
    *bytes_out = out_idx;
    if (sw.bad_point) {
        return 0;
    }
    if (r == 1 && (sw.k != sw.npts || !sw.end_ok)) {
        return 0;
    }
    return r;
}

int test_fault_sweep(void)
{
    static const enum fault kinds[4] = {F_DROP, F_FLIP, F_DUP, F_HANGUP};
    uint32_t total = 0, at, n, runs = 0, intact = 0, hung = 0;
    int dir, kf;
    /* the reference points: the same job through the iterator */
    {
        static struct canal_path tp;
        struct raster_pt pt;
        struct raster_cfg c;
        struct job j;
        int i;
        job_init(&j);
        for (i = 0; job[i] != NULL; i++) {
            CHECK_EQ_INT(job_command(&j, job[i], strlen(job[i])), CP_ST_OK);
        }
        c = j.cfg;
        CHECK_EQ_INT(canal_path_init(&tp, &j.canal, &c), CP_OK);
        sw.npts = canal_path_count(&tp);
        CHECK(sw.npts <= 16u);
        for (i = 0; canal_path_next(&tp, &pt) == CP_OK; i++) {
            sw.ref[i][0] = (int32_t)floor((double)(pt.p.x * CP_R(10000.0) + CP_R(0.5)));
            sw.ref[i][1] = (int32_t)floor((double)(pt.p.y * CP_R(10000.0) + CP_R(0.5)));
            sw.ref[i][2] = (int32_t)floor((double)(pt.p.z * CP_R(10000.0) + CP_R(0.5)));
        }
    }
    /* clean session: measures its length and must be intact */
    CHECK_EQ_INT(session(F_NONE, 0, 0xFFFFFFFFu, &total), 1);
    CHECK(total > 200u);
    for (dir = 0; dir < 2; dir++) {
        uint32_t span = dir == 0 ? total : 40u; /* acks: 6 bytes each, sweep the first ones */
        for (kf = 0; kf < 4; kf++) {
            for (at = 0; at < span; at++) {
                int r = session(kinds[kf], dir, at, &n);
                runs++;
                if (r == 0 || (r == 2 && kinds[kf] != F_HANGUP) ||
                    (kinds[kf] == F_HANGUP && dir == 0 && r != 2)) {
                    printf("  fault %d dir %d at byte %u: result %d (points %u of %u)\n", kf, dir,
                           (unsigned)at, r, (unsigned)sw.k, (unsigned)sw.npts);
                    return __LINE__;
                }
                intact += r == 1;
                hung += r == 2;
            }
        }
    }
    TEST_NOTE("fault sweep: %u sessions over %u stream bytes: %u intact, %u ended by the "
              "injected hang-up, 0 wrong/missing/duplicated\n",
              (unsigned)runs, (unsigned)total, (unsigned)intact, (unsigned)hung);
    return 0;
}
