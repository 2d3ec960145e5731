/* test_hal.c - the test ports (hal_mem, hal_fault) and the protocol engine over a
 * faulty link: every fault at every byte index of a short session.
 * SPDX-License-Identifier: MIT
 */
#include <string.h>

#include "hal_fault.h"
#include "hal_mem.h"
#include "proto.h"
#include "test.h"

/* Large state is static: the same tests run on the Cortex-M4F unit image. */
static struct hal_mem hm;
static struct hal_fault hf;
static struct proto pe;
static uint8_t ref_out[1024];
static size_t ref_len;
static uint8_t want[1024];

/* Run the engine until it is idle for a few polls or fails (bounded).
 * Returns the first negative proto_poll result, else 0. */
static int pump(struct proto *p)
{
    int idle = 0, i, r;
    for (i = 0; i < 100000 && idle < 4; i++) {
        r = proto_poll(p);
        if (r < 0) {
            return r;
        }
        idle = r > 0 ? 0 : idle + 1;
    }
    return 0;
}

int test_hal_mem(void)
{
    struct hal_uart u;
    uint8_t b[16];
    hal_mem_init(&hm, &u);
    CHECK_EQ_INT(hal_uart_read(&u, b, sizeof b), 0);
    CHECK_EQ_INT(hal_mem_feed_str(&hm, "abcdef"), 0);
    hm.read_chunk = 4;
    CHECK_EQ_INT(hal_uart_read(&u, b, sizeof b), 4);
    CHECK(memcmp(b, "abcd", 4) == 0);
    CHECK_EQ_INT(hal_uart_read(&u, b, 1), 1);
    CHECK_EQ_INT(b[0], 'e');
    CHECK_EQ_INT(hal_uart_read(&u, b, sizeof b), 1);
    CHECK_EQ_INT(hal_uart_read(&u, b, sizeof b), 0);
    /* the input buffer refuses what does not fit beside the unread bytes, whole */
    CHECK_EQ_INT(hal_mem_feed(&hm, b, HAL_MEM_IN + 1u), -1);
    CHECK_EQ_INT(hal_mem_feed_str(&hm, "gh"), 0);
    CHECK_EQ_INT(hal_mem_feed(&hm, b, HAL_MEM_IN - 1u), -1);
    hm.read_chunk = 0;
    CHECK_EQ_INT(hal_uart_read(&u, b, sizeof b), 2);
    CHECK(memcmp(b, "gh", 2) == 0);
    hm.write_chunk = 3;
    CHECK_EQ_INT(hal_uart_write(&u, (const uint8_t *)"hello", 5), 3);
    CHECK_EQ_INT(hal_uart_write(&u, (const uint8_t *)"lo", 2), 2);
    CHECK_EQ_INT(hm.out_len, 5);
    CHECK(memcmp(hm.out, "hello", 5) == 0);
    hal_mem_clear_out(&hm);
    CHECK_EQ_INT(hm.out_len, 0);
    /* a full output buffer accepts 0 bytes (back-pressure), not an error */
    hm.write_chunk = 0;
    hm.out_len = HAL_MEM_OUT - 2;
    CHECK_EQ_INT(hal_uart_write(&u, (const uint8_t *)"xyz", 3), 2);
    CHECK_EQ_INT(hal_uart_write(&u, (const uint8_t *)"xyz", 3), 0);
    hm.tick_ms = 5;
    CHECK_EQ_INT(hal_uart_now_ms(&u), 5);
    CHECK_EQ_INT(hal_uart_now_ms(&u), 10);
    hal_mem_hangup(&hm);
    CHECK_EQ_INT(hal_uart_read(&u, b, sizeof b), CP_ERR_IO);
    CHECK_EQ_INT(hal_uart_write(&u, b, 1), CP_ERR_IO);
    return 0;
}

/* Write "0123456789" through a fault, in calls of `chunk` bytes, retrying short
 * writes (bounded). Returns the first error, else 0. */
