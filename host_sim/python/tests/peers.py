"""Test peers and transports: misbehaving ports on a pty pair, a transport that corrupts
the bytes it reads."""
from __future__ import annotations

import os
import select
import threading
import tty

from canalpath import frames as fr
from canalpath.transport import FdTransport


class FakePeer:
    """A thread on the master side of a pty pair; the library opens ``path`` (the slave).

    kind: "echo" (every byte back), "silent" (reads, never answers), "garbage" (answers
    ``\\n`` and ``$I`` as canalpath, then answers RUN with endless garbage frames),
    "chatter" (answers every line with a line that is not canalpath's).
    """

    def __init__(self, kind: str) -> None:
        self.kind = kind
        self.master, slave = os.openpty()
        tty.setraw(self.master)
        tty.setraw(slave)
        self.path = os.ttyname(slave)
        self._slave = slave          # held: the pty stays up between client opens
        self._stop = threading.Event()
        self.received = bytearray()
        self._t = threading.Thread(target=self._loop, daemon=True)
        self._t.start()

    def _send(self, b: bytes) -> None:
        try:
            os.write(self.master, b)
        except OSError:
            pass

    def _loop(self) -> None:
        line = bytearray()
        running = False
        seq = 0
        while not self._stop.is_set():
            r, _, _ = select.select([self.master], [], [], 0.01)
            if running:  # garbage: frames with bad CRCs and random bytes, never a good one
                junk = bytes([32, seq & 0xFF, 2]) + os.urandom(26) + b"\x00\x00\x7e" + os.urandom(7)
                self._send(junk)
                seq += 1
            if not r:
                continue
            try:
                data = os.read(self.master, 4096)
            except OSError:
                continue
            self.received += data
            if self.kind == "echo":
                self._send(data)
                continue
            if self.kind == "silent":
                continue
            for c in data:
                if c != 10:
                    line.append(c)
                    continue
                s = bytes(line).decode("ascii", "replace")
                line.clear()
                if self.kind == "chatter":
                    self._send(b"Hello from another device\r\n")
                elif s == "":
                    self._send(b"ok\n")
                elif s == "$I":
                    self._send(b"[VER:canalpath 0.1.0 proto 1]\n[OPT:window=16]\nok\n")
                elif s == "RUN":
                    running = True
                else:
                    self._send(b"ok\n")

    def close(self) -> None:
        self._stop.set()
        self._t.join(2)
        os.close(self.master)
        os.close(self._slave)


class FaultyTransport(FdTransport):
    """An FdTransport that corrupts the bytes it reads: ``faults`` maps the index of a
    received byte (0-based, counted from ``arm()``) to "flip" (bit 0), "drop" or "dup"."""

    def __init__(self, fd: int, faults: dict[int, str], owns: bool = False) -> None:
        super().__init__(fd, owns=owns)
        self.faults = dict(faults)
        self.count = -1 << 62      # not armed: no byte is at a fault index
        self.injected = 0

    def arm(self) -> None:
        """Count from the next byte read (the RUN's stream), and the writes from the next."""
        self.count = 0
        self.writes = 0

    write_faults: dict[int, str] = {}
    writes = -1 << 62

    def write(self, data: bytes, timeout: float) -> None:
        """Writes (ACK, NAK, ok) after arm(): index -> "drop" (the whole write) or "flip"
        (bit 0 of its second byte)."""
        f = self.write_faults.get(self.writes)
        self.writes += 1
        if f == "drop":
            self.injected += 1
            return
        if f == "flip" and len(data) > 1:
            self.injected += 1
            data = data[:1] + bytes((data[1] ^ 1,)) + data[2:]
        super().write(data, timeout)

    def read(self, timeout: float) -> bytes:
        data = super().read(timeout)
        if not data or not self.faults:
            self.count += len(data)
            return data
        out = bytearray()
        for b in data:
            f = self.faults.get(self.count)
            self.count += 1
            if f is None:
                out.append(b)
            elif f == "flip":
                out.append(b ^ 1)
                self.injected += 1
            elif f == "dup":
                out += bytes((b, b))
                self.injected += 1
            else:
                self.injected += 1
        return bytes(out)


def abort_frame() -> bytes:
    """The ABORT frame of docs/PROTOCOL.md ``06 00 83 DF D7 7E``."""
    return fr.encode(0, fr.ABORT)
