#!/usr/bin/env bash
# cinepath render against Blender Cycles over a sequence with heavy blur: 30 consecutive samples of the
# bundled plan (FIRST ...), each through an 85 mm f/1.4 lens focused at 5 m (the ground 30-40 m away is
# ~10 px out of focus at 320 px wide, ~20 px at 640), no subjects, no motion blur, the vertex-coloured draft
# mesh (no texture: bench/cycles_render.py shades the colour attribute), `--backdrop none` (Cycles' world
# below the horizon is render's plain grey). Like for like with bench/render_vs_cycles.sh otherwise.
# Each renderer runs the 30 frames at N = 1, 2, 4, ... rays per pixel and is compared, frame by frame, with
# its own converged frames (REF rays per pixel: cinepath `--spp REF --min-spp REF`, Cycles REF samples);
# PSNR on sRGB-encoded float images (idiff). Timed:
#   cinepath  the whole process for the 30 frames (`--quality final --spp N`: start-up, mesh, BVH, render,
#             EXR writing: half floats, the default; the converged frames in float), wall and user + sys CPU
#             (/usr/bin/time);
#   Cycles    render time only, with persistent data (the sum of its 30 `render_seconds`: scene sync and
#             BVH once, then sampling): Blender's start-up and the glTF import not counted.
# Then cinepath with its denoiser (DENOISE_SPPS, default "1 2": `--quality final --spp N --denoise`) and its
# presets as they are (PRESETS, default "draft standard": `--quality Q`, no --spp), timed and compared the
# same way (Cycles has no such rows).
# Prints a markdown table, one row per N and per preset.
#   bench/render_sequence_vs_cycles.sh BUILD_DIR [OUT_DIR]
# Environment: WIDTH (320), FIRST (840), REF_SPP (512), CYCLES_REF_SPP (REF_SPP: Cycles' converged frames),
# SPPS ("1 2 4 8 16 32 64"), DENOISE_SPPS ("1 2"), PRESETS ("draft standard"), THREADS (2, Cycles).
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
CINEPATH=$(cd "${1:?usage: $0 BUILD_DIR [OUT_DIR]}" && pwd)/cli/cinepath
OUT=${2:-$(mktemp -d)}
WIDTH=${WIDTH:-320}
FIRST=${FIRST:-840}
LAST=$((FIRST + 29))
REF_SPP=${REF_SPP:-512}
CYCLES_REF_SPP=${CYCLES_REF_SPP:-$REF_SPP}
SPPS=${SPPS:-1 2 4 8 16 32 64}
DENOISE_SPPS=${DENOISE_SPPS-1 2}
PRESETS=${PRESETS-draft standard}
THREADS=${THREADS:-2}
S=$ROOT/data/brighton_beach
mkdir -p "$OUT/logs"
OUT=$(cd "$OUT" && pwd)
echo "Blender: $(blender --version 2> /dev/null | head -1); CPU: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2)," \
  "$(nproc) cores; load at start: $(cut -d' ' -f1-3 /proc/loadavg)"

[[ -f $OUT/scene/scene.glb ]] || "$CINEPATH" mesh --colmap "$S/colmap/sparse_default" --refs "$S/refs_gps.txt" \
  --images "$S/images" --quality draft --no-texture --no-timestamp -o "$OUT/scene" 2> "$OUT/logs/mesh.log"
"$CINEPATH" plan "$S/shots.json" --scene "$OUT/scene/scene.json" -o "$OUT/plan.json" 2> "$OUT/logs/plan.log"
python3 - "$OUT" "$FIRST" "$LAST" << 'PY'
import json, sys
out, first, last = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
plan = json.load(open(out + "/plan.json"))
plan["subjects"] = []
for k, sample in enumerate(plan["samples"]):
    sample["shutter_s"] = 1e-6
    if first <= k <= last:
        sample.update(focal_length_mm=85.0, f_number=1.4, focus_distance_m=5.0)
json.dump(plan, open(out + "/plan_seq.json", "w"))
PY
HEIGHT=$(python3 -c "import json, sys; c = json.load(open(sys.argv[1]))['camera']; print(round($WIDTH * c['height_px'] / c['width_px']))" "$OUT/plan.json")

