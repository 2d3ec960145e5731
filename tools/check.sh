#!/bin/sh
# check.sh - run every test runner and guard of `make check`, then print ONE
# closing line "N passed, N failed" (the sum of every "<word>: N passed, N failed"
# line). A step that exits non-zero without such a line counts as 1 failed.
# SPDX-License-Identifier: MIT
MAKE=${MAKE:-make}
STEPS=${CHECK_STEPS:-"unit unit-double unit-asan fuzz-check guard-docs guard-readme guard-warn guard-alloc guard-double guard-stack guard-budget guard-selftest m4f-unit m4f-pty sim-native sim-qemu sim-robust sim-run-native sim-run-qemu sim-baud sim-faults sim-resume sim-identical sim-rs274 sim-pyserial"}
LOG=${BUILD:-build}/check.log
mkdir -p "$(dirname "$LOG")"
: > "$LOG"
pass=0; fail=0
for s in $STEPS; do
    echo "== $s"
    out=$($MAKE --no-print-directory "$s" 2>&1); rc=$?
    printf '%s\n' "$out"
    printf '== %s (rc=%s)\n%s\n' "$s" "$rc" "$out" >> "$LOG"
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