static int tx_session(struct hal_uart *u, size_t chunk)
{
    static const uint8_t msg[] = "0123456789";
    size_t pos = 0;
    int guard, r;
    for (guard = 0; guard < 100 && pos < 10u; guard++) {
        size_t n = 10u - pos < chunk ? 10u - pos : chunk;
        r = hal_uart_write(u, msg + pos, n);
        if (r < 0) {
            return r;
        }
        pos += (size_t)r;
    }
    /* flush an owed duplicate */
    (void)hal_uart_write(u, msg, 0);
    return 0;
}

int test_hal_fault_tx(void)
{
    struct hal_uart inner, u;
    size_t chunk;
    for (chunk = 1; chunk <= 10; chunk += 3) {
        hal_mem_init(&hm, &inner);
        hal_fault_init(&hf, &u, &inner);
        CHECK_EQ_INT(tx_session(&u, chunk), 0);
        CHECK(hm.out_len == 10 && memcmp(hm.out, "0123456789", 10) == 0);
        CHECK_EQ_INT(hf.faults, 0);

        hal_mem_init(&hm, &inner);
        hal_fault_init(&hf, &u, &inner);
        hal_fault_arm(&hf, HAL_FAULT_DROP, HAL_FAULT_TX, 4, 0);
        CHECK_EQ_INT(tx_session(&u, chunk), 0);
        CHECK(hm.out_len == 9 && memcmp(hm.out, "012356789", 9) == 0);
        CHECK_EQ_INT(hf.faults, 1);
        CHECK_EQ_INT(hf.tx_seen, 10);
        CHECK_EQ_INT(hf.tx_sent, 9);

        hal_mem_init(&hm, &inner);
        hal_fault_init(&hf, &u, &inner);
        hal_fault_arm(&hf, HAL_FAULT_FLIP, HAL_FAULT_TX, 0, 0x40);
        CHECK_EQ_INT(tx_session(&u, chunk), 0);
        CHECK(hm.out_len == 10 && memcmp(hm.out, "p123456789", 10) == 0);

        hal_mem_init(&hm, &inner);
        hal_fault_init(&hf, &u, &inner);
        hal_fault_arm(&hf, HAL_FAULT_DUP, HAL_FAULT_TX, 9, 0);
        CHECK_EQ_INT(tx_session(&u, chunk), 0);
        CHECK(hm.out_len == 11 && memcmp(hm.out, "01234567899", 11) == 0);
        CHECK_EQ_INT(hf.tx_sent, 11);

        hal_mem_init(&hm, &inner);
        hal_fault_init(&hf, &u, &inner);
        hal_fault_arm(&hf, HAL_FAULT_TRUNCATE, HAL_FAULT_TX, 5, 0);
        CHECK_EQ_INT(tx_session(&u, chunk), 0);
        CHECK(hm.out_len == 10 && memcmp(hm.out, "0123456789", 10) == 0);
        CHECK_EQ_INT(hf.faults, 1);

        hal_mem_init(&hm, &inner);
        hal_fault_init(&hf, &u, &inner);
        hal_fault_arm(&hf, HAL_FAULT_FAIL, HAL_FAULT_TX, 7, 0);
        CHECK_EQ_INT(tx_session(&u, chunk), CP_ERR_IO);
        CHECK(hm.out_len == 7 && memcmp(hm.out, "0123456", 7) == 0);
        CHECK_EQ_INT(hal_uart_write(&u, (const uint8_t *)"x", 1), CP_ERR_IO); /* sticky */
        /* the other direction is untouched */
        CHECK_EQ_INT(hal_mem_feed_str(&hm, "ab"), 0);
        CHECK_EQ_INT(hal_uart_read(&u, want, sizeof want), 2);
    }
    /* an inner back-pressure (0 accepted) at the fault byte delays the fault */
    hal_mem_init(&hm, &inner);
    hal_fault_init(&hf, &u, &inner);
    hal_fault_arm(&hf, HAL_FAULT_FLIP, HAL_FAULT_TX, 2, 0x01);
    hm.out_len = HAL_MEM_OUT - 2;
    CHECK_EQ_INT(hal_uart_write(&u, (const uint8_t *)"abcd", 4), 2);
    CHECK_EQ_INT(hal_uart_write(&u, (const uint8_t *)"cd", 2), 0);
    CHECK_EQ_INT(hf.faults, 0);
    hm.out_len = 0;
    CHECK_EQ_INT(hal_uart_write(&u, (const uint8_t *)"cd", 2), 1);
    CHECK_EQ_INT(hm.out[0], 'b');
    CHECK_EQ_INT(hf.faults, 1);
    return 0;
}

