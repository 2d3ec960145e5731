/* hal_uart.h - THE contract between the portable firmware and a serial port.
 * SPDX-License-Identifier: MIT
 *
 * A port fills a struct hal_uart with its private context and three
 * non-blocking calls. The firmware never blocks on I/O: a short write is normal
 * and the caller keeps the rest for the next poll. Ports in this tree:
 *   hal/posix/     a file descriptor (the pty slave) for the native firmware build
 *   hal/cortex-m/  CMSDK UART0 of QEMU mps2-an386, IRQ-driven RX ring, TIMER0 time
 *   tests/hal_mem.c, tests/hal_fault.c   in-memory loopback and fault injection
 * hal/template/hal_uart_template.c lists every obligation of a new port.
 */
#ifndef HAL_UART_H
#define HAL_UART_H

#include <stddef.h>
#include <stdint.h>

/*---------------------------------------------------------------------------
 * Implemented by each port
 *-------------------------------------------------------------------------*/
struct hal_uart {
    void *ctx; /* port-private state, passed back to every call */

    /* Queue up to len bytes for transmission. Never blocks.
     * Returns the number of bytes accepted (0..len; 0 = TX full, try later),
     * or a negative enum cp_err: CP_ERR_IO when the link is gone (hang-up). */
    int (*write)(void *ctx, const uint8_t *buf, size_t len);

    /* Copy up to cap received bytes into buf. Never blocks.
     * Returns the number of bytes copied (0 = nothing pending), or a negative
     * enum cp_err: CP_ERR_IO when the link is gone (hang-up, EOF). */
    int (*read)(void *ctx, uint8_t *buf, size_t cap);

    /* Monotonic milliseconds since an arbitrary origin; wraps at 2^32.
     * Compare times with (uint32_t)(a - b) only. */
    uint32_t (*now_ms)(void *ctx);
};

/* Convenience wrappers: the firmware calls only these. */
static inline int hal_uart_write(const struct hal_uart *u, const uint8_t *buf, size_t len)
{
    return u->write(u->ctx, buf, len);
}

static inline int hal_uart_read(const struct hal_uart *u, uint8_t *buf, size_t cap)
{
    return u->read(u->ctx, buf, cap);
}

static inline uint32_t hal_uart_now_ms(const struct hal_uart *u)
{
    return u->now_ms(u->ctx);
}

#endif /* HAL_UART_H */
