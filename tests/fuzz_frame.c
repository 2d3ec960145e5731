/* fuzz_frame.c - libFuzzer target: the frame decoder (firmware/proto/frame.c).
 * SPDX-License-Identifier: MIT
 *
 * Input: arbitrary bytes fed one at a time to frame_rx_feed.
 * Invariants (abort() on violation):
 *   - every accepted frame has 6 <= len <= 64, ends in the sync byte 0x7E, carries
 *     a CRC-16/CCITT-FALSE computed here independently (bitwise, own code), and is
 *     exactly the last len bytes fed (the decoder never splices bytes);
 *   - re-encoding it with frame_encode(seq, type, payload) reproduces its bytes, and
 *     frame_encode in sizing mode returns the same length;
 *   - the decoder state stays in range (len < 64 or the discard marker);
 *   - resync: after the input, at most FRAME_MAX sync bytes bring the decoder to
 *     idle, and a valid frame built from the input's first bytes is then accepted.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "frame.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define FAIL(...)                                    \
    do {                                             \
        fprintf(stderr, "fuzz_frame: " __VA_ARGS__); \
        fprintf(stderr, "\n");                       \
        abort();                                     \
    } while (0)

/* CRC-16/CCITT-FALSE, written from the definition (not frame_crc16). */
static unsigned crc_ref(const uint8_t *p, size_t n)
{
    unsigned crc = 0xFFFFu;
    size_t i;
    int b;
    for (i = 0; i < n; i++) {
        for (b = 7; b >= 0; b--) {
            unsigned in = (p[i] >> b) & 1u, top = (crc >> 15) & 1u;
            crc = (crc << 1) & 0xFFFFu;
            if (in ^ top) {
                crc ^= 0x1021u;
            }
        }
    }
    return crc;
}

static void check_frame(const struct frame_rx *r, const uint8_t *fed, size_t nfed)
{
    uint8_t re[FRAME_MAX + 8];
    unsigned len = r->buf[0], crc;
    int n;
    if (len < FRAME_MIN || len > FRAME_MAX) {
        FAIL("accepted frame with len %u", len);
    }
    if (r->buf[len - 1u] != FRAME_SYNC) {
        FAIL("accepted frame without sync");
    }
    crc = crc_ref(r->buf, len - 3u);
    if (r->buf[len - 3u] != (uint8_t)(crc >> 8) || r->buf[len - 2u] != (uint8_t)crc) {
        FAIL("accepted frame with a bad CRC");
    }
    if (nfed < len || memcmp(fed + nfed - len, r->buf, len) != 0) {
        FAIL("accepted frame is not the last %u bytes fed", len);
    }
    n = frame_encode(r->buf[1], r->buf[2], r->buf + 3, len - FRAME_OVERHEAD, re, sizeof re);
    if (n != (int)len || memcmp(re, r->buf, len) != 0) {
        FAIL("re-encoding an accepted frame differs (n %d, len %u)", n, len);
    }
    if (frame_encode(r->buf[1], r->buf[2], r->buf + 3, len - FRAME_OVERHEAD, NULL, 0) != (int)len) {
        FAIL("frame_encode sizing mode disagrees");
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    struct frame_rx r;
    uint8_t good[FRAME_MAX];
    size_t i;
    int n, got = 0;
    frame_rx_init(&r);
    for (i = 0; i < size; i++) {
        if (frame_rx_feed(&r, data[i])) {
            check_frame(&r, data, i + 1);
        }
        if (r.len >= FRAME_MAX && r.len != 0xFFu) {
            FAIL("decoder state len %u", r.len);
        }
    }
    /* resync guarantee */
    for (i = 0; i < FRAME_MAX && r.len != 0u; i++) {
        (void)frame_rx_feed(&r, FRAME_SYNC);
    }
    if (r.len != 0u) {
        FAIL("decoder not idle after %u sync bytes (len %u)", (unsigned)FRAME_MAX, r.len);
    }
    {
        uint8_t seq = size > 0 ? data[0] : 0, type = size > 1 ? data[1] : 0x81;
        size_t plen = size > 2 ? data[2] % (FRAME_MAX - FRAME_OVERHEAD + 1u) : 0;
        uint8_t pl[FRAME_MAX];
        for (i = 0; i < plen; i++) {
            pl[i] = size > 3 + i ? data[3 + i] : (uint8_t)i;
        }
        n = frame_encode(seq, type, pl, plen, good, sizeof good);
        if (n != (int)(plen + FRAME_OVERHEAD)) {
            FAIL("frame_encode of %u payload bytes returned %d", (unsigned)plen, n);
        }
        for (i = 0; i < (size_t)n; i++) {
            if (frame_rx_feed(&r, good[i])) {
                got = (int)(i + 1);
            }
        }
        if (got != n || memcmp(r.buf, good, (size_t)n) != 0) {
            FAIL("valid frame after resync not accepted");
        }
    }
    /* oversize payloads are refused, never written */
    if (frame_encode(0, 0, good, FRAME_MAX - FRAME_OVERHEAD + 1u, good, sizeof good) != CP_ERR_FULL) {
        FAIL("frame_encode accepted an oversize payload");
    }
    return 0;
}
