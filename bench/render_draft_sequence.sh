#!/usr/bin/env bash
# Draft frames per second over a sequence, and draft's PSNR against converged frames, on the README scene
# (the README's `mesh` and `plan` commands on the bundled sample: textured, two subjects).
#   bench/render_draft_sequence.sh BUILD_DIR [OUT] [PEER_BUILD_DIR]
# Renders frames 0-299 at --quality draft, 640 px wide, three times with BUILD_DIR, in turns with
# PEER_BUILD_DIR when given (another build, e.g. main's, in the same run), printing wall and CPU seconds;
# then six frames (100, 300, ..., 1100) converged (`--quality final --min-spp 1024`, several minutes: REFS=0
# skips them) and at draft, with the PSNR of each draft frame against its converged one (idiff, OpenImageIO,
# on the 8-bit PNGs).
set -euo pipefail
BUILD=${1:-build}
OUT=${2:-$(mktemp -d)}
PEER=${3:-}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
S=$ROOT/data/brighton_beach
mkdir -p "$OUT"
"$BUILD/cli/cinepath" mesh --colmap "$S/colmap/sparse_default" --refs "$S/refs_gps.txt" --images "$S/images" \
  --draco --no-timestamp -o "$OUT/scene" 2> /dev/null
"$BUILD/cli/cinepath" plan "$S/shots.json" --scene "$OUT/scene/scene.json" -o "$OUT/plan.json"
draft() {  # draft BUILD_DIR FRAMES DIR
  rm -rf "$3"
  "$1/cli/cinepath" render "$OUT/plan.json" --scene "$OUT/scene/scene.json" --quality draft --width-px 640 \
    --frames "$2" --progress never -o "$3"
}
echo "| run | build | s wall | s CPU | frames/s |"
echo "|---|---|---|---|---|"
for run in 1 2 3; do
  for build in ${PEER:+"$PEER"} "$BUILD"; do
    /usr/bin/time -f "%e %U %S" -o "$OUT/time.txt" bash -c "$(declare -f draft); OUT='$OUT'; draft '$build' 0-299 '$OUT/seq'"
    read -r wall user sys < "$OUT/time.txt"
    awk -v r="$run" -v b="$build" -v w="$wall" -v c="$(awk -v u="$user" -v s="$sys" 'BEGIN {print u + s}')" \
      'BEGIN {printf "| %d | %s | %.2f | %.1f | %.1f |\n", r, b, w, c, 300 / w}'
  done
done
[ "${REFS:-1}" = 0 ] && exit 0
echo
echo "| frame | draft PSNR (dB) vs converged (final, 1024 rays a pixel) |"
echo "|---|---|"
for frame in 100 300 500 700 900 1100; do
  name=$(printf 'frame_%06d.png' $frame)
  "$BUILD/cli/cinepath" render "$OUT/plan.json" --scene "$OUT/scene/scene.json" --quality final --min-spp 1024 \
    --width-px 640 --frames $frame --progress never -o "$OUT/ref"
  draft "$BUILD" $frame "$OUT/draft_$frame"
  psnr=$(idiff -v -fail 1 -warn 1 "$OUT/draft_$frame/$name" "$OUT/ref/$name" 2>&1 | awk '/Peak SNR/ {print $4}' || true)
  echo "| $frame | ${psnr:-inf} |"
done
