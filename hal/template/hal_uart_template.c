/* hal_uart_template.c - skeleton of a new serial port for firmware/port/hal_uart.h; lists every obligation.
 * SPDX-License-Identifier: MIT
 *
 * Copy to hal/<port>/hal_uart_<port>.c, rename hal_uart_template_* to hal_uart_<port>_*, fill the
 * TODOs. hal/cortex-m/hal_uart_cmsdk.c is the worked example (IRQ RX ring,
 * non-blocking TX, timer milliseconds, WFI idle); hal/posix/ the host one.
 *
 * Obligations of a port (the firmware relies on every one of them):
 *  1. Three calls, all NON-BLOCKING: write, read, now_ms. Never busy-wait for the
 *     line, never sleep. The firmware polls; the main loop sleeps, not the HAL.
 *  2. write(ctx, buf, len): accept 0..len bytes, return the count. 0 means "full,
 *     try later" and is NOT an error. Bytes accepted must eventually go out in
 *     order. Return CP_ERR_IO (<0) only when the link is gone for good (hang-up).
 *  3. read(ctx, buf, cap): copy 0..cap received bytes in order, return the count;
 *     0 = nothing pending. Never drop silently: when your buffer is full, leave
 *     data in the hardware/kernel (back-pressure) or count the overrun where a
 *     debugger can see it. CP_ERR_IO only on hang-up/EOF.
 *  4. now_ms(ctx): monotonic milliseconds, arbitrary origin, wraps at 2^32; the
 *     firmware compares with (uint32_t)(a - b) only. It must stay correct when
 *     nobody calls it for a long time (extend a short hardware counter in its
 *     wrap interrupt, as the cmsdk port does).
 *  5. Interrupt-driven ports: the ISR only moves bytes between the peripheral and
 *     a ring and sets an "event" flag; no firmware calls from interrupt context.
 *     Clear the peripheral's RX flag BEFORE draining its data register, or a byte
 *     arriving in between loses its interrupt.
 *  6. Idle: provide a sleep helper the main loop calls when the firmware returned
 *     0 (idle). Check the event flag and enter the low-power wait with interrupts
 *     masked (cpsid i; check; wfi; cpsie i) so a wake-up cannot be lost. A TX that
 *     returned short must arm something (TX-empty interrupt) that ends the sleep.
 *  7. Stack: write/read/now_ms are reached through function pointers, which gcc's
 *     call graph cannot follow. Keep them leaf-ish (no deep calls) and list them in
 *     M4F_INDIRECT (mk/m4f.mk) or the port's equivalent, so tools/stack.sh charges
 *     indirect calls with their frames. List the ISRs too (M4F_ISRS).
 *  8. No malloc, no stdio, C99 with the project WARN flags (guard-warn compiles
 *     every hal/<port> C file with clang and gcc). File-scope state is allowed in hal/ only.
 *  9. Transmit nothing before the host has spoken (a pty or QEMU UART drops it).
 * 10. Two links (struct proto_cfg: .uart the host link, .machine the machine link or
 *     NULL): the same driver code serves both, one state struct per instance (see
 *     "A second instance" below). Every instance's now_ms reads the ONE clock of the
 *     port; the sleep helper of obligation 6 wakes on an event of EITHER instance (one
 *     event flag set by every ISR is the simplest way); 1-9 hold per instance.
 */
#include "hal_uart.h"

/* Port state; owned by the caller (main_<port>.c), static storage if ISRs use it. */
struct hal_uart_template {
    int fd_or_base; /* TODO: device handle or register base */
};

void hal_uart_template_init(struct hal_uart_template *s, struct hal_uart *u);

/* A second instance (obligation 10; hal/cortex-m/hal_uart_cmsdk.c is the worked example
 * with UART0 and UART1). init takes the instance number and looks its wiring up in a
 * const table; each instance's ISRs reach its state through a per-instance pointer; the
 * clock and the wake-up event are the port's, not an instance's:
 *
 *   static const struct { uint32_t base; uint8_t irq_rx, irq_tx; } wiring[2] = {
 *       {UART0_BASE, UART0_RX_IRQ, UART0_TX_IRQ},   // TODO: from the board's manual
 *       {UART1_BASE, UART1_RX_IRQ, UART1_TX_IRQ},
 *   };
 *   static struct hal_uart_template *units[2]; // set by init, for the ISRs
 *   static volatile uint8_t event;             // set by every ISR, taken by sleep
 *   void UART0_RX_IRQHandler(void) { rx_drain(units[0]); event = 1u; }
 *   void UART1_RX_IRQHandler(void) { rx_drain(units[1]); event = 1u; }
 *   void hal_uart_template_init(struct hal_uart_template *s, struct hal_uart *u,
 *                               unsigned unit); // u->now_ms: the one clock for both
 *
 * and in main_<port>.c (file-scope state: hal/ only):
 *
 *   static struct hal_uart_template uart0, uart1;
 *   static struct hal_uart host, machine;
 *   hal_uart_template_clock_init();
 *   hal_uart_template_init(&uart0, &host, 0u);
 *   hal_uart_template_init(&uart1, &machine, 1u);
 *   cfg.uart = &host;
 *   cfg.machine = &machine; // NULL on a port with one link
 *   ... proto_poll() == 0: hal_uart_template_sleep(); // wakes on either instance
 */

static int hal_uart_template_write(void *ctx, const uint8_t *buf, size_t len)
{
    struct hal_uart_template *s = ctx;
    (void)s;
    (void)buf;
    (void)len;
    return 0; /* TODO: bytes accepted (0 = full), or CP_ERR_IO on hang-up */
}

static int hal_uart_template_read(void *ctx, uint8_t *buf, size_t cap)
{
    struct hal_uart_template *s = ctx;
    (void)s;
    (void)buf;
    (void)cap;
    return 0; /* TODO: bytes copied (0 = none), or CP_ERR_IO on hang-up */
}

static uint32_t hal_uart_template_now_ms(void *ctx)
{
    struct hal_uart_template *s = ctx;
    (void)s;
    return 0u; /* TODO: monotonic ms, wrapping at 2^32 */
}

/* Set up the device and fill u. Must not transmit anything. */
void hal_uart_template_init(struct hal_uart_template *s, struct hal_uart *u)
{
    s->fd_or_base = 0; /* TODO: open/configure the device, enable RX interrupts */
    u->ctx = s;
    u->write = hal_uart_template_write;
    u->read = hal_uart_template_read;
    u->now_ms = hal_uart_template_now_ms;
}
