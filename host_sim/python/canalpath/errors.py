"""Typed exceptions of the canalpath host library.

Two families:

* :class:`FirmwareError` - a status of the firmware's table (docs/PROTOCOL.md "Status
  codes"): an ``error:<code> <text>`` reply, or a job value the library refused before
  sending it (:class:`JobValueError`, with the code and text the firmware would answer).
* :class:`LinkError` - the link itself: no answer in time, a peer that is not canalpath,
  a hang-up, a stream that cannot be decoded.
"""
from __future__ import annotations

import re

from .status import status_name, status_text

_ERROR_RE = re.compile(r"^error:(\d+)(?: (.*))?$")


class CanalpathError(Exception):
    """Base class of every exception the library raises on purpose."""


class FirmwareError(CanalpathError):
    """A firmware status other than ``ok``.

    Attributes: ``code`` (the wire code), ``name`` (its NAME in cp_status.def),
    ``text`` (the firmware's text), ``cause`` (what follows in parentheses, e.g.
    ``"FEED 0.0009: 0 or 0.001..1e6"``, or ``""``), ``command`` (the line that was
    answered, if known).
    """

    def __init__(self, code: int, text: str | None = None, cause: str = "", command: str = "") -> None:
        self.code = code
        self.name = status_name(code)
        self.text = text if text is not None else status_text(code)
        self.cause = cause
        self.command = command
        super().__init__(self.wire())

    def wire(self) -> str:
        """The reply as the firmware writes it: ``error:<code> <text>[ (<cause>)]``."""
        s = "error:%d %s" % (self.code, self.text)
        return s + (" (%s)" % self.cause if self.cause else "")

    def __str__(self) -> str:
        return self.wire() + (" [to %r]" % self.command if self.command else "")


class CommandError(FirmwareError):
    """The firmware answered a command line with ``error:<code> ...``."""


class RunError(FirmwareError):
    """RUN or RESUME was refused, or the run stopped early (``error:<code>`` after it).

    ``points`` is the number of points received before the error.
    """

    def __init__(self, code: int, text: str | None = None, cause: str = "", command: str = "",
                 points: int = 0) -> None:
        super().__init__(code, text, cause, command)
        self.points = points


class Aborted(RunError):
    """The run was aborted (``error:20 aborted``)."""


class JobValueError(FirmwareError, ValueError):
    """A job value the library refused before sending it, with the firmware's own code,
    text and cause (what the firmware would have answered)."""


class LinkError(CanalpathError):
    """A problem of the link, not a firmware status."""


class LinkTimeout(LinkError, TimeoutError):
    """No (complete) answer within the timeout."""


class SilentPeer(LinkTimeout):
    """The port answered nothing at all to the handshake."""


class NotCanalpath(LinkError):
    """The peer answered, but not as a canalpath firmware (an echo, another device)."""


class LinkClosed(LinkError, ConnectionError):
    """The port hung up (end of file or an I/O error)."""


class StreamError(LinkError):
    """The run's stream could not be decoded: garbage frames without progress, an
    unparsable program line, a reply flood."""


def parse_error_line(line: str, command: str = "", cls: type[FirmwareError] = CommandError,
                     **kw: int) -> FirmwareError | None:
    """The exception for an ``error:<code> <text> (<cause>)`` line, or None if the line
    is not one. The text is taken up to `` (`` (docs/PROTOCOL.md "Lines")."""
    m = _ERROR_RE.match(line)
    if m is None:
        return None
    code = int(m.group(1))
    rest = m.group(2) or ""
    text, cause = rest, ""
    i = rest.find(" (")
    if i >= 0 and rest.endswith(")"):
        text, cause = rest[:i], rest[i + 2:-1]
    if cls is RunError and code == 20:
        cls = Aborted
    return cls(code, text, cause, command, **kw)
