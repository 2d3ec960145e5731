"""Streams through the library against fw_native on a pty: every demo job gives host_sim's
points; the link's commands, real-time bytes and refusals."""
from __future__ import annotations

import pytest
from conftest import JOBS, demo_jobs, host_sim_csv, points_csv

from canalpath import Aborted, CommandError, Job, Link, Progress, RunError, read_script, run_script


@pytest.mark.parametrize("job", demo_jobs())
def test_demo_job_gives_host_sims_points(fw, job):
    """Every job of `make demo`, as a job file (all its RUNs and expectations)."""
    pts = []
    with Link.open(fw.link) as link:
        n = run_script(link, read_script(str(JOBS / (job + ".job"))), on_point=pts.append)
    assert n == len(pts) > 100
    assert points_csv(pts) == host_sim_csv(job)


@pytest.mark.parametrize("job", ["paper_frames", "paper_gcode_cs", "boss_gcode", "placed_frames", "axis5_ijk"])
def test_more_jobs_give_host_sims_points(fw, job):
    """Formats and options beyond the demo: checksums, ball tool, placement, 5-axis words."""
    pts = []
    with Link.open(fw.link) as link:
        run_script(link, read_script(str(JOBS / (job + ".job"))), on_point=pts.append)
    assert points_csv(pts) == host_sim_csv(job)


def test_builder_job_both_formats_and_progress(fw):
    job = Job().curve_arc(0, 0, 3, 0, 360).radius_cos(5.5, 10.5, 2).lines(8, -25, 10).tol(2).feed(600).safe(50)
    seen: list[Progress] = []
    program: list[str] = []
    with Link.open(fw.link) as link:
        link.send_job(job.format("GCODE"))
        g = list(link.run(progress=seen.append, on_gcode=program.append))
        info = link.last_run.info
        assert info is not None and info.format == "GCODE" and info.points == len(g) == 4117
        assert program[0] == "G21 G90 G17 G94 G54" and program[-1] == "M2"
        assert sum(1 for s in program if s.startswith("G1 ")) == 4117
        link.send_job(job.format("FRAMES"))
        f = list(link.run(progress=seen.append))
        assert link.last_run.format == "FRAMES" and link.last_run.naks == 0
    assert [(p.k, p.x, p.y, p.z, p.line, p.index) for p in g] == [(p.k, p.x, p.y, p.z, p.line, p.index) for p in f]
    assert all(p.normal is not None for p in f)
    assert points_csv(g) == host_sim_csv("paper_gcode")
    final = [s for s in seen if s.points == 4117]
    assert len(final) >= 2 and all(s.total == 4117 and s.rate > 0 for s in final)


def test_handshake_commands_status_dump(fw):
    with Link.open(fw.link) as link:
        assert link.info is not None and link.info.version.startswith("canalpath ")
        assert link.info.proto == 1 and link.info.window == 16 and "CANAL" in link.info.models
        assert link.status().state == "Idle"
        link.command("CURVE ARC 0 0 3 0 360")
        assert link.dump() == ["CURVE ARC 0 0 3 0 360"]
        with pytest.raises(CommandError) as ei:
            link.command("LINES 3 -10 200")
        assert ei.value.code == 6 and ei.value.cause == "LINES 200: |u| <= 180"
        with pytest.raises(CommandError) as ei:
            link.command("FOO")
        assert ei.value.code == 1 and ei.value.text == "unknown command"
        assert link.status().state == "Idle"      # answered normally after the errors


def test_run_refusals_are_typed(fw):
    with Link.open(fw.link) as link:
        link.command("JOB CLEAR")
        with pytest.raises(RunError) as ei:
            list(link.run())
        assert ei.value.code == 10
        link.send_job(Job().curve_arc(0, 0, 3, 0, 360).radius_cos(5.5, 10.5, 2).lines(5, -20, 60).format("FRAMES"))
        with pytest.raises(RunError) as ei:
            list(link.run())
        assert ei.value.code == 16 and ei.value.text == "line crosses a cuspidal edge"
        link.send_job(Job().curve_arc(0, 0, 3, 0, 360).radius_cos(5.5, 10.5, 2).lines(8, -25, 10).safe(50))
        with pytest.raises(RunError) as ei:
            list(link.run())
        assert ei.value.code == 40
        with pytest.raises(RunError) as ei:
            list(link.resume(10 ** 6))
        assert ei.value.code in (21, 40)
        assert link.status().state == "Idle"


@pytest.mark.parametrize("fmt", ["GCODE", "FRAMES"])
def test_hold_go_and_abort(fw, fmt):
    job = Job().curve_arc(0, 0, 3, 0, 360).radius_cos(5.5, 10.5, 2).lines(8, -25, 10).tol(2).feed(600).safe(50)
    with Link.open(fw.link) as link:
        link.send_job(job.format(fmt))
        n = 0
        with pytest.raises(Aborted):
            for _p in link.run():
                n += 1
                if n == 200:
                    link.hold()
                    link.go()
                if n == 1000:
                    link.abort()
        assert 1000 <= n < 4117
        assert link.last_run.error is not None
        link.connect()                              # late lines of the run drained
        assert link.status().state == "Idle"
        # and the job runs again, whole
        assert len(list(link.run())) == 4117


@pytest.mark.parametrize("fmt", ["GCODE", "FRAMES"])
def test_leaving_a_run_early_aborts_it(fw, fmt):
    """A caller that stops iterating: the run is aborted and the link is idle again."""
    job = Job().curve_arc(0, 0, 3, 0, 360).radius_cos(5.5, 10.5, 2).lines(8, -25, 10).tol(2).feed(600).safe(50)
    with Link.open(fw.link) as link:
        link.send_job(job.format(fmt))
        it = link.run()
        first = [next(it) for _ in range(300)]
        it.close()
        assert link.status().state == "Idle"
        assert link.dump()[-1].startswith("RADIUS")      # commands answered normally
        again = list(link.run())
        assert [p.k for p in first] == list(range(300)) and len(again) == 4117
