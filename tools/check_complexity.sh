#!/bin/sh
# Complexity gate: fails when any function, method or class under src/ gets radon's
# cyclomatic-complexity grade D or worse (complexity 21+). Split such blocks into
# small functions with one job. Usage: RADON=.venv/bin/radon sh tools/check_complexity.sh
set -eu
RADON="${RADON:-radon}"
out=$("$RADON" cc -n D src)
if [ -n "$out" ]; then
    echo "too complex (radon grade D or worse); split these:" >&2
    echo "$out" >&2
    exit 1
fi
