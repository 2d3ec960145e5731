/* startup.c - vector table and reset handler for Cortex-M4F on QEMU mps2-an386.
 * SPDX-License-Identifier: MIT
 *
 * Reset_Handler: enable the FPU (CPACR) before any floating-point instruction,
 * paint the unused stack, copy .data from flash, zero .bss, call main().
 * Build this file with -fno-tree-loop-distribute-patterns: otherwise GCC turns
 * the copy/zero loops into memcpy/memset calls, i.e. library code running
 * before .data/.bss exist (QEMU.md §7).
 */
#include "startup.h"
#include "mps2.h"

extern uint32_t _sidata, _sdata, _edata, _sbss, _ebss, _sstack, _estack;

/* The vector table as a struct: ISO C forbids mixing the initial stack pointer
 * (an object address) into an array of function pointers under -pedantic. */
/* mps2-an386 wires IRQ 0..31; the table stops at the highest one a HAL enables,
 * MPS2_IRQ_TIMER0 = 8 (the NVIC_ISER0 writes of hal_uart_cmsdk.c: UART0 RX 0, TX 1,
 * UART1 RX 2, TX 3, TIMER0 8). IRQ 9..31 stay disabled in the NVIC (their reset state),
 * so their vectors are never fetched (-92 B of flash). A port that enables a higher IRQ
 * must raise this (the static assert below ties it to the IRQ numbers of mps2.h). */
#define STARTUP_N_IRQ 9
struct startup_vectors {
    uint32_t *stack_top;
    void (*exc[15])(void);             /* vectors 1..15 */
    void (*irq[STARTUP_N_IRQ])(void);  /* vectors 16..47 */
};

void UART0RX_IRQHandler(void) __attribute__((weak, alias("Default_Handler")));
void UART0TX_IRQHandler(void) __attribute__((weak, alias("Default_Handler")));
void UART1RX_IRQHandler(void) __attribute__((weak, alias("Default_Handler")));
void UART1TX_IRQHandler(void) __attribute__((weak, alias("Default_Handler")));
void TIMER0_IRQHandler(void) __attribute__((weak, alias("Default_Handler")));
void HardFault_Handler(void) __attribute__((weak, alias("Default_Handler")));

#define D Default_Handler
__attribute__((section(".isr_vector"), used))
static const struct startup_vectors vectors = {
    &_estack,
    {
        Reset_Handler, D /* NMI */, HardFault_Handler, D /* MemManage */,
        D /* BusFault */, D /* UsageFault */, 0, 0, 0, 0,
        D /* SVCall */, D /* DebugMon */, 0, D /* PendSV */, D /* SysTick */
    },
    {
        UART0RX_IRQHandler /* 0 */, UART0TX_IRQHandler /* 1 */,
        UART1RX_IRQHandler /* 2 */, UART1TX_IRQHandler /* 3 */, D, D, D, D,
        TIMER0_IRQHandler /* 8 */
    }
};
#undef D
/* compile-time check: every IRQ the port enables has its vector (C99: no _Static_assert) */
typedef char startup_irqs_in_table[(MPS2_IRQ_UART0_RX < STARTUP_N_IRQ &&
                                    MPS2_IRQ_UART0_TX < STARTUP_N_IRQ &&
                                    MPS2_IRQ_UART1_RX < STARTUP_N_IRQ &&
                                    MPS2_IRQ_UART1_TX < STARTUP_N_IRQ &&
                                    MPS2_IRQ_TIMER0 < STARTUP_N_IRQ) ? 1 : -1];

/* An unexpected exception: stop here (a debugger shows which via IPSR). The test
 * and bench images override HardFault_Handler to report and exit (semihost.c). */
void Default_Handler(void)
{
    for (;;) {
    }
}

void Reset_Handler(void)
{
    uint32_t *s, *d, *sp;

    MPS2_SCB_CPACR |= MPS2_CPACR_FPU_FULL;
    __asm volatile("dsb\n\tisb" ::: "memory");

    /* Paint the stack below the current frame (this function's own frame and
     * anything above it are live). */
    __asm volatile("mov %0, sp" : "=r"(sp));
    for (d = &_sstack; d < sp - 8; d++) {
        *d = STARTUP_STACK_PAINT;
    }
    for (s = &_sidata, d = &_sdata; d < &_edata;) {
        *d++ = *s++;
    }
    for (d = &_sbss; d < &_ebss;) {
        *d++ = 0u;
    }
    (void)main();
    for (;;) {
    }
}

size_t startup_stack_size(void)
{
    return (size_t)((uintptr_t)&_estack - (uintptr_t)&_sstack);
}

size_t startup_stack_peak(void)
{
    const volatile uint32_t *p = &_sstack;
    while (p < &_estack && *p == STARTUP_STACK_PAINT) {
        p++;
    }
    return (size_t)((uintptr_t)&_estack - (uintptr_t)p);
}
