"""Job builders: the command lines of docs/PROTOCOL.md "Commands", checked before sending.

A :class:`Job` is the list of command lines that set a job up (everything but RUN and
RESUME, which :meth:`canalpath.Link.run` sends). Every builder method emits exactly the
documented command line and checks it first, the way the firmware does
(firmware/job/commands.def, job.c, job_<model>.c, parse.c): a refused value raises
:class:`~canalpath.errors.JobValueError` carrying the code, text and cause the firmware
would have answered, e.g. ``error:6 value out of range (FEED 0.0009: 0 or 0.001..1e6)``.
The checks are those a command can make on its own; what needs the whole job (R > 0 on
the interval, cusps, the tool fit) is the firmware's, at RUN.
"""
from __future__ import annotations

import math
import re
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field

from .errors import JobValueError

LINE_MAX = 95          # bytes of a command line (CP_LINE_MAX - 1, $I line=)
MAX_TOKENS = 20        # JOB_MAX_TOKENS
KW_MAX = 16            # PARSE_KW_MAX: the keyword part of a cause
CAUSE_TOKEN_MAX = 24   # PROTO_CAUSE_TOKEN_MAX
ABS_MAX = 1.0e9        # PARSE_ABS_MAX
MAX_LINES = 256        # CP_MAX_LINES ($I lines=)
MAX_STEPS = 4096       # CP_MAX_STEPS ($I steps=)
MAX_SECTIONS = 4       # CP_MAX_SECTIONS
MAX_DRC_POINTS = 12    # CP_MAX_DRC_POINTS
MAX_PASSES = 7         # CP_MAX_PASSES
COORD_MAX = 1.0e4      # CANAL_COORD_MAX, GSR_COEF_MAX, SPINE_COORD_MAX
UINT32_MAX = 0xFFFFFFFF

MODELS = ("CANAL", "GSR", "CHANNEL", "DRC", "SPINE", "PLANE")
MACHINES = ("GENERIC", "GRBL", "MARLIN", "LINUXCNC")
WCS_WORDS = ("G54", "G55", "G56", "G57", "G58", "G59")
FORMATS = ("GCODE", "FRAMES")

_NUM_RE = re.compile(r"^[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?$")


class _Refuse(Exception):
    """Internal: a check failed (code, index of the token at fault or None, limit)."""

    def __init__(self, code: int, tok: int | None = None, limit: str | None = None,
                 args: tuple[int, int] | None = None) -> None:
        super().__init__(code)
        self.code, self.tok, self.limit, self.args_ = code, tok, limit, args


def parse_real(tok: str) -> float:
    """A number as the firmware's parse_real reads it; raises _Refuse(4|5|6)."""
    body = tok[1:] if tok[:1] in "+-" else tok
    if body.upper() in ("NAN", "INF", "INFINITY"):
        raise _Refuse(5)
    if not _NUM_RE.match(tok):
        raise _Refuse(4)
    v = float(tok)
    if abs(v) > ABS_MAX:
        raise _Refuse(6, limit="|x| <= 1e9")
    return v


def parse_uint(tok: str) -> int:
    """An unsigned 32-bit number as parse_uint reads it; raises _Refuse(4|6)."""
    if not tok or not tok.isdigit() or not tok.isascii():
        raise _Refuse(4)
    v = int(tok)
    if v > UINT32_MAX:
        raise _Refuse(6)
    return v


@dataclass
class _State:
    """What a command's check depends on besides its line."""

    surface: str = "CANAL"
    sections: int = 0
    drc_points: int = 0


# ---- the commands: shape and the hook's checks ------------------------------------------

