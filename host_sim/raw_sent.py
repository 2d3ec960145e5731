#!/usr/bin/python3
"""raw_sent.py - a raw RUN stream (host_sim --raw) without the FRAMES retransmissions.

SPDX-License-Identifier: MIT

Usage: python3 host_sim/raw_sent.py RAW OUT
Writes RAW to OUT with every frame removed that repeats, byte for byte, a frame already
sent in the same run (a run ends at a text line: the RUN reply), and prints how many were
removed.

Why: a FRAMES run is go-back-N (docs/PROTOCOL.md "Frames"): when no ACK comes within
OUT_FRAMES_RTO_MS (250 ms) the firmware sends its window again. Whether that happens
depends on how fast the host answers (a loaded CI machine stalls host_sim for that long
now and then), not on the firmware's output, so sim_suite.sh's native-vs-QEMU comparison
compares the streams as SENT ONCE: every frame's bytes and order are still compared, and a
retransmitted frame that differs from the original is kept, so it still fails the
comparison. A frame is: length byte L (6..64), L - 1 more bytes ending in the sync byte 0x7E,
CRC-16/CCITT-FALSE over the first L - 1 bytes equal to 0 (firmware/proto/frame.h);
anything else is text up to its newline.
"""
import binascii
import sys

SYNC = 0x7E
FRAME_MIN, FRAME_MAX = 6, 64


def frame_at(d: bytes, i: int) -> int:
    """The length of the CRC-valid frame at d[i], or 0."""
    ln = d[i]
    if ln < FRAME_MIN or ln > FRAME_MAX or i + ln > len(d) or d[i + ln - 1] != SYNC:
        return 0
    return ln if binascii.crc_hqx(d[i:i + ln - 1], 0xFFFF) == 0 else 0


def sent_once(d: bytes) -> tuple[bytes, int]:
    out = bytearray()
    seen: set[bytes] = set()
    removed = 0
    i = 0
    while i < len(d):
        ln = frame_at(d, i)
        if ln:
            f = d[i:i + ln]
            if f in seen:
                removed += 1
            else:
                seen.add(f)
                out += f
            i += ln
            continue
        out.append(d[i])
        if d[i] == 0x0A:
            seen.clear()  # a text line ended: the run's reply (or text before a run)
        i += 1
    return bytes(out), removed


def main() -> int:
    if len(sys.argv) != 3:
        print("usage: raw_sent.py RAW OUT", file=sys.stderr)
        return 2
    with open(sys.argv[1], "rb") as f:
        data, removed = sent_once(f.read())
    with open(sys.argv[2], "wb") as f:
        f.write(data)
    print(removed)
    return 0


if __name__ == "__main__":
    sys.exit(main())
