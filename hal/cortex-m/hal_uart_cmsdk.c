/* hal_uart_cmsdk.c - CMSDK UART0 (IRQ-driven RX ring, non-blocking TX) + TIMER0 milliseconds.
 * SPDX-License-Identifier: MIT
 */
#include "hal_uart_cmsdk.h"
#include "mps2.h"
#include "startup.h"

#define RING_MASK ((uint8_t)(HAL_UART_CMSDK_RX_RING - 1))
#define TICKS_PER_MS (MPS2_SYSCLK_HZ / 1000u)
#define UART_BAUD 115200u

static struct hal_uart_cmsdk *port; /* the one instance, for the ISRs */

/* Move bytes from the holding register into the ring. Runs in the RX ISR or in
 * read() with PRIMASK set. The RX interrupt flag is cleared BEFORE draining: a
 * byte landing after the clear raises it again, whereas clearing after the
 * drain could swallow that byte's interrupt and deadlock a WFI loop (QEMU.md §7).
 * With the ring full the byte stays in the UART and RXIE is masked (back-pressure);
 * read() re-runs this after making room. */
static void rx_drain(struct hal_uart_cmsdk *s)
{
    uint8_t head = s->rx_head;
    MPS2_UART0_INTSTATUS = MPS2_UART_INT_RX;
    if (MPS2_UART0_STATE & MPS2_UART_STATE_RXOVR) {
        MPS2_UART0_STATE = MPS2_UART_STATE_RXOVR;
        s->rx_overruns++;
    }
    while (MPS2_UART0_STATE & MPS2_UART_STATE_RXFULL) { /* bounded: ring size */
        if ((uint8_t)((head + 1u) & RING_MASK) == s->rx_tail) {
            MPS2_UART0_CTRL &= ~MPS2_UART_CTRL_RXIE;
            s->rx_head = head;
            return;
        }
        s->rx[head] = (uint8_t)MPS2_UART0_DATA;
        head = (uint8_t)((head + 1u) & RING_MASK);
    }
    s->rx_head = head;
    MPS2_UART0_CTRL |= MPS2_UART_CTRL_RXIE;
}

/* TIMER0 reloads every TIMER_PERIOD ticks (10 ms): its interrupt wakes the main loop
 * from WFI, so the protocol's timeouts (resend quiet time, FRAMES retransmission, peer
 * timeout) run on time even when the line is silent. */
#define TIMER_PERIOD (TICKS_PER_MS * 10u)

/* Fold the TIMER0 ticks elapsed since the last update into ms. Exact as long as it
 * runs at least once per period (10 ms): the period ISR guarantees that, and the
 * PRIMASK sections that may delay it are a few instructions long.
 * Runs with PRIMASK set or in the TIMER0 ISR. */
static void time_update(struct hal_uart_cmsdk *s)
{
    uint32_t now = MPS2_TIMER0_VALUE;
    /* down-counter from TIMER_PERIOD - 1 to 0, then reload: one wrap at most */
    uint32_t delta = now <= s->tick_last ? s->tick_last - now : s->tick_last + (TIMER_PERIOD - now);
    s->tick_last = now;
    s->ms += delta / TICKS_PER_MS;
    s->tick_frac += delta % TICKS_PER_MS;
    if (s->tick_frac >= TICKS_PER_MS) {
        s->tick_frac -= TICKS_PER_MS;
        s->ms++;
    }
}

void UART0RX_IRQHandler(void)
{
    rx_drain(port);
    port->event = 1u;
}

void UART0TX_IRQHandler(void)
{
    MPS2_UART0_INTSTATUS = MPS2_UART_INT_TX;
    MPS2_UART0_CTRL &= ~MPS2_UART_CTRL_TXIE;
    port->event = 1u;
}

void TIMER0_IRQHandler(void)
{
    MPS2_TIMER0_INTSTATUS = 1u;
    time_update(port);
    port->event = 1u;
}

