/* machine.c - machine dialects, answers and the machine link (machine.h).
 * SPDX-License-Identifier: MIT
 */
#include "machine.h"
#include "parse.h"

static const struct machine_dialect dialects[JOB_MACHINES] = {
#define CP_MACHINE(NAME, WORD, RXBUF, LINE_MAX, ACKS, CHECKSUM, SPLIT, POLL, END, AC, IJK)                   \
    [JOB_MACHINE_##NAME] = {RXBUF, LINE_MAX, ACKS, CHECKSUM, SPLIT, POLL, END, AC, IJK},
#include "machines.def"
#undef CP_MACHINE
};

const struct machine_dialect *machine_dialect(unsigned m)
{
    return &dialects[m < (unsigned)JOB_MACHINES ? m : (unsigned)JOB_MACHINE_GENERIC];
}

/* The length of the NUL-terminated w (not empty) if line[0..len) starts with it, else 0. */
static size_t starts(const char *line, size_t len, const char *w)
{
    size_t i = 0;
    while (w[i] != '\0') {
        if (i >= len || line[i] != w[i]) {
            return 0;
        }
        i++;
    }
    return i;
}

/* 1 if line[0..len) contains the NUL-terminated w (len and w are short: a line). */
static int contains(const char *line, size_t len, const char *w)
{
    size_t i;
    for (i = 0; i < len; i++) {
        if (starts(line + i, len - i, w) != 0u) {
            return 1;
        }
    }
    return 0;
}

/* "Resend: n" / "Resend:n" / "rs n" (and Marlin's "rs N<n>"): the number after the prefix;
 * UINT32_MAX when none parses (a line never sent: the run stops). */
static uint32_t resend_number(const char *s, size_t len)
{
    uint32_t n = 0;
    size_t a = 0, b;
    while (a < len && (s[a] == ' ' || s[a] == 'N')) {
        a++;
    }
    b = a;
    while (b < len && s[b] >= '0' && s[b] <= '9') {
        b++;
    }
    if (b == a || parse_uint(s + a, b - a, UINT32_MAX, &n) != CP_ST_OK) {
        return UINT32_MAX;
    }
    return n;
}

/* The answers known by how they start (machine.h), tried in this order. Marlin's
 * "Error:" is a RETRY only when it names the "Last Line" (its line-number and checksum
 * errors: a Resend follows); any other Error: (kill(), MINTEMP, ...) stops the machine. */
static const struct {
    const char *start;
    uint8_t kind; /* enum machine_reply */
} answers[] = {
    {"error:", MACHINE_ERROR},     {"ALARM:", MACHINE_ALARM},   {"!!", MACHINE_ALARM},
    {"Error:", MACHINE_RETRY},     {"Resend:", MACHINE_RESEND}, {"rs ", MACHINE_RESEND},
    {"echo:busy:", MACHINE_ALIVE}, {"busy:", MACHINE_ALIVE},    {"Grbl ", MACHINE_RESET},
};

enum machine_reply machine_reply(unsigned m, const char *line, size_t len, uint32_t *num)
{
    size_t i, n;
    *num = 0u;
    if (len == 2u && starts(line, len, "ok") != 0u) {
        return MACHINE_OK;
    }
    /* Marlin's ok carries ADVANCED_OK's " N<n> P<p> B<b>" or a temperature report; grbl's
     * is the whole line, and grbl sends no other line starting "ok " */
    if (m != (unsigned)JOB_MACHINE_GRBL && starts(line, len, "ok ") != 0u) {
        return MACHINE_OK;
    }
    for (i = 0; i < sizeof answers / sizeof answers[0]; i++) {
        n = starts(line, len, answers[i].start);
        if (n == 0u) {
            continue;
        }
        switch ((enum machine_reply)answers[i].kind) {
        case MACHINE_RETRY:
            return contains(line, len, "Last Line") ? MACHINE_RETRY : MACHINE_ERROR;
        case MACHINE_RESEND:
            *num = resend_number(line + n, len - n);
            return MACHINE_RESEND;
        default:
            return (enum machine_reply)answers[i].kind;
        }
    }
    if (len >= 2u && line[0] == '<' && line[len - 1u] == '>') {
        return MACHINE_ALIVE; /* grbl's status report */
    }
    if (len == 5u && starts(line, len, "start") != 0u) {
        return MACHINE_RESET;
    }
    return MACHINE_OTHER;
}

void machine_link_init(struct machine_link *l, const struct hal_uart *uart)
{
    l->uart = uart;
    l->rx_len = l->rx_pos = 0u;
    l->last_cr = l->cut = l->done = 0u;
    l->line_len = 0u;
    l->tx_len = l->tx_pos = 0u;
}

int machine_link_flush(struct machine_link *l)
{
    if (l->uart == NULL) {
        return 0;
    }
    return link_tx_flush(l->uart, l->tx, &l->tx_len, &l->tx_pos);
}

size_t machine_link_room(struct machine_link *l)
{
    return link_tx_room(l->tx, sizeof l->tx, &l->tx_len, &l->tx_pos);
}

void machine_link_put(struct machine_link *l, const char *s, size_t n)
{
    link_tx_put(l->tx, sizeof l->tx, &l->tx_len, s, n);
}

int machine_link_line(struct machine_link *l)
{
    if (l->uart == NULL) {
        return 0;
    }
    if (l->done) { /* the last call returned a line: start the next */
        l->line_len = 0u;
        l->cut = 0u;
        l->done = 0u;
    }
    if (l->rx_pos == l->rx_len) {
        int n = hal_uart_read(l->uart, l->rx, sizeof l->rx);
        if (n < 0) {
            return CP_ERR_IO;
        }
        l->rx_len = (uint8_t)n;
        l->rx_pos = 0u;
    }
    while (l->rx_pos < l->rx_len) { /* <= MACHINE_RX_CHUNK */
        uint8_t c = l->rx[l->rx_pos++];
        if (c == '\n' || c == '\r') {
            int skip = c == '\n' && l->last_cr;
            l->last_cr = (uint8_t)(c == '\r');
            if (!skip) {
                l->line_len = parse_trim(l->line, l->line_len);
                l->done = 1u;
                return 1;
            }
            continue;
        }
        l->last_cr = 0u;
        if (c < 0x20u || c > 0x7Eu) {
            continue; /* line noise: dropped */
        }
        if (l->line_len >= MACHINE_LINE_MAX - 1u) {
            l->cut = 1u;
            continue;
        }
        l->line[l->line_len++] = (char)c;
    }
    return 0;
}
