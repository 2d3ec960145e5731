#!/bin/sh
# gen_status_md.sh - print the status-code table of docs/PROTOCOL.md from the one
# source of truth, firmware/base/cp_status.def. `make guard-docs` fails if the table in
# docs/PROTOCOL.md differs from this output.
# SPDX-License-Identifier: MIT
echo "| code | name | text on the wire |"
echo "|---:|---|---|"
sed -n 's/^CP_STATUS(\([A-Z_]*\), *\([0-9]*\), *"\(.*\)", *[A-Z_]*)$/| \2 | \1 | `\3` |/p' "${1:-firmware/base/cp_status.def}"
