/* hal_uart_cmsdk.h - struct hal_uart on the CMSDK APB UART0 + TIMER0 of mps2-an386.
 * SPDX-License-Identifier: MIT
 *
 * RX is interrupt-driven (UART0 RX = IRQ 0) into a ring of HAL_UART_CMSDK_RX_RING
 * bytes. When the ring is full the ISR leaves the byte in the UART's holding
 * register and masks the RX interrupt; read() unmasks it after making room, so
 * a slow consumer back-pressures the sender instead of dropping (on QEMU the
 * host's pty write then blocks; on real silicon the UART's RX overrun bit is set
 * and counted in rx_overruns).
 * TX is non-blocking: write() fills the 1-byte holding register while TXFULL is
 * clear and returns the bytes accepted (0 when TXFULL). A short write arms the
 * TX interrupt (IRQ 1), which only wakes the sleeping main loop.
 * now_ms() counts TIMER0 (25 MHz, reloaded every 10 ms) in software; its period
 * interrupt (IRQ 8) keeps the count exact and wakes the main loop from WFI, so the
 * protocol's timeouts run on time while the line is silent.
 *
 * Single instance: the ISRs reach the state through one file-scope pointer, set
 * by hal_uart_cmsdk_init(). All ISRs are a few dozen instructions and use only
 * integer registers (no FP context is stacked lazily beyond the hardware frame).
 */
#ifndef HAL_UART_CMSDK_H
#define HAL_UART_CMSDK_H

#include <stdint.h>

#include "hal_uart.h"

/* RX ring size, bytes. Power of two (2-256). On QEMU any size is lossless; on real
 * hardware it must cover the longest gap between two read() calls at line rate
 * (115200 baud = 11.5 bytes/ms). */
#ifndef HAL_UART_CMSDK_RX_RING
#define HAL_UART_CMSDK_RX_RING 64
#endif
#if HAL_UART_CMSDK_RX_RING < 2 || HAL_UART_CMSDK_RX_RING > 256 || \
    (HAL_UART_CMSDK_RX_RING & (HAL_UART_CMSDK_RX_RING - 1)) != 0
#error "HAL_UART_CMSDK_RX_RING must be a power of two in 2..256"
#endif

/* Port state; the caller owns it (static storage: the ISRs keep a pointer). */
struct hal_uart_cmsdk {
    volatile uint8_t rx_head;            /* next write index (ISR / read() under PRIMASK) */
    volatile uint8_t rx_tail;            /* next read index (read() only) */
    volatile uint8_t event;              /* set by every ISR; consumed by _sleep() */
    uint32_t rx_overruns;                /* RX overrun flags seen (real hardware only) */
    uint32_t tick_last;                  /* TIMER0 value at the last time update, ticks */
    uint32_t tick_frac;                  /* ticks not yet counted as a whole ms (0..24999) */
    uint32_t ms;                         /* milliseconds since init, wraps at 2^32 */
    uint8_t rx[HAL_UART_CMSDK_RX_RING]; /* received bytes, ring (after the scalars: their
                                            offsets stay in reach of 16-bit Thumb loads) */
};

/* Configure UART0 (8N1, BAUDDIV for 115200 at 25 MHz; QEMU ignores the rate),
 * TIMER0 (free-running from 0xFFFFFFFF), clear and enable IRQs 0, 1, 8 in the
 * NVIC, and fill u with this port's three calls (u->ctx = s).
 * Interrupts must be globally enabled (PRIMASK clear, the reset state). */
void hal_uart_cmsdk_init(struct hal_uart_cmsdk *s, struct hal_uart *u);

/* Idle helper for the main loop: sleep in WFI until the next interrupt unless an
 * ISR ran since the previous call (then return at once). Call it only after the
 * firmware reported "idle" (proto_poll() == 0). Lost-wake-up free: the check and
 * the WFI run with PRIMASK set (cpsid i; check; wfi; cpsie i), and a pending
 * interrupt still ends WFI while masked. */
void hal_uart_cmsdk_sleep(struct hal_uart_cmsdk *s);

#endif /* HAL_UART_CMSDK_H */
