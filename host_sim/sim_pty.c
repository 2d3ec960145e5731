/* sim_pty.c - the pseudo-tty and the firmware process.
 * SPDX-License-Identifier: MIT
 */
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include "sim_pty.h"

static void pty_cloexec(int fd)
{
    int fl = fcntl(fd, F_GETFD);
    if (fl >= 0) {
        (void)fcntl(fd, F_SETFD, fl | FD_CLOEXEC);
    }
}

int sim_pty_open(struct sim_pty *t, char *err, size_t errcap)
{
    struct termios tio;
    const char *name;
    int fl;
    t->master = -1;
    t->slave = -1;
    t->path[0] = '\0';
    t->pid = -1;
    t->reaped = 0;
    t->status = 0;
    t->master = posix_openpt(O_RDWR | O_NOCTTY);
    if (t->master < 0) {
        snprintf(err, errcap, "posix_openpt: %s", strerror(errno));
        return -1;
    }
    pty_cloexec(t->master);
    if (grantpt(t->master) != 0 || unlockpt(t->master) != 0) {
        snprintf(err, errcap, "grantpt/unlockpt: %s", strerror(errno));
        goto fail;
    }
    name = ptsname(t->master);
    if (name == NULL || strlen(name) >= sizeof t->path) {
        snprintf(err, errcap, "ptsname failed");
        goto fail;
    }
    strcpy(t->path, name);
    /* raw: no echo, no line discipline, no CR/LF mapping, 8 data bits */
    if (tcgetattr(t->master, &tio) != 0) {
        snprintf(err, errcap, "tcgetattr: %s", strerror(errno));
        goto fail;
    }
    tio.c_iflag = 0;
    tio.c_oflag = 0;
    tio.c_lflag = 0;
    tio.c_cflag = (tio.c_cflag & ~(tcflag_t)(CSIZE | PARENB | CSTOPB)) | CS8 | CREAD | CLOCAL;
    tio.c_cc[VMIN] = 1;
    tio.c_cc[VTIME] = 0;
    if (tcsetattr(t->master, TCSANOW, &tio) != 0) {
        snprintf(err, errcap, "tcsetattr: %s", strerror(errno));
        goto fail;
    }
    fl = fcntl(t->master, F_GETFL);
    if (fl < 0 || fcntl(t->master, F_SETFL, fl | O_NONBLOCK) < 0) {
        snprintf(err, errcap, "fcntl O_NONBLOCK: %s", strerror(errno));
        goto fail;
    }
    t->slave = open(t->path, O_RDWR | O_NOCTTY);
    if (t->slave < 0) {
        snprintf(err, errcap, "open %s: %s", t->path, strerror(errno));
        goto fail;
    }
    pty_cloexec(t->slave);
    return 0;
fail:
    close(t->master);
    t->master = -1;
    return -1;
}

/* In the child, after fork: never returns. Reports errno through fd `ep`. */
static void pty_child(struct sim_pty *t, char *const argv[], int on_stdio, int ep)
{
    sigset_t none;
    int e, fd;
    (void)signal(SIGPIPE, SIG_DFL); /* ignored dispositions survive exec */
    (void)signal(SIGINT, SIG_DFL);
    (void)signal(SIGTERM, SIG_DFL);
    (void)signal(SIGHUP, SIG_DFL);
    sigemptyset(&none);
    (void)sigprocmask(SIG_SETMASK, &none, NULL);
    if (on_stdio) {
        (void)setsid(); /* the slave becomes its controlling terminal */
        fd = open(t->path, O_RDWR); /* becomes the controlling terminal */
        if (fd < 0 || dup2(fd, 0) < 0 || dup2(fd, 1) < 0) {
            goto fail;
        }
        if (fd > 1) {
            close(fd);
        }
    } else {
        /* own process group, but no new session: a program that opens the slave
         * itself (QEMU) does not acquire it as controlling terminal, so the
         * hang-up never SIGHUPs it; host_sim ends it with SIGTERM */
        (void)setpgid(0, 0);
        fd = open("/dev/null", O_RDONLY);
        if (fd < 0 || dup2(fd, 0) < 0 || dup2(2, 1) < 0) {
            goto fail;
        }
        if (fd > 1) {
            close(fd);
        }
    }
    /* master, the parent's slave and ep are close-on-exec */
    execvp(argv[0], argv);
fail:
    e = errno;
    if (write(ep, &e, sizeof e) < 0) {
        /* nothing left to report to */
    }
    _exit(127);
}