static int cmsdk_write(void *ctx, const uint8_t *buf, size_t len)
{
    struct hal_uart_cmsdk *s = ctx;
    size_t n = 0;
    while (n < len && !(MPS2_UART0_STATE & MPS2_UART_STATE_TXFULL)) {
        MPS2_UART0_DATA = buf[n++];
    }
    if (n < len) {
        /* Wake the main loop when the holding register empties. The UART raises
         * the TX flag only if TXIE is set at the moment the byte leaves, so
         * re-check after arming: if it already left, report the event ourselves. */
        MPS2_UART0_CTRL |= MPS2_UART_CTRL_TXIE;
        if (!(MPS2_UART0_STATE & MPS2_UART_STATE_TXFULL)) {
            s->event = 1u;
        }
    }
    return (int)n;
}

static int cmsdk_read(void *ctx, uint8_t *buf, size_t cap)
{
    struct hal_uart_cmsdk *s = ctx;
    size_t n = 0;
    uint8_t tail = s->rx_tail;
    mps2_irq_off();
    while (n < cap && tail != s->rx_head) {
        buf[n++] = s->rx[tail];
        tail = (uint8_t)((tail + 1u) & RING_MASK);
    }
    s->rx_tail = tail;
    if (n > 0u) {
        rx_drain(s); /* refill from the holding register, unmask RX */
    }
    mps2_irq_on();
    return (int)n;
}

static uint32_t cmsdk_now_ms(void *ctx)
{
    struct hal_uart_cmsdk *s = ctx;
    uint32_t ms;
    mps2_irq_off();
    time_update(s);
    ms = s->ms;
    mps2_irq_on();
    return ms;
}

void hal_uart_cmsdk_init(struct hal_uart_cmsdk *s, struct hal_uart *u)
{
    const uint32_t irqs = (1u << MPS2_IRQ_UART0_RX) | (1u << MPS2_IRQ_UART0_TX) |
                          (1u << MPS2_IRQ_TIMER0);
    mps2_irq_off();
    port = s;
    s->rx_head = 0u;
    s->rx_tail = 0u;
    s->event = 0u;
    s->rx_overruns = 0u;
    s->tick_frac = 0u;
    s->ms = 0u;

    MPS2_TIMER0_CTRL = 0u;
    MPS2_TIMER0_RELOAD = TIMER_PERIOD - 1u;
    MPS2_TIMER0_VALUE = TIMER_PERIOD - 1u;
    MPS2_TIMER0_INTSTATUS = 1u;
    MPS2_TIMER0_CTRL = MPS2_TIMER_CTRL_EN | MPS2_TIMER_CTRL_IE;
    s->tick_last = MPS2_TIMER0_VALUE;

    MPS2_UART0_CTRL = 0u;
    MPS2_UART0_BAUDDIV = MPS2_SYSCLK_HZ / UART_BAUD; /* 217 >= 16 */
    MPS2_UART0_STATE = MPS2_UART_STATE_RXOVR | MPS2_UART_STATE_TXOVR;
    MPS2_UART0_INTSTATUS = MPS2_UART_INT_RX | MPS2_UART_INT_TX;
    MPS2_UART0_CTRL = MPS2_UART_CTRL_TXEN | MPS2_UART_CTRL_RXEN | MPS2_UART_CTRL_RXIE;

    MPS2_NVIC_ICPR0 = irqs;
    MPS2_NVIC_ISER0 = irqs;

    u->ctx = s;
    u->write = cmsdk_write;
    u->read = cmsdk_read;
    u->now_ms = cmsdk_now_ms;
    rx_drain(s); /* a byte that arrived before RXIE was set raised no interrupt */
    mps2_irq_on();
}

void hal_uart_cmsdk_sleep(struct hal_uart_cmsdk *s)
{
    mps2_irq_off();
    if (s->event) {
        s->event = 0u;
    } else {
        mps2_wfi();
    }
    mps2_irq_on();
}