# words of the WORD_THEN_NUMBERS / WORD commands: keyword -> {word: numbers}
_WORDS: dict[str, dict[str, int]] = {
    "CURVE": {"LINE": 4, "ARC": 5, "ELLIPSE": 6, "BEZIER": 8},
    "RADIUS": {"CONST": 1, "LINEAR": 2, "COS": 3, "CUBIC": 4},
    "TOOL": {"NONE": 0, "BALL": 1},
    "FORMAT": {w: 0 for w in FORMATS},
    "CHECKSUM": {"OFF": 0, "ON": 0},
    "SURFACE": {w: 0 for w in MODELS},
    "JOB": {"CLEAR": 0},
    "WCS": {w: 0 for w in WCS_WORDS},
    "MACHINE": {w: 0 for w in MACHINES},
    "TOOLAXIS": {"OFF": 0, "AC": 2, "IJK": 2},
    "LINK": {"HOST": 0, "MACHINE": 0},
    "CENTER": {"X": 7, "Y": 7, "Z": 7, "P0": 3, "P1": 3, "P2": 3, "P3": 3},
    "RADII": {"N": 7, "B": 7, "T": 7},
    "FRAME": {"FIXED": 0, "FRENET": 0, "N0": 3, "RMF": 3},
    "FORM": {"RATIONAL": 0, "TRIG": 0},
    "SECTIONS": {"CLEAR": 0},
    "POINTS": {"CLEAR": 0},
    "THICKEN": {"AUTO": 0},
    "EDGE": {"OFF": 0, "ON": 0},
    "SPINE": {"LINE": 6, "ARC": 8, "HELIX": 9, "P0": 3, "P1": 3, "P2": 3, "P3": 3},
}
_OPTIONS: dict[str, tuple[str, ...]] = {"TOOL": ("TIP", "CENTRE", "CENTER"), "CIRCLES": ("PATCH",)}

# keyword -> (shape, min, max, owner model or None)
_CMDS: dict[str, tuple[str, int, int, str | None]] = {
    "CURVE": ("word_numbers", 0, 0, None), "RADIUS": ("word_numbers", 0, 0, None),
    "TOOL": ("word_numbers_option", 0, 0, None),
    "LINES": ("uint_numbers_option", 2, 2, None), "CIRCLES": ("uint_numbers_option", 2, 2, None),
    "STEPS": ("uint_or_word", 0, 0, None), "TOL": ("numbers", 1, 1, None),
    "FEED": ("numbers", 1, 3, None), "RXBUF": ("uint_or_word", 0, 0, None),
    "FORMAT": ("word", 0, 0, None), "CHECKSUM": ("word", 0, 0, None),
    "SURFACE": ("word", 0, 0, None), "JOB": ("word", 0, 0, None),
    "SAFE": ("numbers", 1, 1, None), "SPINDLE": ("numbers", 1, 1, None),
    "WCS": ("word", 0, 0, None), "MACHINE": ("word", 0, 0, None),
    "TOOLAXIS": ("word_numbers", 0, 0, None), "LINK": ("word", 0, 0, None),
    "PLACE": ("numbers", 3, 4, None), "TILT": ("numbers", 2, 2, None),
    "RUN": ("alone", 0, 0, None), "RESUME": ("uint_or_word", 0, 0, None),
    "$J": ("alone", 0, 0, None),
    "CENTER": ("word_numbers", 0, 0, "GSR"), "RADII": ("word_numbers", 0, 0, "GSR"),
    "FRAME": ("word_numbers", 0, 0, "GSR"), "FORM": ("word_numbers", 0, 0, "GSR"),
    "SECTION": ("numbers", 9, 9, "CHANNEL"), "AXES": ("numbers", 6, 6, "CHANNEL"),
    "SECTIONS": ("word", 0, 0, "CHANNEL"),
    "POINT": ("numbers", 2, 3, "DRC"), "POINTS": ("word", 0, 0, "DRC"),
    "THICKEN": ("uint_or_word", 0, 0, "DRC"), "EDGE": ("word", 0, 0, "DRC"),
    "SPINE": ("word_numbers", 0, 0, "SPINE"), "SPINEDIR": ("numbers", 3, 3, "SPINE"),
    "SPINEREF": ("numbers", 3, 3, "SPINE"),
    "STRIP": ("numbers", 2, 2, "PLANE"),
}


@dataclass
class _Args:
    """A command's arguments after the shape check (job_args)."""

    kw: str
    word: str | None = None
    option: str | None = None
    u: int | None = None
    u_tok: int = 0
    v: list[float] = field(default_factory=list)
    v_tok: int = 1


def _sfun(f: list[float], u: float) -> tuple[float, float]:
    """GSR's function family a0 + a1 u + a2 u^2 + a3 u^3 + b sin(w u) + c cos(w u) (w in
    degrees per unit) and its derivative."""
    a0, a1, a2, a3, b, c, w = f
    wr = math.radians(w)
    val = a0 + u * (a1 + u * (a2 + u * a3)) + b * math.sin(wr * u) + c * math.cos(wr * u)
    der = a1 + u * (2 * a2 + 3 * a3 * u) + b * wr * math.cos(wr * u) - c * wr * math.sin(wr * u)
    return val, der


