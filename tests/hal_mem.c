/* hal_mem.c - in-memory loopback port of hal_uart for tests.
 * SPDX-License-Identifier: MIT
 */
#include <string.h>

#include "hal_mem.h"

static int mem_write(void *ctx, const uint8_t *buf, size_t len)
{
    struct hal_mem *m = ctx;
    size_t n = len;
    if (m->hangup) {
        return CP_ERR_IO;
    }
    if (m->write_chunk != 0 && n > m->write_chunk) {
        n = m->write_chunk;
    }
    if (n > HAL_MEM_OUT - m->out_len) {
        n = HAL_MEM_OUT - m->out_len;
    }
    memcpy(m->out + m->out_len, buf, n);
    m->out_len += n;
    return (int)n;
}

static int mem_read(void *ctx, uint8_t *buf, size_t cap)
{
    struct hal_mem *m = ctx;
    size_t n = m->in_len - m->in_pos;
    if (m->hangup) {
        return CP_ERR_IO;
    }
    if (n > cap) {
        n = cap;
    }
    if (m->read_chunk != 0 && n > m->read_chunk) {
        n = m->read_chunk;
    }
    memcpy(buf, m->in + m->in_pos, n);
    m->in_pos += n;
    return (int)n;
}

static uint32_t mem_now(void *ctx)
{
    struct hal_mem *m = ctx;
    m->now += m->tick_ms;
    return m->now;
}

void hal_mem_init(struct hal_mem *m, struct hal_uart *u)
{
    memset(m, 0, sizeof *m);
    u->ctx = m;
    u->write = mem_write;
    u->read = mem_read;
    u->now_ms = mem_now;
}

int hal_mem_feed(struct hal_mem *m, const void *data, size_t n)
{
    if (n > HAL_MEM_IN - m->in_len && m->in_pos > 0) {
        /* compact: drop the bytes the firmware has already read */
        memmove(m->in, m->in + m->in_pos, m->in_len - m->in_pos);
        m->in_len -= m->in_pos;
        m->in_pos = 0;
    }
    if (n > HAL_MEM_IN - m->in_len) {
        return -1;
    }
    memcpy(m->in + m->in_len, data, n);
    m->in_len += n;
    return 0;
}

int hal_mem_feed_str(struct hal_mem *m, const char *s)
{
    return hal_mem_feed(m, s, strlen(s));
}

void hal_mem_clear_out(struct hal_mem *m)
{
    m->out_len = 0;
}

void hal_mem_hangup(struct hal_mem *m)
{
    m->hangup = 1;
}
