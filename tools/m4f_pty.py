#!/usr/bin/python3
# m4f_pty.py - talk to build/m4f/fw.elf on QEMU through a host-created pty, then read the
# painted stack back through the QEMU monitor (measured stack peak of the real image).
# SPDX-License-Identifier: MIT
# Usage: m4f_pty.py <fw.elf> <sstack-hex> <stack-bytes> <peak-out-file>
# Prints "m4f-pty: N passed, N failed"; exit status 0 iff nothing failed.
import os, select, socket, subprocess, sys, time, tty

elf, sstack, size, peak_out = sys.argv[1], int(sys.argv[2], 16), int(sys.argv[3]), sys.argv[4]
PAINT = 0xC0FFEE55  # STARTUP_STACK_PAINT in hal/cortex-m/startup.h
mon_path = os.path.join(os.path.dirname(elf), "qemu-mon.sock")
dump_path = os.path.abspath(os.path.join(os.path.dirname(elf), "stack.bin"))
for p in (mon_path, dump_path):
    if os.path.exists(p):
        os.unlink(p)
master, slave = os.openpty()  # keep slave open until QEMU has opened the path (QEMU.md §3)
tty.setraw(master)
# timeouts (the rule of mk/m4f.mk: >= 5x the unloaded time; 2026-11-26): the whole script
# takes 0.6 s, each reply <= 0.03 s, so 30 s for QEMU and 2-60 s per step are hang guards
qemu = subprocess.Popen(["timeout", "30", "qemu-system-arm", "-M", "mps2-an386", "-display", "none",
                         "-monitor", "unix:%s,server=on,wait=off" % mon_path,
                         "-serial", os.ttyname(slave), "-semihosting-config", "enable=on,target=native",
                         "-icount", "shift=7", "-kernel", elf])
passed = failed = 0


def check(ok, what):
    global passed, failed
    passed += bool(ok)
    failed += not ok
    print("  %s: %s" % ("ok  " if ok else "FAIL", what))


def read_until(want, timeout):
    buf, end = b"", time.time() + timeout
    while time.time() < end and want not in buf:
        r, _, _ = select.select([master], [], [], 0.05)
        if r:
            buf += os.read(master, 4096)
    return buf


# 1. sync: the firmware never speaks first; repeat $I until it answers
got, t0 = b"", time.time()
while time.time() - t0 < 10 and b"ok\n" not in got:
    os.write(master, b"$I\n")
    got += read_until(b"ok\n", 0.2)
check(b"[VER:canalpath" in got and b"ok\n" in got, "$I answered: %r" % got.split(b"\n")[0])
time.sleep(0.2)
read_until(b"\x00", 0.1)  # drain duplicate answers of the sync
# 2. unknown command -> error line
os.write(master, b"NOSUCH\n")
r = read_until(b"\n", 2)
check(r.startswith(b"error:"), "unknown command -> %r" % r.strip())
# 3. a pipelined burst larger than the RX ring and the UART: back-pressure, no loss
n = 40
os.write(master, b"$I\n" * n)
r, end = b"", time.time() + 10
while time.time() < end and r.count(b"ok\n") < n:
    r += read_until(b"ok\n", 0.2)
check(r.count(b"ok\n") == n and r.count(b"[VER:") == n, "%d pipelined $I -> %d ok" % (n, r.count(b"ok\n")))
# 4. a real job: the deepest firmware paths (canal_path_init's walk, streaming) run
#    before the stack is read; act as a machine that answers ok per G-code line
job = [b"CURVE ARC 0 0 3 0 360", b"RADIUS COS 5.5 10.5 2", b"LINES 3 -25 10", b"TOL 20",
       b"TOOL BALL 1", b"CIRCLES 24 -20 10", b"CHECKSUM ON", b"FEED 600", b"SAFE 40"]
okc = 0
for line in job:
    os.write(master, line + b"\n")
    okc += read_until(b"ok\n", 5).endswith(b"ok\n")
check(okc == len(job), "job accepted (%d/%d ok)" % (okc, len(job)))
os.write(master, b"RUN\n")
buf, glines, done, end = b"", 0, False, time.time() + 60
while time.time() < end and not done:
    r, _, _ = select.select([master], [], [], 0.05)
    if r:
        buf += os.read(master, 4096)
    while b"\n" in buf:
        line, buf = buf.split(b"\n", 1)
        if line.startswith(b"N"):
            glines += 1
            os.write(master, b"ok\n")
        elif line == b"ok" or line.startswith(b"error:"):
            if line != b"ok":
                print("  RUN -> %r" % line)
            done = line == b"ok"
            end = 0
            break
check(done and glines > 50, "RUN streamed %d checksummed G-code lines, then ok" % glines)
# 5. measured stack: dump the stack region through the monitor
peak = None
try:
    s = socket.socket(socket.AF_UNIX)
    s.connect(mon_path)
    s.settimeout(2)
    s.sendall(b'pmemsave 0x%x %d "%s"\n' % (sstack, size, dump_path.encode()))
    for _ in range(40):
        if os.path.exists(dump_path) and os.path.getsize(dump_path) == size:
            break
        time.sleep(0.05)
    data = open(dump_path, "rb").read()
    words = [int.from_bytes(data[i:i + 4], "little") for i in range(0, len(data), 4)]
    low = next((i for i, w in enumerate(words) if w != PAINT), len(words))
    peak = size - 4 * low
    with open(peak_out, "w") as f:
        f.write("%d\n" % peak)
    s.sendall(b"quit\n")
except (OSError, ValueError) as e:
    print("  monitor: %s" % e)
check(peak is not None and 0 < peak < size, "painted stack peak of fw.elf: %s of %d bytes" % (peak, size))
try:
    qemu.wait(timeout=5)
except subprocess.TimeoutExpired:
    qemu.kill()
os.close(slave)
os.close(master)
print("m4f-pty: %d passed, %d failed" % (passed, failed))
sys.exit(failed != 0)
