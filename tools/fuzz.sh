#!/usr/bin/env bash
# Runs every fuzz target of BUILD (default build-fuzz; fuzz/README.md) for SECONDS each (default
# 30), seed 1, from fuzz/corpus/TARGET, as many at once as there are cores (each libFuzzer run
# takes one); new inputs go to BUILD/corpus/TARGET, failing ones to BUILD/artifacts/. Prints each
# target's summary in order, and exits non-zero if any target failed.
#   tools/fuzz.sh [SECONDS [BUILD]]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-30}
build=${2:-build-fuzz}
export LSAN_OPTIONS="suppressions=$PWD/fuzz/lsan.supp:print_suppressions=0"
targets=(obj gltf glb settings density)
mkdir -p "$build/artifacts" "$build/fuzz-logs"
rm -f "$build"/fuzz-logs/*.passed
fuzz() {  # fuzz TARGET: one target's run, its log in BUILD/fuzz-logs; the fuzzer's exit status
  mkdir -p "$build/corpus/$1"
  "$build/bin/fuzz_$1" -max_total_time="$seconds" -seed=1 -timeout=10 -rss_limit_mb=4096 -malloc_limit_mb=4096 \
    -print_final_stats=1 -artifact_prefix="$build/artifacts/$1-" \
    "$build/corpus/$1" "fuzz/corpus/$1" >"$build/fuzz-logs/$1.log" 2>&1
}
export -f fuzz
export build seconds
printf '%s\n' "${targets[@]}" | xargs -P "$(nproc)" -I{} bash -c 'fuzz {} && touch "$build/fuzz-logs/{}.passed"' || true
failed=0
for target in "${targets[@]}"; do
  echo "fuzz_$target: $seconds s"
  grep -E "^(#|stat::|==|SUMMARY|INFO: Seed)" "$build/fuzz-logs/$target.log" | tail -6 || true
  if [ ! -e "$build/fuzz-logs/$target.passed" ]; then
    echo "fuzz_$target failed: $build/fuzz-logs/$target.log" >&2
    failed=1
  fi
  rm -f "$build/fuzz-logs/$target.passed"
done
exit "$failed"
