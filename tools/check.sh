#!/bin/sh
# check.sh - run every test runner and guard of `make check`, then print ONE
# closing line "N passed, N failed" (the sum of every "<word>: N passed, N failed"
# line). A step that exits non-zero without such a line counts as 1 failed.
#
# Two lanes first, then one: the pure-CPU steps (no pty, no wall-clock limit) run as two
# concurrent lanes, LANE_A in the foreground and LANE_B in the background, each serial
# within itself and each building only its own tree (build/host + build/m4f; build/hostd,
# build/asan, build/fuzz), so the machine's two cores are both used. Then every step that
# talks over a pty or runs QEMU against a clock (STEPS) runs alone, on an otherwise idle
# machine, which is what their timeouts were measured on. The output is printed in lane
# order, each step whole. CHECK_STEPS=<steps> runs just those, one after another.
# SPDX-License-Identifier: MIT
MAKE=${MAKE:-make}
LANE_A="unit guard-docs guard-readme guard-warn guard-fnlen guard-layers guard-alloc guard-double guard-stack guard-budget guard-images guard-selftest m4f-unit"
LANE_B="unit-double unit-asan fuzz-check"
STEPS="m4f-pty pollgap sim-native sim-qemu sim-robust sim-machine sim-run-native sim-run-qemu sim-baud sim-faults sim-resume sim-identical sim-models sim-machines example-model sim-rs274 sim-pyserial py-test soak-quick stack-soak sim-asan"
if [ -n "${CHECK_STEPS:-}" ]; then LANE_A=""; LANE_B=""; STEPS=$CHECK_STEPS; fi
LOG=${BUILD:-build}/check.log
mkdir -p "$(dirname "$LOG")"
: > "$LOG"
pass=0; fail=0
# Preflight: every tool the steps need, with the Debian package that provides it.
# A missing one is one failed check here (and its steps fail with their own message).
need() { # description, test command, package
    if sh -c "$2" >/dev/null 2>&1; then pass=$((pass + 1));
    else fail=$((fail + 1)); echo "check: missing $1: apt-get install $3  (or: bash .ci/run)"; fi
}
if [ -z "${CHECK_STEPS:-}" ]; then
    echo "== prerequisites"
    need "arm-none-eabi-gcc" "command -v arm-none-eabi-gcc" gcc-arm-none-eabi
    need "newlib for arm-none-eabi" "test -f \"\$(arm-none-eabi-gcc -print-file-name=nano.specs)\"" libnewlib-arm-none-eabi
    need "qemu-system-arm" "command -v qemu-system-arm" qemu-system-arm
    need "clang" "command -v clang" clang
    need "libFuzzer/ASan runtime" "test -f \"\$(clang -print-file-name=libclang_rt.fuzzer-x86_64.a)\"" libclang-rt-14-dev
    need "rs274 (LinuxCNC interpreter)" "command -v rs274" linuxcnc-uspace
    need "pyserial for /usr/bin/python3" "/usr/bin/python3 -c 'import serial'" python3-serial
    need "pytest for /usr/bin/python3" "/usr/bin/python3 -c 'import pytest'" python3-pytest
    need "venv and pip for /usr/bin/python3" "/usr/bin/python3 -c 'import venv, ensurepip'" python3-venv
fi
LANES=${BUILD:-build}/check-lanes
# run_step <step>: run it, keep its output, wall time and exit status in $LANES/<step>.*
run_step() {
    step_t0=$(date +%s)
    $MAKE --no-print-directory "$1" > "$LANES/$1.out" 2>&1
    echo $? > "$LANES/$1.rc"
    echo $(($(date +%s) - step_t0)) > "$LANES/$1.s"
}
# count_step <step>: print what run_step kept and add it to the totals
count_step() {
    s=$1
    out=$(cat "$LANES/$s.out"); rc=$(cat "$LANES/$s.rc" 2>/dev/null || echo 1)
    echo "== $s"
    printf '%s\n' "$out"
    echo "== $s took $(cat "$LANES/$s.s" 2>/dev/null) s"
    printf '== %s (rc=%s, %s s)\n%s\n' "$s" "$rc" "$(cat "$LANES/$s.s" 2>/dev/null)" "$out" >> "$LOG"
    sums=$(printf '%s\n' "$out" | sed -n 's/^[A-Za-z0-9_.-]*: \([0-9][0-9]*\) passed, \([0-9][0-9]*\) failed$/\1 \2/p')
    if [ -z "$sums" ]; then
        if [ "$rc" -eq 0 ]; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "check: step $s failed (rc=$rc)"; fi
    else
        p=$(printf '%s\n' "$sums" | awk '{s+=$1} END{print s+0}')
        f=$(printf '%s\n' "$sums" | awk '{s+=$2} END{print s+0}')
        if [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then f=1; echo "check: step $s exited $rc"; fi
        pass=$((pass + p)); fail=$((fail + f))
    fi
}
rm -rf "$LANES" && mkdir -p "$LANES"
if [ -n "$LANE_B" ]; then
    echo "== lanes: [$LANE_A] beside [$LANE_B]"
    lanes_t0=$(date +%s)
    (for s in $LANE_B; do run_step "$s"; done) &
    lane_b=$!
    for s in $LANE_A; do run_step "$s"; done
    wait "$lane_b"
    echo "== lanes took $(($(date +%s) - lanes_t0)) s"
    for s in $LANE_A $LANE_B; do count_step "$s"; done
fi
for s in $STEPS; do
    run_step "$s"
    count_step "$s"
done
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
