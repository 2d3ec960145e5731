#!/bin/sh
# rs274_check.sh - conformance of a streamed G-code program with LinuxCNC's
# standalone interpreter (Debian linuxcnc-uspace): rs274 -g must run it with no
# error, and its STRAIGHT_FEED calls must equal the points host_sim received
# (CSV line,index,x,y,z,...) to 0.1 um, one for one, in order.
# Usage: rs274_check.sh PROGRAM.ngc POINTS.csv   Prints "rs274: N passed, N failed".
# SPDX-License-Identifier: MIT
ngc=$1; csv=$2
out=${TMPDIR:-/tmp}/rs274_check.$$
if ! command -v rs274 >/dev/null 2>&1; then
    echo "rs274: not installed (Debian package linuxcnc-uspace); run .ci/run or apt-get install linuxcnc-uspace"
    echo "rs274: 0 passed, 1 failed"; exit 1
fi
pass=0; fail=0
# timeout 120: sim-rs274 runs 0.4 s unloaded (2026-11-26; the rule of mk/m4f.mk: >= 5x)
timeout 120 rs274 -g "$ngc" > "$out" 2>&1; rc=$?
if [ $rc -eq 0 ] && ! grep -qi "error" "$out"; then pass=$((pass+1)); echo "  PASS rs274 -g ran the program, 0 errors"
else fail=$((fail+1)); echo "  FAIL rs274 -g exit $rc:"; grep -v "^ *[0-9]* N\\.\\.\\.\\.\\." "$out" | head -5; fi
# STRAIGHT_FEED(x, y, z, a, b, c) vs the received points
res=$(awk -v csv="$csv" '
    BEGIN { n = 0; FS = ","
            while ((getline l < csv) > 0) { if (l ~ /^line/) continue; split(l, f, ","); n++; X[n]=f[3]; Y[n]=f[4]; Z[n]=f[5] } }
    /STRAIGHT_FEED\(/ { s = $0; sub(/.*STRAIGHT_FEED\(/, "", s); sub(/\).*/, "", s); split(s, v, ", *"); m++
          d = (v[1]-X[m])^2 + (v[2]-Y[m])^2 + (v[3]-Z[m])^2; if (d > worst) worst = d }
    END { printf "%d %d %.3g\n", m, n, sqrt(worst) * 1000 }' FS='\n' "$out")
feeds=$(echo "$res" | cut -d' ' -f1); pts=$(echo "$res" | cut -d' ' -f2); worst=$(echo "$res" | cut -d' ' -f3)
if [ "$feeds" = "$pts" ] && [ "$pts" -gt 0 ]; then pass=$((pass+1)); echo "  PASS $feeds STRAIGHT_FEED for $pts received points"
else fail=$((fail+1)); echo "  FAIL $feeds STRAIGHT_FEED for $pts received points"; fi
if [ "$feeds" -gt 0 ] && awk -v w="$worst" 'BEGIN { exit !(w <= 0.1) }'; then pass=$((pass+1)); echo "  PASS max |STRAIGHT_FEED - point| = $worst um (limit 0.1 um)"
else fail=$((fail+1)); echo "  FAIL max |STRAIGHT_FEED - point| = $worst um (limit 0.1 um)"; fi
rm -f "$out"
echo "rs274: $pass passed, $fail failed"
[ $fail -eq 0 ]
