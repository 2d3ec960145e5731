/* proto.c - the line protocol engine (grbl-style ok / error:<code> replies).
 * SPDX-License-Identifier: MIT
 */
#include "proto.h"
#include "fmt.h"

#define PROTO_LF_OVERFLOW 0x01u /* the line exceeded CP_LINE_MAX-1 bytes */
#define PROTO_LF_BADCHAR 0x02u  /* the line held a byte outside 0x20..0x7E */

const char *cp_status_text(int code)
{
    switch (code) {
#define CP_STATUS(name, num, text) \
    case num:                      \
        return text;
#include "cp_status.def"
#undef CP_STATUS
    default:
        return "?";
    }
}

int proto_init(struct proto *p, const struct proto_cfg *cfg)
{
    if (p == NULL || cfg == NULL || cfg->uart == NULL || cfg->uart->write == NULL ||
        cfg->uart->read == NULL || cfg->uart->now_ms == NULL) {
        return CP_ERR_INVAL;
    }
    p->uart = cfg->uart;
    p->line_len = 0;
    p->line_flags = 0;
    p->last_cr = 0;
    p->rx_len = 0;
    p->rx_pos = 0;
    p->tx_len = 0;
    p->tx_pos = 0;
    p->lines_seen = 0;
    p->err = CP_OK;
    return CP_OK;
}

/* Append text to the reply buffer. The caller has checked that a whole reply
 * burst (PROTO_REPLY_MAX) fits, so this cannot fail; a failure would only
 * truncate a reply, never overrun memory. */
static void tx_str(struct proto *p, const char *s)
{
    size_t pos = p->tx_len;
    (void)fmt_str((char *)p->tx, sizeof p->tx, &pos, s);
    p->tx_len = (uint16_t)pos;
}

static void tx_u32(struct proto *p, uint32_t v)
{
    size_t pos = p->tx_len;
    (void)fmt_u32((char *)p->tx, sizeof p->tx, &pos, v);
    p->tx_len = (uint16_t)pos;
}

static void reply_status(struct proto *p, int code)
{
    if (code == CP_ST_OK) {
        tx_str(p, "ok\n");
        return;
    }
    tx_str(p, "error:");
    tx_u32(p, (uint32_t)code);
    tx_str(p, " ");
    tx_str(p, cp_status_text(code));
    tx_str(p, "\n");
}

static void reply_info(struct proto *p)
{
    tx_str(p, "[VER:canalpath " CP_FW_VERSION " proto ");
    tx_u32(p, CP_PROTO_VERSION);
    tx_str(p, "]\n[OPT:real=" CP_REAL_NAME ",line=");
    tx_u32(p, CP_LINE_MAX);
    tx_str(p, ",tx=");
    tx_u32(p, CP_TX_BUF);
    tx_str(p, ",steps=");
    tx_u32(p, CP_MAX_STEPS);
    tx_str(p, ",sub=");
    tx_u32(p, CP_MAX_SUBSTEPS);
    tx_str(p, ",lines=");
    tx_u32(p, CP_MAX_LINES);
    tx_str(p, ",link=");
    tx_u32(p, CP_MAX_LINK);
    tx_str(p, "]\n");
}

/* Case-insensitive comparison of the line with an upper-case keyword. */
static int line_is(const struct proto *p, const char *kw)
{
    uint16_t i;
    for (i = 0; i < p->line_len; i++) {
        char c = p->line[i];
        if (c >= 'a' && c <= 'z') {
            c = (char)(c - 'a' + 'A');
        }
        if (kw[i] == '\0' || kw[i] != c) {
            return 0;
        }
    }
    return kw[i] == '\0';
}

