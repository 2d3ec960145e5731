/* sim_run.c - the RUN receiver: machine model (GCODE), frame receiver (FRAMES),
 * UART pacing and fault injection (sim_run.h, docs/HOST_SIM.md).
 * SPDX-License-Identifier: MIT
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/select.h>
#include <time.h>
#include <unistd.h>

#include "frame.h"
#include "sim_cell.h"
#include "sim_check.h"
#include "sim_out.h"
#include "sim_run.h"

#define RUN_LINE_MAX 1024   /* machine line buffer (longer lines are cut, and fail) */
#define RUN_OUTQ 1024       /* host replies queued for their paced write time */
#define RUN_PROGRESS_US 250000u

struct outq_item {
    double due;       /* us, sim_link_now_us() clock */
    uint8_t b[40];
    uint8_t n, off;
    uint16_t freed;   /* machine RX bytes this reply frees (GCODE) */
};

struct run {
    struct sim_link *l;
    const struct sim_run_opts *o;
    struct sim_run_result *r;
    /* bytes read from the pty, not yet delivered */
    uint8_t *ib;
    uint64_t *ia;
    size_t ihead, ilen, icap;
    double dlast;         /* delivery time of the last delivered byte, us */
    unsigned long long raw_i;
    uint64_t t_cmd, t_last_rx;
    /* replies */
    struct outq_item q[RUN_OUTQ];
    size_t qh, qn;
    double hfree;         /* host -> firmware line busy until, us */
    /* text line */
    char line[RUN_LINE_MAX + 1];
    size_t len, raw_len;
    /* GCODE machine */
    unsigned long unanswered;
    uint32_t expect_n;
    int resend_wait;
    unsigned long g1, preamble;
    /* FRAMES */
    struct frame_rx fr;
    uint32_t bad_prev;
    uint32_t expected;
    int64_t nak_for;
    int begin_seen, end_seen;
    /* end */
    int done, began;
    double t_done, t_first;
    uint64_t t_prog;
};

static double dmax(double a, double b)
{
    return a > b ? a : b;
}

static void run_queue(struct run *u, const void *b, size_t n, unsigned freed)
{
    struct outq_item *it;
    double now = (double)sim_link_now_us();
    if (u->qn == RUN_OUTQ || n > sizeof it->b) {
        return; /* cannot happen with the replies below */
    }
    it = &u->q[(u->qh + u->qn) % RUN_OUTQ];
    u->hfree = dmax(now, u->hfree) + (double)n * u->o->byte_us;
    it->due = u->hfree;
    memcpy(it->b, b, n);
    it->n = (uint8_t)n;
    it->off = 0;
    it->freed = (uint16_t)freed;
    u->qn++;
    sim_link_log(u->l, ">", (const char *)b, n > 0 && ((const char *)b)[n - 1] == '\n' ? n - 1 : n);
}

/* Write the replies that are due (all of them if force). Returns 0 or a negative rc. */
static int run_flush(struct run *u, int force)
{
    double now = (double)sim_link_now_us();
    while (u->qn > 0) {
        struct outq_item *it = &u->q[u->qh];
        ssize_t w;
        if (!force && it->due > now) {
            return 0;
        }
        if (u->l->pty->master < 0) {
            return SIM_LINK_EOF;
        }
        w = write(u->l->pty->master, it->b + it->off, (size_t)(it->n - it->off));
        if (w < 0) {
            if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) {
                return 0;
            }
            return errno == EIO ? SIM_LINK_EOF : SIM_LINK_IOERR;
        }
        it->off = (uint8_t)(it->off + w);
        u->l->bytes_out += (unsigned long long)w;
        u->r->bytes_out += (unsigned long long)w;
        if (it->off < it->n) {
            return 0;
        }
        u->unanswered -= it->freed;
        u->qh = (u->qh + 1u) % RUN_OUTQ;
        u->qn--;
    }
    return 0;
}