def _check_hook(a: _Args, st: _State) -> None:  # noqa: C901 - one case per command, as job.c
    """The owner's hook checks of job.c / job_<model>.c (raise _Refuse)."""
    v = a.v
    vt = a.v_tok
    kw = a.kw
    if kw == "CURVE":  # canal_curve_check: no cause
        n = len(v)
        angles = 2 if a.word in ("ARC", "ELLIPSE") else 0
        for i, x in enumerate(v):
            if abs(x) > (720.0 if i >= n - angles else COORD_MAX):
                raise _Refuse(6)
        if a.word == "LINE" and v[0] == v[2] and v[1] == v[3]:
            raise _Refuse(12)
        if a.word == "BEZIER" and all(v[i] == v[0] and v[i + 1] == v[1] for i in range(0, 8, 2)):
            raise _Refuse(12)
        if angles:
            radii = v[2:3] if a.word == "ARC" else v[2:4]
            if any(r <= 0 for r in radii):
                raise _Refuse(6)
            if v[-1] == v[-2]:
                raise _Refuse(13)
            if abs(v[-1] - v[-2]) > 360.0 * (1 + 4 * 1.2e-7):
                raise _Refuse(6)
    elif kw == "RADIUS":  # canal_radius_check: no cause
        for i, x in enumerate(v):
            if abs(x) > (64.0 if a.word == "COS" and i == 2 else COORD_MAX):
                raise _Refuse(6)
    elif kw == "TOOL":
        if a.word == "BALL":
            if not (0 < v[0] <= COORD_MAX):
                raise _Refuse(6, vt, "0 < r <= 1e4")
            if a.option == "?":
                raise _Refuse(9, -1)
    elif kw in ("LINES", "CIRCLES"):
        n = a.u or 0
        if n > MAX_LINES:
            raise _Refuse(14, a.u_tok, "$I lines=")
        if n == 0:
            raise _Refuse(6, a.u_tok, "n >= 1")
        if abs(v[0]) > 180 or abs(v[1]) > 180:
            raise _Refuse(6, vt + (0 if abs(v[0]) > 180 else 1), "|u| <= 180")
        if v[0] == v[1] and n > 1:
            raise _Refuse(6, vt + 1, "u0 != u1 for n > 1")
    elif kw == "STEPS":
        if (a.u or 0) > MAX_STEPS:
            raise _Refuse(14, a.u_tok, "$I steps=")
        if a.u == 0:
            raise _Refuse(6, a.u_tok, "m >= 1")
    elif kw == "TOL":
        if not (0.01 <= v[0] <= 10000.0):
            raise _Refuse(6, vt, "0.01..10000")
    elif kw == "FEED":
        for i, f in enumerate(v):
            if not (f == 0 and len(v) == 1) and not (0.001 <= f <= 1.0e6):
                raise _Refuse(6, vt + i, "0 or 0.001..1e6" if i == 0 else "0.001..1e6")
    elif kw == "SAFE":
        if not abs(v[0]) <= 1000.0:
            raise _Refuse(6, vt, "|z| <= 1000")
    elif kw == "SPINDLE":
        if not (v[0] == 0 or 1 <= v[0] <= 100000.0):
            raise _Refuse(6, vt, "0 or 1..100000")
    elif kw == "TOOLAXIS":
        if len(v) == 2:
            for i, what in enumerate(("lead", "side")):
                if not abs(v[i]) <= 60.0:
                    raise _Refuse(6, vt + i, "|%s| <= 60" % what)
    elif kw == "RXBUF":
        if a.u is None or not (120 <= a.u <= 1024):
            raise _Refuse(6, a.u_tok, "120..1024")
    elif kw == "TILT":
        if not abs(v[0]) <= 360:
            raise _Refuse(6, vt, "|axis| <= 360")
        if not abs(v[1]) <= 90:
            raise _Refuse(6, vt + 1, "|angle| <= 90")
    elif kw == "PLACE":
        for i in range(3):
            if not abs(v[i]) <= 1000:
                raise _Refuse(6, vt + i, "|x|, |y|, |z| <= 1000")
        if len(v) == 4 and not abs(v[3]) <= 360:
            raise _Refuse(6, vt + 3, "|rz| <= 360")
    elif kw in ("CENTER", "RADII", "FRAME", "FORM"):
        for i, x in enumerate(v):
            if not abs(x) <= (23040.0 if i == 6 else COORD_MAX):
                raise _Refuse(6, vt + i, "|w| <= 23040" if i == 6 else "|x| <= 1e4")
        if kw == "RADII":
            t = a.word == "T"
            f0 = _sfun(v, 0.0)[0]
            for k in range(257):
                f, df = _sfun(v, k / 256.0)
                if (not (0 <= f <= 1 and df >= 0)) if t else not f > 0:
                    raise _Refuse(29 if t else 28, None,
                                  "0 <= f_t <= 1, increasing" if t else "f > 0 at u = k/256")
            if t and not _sfun(v, 1.0)[0] > f0:
                raise _Refuse(29, None, "0 <= f_t <= 1, increasing")
        if kw == "FRAME" and v and not (v[0] * v[0] + v[1] * v[1] + v[2] * v[2] > 0):
            raise _Refuse(6, None, "x y z != 0 0 0")
    elif kw == "SECTION":
        if st.sections >= MAX_SECTIONS:
            raise _Refuse(14, None, "SECTIONS CLEAR")
        for i in range(6, 9):
            if abs(v[i]) > 360:
                raise _Refuse(6, vt + i, "|angle| <= 360")
        if not (v[0] > 0 and v[1] > 0):
            raise _Refuse(28)
        if v[2] < 1:
            raise _Refuse(32)
    elif kw == "AXES":
        if st.sections == 0:
            raise _Refuse(31, None, "SECTION first")
        x, z = v[0:3], v[3:6]
        if (abs(math.fsum(c * c for c in x) - 1) > 1e-4 or abs(math.fsum(c * c for c in z) - 1) > 1e-4
                or abs(math.fsum(p * q for p, q in zip(x, z))) > 1e-4):
            raise _Refuse(6)
    elif kw == "POINT":
        if any(abs(x) > COORD_MAX for x in v):
            raise _Refuse(6, None, "|x|, |y|, |z| <= 1e4")
        if len(v) == 3 and v[2] != 0:
            raise _Refuse(25, None, "z = 0")
        if st.drc_points >= MAX_DRC_POINTS:
            raise _Refuse(14, None, "POINTS CLEAR")
    elif kw == "THICKEN":
        if a.u is not None and a.u > MAX_PASSES:
            raise _Refuse(14, a.u_tok)
    elif kw in ("SPINE", "SPINEDIR", "SPINEREF"):
        for i, x in enumerate(v):
            span = a.word == "ARC" and i == 7
            if not abs(x) <= (360.0 if span else COORD_MAX):
                raise _Refuse(6, vt + i, "|span| <= 360" if span else "|x| <= 1e4")
    elif kw == "STRIP":
        for i, x in enumerate(v):
            if not (0 < x <= COORD_MAX):
                raise _Refuse(6, vt + i, "(0, 1e4]")


