/* mps2.h - register map of the QEMU mps2-an386 board (Cortex-M4F) used by the cortex-m port.
 * SPDX-License-Identifier: MIT
 *
 * Only what the port touches: CMSDK APB UART0, CMSDK APB TIMER0, the NVIC
 * enable/pending registers, SCB CPACR, and the interrupt-mask instructions.
 * Addresses and IRQ numbers: QEMU hw/arm/mps2.c (an385/an386 map), checked on
 * QEMU 7.2 (see docs QEMU.md). Nothing here is QEMU-specific beyond the
 * board map: the same CMSDK blocks exist on the real MPS2 FPGA images.
 */
#ifndef MPS2_H
#define MPS2_H

#include <stdint.h>

#define MPS2_REG(addr) (*(volatile uint32_t *)(addr))

/* Core clock and the APB peripheral clock: 25 MHz on mps2 (SYSCLK_FRQ). */
#define MPS2_SYSCLK_HZ 25000000u

/* CMSDK APB UART0. Registers: DATA +0x0, STATE +0x4, CTRL +0x8, INTSTATUS +0xC (W1C),
 * BAUDDIV +0x10 (must be >= 16 when TX is enabled). */
#define MPS2_UART0_BASE 0x40004000u
#define MPS2_UART0_DATA MPS2_REG(MPS2_UART0_BASE + 0x00u)
#define MPS2_UART0_STATE MPS2_REG(MPS2_UART0_BASE + 0x04u)
#define MPS2_UART0_CTRL MPS2_REG(MPS2_UART0_BASE + 0x08u)
#define MPS2_UART0_INTSTATUS MPS2_REG(MPS2_UART0_BASE + 0x0Cu)
#define MPS2_UART0_BAUDDIV MPS2_REG(MPS2_UART0_BASE + 0x10u)
#define MPS2_UART_STATE_TXFULL 0x01u
#define MPS2_UART_STATE_RXFULL 0x02u
#define MPS2_UART_STATE_TXOVR 0x04u /* W1C */
#define MPS2_UART_STATE_RXOVR 0x08u /* W1C */
#define MPS2_UART_CTRL_TXEN 0x01u
#define MPS2_UART_CTRL_RXEN 0x02u
#define MPS2_UART_CTRL_TXIE 0x04u
#define MPS2_UART_CTRL_RXIE 0x08u
#define MPS2_UART_INT_TX 0x01u
#define MPS2_UART_INT_RX 0x02u

/* CMSDK APB TIMER0: a 32-bit down-counter at MPS2_SYSCLK_HZ. CTRL +0x0 (b0 enable,
 * b3 interrupt enable), VALUE +0x4, RELOAD +0x8, INTSTATUS +0xC (W1C, b0). */
#define MPS2_TIMER0_BASE 0x40000000u
#define MPS2_TIMER0_CTRL MPS2_REG(MPS2_TIMER0_BASE + 0x00u)
#define MPS2_TIMER0_VALUE MPS2_REG(MPS2_TIMER0_BASE + 0x04u)
#define MPS2_TIMER0_RELOAD MPS2_REG(MPS2_TIMER0_BASE + 0x08u)
#define MPS2_TIMER0_INTSTATUS MPS2_REG(MPS2_TIMER0_BASE + 0x0Cu)
#define MPS2_TIMER_CTRL_EN 0x01u
#define MPS2_TIMER_CTRL_IE 0x08u

/* External interrupt numbers (vector = 16 + irq). */
#define MPS2_IRQ_UART0_RX 0
#define MPS2_IRQ_UART0_TX 1
#define MPS2_IRQ_TIMER0 8

/* NVIC set-enable / clear-enable / clear-pending, IRQ 0..31. */
#define MPS2_NVIC_ISER0 MPS2_REG(0xE000E100u)
#define MPS2_NVIC_ICER0 MPS2_REG(0xE000E180u)
#define MPS2_NVIC_ICPR0 MPS2_REG(0xE000E280u)

/* SCB coprocessor access control: CP10/CP11 full access = FPU on. */
#define MPS2_SCB_CPACR MPS2_REG(0xE000ED88u)
#define MPS2_CPACR_FPU_FULL (0xFu << 20)

/* Mask / unmask interrupts (PRIMASK). A pending interrupt still ends WFI while masked. */
static inline void mps2_irq_off(void)
{
    __asm volatile("cpsid i" ::: "memory");
}

static inline void mps2_irq_on(void)
{
    __asm volatile("cpsie i" ::: "memory");
}

/* Wait for interrupt; the caller masks interrupts around its idle check. */
static inline void mps2_wfi(void)
{
    __asm volatile("wfi" ::: "memory");
}

#endif /* MPS2_H */