/* "error:<code> <text>": fills the result, returns 1; else 0 */
static int run_error_line(struct run *u, const char *s)
{
    const char *want;
    char *e;
    long code;
    if (strncmp(s, "error:", 6) != 0 || s[6] < '0' || s[6] > '9') {
        return 0;
    }
    code = strtol(s + 6, &e, 10);
    want = sim_link_status_text((int)code);
    u->r->error = 1;
    u->r->code = (int)code;
    u->r->text_ok = *e == ' ' && want != NULL && sim_link_text_is(e + 1, strlen(e + 1), want);
    return 1;
}

static void run_terminal(struct run *u)
{
    u->done = 1;
    u->t_done = u->dlast;
}

/* overlap: the header's flag (",overlap=1" / BEGIN's byte 15; issue 22) */
static void run_begin(struct run *u, uint32_t points, uint32_t first, int mode, unsigned n,
                      unsigned steps, unsigned link, int overlap)
{
    struct sim_run_result *r = u->r;
    r->header = 1;
    r->points = points;
    r->first = first;
    r->mode = mode;
    r->n = n;
    r->steps = steps;
    r->link = link;
    u->began = 1;
    sim_check_run_begin(points, first, mode, n, steps, link, overlap);
    sim_out_run_begin(sim_check_surface(), points, first, mode, n, steps, link);
}

/* Fixed-point "[-]I[.FFFF]" (at most 4 decimals) -> 0.1 um; 0 on success. */
static int run_fixed4(const char *s, const char **end, int32_t *v)
{
    int neg = 0, dec = 0, digits = 0;
    int64_t a = 0;
    if (*s == '-' || *s == '+') {
        neg = *s == '-';
        s++;
    }
    while (*s >= '0' && *s <= '9' && a < 100000000000LL) {
        a = a * 10 + (*s++ - '0');
        digits++;
    }
    if (*s == '.') {
        s++;
        while (*s >= '0' && *s <= '9') {
            if (dec == 4) {
                return -1;
            }
            a = a * 10 + (*s++ - '0');
            dec++;
            digits++;
        }
    }
    while (dec++ < 4) {
        a *= 10;
    }
    if (digits == 0 || a > 2147483647LL) {
        return -1;
    }
    *v = (int32_t)(neg ? -a : a);
    *end = s;
    return 0;
}

/* " A<deg> C<deg>" (TOOLAXIS AC) or " I.. J.. K.." (TOOLAXIS IJK) after Z: the unit tool
 * axis in *n (1/32767, as a frame's normal; toolaxis.h's a = (sin A sin C, -sin A cos C,
 * cos A)); *s past them. 1 if the words were there, 0 if none, -1 if malformed. */
static int run_parse_axis(const char **s, int16_t n[3])
{
    static const char ac[2] = {'A', 'C'}, ijk[3] = {'I', 'J', 'K'};
    double v[3], a[3];
    int32_t q;
    int i, m;
    const char *w = **s == 'A' ? ac : **s == 'I' ? ijk : NULL;
    if (w == NULL) {
        return 0;
    }
    m = w == ac ? 2 : 3;
    for (i = 0; i < m; i++) {
        if (**s != w[i] || run_fixed4(*s + 1, s, &q) != 0) {
            return -1;
        }
        v[i] = q / 1e4;
        if (**s == ' ') {
            (*s)++;
        }
    }
    if (w == ac) {
        double A = v[0] * 3.14159265358979323846 / 180.0, C = v[1] * 3.14159265358979323846 / 180.0;
        a[0] = sin(A) * sin(C);
        a[1] = -sin(A) * cos(C);
        a[2] = cos(A);
    } else {
        a[0] = v[0];
        a[1] = v[1];
        a[2] = v[2];
    }
    for (i = 0; i < 3; i++) {
        n[i] = (int16_t)lround(a[i] * 32767.0);
    }
    return 1;
}

/* "G1 X.. Y.. Z.. [A.. C.. | I.. J.. K..] [F..]" -> 0 and the point (and *has_n with the
 * tool axis in n); -1 if malformed */
