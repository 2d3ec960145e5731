/* hal_uart_posix.c - struct hal_uart over POSIX file descriptors.
 * SPDX-License-Identifier: MIT
 */
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include "cp_types.h"
#include "hal_uart_posix.h"

/* A tty in non-canonical mode with VMIN=0 returns 0 when no byte is pending, so on
 * a tty 0 means end of file only if the line has hung up. */
static int posix_is_eof(int fd)
{
    struct pollfd pf;
    if (!isatty(fd)) {
        return 1;
    }
    pf.fd = fd;
    pf.events = POLLIN;
    pf.revents = 0;
    if (poll(&pf, 1, 0) < 0) {
        return errno != EINTR;
    }
    return (pf.revents & (POLLHUP | POLLERR | POLLNVAL)) != 0;
}

static int posix_read(void *ctx, uint8_t *buf, size_t cap)
{
    struct hal_uart_posix *p = ctx;
    ssize_t n;
    if (p->hup) {
        return CP_ERR_IO;
    }
    if (cap == 0u) {
        return 0;
    }
    if (cap > 4096u) {
        cap = 4096u; /* the result must fit an int */
    }
    n = read(p->rfd, buf, cap);
    if (n > 0) {
        p->bytes_in += (uint32_t)n;
        return (int)n;
    }
    if (n == 0) {
        if (posix_is_eof(p->rfd)) {
            p->hup = 1;
            return CP_ERR_IO;
        }
        return 0;
    }
    if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) {
        return 0;
    }
    p->hup = 1; /* EIO (pty hang-up), EBADF, ... */
    return CP_ERR_IO;
}

static int posix_write(void *ctx, const uint8_t *buf, size_t len)
{
    struct hal_uart_posix *p = ctx;
    ssize_t n;
    if (p->hup) {
        return CP_ERR_IO;
    }
    if (len == 0u) {
        return 0;
    }
    if (len > 4096u) {
        len = 4096u;
    }
    n = write(p->wfd, buf, len);
    if (n >= 0) {
        p->bytes_out += (uint32_t)n;
        p->tx_short = (size_t)n < len;
        return (int)n;
    }
    if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) {
        p->tx_short = 1;
        return 0;
    }
    p->hup = 1; /* EPIPE, EIO, ... */
    return CP_ERR_IO;
}

static uint32_t posix_now_ms(void *ctx)
{
    struct timespec ts;
    (void)ctx;
    if (clock_gettime(CLOCK_MONOTONIC, &ts) != 0) {
        return 0; /* cannot happen for CLOCK_MONOTONIC on POSIX.1-2008 systems */
    }
    return (uint32_t)((uint64_t)ts.tv_sec * 1000u + (uint64_t)ts.tv_nsec / 1000000u);
}

static int posix_nonblock(int fd, int *old)
{
    int fl = fcntl(fd, F_GETFL);
    if (fl < 0) {
        return CP_ERR_IO;
    }
    *old = fl;
    if ((fl & O_NONBLOCK) == 0 && fcntl(fd, F_SETFL, fl | O_NONBLOCK) < 0) {
        return CP_ERR_IO;
    }
    return CP_OK;
}

int hal_uart_posix_init(struct hal_uart_posix *p, struct hal_uart *u, int rfd, int wfd)
{
    if (p == NULL || u == NULL || rfd < 0 || wfd < 0) {
        return CP_ERR_INVAL;
    }
    p->rfd = rfd;
    p->wfd = wfd;
    p->hup = 0;
    p->tx_short = 0;
    p->bytes_in = 0;
    p->bytes_out = 0;
    if (posix_nonblock(rfd, &p->rfl) != CP_OK || posix_nonblock(wfd, &p->wfl) != CP_OK) {
        return CP_ERR_IO;
    }
    u->ctx = p;
    u->read = posix_read;
    u->write = posix_write;
    u->now_ms = posix_now_ms;
    return CP_OK;
}

int hal_uart_posix_raw(int fd)
{
    struct termios t;
    if (!isatty(fd)) {
        return CP_OK;
    }
    if (tcgetattr(fd, &t) != 0) {
        return CP_ERR_IO;
    }
    t.c_iflag = 0;
    t.c_oflag = 0;
    t.c_lflag = 0;
    t.c_cflag = (t.c_cflag & ~(tcflag_t)(CSIZE | PARENB | CSTOPB)) | CS8 | CREAD | CLOCAL;
    t.c_cc[VMIN] = 1;
    t.c_cc[VTIME] = 0;
    return tcsetattr(fd, TCSANOW, &t) == 0 ? CP_OK : CP_ERR_IO;
}

/* The event that makes progress on p likely (hal_uart_posix_wait). */
static void wait_event(const struct hal_uart_posix *p, struct pollfd *pf)
{
    if (p->tx_short) {
        pf->fd = p->wfd;
        pf->events = POLLOUT;
    } else {
        pf->fd = p->rfd;
        pf->events = POLLIN;
    }
    pf->revents = 0;
}

int hal_uart_posix_wait(struct hal_uart_posix *p, struct hal_uart_posix *q, int timeout_ms)
{
    struct pollfd pf[2];
    nfds_t n = 1;
    int r;
    if (timeout_ms < 0) {
        timeout_ms = 0;
    }
    if (timeout_ms > 60000) {
        timeout_ms = 60000;
    }
    wait_event(p, &pf[0]);
    if (q != NULL && !q->hup) {
        wait_event(q, &pf[1]);
        n = 2;
    }
    r = poll(pf, n, timeout_ms);
    if (r < 0) {
        return errno == EINTR ? 0 : CP_ERR_IO;
    }
    return r > 0;
}

void hal_uart_posix_close(struct hal_uart_posix *p)
{
    (void)fcntl(p->rfd, F_SETFL, p->rfl);
    if (p->wfd != p->rfd) {
        (void)fcntl(p->wfd, F_SETFL, p->wfl);
    }
}
