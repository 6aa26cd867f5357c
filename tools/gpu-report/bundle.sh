#!/usr/bin/env bash
# bundle.sh BUILD DEST: packs the GPU report's programs from BUILD/bin into DEST for a machine
# that has a GPU driver and nothing else: DEST/bin/ the programs, DEST/libraries.tar.gz the
# shared libraries they load (all but the C and C++ runtimes, which such a machine has), the
# Vulkan loader and the Khronos validation layer. tools/gpu-report.sh --build DEST unpacks it.
set -euo pipefail
build=$1 dest=$2
source "$(dirname "$0")/programs.sh"
limit_mib=60  # what a remote call can carry, with room for the checkout

for program in "${report_programs[@]}"; do
  [ -x "$build/bin/$program" ] || { echo "gpu-report --bundle: $build/bin/$program is missing (build it first)" >&2; exit 1; }
done
stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
mkdir -p "$stage/lib" "$stage/layers"
rm -rf "$dest"; mkdir -p "$dest/bin"

runtime='^(linux-vdso|ld-linux|libc\.so|libm\.so|libstdc\+\+|libgcc_s|libpthread|libdl\.so|librt\.so)'
for program in "${report_programs[@]}"; do
  cp "$build/bin/$program" "$dest/bin/"
  ldd "$build/bin/$program" | awk '$3 ~ /^\// { print $1, $3 }' | while read -r name path; do
    [[ "$name" =~ $runtime ]] || cp -L "$path" "$stage/lib/$name"
  done
done

layer=/usr/lib/x86_64-linux-gnu/libVkLayer_khronos_validation.so
manifest=/usr/share/vulkan/explicit_layer.d/VkLayer_khronos_validation.json
if [ ! -f "$layer" ] || [ ! -f "$manifest" ]; then
  echo "gpu-report --bundle: the validation layer is not installed (Debian: vulkan-validationlayers)" >&2
  exit 1
fi
cp "$layer" "$stage/layers/"
sed 's#"library_path": *"[^"]*"#"library_path": "./libVkLayer_khronos_validation.so"#' "$manifest" \
  > "$stage/layers/VkLayer_khronos_validation.json"

tar -czf "$dest/libraries.tar.gz" -C "$stage" lib layers
size_mib=$(du -sm "$dest" | cut -f1)
if [ "$size_mib" -gt "$limit_mib" ]; then
  echo "gpu-report --bundle: the bundle is $size_mib MiB, more than $limit_mib: build the programs without" \
       "OpenImageIO, whose libraries alone come to hundreds of MiB (cmake -DTRS_OPENIMAGEIO=OFF)" >&2
  rm -rf "$dest"
  exit 1
fi
echo "gpu-report: bundle of $size_mib MiB in $dest; on the GPU machine: bash tools/gpu-report.sh --build $(basename "$dest") OUT_DIR"
