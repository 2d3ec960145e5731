"""The library against the Cortex-M image: build/m4f/fw.elf under qemu-system-arm
(mps2-an386), UART0 on a pty the test creates (as host_sim --target qemu does). The
streams are byte-identical to the native build's (docs/PROTOCOL.md "Resume"), so the
points equal host_sim's native CSV."""
from __future__ import annotations

import os
import shutil
import subprocess
import tty

import pytest
from conftest import ELF, JOBS, QEMU, host_sim_csv, points_csv

from canalpath import FdTransport, Link, read_script, run_script


@pytest.fixture
def qemu_link():
    if shutil.which(QEMU) is None:
        pytest.fail("%s not found (apt-get install qemu-system-arm)" % QEMU)
    if not ELF.exists():
        pytest.fail("%s missing: make m4f-fw" % ELF)
    master, slave = os.openpty()
    tty.setraw(master)
    tty.setraw(slave)
    proc = subprocess.Popen([QEMU, "-M", "mps2-an386", "-display", "none", "-monitor", "none",
                             "-serial", os.ttyname(slave), "-semihosting-config", "enable=on,target=native",
                             "-icount", "shift=7", "-kernel", str(ELF)],
                            stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    link = None
    try:
        # QEMU boots in <= 45 ms to the first answer; bytes before are lost: the link's
        # probe repeats until answered (timeout 5 s: > 100x)
        link = Link(FdTransport(master, owns=False), timeout=5.0, run_timeout=30.0)
        yield link
    finally:
        if link is not None:
            link.close()
        proc.terminate()
        try:
            proc.wait(5)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()
        os.close(master)
        os.close(slave)


@pytest.mark.parametrize("job", ["paper_frames", "paper_gcode_cs", "model_gsr_frames"])
def test_qemu_stream_equals_host_sims(qemu_link, job):
    assert qemu_link.info is not None and "GSR" in qemu_link.info.models
    pts = []
    run_script(qemu_link, read_script(str(JOBS / (job + ".job"))), on_point=pts.append)
    assert points_csv(pts) == host_sim_csv(job)
