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
# STRAIGHT_FEED(x, y, z, a, b, c) vs the received points; with TOOLAXIS AC (a CSV with the
# normals host_sim recovered from the A/C words) also the tool axis of a and c,
# (sin a sin c, -sin a cos c, cos a) (firmware/proto/toolaxis.h), against that normal
res=$(awk -v csv="$csv" '
    BEGIN { n = 0; FS = ","; pi = atan2(0, -1)
            while ((getline l < csv) > 0) { if (l ~ /^line/) { hasn = l ~ /nx/; continue }
                split(l, f, ","); n++; X[n]=f[3]; Y[n]=f[4]; Z[n]=f[5]; NX[n]=f[6]; NY[n]=f[7]; NZ[n]=f[8] } }
    /STRAIGHT_FEED\(/ { s = $0; sub(/.*STRAIGHT_FEED\(/, "", s); sub(/\).*/, "", s); split(s, v, ", *"); m++
          d = (v[1]-X[m])^2 + (v[2]-Y[m])^2 + (v[3]-Z[m])^2; if (d > worst) worst = d
          if (v[3] > fzmax || m == 1) fzmax = v[3]
          if (hasn && (v[4] != 0 || v[6] != 0)) { A = v[4] * pi / 180; C = v[6] * pi / 180; axes++
              ax = sin(A) * sin(C); ay = -sin(A) * cos(C); az = cos(A)
              cx = ay * NZ[m] - az * NY[m]; cy = az * NX[m] - ax * NZ[m]; cz = ax * NY[m] - ay * NX[m]
              e = atan2(sqrt(cx*cx + cy*cy + cz*cz), ax*NX[m] + ay*NY[m] + az*NZ[m]); if (e > aworst) aworst = e } }
    /STRAIGHT_TRAVERSE\(/ { s = $0; sub(/.*STRAIGHT_TRAVERSE\(/, "", s); sub(/\).*/, "", s); split(s, v, ", *")
          t++; TZ[t] = v[3]; if (t == 1 || v[3] > safe) safe = v[3] }
    END { low = 0; for (i = 1; i <= t; i++) if (TZ[i] != safe) low++
          printf "%d %d %.3g %d %.3g %d %d %s %s\n", m, n, sqrt(worst) * 1000, axes, aworst * 180 / pi,
                 t, low, safe, fzmax }' FS='\n' "$out")
feeds=$(echo "$res" | cut -d' ' -f1); pts=$(echo "$res" | cut -d' ' -f2); worst=$(echo "$res" | cut -d' ' -f3)
axes=$(echo "$res" | cut -d' ' -f4); aworst=$(echo "$res" | cut -d' ' -f5)
trav=$(echo "$res" | cut -d' ' -f6); low=$(echo "$res" | cut -d' ' -f7)
safe=$(echo "$res" | cut -d' ' -f8); fzmax=$(echo "$res" | cut -d' ' -f9)
if [ "$feeds" = "$pts" ] && [ "$pts" -gt 0 ]; then pass=$((pass+1)); echo "  PASS $feeds STRAIGHT_FEED for $pts received points"
else fail=$((fail+1)); echo "  FAIL $feeds STRAIGHT_FEED for $pts received points"; fi
if [ "$feeds" -gt 0 ] && awk -v w="$worst" 'BEGIN { exit !(w <= 0.1) }'; then pass=$((pass+1)); echo "  PASS max |STRAIGHT_FEED - point| = $worst um (limit 0.1 um)"
else fail=$((fail+1)); echo "  FAIL max |STRAIGHT_FEED - point| = $worst um (limit 0.1 um)"; fi
# the program's safe moves: every rapid (STRAIGHT_TRAVERSE) at the safe height, which is
# above every feed move (3 rapids per RUN: up, above the first point, the retract)
if [ "$trav" -ge 3 ] && [ "$low" -eq 0 ] && awk -v s="$safe" -v f="$fzmax" 'BEGIN { exit !(s > f) }'; then
    pass=$((pass+1)); echo "  PASS $trav STRAIGHT_TRAVERSE, all at the safe height Z $safe > every feed move (max Z $fzmax)"
else fail=$((fail+1)); echo "  FAIL $trav STRAIGHT_TRAVERSE, $low below the safe height Z $safe (feed moves up to Z $fzmax)"; fi
if [ "$axes" -gt 0 ]; then
    if [ "$axes" = "$pts" ] && awk -v w="$aworst" 'BEGIN { exit !(w <= 0.01) }'; then pass=$((pass+1))
        echo "  PASS $axes STRAIGHT_FEED a, c: max angle to the received axis $aworst deg (limit 0.01 deg)"
    else fail=$((fail+1)); echo "  FAIL $axes STRAIGHT_FEED a, c for $pts points: max angle $aworst deg (limit 0.01 deg)"; fi
fi
rm -f "$out"
echo "rs274: $pass passed, $fail failed"
[ $fail -eq 0 ]
