/* sim_link.c - bounded line I/O with the firmware over the pty master.
 * SPDX-License-Identifier: MIT
 */
#include <errno.h>
#include <poll.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "sim_link.h"

/* Text of a wire status from the frozen table (NULL if the code is unknown). */
static const char *link_status_text(int code)
{
    switch (code) {
#define CP_STATUS(name, num, text, from) \
    case num:                      \
        return text;
#include "cp_status.def"
#undef CP_STATUS
    default:
        return NULL;
    }
}

const char *sim_link_status_text(int code)
{
    return link_status_text(code);
}

uint64_t sim_link_now_us(void)
{
    struct timespec ts;
    (void)clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000u + (uint64_t)ts.tv_nsec / 1000u;
}

uint64_t sim_link_now_ms(void)
{
    return sim_link_now_us() / 1000u;
}

void sim_link_init(struct sim_link *l, struct sim_pty *pty, volatile sig_atomic_t *stop,
                   FILE *log)
{
    memset(l, 0, sizeof *l);
    l->pty = pty;
    l->stop = stop;
    l->log = log;
    l->t0 = sim_link_now_us();
    l->max_lines = 64;
    l->max_bytes = 16384;
}

void sim_link_escape(const char *s, size_t n, char *out, size_t cap)
{
    static const char hex[] = "0123456789abcdef";
    size_t i, o = 0;
    if (cap == 0) {
        return;
    }
    for (i = 0; i < n && o + 5 < cap; i++) {
        unsigned char c = (unsigned char)s[i];
        if (c >= 0x20 && c < 0x7f && c != '\\') {
            out[o++] = (char)c;
        } else {
            out[o++] = '\\';
            out[o++] = 'x';
            out[o++] = hex[c >> 4];
            out[o++] = hex[c & 15u];
        }
    }
    if (i < n && o + 3 < cap) {
        out[o++] = '.';
        out[o++] = '.';
        out[o++] = '.';
    }
    out[o] = '\0';
}

void sim_link_log(struct sim_link *l, const char *dir, const char *s, size_t n)
{
    char esc[4 * SIM_LINK_LINE_MAX + 8];
    if (l->log == NULL) {
        return;
    }
    sim_link_escape(s, n, esc, sizeof esc);
    fprintf(l->log, "%10.3f %s %s\n", (double)(sim_link_now_us() - l->t0) / 1000.0, dir, esc);
}

/* Wait for fd readiness (events) for at most one slice before the deadline.
 * Returns 0 to retry, or a negative enum sim_link_rc. */
static int link_wait(struct sim_link *l, short events, uint64_t deadline_ms)
{
    struct pollfd pf;
    uint64_t now = sim_link_now_ms();
    int ms;
    if (l->stop != NULL && *l->stop) {
        return SIM_LINK_INTR;
    }
    if (now >= deadline_ms) {
        return SIM_LINK_TIMEOUT;
    }
    ms = deadline_ms - now > SIM_LINK_SLICE_MS ? SIM_LINK_SLICE_MS : (int)(deadline_ms - now);
    if (l->idle != NULL) {
        l->idle(l->idle_ctx);
        ms = ms > 1 ? 1 : ms;
    }
    pf.fd = l->pty->master;
    pf.events = events;
    pf.revents = 0;
    if (poll(&pf, 1, ms) < 0 && errno != EINTR) {
        return SIM_LINK_IOERR;
    }
    if (l->stop != NULL && *l->stop) {
        return SIM_LINK_INTR;
    }
    return 0;
}

int sim_link_send(struct sim_link *l, const char *s, size_t n, uint64_t deadline_ms)
{
    size_t done = 0;
    sim_link_log(l, ">", s, n > 0 && s[n - 1] == '\n' ? n - 1 : n);
    while (done < n) {
        ssize_t w;
        int rc;
        if (l->pty->master < 0) {
            return SIM_LINK_EOF;
        }
        w = write(l->pty->master, s + done, n - done);
        if (w > 0) {
            done += (size_t)w;
            l->bytes_out += (unsigned long long)w;
            continue;
        }
        if (w < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) {
            return errno == EIO ? SIM_LINK_EOF : SIM_LINK_IOERR;
        }
        if (sim_pty_exited(l->pty)) {
            return SIM_LINK_EXITED;
        }
        rc = link_wait(l, POLLOUT, deadline_ms);
        if (rc < 0) {
            return rc;
        }
    }
    return SIM_LINK_REPLY;
}

