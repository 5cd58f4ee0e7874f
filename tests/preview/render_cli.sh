#!/usr/bin/env bash
# `cinepath render` through the real binary, on the bundled sample:
#   - two shards (--shard 0/2, 1/2) give exactly the files of one full run, byte for byte, and so does a run
#     on one core (with --denoise too);
#   - the GNU parallel example of docs/scale-out.md gives the same files again;
#   - a missing mesh, a GLB without geometry, a frame range outside the plan and an unwritable output
#     folder exit 2 and write nothing; --video without ffmpeg says so;
#   - --overlay, --contact-sheet, --aov and --format exr write what they promise, the same bytes every run;
#   - a camera at the scene's edge looking out level sees the ground past the edge: a finite depth below the
#     horizon, unless --backdrop none.
#   render_cli.sh CINEPATH SOURCE_DIR
set -euo pipefail
CINEPATH=$1
SRC=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
sample=$SRC/data/brighton_beach

"$CINEPATH" mesh --colmap "$sample/colmap/sparse_default" --refs "$sample/refs_gps.txt" --images "$sample/images" \
  --quality draft --draco --no-timestamp -o "$work/scene" 2> /dev/null
"$CINEPATH" plan "$SRC/examples/orbit_shots.json" -o "$work/plan.json"
render=("$CINEPATH" render "$work/plan.json" --scene "$work/scene/scene.json" --every 40 --width-px 96 --spp 16)

# Shards against one run.
"${render[@]}" -o "$work/full"
n=$(ls "$work/full" | wc -l)
[[ $n -ge 3 ]] || fail "expected several frames, got $n"
"${render[@]}" --shard 0/2 -o "$work/shards"
"${render[@]}" --shard 1/2 -o "$work/shards"
diff -r "$work/full" "$work/shards" > /dev/null || fail "two shards differ from one full run"
echo "shards: $n frames identical to one run"
# The thread count: the same frames on one core (taskset: TBB and Embree see one), lens rays and packets
# included (the orbit's frames are blurred: standard traces them through the lens, eight rays a packet).
if command -v taskset > /dev/null; then
  taskset -c 0 "${render[@]}" -o "$work/one_core"
  diff -r "$work/full" "$work/one_core" > /dev/null || fail "one core gives other bytes than every core"
  echo "threads: $n frames identical on one core and on all"
  # The denoiser too: few lens rays filtered, the same bytes on one core, and not the unfiltered frames.
  few_rays=("$CINEPATH" render "$work/plan.json" --scene "$work/scene/scene.json" --every 40 --width-px 96 --spp 2)
  "${few_rays[@]}" --denoise -o "$work/denoised"
  taskset -c 0 "${few_rays[@]}" --denoise -o "$work/denoised_one_core"
  diff -r "$work/denoised" "$work/denoised_one_core" > /dev/null || fail "--denoise: one core gives other bytes"
  "${few_rays[@]}" -o "$work/noisy"
  ! diff -r "$work/denoised" "$work/noisy" > /dev/null || fail "--denoise changed no frame"
  echo "denoise: $n frames identical on one core and on all"
fi
# --denoise at draft, which traces no lens rays: a warning, not a silent no-op.
"$CINEPATH" render "$work/plan.json" --scene "$work/scene/scene.json" --frames 0-0 --width-px 32 --quality draft \
  --denoise -o "$work/draft_denoise" 2>&1 | grep -q "denoise does nothing at --quality draft" ||
  fail "--denoise at draft says nothing"

# Memory at start-up: the textures stay 8-bit in memory, and no OpenImageIO is loaded. One small frame of the
# draft sample (a 2048² atlas) peaked at 234 MB when its texels were linear floats, 162-165 MB with 8-bit
# texels and OpenImageIO's ~260 libraries, 30 MB without them (2026-11-27, 2 cores); the bound (twice that)
# catches a return of either: float texels alone would add 50 MB. Not under the sanitizers, whose shadow memory
# is counted too.
# Page faults of one 640 px draft frame (the kernel's traps on first touching a page, getrusage's ru_minflt):
# 8,400-8,700 with the heap in 4 KiB pages and its large blocks mmapped afresh, 2,100-2,600 with the main
# heap asked for in 2 MiB pages (core/heap_pages.h; 2026-11-28). The bound, 5,000, catches a return to small
# pages; it needs the kernel's transparent huge pages ("always" or "madvise"), so it is skipped without them.
if [[ -z ${ASAN_OPTIONS:-} ]]; then
  read -r peak_mb faults < <(python3 - "${render[@]:0:5}" "$work/memory" <<'PY'
import resource, subprocess, sys
cinepath, command, plan, scene_flag, scene, out = sys.argv[1:7]
subprocess.run([cinepath, command, plan, scene_flag, scene, "--frames", "0", "--width-px", "96", "--spp", "1",
                "-o", out], check=True)
peak_mb = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss // 1024
before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_minflt
subprocess.run([cinepath, command, plan, scene_flag, scene, "--frames", "0", "--width-px", "640", "--quality",
                "draft", "-o", out], check=True)
print(peak_mb, resource.getrusage(resource.RUSAGE_CHILDREN).ru_minflt - before)
PY
  )
  [[ $peak_mb -lt 64 ]] || fail "render of one frame peaked at $peak_mb MB (bound 64 MB: textures held as floats again?)"
  echo "memory: one frame peaked at $peak_mb MB"
  thp=/sys/kernel/mm/transparent_hugepage/enabled
  if [[ -r $thp ]] && ! grep -q '\[never\]' "$thp"; then
    [[ $faults -lt 5000 ]] || fail "one 640 px draft frame took $faults page faults (bound 5,000: the heap in 4 KiB pages again?)"
    echo "page faults: one 640 px draft frame took $faults"
  fi
