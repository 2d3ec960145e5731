#!/usr/bin/python3
"""bench_py.py - the Python host library's figures (`make bench-py`).

1. decode: the library's whole FRAMES receive path (decoder, CRC, in-order check, Point
   objects, cumulative ACKs) on a recorded-form stream held in memory: BEGIN, N POINT
   frames, END, "ok", read in 4096-byte chunks from an in-memory transport. frames/s.
2. wire: the paper job (LINES 8 -25 10, TOL 2: 4117 points) streamed by the library from
   fw_native --pty through tools/baud_relay.py at 115200 baud (10 bit times per byte,
   both directions), in FORMAT GCODE (the library answers every line "ok", as the
   machine; also with CHECKSUM ON, each line's checksum verified) and FORMAT FRAMES (a
   cumulative ACK per read). Utilization = bytes received x 10 / 115200
   divided by the time from RUN sent to the final "ok" (host_sim's --baud definition).
   Also the same runs unpaced (the pty as fast as firmware and library go), points/s.

Usage: bench_py.py [BUILD]   (default build). Prints one "bench-py:" row per figure.
SPDX-License-Identifier: MIT
"""
from __future__ import annotations

import os
import pathlib
import struct
import subprocess
import sys
import tempfile
import time

REPO = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO / "host_sim" / "python"))

from canalpath import Job, Link  # noqa: E402
from canalpath import frames as fr  # noqa: E402

BAUD = int(os.environ.get("BENCH_BAUD", "115200"))
N_FRAMES = 200000


class MemoryTransport:
    """Reads a prepared byte string in chunks; writes are counted and dropped."""

    def __init__(self, data: bytes, chunk: int = 4096) -> None:
        self.data = memoryview(data)
        self.pos = 0
        self.chunk = chunk
        self.written = 0

    def read(self, timeout: float) -> bytes:
        b = bytes(self.data[self.pos:self.pos + self.chunk])
        self.pos += len(b)
        return b

    def write(self, data: bytes, timeout: float) -> None:
        self.written += len(data)

    def discard_input(self) -> None:
        pass

    def close(self) -> None:
        pass


def stream(n: int) -> bytes:
    """BEGIN, n POINT frames (a helix-like path), END, ok."""
    out = [fr.encode(0, fr.BEGIN, struct.pack("<IIHHHB", n, 0, 1, 4096, 0, 0))]
    for k in range(n):
        pl = struct.pack("<IiiihhhhH", k, 100000 + k, -50000 + 3 * k, 14991 - k % 977,
                         k % 32767, -(k % 32767), 32767 - k % 100, 0, k % 65536)
        out.append(fr.encode(k + 1, fr.POINT, pl))
    out.append(fr.encode(n + 1, fr.END, struct.pack("<BI", 0, n)))
    return b"".join(out) + b"ok\n"


def bench_decode() -> None:
    data = stream(N_FRAMES)
    best = 0.0
    for _ in range(3):
        link = Link(MemoryTransport(data), connect=False)  # type: ignore[arg-type]
        t0 = time.perf_counter()
        pts = list(link.run(fmt="FRAMES"))
        dt = time.perf_counter() - t0
        assert len(pts) == N_FRAMES and pts[-1].k == N_FRAMES - 1 and link.last_run.ok
        best = max(best, N_FRAMES / dt)
    print("bench-py: decode  %8.0f frames/s  (FRAMES receive path: CRC, order, Point, ACK; %d frames, best of 3)"
          % (best, N_FRAMES))


def _timed(link: Link) -> float:
    t0 = time.perf_counter()
    n = sum(1 for _ in link.run())
    assert n == 4117
    return time.perf_counter() - t0


def bench_wire(build: pathlib.Path) -> None:
    tmp = pathlib.Path(tempfile.mkdtemp(prefix="bench-py-"))
    link_path = str(tmp / "ttyCP")
    fw = subprocess.Popen([str(build / "host" / "fw_native"), "--pty", link_path],
                          stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    relay = None
    try:
        end = time.monotonic() + 10
        while not os.path.exists(link_path) and time.monotonic() < end:
            time.sleep(0.01)
        base0 = Job.from_file(str(REPO / "tests" / "jobs" / "paper_gcode.job"))
        with Link.open(link_path) as direct:   # no line model: the pty as fast as it goes
            for fmt in ("GCODE", "FRAMES"):
                direct.send_job(Job(base0.commands).format(fmt))
                best = min(_timed(direct) for _ in range(3))
                print("bench-py: unpaced %-6s %7.0f points/s  (fw_native + library over a pty, the paper, best of 3)"
                      % (fmt, 4117 / best))
        relay = subprocess.Popen([sys.executable, str(REPO / "tools" / "baud_relay.py"), link_path, str(BAUD)],
                                 stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL)
        assert relay.stdout is not None
        slow = relay.stdout.readline().decode().strip()
        base = Job.from_file(str(REPO / "tests" / "jobs" / "paper_gcode.job"))
        bt = 10.0 / BAUD
        with Link.open(slow, timeout=5.0) as link:
            for fmt in ("GCODE", "GCODE+CS", "FRAMES"):
                job = Job(base.commands).format(fmt.split("+")[0])
                if fmt == "GCODE+CS":
                    job.checksum(True)  # N<i> ... *<cs> lines, verified by the library
                link.send_job(job)
                pts = list(link.run())
                r = link.last_run
                util = r.bytes_in * bt / r.seconds
                print("bench-py: wire %-8s %6.2f %% at %d baud  (%d points, %d bytes in %.2f s; wire needs %.2f s;"
                      " naks %d)" % (fmt, 100 * util, BAUD, len(pts), r.bytes_in, r.seconds, r.bytes_in * bt, r.naks))
    finally:
        if relay is not None:
            relay.terminate()
            relay.wait(5)
        fw.terminate()
        fw.wait(5)


def main() -> int:
    build = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "build")
    if not build.is_absolute():
        build = REPO / build
    bench_decode()
    bench_wire(build)
    return 0


if __name__ == "__main__":
    sys.exit(main())
