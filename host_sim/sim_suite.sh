#!/bin/sh
# sim_suite.sh - the RUN suites of host_sim (mk/sim.mk: sim-run-native, sim-run-qemu,
# sim-baud, sim-faults, sim-resume, sim-identical, sim-models, example-model;
# docs/HOST_SIM.md).
# SPDX-License-Identifier: MIT
#
# Usage: sh host_sim/sim_suite.sh run-native|run-qemu|baud|faults|resume|identical|models|example|machines
# Each case is one or two host_sim sessions (exit 0 required) plus, for resume and
# identical, a byte comparison (identical: of the streams as sent once, host_sim/raw_sent.py).
# Prints one line per case and closes with
# "<suite>: N passed, N failed"; exits 1 if any case failed.
# Env: BUILD (build), QEMU (qemu-system-arm), SIM_BAUD (115200), SIM_MIN_UTIL (95),
#      SIM_RUN_TIMEOUT (native reply timeout, ms, 5000), SIM_QEMU_TIMEOUT (20000).
# Timeouts (the rule of mk/m4f.mk: >= 5x the unloaded run time, measured 2026-11-26):
# the reply timeouts bound a reply (<= 6 ms, QEMU boot to the first answer <= 45 ms) and
# a silence within a RUN (the firmware's retransmit timer OUT_FRAMES_RTO_MS is 250 ms); a whole
# session takes <= 13 s (baud: the paced paper job), so `timeout 600` is a hang guard only.
B=${BUILD:-build}
HS=$B/host/host_sim
NAT=$B/host/fw_native
ELF=$B/m4f/fw.elf
QEMU=${QEMU:-qemu-system-arm}
BAUD=${SIM_BAUD:-115200}
UTIL=${SIM_MIN_UTIL:-95}
TN=${SIM_RUN_TIMEOUT:-5000}
TQ=${SIM_QEMU_TIMEOUT:-20000}
J=tests/jobs
suite=$1
OUT=$B/host/sim_suite/$suite
mkdir -p "$OUT"
pass=0; fail=0

# sent_cmp a.raw b.raw out: the two raw RUN streams as sent once (host_sim/raw_sent.py drops
# the FRAMES retransmissions, which follow the host's answer time, not the firmware's output)
# compared byte for byte (cmp's answer in out); echoes "<resent a>/<resent b>"
sent_cmp() {
    ra=$(python3 host_sim/raw_sent.py "$1" "$1.sent") || ra=x
    rb=$(python3 host_sim/raw_sent.py "$2" "$2.sent") || rb=x
    cmp "$1.sent" "$2.sent" > "$3" 2>&1 && [ "$ra" != x ] && [ "$rb" != x ]
    r=$?
    echo "$ra/$rb"
    return $r
}

result() { # name rc detail
    if [ "$2" -eq 0 ]; then
        pass=$((pass + 1)); echo "  PASS $1 $3"
    else
        fail=$((fail + 1)); echo "  FAIL $1 $3 (see $OUT/$1.out)"
        grep -E 'FAIL|host_sim:' "$OUT/$1.out" | head -n 5 | sed 's/^/        /'
    fi
}

# hs NAME native|qemu ARGS... : one host_sim session, output in $OUT/NAME.out
hs() {
    name=$1; tgt=$2; shift 2
    if [ "$tgt" = qemu ]; then
        timeout 600 "$HS" --target qemu --qemu "$QEMU" --fw "$ELF" --timeout-ms "$TQ" \
            --log "$OUT/$name.log" "$@" > "$OUT/$name.out" 2>&1
    else
        timeout 600 "$HS" --target native --fw "$NAT" --timeout-ms "$TN" \
            --log "$OUT/$name.log" "$@" > "$OUT/$name.out" 2>&1
    fi
}

# summary figures of a session: points, bytes/point, points/s, utilization
figs() {
    f=$OUT/$1.out
    p=$(sed -n 's/^  points  *\([0-9]*\)$/\1/p' "$f" | tail -n 1)
    bpp=$(sed -n 's/^  bytes\/point  *//p' "$f" | tail -n 1)
    pps=$(sed -n 's/^  points\/s  *//p' "$f" | tail -n 1)
    u=$(sed -n 's/^  wire utilization  *\([0-9.]*%\).*/\1/p' "$f" | tail -n 1)
    rt=$(sed -n 's/^  retransmits  *//p' "$f" | tail -n 1)
    last=$(tail -n 1 "$f")
    echo "($p points, $bpp B/point, $pps points/s${u:+, wire $u}; $rt; $last)"
}

