#!/usr/bin/env bash
# render's start-up: one 640 x 360 frame at one ray per pixel (frame 720 of the bundled plan), wall clock,
# CPU seconds and peak RSS (/usr/bin/time), with `-v`'s breakdown of the loading steps; on the bundled
# scene as the README meshes it (11.6 k faces, a 4096² JPEG atlas) and on a large one (~1 M faces, an
# 8192² JPEG atlas: bench/render_large_scene.py, its atlas a sample photo scaled by ffmpeg). Also
# `render --help` (the module's loading alone) and draft throughput (43 frames, --every 30).
# PEER: another build's cinepath (e.g. one made before a change), run interleaved with BUILD's.
#   bench/render_startup.sh BUILD [OUT] [PEER_CINEPATH]
set -euo pipefail
BUILD=${1:-build}
OUT=${2:-$(mktemp -d)}
PEER=${3:-}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
CINEPATH=$BUILD/cli/cinepath
S=$ROOT/data/brighton_beach
RUNS=${RUNS:-3}
mkdir -p "$OUT"
[[ -f $OUT/scene/scene.json ]] || "$CINEPATH" mesh --colmap "$S/colmap/sparse_default" --refs "$S/refs_gps.txt" \
  --images "$S/images" --draco -o "$OUT/scene" 2> /dev/null
[[ -f $OUT/plan.json ]] || "$CINEPATH" plan "$S/shots.json" --scene "$OUT/scene/scene.json" -o "$OUT/plan.json"
if [[ ! -f $OUT/large/scene.json ]]; then
  ffmpeg -loglevel error -y -i "$S/images/DJI_0018.JPG" -vf scale=8192:8192 -q:v 3 "$OUT/atlas8k.jpg"
  python3 "$ROOT/bench/render_large_scene.py" "$OUT/scene/scene.json" "$OUT/atlas8k.jpg" "$OUT/large"
fi
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg)"
binaries=("$CINEPATH")
[[ -n $PEER ]] && binaries+=("$PEER")
for scene in scene large; do
  for run in $(seq "$RUNS"); do
    for bin in "${binaries[@]}"; do
      echo "== $scene, run $run: $bin"
      /usr/bin/time -f "total %e s wall, %U s user + %S s sys, peak RSS %M kB" "$bin" render "$OUT/plan.json" \
        --scene "$OUT/$scene/scene.json" --frames 720 --width-px 640 --spp 1 -o "$OUT/frame_$scene" -v 2>&1 |
        sed 's/^render: //'
    done
  done
done
for bin in "${binaries[@]}"; do
  echo "== render --help: $bin"
  /usr/bin/time -f "%e s wall" "$bin" render --help > /dev/null
  echo "== draft, 43 frames of 640 x 360: $bin"
  rm -rf "$OUT/draft"
  /usr/bin/time -f "%e s wall, %U s user + %S s sys" "$bin" render "$OUT/plan.json" --scene "$OUT/scene/scene.json" \
    --every 30 --width-px 640 --quality draft -o "$OUT/draft"
done
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg)"
