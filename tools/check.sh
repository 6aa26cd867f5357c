#!/usr/bin/env bash
# The tests, at two depths.
#
#   bash tools/check.sh         installs the dependencies, builds everything in Release but the
#                               benchmark programs and the Python modules and runs the test suite
#                               (ctest) but its five longest tests, the real assets' renders, the
#                               GPU report's quick run, the install and Python module tests and the
#                               cluster tests. Within ten minutes on two cores.
#   bash tools/check.sh --full  then also builds the benchmark programs (trs-bench, trs-dataset) and
#                               the Python modules and runs their tests, those tests and renders;
#                               runs the animation demo
#                               (tools/demo.sh --animation, at 0.25 s a frame); builds the library
#                               alone, without its Vulkan backend, and runs that configuration's
#                               tests; installs the Python modules with pip into a fresh venv,
#                               imports both from it and runs an example; submits animations and a
#                               study to a one-node Slurm cluster of its own (label cluster);
#                               compares the courtyard's punctual lights and the floor lamp's
#                               transmitting shade with Blender's Cycles;
#                               builds everything without OpenImageIO, runs its tests and the GPU
#                               report's quick run from its bundle; builds everything with the
#                               sanitizers and runs the tests under them; and fuzzes the parsers of
#                               user files for a fixed time each.
#   bash tools/check.sh --full --skip-default
#                               only what --full adds, in a checkout where tools/check.sh has just
#                               passed: CI (.ci/run) runs the README's commands first, each on a
#                               clean clone, then this.
# Each stage prints its time.
set -euo pipefail
cd "$(dirname "$0")/.."
full=false default=true
for option in "$@"; do
  case "$option" in
    --full) full=true ;;
    --skip-default) default=false ;;
    *) echo "usage: tools/check.sh [--full [--skip-default]]" >&2; exit 2 ;;
  esac
done
if ! $default && ! $full; then
  echo "tools/check.sh: --skip-default is for --full" >&2
  exit 2
fi
started=$SECONDS
stage() {  # stage NAME: prints the time of the stage before it
  echo "check.sh: ${stage_name:-start} done at $((SECONDS - started)) s; next: $1"
  stage_name=$1
}

bash tools/setup-debian.sh
export LIGHTSAMPLER_REQUIRE_VULKAN=1  # Vulkan tests fail rather than skip without a device
# Run by --full alone, so that the default check stays within ten minutes on two cores, build
# included: the five longest tests, over four minutes of the suite's thirteen (drivers of tools
# that have tests of their own, trs-study and tools/figures; samplers made and dropped sixty
# times, and ten times holding an eighth of the device's memory each; outputs beyond 128 MiB),
# and the real assets' render cases (the shipped and material scenes' stay, but for the
# experimental strategies').
long='trs_study|figures_quick|VulkanTest\.SixtySamplersComeAndGo|VulkanTest\.DroppedSamplersGiveTheirDeviceMemoryBack'
long+='|VulkanSampler\.OutputsBeyond128MiBAnd65535Workgroups|render\.real-.*'
# The experimental strategies' render cases too (their draws have statistical tests of their own),
# uniform sampling's, which take four times the others' samples (tests/CMakeLists.txt), and the
# baselines power's and tree's (statistical tests of their own too): the default check renders
# each scene with trs, ris and auto, which draw from the light sampler and pick among the rest.
long+='|render\..*\.(texel|tree-texel|uniform|power|tree)'
# And the tests that build and install: a project built against the installed package, the
# example strategy plugin built outside the tree and the statistical suites run on it, and the
# Python modules (whose build is --full's too): a minute and a half of the default check.
long+='|install_consumer|strategy_plugin\..*|python_modules'

if $default; then
  stage "default build"
  # The benchmark programs and their tests (with tools/figures --quick) and the Python modules
  # are --full's: a minute and a half of the default check's build.
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DTRS_BUILD_BENCHMARKS=OFF -DTRS_PYTHON=OFF
  cmake --build build
  stage "default tests"
  # All but those, the cluster tests, and the GPU report's quick run, which --full runs from the
  # report's bundle (minutes on a CPU device; the tools it drives have tests of their own here).
  ctest --test-dir build --output-on-failure --timeout 600 -j "$(nproc)" -E "^(gpu_report_quick|$long)\$" -LE cluster
fi
if ! $full; then
  stage "end"
  echo "check.sh: left out here, run by tools/check.sh --full: the benchmark programs and their" \
    "tests, the cluster tests (a local Slurm), the longest tests and the real assets' renders" \
    "($long), the animation demo, the CPU-only build, the Python install, the builds without" \
    "OpenImageIO and with the sanitizers, the fuzzers"
  exit 0
fi

stage "benchmark programs, Python modules and the longest tests"
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DTRS_BUILD_BENCHMARKS=ON -DTRS_PYTHON=ON
cmake --build build
ctest --test-dir build --output-on-failure --timeout 600 -j "$(nproc)" -R "^($long|trs_bench_.*)\$"

stage "animation demo"
# The README's demo in its animation form, shorter per frame: frames, video and summary.
bash tools/demo.sh --animation 0.25
test -s build/demo/animation/video-wall.mp4