case $suite in
run-native|run-qemu)
    tgt=${suite#run-}
    if [ "$tgt" = qemu ] && ! command -v "$QEMU" >/dev/null 2>&1; then
        echo "sim-run-qemu: $QEMU not found (apt-get install qemu-system-arm)"
        echo "$suite: 0 passed, 1 failed"; exit 1
    fi
    for job in paper_gcode paper_frames paper_gcode_cs boss_gcode boss_frames placed_gcode placed_frames \
        seam_gcode; do
        hs "$job" "$tgt" --job "$J/$job.job" --csv "$OUT/$job.csv" --gcode "$OUT/$job.nc" \
            --svg "$OUT/$job.svg"
        result "$job" $? "$(figs "$job")"
    done
    ;;
baud)
    for job in paper_gcode paper_frames; do
        hs "$job" native --job "$J/$job.job" --baud "$BAUD" --min-util "$UTIL"
        result "$job" $? "$(figs "$job")"
    done
    ;;
faults)
    # FRAMES: inside BEGIN, early/late POINT frames, a sync byte (frame 4 ends at 20+4*32)
    for f in flip@5 drop@1000 flip@5003 dup@20007 drop@77777 flip@148 dup@31 drop@131000; do
        n=frames_$(echo "$f" | tr @ _)
        hs "$n" native --job "$J/paper_frames.job" --fault "$f"
        result "$n" $? "$(figs "$n")"
    done
    # GCODE + CHECKSUM: bytes inside G-code lines; 4122 is a '\n' (the end of N100):
    # duplicated it is an empty line (skipped, as Marlin does), dropped it merges
    # N100 and N101 into one line that fails its checksum -> Resend: 100
    for f in flip@1000 drop@5003 dup@20007 flip@77777 drop@150000 dup@4122 drop@4122; do
        n=gcode_cs_$(echo "$f" | tr @ _)
        hs "$n" native --job "$J/paper_gcode_cs.job" --fault "$f"
        result "$n" $? "$(figs "$n")"
    done
    ;;
resume)
    for job in paper_gcode paper_frames paper_gcode_cs; do
        hs "${job}_full" native --job "$J/$job.job" --csv "$OUT/${job}_full.csv"
        r1=$?
        hs "${job}_resumed" native --job "$J/$job.job" --fault hangup@60001 --resume \
            --csv "$OUT/${job}_resumed.csv"
        r2=$?
        cmp -s "$OUT/${job}_full.csv" "$OUT/${job}_resumed.csv"
        r3=$?
        result "$job" $((r1 + r2 + r3)) \
            "(uninterrupted $r1, hang-up at byte 60001 + RESUME $r2, csv $([ $r3 -eq 0 ] && echo identical || echo DIFFER): $(grep -o 'RESUME [0-9]*' "$OUT/${job}_resumed.out" | head -n 1))"
    done
    if command -v "$QEMU" >/dev/null 2>&1; then
        job=paper_frames
        hs "${job}_qemu_resumed" qemu --job "$J/$job.job" --fault hangup@40001 --resume \
            --csv "$OUT/${job}_qemu_resumed.csv"
        r2=$?
        cmp -s "$OUT/${job}_full.csv" "$OUT/${job}_qemu_resumed.csv"
        r3=$?
        result "${job}_qemu" $((r2 + r3)) \
            "(QEMU hang-up at byte 40001 + new QEMU + RESUME $r2, csv vs native uninterrupted $([ $r3 -eq 0 ] && echo identical || echo DIFFER))"
    fi
    ;;
