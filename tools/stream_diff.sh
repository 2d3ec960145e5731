#!/bin/sh
# stream_diff.sh - the differential check of a refactoring: the firmware of two trees
# must answer and stream byte for byte the same.
# SPDX-License-Identifier: MIT
#
# Usage: sh tools/stream_diff.sh BASE_TREE [NEW_TREE]   (NEW_TREE defaults to .)
#        make stream-diff BASE=<git ref>                (checks the ref out in build/)
# Two comparisons, each one line, then "stream-diff: N passed, N failed":
#   replay   tools/replay.c built against each tree's firmware (in-memory HAL, scripted
#            machine, clock that advances only when the engine idles): every session of
#            tests/corpus/cmd/ and every tests/jobs/*.job (GCODE runs answered "ok" per line,
#            FRAMES runs unanswered to their link error); transcripts compared.
#   host_sim each tree's fw_native driven by NEW_TREE's host_sim over a pty: every job of
#            tests/jobs/ (raw RUN stream and judged CSV compared), the fault sessions of
#            sim-faults and hang-up + RESUME sessions (judged CSV compared: their raw bytes
#            depend on pty timing).
# Only the sessions that BASE_TREE has too are compared: a session file new in NEW_TREE
# exercises new behaviour (e.g. a new command, which the base answers error:1) and has no
# base to equal; each comparison line names how many such new files it left out.
# Needs: cc, make. Exit 1 when anything differs.
BASE=$1
NEW=${2:-.}
[ -n "$BASE" ] || { echo "usage: stream_diff.sh BASE_TREE [NEW_TREE]" >&2; exit 2; }
BASE=$(cd "$BASE" && pwd) || exit 2
NEW=$(cd "$NEW" && pwd) || exit 2
HERE=$(cd "$(dirname "$0")" && pwd)
OUT=$NEW/build/stream_diff
rm -rf "$OUT"; mkdir -p "$OUT/base" "$OUT/new"
pass=0; fail=0
ok() { pass=$((pass + 1)); echo "  PASS $*"; }
ko() { fail=$((fail + 1)); echo "  FAIL $*"; }

# replay binary of a tree: its firmware sources (any depth) + its in-memory HAL
build_replay() { # tree out
    incs=$(find "$1/firmware" "$1/hal" -maxdepth 2 -type d | grep -v '/hal/' | sed 's/^/-I/')
    incs="$incs -I$1/hal -I$1/tests"
    srcs=$(find "$1/firmware" -name '*.c')
    # shellcheck disable=SC2086
    cc -std=c99 -O1 -ffp-contract=off -fno-math-errno $incs -o "$2" \
        "$HERE/replay.c" $srcs "$1/tests/hal_mem.c" -lm
}
build_replay "$BASE" "$OUT/base/replay" || { echo "stream-diff: cannot build replay of $BASE"; echo "stream-diff: 0 passed, 1 failed"; exit 1; }
build_replay "$NEW" "$OUT/new/replay" || { echo "stream-diff: cannot build replay of $NEW"; echo "stream-diff: 0 passed, 1 failed"; exit 1; }

