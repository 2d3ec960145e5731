#!/usr/bin/python3
# m4f_stack_soak.py - measured (painted) stack of build/m4f/fw.elf after soak-like sessions and
# the fuzz corpus replay, next to the static worst path of `make stack` (docs/SOAK.md).
# Grown from a copy of tools/m4f_pty.py.
# SPDX-License-Identifier: MIT
#
# Usage: m4f_stack_soak.py <fw.elf> <sstack-hex> <stack-bytes> <stack.sh-output-file>
#        (mk/hardening.mk: make stack-soak). Env: BUILD, QEMU.
# Part A: one QEMU session on a host-created pty with a monitor socket: $I, an unknown
#   command, a pipelined burst, a checksummed CIRCLES job with a tool where this machine
#   requests two Resends, a FRAMES job with host garbage (tests/corpus/frame) and one
#   NAK, the fuzz corpus tests/corpus/cmd replayed as host bytes (in pieces ending at
#   '\n', a minimal machine answering between them, as tests/fuzz_cmd.c does), the
#   number corpus tests/corpus/num as command arguments; then the stack region is dumped
#   through the monitor (pmemsave) and scanned for the deepest overwritten paint word.
# Part B: host_sim sessions (judged) with this script as the QEMU program (--qemu): in
#   that role (env M4F_STACK_SOAK_WRAP) it runs QEMU with a monitor socket, and when
#   host_sim ends it (SIGTERM) it dumps the stack region first and records the peak.
#   Jobs: FRAMES with drop/flip/dup faults (NAK, go-back-N), hang-ups + RESUME in FRAMES
#   and GCODE+CHECKSUM, CIRCLES, PATCH, ELLIPSE, BEZIER with a tool.
# Checks: every session passes; painted peak (max over all) <= region; static worst
# <= region. Prints "stack-soak: N passed, N failed".
import os, select, signal, socket, subprocess, sys, time, tty

PAINT = 0xC0FFEE55  # STARTUP_STACK_PAINT in hal/cortex-m/startup.h


def painted_peak(mon_path, sstack, size, dump_path):
    """pmemsave the stack region through the monitor; bytes used since reset or None."""
    if os.path.exists(dump_path):
        os.unlink(dump_path)
    s = socket.socket(socket.AF_UNIX)
    s.settimeout(2)
    for _ in range(40):
        try:
            s.connect(mon_path)
            break
        except OSError:
            time.sleep(0.005)
    s.sendall(b'pmemsave 0x%x %d "%s"\n' % (sstack, size, dump_path.encode()))
    for _ in range(200):
        if os.path.exists(dump_path) and os.path.getsize(dump_path) == size:
            break
        time.sleep(0.002)
    data = open(dump_path, "rb").read()
    if len(data) != size:
        return None, s
    words = [int.from_bytes(data[i:i + 4], "little") for i in range(0, len(data), 4)]
    low = next((i for i, w in enumerate(words) if w != PAINT), len(words))
    return size - 4 * low, s


# ---------------------------------------------------------------- wrapper role (part B)
def wrap():
    """Run as host_sim's QEMU: the same command line with a monitor socket instead of
    -monitor none; on SIGTERM dump the stack, record the peak, quit QEMU."""
    out = os.environ["M4F_STACK_SOAK_WRAP"]
    sstack = int(os.environ["M4F_STACK_SOAK_SSTACK"], 16)
    size = int(os.environ["M4F_STACK_SOAK_SIZE"])
    qemu_bin = os.environ.get("QEMU", "qemu-system-arm")
    tag = "%s.%d" % (out, os.getpid())
    mon = tag + ".mon"
    args = sys.argv[1:]
    for i in range(len(args) - 1):
        if args[i] == "-monitor":
            args[i + 1] = "unix:%s,server=on,wait=off" % mon
    import ctypes
    libc = ctypes.CDLL(None, use_errno=True)

    def child():
        os.setpgid(0, 0)  # not in host_sim's group: its SIGTERM must reach this wrapper first
        libc.prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG: never outlive the wrapper

    stop = []
    signal.signal(signal.SIGTERM, lambda *_: stop.append(1))
    signal.signal(signal.SIGINT, lambda *_: stop.append(1))
    q = subprocess.Popen([qemu_bin] + args, preexec_fn=child)
    while q.poll() is None and not stop:
        time.sleep(0.01)
    rc = q.poll()
    if rc is None:
        peak = None
        try:
            peak, s = painted_peak(mon, sstack, size, tag + ".bin")
            s.sendall(b"quit\n")
        except (OSError, ValueError) as e:
            sys.stderr.write("m4f_stack_soak: monitor: %s\n" % e)
        with open(out, "a") as f:
            f.write("%s\n" % (peak if peak is not None else "none"))
        try:
            q.wait(timeout=0.3)
        except subprocess.TimeoutExpired:
            q.kill()
            q.wait()
    for p in (mon, tag + ".bin"):
        if os.path.exists(p):
            os.unlink(p)
    sys.exit(0 if rc is None else rc)


