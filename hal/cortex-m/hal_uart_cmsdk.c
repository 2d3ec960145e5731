/* hal_uart_cmsdk.c - CMSDK UART0/UART1 (IRQ-driven RX ring, non-blocking TX) + TIMER0 milliseconds.
 * SPDX-License-Identifier: MIT
 */
#include "hal_uart_cmsdk.h"
#include "mps2.h"
#include "startup.h"

#define RING_MASK ((uint8_t)(HAL_UART_CMSDK_RX_RING - 1))
#define TICKS_PER_MS (MPS2_SYSCLK_HZ / 1000u)
#define UART_BAUD 115200u

/* The board wiring of each unit (mps2.h). */
struct unit_wiring {
    uint32_t base;  /* register block */
    uint8_t irq_rx; /* NVIC line of its RX interrupt */
    uint8_t irq_tx; /* NVIC line of its TX interrupt */
};

static const struct unit_wiring wiring[HAL_UART_CMSDK_UNITS] = {
    {MPS2_UART0_BASE, MPS2_IRQ_UART0_RX, MPS2_IRQ_UART0_TX},
    {MPS2_UART1_BASE, MPS2_IRQ_UART1_RX, MPS2_IRQ_UART1_TX},
};

static struct hal_uart_cmsdk *units[HAL_UART_CMSDK_UNITS]; /* for the ISRs */

/* Set by every ISR (both units, the clock) and by a write() that finds its byte gone;
 * consumed by hal_uart_cmsdk_sleep(). */
static volatile uint8_t event;

/* The port's one clock (TIMER0), read by every unit's now_ms(). */
static struct {
    uint32_t tick_last; /* TIMER0 value at the last time update, ticks */
    uint32_t tick_frac; /* ticks not yet counted as a whole ms (0..24999) */
    uint32_t ms;        /* milliseconds since hal_uart_cmsdk_clock_init, wraps at 2^32 */
} port_clock;

/* Move bytes from the holding register into the ring. Runs in the unit's RX ISR or in
 * read() with PRIMASK set. The RX interrupt flag is cleared BEFORE draining: a
 * byte landing after the clear raises it again, whereas clearing after the
 * drain could swallow that byte's interrupt and deadlock a WFI loop (QEMU.md §7).
 * With the ring full the byte stays in the UART and RXIE is masked (back-pressure);
 * read() re-runs this after making room. */
static void rx_drain(struct hal_uart_cmsdk *s)
{
    struct mps2_uart *r = s->regs;
    uint8_t head = s->rx_head;
    r->intstatus = MPS2_UART_INT_RX;
    if (r->state & MPS2_UART_STATE_RXOVR) {
        r->state = MPS2_UART_STATE_RXOVR;
        s->rx_overruns++;
    }
    while (r->state & MPS2_UART_STATE_RXFULL) { /* bounded: ring size */
        if ((uint8_t)((head + 1u) & RING_MASK) == s->rx_tail) {
            r->ctrl &= ~MPS2_UART_CTRL_RXIE;
            s->rx_head = head;
            return;
        }
        s->rx[head] = (uint8_t)r->data;
        head = (uint8_t)((head + 1u) & RING_MASK);
    }
    s->rx_head = head;
    r->ctrl |= MPS2_UART_CTRL_RXIE;
}

/* TX interrupt: the holding register emptied after a short write(). Only a wake-up. */
static void tx_done(struct hal_uart_cmsdk *s)
{
    s->regs->intstatus = MPS2_UART_INT_TX;
    s->regs->ctrl &= ~MPS2_UART_CTRL_TXIE;
}

/* TIMER0 reloads every TIMER_PERIOD ticks (10 ms): its interrupt wakes the main loop
 * from WFI, so the protocol's timeouts (resend quiet time, FRAMES retransmission, peer
 * timeout) run on time even when the lines are silent. */
#define TIMER_PERIOD (TICKS_PER_MS * 10u)

/* Fold the TIMER0 ticks elapsed since the last update into port_clock.ms. Exact as long as
 * it runs at least once per period (10 ms): the period ISR guarantees that, and the
 * PRIMASK sections that may delay it are a few instructions long.
 * Runs with PRIMASK set or in the TIMER0 ISR. */
