#!/usr/bin/env bash
# Every stage writes the same bytes on one core and on all of them: the bundled sample through every
# stage this build has, once pinned to CPU 0 (taskset: TBB, Embree and the solvers see one core) and once
# free, and every output file compared.
#   determinism.sh CINEPATH SOURCE_DIR
set -euo pipefail
CINEPATH=$1
SRC=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
has() { "$CINEPATH" --help | grep -q "^  $1 "; }
sample=$SRC/data/brighton_beach

pipeline() {  # pipeline OUT
  local out=$1
  mkdir -p "$out"
  "$CINEPATH" mesh --colmap "$sample/colmap/sparse_default" --refs "$sample/refs_gps.txt" \
    --images "$sample/images" --quality draft --draco --no-timestamp -o "$out/scene" 2> /dev/null
  local shots=$sample/shots.json
  [[ -f "$shots" ]] || shots=$SRC/examples/orbit_shots.json
  "$CINEPATH" plan "$shots" --scene "$out/scene/scene.json" --csv "$out/plan.csv" --plot "$out/plan.svg" \
    -o "$out/plan.json"
  local plan=$out/plan.json
  if has optimize; then
    "$CINEPATH" optimize "$plan" --scene "$out/scene/scene.json" --quality draft --report "$out/report.json" \
      -o "$out/optimized.json"
    # The report's wall-clock figures (solver.time_s, clearance.index_s) are the only keys that may differ.
    python3 -c 'import json, sys; r = json.load(open(sys.argv[1])); r["solver"].pop("time_s"); r.get("clearance", {}).pop("index_s", None); json.dump(r, open(sys.argv[1], "w"), indent=1)' "$out/report.json"
    plan=$out/optimized.json
  fi
  if has render; then
    "$CINEPATH" render "$plan" --scene "$out/scene/scene.json" --quality draft --every 30 --width-px 320 \
      -o "$out/frames"
  fi
  "$CINEPATH" export "$plan" --format qgc-plan --format qgc-wpl --format mavlink-bin --format dji-wpml \
    --format dji-msdk-json --format litchi-csv --force -o "$out/missions" > /dev/null
  if has view; then
    "$CINEPATH" view "$plan" --scene "$out/scene/scene.json" -o "$out/previs.html"
  fi
}

taskset -c 0 bash -c "$(declare -f pipeline has); CINEPATH='$CINEPATH' SRC='$SRC' sample='$sample' pipeline '$work/one'"
pipeline "$work/all"
files=$(cd "$work/all" && find . -type f | sort)
[[ -n "$files" ]] || { echo "no outputs"; exit 1; }
status=0
count=0
for f in $files; do
  count=$((count + 1))
  if ! cmp -s "$work/one/$f" "$work/all/$f"; then
    echo "differs between 1 and $(nproc) cores: $f"
    status=1
  fi
done
echo "$count files compared across the stages: $( [[ $status -eq 0 ]] && echo 'all identical' || echo 'differences above')"
exit $status
