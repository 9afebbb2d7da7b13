#!/usr/bin/env bash
# Builds the libFuzzer targets in a configured fuzz build directory (cmake -DHBOS_FUZZ=ON, Clang)
# and runs each for a bounded time on a copy of its seed corpus; exits non-zero on any finding
# (a crash, an ASan/UBSan report, a broken promise, a timeout or a leak), leaving the input in
# <build>/fuzz-artifacts/. Two fuzzers run at a time (CI has two cores).
#   bash tests/fuzz/run_fuzzers.sh BUILD_DIR [SECONDS_PER_TARGET] [TARGET...]
set -euo pipefail
build=${1:?usage: run_fuzzers.sh BUILD_DIR [SECONDS] [TARGET...]}
seconds=${2:-60}
shift $(( $# >= 2 ? 2 : 1 ))
here=$(cd "$(dirname "$0")" && pwd)
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  targets=(fuzz_library fuzz_screen fuzz_model_file fuzz_csv_reader fuzz_trajectory_reader
           fuzz_camera_reader)
fi
cmake --build "$build" -j2 --target "${targets[@]}"
mkdir -p "$build/fuzz-artifacts" "$build/fuzz-logs"
run_one() {
  local t=$1 corpus="$build/fuzz-corpus/$1"
  rm -rf "$corpus" && mkdir -p "$corpus"
  cp "$here/corpus/$t/"* "$corpus/"
  "$build/tests/fuzz/$t" "$corpus" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -print_final_stats=1 -artifact_prefix="$build/fuzz-artifacts/$t-" >"$build/fuzz-logs/$t.log" 2>&1
}
failed=0
pids=() names=()
for t in "${targets[@]}"; do
  run_one "$t" &
  pids+=($!) names+=("$t")
  if [ ${#pids[@]} -eq 2 ]; then
    for i in 0 1; do
      if ! wait "${pids[$i]}"; then failed=1; echo "FINDING in ${names[$i]}:"; tail -40 "$build/fuzz-logs/${names[$i]}.log"; fi
    done
    pids=() names=()
  fi
done
for i in "${!pids[@]}"; do
  if ! wait "${pids[$i]}"; then failed=1; echo "FINDING in ${names[$i]}:"; tail -40 "$build/fuzz-logs/${names[$i]}.log"; fi
done
for t in "${targets[@]}"; do
  printf '%-24s %s\n' "$t" "$(grep -E 'stat::number_of_executed_units' "$build/fuzz-logs/$t.log" | awk '{print $2 " executions"}')"
done
if [ "$failed" -ne 0 ]; then echo "fuzzing: findings (inputs in $build/fuzz-artifacts)"; exit 1; fi
echo "fuzzing: ${#targets[@]} passed, 0 failed"
