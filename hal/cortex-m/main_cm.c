/* main_cm.c - firmware entry of the Cortex-M4F image (build/m4f/fw.elf).
 * SPDX-License-Identifier: MIT
 *
 * Owns the single protocol engine and the UART0 port (file-scope state is
 * allowed in hal/ only). Loop: proto_poll() until it reports idle, then sleep
 * in WFI until the next interrupt (UART RX/TX, or the 10 ms TIMER0 period). The firmware
 * sends nothing until the host speaks (see proto.h).
 *
 * Run it on QEMU with UART0 on a host-created pty (host_sim does this):
 *   qemu-system-arm -M mps2-an386 -display none -monitor none -serial /dev/pts/N \
 *       -semihosting-config enable=on,target=native -icount shift=7 -kernel build/m4f/fw.elf
 */
#include "hal_uart_cmsdk.h"
#include "proto.h"
#include "startup.h"

static struct hal_uart_cmsdk uart0;
static struct hal_uart uart;
static struct proto proto;

int main(void)
{
    struct proto_cfg cfg = {0};
    hal_uart_cmsdk_clock_init();
    hal_uart_cmsdk_init(&uart0, &uart, 0u);
    cfg.uart = &uart;
    for (;;) {
        int r;
        if (proto_init(&proto, &cfg) != CP_OK) {
            return 1; /* unreachable: uart is complete; Reset_Handler then parks */
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
