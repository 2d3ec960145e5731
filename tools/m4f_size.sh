#!/bin/sh
# m4f_size.sh - flash / RAM / stack figures of the Cortex-M product images, read from
# the ELF section headers and the link map, compared against linker/budget.txt.
# SPDX-License-Identifier: MIT
# Usage:
#   m4f_size.sh <fw.elf> <budget.txt> report|guard <set> [<stack.sh output>]
#       <set>: the image's model set, whose `image <set> <flash key>` row of budget.txt
#       names its flash budget. With tools/stack.sh's output for the image, guard also
#       checks .data + .bss + the static worst stack path <= ram.
#       report  print the figures and the largest symbols (always exits 0 if readable)
#       guard   also print "guard-budget: N passed, N failed" and exit 1 on any failure:
#               flash <= budget, flash <= headroom line (free_pct of the budget free),
#               .data + .bss + stack region <= ram, stack region == stack, the linker's
#               FLASH/RAM lengths (map) == the budgets, no section outside FLASH/RAM
#   m4f_size.sh table <budget.txt> <m4f build dir> <base set> <set>...
#       markdown tables for size-images: every image's flash, budget, % free, RAM with
#       the static worst stack (<dir>/stack-<set>.txt, tools/stack.sh output) and the
#       per-model cost fw-<set>.elf - fw-<base set>.elf. An image whose link failed
#       because of its flash budget (<dir>/link-<set>.log: "region `FLASH' overflowed by
#       N bytes") is shown as budget + N; any other link failure is printed and exits 1.
#       Exits 1 if an image is over its headroom line or did not link.
# Classification (generic, by section flags, so new sections are never missed):
#   allocated section in FLASH                 -> flash
#   allocated PROGBITS in RAM (.data)          -> flash (its initialiser) + RAM
#   allocated NOBITS in RAM named .stack       -> stack region
#   other allocated NOBITS in RAM (.bss, ...)  -> RAM
# The region origins/lengths come from the "Memory Configuration" of <fw.elf>.map.
READELF=${READELF:-arm-none-eabi-readelf}
NM=${NM:-arm-none-eabi-nm}

b() { awk -v k="$1" '$1 == k {print $2}' "$budget"; }
flash_key() { awk -v s="$1" '$1 == "image" && $2 == s {print $3}' "$budget"; }
region() { # <map> <name> -> "origin length" in decimal
    awk -v r="$2" '$1 == r && $2 ~ /^0x/ {print $2, $3; exit}' "$1" |
        while read -r o l; do printf '%d %d\n' "$o" "$l"; done
}
# figures <elf>: sets flash ram stack fl_org fl_len ram_org ram_len fdesc rdesc other
figures() {
    f_elf=$1
    set -- $(region "$f_elf.map" FLASH) 0 0; fl_org=$1; fl_len=$2
    set -- $(region "$f_elf.map" RAM) 0 0; ram_org=$1; ram_len=$2
    eval "$($READELF -SW "$f_elf" | sed -n 's/^ *\[ *[0-9]*\] //p' | awk \
        -v fo="$fl_org" -v fl="$fl_len" -v ro="$ram_org" -v rl="$ram_len" '
        $4 ~ /^[0-9a-f]+$/ && $6 ~ /^[0-9a-f]+$/ {
            name = $1; type = $2; addr = strtonum_("0x" $3); size = strtonum_("0x" $5); flg = $7
            if (flg !~ /A/) next
            if (addr >= fo && addr < fo + fl) { flash += size; fdesc = fdesc " " name " " size }
            else if (addr >= ro && addr < ro + rl) {
                if (type == "PROGBITS") { flash += size; ram += size; rdesc = rdesc " " name " " size }
                else if (name == ".stack") { stack += size }
                else { ram += size; rdesc = rdesc " " name " " size }
            } else { other = other " " name }
        }
        function strtonum_(h,   i, c, v) { v = 0; h = tolower(substr(h, 3))
            for (i = 1; i <= length(h); i++) { c = index("0123456789abcdef", substr(h, i, 1)) - 1; v = v * 16 + c }
            return v }
        END { printf "flash=%d ram=%d stack=%d fdesc=\"%s\" rdesc=\"%s\" other=\"%s\"\n",
              flash, ram, stack, fdesc, rdesc, other }')"
}
# the headroom line of a flash budget: flash <= line keeps free_pct % of it free
line_of() { echo $(( $1 * (100 - B_FREE) / 100 )); }

