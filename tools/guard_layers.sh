#!/bin/sh
# guard_layers.sh - the firmware's folders are its layers (docs/ARCHITECTURE.md), and an
# include may only go DOWN (or stay in its layer):
#     base < models < path < job < proto < port
# port/ is the HAL contract the protocol needs (hal_uart.h): it includes only base/.
# hal/ (the ports) and tests may include anything; firmware/ never includes hal/.
# Prints one line per offending include and "layers: N passed, N failed" (one check per
# layer folder and per file).
# SPDX-License-Identifier: MIT
cd "$(dirname "$0")/.." || exit 2
rank() {
    case $1 in
    base) echo 0 ;; models) echo 1 ;; path) echo 2 ;; job) echo 3 ;; proto) echo 4 ;;
    port) echo 0 ;; *) echo 99 ;;
    esac
}
pass=0; fail=0; nincl=0
for dir in firmware/*/; do
    layer=$(basename "$dir")
    r=$(rank "$layer")
    if [ "$r" -eq 99 ]; then
        echo "  FAIL firmware/$layer/: not a layer of docs/ARCHITECTURE.md"; fail=$((fail + 1)); continue
    fi
    for f in "$dir"*.c "$dir"*.h "$dir"*.def; do
        [ -f "$f" ] || continue
        fbad=0; nin=0
        for h in $(sed -n 's/^#include "\([^"]*\)".*/\1/p' "$f"); do
            where=$(ls firmware/*/"$h" 2>/dev/null | head -n 1)
            if [ -z "$where" ]; then
                echo "  FAIL $f includes \"$h\": not a firmware header (firmware/ never includes hal/ or tests/)"
                fbad=1; continue
            fi
            hl=$(basename "$(dirname "$where")")
            hr=$(rank "$hl")
            if [ "$layer" = port ] && [ "$hl" != base ] && [ "$hl" != port ]; then hr=99; fi
            if [ "$hr" -gt "$r" ]; then
                echo "  FAIL $f ($layer) includes $where ($hl): an include up the layers"
                fbad=1
            fi
            nin=$((nin + 1))
        done
        if [ $fbad -eq 0 ]; then pass=$((pass + 1)); nincl=$((nincl + nin)); else fail=$((fail + 1)); fi
    done
done
[ "$fail" -eq 0 ] && echo "  PASS every include of firmware/ goes down the layers ($pass files, $nincl includes)"
echo "layers: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