int sim_link_read_line(struct sim_link *l, uint64_t deadline_ms)
{
    size_t i = 0;
    int exited = 0;
    l->line_len = 0;
    for (;;) {
        ssize_t n;
        int rc;
        /* assemble from what is buffered */
        while (i < l->len) {
            char c = (char)l->buf[i++];
            if (c == '\n') {
                memmove(l->buf, l->buf + i, l->len - i);
                l->len -= i;
                if (l->line_len > 0 && l->line[l->line_len - 1] == '\r') {
                    l->line_len--;
                }
                l->line[l->line_len] = '\0';
                l->lines_in++;
                sim_link_log(l, "<", l->line, l->line_len);
                return SIM_LINK_LINE;
            }
            if (l->line_len == SIM_LINK_LINE_MAX) {
                l->line[l->line_len] = '\0';
                sim_link_log(l, "<", l->line, l->line_len);
                return SIM_LINK_LONG;
            }
            l->line[l->line_len++] = c;
        }
        l->len = 0;
        i = 0;
        if (l->pty->master < 0) {
            return SIM_LINK_EOF;
        }
        n = read(l->pty->master, l->buf, sizeof l->buf);
        if (n > 0) {
            l->len = (size_t)n;
            l->bytes_in += (unsigned long long)n;
            continue;
        }
        if (n == 0) {
            return SIM_LINK_EOF;
        }
        if (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) {
            return errno == EIO ? SIM_LINK_EOF : SIM_LINK_IOERR;
        }
        if (exited) {
            return SIM_LINK_EXITED; /* exited, and nothing it wrote is left */
        }
        if (sim_pty_exited(l->pty)) {
            exited = 1; /* read once more: output written just before exit */
            continue;
        }
        rc = link_wait(l, POLLIN, deadline_ms);
        if (rc < 0) {
            return rc;
        }
    }
}

int sim_link_text_is(const char *s, size_t n, const char *want)
{
    size_t w = strlen(want);
    if (n < w || memcmp(s, want, w) != 0) {
        return 0;
    }
    /* the text alone, or followed by the cause " (...)" (PROTOCOL.md "Lines") */
    return n == w || (n >= w + 3u && s[w] == ' ' && s[w + 1u] == '(' && s[n - 1u] == ')');
}

/* "error:<code> <text>": 1 and fills r, else 0 (malformed). */
static int link_parse_error(const char *s, size_t n, struct sim_reply *r)
{
    size_t i = 6;
    int code = 0;
    const char *want;
    if (n < 8 || memcmp(s, "error:", 6) != 0) {
        return 0;
    }
    while (i < n && s[i] >= '0' && s[i] <= '9' && code < 100000) {
        code = code * 10 + (s[i] - '0');
        i++;
    }
    if (i == 6 || i >= n || s[i] != ' ') {
        return 0;
    }
    want = link_status_text(code);
    r->error = 1;
    r->code = code;
    r->text_ok = want != NULL && sim_link_text_is(s + i + 1, n - i - 1, want);
    return 1;
}

int sim_link_await(struct sim_link *l, uint64_t deadline_ms, struct sim_reply *r,
                   sim_link_line_fn fn, void *ctx)
{
    unsigned lines = 0;
    unsigned long bytes = 0;
    memset(r, 0, sizeof *r);
    for (;;) {
        const char *s;
        size_t n;
        int rc = sim_link_read_line(l, deadline_ms);
        if (rc < 0) {
            return rc;
        }
        s = l->line;
        n = l->line_len;
        if (n == 2 && memcmp(s, "ok", 2) == 0) {
            return SIM_LINK_REPLY;
        }
        if (link_parse_error(s, n, r)) {
            return SIM_LINK_REPLY;
        }
        if (n >= 2 && s[0] == '[' && s[n - 1] == ']') {
            r->info++;
            if (strncmp(s, "[VER:", 5) == 0 && n < sizeof r->ver) {
                memcpy(r->ver, s, n + 1);
            } else if (strncmp(s, "[OPT:", 5) == 0 && n < sizeof r->opt) {
                memcpy(r->opt, s, n + 1);
            }
        } else if (fn != NULL && fn(ctx, s, n)) {
            r->streamed++;
        } else {
            if (r->unknown == 0) {
                sim_link_escape(s, n, r->first_unknown, sizeof r->first_unknown);
            }
            r->unknown++;
        }
        lines++;
        bytes += (unsigned long)n + 1u;
        if (lines > l->max_lines || bytes > l->max_bytes) {
            return SIM_LINK_FLOOD;
        }
    }
}

const char *sim_link_strerror(int rc)
{
    switch (rc) {
    case SIM_LINK_LINE:
        return "line";
    case SIM_LINK_REPLY:
        return "reply";
    case SIM_LINK_TIMEOUT:
        return "no reply within the timeout (firmware silent or too slow)";
    case SIM_LINK_EOF:
        return "the serial line hung up (EOF/EIO on the pty master: firmware gone)";
    case SIM_LINK_EXITED:
        return "the firmware process exited";
    case SIM_LINK_LONG:
        return "reply line longer than the limit (firmware floods without newlines)";
    case SIM_LINK_FLOOD:
        return "too many lines/bytes without a terminal reply (firmware floods)";
    case SIM_LINK_INTR:
        return "interrupted";
    default:
        return "I/O error on the pty master";
    }
}
