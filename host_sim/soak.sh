#!/bin/sh
# soak.sh - the soak run of host_sim (mk/hardening.mk: soak, soak-quick; docs/SOAK.md).
# SPDX-License-Identifier: MIT
#
# Usage: sh host_sim/soak.sh full|quick
# Many host_sim sessions, each one job with ONE fault injected into the firmware ->
# host bytes of its RUN stream at a seeded random byte index (host_sim --fault
# KIND@N, one fault per session is what host_sim supports):
#   FRAMES          drop | flip | dup   recovered by NAK / go-back-N retransmit
#   GCODE+CHECKSUM  drop | flip | dup   recovered by Resend: n
#   every format    hangup              recovered by a new firmware + RESUME k (--resume)
# Plain GCODE has no integrity check, so it only gets hang-ups. Every point of every
# session is judged by host_sim's judge (sim_check.h: surface, line, ortho, normal,
# chord, coverage); a session passes only if host_sim exits 0 (terminal reply ok,
# points intact = points - first, coverage: none missing, twice, out of order).
# Byte indexes are uniform over the whole RUN stream of the job (header, every point,
# END frame and the closing text included); its length is measured by one clean
# session per job first (those sessions are judged too and count as points).
# Plan: full = 96 native fault sessions of ~10k points (+ 8 clean: >= 1e6) + 24
# QEMU sessions of ~5k points (>= 1e5); quick = 12 native + 3 QEMU. Both are deterministic for a seed.
# Prints one line per failed session (and, with SOAK_VERBOSE=1, every session), a
# summary table, and closes with "soak: N passed, N failed" (N = sessions).
# Env: BUILD (build), QEMU (qemu-system-arm), SOAK_SEED (1), SOAK_NATIVE / SOAK_QEMU
#      (session counts, override the plan), SOAK_TN (native reply timeout ms, 5000),
#      SOAK_TQ (QEMU reply timeout ms, 20000), SOAK_VERBOSE.
# Timeouts (the rule of mk/m4f.mk: >= 5x the unloaded run time, measured 2026-11-26):
# a native session takes <= 0.4 s, a QEMU session <= 1.9 s (soak-quick, the same session
# sizes as full), so the per-session `timeout 600` / `timeout 900` are hang guards; the
# reply timeouts as in host_sim/sim_suite.sh.
B=${BUILD:-build}
HS=$B/host/host_sim
NAT=$B/host/fw_native
ELF=$B/m4f/fw.elf
QEMU=${QEMU:-qemu-system-arm}
TN=${SOAK_TN:-5000}
TQ=${SOAK_TQ:-20000}
mode=${1:-full}
case $mode in
full) NS=${SOAK_NATIVE:-96}; QS=${SOAK_QEMU:-24} ;;
quick) NS=${SOAK_NATIVE:-12}; QS=${SOAK_QEMU:-3} ;;
*) echo "usage: soak.sh full|quick" >&2; echo "soak: 0 passed, 1 failed"; exit 2 ;;
esac
OUT=$B/host/soak/$mode
rm -rf "$OUT"
mkdir -p "$OUT/jobs" "$OUT/native" "$OUT/qemu"
for f in "$HS" "$NAT"; do
    [ -x "$f" ] || { echo "soak: $f missing (make fw-native host-sim)"; echo "soak: 0 passed, 1 failed"; exit 2; }
done
if [ "$QS" -gt 0 ]; then
    if ! command -v "$QEMU" >/dev/null 2>&1 || [ ! -f "$ELF" ]; then
        echo "soak: $QEMU or $ELF missing (apt-get install qemu-system-arm; make m4f-fw)"
        echo "soak: 0 passed, 1 failed"; exit 1
    fi
fi
T0=$(date +%s)