int sim_pty_spawn(struct sim_pty *t, char *const argv[], int on_stdio, char *err,
                  size_t errcap)
{
    int ep[2], e = 0;
    ssize_t n;
    struct pollfd pf;
    if (pipe(ep) != 0) {
        snprintf(err, errcap, "pipe: %s", strerror(errno));
        return -1;
    }
    pty_cloexec(ep[0]);
    pty_cloexec(ep[1]);
    fflush(NULL);
    t->pid = fork();
    if (t->pid < 0) {
        snprintf(err, errcap, "fork: %s", strerror(errno));
        close(ep[0]);
        close(ep[1]);
        return -1;
    }
    if (t->pid == 0) {
        close(ep[0]);
        pty_child(t, argv, on_stdio, ep[1]);
    }
    close(ep[1]);
    /* EOF on the pipe = exec succeeded; 4 bytes = its errno. Bounded wait. */
    pf.fd = ep[0];
    pf.events = POLLIN;
    pf.revents = 0;
    do {
        n = poll(&pf, 1, 5000);
    } while (n < 0 && errno == EINTR);
    n = n > 0 ? read(ep[0], &e, sizeof e) : -1;
    close(ep[0]);
    if (n == (ssize_t)sizeof e) {
        snprintf(err, errcap, "cannot run %s: %s", argv[0], strerror(e));
        (void)sim_pty_wait(t, 1000);
        (void)sim_pty_stop(t, 100);
        return -1;
    }
    if (n != 0) {
        snprintf(err, errcap, "cannot confirm that %s started", argv[0]);
        (void)sim_pty_stop(t, 100);
        return -1;
    }
    return 0;
}

void sim_pty_release(struct sim_pty *t)
{
    if (t->slave >= 0) {
        close(t->slave);
        t->slave = -1;
    }
}

void sim_pty_hangup(struct sim_pty *t)
{
    sim_pty_release(t);
    if (t->master >= 0) {
        close(t->master);
        t->master = -1;
    }
}

int sim_pty_exited(struct sim_pty *t)
{
    pid_t r;
    if (t->pid < 0 || t->reaped) {
        return 1;
    }
    r = waitpid(t->pid, &t->status, WNOHANG);
    if (r == t->pid || (r < 0 && errno == ECHILD)) {
        t->reaped = 1;
        return 1;
    }
    return 0;
}

int sim_pty_wait(struct sim_pty *t, int ms)
{
    struct timespec ts;
    int waited = 0;
    ts.tv_sec = 0;
    ts.tv_nsec = 5 * 1000000L;
    while (!sim_pty_exited(t)) {
        if (waited >= ms) {
            return 0;
        }
        (void)nanosleep(&ts, NULL);
        waited += 5;
    }
    return 1;
}

int sim_pty_stop(struct sim_pty *t, int grace_ms)
{
    if (sim_pty_exited(t)) {
        return 0;
    }
    (void)kill(-t->pid, SIGTERM); /* the whole group (QEMU, a shell's children) */
    (void)kill(t->pid, SIGTERM);  /* in case setsid had not run yet */
    if (sim_pty_wait(t, grace_ms)) {
        return 1;
    }
    (void)kill(-t->pid, SIGKILL);
    (void)kill(t->pid, SIGKILL);
    while (!t->reaped) {
        if (waitpid(t->pid, &t->status, 0) == t->pid || errno == ECHILD) {
            t->reaped = 1;
        }
    }
    return 2;
}

const char *sim_pty_describe(int status, char *buf, size_t cap)
{
    if (WIFEXITED(status)) {
        snprintf(buf, cap, "exit %d", WEXITSTATUS(status));
    } else if (WIFSIGNALED(status)) {
        snprintf(buf, cap, "signal %d", WTERMSIG(status));
    } else {
        snprintf(buf, cap, "status 0x%x", (unsigned)status);
    }
    return buf;
}