static int run_parse_g1(const char *s, int32_t xyz[3], int16_t n[3], int *has_n)
{
    static const char ax[3] = {'X', 'Y', 'Z'};
    int i;
    if (strncmp(s, "G1 ", 3) != 0) {
        return -1;
    }
    s += 3;
    for (i = 0; i < 3; i++) {
        if (*s != ax[i] || run_fixed4(s + 1, &s, &xyz[i]) != 0) {
            return -1;
        }
        if (*s == ' ') {
            s++;
        } else if (*s != '\0' || i < 2) {
            return -1;
        }
    }
    *has_n = run_parse_axis(&s, n);
    if (*has_n < 0) {
        return -1;
    }
    if (*s == 'F') {
        int32_t f;
        if (run_fixed4(s + 1, &s, &f) != 0) {
            return -1;
        }
    }
    return *s == '\0' ? 0 : -1;
}

static void run_line_index(const struct sim_run_result *r, uint32_t k, struct sim_out_pt *p)
{
    uint32_t block = r->steps + 1u + r->link, j, q;
    if (!r->header || block == 0u) {
        p->line = -1;
        p->index = k;
        return;
    }
    j = k / block;
    q = k % block;
    if (q <= r->steps) {
        p->line = (int32_t)j;
        p->index = (j & 1u) ? r->steps - q : q;
    } else {
        p->line = -1;
        p->index = q - r->steps;
    }
}

static void run_point(struct run *u, uint32_t k, const int32_t xyz[3], const int16_t *n,
                      int32_t line, uint32_t index)
{
    struct sim_out_pt p;
    double nv[3];
    memset(&p, 0, sizeof p);
    p.x = xyz[0];
    p.y = xyz[1];
    p.z = xyz[2];
    if (n != NULL) {
        p.has_n = 1;
        p.n[0] = n[0];
        p.n[1] = n[1];
        p.n[2] = n[2];
        p.line = line;
        p.index = index;
        nv[0] = n[0] / 32767.0;
        nv[1] = n[1] / 32767.0;
        nv[2] = n[2] / 32767.0;
    } else {
        run_line_index(u->r, k, &p);
    }
    sim_check_point(k, xyz[0] / 1e4, xyz[1] / 1e4, xyz[2] / 1e4, n != NULL ? nv : NULL);
    sim_out_point(&p);
    u->r->got++;
}

/* Two links: the machine's new feed moves are the run's points, in order (the program's
 * plunge to the first point, then one G1 per point); rapids are its safe moves. Taken
 * once the host link's "[RUN:...]" header has begun the run. */
static void run_cell_moves(struct run *u)
{
    struct sim_machine_move mv;
    while (u->began && sim_cell_next_move(u->o->cell, &mv)) {
        int32_t xyz[3];
        if (mv.rapid) {
            continue;
        }
        xyz[0] = (int32_t)lround(mv.x * 1e4);
        xyz[1] = (int32_t)lround(mv.y * 1e4);
        xyz[2] = (int32_t)lround(mv.z * 1e4);
        run_point(u, u->r->first + (uint32_t)u->g1, xyz, NULL, 0, 0);
        u->g1++;
    }
}