# ---- jobs: name, format (frames | cs | gcode), command lines ----
job() { # name format lines...
    n=$1; fmt=$2; shift 2
    {
        echo "# $n ($fmt) - written by host_sim/soak.sh"
        for l in "$@"; do echo "$l   #! expect ok"; done
        case $fmt in
        frames) echo "FORMAT FRAMES   #! expect ok" ;;
        cs) echo "FORMAT GCODE   #! expect ok"; echo "CHECKSUM ON   #! expect ok" ;;
        gcode) echo "FORMAT GCODE   #! expect ok" ;;
        esac
        # a program needs a feed and a safe height (docs/PROTOCOL.md "The program");
        # the jobs' own FEED, when they have one, comes earlier and stays
        case " $* " in *" FEED "*) ;; *) echo "FEED 600   #! expect ok" ;; esac
        echo "SAFE 60   #! expect ok"
        echo "RUN   #! expect ok"
    } > "$OUT/jobs/$n.job"
    echo "$n $fmt" >> "$OUT/jobs/list"
}
PAPER="CURVE ARC 0 0 3 0 360|RADIUS COS 5.5 10.5 2"
mkjobs() { # prefix lines circles circle-steps patch-circles patch-steps
    p=$1; nl=$2; nc=$3; cs=$4; np=$5; ps=$6
    IFS='|'
    # shellcheck disable=SC2086
    set -- $PAPER
    unset IFS
    a=$1; r=$2
    job "${p}_paper_frames" frames "$a" "$r" "LINES $nl -25 10" "STEPS 1000" "FEED 600"
    job "${p}_paper_cs" cs "$a" "$r" "LINES $nl -25 10" "STEPS 1000" "FEED 600"
    job "${p}_circles_frames" frames "$a" "$r" "CIRCLES $nc -25 10" "STEPS $cs"
    job "${p}_ellipse_frames" frames "CURVE ELLIPSE 0 0 4 3 0 300" "RADIUS LINEAR 1 1.5" \
        "LINES $nl -40 40" "STEPS 1000" "FEED 900"
    job "${p}_patch_cs" cs "$a" "$r" "CIRCLES $np -25 10 PATCH" "STEPS $ps"
    job "${p}_bezier_tool_frames" frames "CURVE BEZIER 0 0 10 20 30 -20 40 0" \
        "RADIUS CUBIC 3 4 4 3" "TOOL BALL 1" "LINES $nl 0 80" "STEPS 1000"
    job "${p}_boss_cs" cs "CURVE ARC 0 0 25 0 360" "RADIUS COS 1 4 3" "TOOL BALL 2 CENTRE" \
        "LINES $nl 0 85" "STEPS 1000" "FEED 1200"
    job "${p}_paper_gcode" gcode "$a" "$r" "LINES $nl -25 10" "STEPS 1000" "FEED 600"
}
: > "$OUT/jobs/list"
mkjobs n 10 30 300 30 300   # about 10k points per native session
mkjobs q 5 30 150 22 200    # about 5k points per QEMU session

# ---- deterministic generator (LCG, 31 bits) ----
seed=$(( ${SOAK_SEED:-1} % 2147483647 + 1 ))
rnd() { # rnd N -> R in [0, N)
    seed=$(( (seed * 1103515245 + 12345) % 2147483648 ))
    hi=$seed
    seed=$(( (seed * 1103515245 + 12345) % 2147483648 ))
    R=$(( ((hi / 65536) * 65536 + seed / 32768) % $1 ))
}

