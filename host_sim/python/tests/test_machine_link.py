"""LINK MACHINE: the program goes down the machine link; the host link carries only
[RUN:...] and the reply. The library polls '?' when the run is quiet, so a machine
that takes longer than the library's run_timeout for one move does not fail the run."""
from __future__ import annotations

import os
import select
import subprocess
import threading
import time
import tty

from conftest import FW, JOBS

from canalpath import Job, Link


def _machine(master: int, stop: threading.Event, lines: list[str], slow_at: int, delay: float) -> None:
    buf = bytearray()
    while not stop.is_set():
        r, _, _ = select.select([master], [], [], 0.02)
        if not r:
            continue
        try:
            data = os.read(master, 4096)
        except OSError:
            return
        if b"?" in data:                   # grbl's real-time status request (the firmware's POLL)
            data = data.replace(b"?", b"")
            os.write(master, b"<Run|MPos:0.000,0.000,0.000|FS:600,0>\n")
        buf += data
        while b"\n" in buf:
            i = buf.index(b"\n")
            line = bytes(buf[:i]).decode()
            del buf[:i + 1]
            lines.append(line)
            if len(lines) == slow_at:
                time.sleep(delay)          # a long move: silent meanwhile
            os.write(master, b"ok\n")


def test_run_on_the_machine_link_with_a_slow_machine(tmp_path):
    master, slave = os.openpty()
    tty.setraw(master)
    tty.setraw(slave)
    link_path = str(tmp_path / "ttyCP")
    fw = subprocess.Popen([str(FW), "--pty", link_path, "--machine-tty", os.ttyname(slave)],
                          stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    stop = threading.Event()
    got: list[str] = []
    t = threading.Thread(target=_machine, args=(master, stop, got, 100, 3.0), daemon=True)
    t.start()
    try:
        end = time.monotonic() + 10
        while not os.path.exists(link_path) and time.monotonic() < end:
            time.sleep(0.01)
        with Link.open(link_path, timeout=2.0, run_timeout=2.0) as link:
            link.send_job(Job.from_file(str(JOBS / "pyserial.job")).machine("GRBL").link("MACHINE"))
            pts = list(link.run())
            r = link.last_run
            assert pts == [] and r.ok and r.info is not None and r.info.points == 1308
            assert any(st.state == "Run" and st.points == 1308 for st in r.statuses)
            assert r.seconds > 3.0
    finally:
        stop.set()
        t.join(5)
        fw.terminate()
        fw.wait(5)
        os.close(master)
        os.close(slave)
    assert sum(1 for ln in got if ln.startswith("G1 ")) == 1308
    assert got[0] == "G21 G90 G17 G94 G54" and got[-1] == "M2"
