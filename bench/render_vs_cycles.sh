#!/usr/bin/env bash
# cinepath render against Blender Cycles, same run, same GLB, camera, lens and resolution: for a frame
# with shallow depth of field and an in-focus one, each renderer's time to reach PSNR >= 40 dB against
# its own converged image (4096 rays per pixel), and the PSNR between the two converged images.
# Shading like for like (bench/cycles_render.py): emission of the vertex colours, no bounces, box filter
# of 1 px, no motion blur (shutter 1 us), no subjects. PSNR by idiff (OpenImageIO) on the EXRs encoded to
# 8-bit sRGB.
#   bench/render_vs_cycles.sh BUILD_DIR [OUT] [WIDTH HEIGHT]
set -euo pipefail
BUILD=${1:-build}
OUT=${2:-$(mktemp -d)}
W=${3:-320}
H=${4:-180}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
CINEPATH=$(cd "$BUILD" && pwd)/cli/cinepath
S=$ROOT/data/brighton_beach
mkdir -p "$OUT"
command -v blender > /dev/null || { echo "needs blender (Debian package blender)"; exit 1; }
"$CINEPATH" mesh --colmap "$S/colmap/sparse_default" --refs "$S/refs_gps.txt" --images "$S/images" \
  --quality draft --no-timestamp -o "$OUT/scene" 2> /dev/null
"$CINEPATH" plan "$S/shots.json" --scene "$OUT/scene/scene.json" -o "$OUT/plan_full.json"
# Frame 90 (orbit) with a 70 mm f/1.4 lens focused at 6 m: the whole view blurred by 5-10 px.
# Frame 1170 (crane reveal) at f/16: in focus everywhere. No subjects, no motion.
python3 - "$OUT/plan_full.json" "$OUT/plan.json" << 'PY'
import json, sys
plan = json.load(open(sys.argv[1]))
plan["subjects"] = []
for s in plan["samples"]:
    s["shutter_s"] = 1e-6
plan["samples"][90].update(focal_length_mm=70, f_number=1.4, focus_distance_m=6)
plan["samples"][1170].update(f_number=16)
json.dump(plan, open(sys.argv[2], "w"))
PY
# PSNR on 8-bit sRGB (what a viewer sees; linear values would flatter dark noise).
srgb() { oiiotool "$1" --ch R,G,B --colorconvert linear sRGB -d uint8 -o "${1%.exr}.png"; }
psnr() {
  srgb "$1" && srgb "$2"
  idiff -v -fail 1 -warn 1 "${1%.exr}.png" "${2%.exr}.png" 2>&1 | awk '/Peak SNR/ {print $4}'
}
echo "renderer | frame | rays/px | seconds | PSNR vs own converged (dB)"
for frame in 90 1170; do
  for spp in 4096 1 4 16 64 256 1024; do
    name=$(printf 'frame_%06d.exr' $frame)
    "$CINEPATH" render "$OUT/plan.json" --scene "$OUT/scene/scene.json" --frames $frame --width-px $W \
      --format exr --quality final --spp $spp $([[ $spp == 4096 ]] && echo --min-spp 4096) -v -o "$OUT/cp_${frame}_$spp" 2> "$OUT/cp_${frame}_$spp.log"
    t=$(awk '{print $5}' "$OUT/cp_${frame}_$spp.log")
    rays=$(awk '{print $7}' "$OUT/cp_${frame}_$spp.log")
    p=$([[ $spp == 4096 ]] && echo ref || psnr "$OUT/cp_${frame}_$spp/$name" "$OUT/cp_${frame}_4096/$name")
    echo "cinepath | $frame | $rays (cap $spp) | $t | ${p:-inf}"
    blender -b --factory-startup --python-exit-code 1 -P "$ROOT/bench/cycles_render.py" -- \
      "$OUT/scene/scene.glb" "$OUT/plan.json" $frame $W $H $spp "$OUT/cy_${frame}_$spp.exr" > "$OUT/cy_${frame}_$spp.log" 2>&1
    t=$(awk '/^render_seconds/ {print $2}' "$OUT/cy_${frame}_$spp.log")
    p=$([[ $spp == 4096 ]] && echo ref || psnr "$OUT/cy_${frame}_$spp.exr" "$OUT/cy_${frame}_4096.exr")
    echo "cycles | $frame | $spp | $t | ${p:-inf}"
  done
  echo "converged cinepath vs converged Cycles, frame $frame: $(psnr "$OUT/cp_${frame}_4096/$(printf 'frame_%06d.exr' $frame)" "$OUT/cy_${frame}_4096.exr") dB"
done