if os.environ.get("M4F_STACK_SOAK_WRAP"):
    wrap()

# ---------------------------------------------------------------- driver
elf, sstack, size, static_file = sys.argv[1], int(sys.argv[2], 16), int(sys.argv[3]), sys.argv[4]
B = os.environ.get("BUILD", "build")
QEMU = os.environ.get("QEMU", "qemu-system-arm")
work = os.path.abspath(os.path.join(os.path.dirname(elf), "stack_soak"))
os.makedirs(work, exist_ok=True)
passed = failed = 0


def check(ok, what):
    global passed, failed
    passed += bool(ok)
    failed += not ok
    print("  %s %s" % ("PASS" if ok else "FAIL", what))
    sys.stdout.flush()


# ---- part A: own session (the structure of tools/m4f_pty.py)
mon_path = os.path.join(work, "qemu-mon.sock")
if os.path.exists(mon_path):
    os.unlink(mon_path)
master, slave = os.openpty()  # keep slave open until QEMU has opened the path (QEMU.md §3)
tty.setraw(master)
# timeout: >= 5x part A's unloaded run time (the rule of mk/m4f.mk). Part A takes 17 s
# (it took 142 s in 2 of 3 runs on 2026-11-26 while step 5's frames_in dropped the
# run's closing "ok" behind the END frame as noise and machine() waited out its 120 s;
# fixed the same day): 900 s stays >= 5 x 142 s even if a step ever waits again. The other
# limits of this file, measured the same day: painted_peak's 0.2 s / 0.4 s loops vs
# <= 7.4 ms, sync()'s 3 s vs <= 0.26 s, the 5-20 s reply waits vs <= 1 ms per reply, the
# 120 s runs vs 0.6 s, host_sim's 600 s / 20 s per session / reply vs <= 2 s.
qemu = subprocess.Popen(["timeout", "900", QEMU, "-M", "mps2-an386", "-display", "none",
                         "-monitor", "unix:%s,server=on,wait=off" % mon_path,
                         "-serial", os.ttyname(slave), "-semihosting-config", "enable=on,target=native",
                         "-icount", "shift=7", "-kernel", elf])
rxbuf = b""


def read_some(timeout):
    global rxbuf
    r, _, _ = select.select([master], [], [], timeout)
    if r:
        rxbuf += os.read(master, 65536)


def read_until(want, timeout):
    global rxbuf
    end = time.time() + timeout
    while time.time() < end and want not in rxbuf:
        read_some(0.02)
    if want in rxbuf:
        i = rxbuf.index(want) + len(want)
        got, rxbuf = rxbuf[:i], rxbuf[i:]
        return got
    got, rxbuf = rxbuf, b""
    return got


def crc16(b):
    c = 0xFFFF
    for x in b:
        c ^= x << 8
        for _ in range(8):
            c = ((c << 1) ^ 0x1021) & 0xFFFF if c & 0x8000 else (c << 1) & 0xFFFF
    return c


def frame(seq, typ):
    body = bytes([6, seq & 0xFF, typ])
    c = crc16(body)
    return body + bytes([c >> 8, c & 0xFF, 0x7E])


def sync(timeout=3.0):
    """Abort whatever runs (ABORT frame after 64 sync bytes, 0x18), then $I until ok."""
    global rxbuf
    os.write(master, b"\x7e" * 64 + frame(0, 0x83) + b"\x18\n")
    end = time.time() + timeout
    while time.time() < end:
        os.write(master, b"$I\n")
        got = read_until(b"ok\n", 0.2)
        if b"[VER:" in got:
            time.sleep(0.05)
            read_some(0.05)
            rxbuf = b""
            return True
    return False


