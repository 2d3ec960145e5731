/* link.h - a serial link's send buffer: the host link's (struct proto: tx, tx_len,
 * tx_pos) and the machine link's (struct machine_link) share this code.
 * SPDX-License-Identifier: MIT
 *
 * A send buffer is buf[0..cap) with the counters *len and *pos owned by the caller: the
 * bytes buf[*pos..*len) wait for the HAL. No state of its own, no clock.
 */
#ifndef LINK_H
#define LINK_H

#include <stddef.h>
#include <stdint.h>

#include "hal_uart.h"

/* Free bytes after the unsent ones, which move to the front first. */
size_t link_tx_room(uint8_t *buf, size_t cap, uint16_t *len, uint16_t *pos);
/* Append s[0..n) (at most the room left). */
void link_tx_put(uint8_t *buf, size_t cap, uint16_t *len, const char *s, size_t n);
/* Write what is pending to uart (non-blocking, partial writes are normal): > 0 if bytes
 * moved, 0 if not, CP_ERR_IO on a HAL failure. */
int link_tx_flush(const struct hal_uart *uart, const uint8_t *buf, uint16_t *len,
                  uint16_t *pos);

#endif /* LINK_H */
