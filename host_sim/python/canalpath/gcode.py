"""FORMAT GCODE: the program lines of docs/PROTOCOL.md "The program (FORMAT GCODE)".

One ``G1`` per point (``G1 X<x> Y<y> Z<z> [A<a> C<c> | I<i> J<j> K<k>] [F<f>]``, 4
decimals), the lead and trail lines around them (``G21 ...``, ``G0 ...``, ``M3``, ``M5``,
``M2``/``M400``), with ``CHECKSUM ON`` each as ``N<i> <line>*<xor>``.
"""
from __future__ import annotations

import math
import re

from .frames import Point, RunInfo

_NUM = r"([+-]?\d+(?:\.\d{1,4})?)"
_G1_RE = re.compile(r"^G1 X%s Y%s Z%s(?: A%s C%s| I%s J%s K%s)?(?: F([0-9.eE+-]+))?$"
                    % ((_NUM,) * 8))
_RUN_RE = re.compile(r"^\[RUN:points=(\d+),first=(\d+),mode=([A-Z]+),n=(\d+),steps=(\d+),link=(\d+)"
                     r"(?:,[^\]]*)?\]$")


def parse_run_header(line: str) -> RunInfo | None:
    """The ``[RUN:points=..,first=..,mode=..,n=..,steps=..,link=..]`` line, or None."""
    m = _RUN_RE.match(line)
    if m is None:
        return None
    p, f, mode, n, st, lk = m.groups()
    return RunInfo(int(p), int(f), mode, int(n), int(st), int(lk), "GCODE",
                   line.endswith(",overlap=1]"))


def checksum(body: str) -> int:
    """Marlin's checksum: the XOR of every byte before ``*``."""
    cs = 0
    for b in body.encode("ascii", "replace"):
        cs ^= b
    return cs


def split_numbered(line: str) -> tuple[int, str] | None:
    """``N<i> <line>*<cs>`` -> (i, line) when the checksum is right, else None."""
    star = line.rfind("*")
    if not line.startswith("N") or star < 0 or not line[star + 1:].isdigit():
        return None
    sp = line.find(" ")
    if sp < 0 or sp > star or not line[1:sp].isdigit():
        return None
    if checksum(line[:star]) != int(line[star + 1:]):
        return None
    return int(line[1:sp]), line[sp + 1:star]


def is_program_line(line: str) -> bool:
    """A line of the program (G or M word first, or a numbered line), not a reply."""
    return line[:1] in ("G", "M") or (line[:1] == "N" and line[1:2].isdigit())


def line_index(info: RunInfo | None, k: int) -> tuple[int, int]:
    """The line (-1: link point) and index on it of point k (the zigzag of path_next)."""
    if info is None or info.steps + 1 + info.link == 0:
        return -1, k
    block = info.steps + 1 + info.link
    j, q = divmod(k, block)
    if q <= info.steps:
        return j, (info.steps - q) if (j & 1) else q
    return -1, q - info.steps


def _axis_ac(a_deg: float, c_deg: float) -> tuple[float, float, float]:
    a, c = math.radians(a_deg), math.radians(c_deg)
    return (math.sin(a) * math.sin(c), -math.sin(a) * math.cos(c), math.cos(a))


def _q(v: tuple[float, float, float]) -> tuple[float, float, float]:
    """A normal at the resolution of a frame's (1/32767), as host_sim keeps it."""
    return (round(v[0] * 32767.0) / 32767.0, round(v[1] * 32767.0) / 32767.0,
            round(v[2] * 32767.0) / 32767.0)


def parse_g1(body: str, k: int, info: RunInfo | None) -> Point | None:
    """A ``G1`` program line as the point k, or None if the line is not a well-formed G1."""
    m = _G1_RE.match(body)
    if m is None:
        return None
    g = m.groups()
    normal: tuple[float, float, float] | None = None
    if g[3] is not None:
        normal = _q(_axis_ac(float(g[3]), float(g[4])))
    elif g[5] is not None:
        normal = _q((float(g[5]), float(g[6]), float(g[7])))
    line, index = line_index(info, k)
    return Point(k, float(g[0]), float(g[1]), float(g[2]), normal, line, index)
