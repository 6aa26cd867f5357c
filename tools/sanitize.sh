#!/usr/bin/env bash
# Runs the test suite of BUILD (default build-sanitize, configured with -DTRS_SANITIZE=ON; README
# "Tests") under AddressSanitizer, LeakSanitizer and UndefinedBehaviorSanitizer, lavapipe
# included. Any report fails its test, also from a tool that a test runs as a subprocess: those
# exit 99, a status no test expects. The cluster tests (a local Slurm driving the same tools) are
# not run here. Without --all, four tests are left out to keep CI within
# its time; --all runs every test.
# LeakSanitizer's own stop-the-world tracer now and then crashes at a process's exit ("Tracer
# caught signal 11", google/sanitizers#1353) with lavapipe's threads alive, after the test has
# passed; that is no finding about the code. A test that failed only so is run once more and
# must then pass; any other failure fails at once.
#   tools/sanitize.sh [--all] [BUILD]
set -euo pipefail
cd "$(dirname "$0")/.."
exclude=(
  # The same sampler made and dropped 200 times; each one's pipelines are compiled by lavapipe,
  # whose allocations all go through AddressSanitizer: over ten minutes on two cores, where every
  # other Vulkan test makes and drops samplers too.
  VulkanTest.SixtySamplersComeAndGo
  # Drivers of the tools (trs-study: trs-render and trs-imgdiff; tools/figures: trs-bench and
  # trs-sample; the GPU report: all of them and the Vulkan tests), minutes each; the cli, render,
  # smoke and vulkan tests run those tools and tests.
  trs_study
  figures_quick
  gpu_report_quick
)
filter=(-E "^($(IFS='|'; echo "${exclude[*]}"))\$")
if [ "${1:-}" = --all ]; then
  filter=()
  shift
fi
build=${1:-build-sanitize}
export ASAN_OPTIONS="exitcode=99"
export UBSAN_OPTIONS="print_stacktrace=1"
export LSAN_OPTIONS="suppressions=$PWD/fuzz/lsan.supp:print_suppressions=0"
export LIGHTSAMPLER_REQUIRE_VULKAN=1  # Vulkan tests fail rather than skip without a device
junit="$build/sanitize-junit.xml"
if ctest --test-dir "$build" --output-on-failure --timeout 1200 -j "$(nproc)" -LE cluster \
  --output-junit "$PWD/$junit" "${filter[@]}"; then
  exit 0
fi
tracer_only=$(/usr/bin/python3 tools/common/lsan_tracer_crashes.py "$junit") || exit 1
echo "Only LeakSanitizer's tracer crashed, in: $tracer_only; running those once more"
ctest --test-dir "$build" --output-on-failure --timeout 1200 -R "^($tracer_only)\$"
