"""Acceptance: `pip install .` in a fresh venv (--system-site-packages for pyserial), then
the installed CLI runs the paper example against fw_native --pty."""
from __future__ import annotations

import pathlib
import shutil
import subprocess

from conftest import JOBS, PYROOT, host_sim_csv


def test_pip_install_in_a_fresh_venv_and_the_cli_runs_the_paper(fw, tmp_path: pathlib.Path):
    src = tmp_path / "src"                  # a copy: the build leaves nothing in the checkout
    shutil.copytree(PYROOT, src, ignore=shutil.ignore_patterns("tests", "build", "*.egg-info", "__pycache__"))
    venv = tmp_path / "venv"
    subprocess.run(["/usr/bin/python3", "-m", "venv", "--system-site-packages", str(venv)], check=True,
                   timeout=120)
    py = venv / "bin" / "python"
    r = subprocess.run([str(py), "-m", "pip", "install", "--no-build-isolation", "--no-index", "-q", str(src)],
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=300)
    assert r.returncode == 0, r.stdout.decode()[-2000:]
    where = subprocess.run([str(py), "-c", "import canalpath; print(canalpath.__file__)"], cwd=tmp_path,
                           stdout=subprocess.PIPE, check=True, timeout=60).stdout.decode()
    assert where.startswith(str(venv)), where
    out = tmp_path / "paper.csv"
    ngc = tmp_path / "paper.ngc"
    r = subprocess.run([str(py), "-m", "canalpath", "run", str(JOBS / "paper_gcode.job"), "--port", fw.link,
                        "--csv", str(out), "--gcode", str(ngc)], cwd=tmp_path,
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=120)
    assert r.returncode == 0, r.stdout.decode()
    assert "4117 points" in r.stdout.decode()
    assert out.read_text() == host_sim_csv("paper_gcode")
    prog = ngc.read_text().splitlines()
    assert prog[0] == "G21 G90 G17 G94 G54" and prog[-1] == "M2" and len(prog) == 4117 + 5  # lead: G21.., G0 Z, G0 XY; trail: G0 Z, M2
    # the console script, info and status
    r = subprocess.run([str(venv / "bin" / "canalpath"), "info", "--port", fw.link], stdout=subprocess.PIPE,
                       timeout=60)
    assert r.returncode == 0 and r.stdout.decode().startswith("[VER:canalpath ")
    r = subprocess.run([str(py), "-m", "canalpath", "status", "--port", fw.link], stdout=subprocess.PIPE,
                       timeout=60)
    assert r.returncode == 0 and r.stdout.decode().strip() == "<Idle>"


def test_cli_reports_errors_with_exit_1(fw, tmp_path: pathlib.Path):
    bad = tmp_path / "bad.job"
    bad.write_text("CURVE ARC 0 0 3 0 360\nLINES 3 -10 200\n")
    r = subprocess.run(["/usr/bin/python3", "-m", "canalpath", "run", str(bad), "--port", fw.link],
                       cwd=PYROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=60)
    assert r.returncode == 1
    assert "error:6 value out of range (LINES 200: |u| <= 180)" in r.stdout.decode()


def test_cli_progress_bar(fw, tmp_path: pathlib.Path):
    r = subprocess.run(["/usr/bin/python3", "-m", "canalpath", "run", str(JOBS / "boss_frames.job"), "--port", fw.link,
                        "--progress"], cwd=PYROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=60)
    assert r.returncode == 0, r.stderr.decode()
    err = r.stderr.decode()
    assert "1999/1999 points" in err and "points/s" in err and "ETA" in err and "[#" in err
