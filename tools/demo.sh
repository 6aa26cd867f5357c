#!/usr/bin/env bash
# The main job: installs the dependencies, builds in Release what it runs, renders the demo
# scene (a neon sign lighting a room) with uniform light sampling and with Triangle Rejection
# Sampling at equal time, prints how much less noisy TRS is against a converged reference and
# writes build/demo/compare.png, the two and the reference side by side. Then samples the demo
# neon panel with the light sampler alone: TRS against plain rejection sampling.
#
# tools/demo.sh --animation [SECONDS]: the video wall's 48 frames instead, rendered with uniform
# light sampling and with the default strategy (ris) at equal time per frame (SECONDS, 1.5 by
# default), into build/demo/animation/: each strategy's frames, and video-wall.mp4 showing the
# two side by side, labelled (ffmpeg, installed with the other packages).
set -euo pipefail
cd "$(dirname "$0")/.."
if [ "${1:-}" = --animation ]; then
  # SECONDS goes to trs-render's --time and into the labels of ffmpeg's filter, whose syntax
  # it must not reach: a positive decimal number, checked before the set-up and the build.
  seconds=${2:-1.5}
  if ! [[ $seconds =~ ^([0-9]+\.?[0-9]*|\.[0-9]+)$ && $seconds =~ [1-9] ]]; then
    echo "tools/demo.sh: error: --animation SECONDS: \"$seconds\" is not a positive decimal number (1.5, say)" >&2
    exit 2
  fi
  bash tools/setup-debian.sh --video
else
  bash tools/setup-debian.sh
fi
# The Python modules on: tools/check.sh leaves them to --full, and its build folder is this one.
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DTRS_PYTHON=ON
# Only what the demo runs: the tests and fuzzers are tools/check.sh's to build.
cmake --build build --target trs-render trs-imgdiff trs-sample trs_render_python
out=build/demo
mkdir -p "$out"
if [ "${1:-}" = --animation ]; then
  exec bash tools/demo/animation.sh "$out/animation" "$seconds"
fi

scene=scenes/neon-sign
seconds=4  # each render's budget, set-up included
for strategy in uniform trs; do
  echo "== render: $strategy, $seconds s =="
  build/bin/trs-render "$scene/neon-sign.gltf" --settings "$scene/render.toml" --time "$seconds" \
    --strategy "$strategy" --out "$out/neon-sign-$strategy.exr" \
    --preview "$out/neon-sign-$strategy.png" --stats "$out/neon-sign-$strategy.json"
  # The noise against the converged reference, over the pixels where no emitter is seen directly.
  build/bin/trs-imgdiff "$out/neon-sign-$strategy.exr" "$scene/reference.exr" \
    --mask "$scene/reference-emitter-mask.exr" --json "$out/neon-sign-$strategy-noise.json" > /dev/null
  echo
done
PYTHONPATH=build/python /usr/bin/python3 tools/demo/compare.py "$out" "$scene/reference.exr" neon-sign uniform trs
echo

mesh=scenes/demo/neon-panel.obj
density=scenes/demo/neon.png
for method in trs rs; do
  echo "== light sampler, $method: 10 million samples =="
  build/bin/trs-sample "$mesh" "$density" --count 1e7 --method "$method" --seed 1 --stats "$out/$method.json"
  echo
done
echo "Outputs in $out/"
