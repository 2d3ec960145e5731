#!/bin/sh
# readme_example.sh - the C example of README.md must compile and run against the
# firmware (littlefs test-example style). Prints "readme: N passed, N failed".
# SPDX-License-Identifier: MIT
BUILD=${BUILD:-build}
d=$BUILD/readme; mkdir -p "$d"
{
    echo '#include <stdio.h>'
    echo '#include "canal_path.h"'
    echo 'static unsigned long n_sent;'
    echo 'static void send(cp_real x, cp_real y, cp_real z) { (void)x; (void)y; (void)z; n_sent++; }'
    echo 'int main(void) {'
    sed -n '/^```c$/,/^```$/p' README.md | sed '1d;$d'
    printf '%s\n' 'printf("readme example: %lu points of %lu\n", n_sent, (unsigned long)canal_path_count(&tp));'
    echo 'return n_sent == 0 || n_sent != canal_path_count(&tp); }'
} > "$d/example.c"
if ${CC:-cc} -std=c99 -Wall -Wextra -Werror -Wno-unused-result $(for d in firmware/*/; do printf -- "-I%s " "$d"; done) -o "$d/example" "$d/example.c" \
        firmware/models/canal.c firmware/models/canal_path.c firmware/models/raster.c firmware/base/cp_math.c -lm && "$d/example"; then
    echo "readme: 1 passed, 0 failed"
else
    echo "readme: 0 passed, 1 failed"; exit 1
fi