/* Read everything through the fault in calls of at most `cap` bytes (bounded).
 * Returns the byte count, or the first error. */
static int rx_session(struct hal_uart *u, uint8_t *out, size_t cap)
{
    size_t n = 0;
    int guard, r, idle = 0;
    for (guard = 0; guard < 200 && idle < 3; guard++) {
        r = hal_uart_read(u, out + n, cap);
        if (r < 0) {
            return r;
        }
        n += (size_t)r;
        idle = r == 0 ? idle + 1 : 0;
    }
    return (int)n;
}

int test_hal_fault_rx(void)
{
    struct hal_uart inner, u;
    size_t cap;
    uint8_t b[32];
    for (cap = 1; cap <= 13; cap += 4) {
        hal_mem_init(&hm, &inner);
        hal_fault_init(&hf, &u, &inner);
        hal_fault_arm(&hf, HAL_FAULT_DROP, HAL_FAULT_RX, 3, 0);
        CHECK_EQ_INT(hal_mem_feed_str(&hm, "0123456789"), 0);
        CHECK_EQ_INT(rx_session(&u, b, cap), 9);
        CHECK(memcmp(b, "012456789", 9) == 0);
        CHECK_EQ_INT(hf.rx_seen, 10);
        CHECK_EQ_INT(hf.rx_given, 9);

        hal_mem_init(&hm, &inner);
        hal_fault_init(&hf, &u, &inner);
        hal_fault_arm(&hf, HAL_FAULT_FLIP, HAL_FAULT_RX, 9, 0x80);
        CHECK_EQ_INT(hal_mem_feed_str(&hm, "0123456789"), 0);
        CHECK_EQ_INT(rx_session(&u, b, cap), 10);
        CHECK(memcmp(b, "012345678\xb9", 10) == 0);

        hal_mem_init(&hm, &inner);
        hal_fault_init(&hf, &u, &inner);
        hal_fault_arm(&hf, HAL_FAULT_DUP, HAL_FAULT_RX, 0, 0);
        CHECK_EQ_INT(hal_mem_feed_str(&hm, "0123456789"), 0);
        CHECK_EQ_INT(rx_session(&u, b, cap), 11);
        CHECK(memcmp(b, "00123456789", 11) == 0);

        hal_mem_init(&hm, &inner);
        hal_fault_init(&hf, &u, &inner);
        hal_fault_arm(&hf, HAL_FAULT_TRUNCATE, HAL_FAULT_RX, 6, 0);
        CHECK_EQ_INT(hal_mem_feed_str(&hm, "0123456789"), 0);
        CHECK_EQ_INT(rx_session(&u, b, cap), 10);
        CHECK(memcmp(b, "0123456789", 10) == 0);
        CHECK_EQ_INT(hf.faults, 1);

        hal_mem_init(&hm, &inner);
        hal_fault_init(&hf, &u, &inner);
        hal_fault_arm(&hf, HAL_FAULT_FAIL, HAL_FAULT_RX, 5, 0);
        CHECK_EQ_INT(hal_mem_feed_str(&hm, "0123456789"), 0);
        CHECK_EQ_INT(rx_session(&u, b, cap), CP_ERR_IO);
        CHECK_EQ_INT(hf.rx_given, 5);
        CHECK(memcmp(b, "01234", 5) == 0);
        CHECK_EQ_INT(hal_uart_read(&u, b, sizeof b), CP_ERR_IO);
        CHECK_EQ_INT(hal_uart_write(&u, b, 3), 3); /* TX untouched */
    }
    /* the fault waits for its byte even if it arrives late */
    hal_mem_init(&hm, &inner);
    hal_fault_init(&hf, &u, &inner);
    hal_fault_arm(&hf, HAL_FAULT_FAIL, HAL_FAULT_RX, 2, 0);
    CHECK_EQ_INT(hal_uart_read(&u, b, sizeof b), 0);
    CHECK_EQ_INT(hal_mem_feed_str(&hm, "ab"), 0);
    CHECK_EQ_INT(hal_uart_read(&u, b, sizeof b), 2);
    CHECK_EQ_INT(hal_mem_feed_str(&hm, "c"), 0);
    CHECK_EQ_INT(hal_uart_read(&u, b, sizeof b), CP_ERR_IO);
    CHECK(strcmp(hal_fault_name(HAL_FAULT_TRUNCATE), "truncate") == 0);
    return 0;
}