def _args_of(toks: list[str], kw: str) -> _Args:
    """job_args_of: arity, words, the unsigned number, the numbers (raise _Refuse)."""
    shape, mn, mx, _owner = _CMDS[kw]
    n = len(toks)
    a = _Args(kw)
    first, na, ntv, uint = 1, 0, n, False
    opts = _OPTIONS.get(kw, ())
    if shape == "numbers":
        if n < 1 + mn or n > 1 + mx:
            raise _Refuse(3, args=(mn, mx))
        na = n - 1
    elif shape == "uint_numbers_option":
        if n == 3 + mn and opts:
            w = toks[-1].upper()
            if w not in opts:
                raise _Refuse(9, n - 1)
            a.option = w
            ntv -= 1
        na = 1 + mn
        uint = True
    elif shape == "alone":
        return a
    else:  # a word after the keyword
        if n < 2 or (n != 2 and shape in ("word", "uint_or_word")):
            raise _Refuse(3, args=(1, 1))
        w = toks[1].upper()
        words = _WORDS.get(kw, {})
        if w not in words:
            if shape != "uint_or_word":
                raise _Refuse(9, 1)
            na, uint = 1, True
        else:
            a.word = w
            na = words[w]
            first = 2
            if shape == "word_numbers_option":
                if na == 0 and n > 2:
                    raise _Refuse(9)
                if n == 3 + na:
                    o = toks[-1].upper()
                    a.option = o if o in opts else "?"
                    ntv -= 1
    if ntv != first + na:
        lo = first - 1 + na
        raise _Refuse(3, args=(lo, lo + (1 if opts else 0)))
    if uint:
        a.u_tok = first
        try:
            a.u = parse_uint(toks[first])
        except _Refuse as r:
            r.tok = first
            raise
        first += 1
        na -= 1
    a.v_tok = first
    for i in range(na):
        try:
            a.v.append(parse_real(toks[first + i]))
        except _Refuse as r:
            r.tok = first + i
            raise
    return a


