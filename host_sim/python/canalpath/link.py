"""The host link: commands, real-time bytes and the run, over a Transport.

docs/PROTOCOL.md is the specification; host_sim (C) is the reference client. A
:class:`Link` is one connection to one firmware; it holds no global state.
"""
from __future__ import annotations

import re
import time
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass, field

from . import frames as fr
from .errors import (CanalpathError, CommandError, JobValueError, LinkError, LinkTimeout, NotCanalpath,
                     RunError, SilentPeer, StreamError, parse_error_line)
from .frames import FrameDecoder, Point, RunInfo
from .gcode import is_program_line, parse_g1, parse_run_header, split_numbered
from .job import LINE_MAX, Job
from .transport import SerialTransport, Transport

ABORT_BYTE = b"\x18"
LINE_LIMIT = 1024           # longest line accepted from the peer (bytes)
REPLY_LINES_MAX = 64        # lines before a command's reply (a flood otherwise)
PROGRESS_PERIOD = 0.25      # s between progress callbacks
POLL_PERIOD = 1.0           # s of quiet in a G-code run before a '?' (alive?)
_STATUS_RE = re.compile(r"^<(Idle|Run|Hold)(?:\|L:(\d+)/(\d+)\|P:(\d+)/(\d+))?>$")


@dataclass(frozen=True)
class Info:
    """The ``$I`` answer: ``[VER:canalpath <version> proto <n>]`` and ``[OPT:k=v,...]``."""

    version: str
    proto: int
    options: dict[str, str]
    lines: tuple[str, ...]

    @property
    def models(self) -> tuple[str, ...]:
        """The surface models of this build (``models=CANAL+GSR+...``)."""
        return tuple(self.options.get("models", "CANAL").split("+"))

    @property
    def window(self) -> int:
        """Frames in flight of a FRAMES run (``window=``)."""
        return int(self.options.get("window", "16"))


@dataclass(frozen=True)
class Status:
    """A status report: ``<Idle>``, ``<Run|L:j/n|P:k/m>`` or ``<Hold|L:j/n|P:k/m>``."""

    state: str
    line: int | None = None
    lines: int | None = None
    point: int | None = None
    points: int | None = None
    raw: str = ""


def parse_status(line: str) -> Status | None:
    """A ``<...>`` status report of the firmware, or None."""
    m = _STATUS_RE.match(line)
    if m is None:
        return None
    st, j, n, k, mm = m.groups()
    if j is None:
        return Status(st, raw=line)
    return Status(st, int(j), int(n), int(k), int(mm), line)


@dataclass(frozen=True)
class Progress:
    """What a progress callback gets: points received of ``total`` (this run), the rate
    (points/s since RUN) and the estimated time left (s; None before the first point)."""

    points: int
    total: int
    rate: float
    eta: float | None
    elapsed: float


@dataclass
class RunResult:
    """The account of the last run (``Link.last_run``)."""

    info: RunInfo | None = None
    format: str = ""
    points: int = 0
    bytes_in: int = 0
    seconds: float = 0.0
    first_byte: float = 0.0
    naks: int = 0
    bad_frames: int = 0
    dup_frames: int = 0
    resends: int = 0
    program_lines: int = 0
    ok: bool = False
    error: CanalpathError | None = None
    statuses: list[Status] = field(default_factory=list)


def _job_format(lines: Iterable[str], start: str | None) -> str | None:
    """The FORMAT after these command lines (JOB CLEAR: GCODE)."""
    f = start
    for line in lines:
        t = line.split()
        if len(t) == 2 and t[0].upper() == "FORMAT" and t[1].upper() in ("GCODE", "FRAMES"):
            f = t[1].upper()
        elif len(t) == 2 and t[0].upper() == "JOB" and t[1].upper() == "CLEAR":
            f = "GCODE"
    return f


