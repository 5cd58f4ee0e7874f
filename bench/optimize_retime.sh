#!/usr/bin/env bash
# Retiming (docs/optimize.md, "Retiming") on orbits too fast for every drone profile: how much longer the
# shot gets with cinepath's local slow-down, against the peer of the same run, one uniform stretch of the
# whole shot by its worst ratio (value / limit)^(1 / order) (what slowing the shot's duration_s in the shot
# list does), and what optimize costs with it.
#   bench/optimize_retime.sh BUILD_DIR [OUT_DIR]
set -euo pipefail
BUILD=$1
OUT=${2:-$(mktemp -d)}
CINEPATH=$BUILD/cli/cinepath
mkdir -p "$OUT"
printf '| profile | orbit | shot s | path retimed | rate limits it broke | uniform stretch of that path: s longer | cinepath retime: s longer | slowest factor | feasible after | optimize CPU s without / with retime |\n'
printf '|---|---|---|---|---|---|---|---|---|---|\n'
for profile in px4-multirotor ardupilot-copter dji-m30 dji-mini4pro; do
  for orbit in "20 0.5 6" "40 0.6 8" "60 0.4 5"; do
    read -r radius turns duration <<< "$orbit"
    for retime in true false; do
      python3 - "$OUT/shots_$retime.json" "$profile" "$radius" "$turns" "$duration" "$retime" << 'PY'
import json, sys
path, profile, radius, turns, duration, retime = sys.argv[1:7]
camera = {"filmback": "super35", "width_px": 1920, "height_px": 1080, "min_focal_length_mm": 24,
          "max_focal_length_mm": 120}
if profile == "dji-mini4pro":  # its built-in lens
    camera.update({"min_focal_length_mm": 6.7, "max_focal_length_mm": 6.7, "min_f_number": 1.7,
                   "max_f_number": 1.7, "min_focus_distance_m": 1.0})
json.dump({"schema": "cinepath.shots/1", "frame_rate_hz": 30, "drone": profile,
           "camera": camera,
           "actors": [{"name": "keeper", "height_m": 1.8, "position_enu_m": [0, 0, 0]}],
           "shots": [{"name": "fast", "type": "ORBIT", "subject": "keeper", "duration_s": float(duration),
                      "radius_m": float(radius), "height_m": 12, "turns": float(turns), "direction": "cw",
                      "easing": "smootherstep",
                      "optimize": {"retime": retime == "true"}},
                     {"name": "after", "type": "ORBIT", "subject": "keeper", "duration_s": 6,
                      "radius_m": float(radius), "height_m": 12, "turns": 0.02, "direction": "cw",
                      "start_bearing_deg": 360 * float(turns), "easing": "smootherstep"}]}, open(path, "w"))
PY
      "$CINEPATH" plan "$OUT/shots_$retime.json" -o "$OUT/plan_$retime.json" 2> /dev/null
      /usr/bin/time -f "%U %S" -o "$OUT/time_$retime" "$CINEPATH" optimize "$OUT/plan_$retime.json" --quality draft \
        --report "$OUT/report_$retime.json" -o "$OUT/opt_$retime.json"
    done
    python3 - "$OUT" "$profile" "$radius m, $turns turns" "$duration" << 'PY'
import json, sys
out, profile, orbit, duration = sys.argv[1:5]
order = {"horizontal_speed": 1, "climb_rate": 1, "descent_rate": 1, "yaw_rate": 1, "gimbal_pitch_rate": 1,
         "focal_length_rate": 1, "focus_rate": 1, "aperture_rate": 1, "horizontal_acceleration": 2, "jerk": 3}
report = json.load(open(f"{out}/report_true.json"))
# The uniform stretch of the path cinepath retimed: the plan as given, or optimize's result without retiming.
retimed_from = report.get("retime", {}).get("from", "optimized")
plain = json.load(open(f"{out}/plan_true.json" if retimed_from == "planned" else f"{out}/opt_false.json"))
factor, broken = 1.0, []
for v in plain["feasibility"]["violations"]:
    if v["shot"] == "fast" and v["limit"] in order:
        factor = max(factor, (v["worst_value"] / v["limit_value"]) ** (1 / order[v["limit"]]))
        if v["limit"] not in broken:
            broken.append(v["limit"])
shots = report.get("retime", {}).get("shots", [])
after = json.load(open(f"{out}/opt_true.json"))
cpu = [sum(map(float, open(f"{out}/time_{r}").read().split())) for r in ("false", "true")]
longer = f'{shots[0]["longer_s"]:.2f}' if shots else "not retimed"
slowest = f'{shots[0]["slowest_factor"]:.2f}' if shots else "-"
print(f'| {profile} | {orbit} | {float(duration):g} | {retimed_from} | {", ".join(broken) or "none"} | {(factor - 1) * float(duration):.2f} '
      f'| {longer} | {slowest} | {after["feasibility"]["feasible"]} | {cpu[0]:.2f} / {cpu[1]:.2f} |')
PY
  done
done