/* Execute one complete line and queue its reply. */
static void exec_line(struct proto *p)
{
    uint16_t a = 0, b = p->line_len;
    p->lines_seen++;
    if (p->line_flags & PROTO_LF_OVERFLOW) {
        reply_status(p, CP_ST_LINE_TOO_LONG);
        return;
    }
    if (p->line_flags & PROTO_LF_BADCHAR) {
        reply_status(p, CP_ST_BAD_CHAR);
        return;
    }
    /* trim spaces and tabs at both ends */
    while (a < b && (p->line[a] == ' ' || p->line[a] == '\t')) {
        a++;
    }
    while (b > a && (p->line[b - 1u] == ' ' || p->line[b - 1u] == '\t')) {
        b--;
    }
    if (a > 0u) {
        uint16_t i;
        for (i = a; i < b; i++) {
            p->line[i - a] = p->line[i];
        }
    }
    p->line_len = (uint16_t)(b - a);
    if (p->line_len == 0u) {
        reply_status(p, CP_ST_OK);
    } else if (line_is(p, "$I") || line_is(p, "HELLO")) {
        reply_info(p);
        reply_status(p, CP_ST_OK);
    } else {
        reply_status(p, CP_ST_UNKNOWN_CMD);
    }
}

/* Feed one received byte to the line assembler. Returns 1 when a line was
 * completed and executed (a reply was queued), else 0. */
static int feed(struct proto *p, uint8_t c)
{
    if (c == '\n' || c == '\r') {
        int skip = (c == '\n' && p->last_cr);
        p->last_cr = (uint8_t)(c == '\r');
        if (skip) {
            return 0;
        }
        exec_line(p);
        p->line_len = 0;
        p->line_flags = 0;
        return 1;
    }
    p->last_cr = 0;
    if (c == '\t') {
        c = ' ';
    }
    if (c < 0x20u || c > 0x7Eu) {
        p->line_flags |= PROTO_LF_BADCHAR;
        return 0;
    }
    if (p->line_len >= CP_LINE_MAX - 1) {
        p->line_flags |= PROTO_LF_OVERFLOW;
        return 0;
    }
    p->line[p->line_len++] = (char)c;
    return 0;
}

int proto_poll(struct proto *p)
{
    int moved = 0;
    int n;
    if (p->err != CP_OK) {
        return p->err;
    }
    /* 1. flush replies (non-blocking, partial writes are normal) */
    if (p->tx_pos < p->tx_len) {
        n = hal_uart_write(p->uart, p->tx + p->tx_pos, (size_t)(p->tx_len - p->tx_pos));
        if (n < 0) {
            p->err = CP_ERR_IO;
            return p->err;
        }
        p->tx_pos = (uint16_t)(p->tx_pos + (uint16_t)n);
        moved |= (n > 0);
        if (p->tx_pos == p->tx_len) {
            p->tx_pos = 0;
            p->tx_len = 0;
        }
    }
    /* 2. refill the receive chunk */
    if (p->rx_pos == p->rx_len) {
        n = hal_uart_read(p->uart, p->rx, sizeof p->rx);
        if (n < 0) {
            p->err = CP_ERR_IO;
            return p->err;
        }
        p->rx_len = (uint8_t)n;
        p->rx_pos = 0;
        moved |= (n > 0);
    }
    /* 3. consume bytes while a whole reply burst still fits (back-pressure:
     *    unread bytes stay in the HAL/kernel buffer, nothing is dropped) */
    while (p->rx_pos < p->rx_len) { /* bounded by sizeof rx */
        if (p->tx_len + PROTO_REPLY_MAX > CP_TX_BUF) {
            if (p->tx_pos == 0u) {
                break;
            }
            /* compact the unsent tail to the front */
            {
                uint16_t i, k = (uint16_t)(p->tx_len - p->tx_pos);
                for (i = 0; i < k; i++) {
                    p->tx[i] = p->tx[p->tx_pos + i];
                }
                p->tx_len = k;
                p->tx_pos = 0;
            }
            if (p->tx_len + PROTO_REPLY_MAX > CP_TX_BUF) {
                break;
            }
        }
        (void)feed(p, p->rx[p->rx_pos++]);
        moved = 1;
    }
    return moved;
}
