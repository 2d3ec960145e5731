#!/bin/sh
# guard_layers.sh - the firmware's folders are its layers (docs/ARCHITECTURE.md), and an
# include may only go DOWN (or stay in its layer):
#     base < models < path < job < proto < port
# port/ is the HAL contract the protocol needs (hal_uart.h): it includes only base/.
# hal/ (the ports) and tests may include anything; firmware/ never includes hal/.
# Prints one line per offending include and "layers: N passed, N failed".
# SPDX-License-Identifier: MIT
cd "$(dirname "$0")/.." || exit 2
rank() {
    case $1 in
    base) echo 0 ;; models) echo 1 ;; path) echo 2 ;; job) echo 3 ;; proto) echo 4 ;;
    port) echo 0 ;; *) echo 99 ;;
    esac
}
pass=0; fail=0
for dir in firmware/*/; do
    layer=$(basename "$dir")
    r=$(rank "$layer")
    if [ "$r" -eq 99 ]; then
        echo "  FAIL firmware/$layer/: not a layer of docs/ARCHITECTURE.md"; fail=$((fail + 1)); continue
    fi
    for f in "$dir"*.c "$dir"*.h; do
        [ -f "$f" ] || continue
        for h in $(sed -n 's/^#include "\([^"]*\)".*/\1/p' "$f"); do
            where=$(ls firmware/*/"$h" 2>/dev/null | head -n 1)
            if [ -z "$where" ]; then
                echo "  FAIL $f includes \"$h\": not a firmware header (firmware/ never includes hal/ or tests/)"
                fail=$((fail + 1)); continue
            fi
            hl=$(basename "$(dirname "$where")")
            hr=$(rank "$hl")
            if [ "$layer" = port ] && [ "$hl" != base ] && [ "$hl" != port ]; then hr=99; fi
            if [ "$hr" -gt "$r" ]; then
                echo "  FAIL $f ($layer) includes $where ($hl): an include up the layers"
                fail=$((fail + 1))
            else
                pass=$((pass + 1))
            fi
        done
    done
done
[ "$fail" -eq 0 ] && echo "  PASS every include of firmware/ goes down the layers ($pass includes)"
echo "layers: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