# ---- per-session figures, parsed from host_sim's summary ----
pass=0; fail=0
tot_pts=0; tot_judged=0; tot_naks=0; tot_bad=0; tot_dupf=0; tot_gap=0; tot_rs=0
tot_hang=0; tot_res=0; tot_missing=0; tot_twice=0; tot_order=0; tot_beyond=0; tot_jfail=0
: > "$OUT/sessions.txt"
num() { sed -n "$1" "$2" | tail -n 1; }
account() { # file -> adds to the totals, sets s_* for the session line
    f=$1
    s_pts=$(num 's/^  points  *\([0-9]*\)$/\1/p' "$f"); s_pts=${s_pts:-0}
    s_judged=$(num 's/^  judge: .* complete, \([0-9]*\) points.*/\1/p' "$f"); s_judged=${s_judged:-0}
    rl=$(sed -n 's/^  retransmits  *//p' "$f" | tail -n 1)
    set -- $(echo "$rl" | tr -c '0-9\n' ' ')
    s_rs=${1:-0}; s_naks=${2:-0}; s_bad=${3:-0}; s_dupf=${4:-0}; s_gap=${5:-0}
    set -- $(sed -n 's/^  runs .*hang-ups \([0-9]*\), resumes \([0-9]*\).*/\1 \2/p' "$f" | tail -n 1)
    s_hang=${1:-0}; s_res=${2:-0}
    set -- $(sed -n 's/.*judge coverage.*: \([0-9]*\) out of order, \([0-9]*\) beyond, \([0-9]*\) twice, \([0-9]*\) missing.*/\1 \2 \3 \4/p' "$f" | tail -n 1)
    s_order=${1:-0}; s_beyond=${2:-0}; s_twice=${3:-0}; s_missing=${4:-0}
    s_jfail=$(grep -c '^  FAIL judge' "$f")
    tot_pts=$((tot_pts + s_pts)); tot_judged=$((tot_judged + s_judged))
    tot_naks=$((tot_naks + s_naks)); tot_bad=$((tot_bad + s_bad)); tot_dupf=$((tot_dupf + s_dupf))
    tot_gap=$((tot_gap + s_gap)); tot_rs=$((tot_rs + s_rs)); tot_hang=$((tot_hang + s_hang))
    tot_res=$((tot_res + s_res)); tot_missing=$((tot_missing + s_missing))
    tot_twice=$((tot_twice + s_twice)); tot_order=$((tot_order + s_order))
    tot_beyond=$((tot_beyond + s_beyond)); tot_jfail=$((tot_jfail + s_jfail))
}
# fault counters: <target>_<format>_<kind>
cnt() { eval "c_$1=\$(( \${c_$1:-0} + 1 ))"; }
get() { eval "echo \${c_$1:-0}"; }

# session NAME TARGET JOB FORMAT FAULT|none
session() {
    name=$1; tgt=$2; jb=$3; fm=$4; flt=$5
    set --
    [ "$flt" = none ] || set -- --fault "$flt"
    case $flt in hangup@*) set -- "$@" --resume ;; esac
    o=$OUT/$tgt/$name.out
    ts=$(date +%s%N)
    if [ "$tgt" = qemu ]; then
        timeout 900 "$HS" --target qemu --qemu "$QEMU" --fw "$ELF" --timeout-ms "$TQ" \
            --job "$OUT/jobs/$jb.job" "$@" > "$o" 2>&1
    else
        timeout 600 "$HS" --target native --fw "$NAT" --timeout-ms "$TN" \
            --job "$OUT/jobs/$jb.job" "$@" > "$o" 2>&1
    fi
    rc=$?
    ms=$(( ($(date +%s%N) - ts) / 1000000 ))
    account "$o"
    line="$name $tgt $jb ${flt} rc=$rc points=$s_pts judged=$s_judged NAK=$s_naks bad=$s_bad dupf=$s_dupf gap=$s_gap resend=$s_rs hangup=$s_hang resume=$s_res missing=$s_missing twice=$s_twice order=$s_order judge_fail=$s_jfail ${ms}ms"
    echo "$line" >> "$OUT/sessions.txt"
    if [ "$rc" -eq 0 ]; then
        pass=$((pass + 1))
        [ -z "$SOAK_VERBOSE" ] || echo "  PASS $line"
        kind=${flt%@*}
        [ "$flt" = none ] || cnt "${tgt}_${fm}_${kind}"
    else
        fail=$((fail + 1))
        echo "  FAIL $line (see $o)"
        grep -E '^  FAIL|host_sim:|^  run ' "$o" | head -n 6 | sed 's/^/        /'
        kind=${flt%@*}
        if [ "$flt" = none ]; then
            cnt clean_failed
        else
            cnt "${tgt}_${fm}_${kind}"
            cnt "${tgt}_${fm}_failed"
        fi
        if [ "$tgt" = native ]; then # the same session again with a transcript
            timeout 600 "$HS" --target native --fw "$NAT" --timeout-ms "$TN" \
                --job "$OUT/jobs/$jb.job" "$@" --log "$OUT/$tgt/$name.log" > "$OUT/$tgt/$name.rerun" 2>&1
            echo "        rerun with transcript: exit $? ($OUT/$tgt/$name.log)"
        fi
    fi
}

