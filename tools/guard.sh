#!/bin/sh
# guard.sh - symbol and warning guards of the firmware; each prints ONE line
# "<word>: N passed, N failed" (plus the offenders) and exits non-zero on failure.
# SPDX-License-Identifier: MIT
#
#   guard.sh alloc  <word> <objects/ELFs...>   no heap, stdio or process exit
#   guard.sh double <word> <objects/ELFs...>   no double-precision helpers (M4F files)
#   guard.sh warn   <word> <sources...>        clang + gcc -fsyntax-only with $WARN
#
# alloc/double use nm on every file (defined OR undefined symbols both count):
# a file nm cannot read is a failure, never a silent pass. ARM files go through
# $NM (arm-none-eabi-nm), host objects through the native nm ($HOST_NM).
# The result is ONE check: "1 passed, 0 failed" or "0 passed, 1 failed" plus
# every offending file and symbol.
# warn: env CC, CLANG, M4F_CC, WARN, INC. hal/posix and host_sim-style files get
# -D_XOPEN_SOURCE=600; hal/cortex-m goes through clang --target=arm-none-eabi
# (newlib headers) and arm-none-eabi-gcc instead of the host compilers.
# tools/guard_selftest.sh runs the same code on injected offenders.

mode=$1; word=$2; shift 2
NM=${NM:-arm-none-eabi-nm}
HOST_NM=${HOST_NM:-nm}

# Banned symbols. alloc: heap, stdio and process exit (firmware must neither
# allocate, print, nor stop the machine). newlib's reentrant _r variants too.
ALLOC_RE='^_*(malloc|calloc|realloc|free|printf|sprintf|snprintf|vprintf|vsnprintf|puts|putchar|exit|abort|_sbrk|sbrk|_malloc_r|_calloc_r|_realloc_r|_free_r|_printf_r|_sprintf_r|_snprintf_r|_puts_r|_putchar_r|_exit|__assert_func|__assert_fail)$'
# double: every ARM EABI double-precision helper (__aeabi_d*: dadd, dmul, ddiv,
# dcmp*, d2f, d2iz, ...) and every conversion INTO double (f2d, i2d, ui2d, l2d, ul2d).
DOUBLE_RE='^__aeabi_(d[a-z0-9]*|[a-z]*2d)$'

pass=0; fail=0
case $mode in
alloc|double)
    if [ "$mode" = alloc ]; then re=$ALLOC_RE; else re=$DOUBLE_RE; fi
    bad=0
    for f in "$@"; do
        if ! list=$($NM "$f" 2>/dev/null) && ! list=$($HOST_NM "$f" 2>/dev/null); then
            echo "  $f: unreadable by $NM and $HOST_NM"; bad=1; continue
        fi
        syms=$(printf '%s\n' "$list" | awk '{print $NF}' | grep -E "$re" | sort -u | tr '\n' ' ')
        if [ -n "$syms" ]; then
            echo "  $f: $syms"; bad=1
        fi
    done
    if [ $# -eq 0 ]; then echo "  no files given"; bad=1; fi
    if [ $bad -eq 0 ]; then pass=1; else fail=1; fi
    ;;
warn)
    : "${CC:=cc}" "${CLANG:=clang}" "${M4F_CC:=arm-none-eabi-gcc}"
    ARM_INC=$(echo | $M4F_CC -mcpu=cortex-m4 -xc -E -v - 2>&1 | awk '/^#include <...>/{f=1;next} /^End of/{f=0} f{print "-isystem " $1}')
    ARM_CPU="-mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16"
    for f in "$@"; do
        case $f in
        hal/cortex-m/*)
            set -- "$CLANG --target=arm-none-eabi $ARM_CPU -nostdinc $ARM_INC" "$M4F_CC $ARM_CPU"
            extra="-Ihal/cortex-m" ;;
        hal/posix/*|host_sim/*)
            set -- "$CLANG" "$CC"; extra="-D_XOPEN_SOURCE=600" ;;
        *)
            set -- "$CLANG" "$CC"; extra="" ;;
        esac
        for cc in "$1" "$2"; do
            # shellcheck disable=SC2086
            if msg=$($cc $WARN $INC $extra -fsyntax-only "$f" 2>&1) && [ -z "$msg" ]; then
                pass=$((pass + 1))
            else
                echo "  ${cc%% *}: $f"; printf '%s\n' "$msg" | sed 's/^/    /' | head -20
                fail=$((fail + 1))
            fi
        done
    done
    ;;
*)
    echo "usage: guard.sh alloc|double|warn <word> files..."; exit 2 ;;
esac
echo "$word: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
