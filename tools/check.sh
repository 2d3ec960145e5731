#!/bin/sh
# check.sh - run every test runner and guard of `make check`, then print ONE
# closing line "N passed, N failed" (the sum of every "<word>: N passed, N failed"
# line). A step that exits non-zero without such a line counts as 1 failed.
# SPDX-License-Identifier: MIT
MAKE=${MAKE:-make}
STEPS=${CHECK_STEPS:-"unit unit-double unit-asan fuzz-check guard-docs guard-readme guard-warn guard-fnlen guard-layers guard-alloc guard-double guard-stack guard-budget guard-images guard-selftest m4f-unit m4f-pty pollgap sim-native sim-qemu sim-robust sim-machine sim-run-native sim-run-qemu sim-baud sim-faults sim-resume sim-identical sim-models sim-machines example-model sim-rs274 sim-pyserial py-test soak-quick stack-soak sim-asan"}
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
for s in $STEPS; do
    echo "== $s"
    t0=$(date +%s)
    out=$($MAKE --no-print-directory "$s" 2>&1); rc=$?
    t1=$(date +%s)
    printf '%s\n' "$out"
    echo "== $s took $((t1 - t0)) s"
    printf '== %s (rc=%s, %s s)\n%s\n' "$s" "$rc" "$((t1 - t0))" "$out" >> "$LOG"
    sums=$(printf '%s\n' "$out" | sed -n 's/^[A-Za-z0-9_.-]*: \([0-9][0-9]*\) passed, \([0-9][0-9]*\) failed$/\1 \2/p')
    if [ -z "$sums" ]; then
        if [ "$rc" -eq 0 ]; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "check: step $s failed (rc=$rc)"; fi
    else
        p=$(printf '%s\n' "$sums" | awk '{s+=$1} END{print s+0}')
        f=$(printf '%s\n' "$sums" | awk '{s+=$2} END{print s+0}')
        if [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then f=1; echo "check: step $s exited $rc"; fi
        pass=$((pass + p)); fail=$((fail + f))
    fi
done
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
