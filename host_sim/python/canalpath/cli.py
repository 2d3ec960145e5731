"""The command line: ``python3 -m canalpath run JOB --port PATH [--csv OUT] [--gcode OUT]``,
``info``, ``status``."""
from __future__ import annotations

import argparse
import sys
import time
from typing import TextIO

from .errors import CanalpathError
from .frames import Point
from .link import Link, Progress
from .script import read_script, run_script


class _Bar:
    """A one-line progress bar on a terminal (stderr)."""

    def __init__(self, out: TextIO) -> None:
        self.out = out
        self.shown = False

    def __call__(self, p: Progress) -> None:
        width = 30
        frac = p.points / p.total if p.total else 0.0
        fill = int(width * min(1.0, frac))
        eta = "%.1f s" % p.eta if p.eta is not None else "?"
        self.out.write("\r[%s%s] %d/%d points  %.0f points/s  ETA %s   "
                       % ("#" * fill, "." * (width - fill), p.points, p.total, p.rate, eta))
        self.out.flush()
        self.shown = True

    def done(self) -> None:
        if self.shown:
            self.out.write("\n")
            self.out.flush()


def _open(a: argparse.Namespace) -> Link:
    return Link.open(a.port, a.baud, timeout=a.timeout)


def cmd_run(a: argparse.Namespace) -> int:
    steps = read_script(a.job)
    csv = open(a.csv, "w", encoding="ascii") if a.csv else None
    gc = open(a.gcode, "w", encoding="ascii") if a.gcode else None
    header = [False]

    def on_point(p: Point) -> None:
        if csv is not None:
            if not header[0]:
                csv.write("line,index,x,y,z,nx,ny,nz\n" if p.normal is not None else "line,index,x,y,z\n")
                header[0] = True
            csv.write(p.csv_row() + "\n")

    def on_gcode(line: str) -> None:
        if gc is not None:
            gc.write(line + "\n")

    bar = _Bar(sys.stderr) if (sys.stderr.isatty() and not a.quiet) or a.progress else None
    t0 = time.monotonic()
    try:
        with _open(a) as link:
            link.command("JOB CLEAR")
            n = run_script(link, steps, on_point=on_point, on_gcode=on_gcode, progress=bar)
    finally:
        if bar is not None:
            bar.done()
        for f in (csv, gc):
            if f is not None:
                f.close()
    dt = time.monotonic() - t0
    print("canalpath: %s: %d points in %.2f s" % (a.job, n, dt))
    return 0


def cmd_info(a: argparse.Namespace) -> int:
    with _open(a) as link:
        assert link.info is not None
        for line in link.info.lines:
            print(line)
    return 0


def cmd_status(a: argparse.Namespace) -> int:
    with _open(a) as link:
        print(link.status().raw)
    return 0


def main(argv: list[str] | None = None) -> int:
    """Entry point of ``python3 -m canalpath``."""
    ap = argparse.ArgumentParser(prog="canalpath", description="canalpath host: run jobs, stream points")
    sub = ap.add_subparsers(dest="cmd", required=True)

    def common(p: argparse.ArgumentParser) -> None:
        p.add_argument("--port", required=True, help="serial port or pty path (fw_native --pty LINK)")
        p.add_argument("--baud", type=int, default=115200)
        p.add_argument("--timeout", type=float, default=2.0, help="reply timeout, s (default 2)")

    r = sub.add_parser("run", help="send a job file and stream its RUNs")
    r.add_argument("job", help="job file (tests/jobs/*.job format)")
    common(r)
    r.add_argument("--csv", help="write the points as CSV (host_sim's columns)")
    r.add_argument("--gcode", help="write the G-code program lines received")
    r.add_argument("--progress", action="store_true", help="progress bar even when not a terminal")
    r.add_argument("--quiet", action="store_true", help="no progress bar")
    r.set_defaults(fn=cmd_run)
    i = sub.add_parser("info", help="$I: version and limits")
    common(i)
    i.set_defaults(fn=cmd_info)
    s = sub.add_parser("status", help="?: the status report")
    common(s)
    s.set_defaults(fn=cmd_status)
    a = ap.parse_args(argv)
    try:
        return int(a.fn(a))
    except (CanalpathError, OSError, ValueError) as e:
        print("canalpath: %s: %s" % (type(e).__name__, e), file=sys.stderr)
        return 1
