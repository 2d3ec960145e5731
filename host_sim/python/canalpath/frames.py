"""FORMAT FRAMES: the binary frames of docs/PROTOCOL.md "RUN with FORMAT FRAMES".

::

    +-----+-----+------+-----------------+------------+------+
    | len | seq | type | payload         | crc16 (BE) | 0x7E |
    +-----+-----+------+-----------------+------------+------+

``len`` is the whole frame (6..64), ``seq`` the low 8 bits of the frame's index in the
run, CRC-16/CCITT-FALSE (poly 0x1021, init 0xFFFF) over len..payload (``binascii.crc_hqx``
computes exactly this CRC). Payload fields are little-endian.
"""
from __future__ import annotations

import binascii
import struct
from dataclasses import dataclass

SYNC = 0x7E
FRAME_MIN = 6
FRAME_MAX = 64
OVERHEAD = 6

BEGIN = 0x01
POINT = 0x02
END = 0x03
ACK = 0x81
NAK = 0x82
ABORT = 0x83
HOLD = 0x84
GO = 0x85

#: 64 sync bytes: they complete any frame that noise started and resynchronise the
#: firmware's decoder (docs/PROTOCOL.md "Reconnecting", point 5)
RESYNC = bytes([SYNC]) * 64

_POINT = struct.Struct("<IiiihhhhH")   # k, x, y, z, nx, ny, nz, line, index (26 bytes)
_BEGIN = struct.Struct("<IIHHHB")      # points, first, n, steps, link, mode (15 bytes), then
                                       # u8 overlap (issue 22; absent before it)
_END = struct.Struct("<BI")            # status, points (5 bytes)
_crc = binascii.crc_hqx


def crc16(data: bytes | bytearray | memoryview, crc: int = 0xFFFF) -> int:
    """CRC-16/CCITT-FALSE of data, continuing from crc."""
    return _crc(data, crc)


def encode(seq: int, ftype: int, payload: bytes = b"") -> bytes:
    """One frame: len, seq, type, payload, CRC (big-endian), 0x7E."""
    n = len(payload) + OVERHEAD
    if n > FRAME_MAX:
        raise ValueError("payload of %d bytes does not fit a frame" % len(payload))
    head = bytes((n, seq & 0xFF, ftype)) + payload
    c = _crc(head, 0xFFFF)
    return head + bytes((c >> 8, c & 0xFF, SYNC))


@dataclass(frozen=True, slots=True)
class Point:
    """One point of the stream.

    ``k`` its index in the job, ``x, y, z`` mm (0.1 um resolution), ``normal`` the unit
    normal (FRAMES; G-code with TOOLAXIS: the tool axis) or None, ``line`` the line or
    circle (-1: a link point), ``index`` the point's index on it.
    """

    k: int
    x: float
    y: float
    z: float
    normal: tuple[float, float, float] | None
    line: int
    index: int

    def csv_row(self) -> str:
        """The row host_sim writes for this point (``--csv``)."""
        s = "%d,%d,%s,%s,%s" % (self.line, self.index, fixed4(self.x), fixed4(self.y), fixed4(self.z))
        if self.normal is not None:
            s += ",%.5f,%.5f,%.5f" % self.normal
        return s


def fixed4(v: float) -> str:
    """v mm with 4 decimals, as the firmware and host_sim print it (0.1 um exactly)."""
    q = round(v * 1e4)
    a = -q if q < 0 else q
    return "%s%d.%04d" % ("-" if q < 0 else "", a // 10000, a % 10000)


@dataclass(frozen=True, slots=True)
class RunInfo:
    """What a run announces first (``[RUN:...]`` line or BEGIN frame)."""

    points: int      # points of the job
    first: int       # first point of this run (RESUME k)
    mode: str        # "LINES" or "CIRCLES"
    n: int           # lines or circles
    steps: int
    link: int        # link points between lines
    format: str      # "GCODE" or "FRAMES"
    overlap: bool = False  # far parts of the sweep meet, the tool inside (issue 22: reported)


@dataclass(frozen=True, slots=True)
class EndInfo:
    """The END frame: status (0 = complete) and the points sent."""

    status: int
    points: int


def decode_point(payload: bytes | bytearray | memoryview) -> Point:
    """A POINT frame's payload as a Point."""
    k, x, y, z, nx, ny, nz, line, index = _POINT.unpack_from(payload)
    return Point(k, x / 1e4, y / 1e4, z / 1e4, (nx / 32767.0, ny / 32767.0, nz / 32767.0), line, index)


def decode_begin(payload: bytes | bytearray | memoryview) -> RunInfo:
    """A BEGIN frame's payload."""
    points, first, n, steps, link, mode = _BEGIN.unpack_from(payload)
    overlap = len(payload) > _BEGIN.size and payload[_BEGIN.size] == 1
    return RunInfo(points, first, "CIRCLES" if mode == 1 else "LINES", n, steps, link, "FRAMES",
                   overlap)


def decode_end(payload: bytes | bytearray | memoryview) -> EndInfo:
    """An END frame's payload."""
    status, points = _END.unpack_from(payload)
    return EndInfo(status, points)


class FrameDecoder:
    """The frame decoder of firmware/proto/frame.c, fed with any number of bytes at once.

    A byte 6..64 where a frame may start is its length; that many bytes are collected and
    the sync byte and CRC checked. A failed frame, or a byte outside 6..64 there, makes it
    skip up to the next 0x7E. ``bad`` counts the frames (and garbage runs) discarded.
    """

    __slots__ = ("_buf", "_discard", "bad")

    def __init__(self) -> None:
        self._buf = bytearray()
        self._discard = False
        self.bad = 0

    def reset(self) -> None:
        """Forget every byte held (a new run)."""
        self._buf.clear()
        self._discard = False

    def feed(self, data: bytes | bytearray) -> list[bytes]:
        """Feed bytes; the complete, CRC-valid frames among them (each ``len`` bytes)."""
        buf = self._buf
        buf += data
        out: list[bytes] = []
        i = 0
        n = len(buf)
        crc = _crc
        while i < n:
            if self._discard:
                j = buf.find(SYNC, i)
                if j < 0:
                    i = n
                    break
                i = j + 1
                self._discard = False
                continue
            ln = buf[i]
            if ln == SYNC:
                i += 1
                continue
            if ln < FRAME_MIN or ln > FRAME_MAX:
                self.bad += 1
                self._discard = True
                i += 1
                continue
            if i + ln > n:
                break
            end = i + ln
            if buf[end - 1] == SYNC and crc(buf[i:end - 1], 0xFFFF) == 0:
                out.append(bytes(buf[i:end]))
            else:
                self.bad += 1
                self._discard = buf[end - 1] != SYNC
            i = end
        del buf[:i]
        return out
