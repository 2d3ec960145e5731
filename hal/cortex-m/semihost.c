/* semihost.c - semihosting exit/output and newlib system calls (test and bench images only).
 * SPDX-License-Identifier: MIT
 */
#include <errno.h>
#include <stddef.h>
#include <stdint.h>
#include <sys/stat.h>

#include "semihost.h"
#include "startup.h"

#define SYS_WRITE0 0x04
#define SYS_EXIT 0x18
#define SYS_EXIT_EXTENDED 0x20
#define ADP_STOPPED_APPLICATION_EXIT 0x20026u
#define ADP_STOPPED_RUN_TIME_ERROR 0x20023u

/* newlib's reentrant layer calls these; declared here for -Wmissing-prototypes. */
int _write(int fd, const char *buf, int len);
int _read(int fd, char *buf, int len);
int _close(int fd);
int _lseek(int fd, int off, int whence);
int _fstat(int fd, struct stat *st);
int _isatty(int fd);
void *_sbrk(ptrdiff_t incr);
void _exit(int code) __attribute__((noreturn));
int _kill(int pid, int sig);
int _getpid(void);

extern uint32_t _ebss, __ram_end; /* linker/cortex_m_common.ld */

static int semihost_call(int op, const void *arg)
{
    register int r0 __asm("r0") = op;
    register const void *r1 __asm("r1") = arg;
    __asm volatile("bkpt 0xab" : "+r"(r0) : "r"(r1) : "memory"); /* M-profile semihosting trap */
    return r0;
}

void semihost_exit(int code)
{
    uint32_t blk[2];
    blk[0] = ADP_STOPPED_APPLICATION_EXIT;
    blk[1] = (uint32_t)code;
    (void)semihost_call(SYS_EXIT_EXTENDED, blk);
    /* Fallback for hosts without SYS_EXIT_EXTENDED: status 0 or 1 only. */
    (void)semihost_call(SYS_EXIT, (const void *)(uintptr_t)(code ? ADP_STOPPED_RUN_TIME_ERROR
                                                                 : ADP_STOPPED_APPLICATION_EXIT));
    for (;;) {
    }
}

void semihost_write0(const char *s)
{
    (void)semihost_call(SYS_WRITE0, s);
}

void HardFault_Handler(void)
{
    semihost_write0("HardFault\n");
    semihost_exit(SEMIHOST_EXIT_FAULT);
}

int _write(int fd, const char *buf, int len)
{
    char chunk[65];
    int done = 0;
    if (fd != 1 && fd != 2) {
        errno = EBADF;
        return -1;
    }
    while (done < len) {
        int n = len - done, i;
        if (n > (int)sizeof chunk - 1) {
            n = (int)sizeof chunk - 1;
        }
        for (i = 0; i < n; i++) {
            chunk[i] = buf[done + i];
        }
        chunk[n] = '\0';
        semihost_write0(chunk);
        done += n;
    }
    return len;
}

int _read(int fd, char *buf, int len)
{
    (void)fd;
    (void)buf;
    (void)len;
    return 0; /* no input: EOF */
}

int _close(int fd)
{
    (void)fd;
    return -1;
}

int _lseek(int fd, int off, int whence)
{
    (void)fd;
    (void)off;
    (void)whence;
    return 0;
}

int _fstat(int fd, struct stat *st)
{
    (void)fd;
    st->st_mode = S_IFCHR;
    return 0;
}

int _isatty(int fd)
{
    return fd <= 2;
}

/* Heap: from the end of .bss to the end of RAM (test linker script: megabytes). */
void *_sbrk(ptrdiff_t incr)
{
    static char *brk;
    char *prev;
    if (brk == NULL) {
        brk = (char *)&_ebss;
    }
    if (incr > (char *)&__ram_end - brk) {
        errno = ENOMEM;
        return (void *)-1;
    }
    prev = brk;
    brk += incr;
    return prev;
}

void _exit(int code)
{
    semihost_exit(code);
}

int _kill(int pid, int sig)
{
    (void)pid;
    (void)sig;
    errno = EINVAL;
    return -1;
}

int _getpid(void)
{
    return 1;
}
