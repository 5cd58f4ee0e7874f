#!/usr/bin/env bash
# `cinepath optimize` through the real binary: bad input exits 2 naming the file and the key, writing
# nothing; --strict exits 3 and writes nothing; the output is a plan every stage reads, marked as
# optimized; the same bytes on every run and at any thread count.
#   tests/optimizer/optimize_cli.sh CINEPATH SOURCE_DIR
set -euo pipefail
CINEPATH=$1
SRC=$2
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

"$CINEPATH" plan "$SRC/examples/orbit_shots.json" -o "$T/plan.json"

# A plan optimized without a scene: same schema, marked, feasible, readable by export and info.
"$CINEPATH" optimize "$T/plan.json" --quality draft --report "$T/report.json" -o "$T/opt.json"
python3 - "$T/opt.json" "$T/report.json" << 'PY'
import json, sys
plan, report = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
assert plan["schema"] == "cinepath.plan/1", plan["schema"]
assert plan["optimized"]["by"] == "cinepath optimize" and plan["optimized"]["quality"] == "draft"
assert plan["optimized"]["scene"] is None
for key in ("terms", "total", "limits", "shots", "solver", "skipped"):
    assert key in report, key
assert "clearance: no scene mesh" in report["skipped"], report["skipped"]
assert report["total"]["after"] <= report["total"]["before"] + 1e-9
PY
"$CINEPATH" export "$T/opt.json" --format qgc-plan -o "$T/mission" > /dev/null
"$CINEPATH" info "$(ls "$T"/mission/*.plan | head -1)" > /dev/null

# The same bytes on every run, and on one core.
"$CINEPATH" optimize "$T/plan.json" --quality draft -o "$T/opt2.json"
taskset -c 0 "$CINEPATH" optimize "$T/plan.json" --quality draft -o "$T/opt3.json"
cmp "$T/opt.json" "$T/opt2.json" || fail "two runs differ"
cmp "$T/opt.json" "$T/opt3.json" || fail "one core differs"
"$CINEPATH" optimize "$T/plan.json" --quality draft -o - | cmp - "$T/opt.json" || fail "stdout differs"

# Bad input: exit 2, the file and the key named, nothing written.
expect_refusal() {  # expect_refusal CODE PATTERN ARGS...
  local code=$1 pattern=$2
  shift 2
  rm -f "$T/out.json"
  set +e
  "$CINEPATH" optimize "$@" -o "$T/out.json" 2> "$T/err"
  local rc=$?
  set -e
  [[ $rc == "$code" ]] || fail "exit $rc, expected $code for $*: $(cat "$T/err")"
  grep -q -- "$pattern" "$T/err" || fail "message lacks '$pattern': $(cat "$T/err")"
  [[ ! -e $T/out.json ]] || fail "output written for $*"
}
sed 's#"cinepath.plan/1"#"cinepath.plan/9"#' "$T/plan.json" > "$T/other_schema.json"
expect_refusal 2 "other_schema.json: schema" "$T/other_schema.json"
python3 - "$T/plan.json" "$T/nan.json" << 'PY'
import json, sys
text = open(sys.argv[1]).read()
plan = json.loads(text)
plan["samples"][5]["focal_length_mm"] = float("nan")
open(sys.argv[2], "w").write(json.dumps(plan))  # Python writes the bare token NaN
PY
expect_refusal 2 "nan.json" "$T/nan.json"
printf '{"origin": {"lat_deg": 46.84265, "lon_deg": -91.99445, "height_m": 153.0}, "mesh": "absent.glb"}' > "$T/scene.json"
expect_refusal 2 "scene.json: mesh" "$T/plan.json" --scene "$T/scene.json"
expect_refusal 2 "quality" "$T/plan.json" --quality best

