#!/usr/bin/env bash
# render's presets: time per 640x360 frame and error against the converged frame (4096 rays for every
# pixel), on the bundled scene, for a frame with shallow depth of field (f/2.8 orbit, frame 90) and a
# sharp one (f/5.6 crane, frame 1170). PSNR and the RMS error on 8-bit sRGB PNGs (idiff, OpenImageIO).
# Also the draft throughput (frames per second over 43 frames, 2 cores).
#   bench/render_quality.sh BUILD_DIR [OUT]
set -euo pipefail
BUILD=${1:-build}
OUT=${2:-$(mktemp -d)}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
CINEPATH=$BUILD/cli/cinepath
S=$ROOT/data/brighton_beach
mkdir -p "$OUT"
"$CINEPATH" mesh --colmap "$S/colmap/sparse_default" --refs "$S/refs_gps.txt" --images "$S/images" \
  --quality draft --draco --no-timestamp -o "$OUT/scene" 2> /dev/null
"$CINEPATH" plan "$S/shots.json" --scene "$OUT/scene/scene.json" -o "$OUT/plan.json"
now() { date +%s.%N; }
render() {  # render FRAME NAME ARGS...
  local frame=$1 name=$2
  shift 2
  local t0
  t0=$(now)
  "$CINEPATH" render "$OUT/plan.json" --scene "$OUT/scene/scene.json" --frames "$frame" --width-px 640 "$@" \
    -o "$OUT/$name"
  awk -v a="$(now)" -v b="$t0" 'BEGIN {print a - b}'
}
echo "| frame | preset | seconds | PSNR (dB) vs converged | RMS error (8-bit sRGB, 0-1) |"
echo "|---|---|---|---|---|"
for frame in 90 1170; do
  ref_time=$(render $frame ref_$frame --quality final --min-spp 4096)
  ref=$OUT/ref_$frame/$(printf 'frame_%06d.png' $frame)
  for preset in draft standard final; do
    t=$(render $frame ${preset}_$frame --quality $preset)
    img=$OUT/${preset}_$frame/$(printf 'frame_%06d.png' $frame)
    stats=$(idiff -v -fail 1 -warn 1 "$img" "$ref" 2>&1 || true)
    psnr=$(echo "$stats" | awk '/Peak SNR/ {print $4}')
    rms=$(echo "$stats" | awk '/RMS error/ {print $4}')
    printf '| %d | %s | %.2f | %s | %s |\n' $frame $preset "$t" "${psnr:-inf}" "${rms:-0}"
  done
  printf '| %d | converged (final, --min-spp 4096) | %.2f | – | – |\n' $frame "$ref_time"
done
t0=$(now)
"$CINEPATH" render "$OUT/plan.json" --scene "$OUT/scene/scene.json" --every 30 --width-px 640 --quality draft \
  -o "$OUT/draft_all"
t=$(awk -v a="$(now)" -v b="$t0" 'BEGIN {print a - b}')
n=$(ls "$OUT/draft_all" | wc -l)
echo
echo "draft throughput: $n frames of 640x360 in $t s: $(awk -v n="$n" -v t="$t" 'BEGIN {printf "%.1f", n / t}') frames/s (incl. start-up and BVH)"
