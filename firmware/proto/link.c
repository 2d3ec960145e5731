/* link.c - a serial link's send buffer (link.h).
 * SPDX-License-Identifier: MIT
 */
#include "link.h"

#include "cp_types.h"

size_t link_tx_room(uint8_t *buf, size_t cap, uint16_t *len, uint16_t *pos)
{
    if (*pos > 0u) { /* compact the unsent tail to the front */
        uint16_t i, k = (uint16_t)(*len - *pos);
        for (i = 0; i < k; i++) {
            buf[i] = buf[*pos + i];
        }
        *len = k;
        *pos = 0u;
    }
    return cap - *len;
}

void link_tx_put(uint8_t *buf, size_t cap, uint16_t *len, const char *s, size_t n)
{
    size_t i;
    for (i = 0; i < n && *len < cap; i++) {
        buf[(*len)++] = (uint8_t)s[i];
    }
}

int link_tx_flush(const struct hal_uart *uart, const uint8_t *buf, uint16_t *len, uint16_t *pos)
{
    int n;
    if (*pos >= *len) {
        return 0;
    }
    n = hal_uart_write(uart, buf + *pos, (size_t)(*len - *pos));
    if (n < 0) {
        return CP_ERR_IO;
    }
    *pos = (uint16_t)(*pos + (uint16_t)n);
    if (*pos == *len) {
        *pos = *len = 0u;
    }
    return n > 0;
}

