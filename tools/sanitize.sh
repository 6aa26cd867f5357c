#!/usr/bin/env bash
# Runs the test suite of BUILD (default build-sanitize, configured with -DTRS_SANITIZE=ON; README
# "Tests") under AddressSanitizer, LeakSanitizer and UndefinedBehaviorSanitizer, lavapipe
# included. Any report fails its test, also from a tool that a test runs as a subprocess: those
# exit 99, a status no test expects. The cluster tests (a local Slurm driving the same tools) are
# not run here. Without --all, four tests and the real assets' renders are left out to keep CI
# within its time; --all runs every test.
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
  # The real assets' renders, minutes under AddressSanitizer: the same renderer and loaders run
  # in the shipped and material scenes' render cases, and the fuzzers feed the loaders.
  'render\.real-.*'
  # The shipped scenes' render cases but those of the strategies `auto` chooses between (trs,
  # ris) and `auto`'s own: the renderer and loaders under the others run in these.
  'render\..*\.(uniform|power|tree|texel|tree-texel)'
)
filter=(-E "^($(IFS='|'; echo "${exclude[*]}"))\$")
if [ "${1:-}" = --all ]; then
  filter=()
  shift
fi
build=${1:-build-sanitize}
# intercept_tls_get_addr=0: LeakSanitizer then leaves the dynamic TLS of libraries loaded at run
# time (lavapipe's, and LLVM's within it) out of its scan. With it tracked, its stop-the-world
# tracer crashed at exit ("Tracer caught signal 11", google/sanitizers#1353) in 7 of 9 runs of
# VulkanSampler.SamplesFollowTheDensity after the test had passed; without, in none of 9.
export ASAN_OPTIONS="exitcode=99:intercept_tls_get_addr=0"
export UBSAN_OPTIONS="print_stacktrace=1"
export LSAN_OPTIONS="suppressions=$PWD/fuzz/lsan.supp:print_suppressions=0"
export LIGHTSAMPLER_REQUIRE_VULKAN=1  # Vulkan tests fail rather than skip without a device
ctest --test-dir "$build" --output-on-failure --timeout 1200 -j "$(nproc)" -LE cluster "${filter[@]}"
