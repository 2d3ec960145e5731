/* hal_mem.h - in-memory loopback port of hal_uart for tests (host and target).
 * SPDX-License-Identifier: MIT
 *
 * The test writes what the "host" sends into in[] (hal_mem_feed) and reads what
 * the firmware sent from out[]. read/write move at most *_chunk bytes per call
 * (0 = unlimited) to exercise partial I/O. After hal_mem_hangup() both calls
 * return CP_ERR_IO. now_ms() returns `now`, advanced by `tick_ms` per call.
 */
#ifndef HAL_MEM_H
#define HAL_MEM_H

#include "cp_types.h"
#include "hal_uart.h"

#define HAL_MEM_IN 4096
#define HAL_MEM_OUT 16384

struct hal_mem {
    uint8_t in[HAL_MEM_IN];
    size_t in_len, in_pos;
    uint8_t out[HAL_MEM_OUT];
    size_t out_len;
    size_t read_chunk, write_chunk; /* max bytes per call, 0 = unlimited */
    uint32_t now, tick_ms;
    int hangup;
};

/* Reset m and point u at it. */
void hal_mem_init(struct hal_mem *m, struct hal_uart *u);
/* Append n bytes (host -> firmware), compacting in[] first if needed. Returns 0,
 * or -1 if the unread bytes and n do not fit in in[]. */
int hal_mem_feed(struct hal_mem *m, const void *data, size_t n);
/* Append a NUL-terminated string (host -> firmware). */
int hal_mem_feed_str(struct hal_mem *m, const char *s);
/* Drop everything the firmware has sent so far. */
void hal_mem_clear_out(struct hal_mem *m);
/* From now on the link is gone: read and write return CP_ERR_IO. */
void hal_mem_hangup(struct hal_mem *m);

#endif /* HAL_MEM_H */
