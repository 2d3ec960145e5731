"""Byte transports under a :class:`~canalpath.Link`: a serial port or pty path (pyserial),
or an open file descriptor (a pty master, a socket pair in tests).

Every read and write is bounded by a timeout; a hang-up (end of file, EIO) raises
:class:`~canalpath.errors.LinkClosed`.
"""
from __future__ import annotations

import errno
import os
import select
import time
from typing import Protocol

from .errors import LinkClosed, LinkTimeout


class Transport(Protocol):
    """What a Link needs from the port."""

    def read(self, timeout: float) -> bytes:
        """The bytes available within timeout seconds (b"" if none came)."""

    def write(self, data: bytes, timeout: float) -> None:
        """Write every byte of data within timeout seconds."""

    def discard_input(self) -> None:
        """Drop the bytes received and not read yet."""

    def close(self) -> None:
        """Close the port (a hang-up as the firmware sees it)."""


class FdTransport:
    """A transport over an open, non-blocking file descriptor (e.g. a pty master)."""

    def __init__(self, fd: int, owns: bool = True, chunk: int = 65536) -> None:
        self.fd = fd
        self._owns = owns
        self._chunk = chunk
        os.set_blocking(fd, False)
        self.bytes_in = 0
        self.bytes_out = 0

    def read(self, timeout: float) -> bytes:
        if self.fd < 0:
            raise LinkClosed("the port is closed")
        try:
            r, _, _ = select.select([self.fd], [], [], max(0.0, timeout))
        except InterruptedError:  # pragma: no cover - PEP 475 retries
            return b""
        if not r:
            return b""
        try:
            data = os.read(self.fd, self._chunk)
        except BlockingIOError:
            return b""
        except OSError as e:
            raise LinkClosed("the port hung up (%s)" % os.strerror(e.errno or errno.EIO)) from e
        if not data:
            raise LinkClosed("the port hung up (end of file)")
        self.bytes_in += len(data)
        return data

    def write(self, data: bytes, timeout: float) -> None:
        if self.fd < 0:
            raise LinkClosed("the port is closed")
        view = memoryview(data)
        deadline = time.monotonic() + timeout
        while view:
            try:
                n = os.write(self.fd, view)
                self.bytes_out += n
                view = view[n:]
                continue
            except BlockingIOError:
                pass
            except OSError as e:
                raise LinkClosed("the port hung up (%s)" % os.strerror(e.errno or errno.EIO)) from e
            left = deadline - time.monotonic()
            if left <= 0:
                raise LinkTimeout("the port took no bytes for %.1f s (nobody reads it?)" % timeout)
            select.select([], [self.fd], [], min(left, 0.05))

    def discard_input(self) -> None:
        while self.fd >= 0:
            r, _, _ = select.select([self.fd], [], [], 0)
            if not r:
                return
            try:
                if not os.read(self.fd, self._chunk):
                    return
            except OSError:
                return

    def close(self) -> None:
        if self.fd >= 0 and self._owns:
            os.close(self.fd)
        self.fd = -1


class SerialTransport(FdTransport):
    """A serial port or pty path opened with pyserial (raw, 8N1, no flow control).

    pyserial opens and configures the port; reads and writes then go through its
    descriptor with select(), so every wait is bounded.
    """

    def __init__(self, path: str, baudrate: int = 115200) -> None:
        import serial  # Debian: python3-serial

        try:
            self.serial = serial.Serial(path, baudrate, timeout=0, write_timeout=0,
                                        exclusive=False)
        except (serial.SerialException, OSError) as e:
            raise LinkClosed("cannot open %s: %s" % (path, e)) from e
        self.path = path
        super().__init__(self.serial.fileno(), owns=False)

    def discard_input(self) -> None:
        try:
            self.serial.reset_input_buffer()
        except Exception:  # noqa: BLE001 - a hung-up port: nothing to drop
            pass
        super().discard_input()

    def close(self) -> None:
        try:
            self.serial.close()
        finally:
            self.fd = -1
