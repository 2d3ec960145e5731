#!/bin/sh
# guard_selftest.sh - prove that guard-alloc and guard-double bite: build scratch copies
# of firmware/ with an injected offender and require tools/guard.sh to FAIL on them
# (and to PASS on an untouched copy, so a broken harness cannot fake a "bite").
# The same for guard-fnlen on generated functions of FNLEN_MAX and FNLEN_MAX + 1 lines.
# Prints "guard-selftest: N passed, N failed".
# SPDX-License-Identifier: MIT
#
# env: FNLEN_MAX (120), CC HOST_CFLAGS M4F_CC M4F_FWFLAGS M4F_LDFLAGS SCRATCH, M4F_LDBUDGET (the
# --defsym CP_FLASH/CP_RAM/CP_STACK of linker/mps2_an386.ld for the image: mk/m4f.mk M4F_LD_BUDGET)
# args: the M4F port objects (startup, UART port, main_cm) to link a scratch fw.elf.
# Injected code is linked with -Wl,-u,<symbol>: --gc-sections would otherwise drop
# an uncalled function, and a real call site keeps it the same way.
port_obj=$*
S=${SCRATCH:-build/selftest}
pass=0; fail=0
ok()  { pass=$((pass + 1)); echo "  ok:   $1"; }
bad() { fail=$((fail + 1)); echo "  FAIL: $1"; }

rm -rf "$S"; mkdir -p "$S"

# build <name> <inject-file-body> <extra link flags> <link: yes|no>: firmware copy,
# objects for host and M4F, and (yes) an M4F fw.elf. The malloc copy is not linked:
# with no _sbrk in the firmware image the link itself already fails.
build() {
    d=$S/$1; mkdir -p "$d/src" "$d/host" "$d/m4f"
    cp firmware/*/*.c firmware/*/*.h firmware/*/*.def "$d/src/" 2>/dev/null
    [ -n "$2" ] && printf '%s\n' "$2" > "$d/src/selftest_inject.c"
    for c in "$d"/src/*.c; do
        b=$(basename "$c" .c)
        # shellcheck disable=SC2086
        $CC $HOST_CFLAGS -I"$d/src" -Wno-error -c "$c" -o "$d/host/$b.o" || return 1
        # shellcheck disable=SC2086
        $M4F_CC $M4F_FWFLAGS -I"$d/src" -Wno-error -c "$c" -o "$d/m4f/$b.o" \
            -fstack-usage -fcallgraph-info=su || return 1
    done
    [ "$4" = yes ] || return 0
    # shellcheck disable=SC2086
    $M4F_CC $M4F_LDFLAGS -T mps2_an386.ld $M4F_LDBUDGET $3 \
        -o "$d/fw.elf" "$d"/m4f/*.o $port_obj -lm || return 1
}

# expect <pass|fail> <guard mode> <must-mention> <description> <files...>
expect() {
    want=$1; mode=$2; sym=$3; what=$4; shift 4
    out=$(sh tools/guard.sh "$mode" "guard-$mode" "$@" 2>&1); rc=$?
    if [ "$want" = pass ]; then
        if [ $rc -eq 0 ]; then ok "$what"; else bad "$what"; printf '%s\n' "$out"; fi
    else
        if [ $rc -ne 0 ] && printf '%s\n' "$out" | grep -q -- "$sym"; then
            ok "$what -> $(printf '%s\n' "$out" | grep -m1 -- "$sym" | sed 's/^ *//' | cut -c1-90)"
        else bad "$what (guard did not fail on $sym)"; printf '%s\n' "$out"; fi
    fi
}