def _line_error(line: str) -> JobValueError | None:
    """The firmware's checks of the line itself: length (error:2) and bytes (error:8)."""
    if len(line.encode("utf-8", "surrogateescape")) > LINE_MAX:
        return JobValueError(2, command=line)
    if any(not (0x20 <= ord(c) <= 0x7E or c == "\t") for c in line):
        return JobValueError(8, command=line)
    return None


def check_line(line: str, state: _State | None = None) -> None:
    """Check one command line as the firmware would; raise JobValueError with the firmware's
    code, text and cause, or return None if the firmware would take it (or if it is not a
    job command: RUN, RESUME k, $J are checked for their shape only)."""
    st = state if state is not None else _State()
    err = _line_error(line)
    if err is not None:
        raise err
    text = line.replace("\t", " ").strip(" ")
    toks = text.split(" ")
    toks = [t for t in toks if t]
    if not toks:
        return
    kwtyped = toks[0]
    kw = kwtyped.upper()
    if kw not in _CMDS:
        raise JobValueError(1, command=line)
    shape, _mn, _mx, owner = _CMDS[kw]
    if shape == "alone" and len(toks) != 1:
        raise JobValueError(1, command=line)
    if len(toks) > MAX_TOKENS:
        raise JobValueError(3, command=line)
    if owner is not None and st.surface != owner:
        raise JobValueError(24, command=line)
    try:
        a = _args_of(toks, kw)
        if kw == "RESUME":
            return
        _check_hook(a, st)
    except _Refuse as r:
        if kw == "RESUME":  # no cause; a k above 2^32 - 1 is error:21
            raise JobValueError(21 if r.code == 6 else r.code, command=line) from None
        cause = ""
        if r.tok is not None or r.limit is not None or r.args_ is not None:
            cause = kwtyped[:KW_MAX]
            if r.tok is not None:
                cause += " " + toks[r.tok][:CAUSE_TOKEN_MAX]
            if r.limit is not None:
                cause += ": " + r.limit
            if r.args_ is not None:
                lo, hi = r.args_
                cause += ": %d%s %s" % (lo, "" if lo == hi else "..%d" % hi,
                                        "argument" if hi == 1 else "arguments")
        raise JobValueError(r.code, cause=cause, command=line) from None
    # the job's state after the command
    if kw == "SURFACE":
        st.surface = a.word or st.surface
        st.sections = st.drc_points = 0
    elif kw == "JOB":
        st.surface, st.sections, st.drc_points = "CANAL", 0, 0
    elif kw == "SECTION":
        st.sections += 1
    elif kw == "SECTIONS":
        st.sections = 0
    elif kw == "POINT":
        st.drc_points += 1
    elif kw == "POINTS":
        st.drc_points = 0


def fmt(v: float | int) -> str:
    """A number as a command argument: integers plainly, other floats as Python's shortest
    repr (which the firmware reads back to the same double)."""
    if isinstance(v, bool):
        raise TypeError("a number, not a bool")
    if isinstance(v, int):
        return str(v)
    f = float(v)
    if math.isfinite(f) and f.is_integer() and abs(f) < 1e15:
        return str(int(f))
    return repr(f)


