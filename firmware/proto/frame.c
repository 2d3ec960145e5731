/* frame.c - binary frames: CRC-16/CCITT, encoder, resynchronising decoder.
 * SPDX-License-Identifier: MIT
 */
#include "frame.h"

uint16_t frame_crc16(uint16_t crc, const uint8_t *p, size_t n)
{
    size_t i;
    unsigned b;
    for (i = 0; i < n; i++) {
        crc ^= (uint16_t)((uint16_t)p[i] << 8);
        for (b = 0; b < 8u; b++) {
            crc = (crc & 0x8000u) ? (uint16_t)((crc << 1) ^ 0x1021u) : (uint16_t)(crc << 1);
        }
    }
    return crc;
}

void frame_put_u16(uint8_t *p, uint16_t v)
{
    p[0] = (uint8_t)(v & 0xFFu);
    p[1] = (uint8_t)(v >> 8);
}

void frame_put_u32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)(v & 0xFFu);
    p[1] = (uint8_t)((v >> 8) & 0xFFu);
    p[2] = (uint8_t)((v >> 16) & 0xFFu);
    p[3] = (uint8_t)(v >> 24);
}

uint16_t frame_get_u16(const uint8_t *p)
{
    return (uint16_t)(p[0] | (p[1] << 8));
}

uint32_t frame_get_u32(const uint8_t *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}

/* Out of line: inlined into its one caller (LTO) the payload loop becomes a memcpy call
 * and links the library's memcpy into the image. */
CP_NOINLINE int frame_encode(uint8_t seq, uint8_t type, const uint8_t *payload, size_t plen, uint8_t *out,
                 size_t cap)
{
    size_t len = plen + FRAME_OVERHEAD, i;
    uint16_t crc;
    if (len > FRAME_MAX) {
        return CP_ERR_FULL;
    }
    if (out == NULL) {
        return (int)len;
    }
    if (len > cap) {
        return CP_ERR_FULL;
    }
    out[0] = (uint8_t)len;
    out[1] = seq;
    out[2] = type;
    for (i = 0; i < plen; i++) {
        out[3u + i] = payload[i];
    }
    crc = frame_crc16(0xFFFFu, out, 3u + plen);
    out[3u + plen] = (uint8_t)(crc >> 8);
    out[4u + plen] = (uint8_t)(crc & 0xFFu);
    out[5u + plen] = FRAME_SYNC;
    return (int)len;
}

void frame_rx_init(struct frame_rx *r)
{
    r->len = 0;
    r->bad = 0;
}

/* A frame starts with a plausible length byte right after a sync byte (or at the
 * start). While assembling, the first byte gives the length; when it is complete
 * its sync and CRC are checked. On any failure everything up to and including the
 * next sync byte is dropped, which re-aligns the decoder on the following frame. */
int frame_rx_feed(struct frame_rx *r, uint8_t c)
{
    if (r->len == 0u) {
        if (c == FRAME_SYNC) {
            return 0; /* idle sync bytes between frames */
        }
        if (c < FRAME_MIN || c > FRAME_MAX) {
            r->bad++;
            r->len = 0xFFu; /* discard until the next sync */
            return 0;
        }
    } else if (r->len == 0xFFu) {
        if (c == FRAME_SYNC) {
            r->len = 0;
        }
        return 0;
    }
    r->buf[r->len++] = c;
    if (r->len < r->buf[0]) {
        return 0;
    }
    /* complete: check sync and CRC */
    {
        /* the CRC over len..payload followed by its own big-endian CRC is 0 exactly
         * when that CRC is right (CCITT-FALSE: not reflected, no final xor) */
        uint8_t n = r->buf[0];
        int ok = r->buf[n - 1u] == FRAME_SYNC && frame_crc16(0xFFFFu, r->buf, (size_t)n - 1u) == 0u;
        if (ok) {
            r->len = 0;
            return 1;
        }
        r->bad++;
        /* resync: if the last byte was a sync, the next byte may start a frame */
        r->len = r->buf[n - 1u] == FRAME_SYNC ? 0u : 0xFFu;
        return 0;
    }
}
