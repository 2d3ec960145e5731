/* main_cm.c - firmware entry of the Cortex-M4F image (build/m4f/fw.elf).
 * SPDX-License-Identifier: MIT
 *
 * Owns the single protocol engine and the two UART ports (file-scope state is allowed
 * in hal/ only): UART0 is the host link, UART1 the machine link (cfg.machine; the image
 * always has one, LINK MACHINE sends the program there and pass-through uses it). Loop:
 * proto_poll() until it reports idle, then sleep in WFI until the next interrupt (either
 * UART's RX/TX, or the 10 ms TIMER0 period). The firmware sends nothing until the host
 * speaks (see proto.h).
 *
 * Run it on QEMU with UART0 on a host-created pty (host_sim does this) and, for the
 * machine link, UART1 on a second one (the second -serial):
 *   qemu-system-arm -M mps2-an386 -display none -monitor none -serial /dev/pts/N \
 *       [-serial /dev/pts/M] -semihosting-config enable=on,target=native -icount shift=7 \
 *       -kernel build/m4f/fw.elf
 * With one -serial, UART1 has no backend: QEMU drops what the firmware sends there and
 * nothing comes back (a LINK MACHINE run or a passed-through line then ends in error:22
 * after OUT_GCODE_PEER_TIMEOUT_MS).
 */
#include "hal_uart_cmsdk.h"
#include "proto.h"
#include "startup.h"

static struct hal_uart_cmsdk uart0; /* unit 0: the host link */
static struct hal_uart_cmsdk uart1; /* unit 1: the machine link */
static struct hal_uart host;
static struct hal_uart machine;
static struct proto proto;

int main(void)
{
    struct proto_cfg cfg = {0};
    hal_uart_cmsdk_clock_init();
    hal_uart_cmsdk_init(&uart0, &host, 0u);
    hal_uart_cmsdk_init(&uart1, &machine, 1u);
    cfg.uart = &host;
    cfg.machine = &machine;
    for (;;) {
        int r;
        if (proto_init(&proto, &cfg) != CP_OK) {
            return 1; /* unreachable: both ports are complete; Reset_Handler then parks */
        }
        /* Serve until the engine reports a fatal error. CP_ERR_IO is sticky, but
         * this port never reports it (a serial line has no hang-up), so a fatal
         * error restarts the engine rather than stopping the firmware. */
        do {
            r = proto_poll(&proto);
            if (r == 0) {
                hal_uart_cmsdk_sleep();
            }
        } while (r >= 0);
    }
}
