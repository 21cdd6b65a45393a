#!/usr/bin/env bash
# Runs every fuzz target for SECONDS (default 600) one after the other, then
# minimises each corpus. Needs cargo-fuzz (`cargo install cargo-fuzz`); on a
# stable toolchain RUSTC_BOOTSTRAP=1 lets it use the sanitizer flags.
#   fuzz/run-all.sh [SECONDS] [TARGET...]
# Logs go to fuzz/logs/<target>.log (not committed); crashes to fuzz/artifacts/.
set -uo pipefail
cd "$(dirname "$0")"
seconds=${1:-600}
shift || true
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(urdf description scenario scenario_tables cli_numbers dynamics_command ik_command)
export RUSTC_BOOTSTRAP=1
mkdir -p logs
for target in "${targets[@]}"; do
  echo "== $target: ${seconds} s"
  nice cargo fuzz run ${FUZZ_TARGET_DIR:+--target-dir "$FUZZ_TARGET_DIR"} "$target" "corpus/$target" -- \
    -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    >"logs/$target.log" 2>&1
  echo "   exit $?: $(grep -E '^Done|stat::number_of_executed_units' "logs/$target.log" | tr '\n' ' ')"
  cargo fuzz cmin ${FUZZ_TARGET_DIR:+--target-dir "$FUZZ_TARGET_DIR"} "$target" "corpus/$target" \
    >"logs/cmin-$target.log" 2>&1
  echo "   corpus minimised: $(ls "corpus/$target" | wc -l) files"
done
