"""canalpath - the Python host library of the canalpath firmware.

Send jobs, take the stream (FRAMES or G-code), resume after a hang-up::

    from canalpath import Job, Link

    job = (Job().curve_arc(0, 0, 3, 0, 360).radius_cos(5.5, 10.5, 2)
                .lines(8, -25, 10).tol(2).feed(600).safe(50).format("FRAMES"))
    with Link.open("/dev/ttyACM0") as link:
        link.send_job(job)
        for p in link.run():
            print(p.k, p.x, p.y, p.z)

docs/PROTOCOL.md is the specification of every byte.
"""
from .errors import (Aborted, CanalpathError, CommandError, FirmwareError, JobValueError,
                     LinkClosed, LinkError, LinkTimeout, NotCanalpath, RunError, SilentPeer,
                     StreamError)
from .frames import EndInfo, FrameDecoder, Point, RunInfo
from .job import Job, check_line
from .link import Info, Link, Progress, RunResult, Status, parse_status
from .script import ExpectationError, Step, read_script, run_script
from .status import STATUS, status_text
from .transport import FdTransport, SerialTransport, Transport

__version__ = "0.1.0"

__all__ = [
    "Aborted", "CanalpathError", "CommandError", "EndInfo", "ExpectationError", "FdTransport",
    "FirmwareError", "FrameDecoder", "Info", "Job", "JobValueError", "Link", "LinkClosed",
    "LinkError", "LinkTimeout", "NotCanalpath", "Point", "Progress", "RunError", "RunInfo",
    "RunResult", "STATUS", "SerialTransport", "SilentPeer", "Status", "Step", "StreamError",
    "Transport", "check_line", "parse_status", "read_script", "run_script", "status_text",
]
