#!/usr/bin/env bash
# The main job: installs the dependencies, builds in Release, and samples the demo neon panel
# with Triangle Rejection Sampling and with plain rejection sampling, side by side.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/setup-debian.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build
out=build/demo
mkdir -p "$out"
mesh=scenes/demo/neon-panel.obj
density=scenes/demo/neon.png
for method in trs rs; do
  echo "== $method: 10 million samples =="
  build/bin/trs-sample "$mesh" "$density" --count 1e7 --method "$method" --seed 1 --stats "$out/$method.json"
  echo
done
echo "== trs: 100 thousand samples written as a point cloud =="
build/bin/trs-sample "$mesh" "$density" --count 1e5 --seed 2 --out "$out/neon-samples.ply" --stats "$out/neon-samples.json"
echo "Outputs in $out/"
