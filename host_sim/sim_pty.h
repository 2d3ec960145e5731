/* sim_pty.h - the pseudo-tty host_sim creates, and the firmware process on it.
 * SPDX-License-Identifier: MIT
 *
 * The host creates the pty (QEMU.md section 3): posix_openpt(O_RDWR|O_NOCTTY),
 * grantpt, unlockpt, raw termios and O_NONBLOCK on the master. The parent also
 * opens the slave and keeps it open until the firmware is known to have it (the
 * handshake answered): if nobody holds the slave, QEMU cannot open the path and
 * master reads fail with EIO. sim_pty_release() closes it afterwards, so a dying
 * firmware then shows up as EIO on the master as well as through waitpid.
 *
 * The child runs in its own process group, so Ctrl-C on host_sim's terminal never
 * reaches it and sim_pty_stop() can signal the group: with the slave on its stdio
 * it also gets its own session (setsid) with the slave as controlling terminal;
 * a program that opens the path itself (QEMU) only gets setpgid(0, 0).
 */
#ifndef SIM_PTY_H
#define SIM_PTY_H

#include <stddef.h>
#include <sys/types.h>

struct sim_pty {
    int master;      /* raw, O_NONBLOCK; -1 when closed */
    int slave;       /* the parent's slave descriptor; -1 once released */
    char path[64];   /* slave path, /dev/pts/N */
    pid_t pid;       /* child process (and process group), -1 if none */
    int reaped;      /* 1 once waitpid collected the child */
    int status;      /* its wait status (valid when reaped) */
};

/* Create the pty. Returns 0, or -1 with a message in err. */
int sim_pty_open(struct sim_pty *t, char *err, size_t errcap);

/* Fork and exec argv[0] (PATH search) with argv. on_stdio: the child opens the
 * slave as its controlling terminal on fds 0 and 1 (stderr stays host_sim's);
 * else its stdin is /dev/null, its stdout goes to host_sim's stderr and the
 * program is expected to open t->path itself (QEMU -serial /dev/pts/N).
 * Returns 0 once exec succeeded, or -1 with a message (exec failure included). */
int sim_pty_spawn(struct sim_pty *t, char *const argv[], int on_stdio, char *err,
                  size_t errcap);

/* Close the parent's slave descriptor (idempotent). */
void sim_pty_release(struct sim_pty *t);

/* Close the master: the firmware sees a hang-up (idempotent). */
void sim_pty_hangup(struct sim_pty *t);

/* Non-blocking: 1 if the child has exited (status recorded), else 0. */
int sim_pty_exited(struct sim_pty *t);

/* Wait up to ms for the child to exit on its own. 1 if it did, else 0. */
int sim_pty_wait(struct sim_pty *t, int ms);

/* Make sure the child is gone: SIGTERM to its process group, wait up to
 * grace_ms, then SIGKILL and reap. Returns 0 if it had already exited, 1 if
 * SIGTERM ended it, 2 if SIGKILL was needed. Idempotent. */
int sim_pty_stop(struct sim_pty *t, int grace_ms);

/* Describe a wait status ("exit 0", "signal 9") into buf. */
const char *sim_pty_describe(int status, char *buf, size_t cap);

#endif /* SIM_PTY_H */
