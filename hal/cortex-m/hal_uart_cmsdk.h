/* hal_uart_cmsdk.h - struct hal_uart on the CMSDK APB UARTs + TIMER0 of mps2-an386.
 * SPDX-License-Identifier: MIT
 *
 * Two instances of the same driver: unit 0 = UART0 (0x40004000, RX IRQ 0, TX IRQ 1),
 * unit 1 = UART1 (0x40005000, RX IRQ 2, TX IRQ 3); mps2.h cites the board map. Each
 * unit is one struct hal_uart_cmsdk owned by the caller, filled into its own struct
 * hal_uart by hal_uart_cmsdk_init().
 *
 * RX is interrupt-driven into a ring of HAL_UART_CMSDK_RX_RING bytes per unit. When
 * the ring is full the ISR leaves the byte in the UART's holding register and masks
 * that unit's RX interrupt; read() unmasks it after making room, so a slow consumer
 * back-pressures the sender instead of dropping (on QEMU the host's pty write then
 * blocks; on real silicon the UART's RX overrun bit is set and counted in rx_overruns).
 * TX is non-blocking: write() fills the 1-byte holding register while TXFULL is
 * clear and returns the bytes accepted (0 when TXFULL). A short write arms that unit's
 * TX interrupt, which only wakes the sleeping main loop.
 *
 * The clock is one for the whole port, not per unit: TIMER0 (25 MHz, reloaded every
 * 10 ms) counted in software by this file, started by hal_uart_cmsdk_clock_init(). Every
 * unit's now_ms() reads that one clock. Its period interrupt (IRQ 8) keeps the count
 * exact and wakes the main loop from WFI, so the protocol's timeouts run on time while
 * the lines are silent.
 *
 * Wake-ups are one for the whole port too: every ISR (both units' RX and TX, TIMER0)
 * sets one event flag in this file, and hal_uart_cmsdk_sleep() consumes it.
 *
 * The ISRs reach a unit's state through a file-scope pointer per unit, set by
 * hal_uart_cmsdk_init(); a unit that was never initialised has its IRQs disabled. All
 * ISRs are a few dozen instructions and use only integer registers (no FP context is
 * stacked lazily beyond the hardware frame).
 */
#ifndef HAL_UART_CMSDK_H
#define HAL_UART_CMSDK_H

#include <stdint.h>

#include "hal_uart.h"

/* RX ring size per unit, bytes. Power of two (2-256). On QEMU any size is lossless; on
 * real hardware it must cover the longest gap between two read() calls at line rate
 * (115200 baud = 11.5 bytes/ms). */
#ifndef HAL_UART_CMSDK_RX_RING
#define HAL_UART_CMSDK_RX_RING 64
#endif
#if HAL_UART_CMSDK_RX_RING < 2 || HAL_UART_CMSDK_RX_RING > 256 || \
    (HAL_UART_CMSDK_RX_RING & (HAL_UART_CMSDK_RX_RING - 1)) != 0
#error "HAL_UART_CMSDK_RX_RING must be a power of two in 2..256"
#endif

/* Units this driver knows: 0 = UART0, 1 = UART1. */
#define HAL_UART_CMSDK_UNITS 2u

struct mps2_uart; /* the register block (mps2.h) */

/* State of one unit; the caller owns it (static storage: the ISRs keep a pointer). */
struct hal_uart_cmsdk {
    struct mps2_uart *regs;             /* this unit's registers (set by init) */
    volatile uint8_t rx_head;           /* next write index (ISR / read() under PRIMASK) */
    volatile uint8_t rx_tail;           /* next read index (read() only) */
    uint32_t rx_overruns;               /* RX overrun flags seen (real hardware only) */
    uint8_t rx[HAL_UART_CMSDK_RX_RING]; /* received bytes, ring (after the scalars: their
                                           offsets stay in reach of 16-bit Thumb loads) */
};

/* Start the port's clock: TIMER0 free-running with a 10 ms period, its IRQ 8 cleared and
 * enabled in the NVIC, now_ms() = 0 from here. Call it once, before the units' init
 * (a unit's now_ms() reads 0 until then). Interrupts must be globally enabled (PRIMASK
 * clear, the reset state). */
void hal_uart_cmsdk_clock_init(void);

/* Configure unit `unit` (0 = UART0, 1 = UART1): 8N1, BAUDDIV for 115200 at 25 MHz (QEMU
 * ignores the rate), RX and its interrupt enabled, the unit's RX and TX IRQs cleared and
 * enabled in the NVIC; fill u with the unit's three calls (u->ctx = s). Transmits
 * nothing. A unit >= HAL_UART_CMSDK_UNITS leaves s and u untouched (u's calls stay as
 * the caller had them: NULL in static storage, which proto_init() refuses). Each unit
 * once, each with its own s. Interrupts must be globally enabled (PRIMASK clear). */
void hal_uart_cmsdk_init(struct hal_uart_cmsdk *s, struct hal_uart *u, unsigned unit);

/* Idle helper for the main loop: sleep in WFI until the next interrupt unless an ISR
 * of any unit or of the clock ran since the previous call (then return at once). Call
 * it only after the firmware reported "idle" (proto_poll() == 0). Lost-wake-up free:
 * the check and the WFI run with PRIMASK set (cpsid i; check; wfi; cpsie i), and a
 * pending interrupt still ends WFI while masked. */
void hal_uart_cmsdk_sleep(void);

#endif /* HAL_UART_CMSDK_H */
