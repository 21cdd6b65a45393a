#!/usr/bin/env bash
# armkit's kinematics and mass-matrix benches and Pinocchio 4.1 C++ on the
# same robots, alternated (default twice), so that a ratio is measured in one
# run. Needs ../shared/peers set up: ./setup.sh, .venv/bin/python
# make_reference.py, ./build_bench_pinocchio.sh (its README).
# Usage: scripts/bench-vs-pinocchio.sh [rounds]
set -euo pipefail
cd "$(dirname "$0")/.."
peers="$(pwd)/../shared/peers"
rounds="${1:-2}"
kinematics='^(fk/ur5|fk/panda|fk\+jacobian/ur5|fk\+jacobian/panda|fk-batch/ur5/1024|fk-batch/panda/1024|jacobian-batch/ur5/1024|jacobian-batch/panda/1024)$'
for round in $(seq 1 "$rounds"); do
  echo "=== round $round $(date -u +%H:%M:%S), load average $(cut -d' ' -f1-3 /proc/loadavg)"
  cargo bench -q -p armkit --bench kinematics -- --noplot "$kinematics" 2>&1 | grep -E "^(fk|jacobian)|time:"
  cargo bench -q -p armkit --bench dynamics -- --noplot '^crba/(ur5|panda)$' 2>&1 | grep -E "^crba|time:"
  (cd "$peers" && .venv/bin/python bench_cpp.py --robots ur5,panda --reps 5 | tail -8)
done
