"""Bytes corrupted on the way (a test transport flips, drops or duplicates bytes of the
firmware's stream): FRAMES are NAKed and resent, CHECKSUM ON lines are asked again with
Resend; the points are exactly the uninterrupted run's."""
from __future__ import annotations

import os
import tty

import pytest
from conftest import JOBS, host_sim_csv, points_csv
from peers import FaultyTransport

from canalpath import Job, Link


def _faulty_link(path: str, faults: dict[int, str]) -> tuple[Link, FaultyTransport]:
    fd = os.open(path, os.O_RDWR | os.O_NOCTTY | os.O_NONBLOCK)
    tty.setraw(fd)
    t = FaultyTransport(fd, faults, owns=True)
    return Link(t), t


FRAME_FAULTS = [
    {5: "flip"},                                   # inside BEGIN
    {1000: "drop"}, {5003: "flip"}, {20007: "dup"},  # POINT frames
    {148: "flip"},                                 # a sync byte (frame 4 ends at 20 + 4 * 32)
    {31: "dup", 64: "drop", 65: "drop"},           # several in a row
    {k: "flip" for k in range(3000, 60000, 1777)},  # one every ~55 frames
]


@pytest.mark.parametrize("faults", FRAME_FAULTS, ids=lambda f: ",".join("%s@%d" % (v, k) for k, v in list(f.items())[:3]))
def test_corrupted_frames_are_recovered(fw, faults):
    spec = Job.from_file(str(JOBS / "paper_frames.job"))
    link, t = _faulty_link(fw.link, faults)
    with link:
        link.send_job(spec)
        t.arm()
        pts = list(link.run())
        res = link.last_run
        assert t.injected == len(faults)
        assert res.naks + res.dup_frames > 0 or res.bad_frames > 0
        assert link.status().state == "Idle"
    assert points_csv(pts) == host_sim_csv("paper_frames")


@pytest.mark.parametrize("faults", [{1000: "flip"}, {5003: "drop"}, {20007: "dup"}, {4122: "dup"},
                                    {4122: "drop"}, {k: "flip" for k in range(2000, 150000, 9999)}],
                         ids=lambda f: ",".join("%s@%d" % (v, k) for k, v in list(f.items())[:2]))
def test_corrupted_gcode_lines_are_resent(fw, faults):
    spec = Job.from_file(str(JOBS / "paper_gcode_cs.job"))
    link, t = _faulty_link(fw.link, faults)
    with link:
        link.send_job(spec)
        t.arm()
        pts = list(link.run())
        assert t.injected == len(faults)
        assert link.last_run.resends > 0
    assert points_csv(pts) == host_sim_csv("paper_gcode_cs")


def test_corrupted_acks_are_recovered(fw):
    """The other direction: ACKs dropped or garbled on their way to the firmware; the next
    cumulative ACK or the firmware's resend after 250 ms covers them. (A G-code machine's
    lost "ok" is not recoverable by design: the firmware counts characters and ends the
    run with error:22 after 10 s.)"""
    spec = Job.from_file(str(JOBS / "paper_frames.job"))
    link, t = _faulty_link(fw.link, {})
    t.write_faults = {3: "drop", 40: "flip", 41: "drop", 150: "flip"}
    with link:
        link.send_job(spec)
        t.arm()
        pts = list(link.run())
        assert t.injected == len(t.write_faults), t.writes
    assert points_csv(pts) == host_sim_csv("paper_frames")