def frames_in(buf):
    """Complete valid frames at the start of buf: (list of (seq, type, payload), rest).
    Stops after an END frame, so that the text reply behind it stays in rest."""
    out, i = [], 0
    while i < len(buf):
        n = buf[i]
        if 6 <= n <= 64 and i + n <= len(buf) and buf[i + n - 1] == 0x7E and \
                crc16(buf[i:i + n - 3]) == (buf[i + n - 3] << 8 | buf[i + n - 2]):
            out.append((buf[i + 1], buf[i + 2], buf[i + 3:i + n - 3]))
            i += n
            if buf[i - n + 2] == 0x03:
                break  # END: what follows is text (the run's "ok"), not line noise
        elif 6 <= n <= 64 and i + n > len(buf):
            break  # maybe incomplete
        else:
            i += 1
    return out, buf[i:]


def machine(duration, resend_at=(), frames_mode=False, nak_at=None, garbage=None, wake=False):
    """Answer the firmware for up to `duration` s or until its run ends: ok per G-code
    line (Resend: n at the given N, then ok; lines with an unexpected N get ok only), or
    an ACK per in-order frame (one NAK at frame nak_at; garbage bytes after frame 8).
    Returns (points, terminal line or None)."""
    global rxbuf
    end, pts, term, expect, seq, sent_nak, sent_garbage = time.time() + duration, 0, None, 1, 0, False, False
    pending = list(resend_at)
    last_wake = time.time()
    while time.time() < end and term is None:
        read_some(0.02)
        if wake and time.time() - last_wake > 0.05:
            os.write(master, b"?")  # wakes the WFI loop (see docs/SOAK.md: TIMER0 finding)
            last_wake = time.time()
        if frames_mode:
            fr, rxbuf = frames_in(rxbuf)
            for s, typ, pl in fr:
                if s != seq & 0xFF:
                    continue
                if nak_at is not None and seq == nak_at and not sent_nak:
                    sent_nak = True
                    os.write(master, frame(seq, 0x82))
                    continue
                seq += 1
                pts += typ == 0x02
                os.write(master, frame(seq, 0x81))
                if garbage is not None and seq == 8 and not sent_garbage:
                    sent_garbage = True
                    os.write(master, garbage)
                if typ == 0x03:
                    frames_mode = False
            continue
        while b"\n" in rxbuf:
            line, rxbuf = rxbuf.split(b"\n", 1)
            if line.startswith(b"N"):
                try:
                    n = int(line[1:line.index(b" ")])
                except ValueError:
                    n = -1
                if n == expect and pending and n == pending[0]:
                    pending.pop(0)
                    os.write(master, b"Resend: %d\nok\n" % n)
                elif n == expect:
                    expect += 1
                    pts += 1
                    os.write(master, b"ok\n")
                else:
                    os.write(master, b"ok\n")
            elif line.startswith((b"G", b"M")):
                pts += 1
                os.write(master, b"ok\n")
            elif line == b"ok" or line.startswith(b"error:"):
                term = line
                break
    return pts, term


# 1. sync: the firmware never speaks first; repeat $I until it answers
got, t0 = b"", time.time()
while time.time() - t0 < 10 and b"ok\n" not in got:
    os.write(master, b"$I\n")
    got += read_until(b"ok\n", 0.2)
check(b"[VER:canalpath" in got and b"ok\n" in got, "A: $I answered: %r" % got.split(b"\n")[0])
time.sleep(0.2)
read_some(0.1)
rxbuf = b""
# 2. unknown command -> error line
os.write(master, b"NOSUCH\n")
r = read_until(b"\n", 2)
check(r.startswith(b"error:"), "A: unknown command -> %r" % r.strip())
# 3. a pipelined burst larger than the RX ring and the UART: back-pressure, no loss
n = 40
os.write(master, b"$I\n" * n)
r, end = b"", time.time() + 10
while time.time() < end and r.count(b"ok\n") < n:
    r += read_until(b"ok\n", 0.2)
