/* hal_fault.c - fault-injecting wrapper around any struct hal_uart.
 * SPDX-License-Identifier: MIT
 */
#include "hal_fault.h"

/* 1 if the armed fault concerns direction dir and is still due. */
static int fault_due(const struct hal_fault *f, uint8_t dir)
{
    if (f->mode == HAL_FAULT_NONE || f->dir != dir) {
        return 0;
    }
    return !f->done || f->mode == HAL_FAULT_FAIL;
}

/* Bytes before the fault index in a stream where `seen` bytes have passed. */
static uint32_t fault_gap(const struct hal_fault *f, uint32_t seen)
{
    return f->at > seen ? f->at - seen : 0u;
}

static int fault_write(void *ctx, const uint8_t *buf, size_t len)
{
    struct hal_fault *f = ctx;
    uint32_t k;
    uint8_t b;
    int r;
    f->calls++;
    if (f->owe && f->dir == HAL_FAULT_TX) { /* the second copy of a duplicated byte */
        r = hal_uart_write(f->inner, &f->owed, 1u);
        if (r <= 0) {
            return r;
        }
        f->owe = 0;
        f->tx_sent++;
    }
    if (len == 0u) {
        return 0;
    }
    if (!fault_due(f, HAL_FAULT_TX) || (uint32_t)len <= fault_gap(f, f->tx_seen)) {
        r = hal_uart_write(f->inner, buf, len);
        if (r > 0) {
            f->tx_seen += (uint32_t)r;
            f->tx_sent += (uint32_t)r;
        }
        return r;
    }
    k = fault_gap(f, f->tx_seen);
    if (f->mode == HAL_FAULT_FAIL && k == 0u) {
        f->faults++;
        return CP_ERR_IO;
    }
    if (k > 0u) { /* split the call at the fault index */
        r = hal_uart_write(f->inner, buf, k);
        if (r > 0) {
            f->tx_seen += (uint32_t)r;
            f->tx_sent += (uint32_t)r;
        }
        if (f->mode == HAL_FAULT_TRUNCATE && r == (int)k) {
            f->done = 1;
            f->faults++;
        }
        return r;
    }
    switch (f->mode) {
    case HAL_FAULT_DROP:
        f->done = 1;
        f->faults++;
        f->tx_seen++;
        return 1;
    case HAL_FAULT_FLIP:
        b = (uint8_t)(buf[0] ^ f->mask);
        r = hal_uart_write(f->inner, &b, 1u);
        if (r <= 0) {
            return r;
        }
        break;
    case HAL_FAULT_DUP:
        r = hal_uart_write(f->inner, buf, 1u);
        if (r <= 0) {
            return r;
        }
        f->owe = 1;
        f->owed = buf[0];
        if (hal_uart_write(f->inner, &f->owed, 1u) == 1) {
            f->owe = 0;
            f->tx_sent++;
        }
        break;
    default: /* HAL_FAULT_TRUNCATE at the first byte of the call */
        f->done = 1;
        f->faults++;
        return 0;
    }
    f->done = 1;
    f->faults++;
    f->tx_seen++;
    f->tx_sent++;
    return 1;
}

static int fault_read(void *ctx, uint8_t *buf, size_t cap)
{
    struct hal_fault *f = ctx;
    uint32_t k;
    int r;
    f->calls++;
    if (cap == 0u) {
        return 0;
    }
    if (f->owe && f->dir == HAL_FAULT_RX) {
        buf[0] = f->owed;
        f->owe = 0;
        f->rx_given++;
        return 1;
    }
    if (!fault_due(f, HAL_FAULT_RX)) {
        goto pass;
    }
    k = fault_gap(f, f->rx_seen);
    if (f->mode == HAL_FAULT_FAIL && k == 0u) {
        f->faults++;
        return CP_ERR_IO;
    }
    if (k > 0u) { /* never read past the fault index in one call */
        if ((uint32_t)cap > k) {
            cap = k;
        }
        r = hal_uart_read(f->inner, buf, cap);
        if (r > 0) {
            f->rx_seen += (uint32_t)r;
            f->rx_given += (uint32_t)r;
        }
        if (f->mode == HAL_FAULT_TRUNCATE && r == (int)k) {
            f->done = 1;
            f->faults++;
        }
        return r;
    }
    if (f->mode == HAL_FAULT_TRUNCATE) {
        f->done = 1;
        f->faults++;
        return 0;
    }
    r = hal_uart_read(f->inner, buf, 1u);
    if (r <= 0) {
        return r;
    }
    f->rx_seen++;
    f->done = 1;
    f->faults++;
    switch (f->mode) {
    case HAL_FAULT_DROP:
        goto pass; /* the byte is gone; deliver what follows it */
    case HAL_FAULT_FLIP:
        buf[0] = (uint8_t)(buf[0] ^ f->mask);
        f->rx_given++;
        return 1;
    default: /* HAL_FAULT_DUP */
        if (cap >= 2u) {
            buf[1] = buf[0];
            f->rx_given += 2u;
            return 2;
        }
        f->owe = 1;
        f->owed = buf[0];
        f->rx_given++;
        return 1;
    }
pass:
    r = hal_uart_read(f->inner, buf, cap);
    if (r > 0) {
        f->rx_seen += (uint32_t)r;
        f->rx_given += (uint32_t)r;
    }
    return r;
}

static uint32_t fault_now(void *ctx)
{
    struct hal_fault *f = ctx;
    return hal_uart_now_ms(f->inner);
}

void hal_fault_init(struct hal_fault *f, struct hal_uart *outer, const struct hal_uart *inner)
{
    f->inner = inner;
    f->mode = HAL_FAULT_NONE;
    f->dir = HAL_FAULT_RX;
    f->mask = 0x01u;
    f->done = 0;
    f->at = 0;
    f->owe = 0;
    f->owed = 0;
    f->rx_seen = 0;
    f->rx_given = 0;
    f->tx_seen = 0;
    f->tx_sent = 0;
    f->faults = 0;
    f->calls = 0;
    outer->ctx = f;
    outer->write = fault_write;
    outer->read = fault_read;
    outer->now_ms = fault_now;
}

void hal_fault_arm(struct hal_fault *f, enum hal_fault_mode mode, enum hal_fault_dir dir,
                   uint32_t at, uint8_t arg)
{
    f->mode = (uint8_t)mode;
    f->dir = (uint8_t)dir;
    f->at = at;
    f->mask = arg != 0u ? arg : 0x01u;
    f->done = 0;
    f->owe = 0;
}

const char *hal_fault_name(enum hal_fault_mode mode)
{
    switch (mode) {
    case HAL_FAULT_NONE:
        return "none";
    case HAL_FAULT_DROP:
        return "drop";
    case HAL_FAULT_FLIP:
        return "flip";
    case HAL_FAULT_DUP:
        return "dup";
    case HAL_FAULT_TRUNCATE:
        return "truncate";
    case HAL_FAULT_FAIL:
        return "fail";
    default:
        return "?";
    }
}
