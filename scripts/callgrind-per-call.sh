#!/bin/bash
# Instructions per call of one function inside one criterion bench, by callgrind.
#
#   scripts/callgrind-per-call.sh BENCH_BINARY 'BENCH_FILTER' ['FUNCTION_REGEX']
#
# BENCH_BINARY: a criterion bench binary (`cargo bench -p armkit --bench ik --no-run`
# prints it, target/release/deps/ik-<hash>); BENCH_FILTER: a criterion filter
# ('ik/analytic/one_pair_5_6_elimination/distinct$'); FUNCTION_REGEX: the function
# whose inclusive instructions are summed over its calls (default
# 'AnalyticSolver::solve$'). Prints the calls and instructions per call.
# Used for the README's "instructions per solve" columns: unlike wall-clock time
# on a shared VM, the count is the same from run to run (to ~1 % with code layout).
set -euo pipefail
if [ $# -lt 2 ]; then
    sed -n '2,12p' "$0"
    exit 2
fi
command -v valgrind >/dev/null || { echo "valgrind is not installed" >&2; exit 2; }
out=$(mktemp /tmp/callgrind.XXXXXX)
trap 'rm -f "$out"' EXIT
valgrind --tool=callgrind --callgrind-out-file="$out" "$1" --bench "$2" --profile-time 1 >/dev/null 2>&1
python3 - "$out" "${3:-AnalyticSolver::solve\$}" "$2" <<'PY'
import re
import sys

path, function, label = sys.argv[1:4]
wanted = re.compile(function)
names = {}
callee = None
calls = 0
inclusive = 0
pending = False
for line in open(path).read().split("\n"):
    named = re.match(r"(c?fn)=\((\d+)\)(?: (.*))?$", line)
    if named:
        if named.group(3):
            names[named.group(2)] = named.group(3)
        if named.group(1) == "cfn":
            callee = names.get(named.group(2), "")
        continue
    if line.startswith("calls="):
        pending = bool(callee and wanted.search(callee))
        if pending:
            calls += int(line.split("=")[1].split()[0])
        continue
    if pending:
        parts = line.split()
        if len(parts) >= 2:
            inclusive += int(parts[1])
        pending = False
if calls == 0:
    sys.exit(f"no call of {function!r} in the bench(es) matching {label!r} (the binary's --list names them)")
print(f"{label}: calls {calls} instructions/call {inclusive // calls}")
PY