fi

# The GNU parallel example (docs/scale-out.md).
if command -v parallel > /dev/null; then
  parallel --will-cite -j 2 "${render[@]}" --shard {}/4 -o "$work/parallel" ::: 0 1 2 3
  diff -r "$work/full" "$work/parallel" > /dev/null || fail "GNU parallel shards differ from one full run"
  echo "GNU parallel: identical"
fi

# Bad input: exit 2, nothing written.
expect_refusal() {  # expect_refusal OUTDIR WORDS-IN-MESSAGE -- ARGS...
  local out=$1 words=$2
  shift 3
  set +e
  "$@" -o "$out" 2> "$work/stderr"
  local code=$?
  set -e
  [[ $code -eq 2 ]] || fail "exit $code (expected 2) for: $* ($(cat "$work/stderr"))"
  grep -q -- "$words" "$work/stderr" || fail "message lacks '$words': $(cat "$work/stderr")"
  [[ ! -e $out ]] || [[ -z $(ls -A "$out") ]] || fail "$out was written to"
}
mkdir -p "$work/missing_mesh"
sed 's/"mesh": *"scene.glb"/"mesh": "absent.glb"/' "$work/scene/scene.json" > "$work/missing_mesh/scene.json"
grep -q absent.glb "$work/missing_mesh/scene.json" || fail "could not point scene.json at a missing mesh"
expect_refusal "$work/out1" "absent.glb" -- "$CINEPATH" render "$work/plan.json" --scene "$work/missing_mesh/scene.json"
expect_refusal "$work/out2" "outside the plan" -- "$CINEPATH" render "$work/plan.json" \
  --scene "$work/scene/scene.json" --frames 0-99999999
# A GLB holding no geometry: the 12-byte header and one JSON chunk {"asset":{"version":"2.0"}}.
mkdir -p "$work/empty"
printf 'glTF\x02\x00\x00\x00\x30\x00\x00\x00\x1c\x00\x00\x00JSON{"asset":{"version":"2.0"}} ' > "$work/empty/scene.glb"
sed 's/"mesh": *"scene.glb"/"mesh": "scene.glb"/' "$work/scene/scene.json" > "$work/empty/scene.json"
expect_refusal "$work/out3" "scene.glb" -- "$CINEPATH" render "$work/plan.json" --scene "$work/empty/scene.json"
touch "$work/a_file"
expect_refusal "$work/a_file/frames" "a_file" -- "$CINEPATH" render "$work/plan.json" --scene "$work/scene/scene.json"
# Midnight at the scene: the sun is below the horizon.
expect_refusal "$work/out4" "below the horizon" -- "$CINEPATH" render "$work/plan.json" \
  --scene "$work/scene/scene.json" --sun-time 2026-06-21T06:00:00Z
echo "bad input: exit 2, nothing written"

# --video without ffmpeg on PATH: a clear message, nothing rendered.
mkdir -p "$work/bin"
set +e
PATH=$work/bin "$CINEPATH" render "$work/plan.json" --scene "$work/scene/scene.json" --every 40 --width-px 32 \
  --video "$work/v.mp4" -o "$work/novideo" 2> "$work/stderr"
code=$?
set -e
[[ $code -ne 0 ]] || fail "--video without ffmpeg succeeded"
grep -q ffmpeg "$work/stderr" || fail "--video without ffmpeg: $(cat "$work/stderr")"
[[ ! -e $work/novideo ]] || [[ -z $(ls -A "$work/novideo") ]] || fail "--video without ffmpeg rendered frames"

# Overlay, contact sheet, AOVs, EXR.
"${render[@]}" --frames 0-80 --overlay --contact-sheet "$work/sheet.png" --aov depth,blur,mask --format exr \
  -o "$work/extras"
for f in frame_000000.exr frame_000040.exr frame_000080.exr frame_000040.depth.exr frame_000040.blur.exr \
  frame_000040.mask.exr; do
  [[ -s $work/extras/$f ]] || fail "missing $f"
done
[[ $(head -c 8 "$work/sheet.png" | od -An -tx1 | tr -d ' \n') == 89504e470d0a1a0a ]] || fail "sheet.png is not a PNG"
# The same bytes on a second run a second later (no wall-clock time in any file).
sleep 1.1
"${render[@]}" --frames 0-80 --aov mask,depth,blur --format exr -o "$work/extras_again"
for f in frame_000040.exr frame_000040.depth.exr frame_000040.blur.exr frame_000040.mask.exr; do
  cmp -s "$work/extras/$f" "$work/extras_again/$f" || fail "$f differs between two runs"
