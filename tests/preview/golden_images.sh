#!/usr/bin/env bash
# Golden images: three frames of the bundled sample's plan (an f/2.8 orbit, a chase, a crane reveal),
# rendered at 192 x 108 in each shading mode, against tests/preview/golden/<shading>_<frame>.png.
# A PSNR tolerance (>= 40 dB, idiff on 8-bit sRGB), not bytes: another compiler or Embree build may
# move a float by an ulp and a pixel by a level. CINEPATH_UPDATE_GOLDEN=1 rewrites the images
# (view them before committing).
#   golden_images.sh CINEPATH SOURCE_DIR
set -euo pipefail
CINEPATH=$1
SRC=$2
GOLDEN=$SRC/tests/preview/golden
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
sample=$SRC/data/brighton_beach
# The goldens are of the vertex-coloured sample (--no-texture); the photo texture's look is checked in
# docs/mesh.md's image and bench/texture_fidelity.sh until they are regenerated with it.
"$CINEPATH" mesh --colmap "$sample/colmap/sparse_default" --refs "$sample/refs_gps.txt" --images "$sample/images" \
  --quality draft --draco --no-texture --no-timestamp -o "$work/scene" 2> /dev/null
"$CINEPATH" plan "$sample/shots.json" --scene "$work/scene/scene.json" -o "$work/plan.json"
status=0
for shading in flat sun; do
  for frame in 90 720 1170; do
    "$CINEPATH" render "$work/plan.json" --scene "$work/scene/scene.json" --frames $frame --width-px 192 \
      --shading $shading -o "$work/$shading"
    image=$work/$shading/$(printf 'frame_%06d.png' $frame)
    golden=$GOLDEN/${shading}_$(printf '%06d' $frame).png
    if [[ ${CINEPATH_UPDATE_GOLDEN:-0} == 1 ]]; then
      mkdir -p "$GOLDEN"
      cp "$image" "$golden"
      continue
    fi
    [[ -f $golden ]] || { echo "missing golden image $golden"; status=1; continue; }
    psnr=$(idiff -v -fail 1 -warn 1 "$image" "$golden" 2>&1 | awk '/Peak SNR/ {print $4}')
    psnr=${psnr:-inf}  # identical images print no PSNR
    if [[ $psnr != inf ]] && awk -v p="$psnr" 'BEGIN {exit !(p < 40)}'; then
      echo "FAIL $shading frame $frame: PSNR $psnr dB < 40 dB against $golden"
      status=1
    else
      echo "ok   $shading frame $frame: PSNR $psnr dB"
    fi
  done
done
exit $status
