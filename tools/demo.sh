#!/usr/bin/env bash
# The main job: installs the dependencies, builds in Release, renders the demo scene (a neon sign
# lighting a room) with uniform light sampling and with Triangle Rejection Sampling at equal
# samples per pixel, and prints how much less noisy TRS is. Then samples the demo neon panel
# with the light sampler alone: TRS against plain rejection sampling.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/setup-debian.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build
out=build/demo
mkdir -p "$out"

scene=scenes/neon-sign
for strategy in uniform trs; do
  echo "== render: $strategy =="
  build/bin/trs-render "$scene/neon-sign.gltf" --settings "$scene/render.toml" \
    --strategy "$strategy" --out "$out/neon-sign-$strategy.exr" \
    --preview "$out/neon-sign-$strategy.png" --stats "$out/neon-sign-$strategy.json"
  echo
done
python3 - "$out/neon-sign-uniform.json" "$out/neon-sign-trs.json" <<'PY'
import json, sys
uniform, trs = (json.load(open(path)) for path in sys.argv[1:3])
noise = uniform["relative_variance"] / trs["relative_variance"]
time = trs["render_seconds"] / uniform["render_seconds"]
print(f"At {trs['frames']} spp, trs is {noise:.1f}x less noisy than uniform (relative variance "
      f"{trs['relative_variance']:.3g} against {uniform['relative_variance']:.3g}); "
      f"it took {time:.2f}x the time, so {noise / time:.1f}x the efficiency.")
PY
echo

mesh=scenes/demo/neon-panel.obj
density=scenes/demo/neon.png
for method in trs rs; do
  echo "== light sampler, $method: 10 million samples =="
  build/bin/trs-sample "$mesh" "$density" --count 1e7 --method "$method" --seed 1 --stats "$out/$method.json"
  echo
done
echo "Outputs in $out/"
