#!/bin/sh
# m4f_size.sh - flash / RAM / stack figures of a Cortex-M image, read from the ELF
# section headers and the link map, compared against linker/budget.txt.
# SPDX-License-Identifier: MIT
# Usage: m4f_size.sh <fw.elf> <budget.txt> report|guard
#   report  print the figures and the largest symbols (always exits 0 if readable)
#   guard   also print "guard-budget: N passed, N failed" and exit 1 on any failure
# Classification (generic, by section flags, so new sections are never missed):
#   allocated section in FLASH                 -> flash
#   allocated PROGBITS in RAM (.data)          -> flash (its initialiser) + RAM
#   allocated NOBITS in RAM named .stack       -> stack region
#   other allocated NOBITS in RAM (.bss, ...)  -> RAM
# The region origins/lengths come from the "Memory Configuration" of <fw.elf>.map.
elf=$1; budget=$2; mode=${3:-report}
READELF=${READELF:-arm-none-eabi-readelf}
NM=${NM:-arm-none-eabi-nm}
map=$elf.map
[ -f "$elf" ] && [ -f "$map" ] || { echo "m4f_size: need $elf and $map"; exit 1; }

b() { awk -v k="$1" '$1 == k {print $2}' "$budget"; }
region() { # <name> -> "origin length" in decimal
    awk -v r="$1" '$1 == r && $2 ~ /^0x/ {print $2, $3; exit}' "$map" |
        while read -r o l; do printf '%d %d\n' "$o" "$l"; done
}
set -- $(region FLASH); fl_org=$1; fl_len=$2
set -- $(region RAM); ram_org=$1; ram_len=$2

eval "$($READELF -SW "$elf" | sed -n 's/^ *\[ *[0-9]*\] //p' | awk \
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

B_FLASH=$(b flash); B_RAM=$(b ram); B_STACK=$(b stack)
total=$((ram + stack))
pct() { echo $(( $1 * 100 / $2 )); }
echo "fw image: $elf"
printf '  flash  %6d / %6d bytes (%d%%)  =%s\n' "$flash" "$B_FLASH" "$(pct "$flash" "$B_FLASH")" "$fdesc"
printf '  RAM    %6d bytes .data+.bss     =%s\n' "$ram" "$rdesc"
printf '  stack  %6d bytes region (linker CP_STACK, bottom of RAM)\n' "$stack"
printf '  RAM+stack %3d / %6d bytes (%d%%), %d bytes free\n' "$total" "$B_RAM" \
    "$(pct "$total" "$B_RAM")" $((B_RAM - total))
printf '  linker regions (map): FLASH %d @0x%x, RAM %d @0x%x\n' "$fl_len" "$fl_org" "$ram_len" "$ram_org"
peak=build/m4f/fw_stack_peak.txt
if [ -f "$peak" ] && [ "$peak" -nt "$elf" ]; then
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
chk $([ "$flash" -le "$B_FLASH" ] && echo 1 || echo 0) "flash $flash > budget $B_FLASH"
chk $([ "$total" -le "$B_RAM" ] && echo 1 || echo 0) "RAM+stack $total > budget $B_RAM"
chk $([ "$stack" -eq "$B_STACK" ] && echo 1 || echo 0) "stack region $stack != budget stack $B_STACK"
chk $([ "$fl_len" -eq "$B_FLASH" ] && echo 1 || echo 0) "linker FLASH LENGTH $fl_len != budget flash $B_FLASH"
chk $([ "$ram_len" -eq "$B_RAM" ] && echo 1 || echo 0) "linker RAM LENGTH $ram_len != budget ram $B_RAM"
chk $([ -z "$other" ] && echo 1 || echo 0) "sections outside FLASH/RAM:$other"
echo "guard-budget: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
