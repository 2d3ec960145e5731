#!/usr/bin/python3
"""baud_relay.py - a serial line of a given baud rate between two ptys (the wire model of
`make bench-py` and of the library's paced test).

Usage: baud_relay.py UPSTREAM BAUD
  UPSTREAM  a pty path (the LINK of `fw_native --pty LINK`)
  BAUD      bits per second; every byte takes 10 bit times (8N1), in each direction

Creates a new pty pair, prints its slave path on stdout (one line) and relays both ways:
a byte read from one side is written to the other side once its 10 bit times on the
wire have passed after the previous byte in the same direction (or after its arrival,
if the line was idle), so each direction carries at most BAUD/10 bytes per second, as a
UART does. Runs until SIGTERM or stdin closes; then prints the bytes relayed on stderr.
SPDX-License-Identifier: MIT
"""
from __future__ import annotations

import os
import select
import signal
import sys
import time
import tty


class Direction:
    """One direction of the line: the bytes waiting and the start time of the next one."""

    def __init__(self, out_fd: int) -> None:
        self.out = out_fd
        self.q = bytearray()
        self.t = 0.0
        self.relayed = 0

    def take(self, data: bytes, now: float) -> None:
        if not self.q:
            self.t = max(self.t, now)  # an idle line starts the byte at once
        self.q += data

    def due(self, bt: float) -> float:
        """When the next byte is complete on the wire (inf if none waits)."""
        return self.t + bt if self.q else float("inf")

    def pump(self, now: float, bt: float) -> None:
        n = min(len(self.q), int((now - self.t) / bt)) if self.q else 0
        if n <= 0:
            return
        try:
            w = os.write(self.out, self.q[:n])
        except BlockingIOError:
            w = 0
        except OSError:
            w = n  # the reader hung up: the bytes are lost on the wire
        del self.q[:w]
        self.t += w * bt
        self.relayed += w
        if w < n:
            self.t = max(self.t, now)  # the receiver did not take them: the line waited


def main() -> int:
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    up = os.open(sys.argv[1], os.O_RDWR | os.O_NOCTTY | os.O_NONBLOCK)
    tty.setraw(up)
    bt = 10.0 / float(sys.argv[2])
    master, slave = os.openpty()
    tty.setraw(master)
    tty.setraw(slave)
    os.set_blocking(master, False)
    print(os.ttyname(slave), flush=True)
    down, upw = Direction(master), Direction(up)
    stop = []
    signal.signal(signal.SIGTERM, lambda *_: stop.append(1))
    rd = [up, master, sys.stdin.fileno()]
    while not stop:
        now = time.monotonic()
        wake = min(down.due(bt), upw.due(bt), now + 0.05)
        try:
            r, _, _ = select.select(rd, [], [], max(0.0, wake - now))
        except InterruptedError:
            continue
        now = time.monotonic()
        for fd, d in ((up, down), (master, upw)):
            if fd in r:
                try:
                    data = os.read(fd, 65536)
                except OSError:
                    data = b""  # a pty side with nobody on it: EIO, nothing to relay
                if data:
                    d.take(data, now)
                elif fd == up:
                    stop.append(1)
        if sys.stdin.fileno() in r and not os.read(sys.stdin.fileno(), 4096):
            break
        down.pump(now, bt)
        upw.pump(now, bt)
    print("baud_relay: %d bytes down, %d up" % (down.relayed, upw.relayed), file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