/* A machine line (not [..], not a terminal reply) of a GCODE run. */
static void run_machine_line(struct run *u, char *s, unsigned mlen)
{
    struct sim_run_result *r = u->r;
    const char *body = s;
    char rep[40];
    int32_t xyz[3];
    int16_t axis[3];
    int has_axis = 0;
    u->unanswered += mlen;
    if (u->unanswered > r->max_inbuf) {
        r->max_inbuf = u->unanswered;
    }
    if (u->unanswered > u->o->rxbuf) {
        if (r->rx_overflow == 0) {
            snprintf(r->why, sizeof r->why,
                     "character counting broken: %lu unanswered bytes > RXBUF %u at line %lu",
                     u->unanswered, u->o->rxbuf, u->g1 + u->preamble + 1u);
        }
        r->rx_overflow++;
    }
    if (u->o->checksum) {
        char *star = strrchr(s, '*'), *e;
        unsigned long nn = 0, cs = 0, want = 0;
        int ok = 0;
        const char *p;
        if (s[0] == 'N' && s[1] >= '0' && s[1] <= '9' && star != NULL) {
            nn = strtoul(s + 1, &e, 10);
            for (p = s; p < star; p++) {
                cs ^= (unsigned char)*p;
            }
            want = strtoul(star + 1, &e, 10);
            ok = *e == '\0' && star[1] >= '0' && star[1] <= '9' && cs == want &&
                 strchr(s, ' ') != NULL && strchr(s, ' ') < star;
        }
        if (ok && strncmp(strchr(s, ' ') + 1, "M110 N", 6) == 0) {
            /* Marlin: M110 N<v> (accepted whatever its own N) sets the line number */
            u->expect_n = (uint32_t)strtoul(strchr(s, ' ') + 7, NULL, 10) + 1u;
            u->resend_wait = 0;
            run_queue(u, "ok\n", 3, mlen);
            return;
        }
        if (!ok || nn != u->expect_n) {
            if (!ok) {
                r->bad_lines++;
            }
            if (!u->resend_wait || (nn == u->expect_n && !ok)) {
                snprintf(rep, sizeof rep, "Resend: %lu\nok\n", (unsigned long)u->expect_n);
                r->resends++;
                u->resend_wait = 1;
            } else {
                snprintf(rep, sizeof rep, "ok\n");
            }
            run_queue(u, rep, strlen(rep), mlen);
            return;
        }
        u->expect_n++;
        u->resend_wait = 0;
        *star = '\0';
        body = strchr(s, ' ') + 1;
    }
    if (strncmp(body, "G1 ", 3) != 0 && strchr("GM", body[0]) != NULL && body[0] != '\0') {
        u->preamble++; /* the program around the points: modes, spindle, rapids, end */
        sim_out_gcode(body);
    } else if (run_parse_g1(body, xyz, axis, &has_axis) == 0) {
        uint32_t k = (r->header ? r->first : 0u) + (uint32_t)u->g1;
        struct sim_out_pt at;
        sim_out_gcode(body);
        run_line_index(r, k, &at); /* TOOLAXIS: the axis is judged as the point's normal */
        run_point(u, k, xyz, has_axis ? axis : NULL, at.line, at.index);
        u->g1++;
    } else {
        r->bad_lines++;
        if (r->why[0] == '\0') {
            char esc[80];
            sim_link_escape(body, strlen(body), esc, sizeof esc);
            snprintf(r->why, sizeof r->why, "unparsable machine line \"%s\"", esc);
        }
    }
    run_queue(u, "ok\n", 3, mlen);
}

/* A complete text line of a GCODE run. */
static void run_gcode_line(struct run *u)
{
    char *s = u->line;
    unsigned mlen = (unsigned)u->raw_len + 1u;
    size_t n = u->len;
    if (n > 0 && s[n - 1] == '\r') {
        s[--n] = '\0';
    }
    sim_link_log(u->l, "<", s, n);
    u->l->lines_in++;
    if (strcmp(s, "ok") == 0) {
        run_terminal(u);
        return;
    }
    if (run_error_line(u, s)) {
        run_terminal(u);
        return;
    }
    if (s[0] == '[') {
        unsigned p, f, nn, st, lk;
        char mode[16];
        if (sscanf(s, "[RUN:points=%u,first=%u,mode=%15[A-Z],n=%u,steps=%u,link=%u]", &p, &f,
                   mode, &nn, &st, &lk) == 6) {
            run_begin(u, p, f, strcmp(mode, "CIRCLES") == 0, nn, st, lk,
                      strstr(s, ",overlap=1]") != NULL);
        }
        return;
    }
    if (s[0] == '<') {
        return; /* status report */
    }
    if (u->o->cell != NULL) {
        /* two links: the program goes to the machine link, nothing of it to the host */
        u->r->host_program++;
        if (u->r->why[0] == '\0') {
            char esc[80];
            sim_link_escape(s, n, esc, sizeof esc);
            snprintf(u->r->why, sizeof u->r->why, "program line on the host link \"%s\"", esc);
        }
        return;
    }
    if (n == 0 && u->o->checksum) {
        return; /* Marlin skips empty lines without an answer (grbl answers ok) */
    }
    run_machine_line(u, s, mlen);
}

