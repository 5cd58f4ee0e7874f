#!/usr/bin/env bash
# Georeferencing: cinepath mesh vs COLMAP 3.8 model_aligner on the same inputs (Brighton Beach).
#   bench/georef_vs_model_aligner.sh [BUILD_DIR] [DATA_DIR]
# Prints, per model: model_aligner's mean/median camera-centre error and wall time; cinepath's RMSE /
# inliers / focal handling from scene.json and wall time (with and without bundle adjustment).
# The vertical check against the OpenDroneMap reference is a unit test:
#   photogrammetry_test --gtest_filter='GeoreferenceModel.BrightonBeach*'
set -euo pipefail
BUILD=${1:-build}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
DATA=${2:-$ROOT/data/brighton_beach}
CINEPATH=$BUILD/cli/cinepath
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT

now() { date +%s.%N; }
for model in sparse_default sparse_exif_focal; do
  [[ -d "$DATA/colmap/$model" ]] || { echo "== $model: not in $DATA (skipped)"; continue; }
  echo "== $model"
  mkdir -p "$WORK/$model/aligned"
  t0=$(now)
  colmap model_aligner --input_path "$DATA/colmap/$model" --output_path "$WORK/$model/aligned" \
    --ref_images_path "$DATA/refs_gps.txt" --ref_is_gps 1 --alignment_type ecef \
    --robust_alignment 1 --robust_alignment_max_error 3 \
    --transform_path "$WORK/$model/transform.txt" > "$WORK/$model/aligner.log" 2>&1
  t1=$(now)
  echo "model_aligner: $(grep -o 'Alignment error: .*' "$WORK/$model/aligner.log") (mean, median m); $(echo "$t1 - $t0" | bc) s"
  for mode in "" "--no-bundle-adjust"; do
    out="$WORK/$model/cinepath$mode"
    t0=$(now)
    "$CINEPATH" mesh --colmap "$DATA/colmap/$model" --refs "$DATA/refs_gps.txt" --images "$DATA/images" \
      $mode --no-timestamp -o "$out" 2> "$out.stderr" || true
    t1=$(now)
    /usr/bin/python3 - "$out/scene.json" "$mode" "$(echo "$t1 - $t0" | bc)" <<'PY'
import json, statistics, sys
s = json.load(open(sys.argv[1]))
g = s["georeferencing"]
first = g["similarity_fit"]
res = [r["residual_m"] for r in (g.get("final_fit") or first)["residuals"]]
line = "cinepath %s: rmse %.3f m, mean %.3f / median %.3f m, inliers %d/%d" % (
    sys.argv[2] or "(with BA)", g["rmse_m"], statistics.mean(res), statistics.median(res), g["inliers"],
    first["num_references"])
if "bundle_adjustment" in g:
    f = g["bundle_adjustment"]["focal_length"][0]
    line += "; similarity-only rmse %.3f m; focal %.1f -> %.1f px (held at prior: %s)" % (
        first["rmse_m"], f["before_px"], f["after_px"], f["held_at_prior"])
print(line + "; whole mesh command %s s" % sys.argv[3])
PY
  done
done
