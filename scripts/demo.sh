#!/usr/bin/env bash
# Runs every pipeline stage cinepath has on the bundled sample (data/brighton_beach) into OUT.
#   scripts/demo.sh BUILD/cli/cinepath OUT
set -euo pipefail
CINEPATH=${1:-build/cli/cinepath}
OUT=${2:-demo-out}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
SAMPLE=$ROOT/data/brighton_beach
mkdir -p "$OUT"
has() { "$CINEPATH" --help | grep -q "^  $1 "; }
step() { echo "== $*" >&2; }

step "cinepath lens: depth of field of the sample's camera (DJI FC300S, 3.61 mm f/2.8, focused at 40 m)"
"$CINEPATH" lens --focal-mm 3.61 --f-number 2.8 --focus-m 40 --sensor one-over-2.3-inch --width-px 4000 \
  --at-m 5 --at-m 20 | tee "$OUT/lens.txt"

if has mesh; then
  step "cinepath mesh: COLMAP sparse model + GPS references -> georeferenced mesh"
  "$CINEPATH" mesh --colmap "$SAMPLE/colmap/sparse_default" --refs "$SAMPLE/refs_gps.txt" \
    --images "$SAMPLE/images" --quality draft --draco -o "$OUT/scene"
  ls -l "$OUT/scene"
fi

SHOTS=$SAMPLE/shots.json
PLAN_ARGS=()
[[ -f "$OUT/scene/scene.json" ]] && PLAN_ARGS=(--scene "$OUT/scene/scene.json")
if has plan; then
  step "cinepath plan: the sample's shots on its ground -> plan.json (+ CSV and SVG plot)"
  "$CINEPATH" plan "$SHOTS" "${PLAN_ARGS[@]}" --csv "$OUT/plan.csv" --plot "$OUT/plan.svg" -o "$OUT/plan.json"
  FLIGHT=$OUT/plan.json
  if has optimize; then
    step "cinepath optimize: path and lens together against the scene -> optimized.json (+ report)"
    "$CINEPATH" optimize "$OUT/plan.json" "${PLAN_ARGS[@]}" --quality draft --report "$OUT/optimize_report.json" \
      -o "$OUT/optimized.json"
    python3 -c 'import json, sys; r = json.load(open(sys.argv[1])); print("cost %.4g -> %.4g; worst limits before/after:" % (r["total"]["before"], r["total"]["after"]), {k: (v["before"], v["after"]) for k, v in r["limits"].items()})' "$OUT/optimize_report.json"
    FLIGHT=$OUT/optimized.json
  fi
  if has render && [[ -f "$OUT/scene/scene.json" ]]; then
    step "cinepath render: every 3 s of the plan, 640 px, sun shading, with a contact sheet"
    "$CINEPATH" render "$FLIGHT" --scene "$OUT/scene/scene.json" --every 90 --width-px 640 --shading sun \
      --overlay --contact-sheet "$OUT/contact_sheet.png" -o "$OUT/frames"
    ls "$OUT/frames" | head -3
  fi
  if has view; then
    step "cinepath view: one offline previs page (open it in a browser): 3D scene and flight, timeline, lens"
    VIEW_ARGS=("${PLAN_ARGS[@]}")
    [[ -d "$OUT/frames" ]] && VIEW_ARGS+=(--frames "$OUT/frames")
    "$CINEPATH" view "$FLIGHT" "${VIEW_ARGS[@]}" -o "$OUT/previs.html"
    ls -l "$OUT/previs.html"
  fi
  if has export; then
    step "cinepath export: the flight -> missions for QGroundControl, MAVLink, DJI and Litchi"
    mkdir -p "$OUT/missions"
    "$CINEPATH" export "$FLIGHT" "${PLAN_ARGS[@]}" --format qgc-plan --format qgc-wpl --format mavlink-bin \
      --format dji-wpml --format dji-msdk-json --format litchi-csv -o "$OUT/missions"
    ls -l "$OUT/missions"
  fi
fi
step "demo outputs are in $OUT/"