/* FRAMES: send ACK/NAK with seq = expected */
static void run_frame_reply(struct run *u, uint8_t type)
{
    uint8_t b[8];
    int n = frame_encode((uint8_t)u->expected, type, NULL, 0, b, sizeof b);
    if (n > 0) {
        run_queue(u, b, (size_t)n, 0);
    }
    if (type == FRAME_ACK) {
        u->r->acks++;
    } else {
        u->r->naks++;
    }
}

static void run_frame(struct run *u, const uint8_t *f)
{
    struct sim_run_result *r = u->r;
    uint8_t diff = (uint8_t)(f[1] - (uint8_t)u->expected);
    size_t plen = (size_t)f[0] - FRAME_OVERHEAD;
    const uint8_t *pl = f + 3;
    char esc[80];
    if (diff != 0u) {
        if (diff < 128u) {
            r->gap_frames++;
            if (u->nak_for != (int64_t)u->expected) {
                u->nak_for = (int64_t)u->expected;
                run_frame_reply(u, FRAME_NAK);
            }
        } else {
            r->dup_frames++;
            run_frame_reply(u, FRAME_ACK);
        }
        return;
    }
    if (f[2] == FRAME_BEGIN && plen >= 15u) {
        run_begin(u, frame_get_u32(pl), frame_get_u32(pl + 4), pl[14], frame_get_u16(pl + 8),
                  frame_get_u16(pl + 10), frame_get_u16(pl + 12), plen >= 16u && pl[15] == 1u);
        u->begin_seen = 1;
    } else if (f[2] == FRAME_POINT && plen >= FRAME_POINT_PAYLOAD) {
        int32_t xyz[3];
        int16_t n[3];
        uint32_t k = frame_get_u32(pl);
        xyz[0] = (int32_t)frame_get_u32(pl + 4);
        xyz[1] = (int32_t)frame_get_u32(pl + 8);
        xyz[2] = (int32_t)frame_get_u32(pl + 12);
        n[0] = (int16_t)frame_get_u16(pl + 16);
        n[1] = (int16_t)frame_get_u16(pl + 18);
        n[2] = (int16_t)frame_get_u16(pl + 20);
        if (k != r->first + r->got) {
            if (r->order_err == 0) {
                snprintf(r->why, sizeof r->why, "POINT k=%lu, expected %lu", (unsigned long)k,
                         (unsigned long)(r->first + r->got));
            }
            r->order_err++;
        }
        run_point(u, k, xyz, n, (int16_t)frame_get_u16(pl + 22), frame_get_u16(pl + 24));
    } else if (f[2] == FRAME_END && plen >= 5u) {
        r->end_status = pl[0];
        r->end_points = frame_get_u32(pl + 1);
        u->end_seen = 1;
    } else {
        snprintf(esc, sizeof esc, "unexpected frame type 0x%02x len %u", f[2], f[0]);
        if (r->why[0] == '\0') {
            snprintf(r->why, sizeof r->why, "%s", esc);
        }
        r->order_err++;
    }
    if (u->l->log != NULL) {
        char t[64];
        snprintf(t, sizeof t, "[frame seq %u type 0x%02x len %u]", f[1], f[2], f[0]);
        sim_link_log(u->l, "<", t, strlen(t));
    }
    u->expected++;
    u->nak_for = -1;
    run_frame_reply(u, FRAME_ACK);
}

/* FRAMES runs: text replies before BEGIN (validation errors) and after END */
static void run_frames_text(struct run *u, uint8_t c)
{
    char *s;
    if (c != '\n') {
        if (u->len < RUN_LINE_MAX) {
            u->line[u->len++] = (char)c;
        }
        return;
    }
    u->line[u->len] = '\0';
    s = strrchr(u->line, FRAME_SYNC);
    s = s != NULL ? s + 1 : u->line;
    u->len = 0;
    if (strlen(s) > 0 && s[strlen(s) - 1] == '\r') {
        s[strlen(s) - 1] = '\0';
    }
    if (strcmp(s, "ok") == 0 || run_error_line(u, s)) {
        sim_link_log(u->l, "<", s, strlen(s));
        run_terminal(u);
    }
}

