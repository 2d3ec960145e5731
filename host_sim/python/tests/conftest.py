"""Fixtures: the native firmware on a pty (fw_native --pty), host_sim's reference CSVs,
misbehaving peers on a pty pair.

Timeouts follow the rule of mk/m4f.mk (>= 5x the unloaded time, measured 2026-11-26):
a reply takes <= 7 ms natively and QEMU's boot to the first answer <= 45 ms, so the 2 s
reply timeout is > 40x; a whole demo job streams in <= 0.3 s, each test's own bounds
are 10 s or more.
"""
from __future__ import annotations

import os
import pathlib
import re
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterator

import pytest

HERE = pathlib.Path(__file__).resolve().parent
PYROOT = HERE.parent
REPO = PYROOT.parent.parent
sys.path.insert(0, str(PYROOT))          # the package from the checkout
sys.path.insert(0, str(HERE))            # the helpers

BUILD = pathlib.Path(os.environ.get("BUILD", str(REPO / "build")))
if not BUILD.is_absolute():
    BUILD = REPO / BUILD
FW = BUILD / "host" / "fw_native"
HOST_SIM = BUILD / "host" / "host_sim"
ELF = BUILD / "m4f" / "fw.elf"
JOBS = REPO / "tests" / "jobs"
QEMU = os.environ.get("QEMU", "qemu-system-arm")


def demo_jobs() -> list[str]:
    """The jobs of `make demo` (mk/stream.mk)."""
    text = (REPO / "mk" / "stream.mk").read_text()
    m = re.search(r"^demo:.*?for j in ([^;]*); do", text, re.S | re.M)
    assert m, "the demo list in mk/stream.mk"
    return m.group(1).split()


class Firmware:
    """fw_native --pty LINK, started and stopped by the fixture."""

    def __init__(self, tmp: pathlib.Path) -> None:
        self.link = str(tmp / "ttyCP")
        self.log = open(tmp / "fw.log", "w")
        self.proc = subprocess.Popen([str(FW), "--pty", self.link], stdin=subprocess.DEVNULL,
                                     stdout=subprocess.DEVNULL, stderr=self.log)
        end = time.monotonic() + 10
        while not os.path.exists(self.link):
            if time.monotonic() > end or self.proc.poll() is not None:
                raise RuntimeError("fw_native --pty did not create %s" % self.link)
            time.sleep(0.01)

    def stop(self) -> None:
        if self.proc.poll() is None:
            self.proc.terminate()
            try:
                self.proc.wait(5)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        self.log.close()


@pytest.fixture
def fw(tmp_path: pathlib.Path) -> Iterator[Firmware]:
    """A fresh native firmware on a pty; its path is ``fw.link``."""
    if not FW.exists():
        pytest.fail("%s missing: make build/host/fw_native" % FW)
    f = Firmware(tmp_path)
    try:
        yield f
    finally:
        f.stop()


_REF_DIR = pathlib.Path(tempfile.mkdtemp(prefix="canalpath-ref-"))


def host_sim_csv(job: str) -> str:
    """host_sim's --csv of tests/jobs/<job>.job against fw_native (the reference client)."""
    out = _REF_DIR / (job + ".csv")
    if not out.exists():
        r = subprocess.run([str(HOST_SIM), "--target", "native", "--fw", str(FW), "--job",
                            str(JOBS / (job + ".job")), "--csv", str(out)],
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=120)
        assert r.returncode == 0, "host_sim on %s: %s" % (job, r.stdout.decode()[-500:])
    return out.read_text()


def points_csv(points: list) -> str:
    """Points as host_sim writes them (header by the first point, one row per point)."""
    if not points:
        return ""
    head = "line,index,x,y,z,nx,ny,nz\n" if points[0].normal is not None else "line,index,x,y,z\n"
    return head + "".join(p.csv_row() + "\n" for p in points)
