#!/usr/bin/env bash
# Runs every fuzz target of BUILD (default build-fuzz; fuzz/README.md) for SECONDS each (default
# 30), seed 1, from fuzz/corpus/TARGET; new inputs go to BUILD/corpus/TARGET, failing ones to
# BUILD/artifacts/. Exits non-zero on the first target that fails.
#   tools/fuzz.sh [SECONDS [BUILD]]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-30}
build=${2:-build-fuzz}
export LSAN_OPTIONS="suppressions=$PWD/fuzz/lsan.supp:print_suppressions=0"
for target in obj gltf glb settings density; do
  mkdir -p "$build/corpus/$target" "$build/artifacts"
  echo "fuzz_$target: $seconds s"
  "$build/bin/fuzz_$target" -max_total_time="$seconds" -seed=1 -timeout=10 -rss_limit_mb=4096 -malloc_limit_mb=4096 \
    -print_final_stats=1 -artifact_prefix="$build/artifacts/$target-" \
    "$build/corpus/$target" "fuzz/corpus/$target" 2>&1 | grep -E "^(#|stat::|==|SUMMARY|INFO: Seed)" | tail -6
  test "${PIPESTATUS[0]}" -eq 0
done
