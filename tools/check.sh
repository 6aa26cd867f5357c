#!/usr/bin/env bash
# Installs the dependencies, builds everything and runs the whole test suite (ctest); then builds
# the library without its Vulkan backend and runs the tests of that configuration.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/setup-debian.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build
export LIGHTSAMPLER_REQUIRE_VULKAN=1  # Vulkan tests fail rather than skip without a device
ctest --test-dir build --output-on-failure --timeout 600 -j "$(nproc)"
# The library alone, CPU backend only: it must build, pass its tests and install without Vulkan.
cmake -S . -B build-cpu-only -G Ninja -DCMAKE_BUILD_TYPE=Release -DLIGHTSAMPLER_VULKAN=OFF \
  -DLIGHTSAMPLER_BUILD_TOOLS=OFF
cmake --build build-cpu-only
ctest --test-dir build-cpu-only --output-on-failure --timeout 600 -j "$(nproc)"