# --strict: a plan that still breaks a limit after optimizing exits 3 and writes nothing.
python3 - "$T/plan.json" "$T/strict.json" << 'PY'
import json, sys
plan = json.load(open(sys.argv[1]))
plan["drone"]["min_altitude_m"] = 0.0
plan["drone"]["max_altitude_m"] = 1.0  # the orbit flies at 10 m: no 5 m deviation can fix that
json.dump(plan, open(sys.argv[2], "w"))
PY
expect_refusal 3 "after optimizing" "$T/strict.json" --strict --quality draft
# Retiming: an orbit too fast for the drone passes --strict when the shot opts in (longer, the report says by
# how much, the same bytes on one core, export reads it) and is refused when it does not.
python3 - "$T/fast_shots.json" "$T/fast_no_retime_shots.json" << 'PY'
import json, sys
shots = {"schema": "cinepath.shots/1", "frame_rate_hz": 30, "drone": "px4-multirotor",
         "origin": {"lat_deg": 46.84265, "lon_deg": -91.99445, "height_m": 153.0},
         "camera": {"filmback": "super35", "width_px": 1920, "height_px": 1080, "min_focal_length_mm": 24,
                    "max_focal_length_mm": 120},
         "actors": [{"name": "keeper", "height_m": 1.8, "position_enu_m": [0, 0, 0]}],
         "shots": [{"name": "fast", "type": "ORBIT", "subject": "keeper", "duration_s": 5, "radius_m": 30,
                    "height_m": 12, "turns": 0.6, "easing": "smootherstep", "optimize": {"retime": True}}]}
json.dump(shots, open(sys.argv[1], "w"))
shots["shots"][0]["optimize"]["retime"] = False
json.dump(shots, open(sys.argv[2], "w"))
PY
"$CINEPATH" plan "$T/fast_shots.json" -o "$T/fast.json" 2> /dev/null
"$CINEPATH" plan "$T/fast_no_retime_shots.json" -o "$T/fast_no_retime.json" 2> /dev/null
"$CINEPATH" optimize "$T/fast.json" --quality draft --strict --report "$T/fast_report.json" -o "$T/fast_opt.json"
taskset -c 0 "$CINEPATH" optimize "$T/fast.json" --quality draft -o "$T/fast_opt1.json"
cmp "$T/fast_opt.json" "$T/fast_opt1.json" || fail "a retimed plan differs on one core"
python3 - "$T/fast.json" "$T/fast_opt.json" "$T/fast_report.json" << 'PY'
import json, sys
before, after, report = (json.load(open(p)) for p in sys.argv[1:4])
assert before["shots"][0]["intent"]["retime"] is True, before["shots"][0]
shot = report["retime"]["shots"][0]
assert shot["shot"] == "fast" and shot["longer_s"] > 0.5 and shot["broken_samples_after"] == 0, shot
grown = len(after["samples"]) - len(before["samples"])
assert abs(grown / before["frame_rate_hz"] - report["retime"]["added_s"]) < 1e-6, (grown, report["retime"])
assert after["optimized"]["retimed_s"] == report["retime"]["added_s"]
assert after["feasibility"]["feasible"], after["feasibility"]
PY
"$CINEPATH" export "$T/fast_opt.json" --format litchi-csv -o "$T/fast_mission" > /dev/null
expect_refusal 3 "retime" "$T/fast_no_retime.json" --strict --quality draft

# Several drones: the team plan of the golden test (north's 24 mm orbit sees south for 1.4 s) comes back
# as version 2 with the conflict resolved, the same bytes on one core, and a report per drone.
"$CINEPATH" plan "$SRC/tests/golden/plan/team_two_drones/shots.json" -o "$T/team.json"
"$CINEPATH" optimize "$T/team.json" --quality standard --strict --report "$T/team_report.json" -o "$T/team_opt.json"
taskset -c 0 "$CINEPATH" optimize "$T/team.json" --quality standard -o "$T/team_opt1.json"
cmp "$T/team_opt.json" "$T/team_opt1.json" || fail "a team plan differs on one core"
python3 - "$T/team.json" "$T/team_opt.json" "$T/team_report.json" << 'PY'
import json, sys
before, after, report = (json.load(open(p)) for p in sys.argv[1:4])
assert after["schema"] == "cinepath.plan/2", after["schema"]
assert [c["limit"] for c in before["team"]["conflicts"]] == ["in_shot"], before["team"]["conflicts"]
assert after["team"]["conflicts"] == [] and after["team"]["clear"], after["team"]
assert after["optimized"]["conflicts_before"] == 1 and after["optimized"]["conflicts_after"] == 0
assert [d["drone"] for d in report["drones"]] == ["north", "south"]
assert len(report["team"]["conflicts_before"]) == 1 and report["team"]["conflicts_after"] == []
for f in after["flights"]:
    assert f["optimized"]["by"] == "cinepath optimize", f["name"]
PY
echo "optimize_cli: ok"