identical)
    if ! command -v "$QEMU" >/dev/null 2>&1; then
        echo "sim-identical: $QEMU not found (apt-get install qemu-system-arm)"
        echo "$suite: 0 passed, 1 failed"; exit 1
    fi
    for job in paper_gcode paper_frames boss_frames; do
        hs "${job}_native" native --job "$J/$job.job" --raw "$OUT/${job}_native.raw"
        r1=$?
        hs "${job}_qemu" qemu --job "$J/$job.job" --raw "$OUT/${job}_qemu.raw"
        r2=$?
        rs=$(sent_cmp "$OUT/${job}_native.raw" "$OUT/${job}_qemu.raw" "$OUT/${job}.cmp")
        r3=$?
        result "$job" $((r1 + r2 + r3)) \
            "(native $r1, qemu $r2, raw RUN streams as sent once $(wc -c < "$OUT/${job}_native.raw.sent") bytes: $([ $r3 -eq 0 ] && echo identical || cat "$OUT/${job}.cmp"); frames resent native/qemu $rs)"
    done
    ;;
models)
    # the seed 001-003 models (SURFACE GSR | CHANNEL | DRC): every tests/jobs/model_<m>_*.job,
    # judged, natively (all models) and under QEMU (the all-features image fw.elf: all
    # four models), and the two raw RUN streams byte-identical
    for f in "$J"/model_*.job; do
        [ -f "$f" ] || continue
        job=$(basename "$f" .job)
        hs "${job}_native" native --job "$f" --csv "$OUT/${job}_native.csv" --raw "$OUT/${job}_native.raw"
        r1=$?
        result "${job}_native" $r1 "$(figs "${job}_native")"
        # the judge can fail: the same session with point 10 judged 5 um off must exit 1
        # with a FAIL row of the model's judge
        SIM_JUDGE_PERTURB_K=10 hs "${job}_wrong" native --job "$f"
        r0=$?
        m=${job#model_}; m=${m%%_*}
        if [ $r0 -eq 1 ] && grep -q "FAIL judge $m-" "$OUT/${job}_wrong.out"; then r0=0; else r0=1; fi
        result "${job}_judge_fails" $r0 "(point 10 moved 5 um: $(grep -o "FAIL judge $m-[a-z]*" "$OUT/${job}_wrong.out" | tr '\n' ' '))"
        if grep -qi '^ *PLACE' "$f"; then
            # a placed job: the judge's inverse turned 0.01 deg more (a firmware with a
            # wrong rz) must fail the model's judge
            SIM_PLACE_SKEW_DEG=0.01 hs "${job}_skewed" native --job "$f"
            r0=$?
            if [ $r0 -eq 1 ] && grep -q "FAIL judge $m-" "$OUT/${job}_skewed.out"; then r0=0; else r0=1; fi
            result "${job}_place_judge_fails" $r0 "(inverse placement 0.01 deg off: $(grep -o "FAIL judge $m-[a-z]*" "$OUT/${job}_skewed.out" | tr '\n' ' '))"
        fi
        if command -v "$QEMU" >/dev/null 2>&1; then
            # the all-features image, all four models (mk/m4f.mk: fw.elf = fw-all.elf)
            ELF=$B/m4f/fw.elf
            hs "${job}_qemu" qemu --job "$f" --csv "$OUT/${job}_qemu.csv" --raw "$OUT/${job}_qemu.raw"
            r2=$?
            result "${job}_qemu" $r2 "$(figs "${job}_qemu")"
            rs=$(sent_cmp "$OUT/${job}_native.raw" "$OUT/${job}_qemu.raw" "$OUT/${job}.cmp")
            result "${job}_identical" $? "(native and QEMU raw RUN streams as sent once; frames resent native/qemu $rs)"
        else
            result "${job}_qemu" 1 "($QEMU not found: apt-get install qemu-system-arm)"
        fi
    done
    # the canal's judge (row 0 of the judge table; its rows carry no model prefix) fails too
    SIM_JUDGE_PERTURB_K=10 hs canal_paper_frames_wrong native --job "$J/paper_frames.job"
    r0=$?
    if [ $r0 -eq 1 ] && grep -q "FAIL judge line" "$OUT/canal_paper_frames_wrong.out"; then r0=0; else r0=1; fi
    result canal_paper_frames_judge_fails $r0 "(point 10 moved 5 um: $(grep -o "FAIL judge [a-z]*" "$OUT/canal_paper_frames_wrong.out" | tr '\n' ' '))"
    # a placed canal job: the judge's inverse turned 0.01 deg more (a firmware with a wrong
    # rz) fails the canal's judge
    for job in placed_frames placed_gcode; do
        SIM_PLACE_SKEW_DEG=0.01 hs "canal_${job}_skewed" native --job "$J/$job.job"
        r0=$?
        if [ $r0 -eq 1 ] && grep -q "FAIL judge line" "$OUT/canal_${job}_skewed.out"; then r0=0; else r0=1; fi
        result "canal_${job}_place_judge_fails" $r0 "(inverse placement 0.01 deg off: $(grep -o "FAIL judge [a-z]*" "$OUT/canal_${job}_skewed.out" | tr '\n' ' '))"
    done
    ;;
example)
    # the example model (docs/ARCHITECTURE.md): a firmware built with CP_WITH_PLANE=1
    # (make example-model), its job judged against tests/ref_plane.c; the judge must fail
    # on a point moved 5 um
    NAT=$B/example/host/fw_native
    hs example_plane native --job "$J/example_plane.job" --csv "$OUT/example_plane.csv"
    result example_plane $? "$(figs example_plane)"
    SIM_JUDGE_PERTURB_K=10 hs example_plane_wrong native --job "$J/example_plane.job"
    r0=$?
    if [ $r0 -eq 1 ] && grep -q "FAIL judge plane-point" "$OUT/example_plane_wrong.out"; then r0=0; else r0=1; fi
    result example_plane_judge_fails $r0 "(point 10 moved 5 um: $(grep -o "FAIL judge plane-[a-z]*" "$OUT/example_plane_wrong.out" | tr '\n' ' '))"
    ;;