static void run_deliver(struct run *u, uint8_t c)
{
    u->r->bytes_in++;
    if (u->t_first == 0.0) {
        u->t_first = u->dlast;
    }
    if (u->o->frames) {
        if (u->end_seen || !u->begin_seen) {
            run_frames_text(u, c);
            if (u->done || u->end_seen) {
                return;
            }
        }
        if (frame_rx_feed(&u->fr, c)) {
            u->len = 0;
            run_frame(u, u->fr.buf);
        } else if (u->fr.bad != u->bad_prev) {
            u->bad_prev = u->fr.bad;
            if (u->begin_seen) {
                u->r->bad_frames++;
                u->nak_for = (int64_t)u->expected;
                run_frame_reply(u, FRAME_NAK);
            }
        }
        return;
    }
    if (c == '\n') {
        u->line[u->len] = '\0';
        run_gcode_line(u);
        u->len = 0;
        u->raw_len = 0;
        return;
    }
    u->raw_len++;
    if (u->len < RUN_LINE_MAX) {
        u->line[u->len++] = (char)c;
    }
}

static int run_read(struct run *u)
{
    for (;;) {
        uint8_t tmp[4096];
        ssize_t n;
        uint64_t now;
        size_t i;
        if (u->l->pty->master < 0) {
            return SIM_LINK_EOF;
        }
        n = read(u->l->pty->master, tmp, sizeof tmp);
        if (n == 0) {
            return SIM_LINK_EOF;
        }
        if (n < 0) {
            if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) {
                return 0;
            }
            return errno == EIO ? SIM_LINK_EOF : SIM_LINK_IOERR;
        }
        now = sim_link_now_us();
        u->t_last_rx = now;
        u->l->bytes_in += (unsigned long long)n;
        if (u->ihead > 0 && u->ihead == u->ilen) {
            u->ihead = u->ilen = 0;
        }
        if (u->ilen + (size_t)n > u->icap) {
            size_t nc = (u->icap ? u->icap : 65536u), live = u->ilen - u->ihead;
            uint8_t *b;
            uint64_t *a;
            while (nc < live + (size_t)n) {
                nc *= 2u;
            }
            b = malloc(nc);
            a = malloc(nc * sizeof *a);
            if (b == NULL || a == NULL) {
                free(b);
                free(a);
                return SIM_LINK_IOERR;
            }
            if (live) {
                memcpy(b, u->ib + u->ihead, live);
                memcpy(a, u->ia + u->ihead, live * sizeof *a);
            }
            free(u->ib);
            free(u->ia);
            u->ib = b;
            u->ia = a;
            u->icap = nc;
            u->ihead = 0;
            u->ilen = live;
        }
        for (i = 0; i < (size_t)n; i++) {
            u->ib[u->ilen] = tmp[i];
            u->ia[u->ilen++] = now;
        }
    }
}

static void run_progress(struct run *u, int last)
{
    uint64_t now = sim_link_now_us();
    double el;
    struct sim_run_result *r = u->r;
    if (!u->o->progress || (!last && now - u->t_prog < RUN_PROGRESS_US)) {
        return;
    }
    u->t_prog = now;
    el = (double)(now - u->t_cmd) / 1e6;
    if (r->header && el > 0.0) {
        double rate = r->got / el;
        uint32_t todo = r->points - r->first;
        double eta = rate > 0.0 && todo > r->got ? (todo - r->got) / rate : 0.0;
        fprintf(stderr, "\r  run: %lu/%lu points, %.0f points/s, ETA %.1f s   ",
                (unsigned long)r->got, (unsigned long)todo, rate, eta);
    }
    if (last) {
        fputc('\n', stderr);
    }
}