n=0; d=0; nnew=0
for f in "$NEW"/tests/corpus/cmd/* "$NEW"/tests/jobs/*.job; do
    [ -f "$f" ] || continue
    name=$(basename "$f")
    if [ ! -f "$BASE/${f#"$NEW"/}" ]; then # new in NEW_TREE: nothing to compare with
        nnew=$((nnew + 1)); continue
    fi
    if [ "${f%.job}" != "$f" ]; then
        sed -e 's/#!.*$//' -e '/^#/d' "$f" > "$OUT/in_$name"
    else
        cp "$f" "$OUT/in_$name"
    fi
    "$OUT/base/replay" < "$OUT/in_$name" > "$OUT/base/$name.txt" 2>&1
    "$OUT/new/replay" < "$OUT/in_$name" > "$OUT/new/$name.txt" 2>&1
    n=$((n + 1))
    if ! cmp -s "$OUT/base/$name.txt" "$OUT/new/$name.txt"; then
        d=$((d + 1)); echo "    differs: $name (diff $OUT/base/$name.txt $OUT/new/$name.txt)"
    fi
done
newnote=""; [ "$nnew" -eq 0 ] || newnote=" ($nnew new session file(s) not in the base left out)"
if [ "$d" -eq 0 ]; then ok "replay: $n sessions, transcripts identical$newnote"; else ko "replay: $d of $n sessions differ$newnote"; fi

# host_sim sessions against each tree's native firmware
# (each tree built into its own directory under $OUT: a build running in the tree is not disturbed)
make -s -C "$BASE" BUILD="$OUT/base/build" "$OUT/base/build/host/fw_native" >/dev/null 2>&1 ||
    ko "host_sim: cannot build $BASE fw_native"
make -s -C "$NEW" BUILD="$OUT/new/build" "$OUT/new/build/host/fw_native" "$OUT/new/build/host/host_sim" \
    >/dev/null 2>&1 || ko "host_sim: cannot build $NEW fw_native/host_sim"
HS=$OUT/new/build/host/host_sim
run() { # tree-tag name args...
    t=$1; name=$2; shift 2
    fw=$OUT/$t/build/host/fw_native
    # native sessions of a few seconds at most: 600 s and 20 s per reply are hang guards
    # (the rule of mk/m4f.mk: >= 5x the unloaded time)
    (cd "$NEW" && timeout 600 "$HS" --target native --fw "$fw" --timeout-ms 20000 \
        --raw "$OUT/$t/$name.raw" --csv "$OUT/$t/$name.csv" "$@") > "$OUT/$t/$name.out" 2>&1
}
n=0; d=0
sessions() { # emits: name|args
    for f in "$NEW"/tests/jobs/*.job; do
        j=$(basename "$f" .job)
        case $j in pyserial|handshake) continue ;; esac
        [ -f "$BASE/tests/jobs/$j.job" ] || continue # new in NEW_TREE (the replay's note)
        echo "$j|--job tests/jobs/$j.job"
    done
    for f in flip@5 drop@1000 flip@5003 dup@20007 drop@77777; do
        echo "frames_$f|--job tests/jobs/paper_frames.job --fault $f"
    done
    for f in flip@1000 drop@5003 dup@4122 drop@4122; do
        echo "gcode_cs_$f|--job tests/jobs/paper_gcode_cs.job --fault $f"
    done
    echo "resume_frames|--job tests/jobs/paper_frames.job --fault hangup@60001 --resume"
    echo "resume_gcode_cs|--job tests/jobs/paper_gcode_cs.job --fault hangup@60001 --resume"
}
sessions > "$OUT/sessions"
while IFS='|' read -r name args; do
    # shellcheck disable=SC2086
    run base "$name" $args; rb=$?
    # shellcheck disable=SC2086
    run new "$name" $args; rn=$?
    n=$((n + 1))
    # with faults or a hang-up the raw bytes depend on pty timing (retransmissions):
    # there the judged points (CSV) are compared; every other session byte for byte
    case $args in *--fault*) rawcmp=0 ;; *) rawcmp=1 ;; esac
    # (a clean session may still see the window sent again when host_sim stalls for the
    # retransmission time on a loaded machine: the streams are compared as sent once,
    # host_sim/raw_sent.py)
    if [ $rawcmp -eq 1 ]; then
        python3 "$NEW/host_sim/raw_sent.py" "$OUT/base/$name.raw" "$OUT/base/$name.sent" >/dev/null &&
            python3 "$NEW/host_sim/raw_sent.py" "$OUT/new/$name.raw" "$OUT/new/$name.sent" >/dev/null ||
            rawcmp=2
    fi
    if [ $rb -ne $rn ] || [ $rawcmp -eq 2 ] ||
       { [ $rawcmp -eq 1 ] && ! cmp -s "$OUT/base/$name.sent" "$OUT/new/$name.sent"; } ||
       ! cmp -s "$OUT/base/$name.csv" "$OUT/new/$name.csv"; then
        d=$((d + 1)); echo "    differs: $name (exit $rb/$rn; $OUT/{base,new}/$name.{raw,csv,out})"
    fi
done < "$OUT/sessions"
if [ "$d" -eq 0 ]; then ok "host_sim: $n sessions, raw streams and CSVs identical"; else ko "host_sim: $d of $n sessions differ"; fi

echo "stream-diff: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
