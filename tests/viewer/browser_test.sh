#!/usr/bin/env bash
# The previs page in a real browser: headless Chromium opens `cinepath view`'s page from disk (file://) for
# the bundled sample (scene + plan + a few rendered frames) and for each examples/*_shots.json plan, and
# checks what a person would see:
#   - the page says it is ready, with the mesh's triangle count, and counted no error (uncaught exception,
#     console.error, or a request the page's Content-Security-Policy blocked: the page fetches nothing);
#   - the 3D view and the camera view are not blank (pixel standard deviation);
#   - the slider moved to time t shows the plan's sample at t in the camera readout (read from the DOM);
#   - with --frames, the camera view shows render's frame for a sample that has one;
#   - the camera view of a level shot has the sky above the beach (upright), and the camera view frames
#     what `cinepath render` drew for that sample (not its mirror image, not upside down);
#   - the top view matches tests/viewer/golden/top_view.png within a tolerance (idiff), and its
#     upside-down and mirrored copies do not: north up, east right;
#   - the first picture shows every subject: each example's, and a telephoto shot's 1.5 km from its drone
#     (3D and top views); the 3D view's first picture holds the whole grid with its labels and the north
#     arrow below the header (the sample's and the telephoto shot's).
# Screenshots of the 3D view and of the camera view are kept in ARTIFACT_DIR. CINEPATH_UPDATE_GOLDEN=1
# rewrites the golden image (look at it before committing). Exit 77 (skipped) without Chromium.
#   browser_test.sh CINEPATH SOURCE_DIR ARTIFACT_DIR
set -uo pipefail
CINEPATH=$1
SRC=$2
ARTIFACTS=$3
CHROMIUM=$(command -v chromium || command -v chromium-browser || true)
if [[ -z $CHROMIUM ]]; then
  echo "SKIP: no chromium (scripts/install-deps.sh installs Debian's chromium)"
  exit 77
fi
for tool in oiiotool idiff node; do
  command -v $tool > /dev/null || { echo "FAIL: $tool missing (scripts/install-deps.sh)"; exit 1; }
done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$ARTIFACTS"
GOLDEN=$SRC/tests/viewer/golden/top_view.png
WIDTH=1600
HEIGHT=900
status=0
fail() { echo "FAIL $*"; status=1; }

# One headless run: browse PAGE#HASH, then --dump-dom or --screenshot=FILE (ARGS). Software WebGL
# (SwiftShader); a fixed window and scale so screenshots compare.
browse() {
  local url=$1
  shift
  timeout 120 "$CHROMIUM" --headless --no-sandbox --no-first-run --disable-extensions --disable-dev-shm-usage \
    --user-data-dir="$work/profile" --use-angle=swiftshader --enable-unsafe-swiftshader --hide-scrollbars \
    --force-device-scale-factor=1 --window-size=$WIDTH,$HEIGHT --virtual-time-budget=15000 \
    --enable-logging=stderr --v=0 "$@" "$url" 2>> "$work/chromium.log"
}
attr() { grep -o "$1=\"[^\"]*\"" "$2" | head -1 | sed 's/.*="\(.*\)"/\1/'; }
# The mean and the standard deviation (over the three channels) of a region W,H at X,Y of an image.
region_stats() {
  oiiotool -v "$1" --cut "$2" --printstats 2>&1 | awk '/Stats Avg/ {a=($3+$4+$5)/3; r=$3; g=$4; b=$5}
    /Stats StdDev/ {s=($3+$4+$5)/3} END {printf "%f %f %f %f %f\n", a, s, r, g, b}'
}
geometry() { echo "$1" | awk -F, -v dy="${2:-0}" -v hh="${3:-0}" '{h = hh > 0 ? hh : $4;
  printf "%dx%d+%d+%d\n", $3, h, $1, $2 + dy}'; }

# ---- the bundled sample: scene (draft), plan, three rendered frames, the page ----
sample=$SRC/data/brighton_beach
# The goldens are of the vertex-coloured sample (--no-texture); the photo texture's look is checked in
# docs/mesh.md's image and bench/texture_fidelity.sh until they are regenerated with it.
"$CINEPATH" mesh --colmap "$sample/colmap/sparse_default" --refs "$sample/refs_gps.txt" --images "$sample/images" \
  --quality draft --draco --no-texture --no-timestamp -o "$work/scene" 2> /dev/null || { echo "FAIL mesh"; exit 1; }
