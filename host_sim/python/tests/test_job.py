"""Job builders: the exact command lines, and every refusal equal to the firmware's own
reply (code, text and cause) for the same line."""
from __future__ import annotations

import pytest

from canalpath import Job, JobValueError, Link, check_line
from canalpath.errors import CommandError
from canalpath.job import _State


def test_builders_emit_the_documented_lines():
    job = (Job().curve_arc(0, 0, 3, 0, 360).radius_cos(5.5, 10.5, 2).lines(8, -25, 10).tol(2)
           .feed(600, 100, 300).safe(50).spindle(12000).wcs("g55").machine("grbl").link("machine")
           .format("gcode").tool_ball(2, "CENTRE").circles(3, -10, 10, patch=True).steps(40)
           .toolaxis("AC", 5, -2.5).place(1, 2, 3, 90).tilt(45, 30).rxbuf(256).checksum(False))
    assert job.commands == [
        "CURVE ARC 0 0 3 0 360", "RADIUS COS 5.5 10.5 2", "LINES 8 -25 10", "TOL 2",
        "FEED 600 100 300", "SAFE 50", "SPINDLE 12000", "WCS G55", "MACHINE GRBL", "LINK MACHINE",
        "FORMAT GCODE", "TOOL BALL 2 CENTRE", "CIRCLES 3 -10 10 PATCH", "STEPS 40",
        "TOOLAXIS AC 5 -2.5", "PLACE 1 2 3 90", "TILT 45 30", "RXBUF 256", "CHECKSUM OFF"]
    gsr = (Job().surface_model("GSR").center_point(0, 0, 0, 0).center("X", 0, 8, 0, 0, 0, 0, 0)
           .radii("N", 1.2, 0, 0, 0, 0.5, 0, 180).frame("RMF", 0, 0, 1).frame("FIXED").form("TRIG"))
    assert gsr.commands[1:] == ["CENTER P0 0 0 0", "CENTER X 0 8 0 0 0 0 0", "RADII N 1.2 0 0 0 0.5 0 180",
                                "FRAME RMF 0 0 1", "FRAME FIXED", "FORM TRIG"]
    ch = Job().surface_model("CHANNEL").section(5, 3.5, 2, 3, 4.5, 1, 240, 10.5882352941, 30).sections_clear()
    assert ch.commands[1] == "SECTION 5 3.5 2 3 4.5 1 240 10.5882352941 30"
    drc = Job().surface_model("DRC").point(0, 0).point(10, 0.5, 0).thicken("auto").thicken(4).edge(True)
    assert drc.commands[1:] == ["POINT 0 0", "POINT 10 0.5 0", "THICKEN AUTO", "THICKEN 4", "EDGE ON"]
    sp = Job().surface_model("SPINE").spine_helix(0, 0, 0, 0, 0, 1, 15, 10, 2).spinedir(1, 0, 0)
    assert sp.commands[1:] == ["SPINE HELIX 0 0 0 0 0 1 15 10 2", "SPINEDIR 1 0 0"]


def test_from_file_is_the_job_files_settings():
    from conftest import JOBS
    job = Job.from_file(str(JOBS / "paper_gcode.job"))
    assert job.commands == ["CURVE ARC 0 0 3 0 360", "RADIUS COS 5.5 10.5 2", "LINES 8 -25 10", "TOL 2",
                            "FEED 600", "SAFE 50", "FORMAT GCODE"]


@pytest.mark.parametrize("call, code", [
    (lambda j: j.feed(0.0009), 6), (lambda j: j.feed(600, 0), 6), (lambda j: j.safe(1000.1), 6),
    (lambda j: j.spindle(-1), 6), (lambda j: j.lines(0, -10, 10), 6), (lambda j: j.lines(300, -10, 10), 14),
    (lambda j: j.steps(0), 6), (lambda j: j.steps(999999), 14), (lambda j: j.tol(0), 6),
    (lambda j: j.curve_arc(0, 0, 3, 0, float("nan")), 5), (lambda j: j.curve_arc(0, 0, 3, 10, 10), 13),
    (lambda j: j.curve_line(0, 0, 0, 0), 12), (lambda j: j.radius_cos(1, 2, 65), 6),
    (lambda j: j.place(1001, 0, 0), 6), (lambda j: j.tilt(45, 91), 6), (lambda j: j.rxbuf(95), 6),
    (lambda j: j.tool_ball(-1), 6), (lambda j: j.format("XML"), 9), (lambda j: j.center("X", 0, 0, 0, 0, 0, 0, 0), 24),
    (lambda j: j.toolaxis("AC", 61, 0), 6),
])
def test_out_of_range_raises_with_the_firmwares_code(call, code):
    job = Job().curve_arc(0, 0, 3, 0, 360)
    before = job.commands
    with pytest.raises(JobValueError) as ei:
        call(job)
    assert ei.value.code == code
    assert job.commands == before          # a refused command leaves the job unchanged
    assert isinstance(ei.value, ValueError)


