"""docs/examples/ run against fw_native (run_job.py is also `make sim-pyserial`)."""
from __future__ import annotations

import subprocess

from conftest import JOBS, REPO, host_sim_csv


def test_run_job_example(fw, tmp_path):
    ngc = tmp_path / "out.ngc"
    r = subprocess.run(["/usr/bin/python3", str(REPO / "docs/examples/run_job.py"), fw.link,
                        str(JOBS / "paper_gcode.job"), str(ngc)], stdout=subprocess.PIPE, timeout=120)
    assert r.returncode == 0 and r.stdout.decode().strip() == "pyserial: 4117 points, RUN ok"
    g1 = [ln for ln in ngc.read_text().splitlines() if ln.startswith("G1 ")]
    ref = host_sim_csv("paper_gcode").splitlines()[1:]
    assert len(g1) == len(ref) == 4117
    assert all(g.split()[1:4] == ["X" + c.split(",")[2], "Y" + c.split(",")[3], "Z" + c.split(",")[4]]
               for g, c in zip(g1, ref))


def test_stream_frames_example(fw, tmp_path):
    out = tmp_path / "o.csv"
    r = subprocess.run(["/usr/bin/python3", str(REPO / "docs/examples/stream_frames.py"), fw.link, str(out)],
                       stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=120)
    assert r.returncode == 0, r.stderr.decode()
    rows = out.read_text().splitlines()[1:]
    ref = host_sim_csv("paper_frames").splitlines()[1:]
    assert len(rows) == len(ref) == 4117
    # same x, y, z, normal, line, index as host_sim's (columns in another order)
    for row, c in zip(rows, ref):
        k, x, y, z, nx, ny, nz, line, index = row.split(",")
        assert [line, index, x, y, z, nx, ny, nz] == c.split(",")
