#!/usr/bin/env bash
# `cinepath mesh --for-plan` through the binary on the bundled sample: mesh, plan on it, mesh again for
# the plan. The for-plan run exits 0 and its scene.json's decimate step carries the for-plan report with
# the bound met (worst projected error <= --max-error-px), fewer faces than the plain run's mesh, and the
# frozen-tile count matching the tiles marked frozen. The same shots made about their own origin give the
# same for-plan mesh; a plan of several drones meshes for all their cameras. Then bad input: a plan without an origin and a missing plan file each exit 2 with an
# error naming the file, and write nothing.
#   mesh_for_plan.sh CINEPATH SOURCE_DIR
set -euo pipefail
CINEPATH=$1
SRC=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
sample=$SRC/data/brighton_beach
mesh() {  # mesh OUT [ARGS...]
  local out=$1
  shift
  "$CINEPATH" mesh --colmap "$sample/colmap/sparse_default" --refs "$sample/refs_gps.txt" \
    --images "$sample/images" --quality draft --draco --no-timestamp -o "$out" "$@"
}
fail() {
  echo "FAIL: $*" >&2
  exit 1
}

mesh "$work/scene" 2> /dev/null
"$CINEPATH" plan "$sample/shots.json" --scene "$work/scene/scene.json" -o "$work/plan.json"
mesh "$work/for_plan" --for-plan "$work/plan.json" --max-error-px 0.5 2> "$work/for_plan.err" ||
  fail "mesh --for-plan exited $?: $(cat "$work/for_plan.err")"
[[ -f "$work/for_plan/scene.glb" ]] || fail "no scene.glb"

python3 - "$work/scene/scene.json" "$work/for_plan/scene.json" << 'PY'
import json, sys

def decimate(path):
    steps = json.load(open(path))["surface"]["steps"]
    found = [s for s in steps if s.get("step") == "decimate"]
    assert len(found) == 1, f"{path}: {len(found)} decimate steps"
    return found[0]

plain, for_plan = decimate(sys.argv[1]), decimate(sys.argv[2])
assert for_plan["goal"] == "for_plan", for_plan["goal"]
report = for_plan["for_plan"]
print(f"faces {plain['faces_out']} -> {report['faces_out']}, worst {report['worst_projected_px']} px, "
      f"bound_met {report['bound_met']}, frozen tiles {report['tiles_frozen']}, rounds {report['rounds']}")
assert report["max_error_px"] == 0.5, report["max_error_px"]
assert report["bound_met"] is True, report["bound_met"]
assert 0 < report["worst_projected_px"] <= report["max_error_px"], report["worst_projected_px"]
assert report["worst_unseen_error_m"] <= report["unseen_allowed_error_m"]
assert report["faces_in"] == plain["faces_out"], (report["faces_in"], plain["faces_out"])
assert report["faces_out"] == for_plan["faces_out"] < plain["faces_out"], (for_plan["faces_out"], plain["faces_out"])
tiles = report["tiles"]
assert sum(t["faces_out"] for t in tiles) == report["faces_out"]
assert sum(1 for t in tiles if t["frozen"]) == report["tiles_frozen"]
assert all(t["faces_out"] == t["faces_in"] for t in tiles if t["frozen"]), "a frozen tile lost faces"
assert all(t["worst_projected_px"] <= report["max_error_px"] for t in tiles)
PY

# The same shots made about their own origin, 37 m below the scene's (a point on its ground): the plan is
# moved onto the scene's origin, so it asks for the same mesh.
python3 -c 'import json, sys; s = json.load(open(sys.argv[1])); o = json.load(open(sys.argv[2]))["origin"]
s["origin"] = {"lat_deg": o["lat_deg"], "lon_deg": o["lon_deg"], "height_m": o["height_m"] - 37}
json.dump(s, open(sys.argv[3], "w"))' "$sample/shots.json" "$work/scene/scene.json" "$work/own_origin_shots.json"
"$CINEPATH" plan "$work/own_origin_shots.json" --scene "$work/scene/scene.json" -o "$work/own_origin.json"
mesh "$work/own_origin" --for-plan "$work/own_origin.json" --max-error-px 0.5 2> "$work/own_origin.err" ||
  fail "mesh --for-plan with a plan about its own origin exited $?: $(cat "$work/own_origin.err")"
python3 - "$work/for_plan/scene.json" "$work/own_origin/scene.json" "$work/own_origin.json" "$work/plan.json" << 'PY'
import json, sys
reports = [[s for s in json.load(open(p))["surface"]["steps"] if s.get("step") == "decimate"][0]["for_plan"]
           for p in sys.argv[1:3]]
origins = [json.load(open(p))["origin"] for p in sys.argv[3:5]]
assert origins[0] != origins[1], "the plan about its own origin was made about the scene's"
keys = ("faces_out", "tiles_frozen", "worst_projected_px")
assert all(reports[0][k] == reports[1][k] for k in keys), [(k, reports[0][k], reports[1][k]) for k in keys]
print(f"own origin: the same for-plan mesh ({reports[1]['faces_out']} faces)")
PY

# A plan of several drones (examples/brighton_beach_team.json): every drone's cameras count; the bound is
# met, and the report names the drone of the worst frame. (Before, such a plan was refused, exit 2.)
"$CINEPATH" plan "$SRC/examples/brighton_beach_team.json" --scene "$work/scene/scene.json" -o "$work/team.json"
mesh "$work/team" --for-plan "$work/team.json" --max-error-px 0.5 2> "$work/team.err" ||
  fail "mesh --for-plan with a team plan exited $?: $(cat "$work/team.err")"
python3 - "$work/team/scene.json" "$work/team.json" << 'PY'
import json, sys
report = [s for s in json.load(open(sys.argv[1]))["surface"]["steps"] if s.get("step") == "decimate"][0]["for_plan"]
drones = [f["name"] for f in json.load(open(sys.argv[2]))["flights"]]
assert len(drones) == 2, drones
assert report["bound_met"] is True and 0 < report["worst_projected_px"] <= 0.5, report
assert report["worst_camera_drone"] in drones, (report.get("worst_camera_drone"), drones)
print(f"team: {report['faces_out']} faces, worst {report['worst_projected_px']} px in {report['worst_camera_drone']}'s "
      f"frame {report['worst_camera_sample']}")
PY

# A plan without an origin and a missing plan file: exit 2, the file named, no output.
python3 -c 'import json, sys; p = json.load(open(sys.argv[1])); p["origin"] = None; json.dump(p, open(sys.argv[2], "w"))' \
  "$work/plan.json" "$work/no_origin.json"
for case in "no_origin.json:origin: " "no_such_plan.json:cannot read"; do
  plan=$work/${case%%:*}
  expected=${case#*:}
  status=0
  mesh "$work/bad" --for-plan "$plan" 2> "$work/bad.err" || status=$?
  [[ $status -eq 2 ]] || fail "$plan: exit $status, expected 2"
  grep -qF "$plan: $expected" "$work/bad.err" || fail "$plan: expected \"$plan: $expected\" in: $(cat "$work/bad.err")"
  [[ ! -e "$work/bad" ]] || fail "$plan: output written: $(ls -R "$work/bad")"
done
echo "mesh_for_plan: ok"
