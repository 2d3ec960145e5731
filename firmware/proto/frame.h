/* frame.h - binary frames of the FRAMES output format (Klipper-style block).
 * SPDX-License-Identifier: MIT
 *
 *   +-----+-----+------+-----------------+-----------+------+
 *   | len | seq | type | payload (0..N)  | crc16 (BE)| 0x7E |
 *   +-----+-----+------+-----------------+-----------+------+
 *   len   = total frame length in bytes, FRAME_MIN (6) .. FRAME_MAX (64)
 *   seq   = low 8 bits of the frame's sequence number within the run
 *   crc16 = CRC-16/CCITT-FALSE (poly 0x1021, init 0xFFFF) over len..payload
 *   sync  = 0x7E closes every frame; the decoder resynchronises on it
 *
 * Multi-byte payload fields are little-endian, packed by hand (no struct copies).
 * Types firmware -> host: FRAME_BEGIN, FRAME_POINT, FRAME_END.
 * Types host -> firmware: FRAME_ACK (seq = next expected), FRAME_NAK (seq = wanted
 * again), FRAME_ABORT, FRAME_HOLD, FRAME_GO, FRAME_STATUS (payload empty).
 */
#ifndef FRAME_H
#define FRAME_H

#include "cp_types.h"

#define FRAME_SYNC 0x7Eu
#define FRAME_MIN 6u
#define FRAME_MAX 64u
#define FRAME_OVERHEAD 6u

enum frame_type {
    /* u32 count, u32 first point, u16 n, u16 steps, u16 link, u8 mode, u8 overlap (1: far
     * parts of the sweep meet, the tool inside: reported, raster.h) */
    FRAME_BEGIN = 0x01,
    /* u32 k, i32 x, y, z (0.1 um), i16 nx, ny, nz (1/32767), i16 line, u16 index */
    FRAME_POINT = 0x02,
    /* u8 wire status (0 = complete), u32 points sent */
    FRAME_END = 0x03,
    FRAME_ACK = 0x81,
    FRAME_NAK = 0x82,
    FRAME_ABORT = 0x83,
    FRAME_HOLD = 0x84,
    FRAME_GO = 0x85,
    FRAME_STATUS = 0x86
};

#define FRAME_POINT_PAYLOAD 26u
#define FRAME_POINT_LEN (FRAME_POINT_PAYLOAD + FRAME_OVERHEAD)

/* CRC-16/CCITT-FALSE of n bytes, continuing from crc (start with 0xFFFF). */
uint16_t frame_crc16(uint16_t crc, const uint8_t *p, size_t n);

/* Encode a frame into out (cap bytes). With out == NULL only the length is computed
 * (sizing mode). Returns the frame length, or CP_ERR_FULL if it does not fit / the
 * payload is longer than FRAME_MAX - FRAME_OVERHEAD. */
int frame_encode(uint8_t seq, uint8_t type, const uint8_t *payload, size_t plen, uint8_t *out,
                 size_t cap);

/* Decoder (Klipper command_find_block style), one byte at a time. */
struct frame_rx {
    uint8_t buf[FRAME_MAX]; /* bytes of the frame being assembled */
    uint8_t len;            /* bytes in buf */
    uint32_t bad;           /* frames discarded (bad length, CRC or sync) */
};

void frame_rx_init(struct frame_rx *r);

/* Feed one byte. Returns 1 when buf[0..buf[0]) holds a complete, CRC-valid frame
 * (read it before the next call), else 0. Garbage is discarded up to the next
 * sync byte; a bad frame increments `bad`. */
int frame_rx_feed(struct frame_rx *r, uint8_t byte);

/* Little-endian packers. */
void frame_put_u16(uint8_t *p, uint16_t v);
void frame_put_u32(uint8_t *p, uint32_t v);
uint16_t frame_get_u16(const uint8_t *p);
uint32_t frame_get_u32(const uint8_t *p);

#endif /* FRAME_H */