cinepath_run() {  # cinepath_run NAME QUALITY ARGS... -> "wall cpu"
  local name=$1 quality=$2
  shift 2
  rm -rf "${OUT:?}/$name"
  /usr/bin/time -f "%e %U %S" -o "$OUT/logs/$name.time" "$CINEPATH" render "$OUT/plan_seq.json" \
    --scene "$OUT/scene/scene.json" --frames "$FIRST-$LAST" --width-px "$WIDTH" --format exr --backdrop none \
    --quality "$quality" "$@" --progress never -o "$OUT/$name" 2> "$OUT/logs/$name.log"
  awk '{printf "%.2f %.2f\n", $1, $2 + $3}' "$OUT/logs/$name.time"
}
cycles_run() {  # cycles_run SPP NAME -> "render_seconds_sum"
  mkdir -p "$OUT/$2"
  blender -b --factory-startup --python-exit-code 1 -P "$ROOT/bench/cycles_render.py" -- "$OUT/scene/scene.glb" \
    "$OUT/plan_seq.json" "$FIRST-$LAST" "$WIDTH" "$HEIGHT" "$1" "$OUT/$2/frame_#.exr" "$THREADS" \
    > "$OUT/logs/$2.log" 2>&1
  awk '/^render_seconds/ {s += $2} END {printf "%.2f\n", s}' "$OUT/logs/$2.log"
}
srgb() {  # srgb IN.exr OUT.exr: RGB clamped to [0, 1], sRGB-encoded, float
  oiiotool "$1" --ch R,G,B --clamp:min=0:max=1 --colorconvert linear sRGB -d float -o "$2"
}
psnrs() {  # psnrs DIR REF_DIR -> "min mean" PSNR over the 30 frames
  for ((k = FIRST; k <= LAST; ++k)); do
    f=$(printf 'frame_%06d' $k)
    [[ -f $2/$f.srgb.exr ]] || srgb "$2/$f.exr" "$2/$f.srgb.exr"
    srgb "$1/$f.exr" "$1/$f.srgb.exr"
    idiff -v -fail 1 -warn 1 "$1/$f.srgb.exr" "$2/$f.srgb.exr" 2>&1 | awk '/Peak SNR/ {print $4}'
  done | awk '{if (NR == 1 || $1 < m) m = $1; s += $1} END {printf "%.2f %.2f\n", m, s / NR}'
}

[[ -d $OUT/cp_ref ]] || cinepath_run cp_ref final --spp "$REF_SPP" --min-spp "$REF_SPP" --exr-pixel float > /dev/null
[[ -d $OUT/cy_ref ]] || cycles_run "$CYCLES_REF_SPP" cy_ref > /dev/null
echo "| N rays/px | cinepath wall s | cinepath CPU s | cinepath PSNR min / mean dB | Cycles render s | Cycles PSNR min / mean dB | load |"
echo "|---|---|---|---|---|---|---|"
for n in $SPPS; do
  read -r wall cpu <<< "$(cinepath_run cp_$n final --spp "$n")"
  cp_psnr=$(psnrs "$OUT/cp_$n" "$OUT/cp_ref")
  cy_render=$(cycles_run "$n" cy_$n)
  cy_psnr=$(psnrs "$OUT/cy_$n" "$OUT/cy_ref")
  echo "| $n | $wall | $cpu | ${cp_psnr/ / \/ } | $cy_render | ${cy_psnr/ / \/ } | $(cut -d' ' -f1 /proc/loadavg) |"
done | tee "$OUT/results.md"
for n in $DENOISE_SPPS; do
  read -r wall cpu <<< "$(cinepath_run cp_${n}_denoised final --spp "$n" --denoise)"
  cp_psnr=$(psnrs "$OUT/cp_${n}_denoised" "$OUT/cp_ref")
  echo "| $n, \`--denoise\` | $wall | $cpu | ${cp_psnr/ / \/ } | | | $(cut -d' ' -f1 /proc/loadavg) |"
done | tee -a "$OUT/results.md"
for q in $PRESETS; do
  read -r wall cpu <<< "$(cinepath_run cp_$q "$q")"
  cp_psnr=$(psnrs "$OUT/cp_$q" "$OUT/cp_ref")
  echo "| \`--quality $q\` | $wall | $cpu | ${cp_psnr/ / \/ } | | | $(cut -d' ' -f1 /proc/loadavg) |"
done | tee -a "$OUT/results.md"
echo "load at the end: $(cut -d' ' -f1-3 /proc/loadavg)"
