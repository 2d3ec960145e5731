/* hal_fault.h - fault-injecting wrapper around any struct hal_uart (tests, host and target).
 * SPDX-License-Identifier: MIT
 *
 * hal_fault_init(f, &outer, inner) makes `outer` a hal_uart that passes every call
 * through to `inner`, except for ONE fault armed with hal_fault_arm(): at byte
 * index `at` (0-based, counted in the original stream of that direction: bytes
 * the firmware offered for TX, bytes the inner port delivered for RX) it
 *   HAL_FAULT_DROP      loses the byte (TX: accepted but not sent; RX: not delivered)
 *   HAL_FAULT_FLIP      delivers byte ^ arg (arg = xor mask, 0 is taken as 0x01)
 *   HAL_FAULT_DUP       delivers the byte twice
 *   HAL_FAULT_TRUNCATE  ends the call just before the byte: a short write/read
 *                       (returns 0 if the byte is the first of the call); no data
 *                       is lost, it only exercises partial I/O at that index
 *   HAL_FAULT_FAIL      passes the bytes before it, then returns CP_ERR_IO from
 *                       that byte on, for every call in that direction (sticky)
 * The other direction and now_ms() are untouched. A call never crosses the fault
 * index: it is split there (a partial read/write, legal under hal_uart.h), so the
 * fault is applied exactly once at exactly that byte. Errors of the inner port are
 * passed through unchanged.
 * Pure C99, no allocation: runs on the host and in the Cortex-M unit image.
 */
#ifndef HAL_FAULT_H
#define HAL_FAULT_H

#include "cp_types.h"
#include "hal_uart.h"

enum hal_fault_mode {
    HAL_FAULT_NONE = 0,
    HAL_FAULT_DROP = 1,
    HAL_FAULT_FLIP = 2,
    HAL_FAULT_DUP = 3,
    HAL_FAULT_TRUNCATE = 4,
    HAL_FAULT_FAIL = 5
};

enum hal_fault_dir {
    HAL_FAULT_RX = 0, /* link -> firmware (read) */
    HAL_FAULT_TX = 1  /* firmware -> link (write) */
};

struct hal_fault {
    const struct hal_uart *inner; /* the wrapped port */
    uint8_t mode;                 /* enum hal_fault_mode */
    uint8_t dir;                  /* enum hal_fault_dir */
    uint8_t mask;                 /* FLIP: xor mask */
    uint8_t done;                 /* 1 once the fault was applied */
    uint32_t at;                  /* byte index of the fault in the faulted direction */
    /* the pending second copy of a duplicated byte */
    uint8_t owe;                  /* 1: `owed` must still be delivered (before anything else) */
    uint8_t owed;
    /* counters */
    uint32_t rx_seen;             /* RX bytes taken from the inner port */
    uint32_t rx_given;            /* RX bytes handed to the caller */
    uint32_t tx_seen;             /* TX bytes taken from the caller (accepted) */
    uint32_t tx_sent;             /* TX bytes handed to the inner port */
    uint32_t faults;              /* faults applied (0 or 1; FAIL: failing calls) */
    uint32_t calls;               /* read + write calls */
};

/* Reset f (no fault armed, counters 0) and point outer at it. inner must stay valid. */
void hal_fault_init(struct hal_fault *f, struct hal_uart *outer, const struct hal_uart *inner);

/* Arm one fault (replaces a previous one; counters are kept). mode HAL_FAULT_NONE
 * disarms. arg: the FLIP xor mask (ignored otherwise). */
void hal_fault_arm(struct hal_fault *f, enum hal_fault_mode mode, enum hal_fault_dir dir,
                   uint32_t at, uint8_t arg);

/* Name of a mode ("drop", "flip", ...), for messages. */
const char *hal_fault_name(enum hal_fault_mode mode);

#endif /* HAL_FAULT_H */