machines)
    # two-link cells (--machine): every demo and judged job in both dialects, natively
    # (FRAMES jobs run as programs: host_sim makes FORMAT FRAMES GCODE), the emulated
    # machine's motion at 1/200 of real time (its planner fills, oks wait for it)
    for job in paper_gcode paper_frames boss_gcode boss_frames placed_gcode placed_frames \
               model_gsr_gcode model_gsr_frames model_gsr_placed model_channel_gcode \
               model_channel_frames model_drc_curve model_drc_fillet model_spine_gcode \
               model_spine_frames model_spine_demo; do
        hs "grbl_$job" native --job "$J/$job.job" --machine grbl --machine-time 0.005
        result "grbl_$job" $? "$(figs "grbl_$job")"
        hs "marlin_$job" native --job "$J/$job.job" --machine marlin --advanced-ok \
            --machine-time 0.005
        result "marlin_$job" $? "$(figs "marlin_$job")"
    done
    # checksums are Marlin's (grbl refuses them: error:43, tests/test_machine.c)
    hs marlin_paper_gcode_cs native --job "$J/paper_gcode_cs.job" --machine marlin
    result marlin_paper_gcode_cs $? "$(figs marlin_paper_gcode_cs)"
    # homing on: grbl boots in ALARM, $H passes through the firmware
    hs grbl_homing native --job "$J/cell_homing.job" --machine grbl --homing
    result grbl_homing $? "$(figs grbl_homing)"
    # the Cortex-M4F image: the machine link is UART1 (QEMU's second -serial)
    if command -v "$QEMU" >/dev/null 2>&1; then
        hs qemu_grbl_paper_gcode qemu --job "$J/paper_gcode.job" --machine grbl
        result qemu_grbl_paper_gcode $? "$(figs qemu_grbl_paper_gcode)"
        hs qemu_marlin_model_drc_fillet qemu --job "$J/model_drc_fillet.job" --machine marlin \
            --advanced-ok
        result qemu_marlin_model_drc_fillet $? "$(figs qemu_marlin_model_drc_fillet)"
    else
        result qemu_cells 1 "($QEMU not found: apt-get install qemu-system-arm)"
    fi
    ;;
*)
    echo "usage: sim_suite.sh run-native|run-qemu|baud|faults|resume|identical|models|example|machines" >&2
    echo "sim-suite: 0 passed, 1 failed"; exit 2
    ;;
esac
echo "$suite: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
