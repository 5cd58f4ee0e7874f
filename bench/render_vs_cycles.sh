#!/usr/bin/env bash
# cinepath render against Blender Cycles: same GLB, camera, thin lens, resolution and shading (emission of
# the vertex colours, no bounces, box filter 1 px, cinepath's sky as the Blender world; bench/cycles_render.py).
# Two frames of the bundled Brighton Beach plan, no subjects, no motion blur (shutter 1 us):
#   dof    sample FRAME with a 70 mm f/1.4 lens focused at 4 m: the whole view 14-18 px out of focus
#   sharp  sample FRAME as planned (35 mm, focused at 10.7 m) at f/16: under 0.2 px of blur anywhere
# Each is rendered by both at N = 1, 2, 4, ... REF_SPP rays per pixel (cinepath: `--quality final --spp N`,
# a cap, the preset spends fewer where the frame is sharp; Cycles: N samples everywhere). References:
# cinepath `--spp REF --min-spp REF` (REF rays for every pixel, docs/render.md), Cycles at REF samples.
# Per run: wall clock of the whole command (start-up, mesh load, BVH, render, EXR write), and the render
# alone (cinepath -v frame time; Cycles from scene sync to the written file, after Blender's start-up and
# the glTF import). PSNR (idiff, OpenImageIO: 20 log10(1 / RMS) over R, G, B) on the EXRs clamped to [0, 1]
# and sRGB-encoded, kept in float (no 8-bit rounding). Prints markdown tables; keeps everything in OUT.
#   bench/render_vs_cycles.sh BUILD_DIR [OUT_DIR]     (make bench passes BUILD_DIR only: a temporary OUT)
# Environment: WIDTH (640), FRAME (840), REF_SPP (4096), SPPS ("1 2 4 ... REF_SPP"), THREADS (2, Cycles).
set -euo pipefail
if [[ $# -lt 1 || $# -gt 2 ]]; then
  echo "usage: $0 BUILD_DIR [OUT_DIR]" >&2
  exit 2
fi
ROOT=$(cd "$(dirname "$0")/.." && pwd)
CINEPATH=$(cd "$1" && pwd)/cli/cinepath
OUT=${2:-$(mktemp -d)}
WIDTH=${WIDTH:-640}
FRAME=${FRAME:-840}
REF_SPP=${REF_SPP:-4096}
THREADS=${THREADS:-2}
if [[ -z ${SPPS:-} ]]; then
  SPPS=""
  for ((n = 1; n <= REF_SPP; n *= 2)); do SPPS="$SPPS $n"; done
fi
S=$ROOT/data/brighton_beach
for tool in blender idiff oiiotool python3; do
  command -v $tool > /dev/null || { echo "$0: needs $tool" >&2; exit 1; }
done
[[ -x $CINEPATH ]] || { echo "$0: no $CINEPATH" >&2; exit 1; }
mkdir -p "$OUT/logs"
OUT=$(cd "$OUT" && pwd)
now() { date +%s.%N; }

# The scene (no --draco: Blender 3.4's importer reads the plain GLB) and the plan. The shot list is the
# one made for this mesh (data/brighton_beach/shots.json, planned with --scene); examples/orbit_shots.json
# carries its own origin, 45 m below and 34 m west of the mesh's, and `plan --scene` refuses it.
"$CINEPATH" mesh --colmap "$S/colmap/sparse_default" --refs "$S/refs_gps.txt" --images "$S/images" \
  --quality draft --no-timestamp -o "$OUT/scene" 2> "$OUT/logs/mesh.log"
"$CINEPATH" plan "$S/shots.json" --scene "$OUT/scene/scene.json" -o "$OUT/plan.json" 2> "$OUT/logs/plan.log"
python3 - "$OUT" "$FRAME" << 'PY'
import copy, json, sys
out, k = sys.argv[1], int(sys.argv[2])
plan = json.load(open(out + "/plan.json"))
plan["subjects"] = []  # Blender has no subject proxies
for sample in plan["samples"]:
    sample["shutter_s"] = 1e-6  # no motion blur (Cycles renders none)
json.dump(plan, open(out + "/plan_nosubj.json", "w"))
dof = copy.deepcopy(plan)
dof["samples"][k].update(focal_length_mm=70.0, f_number=1.4, focus_distance_m=4.0)
json.dump(dof, open(out + "/plan_dof.json", "w"))
sharp = copy.deepcopy(plan)
sharp["samples"][k].update(f_number=16.0)
json.dump(sharp, open(out + "/plan_sharp.json", "w"))
PY
HEIGHT=$(python3 -c "import json, sys; c = json.load(open(sys.argv[1]))['camera']; print(round($WIDTH * c['height_px'] / c['width_px']))" "$OUT/plan.json")
EXR=$(printf 'frame_%06d.exr' "$FRAME")

# sRGB-encoded copy of an EXR's RGB, clamped to [0, 1] (float).
srgb() {
  local dst=${1%.exr}.srgb.exr
  oiiotool "$1" --ch R,G,B --clamp:min=0:max=1 --colorconvert linear sRGB --clamp:min=0:max=1 \
    -d float -o "$dst"
  echo "$dst"
}
# Linear RGB copy, clamped to [0, 1].
linear() {
  local dst=${1%.exr}.linear.exr
  oiiotool "$1" --ch R,G,B --clamp:min=0:max=1 -d float -o "$dst"
  echo "$dst"
}
idiff_psnr() {
  local p
  p=$(idiff -v -fail 1 -warn 1 "$1" "$2" 2>&1 | awk '/Peak SNR/ {print $4}')
  echo "${p:?idiff $1 $2 printed no PSNR}"
}
psnr() { idiff_psnr "$(srgb "$1")" "$(srgb "$2")"; }  # psnr A.exr B.exr
psnr_linear() { idiff_psnr "$(linear "$1")" "$(linear "$2")"; }

cinepath_run() {  # cinepath_run TAG SPP NAME [ARGS...] -> "rays wall render"
  local tag=$1 spp=$2 name=$3
  shift 3
  local t0 t1
  rm -rf "$OUT/$name"
  t0=$(now)
  "$CINEPATH" render "$OUT/plan_$tag.json" --scene "$OUT/scene/scene.json" --frames "$FRAME-$FRAME" \
    --width-px "$WIDTH" --format exr --exr-pixel float --quality final --spp "$spp" "$@" -v --progress never -o "$OUT/$name" \
    2> "$OUT/logs/$name.log"
  t1=$(now)
  # "render: frame 840 (1/1) 22.94 s, 256.0 rays/px"
  awk -v wall="$(awk -v a="$t1" -v b="$t0" 'BEGIN {printf "%.2f", a - b}')" \
    '/^render: frame/ {print $7, wall, $5}' "$OUT/logs/$name.log"
}
cycles_run() {  # cycles_run TAG SPP NAME -> "rays wall render"
  local tag=$1 spp=$2 name=$3
  local t0 t1
  t0=$(now)
  blender -b --factory-startup --python-exit-code 1 -P "$ROOT/bench/cycles_render.py" -- \
    "$OUT/scene/scene.glb" "$OUT/plan_$tag.json" "$FRAME" "$WIDTH" "$HEIGHT" "$spp" "$OUT/$name.exr" "$THREADS" \
    > "$OUT/logs/$name.log" 2>&1
  t1=$(now)
  awk -v spp="$spp" -v wall="$(awk -v a="$t1" -v b="$t0" 'BEGIN {printf "%.2f", a - b}')" \
    '/^render_seconds/ {print spp, wall, $2}' "$OUT/logs/$name.log"
}

# Results: renderer frame spp rays wall render psnr(sRGB) load
RESULTS=$OUT/results.tsv
: > "$RESULTS"
load() { cut -d' ' -f1 /proc/loadavg; }
for tag in dof sharp; do
  read -r rays wall render <<< "$(cinepath_run $tag "$REF_SPP" cp_${tag}_ref --min-spp "$REF_SPP")"
  echo -e "cinepath\t$tag\tref\t$rays\t$wall\t$render\tref\t$(load)" | tee -a "$RESULTS"
  read -r rays wall render <<< "$(cycles_run $tag "$REF_SPP" cy_${tag}_$REF_SPP)"
  echo -e "cycles\t$tag\t$REF_SPP\t$rays\t$wall\t$render\tref\t$(load)" | tee -a "$RESULTS"
  for spp in $SPPS; do
    read -r rays wall render <<< "$(cinepath_run $tag "$spp" cp_${tag}_$spp)"
    p=$(psnr "$OUT/cp_${tag}_$spp/$EXR" "$OUT/cp_${tag}_ref/$EXR")
    echo -e "cinepath\t$tag\t$spp\t$rays\t$wall\t$render\t$p\t$(load)" | tee -a "$RESULTS"
    [[ $spp == "$REF_SPP" ]] && continue
    read -r rays wall render <<< "$(cycles_run $tag "$spp" cy_${tag}_$spp)"
    p=$(psnr "$OUT/cy_${tag}_$spp.exr" "$OUT/cy_${tag}_$REF_SPP.exr")
    echo -e "cycles\t$tag\t$spp\t$rays\t$wall\t$render\t$p\t$(load)" | tee -a "$RESULTS"
  done
  a=$OUT/cp_${tag}_ref/$EXR
  b=$OUT/cy_${tag}_$REF_SPP.exr
  echo -e "converged\t$tag\t$REF_SPP\t-\t-\t-\t$(psnr "$a" "$b")\t$(psnr_linear "$a" "$b")" | tee -a "$RESULTS"
  oiiotool "$(srgb "$a")" "$(srgb "$b")" --sub --printstats > "$OUT/logs/converged_${tag}_diff_stats.txt"
  oiiotool "$a" --ch R,G,B --colorconvert linear sRGB -o "$OUT/cp_${tag}_ref.png"
  oiiotool "$b" --ch R,G,B --colorconvert linear sRGB -o "$OUT/cy_${tag}_$REF_SPP.png"
done

python3 - "$RESULTS" "$REF_SPP" "$WIDTH" "$HEIGHT" "$FRAME" "$OUT" << 'PY' | tee "$OUT/results.md"
import json, sys
rows = [line.rstrip("\n").split("\t") for line in open(sys.argv[1]) if line.strip()]
ref, width, height, frame = sys.argv[2], sys.argv[3], sys.argv[4], sys.argv[5]
title = {}
for tag in ("dof", "sharp"):
    s = json.load(open(f"{sys.argv[6]}/plan_{tag}.json"))["samples"][int(frame)]
    title[tag] = f"{s['focal_length_mm']:g} mm f/{s['f_number']:g} focused at {s['focus_distance_m']:.1f} m"
def num(s):
    return float("inf") if s in ("inf", "ref") else float(s)
for tag in ("dof", "sharp"):
    print(f"\n#### Sample {frame}, {title[tag]}, {width}x{height}\n")
    print("| N | cinepath rays/px | cinepath wall s | cinepath render s | cinepath PSNR dB "
          "| Cycles wall s | Cycles render s | Cycles PSNR dB |")
    print("|---|---|---|---|---|---|---|---|")
    cp = {r[2]: r for r in rows if r[0] == "cinepath" and r[1] == tag}
    cy = {r[2]: r for r in rows if r[0] == "cycles" and r[1] == tag}
    for n in sorted((k for k in set(cp) | set(cy) if k != "ref"), key=int):
        a, b = cp.get(n), cy.get(n)
        left = f"{a[3]} | {a[4]} | {a[5]} | {a[6]}" if a else "– | – | – | –"
        if b and b[6] == "ref":
            right = f"{b[4]} | {b[5]} | reference"
        else:
            right = f"{b[4]} | {b[5]} | {b[6]}" if b else "– | – | –"
        print(f"| {n} | {left} | {right} |")
    r = cp["ref"]
    print(f"| reference: `--spp {ref} --min-spp {ref}` | {r[3]} | {r[4]} | {r[5]} | reference | | | |")
    print()
    for threshold in (40, 50, 60):
        for name, runs in (("cinepath", cp), ("Cycles", cy)):
            hit = [runs[n] for n in sorted((k for k in runs if k != "ref"), key=int)
                   if runs[n][6] != "ref" and num(runs[n][6]) >= threshold]
            if hit:
                h = hit[0]
                print(f"- {name} first reaches {threshold} dB at N = {h[2]} ({h[3]} rays/px): "
                      f"{h[4]} s wall, {h[5]} s render")
            else:
                print(f"- {name} does not reach {threshold} dB below the reference")
    conv = [r for r in rows if r[0] == "converged" and r[1] == tag][0]
    print(f"- converged cinepath vs converged Cycles ({ref} rays/px each): PSNR {conv[6]} dB (sRGB), "
          f"{conv[7]} dB (linear)")
loads = [float(r[7]) for r in rows if r[0] != "converged"]
print(f"\nload average (1 min) after the runs: {min(loads):.2f} to {max(loads):.2f}")
PY