static void time_update(void)
{
    uint32_t now = MPS2_TIMER0_VALUE;
    uint32_t last = port_clock.tick_last;
    /* down-counter from TIMER_PERIOD - 1 to 0, then reload: one wrap at most */
    uint32_t delta = now <= last ? last - now : last + (TIMER_PERIOD - now);
    port_clock.tick_last = now;
    port_clock.ms += delta / TICKS_PER_MS;
    port_clock.tick_frac += delta % TICKS_PER_MS;
    if (port_clock.tick_frac >= TICKS_PER_MS) {
        port_clock.tick_frac -= TICKS_PER_MS;
        port_clock.ms++;
    }
}

void UART0RX_IRQHandler(void)
{
    rx_drain(units[0]);
    event = 1u;
}

void UART0TX_IRQHandler(void)
{
    tx_done(units[0]);
    event = 1u;
}

void UART1RX_IRQHandler(void)
{
    rx_drain(units[1]);
    event = 1u;
}

void UART1TX_IRQHandler(void)
{
    tx_done(units[1]);
    event = 1u;
}

void TIMER0_IRQHandler(void)
{
    MPS2_TIMER0_INTSTATUS = 1u;
    time_update();
    event = 1u;
}

static int cmsdk_write(void *ctx, const uint8_t *buf, size_t len)
{
    struct hal_uart_cmsdk *s = ctx;
    struct mps2_uart *r = s->regs;
    size_t n = 0;
    while (n < len && !(r->state & MPS2_UART_STATE_TXFULL)) {
        r->data = buf[n++];
    }
    if (n < len) {
        /* Wake the main loop when the holding register empties. The UART raises
         * the TX flag only if TXIE is set at the moment the byte leaves, so
         * re-check after arming: if it already left, report the event ourselves. */
        r->ctrl |= MPS2_UART_CTRL_TXIE;
        if (!(r->state & MPS2_UART_STATE_TXFULL)) {
            event = 1u;
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

/* The same clock for every unit: ctx is not used. */
static uint32_t cmsdk_now_ms(void *ctx)
{
    uint32_t ms;
    (void)ctx;
    mps2_irq_off();
    time_update();
    ms = port_clock.ms;
    mps2_irq_on();
    return ms;
}

void hal_uart_cmsdk_clock_init(void)
{
    const uint32_t irq = 1u << MPS2_IRQ_TIMER0;
    mps2_irq_off();
    port_clock.tick_frac = 0u;
    port_clock.ms = 0u;
    MPS2_TIMER0_CTRL = 0u;
    MPS2_TIMER0_RELOAD = TIMER_PERIOD - 1u;
    MPS2_TIMER0_VALUE = TIMER_PERIOD - 1u;
    MPS2_TIMER0_INTSTATUS = 1u;
    MPS2_TIMER0_CTRL = MPS2_TIMER_CTRL_EN | MPS2_TIMER_CTRL_IE;
    port_clock.tick_last = MPS2_TIMER0_VALUE;
    MPS2_NVIC_ICPR0 = irq;
    MPS2_NVIC_ISER0 = irq;
    mps2_irq_on();
}

void hal_uart_cmsdk_init(struct hal_uart_cmsdk *s, struct hal_uart *u, unsigned unit)
{
    const struct unit_wiring *w;
    struct mps2_uart *r;
    uint32_t irqs;
    if (unit >= HAL_UART_CMSDK_UNITS) {
        return;
    }
    w = &wiring[unit];
    r = MPS2_UART(w->base);
    irqs = (1u << w->irq_rx) | (1u << w->irq_tx);
    mps2_irq_off();
    units[unit] = s;
    s->regs = r;
    s->rx_head = 0u;
    s->rx_tail = 0u;
    s->rx_overruns = 0u;

    r->ctrl = 0u;
    r->bauddiv = MPS2_SYSCLK_HZ / UART_BAUD; /* 217 >= 16 */
    r->state = MPS2_UART_STATE_RXOVR | MPS2_UART_STATE_TXOVR;
    r->intstatus = MPS2_UART_INT_RX | MPS2_UART_INT_TX;
    r->ctrl = MPS2_UART_CTRL_TXEN | MPS2_UART_CTRL_RXEN | MPS2_UART_CTRL_RXIE;

    MPS2_NVIC_ICPR0 = irqs;
    MPS2_NVIC_ISER0 = irqs;

    u->ctx = s;
    u->write = cmsdk_write;
    u->read = cmsdk_read;
    u->now_ms = cmsdk_now_ms;
    rx_drain(s); /* a byte that arrived before RXIE was set raised no interrupt */
    mps2_irq_on();
}

void hal_uart_cmsdk_sleep(void)
{
    mps2_irq_off();
    if (event) {
        event = 0u;
    } else {
        mps2_wfi();
    }
    mps2_irq_on();
}
