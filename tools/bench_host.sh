#!/bin/sh
# bench_host.sh - table of instructions per call from the callgrind dumps of build/host/bench_host.
# SPDX-License-Identifier: MIT
# Usage: bench_host.sh <callgrind-out-file>   (reads <file>.1, <file>.2, ... one dump per call)
# Every dump holds one call (collection toggled around it); the "empty" row is the
# baseline (toggle + indirect call overhead) subtracted from the others. If the
# calls of one routine differ, the row shows min..max.
out=$1
ls "$out".* >/dev/null 2>&1 || { echo "bench-host: no dumps $out.*"; exit 1; }
i=1
while [ -f "$out.$i" ]; do
    f=$out.$i; i=$((i + 1))
    awk '/^desc: Trigger: Client Request: /{n=$5} /^totals: /{t=$2} END{if (n != "") print n, t}' "$f"
done | awk '
    { if (!($1 in lo)) { order[++k] = $1; lo[$1] = $2; hi[$1] = $2 }
      if ($2 < lo[$1]) lo[$1] = $2; if ($2 > hi[$1]) hi[$1] = $2 }
    END {
        base = lo["empty"]
        printf "%-24s%s\n", "routine", "insns/call (host, callgrind Ir)"
        printf "%-24s%d raw\n", "(empty-call baseline)", base
        for (i = 1; i <= k; i++) { r = order[i]; if (r == "empty") continue
            if (lo[r] == hi[r]) printf "%-24s%d\n", r, lo[r] - base
            else printf "%-24s%d..%d (VARIES)\n", r, lo[r] - base, hi[r] - base }
    }'