int sim_run_send(struct sim_link *l, const char *s, size_t n, double byte_us, uint64_t deadline_ms)
{
    if (byte_us > 0.0) {
        double us = byte_us * (double)n;
        struct timespec ts;
        ts.tv_sec = (time_t)(us / 1e6);
        ts.tv_nsec = (long)((us - (double)ts.tv_sec * 1e6) * 1000.0);
        (void)nanosleep(&ts, NULL);
    }
    return sim_link_send(l, s, n, deadline_ms);
}

/* A stream starts: u set up; the bytes the line reader already holds belong to this run.
 * 0, or SIM_LINK_IOERR. */
static int run_start(struct run *u, struct sim_link *l, const struct sim_run_opts *o,
                     struct sim_run_result *r)
{
    memset(u, 0, sizeof *u);
    memset(r, 0, sizeof *r);
    r->end_status = -1;
    u->l = l;
    u->o = o;
    u->r = r;
    u->t_cmd = sim_link_now_us();
    u->t_last_rx = u->t_cmd;
    u->t_prog = u->t_cmd;
    u->dlast = (double)u->t_cmd;
    u->hfree = (double)u->t_cmd;
    u->expect_n = 1;
    u->nak_for = -1;
    frame_rx_init(&u->fr);
    if (l->len > 0) {
        u->icap = 65536u;
        u->ib = malloc(u->icap);
        u->ia = malloc(u->icap * sizeof *u->ia);
        if (u->ib == NULL || u->ia == NULL) {
            return SIM_LINK_IOERR;
        }
        memcpy(u->ib, l->buf, l->len);
        for (u->ilen = 0; u->ilen < l->len; u->ilen++) {
            u->ia[u->ilen] = u->t_cmd;
        }
        l->len = 0;
    }
    return 0;
}

/* Deliver the bytes that are due at now, in order, with the fault injected at its byte.
 * 0, or SIM_LINK_EOF after an injected hang-up. */
static int run_deliver_due(struct run *u, double now)
{
    const struct sim_run_opts *o = u->o;
    while (u->ihead < u->ilen && !u->done) {
        double d = dmax((double)u->ia[u->ihead], u->dlast) + o->byte_us;
        uint8_t c;
        unsigned long long i = u->raw_i;
        if (d > now) {
            break;
        }
        c = u->ib[u->ihead++];
        u->dlast = d;
        u->raw_i++;
        if (o->raw != NULL) {
            fputc(c, o->raw);
        }
        if (o->fault != SIM_FAULT_NONE && i == o->fault_at) {
            if (o->fault == SIM_FAULT_HANGUP) {
                u->r->hung = 1;
                sim_link_log(u->l, "!", "fault: hang-up", 14);
                sim_pty_hangup(u->l->pty);
                return SIM_LINK_EOF;
            }
            if (o->fault == SIM_FAULT_DROP) {
                sim_link_log(u->l, "!", "fault: byte dropped", 19);
                continue;
            }
            if (o->fault == SIM_FAULT_FLIP) {
                sim_link_log(u->l, "!", "fault: bit 0 flipped", 20);
                c ^= 0x01u;
            } else {
                sim_link_log(u->l, "!", "fault: byte duplicated", 22);
                run_deliver(u, c);
            }
        }
        run_deliver(u, c);
    }
    return 0;
}

/* Sleep until the next byte is due, a queued host reply is due, the pty is readable or a
 * slice has passed. */
static void run_wait(struct run *u, double now)
{
    double wake = now + SIM_LINK_SLICE_MS * 1000.0;
    struct timeval tv;
    fd_set rd;
    int nfds;
    if (u->ihead < u->ilen) {
        double d = dmax((double)u->ia[u->ihead], u->dlast) + u->o->byte_us;
        wake = d < wake ? d : wake;
    }
    if (u->qn > 0) {
        wake = u->q[u->qh].due < wake ? u->q[u->qh].due : wake;
    }
    if (u->o->cell != NULL) {
        double d = sim_cell_next_due(u->o->cell, u->o->byte_us);
        wake = d < wake ? d : wake;
        if (u->o->cell->olen > 0u) {
            wake = now + 1000.0; /* replies the pty did not take: try again soon */
        }
    }
    if (wake <= now) {
        return;
    }
    FD_ZERO(&rd);
    FD_SET(u->l->pty->master, &rd);
    nfds = u->l->pty->master + 1;
    if (u->o->cell != NULL && u->o->cell->pty.master >= 0) {
        FD_SET(u->o->cell->pty.master, &rd);
        nfds = u->o->cell->pty.master >= nfds ? u->o->cell->pty.master + 1 : nfds;
    }
    tv.tv_sec = 0;
    tv.tv_usec = (long)(wake - now) + 1;
    (void)select(nfds, &rd, NULL, NULL, &tv);
}

