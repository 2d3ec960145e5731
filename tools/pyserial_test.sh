#!/bin/sh
# pyserial_test.sh - the docs/examples/run_job.py client (a real serial client,
# Debian python3-serial under /usr/bin/python3) runs a job against fw_native --pty.
# Prints "pyserial: N passed, N failed".
# SPDX-License-Identifier: MIT
BUILD=${BUILD:-build}
PY=/usr/bin/python3
dir=$(mktemp -d)
link=$dir/ttyCP
pass=0; fail=0
if ! $PY -c "import serial" 2>/dev/null; then
    echo "pyserial: python3-serial missing for $PY (apt-get install python3-serial)"
    echo "pyserial: 0 passed, 1 failed"; rm -rf "$dir"; exit 1
fi
"$BUILD/host/fw_native" --pty "$link" 2>"$dir/fw.log" &
fw=$!
i=0; while [ ! -e "$link" ] && [ $i -lt 50 ]; do sleep 0.1; i=$((i+1)); done
# timeout 60: the client runs 0.4 s unloaded (2026-11-26; the rule of mk/m4f.mk: >= 5x)
out=$(timeout 60 $PY docs/examples/run_job.py "$link" tests/jobs/pyserial.job "$dir/out.ngc" 2>&1); rc=$?
echo "$out" | sed 's/^/  /'
kill $fw 2>/dev/null; wait $fw 2>/dev/null
if [ $rc -eq 0 ]; then pass=$((pass+1)); echo "  PASS run_job.py exit 0"; else fail=$((fail+1)); echo "  FAIL run_job.py exit $rc"; fi
n=$(grep -c '^G1 ' "$dir/out.ngc" 2>/dev/null || echo 0)
p=$(echo "$out" | sed -n 's/^pyserial: \([0-9]*\) points.*/\1/p')
if [ -n "$p" ] && [ "$n" = "$p" ] && [ "$n" -gt 100 ]; then pass=$((pass+1)); echo "  PASS $n G1 lines saved = points reported"
else fail=$((fail+1)); echo "  FAIL saved $n G1 lines, reported '$p'"; fi
rm -rf "$dir"
echo "pyserial: $pass passed, $fail failed"
[ $fail -eq 0 ]