"$CINEPATH" plan "$sample/shots.json" --scene "$work/scene/scene.json" -o "$work/plan.json" || exit 1
"$CINEPATH" render "$work/plan.json" --scene "$work/scene/scene.json" --frames 90-90 --width-px 320 \
  -o "$work/frames" || exit 1
"$CINEPATH" view "$work/plan.json" --scene "$work/scene/scene.json" --frames "$work/frames" -o "$work/previs.html" ||
  exit 1
"$CINEPATH" view "$work/plan.json" --scene "$work/scene/scene.json" -o "$work/live.html" || exit 1
page_bytes=$(stat -c %s "$work/previs.html")
inputs_bytes=$(($(stat -c %s "$work/scene/scene.glb") + $(stat -c %s "$work/plan.json")))
echo "page $page_bytes bytes; GLB + plan $inputs_bytes bytes"

# The readout at time t must be the plan's sample at t (the one nearest t).
check_time() {
  local t=$1 dom=$work/dom_$1.html
  local start=$SECONDS
  browse "file://$work/previs.html#t=$t" --dump-dom > "$dom"
  local state errors triangles
  state=$(attr data-state "$dom")
  errors=$(attr data-errors "$dom")
  triangles=$(attr data-triangles "$dom")
  [[ $state == ready && $errors == 0 ]] || fail "t=$t: state '$state', $errors errors: $(grep -o '<title>[^<]*' "$dom")"
  [[ ${triangles:-0} -gt 1000 ]] || fail "t=$t: $triangles triangles"
  # The 3D view's first picture holds the whole grid, its labels and the north arrow, below the header.
  local framed
  framed=$(attr data-framed-in-view "$dom")
  [[ -n $framed && ${framed%/*} == "${framed#*/}" ]] || fail "t=$t: framed points in the 3D view: '$framed'"
  local shown expected
  shown="$(attr data-k "$dom") $(attr data-e "$dom") $(attr data-n "$dom") $(attr data-u "$dom")"
  expected=$(node -e '
    const plan = JSON.parse(require("fs").readFileSync(process.argv[1], "utf8"));
    const t = Number(process.argv[2]);
    let k = 0;
    plan.samples.forEach((s, i) => { if (Math.abs(s.time_s - t) < Math.abs(plan.samples[k].time_s - t)) k = i; });
    const p = plan.samples[k].position_enu_m;
    console.log(k, ...p.map((v) => v.toFixed(3)));' "$work/plan.json" "$t")
  if [[ $shown != "$expected" ]]; then
    fail "t=$t: readout 'k e n u' = '$shown', plan.json's sample: '$expected'"
  else
    echo "ok   t=$t: readout $shown = plan.json's sample (module, mesh, picture at $(attr data-timing "$dom") ms;" \
      "$((SECONDS - start)) s with the browser's start)"
  fi
}
check_time 20
check_time 33.3
grep -q 'id="camera-label">live preview<' "$work/dom_20.html" || fail "t=20: no frame rendered there, expected live"
browse "file://$work/previs.html#k=90" --dump-dom > "$work/dom_k90.html"
if grep -q 'id="camera-label">rendered frame 90<' "$work/dom_k90.html"; then
  echo "ok   k=90: the camera view shows render's frame_000090.png"
else
  fail "k=90: the camera view does not show the rendered frame"
fi

# ---- screenshots: not blank, sky above the beach, the golden top view ----
# The page's layout (viewer/previs.html): the 3D view left of a 420 px panel and above a 64 px timeline;
# the camera view at the panel's top (8 px padding, a 16 px heading, a 6 px gap), 403 px wide at the
# plan's aspect. A pixel inside each edge, clear of the outline.
aspect=$(node -e 'const p = JSON.parse(require("fs").readFileSync(process.argv[1], "utf8"));
  console.log(p.camera.height_px / p.camera.width_px)' "$work/plan.json")
main_rect="0,0,$((WIDTH - 420)),$((HEIGHT - 64))"
camera_rect="$((WIDTH - 410)),31,401,$(awk -v a="$aspect" 'BEGIN {printf "%d", 403 * a - 2}')"
# t = 33.3 s: the reveal, whose camera has the horizon in view. (At t = 20 s the flyby looks down enough that
# the ground past the mesh's edge, which the camera view draws as render does, fills the picture's top.)
browse "file://$work/live.html#t=33.3" --screenshot="$work/shot_3d.png" > /dev/null
cp "$work/shot_3d.png" "$ARTIFACTS/view_3d.png"
oiiotool "$work/shot_3d.png" --cut "$(geometry "$camera_rect")" -o "$ARTIFACTS/view_camera.png"
read -r _ main_std _ < <(region_stats "$work/shot_3d.png" "$(geometry "$main_rect")")
read -r _ cam_std _ < <(region_stats "$work/shot_3d.png" "$(geometry "$camera_rect")")
awk -v s="$main_std" 'BEGIN {exit !(s > 0.05)}' || fail "3D view blank (std dev $main_std)"
awk -v s="$cam_std" 'BEGIN {exit !(s > 0.03)}' || fail "camera view blank (std dev $cam_std)"
echo "ok   not blank: std dev 3D view $main_std, camera view $cam_std (screenshots in $ARTIFACTS)"
# The sky colour (#9cc3e4) fills the top strip of a level shot's picture; the beach fills the bottom.
cam_h=$(echo "$camera_rect" | cut -d, -f4)
read -r _ _ tr tg tb < <(region_stats "$work/shot_3d.png" "$(geometry "$camera_rect" 2 $((cam_h / 8)))")
bottom_strip=$(geometry "$camera_rect" $((cam_h * 7 / 8 - 2)) $((cam_h / 8)))
read -r _ _ br bg bb < <(region_stats "$work/shot_3d.png" "$bottom_strip")
sky_top=$(awk -v r="$tr" -v g="$tg" -v b="$tb" 'BEGIN {d = (r-0.612)^2 + (g-0.765)^2 + (b-0.894)^2; print sqrt(d)}')
sky_bottom=$(awk -v r="$br" -v g="$bg" -v b="$bb" 'BEGIN {d = (r-0.612)^2 + (g-0.765)^2 + (b-0.894)^2; print sqrt(d)}')
if awk -v t="$sky_top" -v b="$sky_bottom" 'BEGIN {exit !(t < 0.12 && b > 0.2)}'; then
  echo "ok   camera view upright: top strip $sky_top from the sky colour, bottom strip $sky_bottom"
else
  fail "camera view not upright: top strip $sky_top from the sky colour (want < 0.12), bottom $sky_bottom (> 0.2)"
fi

# The live camera view at sample 90 frames what `render` drew for it (same position, orientation, angle of
# view and aspect): closer to render's frame than to that frame mirrored or upside down, by a margin.
browse "file://$work/live.html#k=90" --screenshot="$work/shot_k90.png" > /dev/null
oiiotool "$work/shot_k90.png" --cut "$(geometry "$camera_rect")" -o "$work/live_k90.png"
cam_size=$(echo "$camera_rect" | awk -F, '{print $3 "x" $4}')
oiiotool "$work/frames/frame_000090.png" --resize "$cam_size" -o "$work/render_k90.png"
oiiotool "$work/render_k90.png" --flop -o "$work/render_k90_mirrored.png"
oiiotool "$work/render_k90.png" --flip -o "$work/render_k90_flipped.png"
mean_error() { idiff -v -fail 1 -warn 1 "$1" "$2" 2>&1 | awk '/Mean error/ {print $4}'; }
e_same=$(mean_error "$work/live_k90.png" "$work/render_k90.png")
e_mirrored=$(mean_error "$work/live_k90.png" "$work/render_k90_mirrored.png")
e_flipped=$(mean_error "$work/live_k90.png" "$work/render_k90_flipped.png")
if awk -v a="$e_same" -v b="$e_mirrored" -v c="$e_flipped" 'BEGIN {exit !(a < 0.6 * b && a < 0.6 * c)}'; then
  echo "ok   camera view = render's frame 90: mean error $e_same (mirrored $e_mirrored, upside down $e_flipped)"
else
  fail "camera view vs render's frame 90: mean error $e_same, mirrored $e_mirrored, upside down $e_flipped"
fi

browse "file://$work/live.html#t=0&view=top" --screenshot="$work/shot_top.png" > /dev/null
oiiotool "$work/shot_top.png" --cut "$(geometry "$main_rect")" -o "$work/top.png"
cp "$work/top.png" "$ARTIFACTS/view_top.png"
if [[ ${CINEPATH_UPDATE_GOLDEN:-0} == 1 ]]; then
  mkdir -p "$(dirname "$GOLDEN")"
  oiiotool "$work/top.png" --resize 50% -o "$GOLDEN"
  echo "updated $GOLDEN"
else
  # Compared at half size: SwiftShader or font versions may move an edge by a pixel.
  oiiotool "$work/top.png" --resize 50% -o "$work/top_half.png"
  oiiotool "$work/top_half.png" --flip -o "$work/top_flipped.png"
  oiiotool "$work/top_half.png" --flop -o "$work/top_mirrored.png"
  compare() { idiff -fail 0.15 -failpercent 3 -warn 0.05 -warnpercent 100 "$1" "$GOLDEN" > "$work/idiff.txt" 2>&1; }
  if compare "$work/top_half.png"; then
    echo "ok   top view matches $GOLDEN"
  else
    fail "top view differs from $GOLDEN: $(grep -E 'pixels|FAIL' "$work/idiff.txt" | tr '\n' ' ')"
  fi
  compare "$work/top_flipped.png" && fail "an upside-down top view passes the golden comparison"
  compare "$work/top_mirrored.png" && fail "a mirrored top view passes the golden comparison"
fi

# ---- the examples: plans without a scene (local metres or their own origin) ----
for shots in "$SRC"/examples/*_shots.json; do
  name=$(basename "$shots" _shots.json)
  "$CINEPATH" plan "$shots" -o "$work/$name.json" 2> /dev/null || { fail "$name: plan"; continue; }
  "$CINEPATH" view "$work/$name.json" -o "$work/$name.html" || { fail "$name: view"; continue; }
  browse "file://$work/$name.html#t=1" --dump-dom > "$work/$name.dom"
  in_view=$(attr data-subjects-in-view "$work/$name.dom")
  if [[ $(attr data-state "$work/$name.dom") == ready && $(attr data-errors "$work/$name.dom") == 0 &&
    -n $in_view && ${in_view%/*} == "${in_view#*/}" ]]; then
    echo "ok   example $name (subjects in the first picture: $in_view)"
  else
    fail "example $name: $(grep -o '<title>[^<]*' "$work/$name.dom"), subjects in view $in_view"
  fi
done

# ---- a telephoto shot from 1.5 km: the first picture, 3D and top, shows the subject as well as the drone ----
cat > "$work/far_shots.json" << 'EOF'
{"schema": "cinepath.shots/1", "frame_rate_hz": 10,
 "camera": {"filmback": "full-frame", "min_focal_length_mm": 1200},
 "drone": "px4-multirotor",
 "actors": [{"name": "sled", "height_m": 2, "keyframes": [{"time_s": 0, "position_enu_m": [-150, 0, 0]},
                                                         {"time_s": 30, "position_enu_m": [150, 0, 0]}]}],
 "shots": [{"name": "tele", "type": "FLYBY", "subject": "sled", "duration_s": 30, "closest_distance_m": 1500,
            "side": "right", "height_m": 60, "speed_m_s": 1, "lens": {"focus": "infinity"}}]}
EOF
"$CINEPATH" plan "$work/far_shots.json" -o "$work/far.json" 2> /dev/null || fail "far: plan"
"$CINEPATH" view "$work/far.json" -o "$work/far.html" || fail "far: view"
for v in 3d top; do
  browse "file://$work/far.html#t=15&view=$v" --dump-dom > "$work/far_$v.dom"
  in_view=$(attr data-subjects-in-view "$work/far_$v.dom")
  framed=$(attr data-framed-in-view "$work/far_$v.dom")
  if [[ $v == 3d && ! (-n $framed && ${framed%/*} == "${framed#*/}") ]]; then
    fail "far subject: the 3D view frames $framed of its grid's and scene's points (want all)"
  fi
  if [[ $(attr data-state "$work/far_$v.dom") == ready && $in_view == 1/1 ]]; then
    echo "ok   far subject in the $v view"
  else
    fail "far subject: $v view: state $(attr data-state "$work/far_$v.dom"), subjects in view '$in_view' (want 1/1)"
  fi
done
if grep -E "Uncaught|Refused to|Failed to load resource" "$work/chromium.log"; then
  fail "the browser logged errors or blocked requests (above)"
fi
exit $status
