/* sim_cell.c - the machine on the firmware's machine link (sim_cell.h).
 * SPDX-License-Identifier: MIT
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "sim_cell.h"
#include "sim_out.h"

static double dmax(double a, double b)
{
    return a > b ? a : b;
}

int sim_cell_open(struct sim_cell *c, const struct sim_machine_opts *o, char *err, size_t errcap)
{
    memset(c, 0, sizeof *c);
    c->pty.master = c->pty.slave = -1;
    c->kind = o->kind;
    c->m = sim_machine_new(o);
    if (c->m == NULL) {
        snprintf(err, errcap, "cannot create the emulated machine");
        return -1;
    }
    return sim_cell_reopen(c, err, errcap);
}

int sim_cell_reopen(struct sim_cell *c, char *err, size_t errcap)
{
    sim_pty_release(&c->pty);
    sim_pty_hangup(&c->pty);
    c->ihead = c->ilen = 0u;
    c->line_len = 0u;
    c->olen = 0u;
    if (sim_pty_open(&c->pty, err, errcap) != 0) {
        return -1;
    }
    c->pty.pid = -1;
    return 0;
}

void sim_cell_release(struct sim_cell *c)
{
    sim_pty_release(&c->pty);
}

void sim_cell_close(struct sim_cell *c)
{
    sim_pty_release(&c->pty);
    sim_pty_hangup(&c->pty);
    sim_machine_free(c->m);
    c->m = NULL;
    free(c->ib);
    free(c->ia);
    c->ib = NULL;
    c->ia = NULL;
    c->icap = c->ihead = c->ilen = 0u;
}

/* A program line complete (for --gcode): without N<n> and *<cs>, without real-time bytes. */
static void cell_line(struct sim_cell *c)
{
    char *s = c->line, *star;
    c->line[c->line_len] = '\0';
    c->line_len = 0u;
    if (s[0] == 'N' && strchr(s, ' ') != NULL) {
        s = strchr(s, ' ') + 1;
    }
    star = strrchr(s, '*');
    if (star != NULL) {
        *star = '\0';
    }
    if (s[0] != '\0') {
        sim_out_gcode(s);
    }
}

/* One byte to the machine at t_us. */
static void cell_deliver(struct sim_cell *c, uint8_t b, double t_us)
{
    sim_machine_rx(c->m, &b, 1u, t_us / 1000.0);
    if (b == '\n' || b == '\r') {
        if (c->line_len > 0u) {
            cell_line(c);
        }
    } else if (b >= 0x20u && b < 0x7Fu && b != '?' && b != '!' && b != '~' &&
               c->line_len < SIM_CELL_LINE_MAX - 1u) {
        c->line[c->line_len++] = (char)b;
    }
}

/* Read what the pty has (with its arrival time). 1 if bytes came, 0, or -1 on EOF/EIO. */
static int cell_read(struct sim_cell *c, double now_us)
{
    uint8_t tmp[512];
    ssize_t n;
    size_t i;
    if (c->pty.master < 0) {
        return -1;
    }
    n = read(c->pty.master, tmp, sizeof tmp);
    if (n < 0) {
        return errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR ? 0 : -1;
    }
    if (n == 0) {
        return -1;
    }
    if (c->ihead > 0u && c->ihead == c->ilen) {
        c->ihead = c->ilen = 0u;
    }
    if (c->ilen + (size_t)n > c->icap) {
        size_t live = c->ilen - c->ihead, cap = 2u * (live + (size_t)n) + 4096u;
        uint8_t *b = malloc(cap);
        double *a = malloc(cap * sizeof *a);
        if (b == NULL || a == NULL) {
            free(b);
            free(a);
            return -1;
        }
        if (live > 0u) {
            memcpy(b, c->ib + c->ihead, live);
            memcpy(a, c->ia + c->ihead, live * sizeof *a);
        }
        free(c->ib);
        free(c->ia);
        c->ib = b;
        c->ia = a;
        c->icap = cap;
        c->ihead = 0u;
        c->ilen = live;
    }
    for (i = 0; i < (size_t)n; i++) {
        c->ib[c->ilen] = tmp[i];
        c->ia[c->ilen++] = now_us;
    }
    c->bytes_in += (unsigned long long)n;
    c->t_last = now_us;
    return 1;
}

double sim_cell_next_due(const struct sim_cell *c, double byte_us)
{
    if (c->ihead >= c->ilen) {
        return 1e300;
    }
    return dmax(c->ia[c->ihead], c->dlast) + byte_us;
}

int sim_cell_pump(struct sim_cell *c, double now_us, double byte_us)
{
    size_t n;
    int moved = 0, r = cell_read(c, now_us);
    if (r < 0) {
        return -1;
    }
    moved |= r;
    while (c->ihead < c->ilen) {
        double d = sim_cell_next_due(c, byte_us);
        if (d > now_us) {
            break;
        }
        c->dlast = d;
        cell_deliver(c, c->ib[c->ihead++], d);
        moved = 1;
    }
    /* the machine's replies: what the pty did not take waits in ob[] (the emulator is
     * asked for no more than ob[] holds) */
    n = sim_machine_tx(c->m, now_us / 1000.0, c->ob + c->olen, sizeof c->ob - c->olen);
    c->olen += n;
    if (c->olen > 0u) {
        ssize_t w = write(c->pty.master, c->ob, c->olen);
        if (w < 0 && errno != EAGAIN && errno != EINTR) {
            return -1;
        }
        if (w > 0) {
            memmove(c->ob, c->ob + w, c->olen - (size_t)w);
            c->olen -= (size_t)w;
            c->bytes_out += (unsigned long long)w;
            c->t_last = now_us;
            moved = 1;
        }
    }
    return moved;
}

int sim_cell_next_move(struct sim_cell *c, struct sim_machine_move *mv)
{
    const struct sim_machine_move *v;
    size_t n = sim_machine_moves(c->m, &v);
    if (c->moves_seen >= n) {
        return 0;
    }
    *mv = v[c->moves_seen++];
    return 1;
}