check(r.count(b"ok\n") == n, "A: %d pipelined $I -> %d ok" % (n, r.count(b"ok\n")))


def send_job(lines):
    okc = 0
    for line in lines:
        os.write(master, line + b"\n")
        okc += read_until(b"\n", 5).endswith(b"ok\n")
    return okc


# 4. checksummed CIRCLES job with a tool; this machine requests two Resends
job = [b"CURVE ARC 0 0 3 0 360", b"RADIUS COS 5.5 10.5 2", b"TOOL BALL 1", b"CIRCLES 24 -20 10",
       b"TOL 20", b"FORMAT GCODE", b"CHECKSUM ON", b"FEED 600", b"SAFE 40"]
okc = send_job(job)
os.write(master, b"RUN\n")
pts, term = machine(120, resend_at=(40, 300), wake=True)
check(okc == len(job) and term == b"ok" and pts > 50,
      "A: CIRCLES + tool + CHECKSUM, 2 Resends: %d lines, RUN -> %r" % (pts, term))
# 5. FRAMES with one NAK and the frame corpus as host garbage mid-run
garb = b"".join(open(os.path.join("tests/corpus/frame", f), "rb").read()
                for f in sorted(os.listdir("tests/corpus/frame")))
job = [b"CURVE BEZIER 0 0 10 20 30 -20 40 0", b"RADIUS CUBIC 3 4 4 3", b"TOOL BALL 1 CENTRE",
       b"LINES 4 0 80", b"STEPS 200", b"FORMAT FRAMES", b"CHECKSUM OFF"]
okc = send_job(job)
os.write(master, b"RUN\n")
pts, term = machine(120, frames_mode=True, nak_at=30, garbage=garb, wake=True)
if term is None:
    r = read_until(b"\n", 5).strip()
    term = r.split(b"\n")[-1] if r else None
check(okc == len(job) and pts > 100,
      "A: FRAMES BEZIER + tool, 1 NAK, %d bytes of frame corpus as garbage: %d points, then %r"
      % (len(garb), pts, term))
sync()
# 6. fuzz corpus replay (tests/corpus/cmd): pieces ending at '\n', a machine between them
nrep = nsync = 0
for name in sorted(os.listdir("tests/corpus/cmd")):
    data = open(os.path.join("tests/corpus/cmd", name), "rb").read()
    pieces, i = [], 0
    while i < len(data):
        j = data.find(b"\n", i)
        j = len(data) if j < 0 else j + 1
        pieces.append(data[i:min(j, i + 96)])
        i = min(j, i + 96)
    for p in pieces:
        os.write(master, p)
        fm = b"FRAMES" in data and b"RUN" in p or b"RESUME" in p and b"FRAMES" in data
        machine(0.5 if b"RUN" in p or b"RESUME" in p else 0.05, frames_mode=fm, wake=True)
    nrep += 1
    nsync += sync()
check(nsync == nrep, "A: fuzz corpus cmd: %d inputs replayed, $I answered after each: %d" % (nrep, nsync))
# 7. number corpus: the text part of each input as a command argument
nnum = 0
for name in sorted(os.listdir("tests/corpus/num")):
    txt = open(os.path.join("tests/corpus/num", name), "rb").read()[5:].split(b"\n")[0][:40]
    for cmd in (b"TOL ", b"CURVE ARC 0 0 "):
        os.write(master, cmd + txt + (b" 0 90\n" if cmd.startswith(b"CURVE") else b"\n"))
        nnum += 1
r, end = b"", time.time() + 20
while time.time() < end and r.count(b"\n") < nnum:
    read_some(0.05)
    r, rxbuf = r + rxbuf, b""
check(sync(), "A: number corpus: %d lines sent, %d replies, $I answered after" % (nnum, r.count(b"\n")))
# 8. the painted stack of this session
peak_a = None
try:
    peak_a, s = painted_peak(mon_path, sstack, size, os.path.join(work, "stack_a.bin"))
    s.sendall(b"quit\n")
except (OSError, ValueError) as e:
    print("  monitor: %s" % e)
check(peak_a is not None and 0 < peak_a <= size, "A: painted stack peak: %s of %d bytes" % (peak_a, size))
try:
    qemu.wait(timeout=5)
except subprocess.TimeoutExpired:
    qemu.kill()
