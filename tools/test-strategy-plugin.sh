#!/usr/bin/env bash
# Runs the statistical tests every registered strategy passes (the light samples against the pdf,
# the MIS weights, the pdf's normalisation, renders against quadratures, a change of emission) on
# the strategies of plugin LIB.so alone, with the test programs of build folder BUILD (default
# build; they are built first).
#   tools/test-strategy-plugin.sh LIB.so [BUILD]
set -euo pipefail
plugin=$(realpath "$1")
cd "$(dirname "$0")/.."
build=${2:-build}
suites=(mis_test integrator_test animation_test)
cmake --build "$build" --target "${suites[@]}"
export TRS_STRATEGY_PLUGIN=$plugin
for suite in "${suites[@]}"; do
  echo "test-strategy-plugin: $suite"
  "$build/bin/$suite" --gtest_brief=1
done