/* A fresh engine on hm (through hf, fault disarmed). */
static int session_start(struct hal_uart *inner, struct hal_uart *u)
{
    struct proto_cfg cfg = {0};
    hal_mem_init(&hm, inner);
    hal_fault_init(&hf, u, inner);
    cfg.uart = u;
    return proto_init(&pe, &cfg);
}

/* The output ends with a complete $I answer: "[VER:..." somewhere, then "]\nok\n". */
static int ends_with_info(const uint8_t *out, size_t len)
{
    size_t i;
    if (len < 20 || memcmp(out + len - 5, "]\nok\n", 5) != 0) {
        return 0;
    }
    for (i = 0; i + 5 <= len; i++) {
        if (memcmp(out + i, "[VER:", 5) == 0) {
            return 1;
        }
    }
    return 0;
}

int test_hal_proto_flip(void)
{
    struct hal_uart inner, u;
    static const char *const bad[] = {"error:1 unknown command\n", "error:8 invalid character in line\n"};
    static const uint8_t masks[] = {0x01, 0x80};
    int k;
    for (k = 0; k < 2; k++) {
        CHECK_EQ_INT(session_start(&inner, &u), CP_OK);
        /* '$I' -> '$H' (unknown command) or '$' ^ 0x80 (not ASCII) */
        hal_fault_arm(&hf, HAL_FAULT_FLIP, HAL_FAULT_RX, k == 0 ? 1u : 0u, masks[k]);
        CHECK_EQ_INT(hal_mem_feed_str(&hm, "$I\n"), 0);
        CHECK_EQ_INT(pump(&pe), 0);
        CHECK_EQ_INT(hf.faults, 1);
        CHECK_EQ_INT(hm.out_len, strlen(bad[k]));
        CHECK(memcmp(hm.out, bad[k], hm.out_len) == 0);
        /* ready for the next line */
        hal_mem_clear_out(&hm);
        CHECK_EQ_INT(hal_mem_feed_str(&hm, "$I\n"), 0);
        CHECK_EQ_INT(pump(&pe), 0);
        CHECK(hm.out_len > 20 && memcmp(hm.out, "[VER:", 5) == 0);
        CHECK(ends_with_info(hm.out, hm.out_len));
    }
    return 0;
}