os.close(slave)
os.close(master)

# ---- part B: judged host_sim sessions, this script as the QEMU wrapper
PAPER = ["CURVE ARC 0 0 3 0 360", "RADIUS COS 5.5 10.5 2"]
jobs_b = [
    ("paper_frames_drop", PAPER + ["LINES 4 -25 10", "STEPS 300", "FORMAT FRAMES"], "drop@20011"),
    ("circles_frames_flip", PAPER + ["CIRCLES 30 -25 10", "STEPS 60", "FORMAT FRAMES"], "flip@30001"),
    ("patch_frames_dup", PAPER + ["CIRCLES 22 -25 10 PATCH", "STEPS 100", "FORMAT FRAMES"], "dup@15003"),
    ("ellipse_frames_hangup", ["CURVE ELLIPSE 0 0 4 3 0 300", "RADIUS LINEAR 1 1.5", "LINES 4 -40 40",
                               "STEPS 300", "FORMAT FRAMES"], "hangup@20001"),
    ("bezier_tool_cs_hangup", ["CURVE BEZIER 0 0 10 20 30 -20 40 0", "RADIUS CUBIC 3 4 4 3",
                               "TOOL BALL 1", "LINES 4 0 80", "STEPS 300", "FEED 900", "SAFE 40",
                               "FORMAT GCODE", "CHECKSUM ON"], "hangup@30001"),
    ("boss_centre_cs", ["CURVE ARC 0 0 25 0 360", "RADIUS COS 1 4 3", "TOOL BALL 2 CENTRE",
                        "LINES 10 0 85", "TOL 5", "FEED 1200", "SAFE 40", "FORMAT GCODE",
                        "CHECKSUM ON"], None),
]
peaks_file = os.path.join(work, "peaks_b.txt")
if os.path.exists(peaks_file):
    os.unlink(peaks_file)
env = dict(os.environ, M4F_STACK_SOAK_WRAP=peaks_file, M4F_STACK_SOAK_SSTACK="%x" % sstack,
           M4F_STACK_SOAK_SIZE=str(size), QEMU=QEMU)
me = os.path.abspath(sys.argv[0])
hs = os.path.join(B, "host", "host_sim")
for name, lines, fault in jobs_b:
    jf = os.path.join(work, name + ".job")
    with open(jf, "w") as f:
        for l in lines + ["RUN"]:
            f.write("%s   #! expect ok\n" % l)
    cmd = [hs, "--target", "qemu", "--qemu", me, "--fw", elf, "--timeout-ms", "20000", "--job", jf]
    if fault:
        cmd += ["--fault", fault] + (["--resume"] if fault.startswith("hangup") else [])
    with open(os.path.join(work, name + ".out"), "w") as o:
        rc = subprocess.call(["timeout", "600"] + cmd, stdout=o, stderr=subprocess.STDOUT, env=env)
    outp = open(os.path.join(work, name + ".out")).read()
    pts = [l.split()[-1] for l in outp.splitlines() if l.startswith("  points ")]
    check(rc == 0, "B: %s (%s): host_sim exit %d, %s points judged, %s" %
          (name, fault or "no fault", rc, pts[-1] if pts else "?", outp.strip().splitlines()[-1]))
peaks_b = []
if os.path.exists(peaks_file):
    peaks_b = [int(x) for x in open(peaks_file).read().split() if x.isdigit()]
check(len(peaks_b) >= len(jobs_b), "B: painted stack read after each QEMU instance: %s" % peaks_b)

# ---- result: painted (max) vs static vs region
static = None
for l in open(static_file):
    if l.startswith("worst case:"):
        static = int(l.split()[2])
painted = max([p for p in [peak_a] + peaks_b if p is not None] or [0])
check(0 < painted <= size, "painted stack peak %d bytes <= stack region %d" % (painted, size))
check(static is not None and static <= size, "static worst path (make stack) %s bytes <= stack region %d"
      % (static, size))
print("stack-soak: painted %d B (part A %s, part B max %s), static worst path %s B, region %d B"
      % (painted, peak_a, max(peaks_b) if peaks_b else None, static, size))
print("stack-soak: %d passed, %d failed" % (passed, failed))
sys.exit(failed != 0)