if build clean "" "" yes; then
    expect pass alloc - "clean copy passes guard-alloc (host + M4F objects, fw.elf)" \
        "$S"/clean/host/*.o "$S"/clean/m4f/*.o "$S/clean/fw.elf"
    expect pass double - "clean copy passes guard-double (fw.elf)" "$S/clean/fw.elf"
else bad "clean copy did not build"; fi

if build malloc '#include <stdlib.h>
void *selftest_inject_alloc(size_t n);
void *selftest_inject_alloc(size_t n) { return malloc(n); }' "" no; then
    expect fail alloc malloc "injected malloc: host objects" "$S"/malloc/host/*.o
    expect fail alloc malloc "injected malloc: M4F objects" "$S"/malloc/m4f/*.o
else bad "malloc copy did not build"; fi

# The double copy links newlib's sqrt wrapper, which sets errno: that pulls in newlib's
# reentrancy data (_impure_ptr, 104 B of .data) and the soft-double library (a few KB)
# that no product image has. Its RAM and flash lengths are the budgets + 512 B / + 8 KB (a
# later --defsym wins), so it is the guard that judges it, not an overflow of the scratch
# image.
ram=$(printf '%s\n' "$M4F_LDBUDGET" | sed -n 's/.*CP_RAM=\([0-9]*\).*/\1/p')
flash=$(printf '%s\n' "$M4F_LDBUDGET" | sed -n 's/.*CP_FLASH=\([0-9]*\).*/\1/p')
if build double '#include <math.h>
float selftest_inject_double(float x);
float selftest_inject_double(float x) { return (float)sqrt((double)x * 1.5); }' \
        "-Wl,-u,selftest_inject_double -Wl,--defsym=CP_RAM=$((ram + 512)) -Wl,--defsym=CP_FLASH=$((flash + 8192))" yes; then
    expect fail double __aeabi_d "injected double sqrt: fw.elf" "$S/double/fw.elf"
    expect fail double __aeabi_ "injected double sqrt: M4F objects" "$S"/double/m4f/*.o
else bad "double copy did not build"; fi

# guard-fnlen (tools/guard_fnlen.sh): a function of exactly FNLEN_MAX lines, signature to
# closing brace, passes; one line more fails and is named with its file:line and length.
# fnfile <path> <name> <lines>: a C file with a struct, an initializer and that function
fnfile() {
    { echo "struct s {"; echo "    int a;"; echo "};"; echo "static const int t[] = {"
      echo "    1, 2,"; echo "};"; echo ""; echo "int $2(int x);"
      echo "int $2(int x)"; echo "{"; i=4; while [ $i -lt "$3" ]; do echo "    x += $i;"; i=$((i + 1)); done
      echo "    return x + t[0];"; echo "}"; } > "$1"
}
FNLEN_MAX=${FNLEN_MAX:-120}
mkdir -p "$S/fnlen"
fnfile "$S/fnlen/ok.c" fits_exactly "$FNLEN_MAX"
fnfile "$S/fnlen/long.c" one_too_long $((FNLEN_MAX + 1))
out=$(sh tools/guard_fnlen.sh guard-fnlen "$FNLEN_MAX" "$S/fnlen/ok.c" 2>&1)
if [ $? -eq 0 ] && printf '%s\n' "$out" | grep -q '^guard-fnlen: 1 passed, 0 failed$'; then
    ok "guard-fnlen: a $FNLEN_MAX-line function passes"
else bad "guard-fnlen: a $FNLEN_MAX-line function"; printf '%s\n' "$out"; fi
want="$S/fnlen/long.c:9: one_too_long $((FNLEN_MAX + 1)) lines"
out=$(sh tools/guard_fnlen.sh guard-fnlen "$FNLEN_MAX" "$S/fnlen/ok.c" "$S/fnlen/long.c" 2>&1)
if [ $? -ne 0 ] && printf '%s\n' "$out" | grep -qF "$want"; then
    ok "guard-fnlen: a $((FNLEN_MAX + 1))-line function fails -> $(printf '%s\n' "$out" | grep -F "$want" | sed 's/^ *//')"
else bad "guard-fnlen: a $((FNLEN_MAX + 1))-line function (guard did not fail on it)"; printf '%s\n' "$out"; fi

echo "guard-selftest: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
