/* semihost.h - ARM semihosting for the TEST and BENCH images (never linked into fw.elf).
 * SPDX-License-Identifier: MIT
 *
 * Needs QEMU's `-semihosting-config enable=on,target=native`; without it the
 * BKPT 0xAB traps to HardFault and the guest spins (always run under `timeout`).
 * Output goes to QEMU's stderr. semihost.c also provides the newlib system calls
 * (_write to stdout/stderr, _sbrk over the RAM above .bss, _exit, ...), so the
 * test image can use printf, and a HardFault_Handler that reports and exits 99.
 */
#ifndef SEMIHOST_H
#define SEMIHOST_H

/* Exit code reported by a HardFault in the test/bench images. */
#define SEMIHOST_EXIT_FAULT 99

/* Stop the emulator; QEMU's exit status is code (SYS_EXIT_EXTENDED, 0x20). */
void semihost_exit(int code) __attribute__((noreturn));

/* Write a NUL-terminated string to the host's stderr (SYS_WRITE0, 0x04). */
void semihost_write0(const char *s);

#endif /* SEMIHOST_H */