int test_hal_proto_fail(void)
{
    struct hal_uart inner, u;
    /* RX fails after byte 5: the first line is answered, then CP_ERR_IO (sticky) */
    CHECK_EQ_INT(session_start(&inner, &u), CP_OK);
    hal_fault_arm(&hf, HAL_FAULT_FAIL, HAL_FAULT_RX, 5, 0);
    CHECK_EQ_INT(hal_mem_feed_str(&hm, "FOO\n$I\n"), 0);
    CHECK_EQ_INT(pump(&pe), CP_ERR_IO);
    CHECK_EQ_INT(proto_poll(&pe), CP_ERR_IO);
    CHECK_EQ_INT(pe.lines_seen, 1);
    /* TX fails after byte 10: exactly 10 bytes of the answer leave, then CP_ERR_IO */
    CHECK_EQ_INT(session_start(&inner, &u), CP_OK);
    hal_fault_arm(&hf, HAL_FAULT_FAIL, HAL_FAULT_TX, 10, 0);
    CHECK_EQ_INT(hal_mem_feed_str(&hm, "$I\n"), 0);
    CHECK_EQ_INT(pump(&pe), CP_ERR_IO);
    CHECK_EQ_INT(hm.out_len, 10);
    CHECK(memcmp(hm.out, "[VER:canal", 10) == 0);
    CHECK_EQ_INT(proto_poll(&pe), CP_ERR_IO);
    return 0;
}

static const char sweep_in[] = "$I\nHELLO\nFOO\n\n$I\n";

/* Check every output line: "ok", "error:<code> <text of code>" or "[...]". Returns
 * the number of terminal replies (ok/error), or -1 on a malformed line. */
static int count_replies(const uint8_t *out, size_t len)
{
    size_t a = 0, b;
    int n = 0;
    char txt[64];
    while (a < len) {
        unsigned code = 0;
        size_t i, l;
        for (b = a; b < len && out[b] != '\n'; b++) {
        }
        if (b == len) {
            return -1; /* unterminated */
        }
        l = b - a;
        if (l == 2 && memcmp(out + a, "ok", 2) == 0) {
            n++;
        } else if (l > 1 && out[a] == '[' && out[b - 1] == ']') {
            /* info line */
        } else if (l > 7 && memcmp(out + a, "error:", 6) == 0) {
            for (i = a + 6; i < b && out[i] >= '0' && out[i] <= '9'; i++) {
                code = code * 10u + (unsigned)(out[i] - '0');
            }
            if (i == a + 6 || i >= b || out[i] != ' ' || b - i - 1 >= sizeof txt) {
                return -1;
            }
            memcpy(txt, out + i + 1, b - i - 1);
            txt[b - i - 1] = '\0';
            if (strcmp(txt, cp_status_text((int)code)) != 0) {
                return -1;
            }
            n++;
        } else {
            return -1;
        }
        a = b + 1;
    }
    return n;
}