/* Read, deliver and answer until the terminal reply (u->done) or an end of the link. */
static int run_loop(struct run *u)
{
    struct sim_link *l = u->l;
    int rc = 0;
    while (!u->done) {
        double now = (double)sim_link_now_us();
        if (u->o->cell != NULL) {
            if (sim_cell_pump(u->o->cell, now, u->o->byte_us) > 0) {
                u->t_last_rx = (uint64_t)now;
            }
            run_cell_moves(u);
        }
        rc = run_deliver_due(u, now);
        if (rc < 0) {
            break;
        }
        rc = run_flush(u, u->done);
        if (rc < 0 || u->done) {
            break;
        }
        run_progress(u, 0);
        rc = run_read(u);
        if (rc < 0) {
            /* the firmware is gone: whatever arrived is still delivered */
            if (u->ihead < u->ilen) {
                continue;
            }
            break;
        }
        if (l->stop != NULL && *l->stop) {
            rc = SIM_LINK_INTR;
            break;
        }
        now = (double)sim_link_now_us();
        if (u->ihead == u->ilen && now - (double)u->t_last_rx > (double)u->o->timeout_ms * 1000.0) {
            rc = SIM_LINK_TIMEOUT;
            break;
        }
        if (u->ihead == u->ilen && sim_pty_exited(l->pty)) {
            rc = run_read(u);
            if (u->ihead == u->ilen) {
                rc = SIM_LINK_EXITED;
                break;
            }
            continue;
        }
        run_wait(u, now);
    }
    return rc;
}

/* The stream ended with rc: hand back what follows the terminal reply, close the judge's
 * run, fill the durations and utilizations. Returns the result code. */
static int run_end(struct run *u, int rc)
{
    struct sim_link *l = u->l;
    struct sim_run_result *r = u->r;
    const struct sim_run_opts *o = u->o;
    double tend;
    if (u->done) {
        rc = SIM_LINK_REPLY;
        /* anything after the terminal reply goes back to the line reader */
        if (u->ihead < u->ilen) {
            size_t n = u->ilen - u->ihead;
            if (n > sizeof l->buf) {
                n = sizeof l->buf;
            }
            memcpy(l->buf, u->ib + u->ihead, n);
            l->len = n;
        }
    }
    r->rc = rc;
    if (o->cell != NULL) {
        run_cell_moves(u); /* every move the machine took before its last answer */
    }
    if (u->began) {
        sim_check_run_end(u->done && !r->error);
    }
    tend = u->done ? u->t_done : (double)sim_link_now_us();
    r->dur_us = tend - (double)u->t_cmd;
    r->first_byte_us = u->t_first > 0.0 ? u->t_first - (double)u->t_cmd : 0.0;
    r->stream_us = u->t_first > 0.0 ? tend - u->t_first + o->byte_us : 0.0;
    if (o->byte_us > 0.0 && r->dur_us > 0.0) {
        r->util = (double)r->bytes_in * o->byte_us / r->dur_us;
    }
    if (o->byte_us > 0.0 && r->stream_us > 0.0) {
        r->util_stream = (double)r->bytes_in * o->byte_us / r->stream_us;
    }
    run_progress(u, 1);
    free(u->ib);
    free(u->ia);
    return rc;
}

int sim_run_stream(struct sim_link *l, const struct sim_run_opts *o, struct sim_run_result *r)
{
    static struct run u;
    int rc = run_start(&u, l, o, r);
    if (rc == 0) {
        rc = run_loop(&u);
    }
    return run_end(&u, rc);
}
