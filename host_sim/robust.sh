#!/bin/sh
# robust.sh - sim-robust: host_sim against every misbehaving fw_fake mode.
# SPDX-License-Identifier: MIT
#
# Each bad mode must make host_sim fail CLEANLY: exit status 1, a message naming
# the cause, within the per-reply timeout plus a margin, and with the fake
# firmware killed and reaped (its pid is gone afterwards). Each such expected
# failure is one PASSED check. The --good mode is the positive control (exit 0).
# A SIGINT to host_sim must stop it (exit 130) and kill its firmware too.
# Prints "robust: N passed, N failed"; exits non-zero on any failure.
# Env: BUILD (build), ROBUST_TIMEOUT_MS (3000), ROBUST_MARGIN_MS (5000).
# Timeouts (the rule of mk/m4f.mk: every wall-clock limit >= 5x the unloaded run time
# of what it bounds; measured 2026-11-26). T is the per-reply timeout under test: the
# good sessions need their answers within it, the slowest is lossy-start (its second $I
# answered about 530 ms in), so T = 3000 ms >= 5 x 530 ms (was 1000 ms: 1.9x). T + M
# bounds a whole case: the silent modes end at T + 20 ms, stubborn (no T wait: host_sim's
# hang-up wait and 500 ms SIGTERM -> SIGKILL grace) at 1560 ms, so M = 5000 ms:
# T + M = 8000 ms >= 5 x 1560 ms (was 2500 ms: 1.6x). The outer `timeout 30` only
# guards against a hung host_sim (>= 5 x the 3020 ms of the silent cases).
B=${BUILD:-build}/host
HS=$B/host_sim
FAKE=$B/fw_fake
JOB=tests/jobs/handshake.job
T=${ROBUST_TIMEOUT_MS:-3000}
M=${ROBUST_MARGIN_MS:-5000}
OUT=$B/robust
mkdir -p "$OUT"
pass=0; fail=0

now_ms() { echo $(($(date +%s%N) / 1000000)); }

# case NAME WANT_RC CAUSE_REGEX FAKE_ARGS...
run_case() {
    name=$1; want=$2; cause=$3; shift 3
    pidf=$OUT/$name.pid; rm -f "$pidf"
    t0=$(now_ms)
    # the outer timeout only guards this script against a hung host_sim (rc 124)
    timeout 30 "$HS" --timeout-ms "$T" --job "$JOB" --log "$OUT/$name.log" \
        --cmd "$FAKE" "$@" --pidfile "$pidf" > "$OUT/$name.out" 2>&1
    rc=$?
    el=$(($(now_ms) - t0))
    why=""
    [ "$rc" -eq "$want" ] || why="$why exit $rc, want $want;"
    [ "$el" -le $((T + M)) ] || why="$why took $el ms > $((T + M)) ms;"
    grep -Eq "$cause" "$OUT/$name.out" || why="$why no message matching /$cause/;"
    tail -n 1 "$OUT/$name.out" | grep -Eq '^sim: [0-9]+ passed, [0-9]+ failed$' ||
        why="$why no closing sim: line;"
    if [ -s "$pidf" ] && kill -0 "$(cat "$pidf")" 2>/dev/null; then
        why="$why fake firmware still running;"
        kill -9 "$(cat "$pidf")" 2>/dev/null
    fi
    if [ -z "$why" ]; then
        pass=$((pass + 1))
        printf '  PASS %-12s exit %d in %5d ms  (%s)\n' "$name" "$rc" "$el" \
            "$(grep -Eo "$cause" "$OUT/$name.out" | head -n 1)"
    else
        fail=$((fail + 1))
        printf '  FAIL %-12s%s\n' "$name" "$why"
        sed 's/^/      | /' "$OUT/$name.out" | tail -n 15
    fi
}

run_case good       0 'sim: [0-9]+ passed, 0 failed'           --good
run_case die        1 'firmware process exited'                 --die
run_case silent     1 'no reply within the timeout'             --silent
run_case flood      1 'floods'                                  --flood
run_case longline   1 'longer than the limit'                   --longline
run_case slow       1 'no reply within the timeout'             --slow 300
run_case chatty     1 'unknown reply line'                      --chatty
run_case wrong      1 'FAIL$'                                   --wrong
run_case die-after  1 'hung up|process exited'                  --die-after 3
run_case hang-after 1 'no reply within the timeout'             --hang-after 3
run_case stubborn   1 'needed SIGKILL'                          --stubborn
# the first answer loses its first bytes: host_sim asks $I again and goes on normally
run_case lossy-start 0 'incomplete answer, [$]I again'          --lossy-start

# SIGINT: host_sim waits on a silent firmware with a long timeout; ^C must stop both.
pidf=$OUT/sigint.pid; rm -f "$pidf"
t0=$(now_ms)
"$HS" --timeout-ms 20000 --job "$JOB" --cmd "$FAKE" --silent --pidfile "$pidf" \
    > "$OUT/sigint.out" 2>&1 &
hs=$!
sleep 0.3
kill -INT "$hs"
wait "$hs"; rc=$?
el=$(($(now_ms) - t0))
why=""
[ "$rc" -eq 130 ] || why="$why exit $rc, want 130;"
[ "$el" -le $((300 + M)) ] || why="$why took $el ms;"
grep -q 'interrupted' "$OUT/sigint.out" || why="$why no 'interrupted' message;"
if [ ! -s "$pidf" ]; then
    why="$why fake never started;"
elif kill -0 "$(cat "$pidf")" 2>/dev/null; then
    why="$why fake firmware still running;"; kill -9 "$(cat "$pidf")" 2>/dev/null
fi
if [ -z "$why" ]; then
    pass=$((pass + 1)); printf '  PASS %-12s exit %d in %5d ms  (firmware reaped)\n' sigint "$rc" "$el"
else
    fail=$((fail + 1)); printf '  FAIL %-12s%s\n' sigint "$why"; sed 's/^/      | /' "$OUT/sigint.out" | tail -n 15
fi

echo "robust: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