# ---- 1. one clean session per job: judged, and the length of its RUN stream ----
while read -r jb fm; do
    # QEMU jobs are measured natively: both streams are byte-identical (sim-identical)
    case $jb in q_*) [ "$QS" -gt 0 ] || continue ;; esac
    session "clean_$jb" native "$jb" "$fm" none
    L=$(sed -n 's/^  run bytes  *in \([0-9]*\),.*/\1/p' "$OUT/native/clean_$jb.out" | tail -n 1)
    eval "len_$jb=${L:-0}"
done < "$OUT/jobs/list"
[ "$mode" = quick ] && [ -z "$SOAK_VERBOSE" ] && echo "  clean sessions: $pass passed, $fail failed"

# ---- 2. fault sessions ----
plan() { # target count prefix
    tgt=$1; count=$2; pfx=$3
    grep "^${pfx}_" "$OUT/jobs/list" > "$OUT/jobs/list.$tgt"
    nj=$(wc -l < "$OUT/jobs/list.$tgt")
    i=0
    while [ "$i" -lt "$count" ]; do
        set -- $(sed -n "$((i % nj + 1))p" "$OUT/jobs/list.$tgt")
        jb=$1; fm=$2
        # the kind rotates so that every job meets every kind; the byte is random
        case $fm in
        gcode) kinds="hangup" ;;
        *) kinds="drop flip dup hangup" ;;
        esac
        set -- $kinds
        k=$(( (i + i / nj) % $# + 1 ))
        eval "kind=\${$k}"
        eval "L=\${len_$jb:-0}"
        if [ "$L" -le 0 ]; then
            echo "  FAIL $tgt session $i: no stream length for $jb"; fail=$((fail + 1))
            i=$((i + 1)); continue
        fi
        rnd "$L"
        session "$(printf '%s_%03d' "$tgt" "$i")" "$tgt" "$jb" "$fm" "$kind@$R"
        i=$((i + 1))
    done
}
plan native "$NS" n
[ "$QS" -gt 0 ] && plan qemu "$QS" q

# ---- 3. summary ----
T1=$(date +%s)
row() { printf '  %-34s %s\n' "$1" "$2"; }
nat_pts=$(awk '$2 == "native" {sub("points=", "", $6); s += $6} END {print s + 0}' "$OUT/sessions.txt")
qemu_pts=$(awk '$2 == "qemu" {sub("points=", "", $6); s += $6} END {print s + 0}' "$OUT/sessions.txt")
nat_n=$(awk '$2 == "native"' "$OUT/sessions.txt" | wc -l)
qemu_n=$(awk '$2 == "qemu"' "$OUT/sessions.txt" | wc -l)
echo "soak summary ($mode, seed ${SOAK_SEED:-1}; sessions in $OUT/sessions.txt)"
row "sessions" "$((nat_n + qemu_n)) (native $nat_n incl. $(grep -c '^clean_' "$OUT/sessions.txt") clean, QEMU $qemu_n)"
row "points received" "$tot_pts (native $nat_pts, QEMU $qemu_pts)"
row "points judged (sim_check)" "$tot_judged"
row "clean sessions failed" "$(get clean_failed)"
for t in native qemu; do
    for f in frames cs gcode; do
        d=$(get "${t}_${f}_drop"); fl=$(get "${t}_${f}_flip"); du=$(get "${t}_${f}_dup")
        h=$(get "${t}_${f}_hangup"); x=$(get "${t}_${f}_failed")
        [ $((d + fl + du + h + x)) -gt 0 ] || continue
        case $f in frames) fn=FRAMES ;; cs) fn=GCODE+CHECKSUM ;; gcode) fn=GCODE ;; esac
        row "faults $t $fn" "drop $d, flip $fl, dup $du, hangup $h (sessions failed: $x)"
    done
done
row "FRAMES recovery" "NAKs $tot_naks, gap frames $tot_gap, dup frames $tot_dupf"
row "GCODE+CHECKSUM recovery" "Resend: $tot_rs"
row "bad lines/frames seen" "$tot_bad"
row "hang-ups / RESUMEs" "$tot_hang / $tot_res"
row "wrong (failed judge rows)" "$tot_jfail"
row "lost (missing)" "$tot_missing"
row "duplicated (twice)" "$tot_twice"
row "out of order / beyond" "$tot_order / $tot_beyond"
row "elapsed" "$((T1 - T0)) s"
echo "soak: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