stage "CPU-only library"
# The library alone, CPU backend only: it must build, pass its tests and install without Vulkan.
cmake -S . -B build-cpu-only -G Ninja -DCMAKE_BUILD_TYPE=Release -DLIGHTSAMPLER_VULKAN=OFF \
  -DLIGHTSAMPLER_BUILD_TOOLS=OFF
cmake --build build-cpu-only
ctest --test-dir build-cpu-only --output-on-failure --timeout 600 -j "$(nproc)"

stage "Python install"
# The README's Python install line in a fresh venv, offline, from an empty pip build folder (one
# left by an earlier run could hide a missing target); both imports from outside the checkout,
# then the variance example.
rm -rf build-pip
/usr/bin/python3 -m venv --system-site-packages build-pip/venv  # Debian's, with its numpy
build-pip/venv/bin/pip install --no-build-isolation --no-index --quiet .
venv_python=$PWD/build-pip/venv/bin/python
(cd / && "$venv_python" -c "import lightsampler, trs_render; print('imported', lightsampler.__file__, trs_render.__file__)")
(cd build-pip && venv/bin/python ../examples/python/variance.py --quick)

stage "cluster tests"
# Animations and studies through a real Slurm: a one-node cluster started and stopped around
# each test (tests/cluster/with_slurm.sh).
bash tools/setup-debian.sh --cluster
ctest --test-dir build --output-on-failure --timeout 600 -L cluster

stage "Cycles comparison"
# Punctual lights against Blender's Cycles as its glTF importer reads the file: the courtyard's
# mean over its lit pixels, diffuse materials in both (docs/renderer.md, "Punctual lights").
bash tools/setup-debian.sh --blender
/usr/bin/python3 tools/cycles_compare.py scenes/courtyard/courtyard.gltf --render build/bin/trs-render \
  --out build/cycles-compare --diffuse --spp 128 --cycles-spp 128 --tolerance 0.05
# A lamp shade's transmission against Cycles (docs/renderer.md, "The material gallery against
# Blender"): the floor lamp's ratio trs-render / Cycles with its shade transmitting, over the
# same ratio with the shade opaque, within 5%; Lambertian materials, then as authored (whose
# caustics off the smooth shade need the samples).
/usr/bin/python3 tools/cycles_extension_check.py scenes/materials/floor-lamp/floor-lamp.gltf \
  --render build/bin/trs-render --out build/cycles-compare/floor-lamp-diffuse --diffuse --spp 128 \
  --cycles-spp 128 --tolerance 0.05
/usr/bin/python3 tools/cycles_extension_check.py scenes/materials/floor-lamp/floor-lamp.gltf \
  --render build/bin/trs-render --out build/cycles-compare/floor-lamp --spp 512 --cycles-spp 512 \
  --tolerance 0.05

stage "build without OpenImageIO"
# The build without OpenImageIO, which the GPU report carries to machines without the project's
# packages: the tests that read or write image files (the other labels run the same code as in
# the build above, where they passed), then the report's quick run from its bundle
# (tools/gpu-report.sh --bundle), which loads and runs every Vulkan test program of this build.
cmake -S . -B build-noiio -G Ninja -DCMAKE_BUILD_TYPE=Release -DTRS_OPENIMAGEIO=OFF
cmake --build build-noiio
# Of the render cases, one a scene (trs): its textures and reference are read the same way
# whatever the strategy.
ctest --test-dir build-noiio --output-on-failure --timeout 600 -j "$(nproc)" \
  -E '^(gpu_report_quick|render\..*\.(uniform|power|ris|tree|texel|tree-texel|auto|ris-vulkan))$' \
  -LE 'stat|vulkan|smoke|cluster'
bash tools/gpu-report.sh --bundle --build build-noiio
cmake -D ROOT="$PWD" -D BUILD="$PWD/.device" -D OUT="$PWD/build-noiio/gpu-report-bundled" \
  -P tests/gpu_report_quick.cmake

stage "sanitizers"
# Everything but the benchmark programs (their runs above drive the same library) under
# AddressSanitizer and UndefinedBehaviorSanitizer (Clang), and all but the four longest tests
# under them (tools/sanitize.sh says which and why). Line tables are all that a report needs, and
# build faster than full debug information.
cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
  -DTRS_SANITIZE=ON -DTRS_BUILD_BENCHMARKS=OFF "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -gline-tables-only -DNDEBUG"
cmake --build build-sanitize
bash tools/sanitize.sh

stage "fuzzers"
# The parsers of user files under libFuzzer, AddressSanitizer and UndefinedBehaviorSanitizer
# (Clang), each for a fixed time from its corpus (fuzz/README.md).
cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
  -DTRS_FUZZ=ON -DLIGHTSAMPLER_VULKAN=OFF -DLIGHTSAMPLER_BUILD_TESTS=OFF
cmake --build build-fuzz --target fuzz_obj fuzz_gltf fuzz_glb fuzz_settings fuzz_density
bash tools/fuzz.sh 30
stage "end"