class Link:
    """One connection to a canalpath firmware.

    ``Link(transport)`` takes any :class:`~canalpath.transport.Transport`;
    :meth:`Link.open` opens a serial port or pty path with pyserial. On connecting the
    link brings the firmware to idle as docs/PROTOCOL.md "Reconnecting" says (a run left
    by a previous host is aborted) and checks ``$I``: a peer that is not canalpath raises
    :class:`~canalpath.errors.NotCanalpath`, a silent one
    :class:`~canalpath.errors.SilentPeer`.

    With ``abort_busy=False`` a run found in progress is left alone and
    :class:`~canalpath.errors.LinkError` is raised instead (a G-code run on the machine
    link goes on without the host).

    ``timeout`` bounds every reply (s); ``run_timeout`` the silence within a run (the
    firmware resends unacknowledged frames every 250 ms and answers a G-code machine's
    silence after 10 s, so the default 15 s is a hang guard).
    """

    def __init__(self, transport: Transport, *, timeout: float = 2.0, run_timeout: float = 15.0,
                 connect: bool = True, abort_busy: bool = True) -> None:
        self.transport = transport
        self.abort_busy = abort_busy
        self.timeout = timeout
        self.run_timeout = run_timeout
        self._rx = bytearray()
        self._format: str | None = None
        self._in_frames = False
        self._held = False        # hold() sent: a held run is silent by design
        self.info: Info | None = None
        self.bytes_in = 0
        self.last_run = RunResult()
        self.last_status: Status | None = None
        if connect:
            try:
                self.connect()
            except BaseException:
                self.close()
                raise

    @classmethod
    def open(cls, port: str, baudrate: int = 115200, **kw: float) -> Link:
        """A link over a serial port or pty path (e.g. the LINK of ``fw_native --pty LINK``)."""
        return cls(SerialTransport(port, baudrate), **kw)  # type: ignore[arg-type]

    def close(self) -> None:
        """Close the port. During a run this is a hang-up: the firmware's run ends by
        itself (docs/PROTOCOL.md "Reconnecting"); :meth:`run` with ``resume`` continues it."""
        self.transport.close()

    def __enter__(self) -> Link:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    # ---- bytes and lines -----------------------------------------------------------------
    def _write(self, data: bytes) -> None:
        self.transport.write(data, self.timeout)

    def _fill(self, deadline: float) -> bool:
        """Read what arrives before the deadline (at most one read); True if bytes came."""
        left = deadline - time.monotonic()
        data = self.transport.read(max(0.0, left))
        if data:
            self.bytes_in += len(data)
            self._rx += data
            return True
        return False

    def _line(self, deadline: float) -> str:
        """The next line (without its end), waiting until the deadline."""
        while True:
            i = self._rx.find(b"\n")
            if i >= 0:
                raw = bytes(self._rx[:i])
                del self._rx[:i + 1]
                return raw.rstrip(b"\r").decode("ascii", "replace")
            if len(self._rx) > LINE_LIMIT:
                sample = bytes(self._rx[:40])
                self._rx.clear()
                raise StreamError("a line longer than %d bytes from the peer: %r..." % (LINE_LIMIT, sample))
            if time.monotonic() >= deadline:
                raise LinkTimeout("no complete line within %.1f s (have %r)" % (self.timeout, bytes(self._rx[:40])))
            self._fill(deadline)

    def _drain_quiet(self, quiet: float, limit: float) -> bytes:
        """Read until nothing arrives for `quiet` s (at most `limit` s); what was read."""
        got = bytearray(self._rx)
        self._rx.clear()
        end = time.monotonic() + limit
        while time.monotonic() < end:
            data = self.transport.read(min(quiet, max(0.0, end - time.monotonic())))
            if not data:
                break
            self.bytes_in += len(data)
            got += data
        return bytes(got)

    # ---- connecting ------------------------------------------------------------------------
    def connect(self) -> Info:
        """Bring the firmware to idle (docs/PROTOCOL.md "Reconnecting") and check ``$I``."""
        self.transport.discard_input()
        self._rx.clear()
        deadline = time.monotonic() + max(self.timeout, 1.0)
        heard = bytearray()
        probe = b"\n"
        idle = False
        while not idle and time.monotonic() < deadline:
            self._write(probe)
            wait_end = min(deadline, time.monotonic() + 0.25)
            while time.monotonic() < wait_end:
                if not self._fill(wait_end):
                    continue
                if len(heard) < 4096:
                    heard += self._rx[-256:]
                if fr.SYNC in self._rx and any(b < 0x20 and b not in (10, 13) for b in self._rx):
                    # binary with sync bytes: a FRAMES run left by a previous host
                    self._busy("a FRAMES run")
                    self._write(fr.RESYNC + fr.encode(0, fr.ABORT))
                    self._rx.clear()
                    continue
                while b"\n" in self._rx:
                    line = self._line(wait_end)
                    if line == "ok" or line == "<Idle>":
                        idle = True
                    elif line.startswith(("<Run|", "<Hold|", "[RUN:")) or is_program_line(line):
                        self._busy("a G-code run (%s)" % line[:40])
                        self._write(ABORT_BYTE)  # a G-code run left by a previous host
                if idle:
                    break
            probe = b"?" if probe == b"\n" and not heard else b"\n"
        if not idle:
            if not heard:
                raise SilentPeer("no answer at all to '\\n' and '?' within %.1f s: is the "
                                 "firmware running on this port?" % max(self.timeout, 1.0))
            raise NotCanalpath("the peer answered, but not as canalpath: %r" % bytes(heard[:60]))
        self._drain_quiet(0.05, self.timeout)  # duplicate answers of the probes
        self.info = self.hello()
        return self.info

    def _busy(self, what: str) -> None:
        if not self.abort_busy:
            raise LinkError("the firmware is busy with %s; Link(..., abort_busy=True) aborts it" % what)

    def hello(self) -> Info:
        """``$I``: the firmware's version and compile-time limits."""
        try:
            lines = self.command("$I")
        except CommandError as e:
            raise NotCanalpath("$I answered %s" % e.wire()) from e
        ver = next((s for s in lines if s.startswith("[VER:")), "")
        opt = next((s for s in lines if s.startswith("[OPT:")), "")
        m = re.match(r"^\[VER:canalpath (\S+) proto (\d+)\]$", ver)
        if m is None:
            raise NotCanalpath("$I answered %r, not a canalpath version line" % (lines[:2],))
        opts = dict(kv.split("=", 1) for kv in opt[5:-1].split(",") if "=" in kv)
        return Info("canalpath " + m.group(1), int(m.group(2)), opts, tuple(lines))

    # ---- commands ----------------------------------------------------------------------------
    def command(self, line: str, timeout: float | None = None) -> list[str]:
        """Send one command line; return the lines before its ``ok`` (info lines, relayed
        machine lines). ``error:<code>`` raises :class:`~canalpath.errors.CommandError`."""
        if self._in_frames:
            raise LinkError("a FRAMES run is in progress: text is not read")
        if len(line.encode("ascii", "replace")) > LINE_MAX:
            raise JobValueError(2, command=line)
        if any(not (0x20 <= ord(c) <= 0x7E or c == "\t") for c in line):
            raise JobValueError(8, command=line)
        t = self.timeout if timeout is None else timeout
        self._write(line.encode("ascii") + b"\n")
        deadline = time.monotonic() + t
        out: list[str] = []
        while True:
            s = self._line(deadline)
            if s == "ok":
                break
            err = parse_error_line(s, line)
            if err is not None:
                raise err
            if s.startswith("<"):
                self.last_status = parse_status(s) or self.last_status
                continue
            out.append(s)
            if len(out) > REPLY_LINES_MAX:
                raise StreamError("more than %d lines without a reply to %r" % (REPLY_LINES_MAX, line))
        self._format = _job_format([line], self._format)
        return out

    def send_job(self, job: Job | Iterable[str], clear: bool = True) -> None:
        """Send a job: ``JOB CLEAR`` (unless ``clear=False``), then every command line.

        ``JOB CLEAR`` keeps MACHINE and LINK in the firmware, so a job that sets neither
        gets ``MACHINE GENERIC`` and ``LINK HOST`` (the defaults) sent explicitly.
        """
        lines = list(job)
        kws = {ln.split()[0].upper() for ln in lines if ln.split()}
        if clear:
            self.command("JOB CLEAR")
            if "MACHINE" not in kws:
                self.command("MACHINE GENERIC")
            if "LINK" not in kws:
                self.command("LINK HOST")
        for line in lines:
            self.command(line)

    def dump(self) -> list[str]:
        """``$J``: the current job as the command lines that rebuild it."""
        return [s[5:-1] for s in self.command("$J") if s.startswith("[JOB:") and s.endswith("]")]

    # ---- real-time -------------------------------------------------------------------------------
    def status(self) -> Status:
        """``?`` when idle (or during a run on the machine link): the parsed report."""
        if self._in_frames:
            raise LinkError("a FRAMES run is in progress: '?' is not read")
        self._write(b"?")
        deadline = time.monotonic() + self.timeout
        while True:
            s = self._line(deadline)
            st = parse_status(s)
            if st is not None:
                self.last_status = st
                return st

    def hold(self) -> None:
        """Feed hold: ``!`` (a HOLD frame during a FRAMES run). While held, the run's
        silence timeout is suspended (a held run waits for :meth:`go` or :meth:`abort`)."""
        self._held = True
        self._write(fr.encode(0, fr.HOLD) if self._in_frames else b"!")

    def go(self) -> None:
        """Resume after a hold: ``~`` (a GO frame during a FRAMES run)."""
        self._held = False
        self._write(fr.encode(0, fr.GO) if self._in_frames else b"~")

    def abort(self) -> None:
        """Abort the run: 0x18 (an ABORT frame, after 64 sync bytes, during a FRAMES run).
        The run then ends with :class:`~canalpath.errors.Aborted`."""
        self._held = False
        self._write(fr.RESYNC + fr.encode(0, fr.ABORT) if self._in_frames else ABORT_BYTE)

    # ---- the run ---------------------------------------------------------------------------------
    def resume(self, k: int, **kw: object) -> Iterator[Point]:
        """``RESUME k``: the job (sent again after a hang-up) from point k on."""
        return self.run(resume=k, **kw)  # type: ignore[arg-type]

    def run(self, resume: int | None = None, *, progress: Callable[[Progress], None] | None = None,
            on_gcode: Callable[[str], None] | None = None,
            machine: Callable[[str], str] | None = None,
            fmt: str | None = None) -> Iterator[Point]:
        """RUN (or RESUME k) and yield the points as they arrive.

        FRAMES are decoded, CRC-checked, acknowledged, and gaps or bad frames NAKed; a G-code
        program is parsed (one point per G1) with the host acting as the machine: each line
        is answered by ``machine(line)`` (default ``"ok"``), with ``CHECKSUM ON`` lines
        verified and a bad one answered ``Resend:``. ``on_gcode`` gets every program line.
        ``progress`` is called with a :class:`Progress` at most every 0.25 s and at the end.
        ``fmt`` ("GCODE" or "FRAMES") overrides the format the link knows from the job
        sent; if neither is known the first byte tells.

        Ends when the firmware answers ``ok``; ``error:<code>`` raises
        :class:`~canalpath.errors.RunError` (:class:`~canalpath.errors.Aborted` for 20).
        ``Link.last_run`` has the account.
        """
        cmd = "RUN" if resume is None else "RESUME %d" % resume
        if self._in_frames:
            raise LinkError("a run is already in progress")
        fmt = fmt or self._format
        res = RunResult()
        self.last_run = res
        t0 = time.monotonic()
        b0 = self.bytes_in - len(self._rx)
        self._write(cmd.encode("ascii") + b"\n")
        if fmt is None:
            deadline = t0 + self.timeout
            while not self._rx:
                if time.monotonic() >= deadline:
                    raise LinkTimeout("no answer to %s within %.1f s" % (cmd, self.timeout))
                self._fill(deadline)
            fmt = "FRAMES" if self._rx[0] == 21 else "GCODE"  # BEGIN's length, or text
        res.format = fmt
        gen = self._run_frames(cmd, res, progress) if fmt == "FRAMES" else \
            self._run_gcode(cmd, res, progress, on_gcode, machine)
        try:
            yield from gen
            res.ok = True
        except CanalpathError as e:
            res.error = e
            raise
        except GeneratorExit:
            # the caller left the run unfinished: abort it, so the link is idle again
            # (after a hang-up, close() first: then there is nothing left to tell)
            self._abandon(fmt)
            raise
        finally:
            res.seconds = time.monotonic() - t0
            res.bytes_in = self.bytes_in - b0 - len(self._rx)
            gen.close()

    def _abandon(self, fmt: str) -> None:
        """Abort a run the caller stopped iterating, and drop its tail (best effort)."""
        try:
            self._write(fr.RESYNC + fr.encode(0, fr.ABORT) if fmt == "FRAMES" else ABORT_BYTE)
            deadline = time.monotonic() + self.timeout
            while time.monotonic() < deadline:
                data = self._drain_quiet(0.2, max(0.0, deadline - time.monotonic()))
                if not data or b"error:20" in data or data.endswith(b"ok\n"):
                    break
            self._drain_quiet(0.05, self.timeout)
            self._rx.clear()
        except (LinkError, OSError):
            pass

    def _progress(self, cb: Callable[[Progress], None] | None, res: RunResult, t0: float,
                  last: list[float], final: bool = False) -> None:
        now = time.monotonic()
        if cb is None or (not final and now - last[0] < PROGRESS_PERIOD):
            return
        last[0] = now
        el = now - t0
        total = (res.info.points - res.info.first) if res.info else 0
        rate = res.points / el if el > 0 else 0.0
        eta = (total - res.points) / rate if rate > 0 and total >= res.points else None
        cb(Progress(res.points, total, rate, eta, el))

    def _fail_run(self, exc: CanalpathError) -> CanalpathError:
        """Abort the run on the firmware (best effort) before raising exc."""
        try:
            self.abort()
            self._drain_quiet(0.3, self.timeout)
        except LinkError:
            pass
        return exc

    def _run_gcode(self, cmd: str, res: RunResult, progress: Callable[[Progress], None] | None,
                   on_gcode: Callable[[str], None] | None,
                   machine: Callable[[str], str] | None) -> Iterator[Point]:
        t0 = time.monotonic()
        last = [t0]
        expect_n = 1          # CHECKSUM ON: the next line number wanted
        resend_wait = False
        rx = self._rx
        progress_at = t0      # the last program line (chatter alone is no progress)
        while True:
            now = time.monotonic()
            if self._held:
                progress_at = now
            if now - progress_at > self.run_timeout:
                raise self._fail_run(StreamError("no program line for %.1f s (%s, %d points)"
                                                 % (self.run_timeout, cmd, res.points)))
            deadline = now + self.run_timeout
            # every complete line now held, answered with one write
            replies: list[bytes] = []
            pts: list[Point] = []
            done: str | None = None
            while done is None:
                i = rx.find(b"\n")
                if i < 0:
                    break
                raw = bytes(rx[:i])
                del rx[:i + 1]
                s = raw.rstrip(b"\r").decode("ascii", "replace")
                if s == "ok" or s.startswith("error:"):
                    done = s
                    break
                if s.startswith("["):
                    info = parse_run_header(s)
                    if info is not None:
                        res.info = info
                        progress_at = time.monotonic()
                    continue
                if s.startswith("<"):
                    st = parse_status(s)
                    if st is not None:
                        self.last_status = st
                        res.statuses.append(st)
                        progress_at = time.monotonic()
                    continue
                if not is_program_line(s):
                    continue  # chatter
                progress_at = time.monotonic()
                body = s
                if s.startswith("N"):
                    sn = split_numbered(s)
                    if sn is not None and sn[1].startswith("M110 N"):
                        expect_n = int(sn[1][6:]) + 1
                        resend_wait = False
                        replies.append(b"ok\n")
                        continue
                    if sn is None or sn[0] != expect_n:
                        if not resend_wait or (sn is None and s[1:].split(" ", 1)[0] == str(expect_n)):
                            replies.append(b"Resend: %d\nok\n" % expect_n)
                            res.resends += 1
                            resend_wait = True
                        else:
                            replies.append(b"ok\n")
                        continue
                    expect_n += 1
                    resend_wait = False
                    body = sn[1]
                res.program_lines += 1
                if on_gcode is not None:
                    on_gcode(body)
                if body.startswith("G1 "):
                    k = (res.info.first if res.info else 0) + res.points
                    p = parse_g1(body, k, res.info)
                    if p is None:
                        raise self._fail_run(StreamError("unparsable program line %r" % body))
                    pts.append(p)
                    res.points += 1
                replies.append((machine(body) + "\n").encode("ascii") if machine else b"ok\n")
            if replies:
                self._write(b"".join(replies))
            if pts:
                yield from pts
                self._progress(progress, res, t0, last)
            if done is not None:
                self._progress(progress, res, t0, last, final=True)
                if done != "ok":
                    err = parse_error_line(done, cmd, RunError, points=res.points)
                    assert err is not None
                    raise err
                return
            if len(rx) > LINE_LIMIT:
                raise self._fail_run(StreamError("a line longer than %d bytes in the run" % LINE_LIMIT))
            if not self._fill(min(deadline, time.monotonic() + POLL_PERIOD)):
                if time.monotonic() >= deadline and not self._held:
                    raise self._fail_run(LinkTimeout("the run fell silent for %.1f s (%s, %d points)"
                                                     % (self.run_timeout, cmd, res.points)))
                # quiet: ask. A run on the machine link sends the host nothing but its
                # reply; its <Run|...> reports show it alive (and give last_status)
                self._write(b"?")

    def _run_frames(self, cmd: str, res: RunResult,
                    progress: Callable[[Progress], None] | None) -> Iterator[Point]:
        t0 = time.monotonic()
        last = [t0]
        dec = FrameDecoder()
        expected = 0          # index of the next frame wanted
        nak_for = -1
        bad_seen = 0
        text = bytearray()
        end: fr.EndInfo | None = None
        began = False
        progress_at = t0      # time of the last in-order frame
        pending = bytes(self._rx)
        self._rx.clear()
        self._in_frames = True
        self._held = False
        write = self.transport.write
        tmo = self.timeout
        point_decode = fr.decode_point
        try:
            while True:
                data = pending
                pending = b""
                if not data:
                    data = self.transport.read(0.05)
                    self.bytes_in += len(data)
                    now = time.monotonic()
                    if self._held:
                        progress_at = now
                    if not data:
                        if now - progress_at > self.run_timeout:
                            raise self._fail_run(LinkTimeout(
                                "no frame for %.1f s (%s, %d points)" % (self.run_timeout, cmd, res.points)))
                        continue
                was_text = not began or end is not None
                got = dec.feed(data)
                pts: list[Point] = []
                ack = False
                for f in got:
                    diff = (f[1] - expected) & 0xFF
                    if diff:
                        if diff < 128:  # a gap: the frame wanted again, once
                            if nak_for != expected:
                                nak_for = expected
                                write(fr.encode(expected, fr.NAK), tmo)
                                res.naks += 1
                        else:           # a duplicate (a resend): acknowledge again
                            res.dup_frames += 1
                            ack = True
                        continue
                    t = f[2]
                    if t == fr.POINT:
                        p = point_decode(f[3:-3])
                        if p.k != (res.info.first if res.info else 0) + res.points:
                            raise self._fail_run(StreamError(
                                "POINT k=%d, expected %d" % (p.k, (res.info.first if res.info else 0) + res.points)))
                        pts.append(p)
                        res.points += 1
                    elif t == fr.BEGIN:
                        res.info = fr.decode_begin(f[3:-3])
                        began = True
                        text.clear()
                    elif t == fr.END:
                        end = fr.decode_end(f[3:-3])
                        text.clear()
                    else:
                        raise self._fail_run(StreamError("unexpected frame type 0x%02x" % t))
                    expected += 1
                    nak_for = -1
                    ack = True
                    progress_at = time.monotonic()
                if was_text or end is not None:
                    # text before BEGIN (a refusal) and after END (the reply)
                    text += data
                    while began and end is None:
                        text.clear()
                        break
                    while True:
                        i = text.find(b"\n")
                        if i < 0:
                            break
                        line = bytes(text[:i])
                        del text[:i + 1]
                        j = line.rfind(b"\x7e")
                        s = line[j + 1:].rstrip(b"\r").decode("ascii", "replace")
                        if (s == "ok" and end is not None) or s.startswith("error:"):
                            if ack:
                                write(fr.encode(expected, fr.ACK), tmo)
                            yield from pts
                            self._rx += text
                            self._progress(progress, res, t0, last, final=True)
                            if s == "ok":
                                return
                            err = parse_error_line(s, cmd, RunError, points=res.points)
                            assert err is not None
                            raise err
                    if len(text) > LINE_LIMIT:
                        del text[:-LINE_LIMIT]
                if dec.bad != bad_seen:
                    bad_seen = dec.bad
                    res.bad_frames = bad_seen
                    if began and end is None and nak_for != expected:
                        nak_for = expected
                        write(fr.encode(expected, fr.NAK), tmo)
                        res.naks += 1
                if ack:
                    write(fr.encode(expected, fr.ACK), tmo)
                if pts:
                    yield from pts
                    self._progress(progress, res, t0, last)
                if time.monotonic() - progress_at > self.run_timeout:
                    raise self._fail_run(StreamError(
                        "no valid frame for %.1f s (%d bad frames): garbage on the link"
                        % (self.run_timeout, dec.bad)))
        finally:
            self._in_frames = False

    # ---- job files -------------------------------------------------------------------------------
    def run_job(self, job: Job, **kw: object) -> list[Point]:
        """Send the job and run it; all points as a list."""
        self.send_job(job)
        return list(self.run(**kw))  # type: ignore[arg-type]


__all__ = ["Info", "Link", "Progress", "RunResult", "Status", "parse_status"]
