#!/bin/sh
# stack.sh - worst-case static stack of a Cortex-M image from gcc -fcallgraph-info=su output.
# SPDX-License-Identifier: MIT
#
# Usage: stack.sh [--guard] --elf fw.elf --root Reset_Handler --isr "A B" \
#                 --indirect "f g" [--indirect-opt "h k"] --stack BYTES --fn-max BYTES
#                 file.ci...
#
# Input: one .ci file per object (gcc -fstack-usage -fcallgraph-info=su): every
# function with its own frame ("N bytes (static)") and every call edge. Static
# functions are qualified by their source path, so same-named statics of two files
# stay apart. Generic: new firmware files only add .ci files to the command line.
#
# Model and assumptions (printed with the result):
#   worst = worst path from --root (Reset_Handler -> main -> ...)
#         + one exception entry with FP context (26 words = 104 B, +4 B alignment pad)
#         + the deepest --isr handler path.
#     All IRQs run at the reset priority, so handlers never nest.
#   Indirect calls (gcc's __indirect_call: the struct hal_uart function pointers)
#     are charged with the deepest of the --indirect functions, the HAL port's
#     write/read/now_ms. A port must keep those leaf-ish; a new port lists its own.
#     --indirect-opt lists more targets charged the same way where the image has them
#     (the models' ball callbacks of raster_overlap_check, raster.h: an image without
#     the model has none); a name of --indirect must exist, one of --indirect-opt may not.
#   Functions without a .ci (newlib: memset, floorf, ...) get the frame their
#     prologue shows in the ELF disassembly (largest push + vpush + sub sp), and
#     are treated as leaves (newlib-nano's memset/floorf/ceilf are).
#   Recursion (a cycle) or a dynamic frame (alloca/VLA) is an error: no bound.
# Output: the worst path with frames, the 8 largest frames, and with --guard one
# line "guard-stack: N passed, N failed" (per-function limit, worst path <= region,
# no recursion, no dynamic frames, every root found).
guard=0; elf=; root=Reset_Handler; isrs=; indirect=; indopt=; region=0; fnmax=0
while [ $# -gt 0 ]; do
    case $1 in
    --guard) guard=1 ;;
    --elf) elf=$2; shift ;;
    --root) root=$2; shift ;;
    --isr) isrs=$2; shift ;;
    --indirect) indirect=$2; shift ;;
    --indirect-opt) indopt=$2; shift ;;
    --stack) region=$2; shift ;;
    --fn-max) fnmax=$2; shift ;;
    *) break ;;
    esac
    shift
