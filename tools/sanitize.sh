#!/usr/bin/env bash
# Runs the whole test suite of BUILD (default build-sanitize, configured with -DTRS_SANITIZE=ON;
# README "Tests") under AddressSanitizer, LeakSanitizer and UndefinedBehaviorSanitizer, lavapipe
# included. Any report fails its test, also one from a tool that a test runs as a subprocess:
# those exit 99, a status no test expects.
#   tools/sanitize.sh [BUILD]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build-sanitize}
export ASAN_OPTIONS="exitcode=99"
export UBSAN_OPTIONS="print_stacktrace=1"
export LSAN_OPTIONS="suppressions=$PWD/fuzz/lsan.supp:print_suppressions=0"
export LIGHTSAMPLER_REQUIRE_VULKAN=1  # Vulkan tests fail rather than skip without a device
# Twice the Release run's limit: tests take up to twelve times as long as in Release
# (VulkanTest.TwoHundredSamplersComeAndGo, four minutes on two cores: lavapipe compiles the
# pipelines of its 200 samplers through AddressSanitizer's allocator).
ctest --test-dir "$build" --output-on-failure --timeout 1200 -j "$(nproc)"
