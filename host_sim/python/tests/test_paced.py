"""The wire model of `make bench-py` (tools/baud_relay.py: a serial line between two ptys)
carries a whole run intact in both formats. Functional only: the utilization figures are
measured by `make bench-py`, not asserted here."""
from __future__ import annotations

import subprocess
import sys

import pytest
from conftest import JOBS, REPO, host_sim_csv, points_csv

from canalpath import Job, Link


@pytest.mark.parametrize("fmt, ref", [("FRAMES", "paper_frames"), ("GCODE", "paper_gcode")])
def test_run_through_a_paced_line(fw, fmt, ref):
    relay = subprocess.Popen([sys.executable, str(REPO / "tools" / "baud_relay.py"), fw.link, "1000000"],
                             stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    try:
        assert relay.stdout is not None
        path = relay.stdout.readline().decode().strip()
        assert path.startswith("/dev/")
        with Link.open(path, timeout=5.0) as link:
            link.send_job(Job.from_file(str(JOBS / "paper_gcode.job")).format(fmt))
            pts = list(link.run())
            r = link.last_run
            # 10 bit times per byte: the run cannot be faster than the line
            assert r.seconds >= r.bytes_in * 10 / 1000000 * 0.99
    finally:
        relay.terminate()
        relay.wait(10)
    assert points_csv(pts) == host_sim_csv(ref)