int test_hal_proto_sweep(void)
{
    struct hal_uart inner, u;
    static const uint8_t modes[] = {HAL_FAULT_DROP, HAL_FAULT_FLIP, HAL_FAULT_DUP,
                                    HAL_FAULT_TRUNCATE, HAL_FAULT_FAIL};
    static const uint8_t masks[] = {0x01, 0x80, 0x20};
    const size_t in_len = sizeof sweep_in - 1;
    size_t i, m, k, j;
    int r, cases = 0;

    /* the reference: no fault */
    CHECK_EQ_INT(session_start(&inner, &u), CP_OK);
    CHECK_EQ_INT(hal_mem_feed_str(&hm, sweep_in), 0);
    CHECK_EQ_INT(pump(&pe), 0);
    ref_len = hm.out_len;
    CHECK(ref_len > 0 && ref_len < sizeof ref_out);
    memcpy(ref_out, hm.out, ref_len);
    CHECK_EQ_INT(count_replies(ref_out, ref_len), 5);

    /* TX: the output is the reference with exactly that fault applied */
    for (i = 0; i < ref_len; i++) {
        for (m = 0; m < sizeof modes; m++) {
            size_t n = 0;
            CHECK_EQ_INT(session_start(&inner, &u), CP_OK);
            hm.write_chunk = (i % 3u) * 5u; /* 0 (unlimited), 5, 10 bytes per write */
            hal_fault_arm(&hf, (enum hal_fault_mode)modes[m], HAL_FAULT_TX, (uint32_t)i, 0x20);
            CHECK_EQ_INT(hal_mem_feed_str(&hm, sweep_in), 0);
            r = pump(&pe);
            for (j = 0; j < ref_len; j++) {
                if (j == i && modes[m] == HAL_FAULT_FAIL) {
                    break;
                }
                if (j == i && modes[m] == HAL_FAULT_DROP) {
                    continue;
                }
                want[n++] = (uint8_t)(j == i && modes[m] == HAL_FAULT_FLIP ? ref_out[j] ^ 0x20u
                                                                           : ref_out[j]);
                if (j == i && modes[m] == HAL_FAULT_DUP) {
                    want[n++] = ref_out[j];
                }
            }
            if (hm.out_len != n || memcmp(hm.out, want, n) != 0 ||
                r != (modes[m] == HAL_FAULT_FAIL ? CP_ERR_IO : 0)) {
                printf("  TX %s at %u: %u bytes, want %u, rc %d\n",
                       hal_fault_name((enum hal_fault_mode)modes[m]), (unsigned)i,
                       (unsigned)hm.out_len, (unsigned)n, r);
                CHECK(0);
            }
            CHECK_EQ_INT(hf.faults, 1);
            cases++;
        }
    }

    /* RX: never a malformed or missing reply; one reply per received line; the
     * engine answers the next $I; FAIL stops with CP_ERR_IO after a prefix. */
    for (i = 0; i < in_len; i++) {
        for (m = 0; m < sizeof modes; m++) {
            for (k = 0; k < (modes[m] == HAL_FAULT_FLIP ? sizeof masks : 1u); k++) {
                uint8_t got[sizeof sweep_in + 1];
                size_t n = 0;
                int lines = 0;
                CHECK_EQ_INT(session_start(&inner, &u), CP_OK);
                hm.read_chunk = i % 4u; /* 0 (unlimited), 1, 2, 3 bytes per read */
                hal_fault_arm(&hf, (enum hal_fault_mode)modes[m], HAL_FAULT_RX, (uint32_t)i,
                              masks[k]);
                CHECK_EQ_INT(hal_mem_feed_str(&hm, sweep_in), 0);
                r = pump(&pe);
                CHECK_EQ_INT(hf.faults, 1);
                if (modes[m] == HAL_FAULT_FAIL) {
                    CHECK_EQ_INT(r, CP_ERR_IO);
                    CHECK(hm.out_len <= ref_len && memcmp(hm.out, ref_out, hm.out_len) == 0);
                    cases++;
                    continue;
                }
                CHECK_EQ_INT(r, 0);
                /* what the engine received */
                for (j = 0; j < in_len; j++) {
                    uint8_t c = (uint8_t)sweep_in[j];
                    if (j == i && modes[m] == HAL_FAULT_DROP) {
                        continue;
                    }
                    if (j == i && modes[m] == HAL_FAULT_FLIP) {
                        c = (uint8_t)(c ^ masks[k]);
                    }
                    got[n++] = c;
                    if (j == i && modes[m] == HAL_FAULT_DUP) {
                        got[n++] = c;
                    }
                }
                for (j = 0; j < n; j++) {
                    lines += got[j] == '\n';
                }
                r = count_replies(hm.out, hm.out_len);
                if (r != lines) {
                    printf("  RX %s/%02x at %u: %d replies, want %d\n",
                           hal_fault_name((enum hal_fault_mode)modes[m]), masks[k], (unsigned)i,
                           r, lines);
                    CHECK(0);
                }
                if (modes[m] == HAL_FAULT_TRUNCATE) {
                    CHECK(hm.out_len == ref_len && memcmp(hm.out, ref_out, ref_len) == 0);
                }
                hal_mem_clear_out(&hm);
                CHECK_EQ_INT(hal_mem_feed_str(&hm, "\n$I\n"), 0);
                CHECK_EQ_INT(pump(&pe), 0);
                CHECK(ends_with_info(hm.out, hm.out_len));
                cases++;
            }
        }
    }
    TEST_NOTE("fault sweep: %d cases (TX %u bytes, RX %u bytes)\n", cases, (unsigned)ref_len,
              (unsigned)in_len);
    return 0;
}