class Job:
    """A job: the command lines that set it up, each checked when it is added.

    Every method adds one documented command (docs/PROTOCOL.md "Commands") and returns
    the job, so calls chain::

        job = (Job().curve_arc(0, 0, 3, 0, 360).radius_cos(5.5, 10.5, 2)
                    .lines(8, -25, 10).tol(2).feed(600).safe(50).format("GCODE"))

    A value the firmware would refuse raises :class:`~canalpath.errors.JobValueError`
    (the job unchanged). ``job.commands`` is the list of lines;
    :meth:`canalpath.Link.send_job` sends them (after ``JOB CLEAR``).
    """

    def __init__(self, lines: Iterable[str] = ()) -> None:
        self._lines: list[str] = []
        self._state = _State()
        for line in lines:
            self.add(line)

    # ---- generic -----------------------------------------------------------------------
    def add(self, line: str) -> Job:
        """Add one command line as typed (checked; RUN, RESUME and $J are not job lines)."""
        kw = line.strip().split(" ", 1)[0].upper() if line.strip() else ""
        if kw in ("RUN", "RESUME", "$J"):
            raise ValueError("%s is not a job setting: use Link.run()" % kw)
        st = _State(self._state.surface, self._state.sections, self._state.drc_points)
        check_line(line, st)
        if line.strip():
            self._lines.append(line.strip())
            self._state = st
        return self

    def _cmd(self, *parts: object) -> Job:
        return self.add(" ".join(fmt(p) if isinstance(p, (int, float)) else str(p) for p in parts))

    @property
    def commands(self) -> list[str]:
        """The command lines, in order."""
        return list(self._lines)

    @property
    def surface(self) -> str:
        """The SURFACE the job's model commands apply to."""
        return self._state.surface

    def __iter__(self) -> Iterator[str]:
        return iter(self._lines)

    def __len__(self) -> int:
        return len(self._lines)

    def __str__(self) -> str:
        return "\n".join(self._lines)

    def __repr__(self) -> str:
        return "Job(%r)" % (self._lines,)

    @classmethod
    def from_file(cls, path: str) -> Job:
        """A job from a job file (one command per line, ``#`` comments; RUN and RESUME lines
        and ``#!`` expectations are left out: see :func:`canalpath.script.read_script`)."""
        from .script import read_script
        job = cls()
        for step in read_script(path):
            kw = step.line.split(" ", 1)[0].upper()
            if kw not in ("RUN", "RESUME", "$J"):
                job.add(step.line)
        return job

    # ---- SURFACE, JOB CLEAR ----------------------------------------------------------------
    def surface_model(self, model: str) -> Job:
        """``SURFACE CANAL | GSR | CHANNEL | DRC | SPINE``: the model RUN streams."""
        return self._cmd("SURFACE", model.upper())

    def clear(self) -> Job:
        """``JOB CLEAR``: the job's defaults."""
        return self._cmd("JOB", "CLEAR")

    # ---- the canal's geometry ------------------------------------------------------------
    def curve_line(self, x0: float, y0: float, x1: float, y1: float) -> Job:
        """``CURVE LINE x0 y0 x1 y1``."""
        return self._cmd("CURVE", "LINE", x0, y0, x1, y1)

    def curve_arc(self, cx: float, cy: float, r: float, a0: float, a1: float) -> Job:
        """``CURVE ARC cx cy r a0 a1`` (degrees; a1 < a0 runs clockwise)."""
        return self._cmd("CURVE", "ARC", cx, cy, r, a0, a1)

    def curve_ellipse(self, cx: float, cy: float, a: float, b: float, a0: float, a1: float) -> Job:
        """``CURVE ELLIPSE cx cy A B a0 a1``."""
        return self._cmd("CURVE", "ELLIPSE", cx, cy, a, b, a0, a1)

    def curve_bezier(self, *xy: float) -> Job:
        """``CURVE BEZIER x0 y0 x1 y1 x2 y2 x3 y3``."""
        return self._cmd("CURVE", "BEZIER", *xy)

    def radius_const(self, c: float) -> Job:
        """``RADIUS CONST c``."""
        return self._cmd("RADIUS", "CONST", c)

    def radius_linear(self, r0: float, r1: float) -> Job:
        """``RADIUS LINEAR r0 r1``."""
        return self._cmd("RADIUS", "LINEAR", r0, r1)

    def radius_cos(self, b: float, c: float, k: float) -> Job:
        """``RADIUS COS b c k``: R = b cos(k theta) + c."""
        return self._cmd("RADIUS", "COS", b, c, k)

    def radius_cubic(self, r0: float, r1: float, r2: float, r3: float) -> Job:
        """``RADIUS CUBIC r0 r1 r2 r3`` (Bernstein)."""
        return self._cmd("RADIUS", "CUBIC", r0, r1, r2, r3)

    # ---- raster and output ---------------------------------------------------------------
    def tool_ball(self, r: float, at: str | None = None) -> Job:
        """``TOOL BALL r [TIP|CENTRE]``: stream the tip (default) or the centre."""
        return self._cmd("TOOL", "BALL", r, *([at.upper()] if at else []))

    def tool_none(self) -> Job:
        """``TOOL NONE``: stream surface points."""
        return self._cmd("TOOL", "NONE")

    def lines(self, n: int, u0: float, u1: float) -> Job:
        """``LINES n u0 u1``: n family-2 curvature lines."""
        return self._cmd("LINES", n, u0, u1)

    def circles(self, n: int, u0: float, u1: float, patch: bool = False) -> Job:
        """``CIRCLES n u0 u1 [PATCH]``: n family-1 arcs."""
        return self._cmd("CIRCLES", n, u0, u1, *(["PATCH"] if patch else []))

    def steps(self, m: int) -> Job:
        """``STEPS m``: fixed steps per line."""
        return self._cmd("STEPS", m)

    def tol(self, chord_um: float) -> Job:
        """``TOL chord_um``: the chord tolerance in micrometres."""
        return self._cmd("TOL", chord_um)

    def feed(self, f: float, plunge: float | None = None, link: float | None = None) -> Job:
        """``FEED f [plunge [link]]`` (mm/min)."""
        if link is not None and plunge is None:
            raise ValueError("FEED: a link feed needs the plunge feed before it")
        return self._cmd("FEED", f, *[x for x in (plunge, link) if x is not None])

    def format(self, fmt_: str) -> Job:
        """``FORMAT GCODE | FRAMES``."""
        return self._cmd("FORMAT", fmt_.upper())

    def rxbuf(self, n: int) -> Job:
        """``RXBUF n``: the machine's RX buffer for character counting (120..1024)."""
        return self._cmd("RXBUF", n)

    def checksum(self, on: bool) -> Job:
        """``CHECKSUM ON | OFF``."""
        return self._cmd("CHECKSUM", "ON" if on else "OFF")

    def safe(self, z: float) -> Job:
        """``SAFE z``: the height of every rapid, mm."""
        return self._cmd("SAFE", z)

    def spindle(self, rpm: float) -> Job:
        """``SPINDLE rpm``: 0 or 1..100000."""
        return self._cmd("SPINDLE", rpm)

    def wcs(self, g: str) -> Job:
        """``WCS G54 .. G59``."""
        return self._cmd("WCS", g.upper())

    def machine(self, dialect: str) -> Job:
        """``MACHINE GENERIC | GRBL | MARLIN | LINUXCNC``."""
        return self._cmd("MACHINE", dialect.upper())

    def link(self, where: str) -> Job:
        """``LINK HOST | MACHINE``."""
        return self._cmd("LINK", where.upper())

    def toolaxis(self, kind: str, lead: float = 0.0, side: float = 0.0) -> Job:
        """``TOOLAXIS OFF | AC lead side | IJK lead side`` (degrees, |.| <= 60)."""
        k = kind.upper()
        if k == "OFF":
            return self._cmd("TOOLAXIS", "OFF")
        return self._cmd("TOOLAXIS", k, lead, side)

    def place(self, x: float, y: float, z: float, rz: float | None = None) -> Job:
        """``PLACE x y z [rz]``: the part's origin on the table and its turn about Z."""
        return self._cmd("PLACE", x, y, z, *([rz] if rz is not None else []))

    def tilt(self, axis_deg: float, angle_deg: float) -> Job:
        """``TILT axis_deg angle_deg``: the base plane inclined."""
        return self._cmd("TILT", axis_deg, angle_deg)

    # ---- SURFACE GSR -----------------------------------------------------------------------
    def center(self, axis: str, a0: float, a1: float, a2: float, a3: float, b: float, c: float,
               w: float) -> Job:
        """``CENTER X|Y|Z a0 a1 a2 a3 b c w`` (SURFACE GSR)."""
        return self._cmd("CENTER", axis.upper(), a0, a1, a2, a3, b, c, w)

    def center_point(self, i: int, x: float, y: float, z: float) -> Job:
        """``CENTER P<i> x y z``: a Bezier control point, i in 0..3 (SURFACE GSR)."""
        return self._cmd("CENTER", "P%d" % i, x, y, z)

    def radii(self, which: str, a0: float, a1: float, a2: float, a3: float, b: float, c: float,
              w: float) -> Job:
        """``RADII N|B|T a0 a1 a2 a3 b c w`` (SURFACE GSR)."""
        return self._cmd("RADII", which.upper(), a0, a1, a2, a3, b, c, w)

    def frame(self, kind: str, x: float | None = None, y: float | None = None,
              z: float | None = None) -> Job:
        """``FRAME FIXED | FRENET | N0 x y z | RMF x y z`` (SURFACE GSR)."""
        return self._cmd("FRAME", kind.upper(), *[q for q in (x, y, z) if q is not None])

    def form(self, kind: str) -> Job:
        """``FORM RATIONAL | TRIG`` (SURFACE GSR)."""
        return self._cmd("FORM", kind.upper())

    # ---- SURFACE CHANNEL ---------------------------------------------------------------------
    def section(self, a: float, b: float, n: float, cx: float, cy: float, cz: float, psi: float,
                theta: float, phi: float) -> Job:
        """``SECTION a b n cx cy cz psi theta phi`` (SURFACE CHANNEL)."""
        return self._cmd("SECTION", a, b, n, cx, cy, cz, psi, theta, phi)

    def axes(self, x1: float, x2: float, x3: float, z1: float, z2: float, z3: float) -> Job:
        """``AXES x1 x2 x3 z1 z2 z3``: the last section's rows (SURFACE CHANNEL)."""
        return self._cmd("AXES", x1, x2, x3, z1, z2, z3)

    def sections_clear(self) -> Job:
        """``SECTIONS CLEAR`` (SURFACE CHANNEL)."""
        return self._cmd("SECTIONS", "CLEAR")

    # ---- SURFACE DRC -------------------------------------------------------------------------
    def point(self, x: float, y: float, z: float | None = None) -> Job:
        """``POINT x y [z]`` (SURFACE DRC)."""
        return self._cmd("POINT", x, y, *([z] if z is not None else []))

    def points_clear(self) -> Job:
        """``POINTS CLEAR`` (SURFACE DRC)."""
        return self._cmd("POINTS", "CLEAR")

    def thicken(self, k: int | str) -> Job:
        """``THICKEN K | AUTO`` (SURFACE DRC)."""
        return self._cmd("THICKEN", k.upper() if isinstance(k, str) else k)

    def edge(self, on: bool) -> Job:
        """``EDGE ON | OFF`` (SURFACE DRC)."""
        return self._cmd("EDGE", "ON" if on else "OFF")

    # ---- SURFACE SPINE -----------------------------------------------------------------------
    def spine_line(self, x0: float, y0: float, z0: float, x1: float, y1: float, z1: float) -> Job:
        """``SPINE LINE x0 y0 z0 x1 y1 z1`` (SURFACE SPINE)."""
        return self._cmd("SPINE", "LINE", x0, y0, z0, x1, y1, z1)

    def spine_arc(self, cx: float, cy: float, cz: float, nx: float, ny: float, nz: float, r: float,
                  span: float) -> Job:
        """``SPINE ARC cx cy cz nx ny nz r span`` (SURFACE SPINE)."""
        return self._cmd("SPINE", "ARC", cx, cy, cz, nx, ny, nz, r, span)

    def spine_helix(self, px: float, py: float, pz: float, ax: float, ay: float, az: float, r: float,
                    pitch: float, turns: float) -> Job:
        """``SPINE HELIX px py pz ax ay az r pitch turns`` (SURFACE SPINE)."""
        return self._cmd("SPINE", "HELIX", px, py, pz, ax, ay, az, r, pitch, turns)

    def spine_point(self, i: int, x: float, y: float, z: float) -> Job:
        """``SPINE P<i> x y z``: a Bezier control point (SURFACE SPINE)."""
        return self._cmd("SPINE", "P%d" % i, x, y, z)

    def spinedir(self, dx: float, dy: float, dz: float) -> Job:
        """``SPINEDIR dx dy dz`` (SURFACE SPINE)."""
        return self._cmd("SPINEDIR", dx, dy, dz)

    def spineref(self, x: float, y: float, z: float) -> Job:
        """``SPINEREF x y z`` (SURFACE SPINE)."""
        return self._cmd("SPINEREF", x, y, z)

    # ---- SURFACE PLANE (test builds) ---------------------------------------------------------
    def strip(self, length: float, width: float) -> Job:
        """``STRIP len width`` (SURFACE PLANE, the example model of test builds)."""
        return self._cmd("STRIP", length, width)

