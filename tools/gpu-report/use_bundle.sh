# shellcheck shell=bash
# Sourced by tools/gpu-report.sh to run from a bundle (--bundle): unpacks its libraries into
# BUNDLE_LIBS (a temporary directory the caller removes) and points the loader and the programs
# at them.
tar -xzf "$1/libraries.tar.gz" -C "$BUNDLE_LIBS"
export LD_LIBRARY_PATH="$BUNDLE_LIBS/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" VK_LAYER_PATH="$BUNDLE_LIBS/layers"
# Container runtimes mount NVIDIA's driver manifest where the loader does not look.
nvidia_icd=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
if [ -f "$nvidia_icd" ]; then
  export VK_ADD_DRIVER_FILES="$nvidia_icd${VK_ADD_DRIVER_FILES:+:$VK_ADD_DRIVER_FILES}"
fi
