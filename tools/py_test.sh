#!/bin/sh
# py_test.sh - the Python host library's tests (host_sim/python/tests, pytest) against
# fw_native on a pty and fw.elf under QEMU. Parses pytest's summary into the line
# "py: N passed, N failed" of make check (errors count as failed; a non-zero exit of
# pytest without a failure in its summary counts as 1 failed). Exit status: pytest's.
# SPDX-License-Identifier: MIT
BUILD=${BUILD:-build}
PY=/usr/bin/python3
if ! $PY -c "import pytest" 2>/dev/null; then
    echo "py: pytest missing for $PY (apt-get install python3-pytest)"
    echo "py: 0 passed, 1 failed"; exit 1
fi
log=$BUILD/py-test.log
mkdir -p "$BUILD"
# the whole suite runs in about 30 s unloaded (2026-11-26); timeout 900 is a hang guard
BUILD=$(cd "$BUILD" && pwd) PYTHONDONTWRITEBYTECODE=1 timeout 900 $PY -m pytest -q -p no:cacheprovider \
    -o console_output_style=classic host_sim/python/tests > "$log" 2>&1
rc=$?
grep -E '^(FAILED|ERROR) |passed|failed|error' "$log" | tail -n 40 | sed 's/^/  /'
sum=$(tail -n 1 "$log")
p=$(echo "$sum" | sed -n 's/.* \([0-9][0-9]*\) passed.*/\1/p; s/^\([0-9][0-9]*\) passed.*/\1/p' | head -n 1)
f=$(echo "$sum" | sed -n 's/.*\b\([0-9][0-9]*\) failed.*/\1/p' | head -n 1)
e=$(echo "$sum" | sed -n 's/.*\b\([0-9][0-9]*\) errors\{0,1\}\b.*/\1/p' | head -n 1)
p=${p:-0}; f=$(( ${f:-0} + ${e:-0} ))
if [ $rc -ne 0 ] && [ $f -eq 0 ]; then f=1; echo "  pytest exited $rc (see $log)"; fi
echo "py: $p passed, $f failed"
exit $rc
