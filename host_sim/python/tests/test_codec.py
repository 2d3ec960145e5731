"""The status table, the frame codec and the G-code parser, without a firmware."""
from __future__ import annotations

import os
import re

from conftest import REPO

from canalpath import STATUS, FrameDecoder
from canalpath import frames as fr
from canalpath.errors import Aborted, CommandError, RunError, parse_error_line
from canalpath.gcode import line_index, parse_g1, parse_run_header, split_numbered


def test_status_table_is_the_firmwares():
    rows = re.findall(r'^CP_STATUS\((\w+),\s*(\d+),\s*"([^"]*)"',
                      (REPO / "firmware/base/cp_status.def").read_text(), re.M)
    assert len(rows) > 40
    assert {int(c): (n, t) for n, c, t in rows} == STATUS


def test_abort_frame_is_the_documented_bytes():
    assert fr.encode(0, fr.ABORT) == bytes.fromhex("060083DFD77E")


def test_point_frame_round_trip_and_fields():
    import struct
    pl = struct.pack("<IiiihhhhH", 7, 97619, -2550, 14991, 0, -32767, 12, 3, 41)
    f = fr.encode(9, fr.POINT, pl)
    assert len(f) == 32
    got = FrameDecoder().feed(f)
    assert got == [f]
    p = fr.decode_point(got[0][3:-3])
    assert (p.k, p.x, p.y, p.z, p.line, p.index) == (7, 9.7619, -0.255, 1.4991, 3, 41)
    assert p.csv_row() == "3,41,9.7619,-0.2550,1.4991,0.00000,-1.00000,0.00037"


def test_decoder_resynchronises_like_the_firmware():
    frames = [fr.encode(i, fr.POINT, bytes(range(i, i + 26))) for i in range(40)]
    stream = bytearray(b"".join(frames))
    stream[32 * 5 + 10] ^= 0x40          # frame 5: bad CRC
    stream[32 * 9] = 0x70                # frame 9: a length outside 6..64
    noise = os.urandom(300).replace(b"\x7e", b"\x00")
    data = bytes(stream[:32 * 20]) + noise + b"\x7e" + bytes(stream[32 * 20:])
    whole = FrameDecoder()
    got = whole.feed(data)
    seqs = [f[1] for f in got]
    assert 5 not in seqs and 9 not in seqs
    assert seqs[:5] == [0, 1, 2, 3, 4]
    assert seqs[-19:] == list(range(21, 40))
    assert whole.bad >= 3
    # byte by byte gives the same frames
    one = FrameDecoder()
    bybyte = [f for b in data for f in one.feed(bytes([b]))]
    assert bybyte == got and one.bad == whole.bad


def test_error_lines_parse_with_cause():
    e = parse_error_line("error:6 value out of range (FEED 0.0009: 0 or 0.001..1e6)", "FEED 0.0009")
    assert isinstance(e, CommandError)
    assert (e.code, e.text, e.cause, e.name) == (6, "value out of range", "FEED 0.0009: 0 or 0.001..1e6",
                                                 "OUT_OF_RANGE")
    r = parse_error_line("error:20 aborted", "RUN", RunError)
    assert isinstance(r, Aborted) and r.code == 20
    assert parse_error_line("ok") is None


def test_gcode_lines():
    info = parse_run_header("[RUN:points=4117,first=0,mode=LINES,n=8,steps=511,link=3]")
    assert info is not None and (info.points, info.steps, info.link, info.mode) == (4117, 511, 3, "LINES")
    assert not info.overlap
    o = parse_run_header("[RUN:points=1049,first=0,mode=LINES,n=2,steps=24,link=1,overlap=1]")
    assert o is not None and o.overlap and o.points == 1049   # issue 22: reported, harmless
    p = parse_g1("G1 X9.7555 Y-0.2550 Z1.4980 F600", 1, info)
    assert p is not None and (p.x, p.y, p.z, p.line, p.index, p.normal) == (9.7555, -0.255, 1.498, 0, 1, None)
    assert parse_g1("G1 X9.7555 Y0.2550", 1, info) is None
    assert parse_g1("G1 X9.75555 Y0 Z0", 1, info) is None      # 5 decimals: not the firmware's
    q = parse_g1("G1 X1 Y2 Z3 I0.0000 J0.0000 K1.0000", 0, info)
    assert q is not None and q.normal == (0.0, 0.0, 1.0)
    assert line_index(info, 511) == (0, 511)       # the last point of line 0
    assert line_index(info, 512) == (-1, 1)        # the first of 3 link points
    assert line_index(info, 515) == (1, 511)       # line 1 runs backwards
    assert split_numbered("N0 M110 N0*125") == (0, "M110 N0")
    assert split_numbered("N1 G21*27") == (1, "G21")
    assert split_numbered("N1 G21*28") is None
