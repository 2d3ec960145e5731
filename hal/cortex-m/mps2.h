/* mps2.h - register map of the QEMU mps2-an386 board (Cortex-M4F) used by the cortex-m port.
 * SPDX-License-Identifier: MIT
 *
 * Only what the port touches: CMSDK APB UART0 and UART1, CMSDK APB TIMER0, the NVIC
 * enable/pending registers, SCB CPACR, and the interrupt-mask instructions.
 * Nothing here is QEMU-specific beyond the board map: the same CMSDK blocks exist on
 * the real MPS2 FPGA images.
 *
 * Addresses and IRQ numbers: QEMU hw/arm/mps2.c, mps2_common_init(), the case shared by
 * FPGA_AN385 / FPGA_AN386 / FPGA_AN500:
 *     uartbase[] = {0x40004000, 0x40005000, 0x40006000, 0x40007000, 0x40009000};
 *     uartirq[]  = {0, 2, 4, 18, 20};   RX irq number; TX irq is always one greater
 *     cmsdk_apb_uart_create(uartbase[i], txint = irq uartirq[i] + 1, rxint = irq uartirq[i],
 *                           ..., serial_hd(i), SYSCLK_FRQ)
 *   and TIMER0 at 0x40000000 on IRQ 8 (timer i: 0x40000000 + i * 0x1000, IRQ 8 + i).
 *   UART i is the i-th -serial of the QEMU command line (serial_hd(i)); without one it
 *   has no backend (QEMU drops what it sends, nothing arrives).
 * Checked on QEMU 7.2.22 (Debian 1:7.2+dfsg-7+deb12u18) with a probe image: with every
 * NVIC enable clear, set TXEN|RXEN|TXIE|RXIE, send one byte, receive one byte, read
 * NVIC_ISPR0. UART0: TX -> 0x2 (IRQ 1), RX -> 0x1 (IRQ 0), its byte on the 1st -serial;
 * UART1: TX -> 0x8 (IRQ 3), RX -> 0x4 (IRQ 2), its byte on the 2nd -serial.
 * (The UARTs' overrun interrupts, ORed on IRQ 12, stay disabled: overruns are counted.)
 */
#ifndef MPS2_H
#define MPS2_H

#include <stdint.h>

#define MPS2_REG(addr) (*(volatile uint32_t *)(addr))

/* Core clock and the APB peripheral clock: 25 MHz on mps2 (SYSCLK_FRQ). */
#define MPS2_SYSCLK_HZ 25000000u

/* CMSDK APB UART: one register block per instance. DATA (RX/TX holding register),
 * STATE (b0 TX full, b1 RX full, b2/b3 TX/RX overrun, W1C), CTRL (b0/b1 TX/RX enable,
 * b2/b3 TX/RX interrupt enable), INTSTATUS (b0 TX, b1 RX, W1C), BAUDDIV (must be >= 16
 * when TX is enabled). */
struct mps2_uart {
    volatile uint32_t data;      /* +0x00 */
    volatile uint32_t state;     /* +0x04 */
    volatile uint32_t ctrl;      /* +0x08 */
    volatile uint32_t intstatus; /* +0x0C */
    volatile uint32_t bauddiv;   /* +0x10 */
};
#define MPS2_UART0_BASE 0x40004000u
#define MPS2_UART1_BASE 0x40005000u
#define MPS2_UART(base) ((struct mps2_uart *)(base))
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
#define MPS2_IRQ_UART1_RX 2
#define MPS2_IRQ_UART1_TX 3
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