if [ "$1" = table ]; then
    budget=$2; dir=$3; base=$4; shift 4
    B_RAM=$(b ram); B_STACK=$(b stack); B_FREE=$(b free_pct)
    rows=""; bad=0
    for s in "$@"; do
        elf=$dir/fw-$s.elf; key=$(flash_key "$s"); B_FLASH=$(b "$key")
        if [ -z "$B_FLASH" ]; then echo "m4f_size: no 'image $s' row (or its flash key) in $budget"; exit 1; fi
        over=$(sed -n "s/.*region .FLASH' overflowed by \([0-9]*\) bytes.*/\1/p" "$dir/link-$s.log" 2>/dev/null | head -n 1)
        worst=$(sed -n 's/^worst case: \([0-9]*\) bytes.*/\1/p' "$dir/stack-$s.txt" 2>/dev/null)
        if [ -n "$over" ]; then flash=$((B_FLASH + over)); ram=-1; bad=1
        elif [ -f "$elf" ] && [ -f "$elf.map" ] && [ -z "$(grep -il error "$dir/link-$s.log" 2>/dev/null)" ]; then
            figures "$elf"
        else echo "m4f_size: fw-$s.elf did not link:"; tail -n 5 "$dir/link-$s.log" 2>/dev/null; exit 1; fi
        [ "$flash" -le "$(line_of "$B_FLASH")" ] || bad=1
        rows="$rows$s $key $B_FLASH $(line_of "$B_FLASH") $flash $ram ${worst:--1}
"
    done
    printf '%s' "$rows" | awk -v ram_b="$B_RAM" -v stack_b="$B_STACK" -v free="$B_FREE" -v base="$base" '
        function th(n,   s, neg) { neg = n < 0; if (neg) n = -n; s = ""
            while (n >= 1000) { s = sprintf(" %03d", n % 1000) s; n = int(n / 1000) }
            return (neg ? "-" : "") n s }
        { n++; set[n] = $1; key[n] = $2; bud[n] = $3; line[n] = $4; fl[n] = $5; ram[n] = $6; worst[n] = $7
          size[$1] = $5 }
        END {
            printf "| image | flash | flash budget | free | headroom line (%d %% free) | RAM: .data+.bss + worst stack (<= %s B) | RAM reserved: .data+.bss + %s B stack region |\n", free, th(ram_b), th(stack_b)
            print "|---|---:|---:|---:|---:|---:|---:|"
            for (i = 1; i <= n; i++) {
                if (ram[i] < 0) { printf "| `fw-%s.elf` | %s B | %s B (`%s`) | **LINK FAILS: over the budget by %s B** | %s B | - | - |\n", set[i], th(fl[i]), th(bud[i]), key[i], th(fl[i] - bud[i]), th(line[i]); continue }
                st = (fl[i] <= line[i]) ? "" : sprintf(" **OVER the line by %s B**", th(fl[i] - line[i]))
                ws = (worst[i] < 0) ? "? (no stack.sh result)" : sprintf("%s + %s = %s B", th(ram[i]), th(worst[i]), th(ram[i] + worst[i]))
                printf "| `fw-%s.elf` | %s B | %s B (`%s`) | %s B (%.1f %%)%s | %s B | %s | %s B |\n", set[i], th(fl[i]), th(bud[i]), key[i],
                    th(bud[i] - fl[i]), 100.0 * (bud[i] - fl[i]) / bud[i], st, th(line[i]), ws, th(ram[i] + stack_b)
            }
            if (!(base in size)) exit
            printf "\n| model set | image | flash | per-model cost (image - `fw-%s.elf`) |\n", base
            print "|---|---|---:|---:|"
            printf "| %s (the base) | `fw-%s.elf` | %s B | 0 B |\n", base, base, th(size[base])
            sum = 0; m = 0
            for (i = 1; i <= n; i++) if (set[i] != base && set[i] != "all") {
                printf "| %s + %s | `fw-%s.elf` | %s B | +%s B |\n", base, set[i], set[i], th(fl[i]), th(fl[i] - size[base]); sum += fl[i] - size[base]; m++ }
            if ("all" in size)
                printf "| all models | `fw-all.elf` | %s B | +%s B (the %d single-model costs sum to %s B) |\n", th(size["all"]), th(size["all"] - size[base]), m, th(sum)
        }'
    exit $bad
fi

