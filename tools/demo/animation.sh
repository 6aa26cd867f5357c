#!/usr/bin/env bash
# The animation demo (tools/demo.sh --animation): scenes/video-wall, frames 0 to 47, with uniform
# and with trs-render's default strategy (ris) at equal time per frame, then both side by side in
# one labelled MP4.
# Usage: tools/demo/animation.sh OUT_DIR SECONDS_PER_FRAME (a positive decimal number, which
# tools/demo.sh checks: it is written into ffmpeg's filter)
set -euo pipefail
out=$1 seconds=$2
scene=scenes/video-wall
mkdir -p "$out"
for strategy in uniform ris; do
  echo "== video wall, $strategy: 48 frames of $seconds s each =="
  mkdir -p "$out/$strategy"
  build/bin/trs-render "$scene/video-wall.gltf" --settings "$scene/render.toml" --frames 0:47 \
    --strategy "$strategy" --time "$seconds" --quiet --out "$out/$strategy/frame.%04d.exr" \
    --preview "$out/$strategy/frame.%04d.png" --stats "$out/$strategy/frame.%04d.json" > "$out/$strategy.log"
  echo
done
# Labels drawn by ffmpeg's drawtext in the DejaVu font (fonts-dejavu-core).
font=/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf
label() { echo "drawtext=fontfile=$font:text='$1':fontsize=18:fontcolor=white:x=12:y=10:box=1:boxcolor=black@0.6:boxborderw=6"; }
ffmpeg -loglevel error -y -framerate 24 -i "$out/uniform/frame.%04d.png" -framerate 24 -i "$out/ris/frame.%04d.png" \
  -filter_complex "[0:v]$(label "uniform ($seconds s a frame)")[a];[1:v]$(label "ris ($seconds s a frame)")[b];[a][b]hstack" \
  -c:v libx264 -pix_fmt yuv420p -crf 18 "$out/video-wall.mp4.part.mp4"
mv "$out/video-wall.mp4.part.mp4" "$out/video-wall.mp4"
ffmpeg -loglevel error -y -i "$out/video-wall.mp4" -frames:v 1 "$out/video-wall-first-frame.png"
/usr/bin/python3 - "$out" <<'PY'
import json, statistics, sys
out = sys.argv[1]
for strategy in ("uniform", "ris"):
    stats = [json.load(open(f"{out}/{strategy}/frame.{f:04d}.json")) for f in range(48)]
    spp = statistics.mean(s["passes"] for s in stats)
    ready = statistics.mean(sum(s["emission_update_ms"].values()) for s in stats[1:])
    print(f"{strategy:8s} {spp:6.1f} spp a frame on average; getting ready for each new frame's emission: {ready:.1f} ms")
PY
echo "Frames in $out/uniform and $out/ris; both side by side in $out/video-wall.mp4"
