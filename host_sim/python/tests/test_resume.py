"""A hang-up mid-run, resumed by the library, gives the uninterrupted stream."""
from __future__ import annotations

import pathlib

import pytest
from conftest import JOBS, Firmware, host_sim_csv, points_csv

from canalpath import Job, Link, LinkError


def _partial(link: Link, n: int) -> list:
    """Run and hang up (close the port, no abort) after n points."""
    got = []
    it = link.run()
    for p in it:
        got.append(p)
        if len(got) == n:
            break
    link.close()                       # the hang-up: the firmware is left mid-run
    it.close()                         # (the generator's abort finds the port closed)
    return got


@pytest.mark.parametrize("job, cut", [("paper_frames", 1500), ("paper_gcode", 2222), ("paper_gcode_cs", 777),
                                      ("boss_frames", 10)])
def test_hangup_then_resume_on_the_same_firmware(fw, job, cut):
    """Reconnect to the firmware that is still in the run (docs/PROTOCOL.md "Reconnecting"),
    send the job again and RESUME k."""
    spec = Job.from_file(str(JOBS / (job + ".job")))
    link = Link.open(fw.link)
    link.send_job(spec)
    got = _partial(link, cut)
    assert len(got) == cut
    with Link.open(fw.link) as again:     # aborts the run left behind, checks $I
        assert again.status().state == "Idle"
        again.send_job(spec)
        rest = list(again.resume(len(got)))
        info = again.last_run.info
        assert info is not None and info.first == cut
    assert rest[0].k == cut
    assert points_csv(got + rest) == host_sim_csv(job)


def test_hangup_then_resume_on_a_new_firmware(fw, tmp_path: pathlib.Path):
    """The firmware is restarted meanwhile (host_sim's sim-resume case)."""
    spec = Job.from_file(str(JOBS / "paper_frames.job"))
    link = Link.open(fw.link)
    link.send_job(spec)
    got = _partial(link, 3000)
    fw.stop()
    (tmp_path / "2").mkdir()
    fw2 = Firmware(tmp_path / "2")
    try:
        with Link.open(fw2.link) as again:
            again.send_job(spec)
            rest = list(again.resume(len(got)))
    finally:
        fw2.stop()
    assert points_csv(got + rest) == host_sim_csv("paper_frames")


def test_a_busy_firmware_is_left_alone_when_asked(fw):
    spec = Job.from_file(str(JOBS / "paper_frames.job"))
    link = Link.open(fw.link)
    link.send_job(spec)
    _partial(link, 100)
    with pytest.raises(LinkError) as ei:
        Link.open(fw.link, abort_busy=False)
    assert "FRAMES run" in str(ei.value)
    with Link.open(fw.link) as again:            # the default takes over
        assert again.status().state == "Idle"