elf=$1; budget=$2; mode=${3:-report}; set=$4; stackout=$5
map=$elf.map
[ -f "$elf" ] && [ -f "$map" ] || { echo "m4f_size: need $elf and $map"; exit 1; }
[ -n "$set" ] || { echo "m4f_size: usage: m4f_size.sh <fw.elf> <budget.txt> report|guard <set>"; exit 2; }
key=$(flash_key "$set")
B_FLASH=$(b "$key"); B_RAM=$(b ram); B_STACK=$(b stack); B_FREE=$(b free_pct)
[ -n "$B_FLASH" ] && [ -n "$B_RAM" ] && [ -n "$B_STACK" ] && [ -n "$B_FREE" ] ||
    { echo "m4f_size: $budget lacks 'image $set <key>', its flash key, ram, stack or free_pct"; exit 1; }
LINE=$(line_of "$B_FLASH")
figures "$elf"

total=$((ram + stack))
pct() { echo $(( $1 * 100 / $2 )); }
echo "fw image: $elf (set $set, flash budget $key)"
printf '  flash  %6d / %6d bytes (%d%%), headroom line %d (%d%% free)  =%s\n' "$flash" "$B_FLASH" \
    "$(pct "$flash" "$B_FLASH")" "$LINE" "$B_FREE" "$fdesc"
printf '  RAM    %6d bytes .data+.bss     =%s\n' "$ram" "$rdesc"
printf '  stack  %6d bytes region (linker CP_STACK, bottom of RAM)\n' "$stack"
printf '  RAM+stack %3d / %6d bytes (%d%%), %d bytes free\n' "$total" "$B_RAM" \
    "$(pct "$total" "$B_RAM")" $((B_RAM - total))
printf '  linker regions (map): FLASH %d @0x%x, RAM %d @0x%x\n' "$fl_len" "$fl_org" "$ram_len" "$ram_org"
peak=build/m4f/fw_stack_peak.txt
if [ "$(basename "$elf")" = fw.elf ] && [ -f "$peak" ] && [ "$peak" -nt "$elf" ]; then
    echo "  stack measured (painted, fw.elf after a \$I session on QEMU): $(cat "$peak") bytes"
fi
[ -n "$other" ] && echo "  WARNING: allocated sections outside FLASH/RAM:$other"
if [ "$mode" = report ]; then
    echo "  largest symbols (bytes):"
    $NM -S --size-sort "$elf" | tail -8 | awk '{printf "    %6d %s %s\n", strtonum_("0x" $2), $3, $4}
        function strtonum_(h,   i, c, v) { v = 0; h = tolower(substr(h, 3))
        for (i = 1; i <= length(h); i++) { c = index("0123456789abcdef", substr(h, i, 1)) - 1; v = v * 16 + c }
        return v }'
    exit 0
fi
pass=0; fail=0
chk() { if [ "$1" -eq 1 ]; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "  FAIL: $2"; fi; }
chk $([ "$flash" -le "$B_FLASH" ] && echo 1 || echo 0) "flash $flash > budget $B_FLASH ($key)"
chk $([ "$flash" -le "$LINE" ] && echo 1 || echo 0) "flash $flash > headroom line $LINE ($B_FREE% of $key $B_FLASH must stay free)"
chk $([ "$total" -le "$B_RAM" ] && echo 1 || echo 0) "RAM+stack $total > budget $B_RAM"
chk $([ "$stack" -eq "$B_STACK" ] && echo 1 || echo 0) "stack region $stack != budget stack $B_STACK"
chk $([ "$fl_len" -eq "$B_FLASH" ] && echo 1 || echo 0) "linker FLASH LENGTH $fl_len != budget $key $B_FLASH"
chk $([ "$ram_len" -eq "$B_RAM" ] && echo 1 || echo 0) "linker RAM LENGTH $ram_len != budget ram $B_RAM"
chk $([ -z "$other" ] && echo 1 || echo 0) "sections outside FLASH/RAM:$other"
if [ -n "$stackout" ]; then
    worst=$(sed -n 's/^worst case: \([0-9]*\) bytes.*/\1/p' "$stackout" 2>/dev/null)
    if [ -n "$worst" ]; then
        printf '  RAM .data+.bss + worst stack %d + %d = %d / %d bytes\n' "$ram" "$worst" $((ram + worst)) "$B_RAM"
        chk $([ $((ram + worst)) -le "$B_RAM" ] && echo 1 || echo 0) ".data+.bss + worst stack $((ram + worst)) > budget ram $B_RAM"
    else chk 0 "no 'worst case:' line in $stackout (tools/stack.sh)"; fi
fi
echo "guard-budget: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
