/* startup.h - reset, vector table and stack-paint interface of the Cortex-M4F port.
 * SPDX-License-Identifier: MIT
 *
 * The handler names are the CMSIS device-vector names (the one exception to
 * the prefix rule: every Cortex-M engineer greps for them). Each IRQ handler
 * is a weak alias of Default_Handler in startup.c; a driver overrides one by
 * defining a function of the same name.
 *
 * Symbols from the linker script (linker/cortex_m_common.ld):
 *   _sstack .. _estack   the stack region, CP_STACK bytes, at the bottom of RAM
 *                        (an overflow leaves RAM, a fault where nothing is
 *                        mapped below it, instead of corrupting .data/.bss)
 *   _sidata              load address of .data in flash
 *   _sdata .. _edata     .data in RAM;   _sbss .. _ebss   .bss in RAM
 */
#ifndef STARTUP_H
#define STARTUP_H

#include <stddef.h>
#include <stdint.h>

/* Word painted over the unused stack at reset (for startup_stack_peak). */
#define STARTUP_STACK_PAINT 0xC0FFEE55u

void Reset_Handler(void);
void Default_Handler(void);
void HardFault_Handler(void);
void UART0RX_IRQHandler(void);
void UART0TX_IRQHandler(void);
void UART1RX_IRQHandler(void);
void UART1TX_IRQHandler(void);
void TIMER0_IRQHandler(void);

/* The application entry, called by Reset_Handler with .data/.bss ready and the FPU on. */
int main(void);

/* Size of the stack region in bytes (the linker's CP_STACK). */
size_t startup_stack_size(void);

/* High-water mark of the main stack in bytes since reset: the stack region is
 * painted with STARTUP_STACK_PAINT before main() runs, and this scans for the
 * deepest overwritten word. Exact to 4 bytes unless a frame happened to store
 * the paint value itself. Cost: one pass over the unused part of the region. */
size_t startup_stack_peak(void);

#endif /* STARTUP_H */
