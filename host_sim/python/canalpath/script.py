"""Job files (tests/jobs/*.job): one command per line, ``#`` comments, and
``#! expect ok`` / ``#! expect error:N`` annotations checked against the replies."""
from __future__ import annotations

import re
from collections.abc import Callable, Iterable
from dataclasses import dataclass

from .errors import CanalpathError, FirmwareError, RunError
from .frames import Point
from .link import Link, Progress

_EXPECT_RE = re.compile(r"^expect\s+(ok|error:(\d+))\s*$")


class ExpectationError(CanalpathError):
    """A reply differs from the job file's ``#! expect`` annotation."""


@dataclass(frozen=True)
class Step:
    """One line of a job file: the command and what it expects (None: ok, else never an
    error unannotated; "ok"; or an error code)."""

    line: str
    expect: str | int | None
    lineno: int


def parse_script(lines: Iterable[str], name: str = "<job>") -> list[Step]:
    """The steps of a job file's lines."""
    out: list[Step] = []
    for no, raw in enumerate(lines, 1):
        text = raw.rstrip("\r\n")
        expect: str | int | None = None
        h = text.find("#")
        if h >= 0:
            note = text[h + 1:]
            if note.startswith("!"):
                m = _EXPECT_RE.match(note[1:].strip())
                if m is None:
                    raise ValueError("%s:%d: bad directive (want '#! expect ok' or '#! expect error:N')"
                                     % (name, no))
                expect = "ok" if m.group(1) == "ok" else int(m.group(2))
            text = text[:h]
        text = text.strip()
        if text:
            out.append(Step(text, expect, no))
    return out


def read_script(path: str) -> list[Step]:
    """The steps of a job file."""
    with open(path, encoding="ascii") as f:
        return parse_script(f, path)


def run_script(link: Link, steps: Iterable[Step], *, on_point: Callable[[Point], None] | None = None,
               on_gcode: Callable[[str], None] | None = None,
               progress: Callable[[Progress], None] | None = None) -> int:
    """Send every step; stream every RUN/RESUME. Returns the points received.

    A reply that differs from the step's expectation raises ExpectationError; an error
    reply to an unannotated step raises it as it came (CommandError, RunError).
    """
    total = 0
    for st in steps:
        kw = st.line.split()[0].upper()
        got: str | int = "ok"
        try:
            if kw in ("RUN", "RESUME"):
                k = int(st.line.split()[1]) if kw == "RESUME" and len(st.line.split()) == 2 else None
                if kw == "RESUME" and k is None:
                    link.command(st.line)
                else:
                    for p in link.run(resume=k, on_gcode=on_gcode, progress=progress):
                        total += 1
                        if on_point is not None:
                            on_point(p)
            else:
                link.command(st.line)
        except FirmwareError as e:
            if st.expect is None or st.expect == "ok":
                if isinstance(e, RunError):
                    e.points = total
                raise
            got = e.code
        if st.expect is not None and got != st.expect:
            raise ExpectationError("line %d %r: expected %s, got %s" % (
                st.lineno, st.line, st.expect if st.expect == "ok" else "error:%s" % st.expect,
                got if got == "ok" else "error:%s" % got))
    return total