done
# The bundled shots' orbit frames its subject (the plan's first): the mask labels it 1, the rest 0.
if command -v oiiotool > /dev/null; then
  "$CINEPATH" plan "$sample/shots.json" --scene "$work/scene/scene.json" -o "$work/subject_plan.json"
  "$CINEPATH" render "$work/subject_plan.json" --scene "$work/scene/scene.json" --frames 90 --width-px 96 --spp 1 \
    --aov mask -o "$work/mask"
  mask_range=$(oiiotool --stats "$work/mask/frame_000090.mask.exr" |
    awk '/Stats Min/ {min=$3} /Stats Max/ {max=$3} END {print min, max}')
  [[ $mask_range == "0.000000 1.000000" ]] || fail "mask AOV spans '$mask_range', expected 0 (ground) to 1 (the subject)"
  # EXR frames hold half floats unless --exr-pixel float asks for 32 bits; the AOVs are data, always float.
  exr_type() { oiiotool --info "$1" | awk 'NR == 1 {print $(NF - 3), $(NF - 2), $(NF - 1)}'; }
  [[ $(exr_type "$work/extras/frame_000040.exr") == "3 channel, half" ]] || fail "EXR frame: $(exr_type "$work/extras/frame_000040.exr")"
  [[ $(exr_type "$work/extras/frame_000040.depth.exr") == "1 channel, float" ]] || fail "depth AOV: $(exr_type "$work/extras/frame_000040.depth.exr")"
  "${render[@]}" --frames 40 --format exr --exr-pixel float -o "$work/exr_float"
  [[ $(exr_type "$work/exr_float/frame_000040.exr") == "3 channel, float" ]] || fail "--exr-pixel float: $(exr_type "$work/exr_float/frame_000040.exr")"
  # The same picture to half precision (values under 2: an absolute error under 2^-11).
  idiff -fail 0.0005 "$work/extras/frame_000040.exr" "$work/exr_float/frame_000040.exr" > /dev/null ||
    fail "the half and float EXR frames differ by more than half's rounding"
fi
set +e
"${render[@]}" --frames 40 --format exr --exr-pixel double -o "$work/exr_double" 2> "$work/stderr"
code=$?
set -e
[[ $code -eq 2 ]] || fail "--exr-pixel double: exit $code, expected 2"
[[ ! -e $work/exr_double ]] || fail "--exr-pixel double wrote $work/exr_double"
echo "extras: EXR frames, depth, blur and mask AOVs, contact sheet; EXR bytes the same on a second run"

# The horizon: a camera at the bundled scene's eastern edge (the easternmost photo's place), looking east and
# level. With the ground past the edge no pixel below the horizon (the lower half of the image) has an infinite
# depth; with --backdrop none the rays past the mesh's edge do.
if command -v oiiotool > /dev/null; then
  # The bundled shots planned on the scene (the scene's origin, so the plan's ENU is the scene's).
  "$CINEPATH" plan "$sample/shots.json" --scene "$work/scene/scene.json" -o "$work/edge_base.json"
  python3 - "$work/edge_base.json" "$work/scene/scene.json" "$work/edge_plan.json" <<'PY'
import json, sys
plan, scene = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
east = max((c["position_enu_m"] for c in scene["cameras"]), key=lambda p: p[0])
sample = plan["samples"][0]
sample["position_enu_m"] = east
# Camera x right = south, y down, z forward = east: the quaternion (w, x, y, z) of the matrix with those columns.
sample["world_from_camera"] = [0.5, -0.5, 0.5, -0.5]
json.dump(plan, open(sys.argv[3], "w"))
PY
  below_horizon_inf() {  # below_horizon_inf DEPTH.exr: how many lower-half pixels have an infinite depth
    oiiotool --dumpdata "$1" | awk -F'[(),: ]+' '$2 == "Pixel" && $4 + 0.5 > h / 2 && $5 ~ /inf/ {n++}
      END {print n + 0}' h=54
  }
  for backdrop in ground none; do
    "$CINEPATH" render "$work/edge_plan.json" --scene "$work/scene/scene.json" --frames 0 --width-px 96 --spp 1 \
      --backdrop $backdrop --aov depth -o "$work/edge_$backdrop"
  done
  oiiotool --info "$work/edge_ground/frame_000000.depth.exr" | grep -Eq "96 x +54" || fail "depth AOV not 96 x 54"
  ground_inf=$(below_horizon_inf "$work/edge_ground/frame_000000.depth.exr")
  none_inf=$(below_horizon_inf "$work/edge_none/frame_000000.depth.exr")
  [[ $ground_inf -eq 0 ]] || fail "--backdrop ground: $ground_inf pixels below the horizon at infinite depth"
  [[ $none_inf -gt 0 ]] || fail "--backdrop none: no pixel below the horizon at infinite depth (is the camera at the edge?)"
  echo "horizon: 0 of 2592 pixels below the horizon at infinite depth with the ground, $none_inf with --backdrop none"
fi