# Lines of docs/PROTOCOL.md "Bad input" and more: the library's verdict must be the
# firmware's reply, word for word.
BAD = [
    "JOB", "CURVE", "CURVE LINE 0 0 1", "CURVE LINE 0 0 1 1 2", "RADIUS COS 1 2", "LINES 3 -10", "TOL 1 2",
    "PLACE 1 2", "PLACE 1 2 3 4 5", "TILT 45", "FEED 600 100 50 7",
    "CURVE LINE 0 0 1 x", "LINES 2.5 -10 10", "STEPS -4", "PLACE 1 2 z",
    "CURVE ARC 0 0 3 0 nan", "PLACE 0 nan 0", "TILT 0 inf", "SAFE -INF",
    "CURVE LINE 0 0 1e12 0", "CURVE ELLIPSE 0 0 0 25 0 360", "CURVE ARC 0 0 3 0 400", "RADIUS COS 1 2 65",
    "LINES 0 -10 10", "LINES 3 -10 200", "LINES 3 5 5", "STEPS 0", "TOL 0", "FEED -5", "FEED 0.0009",
    "FEED 600 0", "SAFE 1000.1", "SPINDLE -1", "RXBUF 8", "RXBUF 95", "TOOL BALL -1", "PLACE 1001 0 0",
    "PLACE 0 0 0 361", "TILT 361 0", "TILT 45 91", "JOB RESET", "CURVE SPIRAL 1 2", "RADIUS WAVY 1",
    "TOOL FLAT 2", "TOOL BALL 1 SIDE", "CIRCLES 3 -10 10 WIDE", "FORMAT XML", "CHECKSUM MAYBE", "WCS G60",
    "MACHINE HAAS", "LINK USB", "CURVE LINE 0 0 0 0", "CURVE BEZIER 1 1 1 1 1 1 1 1", "CURVE ARC 0 0 3 10 10",
    "LINES 99999 -10 10", "STEPS 999999", "TOOLAXIS AC 61 0", "TOOLAXIS IJK 0 -60.5", "TOOLAXIS OFF 1",
    "TOOL NONE 2", "SPINDLE 0.5", "FEED 2e6", "LINES 4294967296 0 1", "TOL 1e10", "SAFE 1.2.3",
    "FOO", "$J 1", "RUN x", "RESUME", "RESUME x", "RESUME 99999999999",
    "CENTER X 0 0 0 0 0 0 0", "POINT 1 2", "SECTION 1 1 2 0 0 0 0 0 0", "SPINE LINE 0 0 0 1 1 1",
    "STEPS 10 20", "FORMAT", "a" * 96,
]
MODEL_BAD = [
    ("GSR", ["CENTER X 0 6 0 0 0 0 9e9", "RADII N 1 -2 0 0 0 0 0", "RADII B 0 0 0 0 0 0 0",
             "RADII T 0 2 0 0 0 0 0", "RADII T 0.5 0 0 0 0 0 0", "CENTER Q 1 2 3", "FRAME N0 0 0 0",
             "CENTER X 1 2 3 4 5 6 30000", "FRAME RMF 1 2"]),
    ("CHANNEL", ["SECTION 5 3.5 2 3 4.5 1 400 0 0", "SECTION -1 2 2 0 0 0 0 0 0", "SECTION 2 1 0.5 0 0 0 0 0 0",
                 "AXES 1 0 0 0 0 1", "SECTIONS ALL"]),
    ("DRC", ["POINT 1 2 3", "POINT 1e5 0", "THICKEN 9", "EDGE MAYBE", "POINT 1 2 3 4"]),
    ("SPINE", ["SPINE HELIX 0 0 0 0 0 1 15 10 2e4", "SPINE ARC 0 0 0 0 0 1 5 400",
               "SPINE HELIX 0 0 0 0 0 1 15 10", "SPINEDIR 1 0", "SPINE P4 0 0 0"]),
]


def _local(line: str, surface: str = "CANAL") -> str:
    try:
        check_line(line, _State(surface))
    except JobValueError as e:
        return e.wire()
    return "ok"


def _firmware(link: Link, line: str) -> str:
    try:
        link.command(line)
    except CommandError as e:
        return e.wire()
    except JobValueError as e:       # the link's own length / byte check
        return e.wire()
    return "ok"


def test_every_refusal_is_the_firmwares(fw):
    with Link.open(fw.link) as link:
        diffs = []
        for line in BAD:
            fwr = _firmware(link, line)
            if fwr == "ok" and line.split()[0] in ("RUN", "RESUME"):
                continue
            if _local(line) != fwr:
                diffs.append((line, _local(line), fwr))
        assert all(_firmware(link, ln) == "ok" for ln in ["JOB CLEAR"])
        for surface, lines in MODEL_BAD:
            link.command("SURFACE " + surface)
            for line in lines:
                fwr, loc = _firmware(link, line), _local(line, surface)
                if loc != fwr:
                    diffs.append((surface + ": " + line, loc, fwr))
            link.command("JOB CLEAR")
        assert not diffs, "\n".join("%r: library %r, firmware %r" % d for d in diffs)
        assert len(BAD) + sum(len(v) for _, v in MODEL_BAD) > 100


def test_builders_are_accepted_by_the_firmware(fw):
    job = (Job().curve_arc(0, 0, 3, 0, 360).radius_cos(5.5, 10.5, 2).lines(8, -25, 10).tol(2)
           .feed(600, 100, 300).safe(50).spindle(12000).wcs("G55").format("GCODE").tool_ball(0.5, "TIP")
           .toolaxis("IJK", 5, -2.5).toolaxis("OFF").place(1, 2, 3, 90).tilt(45, 30).rxbuf(256)
           .checksum(True).machine("MARLIN"))
    with Link.open(fw.link) as link:
        link.send_job(job)
        dump = link.dump()
        assert "FEED 600 100 300" in dump and "PLACE 1 2 3 90" in dump and "MACHINE MARLIN" in dump
        # $J replayed gives the same $J (the firmware's own round trip)
        link.send_job(Job(dump))
        assert link.dump() == dump
