#!/usr/bin/python3
"""run_job.py - drive canalpath over a real serial port with pyserial (Debian python3-serial).

Usage: /usr/bin/python3 docs/examples/run_job.py DEVICE JOBFILE [OUT.ngc]

DEVICE is a serial device or pty path (e.g. /dev/ttyUSB0, or the /dev/pts/N that
`fw_native --pty` prints). The script sends the job (one command per line, '#'
comments), RUN, and then acts as a grbl-style machine: it answers "ok" to every
G-code line it receives. It prints the number of points and exits 0 when RUN is
answered "ok" (1 on any error or timeout). With OUT.ngc the G-code is saved.
"""
import sys
import time

import serial  # Debian: python3-serial (use /usr/bin/python3)


def readline(port, deadline):
    buf = b""
    while time.monotonic() < deadline:
        c = port.read(1)
        if not c:
            continue
        if c == b"\n":
            return buf.decode("ascii", "replace")
        buf += c
        if len(buf) > 512:
            raise RuntimeError("reply line too long: %r" % buf[:40])
    raise TimeoutError("no complete line before the deadline")


def command(port, line, timeout=5.0):
    port.write(line.encode("ascii") + b"\n")
    deadline = time.monotonic() + timeout
    while True:
        reply = readline(port, deadline)
        if reply.startswith("[") or reply.startswith("<"):
            continue
        return reply


def main():
    if len(sys.argv) < 3:
        print(__doc__)
        return 2
    device, jobfile = sys.argv[1], sys.argv[2]
    out = open(sys.argv[3], "w") if len(sys.argv) > 3 else None
    port = serial.Serial(device, 115200, timeout=0.2)
    reply = command(port, "$I")
    if reply != "ok":
        print("handshake failed: %r" % reply)
        return 1
    for raw in open(jobfile):
        line = raw.split("#", 1)[0].strip()
        if not line or line.upper() in ("RUN",):
            continue
        reply = command(port, line)
        if reply != "ok":
            print("%s -> %s" % (line, reply))
            return 1
    port.write(b"RUN\n")
    points = 0
    deadline = time.monotonic() + 120.0
    while True:
        line = readline(port, deadline)
        if line.startswith(("G", "M", "N")):  # a program line (docs/PROTOCOL.md)
            if out:
                out.write(line + "\n")
            if "G1 " in line:  # one feed move per point; G0 lines are the safe moves
                points += 1
            port.write(b"ok\n")  # the machine accepted the line
        elif line == "ok":
            break
        elif line.startswith("error:"):
            print("RUN -> %s" % line)
            return 1
    if out:
        out.close()  # the program ends with its own M2
    print("pyserial: %d points, RUN ok" % points)
    return 0


if __name__ == "__main__":
    sys.exit(main())
