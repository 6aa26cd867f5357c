#!/usr/bin/env bash
# Installs every Debian 12 package the project builds, tests and runs with; with --video also
# ffmpeg, which only the animation demo (tools/demo.sh --animation) uses; with --blender also
# Blender, whose Cycles renders the reference that tools/cycles_compare.py checks against
# (tools/check.sh --full); with --cluster also Slurm and MUNGE, with which tools/slurm-local.sh
# runs a one-node cluster for the tests labelled `cluster` (tests/cluster/with_slurm.sh).
# Idempotent: does nothing when all of them are present. Needs root (or sudo).
set -euo pipefail

packages=(
  # build
  build-essential cmake ninja-build pkg-config
  # renderer and image stack
  libembree-dev libopenimageio-dev openimageio-tools libopenexr-dev libopencolorio-dev
  libtbb-dev libglm-dev
  # Debian's Imath CMake package names the Python binding's library; without it every configure
  # warns about a missing file
  python3-imath
  # Vulkan backend: loader, headers, shader compiler, software device for tests
  libvulkan-dev glslang-tools spirv-tools mesa-vulkan-drivers vulkan-validationlayers
  # small libraries
  libtinygltf-dev libtinyobjloader-dev nlohmann-json3-dev libcli11-dev libstb-dev
  # the noise study (trs-study): arrays, plots, EXR reading
  python3-numpy python3-matplotlib python3-openimageio
  # the Python modules (lightsampler, trs_render), their tests, and pip install from a checkout
  pybind11-dev python3-dev python3-pytest python3-venv python3-pip python3-wheel
  # tests and benchmarks
  libgtest-dev libgmock-dev libbenchmark-dev
  # fuzzing (libFuzzer and the sanitizer runtimes of Clang)
  clang libclang-rt-14-dev
)
for option in "$@"; do
  case "$option" in
    --video) packages+=(ffmpeg fonts-dejavu-core) ;;
    --blender) packages+=(blender) ;;
    # slurmctld, slurmd and the client commands (slurm-wlm), munged and its key tool (munge)
    --cluster) packages+=(slurm-wlm munge) ;;
    *) echo "usage: tools/setup-debian.sh [--video] [--blender] [--cluster]" >&2; exit 2 ;;
  esac
done

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
echo "Installing: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
