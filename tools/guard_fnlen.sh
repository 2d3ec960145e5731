#!/bin/sh
# guard_fnlen.sh - no C function longer than a limit (issue 16: 120 lines in firmware/
# and host_sim/). Prints every function over the limit as "file:line: name N lines"
# and ONE line "<word>: N passed, N failed" (one check per file: it passes when every
# function definition in it is within the limit);
# exits 1 on any failure.
# SPDX-License-Identifier: MIT
#
# Usage: guard_fnlen.sh <word> <max lines> <files...>
#
# No parser, no ctags: the house style (.clang-format BreakBeforeBraces: Linux) puts a
# function body's `{` and `}` at column 0 and nothing else there (struct, enum and
# initializer braces open at the end of their line and close with `};` or `} name;`).
# A body starts at a line that is exactly `{` (or a column-0 signature line ending in
# `) {`) whose signature -- the column-0 text since the previous blank line, comment,
# preprocessor line, `}` or `;` -- has a `(` and no `= {`; it ends at the next line that
# starts with `}`. Length = the lines of the definition, signature to closing brace
# (host_sim main 456, drc_path_init 137, canal_init 124, job_line 109 on 2026-11-26,
# as issue 16 counts them). The name is the identifier before the signature's first
# `(`. A body with no column-0 `}` before the end of its file is a failure too.
# tools/guard_selftest.sh proves a (max+1)-line function fails and a max-line one passes.
word=$1; max=$2; shift 2
[ $# -gt 0 ] || { echo "  no files given"; echo "$word: 0 passed, 1 failed"; exit 1; }
awk -v max="$max" -v word="$word" '
    function name_of(sig,   s, n, w) {
        s = substr(sig, 1, index(sig, "(") - 1); sub(/[ \t]+$/, "", s)
        n = split(s, w, /[^A-Za-z0-9_]+/); return w[n] }
    function unclosed() { if (inbody) { badf[file] = 1; printf "  %s:%d: %s: no closing brace at column 0\n", file, start, nm } }
    FNR == 1 { unclosed(); inbody = 0; sig = ""; sigdone = 0; file = FILENAME; files[file] = 1 }
    # column-0 text outside a body: a signature (or a declaration: it ends with `;`)
    !inbody && /^[A-Za-z_]/ { if (sig == "" || sigdone) { sig = ""; sigl = FNR; sigdone = 0 }
        sig = sig " " $0; if ($0 ~ /;[ \t]*$/) sigdone = 1 }
    !inbody && /^[ \t]/ && sig != "" && !sigdone { sig = sig " " $0; if ($0 ~ /;[ \t]*$/) sigdone = 1 }
    !inbody && (/^\{[ \t]*$/ || (/^[A-Za-z_].*\)[ \t]*\{[ \t]*$/ && $0 !~ /=/)) {
        if (sig != "" && !sigdone && index(sig, "(") && sig !~ /=[ \t]*(\{|$)/) {
            inbody = 1; start = sigl; nm = name_of(sig) }
        sig = ""; sigdone = 0; next }
    !inbody && (/^$/ || /^#/ || /^\}/ || /^\/[\/*]/ || /^ \*/) { sig = ""; sigdone = 0 }
    inbody && /^\}/ { inbody = 0; len = FNR - start + 1
        if (len > max) { badf[file] = 1; printf "  %s:%d: %s %d lines (limit %d)\n", file, start, nm, len, max } }
    END { unclosed(); for (f in files) { if (f in badf) bad++; else good++ }
          printf "%s: %d passed, %d failed\n", word, good, bad; exit (bad > 0) }
' "$@"