done
[ $# -gt 0 ] || { echo "stack.sh: no .ci files"; exit 2; }
for f in "$@"; do [ -f "$f" ] || { echo "stack.sh: missing $f (build with -fcallgraph-info=su)"; exit 2; }; done

# Library frames from the ELF disassembly: "asm <name> <bytes>" lines.
asm_frames() {
    [ -n "$elf" ] && [ -f "$elf" ] || return 0
    ${OBJDUMP:-arm-none-eabi-objdump} -d --no-show-raw-insn "$elf" | awk '
        function flush() { if (fn != "") print "asm", fn, p + v + s }
        /^[0-9a-f]+ <[^>]+>:$/ { flush(); fn = $2; gsub(/[<>:]/, "", fn); p = v = s = 0; next }
        /\tpush(\.w)?\t\{/ || /\tstmdb(\.w)?\tsp!, \{/ {
            n = split(substr($0, index($0, "{")), r, ","); if (4 * n > p) p = 4 * n }
        /\tvpush\t\{/ { x = substr($0, index($0, "{") + 1); sub(/\}.*/, "", x)
            n = 0; m = split(x, r, ",")
            for (i = 1; i <= m; i++) { if (r[i] ~ /-/) { split(r[i], ab, "-"); gsub(/[^0-9]/, "", ab[1]); gsub(/[^0-9]/, "", ab[2]); c = ab[2] - ab[1] + 1 } else c = 1
                n += (r[i] ~ /d/) ? 8 * c : 4 * c }
            if (n > v) v = n }
        /\tsub(\.w|w)?\tsp, (sp, )?#[0-9]+/ { x = $0; sub(/.*#/, "", x); sub(/[^0-9].*/, "", x); if (x + 0 > s) s = x + 0 }
        END { flush() }'
}

{ asm_frames; cat "$@"; } | awk -v guard="$guard" -v root="$root" -v isrs="$isrs" \
    -v indirect="$indirect" -v indopt="$indopt" -v region="$region" -v fnmax="$fnmax" '
function bare(t) { sub(/.*:/, "", t); return t }
# resolve an edge target to a defined node title
function resolve(t,   b) {
    if (t in frame) return t
    if (t in byname) return byname[t]
    if (t in asmf) { frame[t] = asmf[t]; kind[t] = "asm"; return t }
    if (!(t in missing)) { missing[t] = 1; nmissing++ }
    frame[t] = 0; kind[t] = "unknown"; return t
}
# worst stack depth from f, memoised; cycles are recursion
function depth(f,   i, c, d, best, bc) {
    if (f in memo) return memo[f]
    if (state[f] == 1) { cycle = cycle " " bare(f); return 0 }
    state[f] = 1
    best = 0; bc = ""
    for (i = 1; i <= ncall[f]; i++) {
        c = callee[f, i]
        if (c == "__indirect_call") {
            d = depth("__indirect_call")
        } else d = depth(c)
        if (d > best || bc == "") { best = d; bc = c }
    }
    state[f] = 2; nxt[f] = bc
    memo[f] = frame[f] + best
    return memo[f]
}
function show(f, indent,   acc) {
    acc = 0
    while (f != "") {
        acc += frame[f]
        printf "%s%-34s %5d  %6d  %s\n", indent, bare(f), frame[f], acc, (kind[f] == "static" ? loc[f] : "(" kind[f] ")")
        f = nxt[f]
    }
    return acc
}
$1 == "asm" { asmf[$2] = $3; next }
/^node: / && /bytes \(/ {
    t = $0; sub(/^node: \{ title: "/, "", t); sub(/".*/, "", t)
    l = $0; sub(/.* label: "/, "", l); sub(/".*/, "", l)
    n = split(l, part, /\\n/)
    fb = part[3]; sub(/ bytes.*/, "", fb); q = part[3]; sub(/.*\(/, "", q); sub(/\).*/, "", q)
    frame[t] = fb + 0; kind[t] = q; loc[t] = part[2]
    if (t !~ /:/) byname[t] = t; else if (!(bare(t) in byname)) sbyname[bare(t)] = t
    if (q != "static") dyn = dyn " " bare(t) "(" q ")"
    if (fb + 0 > fnmax && fnmax > 0) over = over " " bare(t) "=" fb
    nfn++
    next
}
/^edge: / {
    s = $0; sub(/.*sourcename: "/, "", s); sub(/".*/, "", s)
    d = $0; sub(/.*targetname: "/, "", d); sub(/".*/, "", d)
    if (!((s, d) in seen)) { seen[s, d] = 1; es[++ne] = s; ed[ne] = d }
    next
}
END {
    # statics of the indirect/isr lists may be named bare
    nind = split(indirect, ind, " ")
    for (i = 1; i <= ne; i++) {
        s = es[i]; d = ed[i]
        if (d != "__indirect_call") d = resolve(d)
        callee[s, ++ncall[s]] = d
    }
    # the placeholder node: calls every indirect target
    frame["__indirect_call"] = 0; kind["__indirect_call"] = "indirect"
    for (i = 1; i <= nind; i++) {
        t = ind[i]; if (!(t in byname) && (t in sbyname)) t = sbyname[t]
        if (!(t in frame)) { notfound = notfound " " ind[i]; continue }
        callee["__indirect_call", ++ncall["__indirect_call"]] = t
    }
    nopt = split(indopt, iop, " "); optfound = ""
    for (i = 1; i <= nopt; i++) { # the optional targets this image has
        t = iop[i]; if (!(t in byname) && (t in sbyname)) t = sbyname[t]
        if (!(t in frame)) continue
        callee["__indirect_call", ++ncall["__indirect_call"]] = t
        optfound = optfound " " iop[i]
    }
    if (!(root in frame)) notfound = notfound " " root
    main_d = (root in frame) ? depth(root) : 0
    nisr = split(isrs, isr, " "); isr_d = 0; isr_w = ""
    for (i = 1; i <= nisr; i++) {
        t = isr[i]; if (!(t in frame)) { notfound = notfound " " t; continue }
        if (depth(t) > isr_d || isr_w == "") { isr_d = depth(t); isr_w = t }
    }
    exc = 108
    total = main_d + exc + isr_d

    printf "stack: %d functions with frames from %s\n", nfn, "gcc -fcallgraph-info=su"
    printf "worst path from %s (frame, cumulative bytes):\n", root
    show(root, "  ")
    printf "  + exception entry, FP context          %5d  %6d\n", exc, main_d + exc
    if (isr_w != "") {
        printf "  + deepest interrupt handler path (%s):\n", isr_w
        show(isr_w, "    ")
    }
    printf "worst case: %d bytes = main path %d + exception frame %d + ISR %d;  stack region %d bytes (%d%%)\n",
        total, main_d, exc, isr_d, region, (region > 0 ? int(total * 100 / region) : 0)
    printf "indirect calls charged with the deepest of: %s%s (%d bytes)\n", indirect, optfound, depth("__indirect_call")
    for (t in missing) lib = lib " " t
    for (t in kind) if (kind[t] == "asm") asml = asml " " bare(t) "=" frame[t]
    if (asml != "") printf "library leaves, frame from ELF prologue:%s\n", asml
    if (lib != "") printf "callees with no frame info (counted 0):%s\n", lib
    # largest frames
    printf "largest frames (limit %d bytes per function):\n", fnmax
    for (t in frame) if (kind[t] == "static" || kind[t] ~ /dynamic/) { nl++; lt[nl] = t }
    for (i = 1; i <= nl; i++) for (j = i + 1; j <= nl; j++) if (frame[lt[j]] > frame[lt[i]]) { x = lt[i]; lt[i] = lt[j]; lt[j] = x }
    for (i = 1; i <= nl && i <= 8; i++) printf "  %5d  %-30s %s\n", frame[lt[i]], bare(lt[i]), loc[lt[i]]
    if (guard) {
        p = 0; f = 0
        if (over == "") p++; else { f++; print "  FAIL: frame over " fnmax " bytes:" over }
        if (total <= region) p++; else { f++; print "  FAIL: worst case " total " > stack region " region }
        if (cycle == "") p++; else { f++; print "  FAIL: recursion through:" cycle }
        if (dyn == "") p++; else { f++; print "  FAIL: dynamic frames:" dyn }
        if (notfound == "") p++; else { f++; print "  FAIL: root/ISR/indirect function not found:" notfound }
        printf "guard-stack: %d passed, %d failed\n", p, f
        exit(f != 0)
    }
    if (cycle != "") print "WARNING: recursion through:" cycle
}'
