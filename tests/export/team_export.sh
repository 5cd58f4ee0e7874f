#!/usr/bin/env bash
# `cinepath export` of a plan of several drones (docs/export.md, "Several drones"), through the binary:
#   - one folder per drone with the file names of a one-drone export (qgc-plan, litchi-csv) and its report;
#   - each mission's home is its drone's `home_enu_m` through the plan's origin (checked against WGS84
#     radii of curvature: the homes lie 30 m from the origin, where that is exact to well under 1 cm);
#   - each mission's waypoints are its own flight's samples (first waypoint = first sample within 1 cm, every
#     waypoint within the 0.5 m deviation of that flight and far from the other);
#   - the report names both drones (text and --json); `info` summarizes the plan per drone and the team;
#   - --home with several drones exits 2 and writes nothing.
#   team_export.sh CINEPATH SOURCE_DIR
set -euo pipefail
CINEPATH=$1
SRC=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

"$CINEPATH" plan "$SRC/tests/export/data/two_drones_shots.json" -o "$work/plan.json"
"$CINEPATH" export "$work/plan.json" --format qgc-plan --format litchi-csv -o "$work/m" > "$work/report.txt"
for d in north south; do
  for f in mission.plan mission.litchi.csv export_report.json; do
    [[ -s $work/m/$d/$f ]] || fail "no $d/$f"
  done
  grep -q "^drone $d -> " "$work/report.txt" || fail "the report lacks drone $d: $(cat "$work/report.txt")"
done
[[ ! -e $work/m/mission.plan ]] || fail "a mission was written outside the drones' folders"
"$CINEPATH" export "$work/plan.json" --format qgc-plan --json -o "$work/j" > "$work/report.json"

python3 - "$work" <<'PY'
import csv, json, math, sys
work = sys.argv[1]
plan = json.load(open(f"{work}/plan.json"))
assert plan["schema"] == "cinepath.plan/2", plan["schema"]
o = plan["origin"]
a, f = 6378137.0, 1 / 298.257223563
e2 = f * (2 - f)
lat0 = math.radians(o["lat_deg"])
M = a * (1 - e2) / (1 - e2 * math.sin(lat0) ** 2) ** 1.5  # meridian radius of curvature
N = a / math.sqrt(1 - e2 * math.sin(lat0) ** 2)           # prime vertical
def geodetic(e, n):
    return o["lat_deg"] + math.degrees(n / M), o["lon_deg"] + math.degrees(e / (N * math.cos(lat0)))
def metres(lat1, lon1, lat2, lon2):
    return math.hypot(math.radians(lat1 - lat2) * M, math.radians(lon1 - lon2) * N * math.cos(lat0))
flights = {fl["name"]: fl for fl in plan["flights"]}
assert sorted(flights) == ["north", "south"], sorted(flights)
def samples(name):
    return [(s["lat_deg"], s["lon_deg"]) if "lat_deg" in s else (s["geodetic"]["lat_deg"], s["geodetic"]["lon_deg"])
            for s in flights[name]["samples"]]
for name, other in (("north", "south"), ("south", "north")):
    home_enu = flights[name]["home_enu_m"]
    want = geodetic(home_enu[0], home_enu[1])
    mission = json.load(open(f"{work}/m/{name}/mission.plan"))
    home = mission["mission"]["plannedHomePosition"]
    err = metres(home[0], home[1], *want)
    assert err < 0.01, f"{name}: home {home[:2]} is {err:.4f} m from its home_enu_m {home_enu} ({want})"
    own, theirs = samples(name), samples(other)
    points = [(i["params"][4], i["params"][5]) for i in mission["mission"]["items"]
              if i.get("command") == 16]
    assert points, f"{name}: no NAV_WAYPOINT"
    assert metres(*points[0], *own[0]) < 0.01, f"{name}: first waypoint {points[0]} is not its first sample {own[0]}"
    for p in points:
        near = min(metres(*p, *s) for s in own)
        far = min(metres(*p, *s) for s in theirs)
        assert near < 0.5, f"{name}: waypoint {p} is {near:.3f} m from its flight"
        assert far > 10, f"{name}: waypoint {p} lies on {other}'s flight"
    rows = list(csv.DictReader(open(f"{work}/m/{name}/mission.litchi.csv")))
    assert rows, f"{name}: empty Litchi CSV"
    first = (float(rows[0]["latitude"]), float(rows[0]["longitude"]))
    assert metres(*first, *own[0]) < 0.01, f"{name}: Litchi's first waypoint {first} is not its first sample"
    report = json.load(open(f"{work}/m/{name}/export_report.json"))
    assert metres(report["home"]["lat_deg"], report["home"]["lon_deg"], *want) < 0.01, f"{name}: report home"
    print(f"{name}: home within {err * 1000:.2f} mm, {len(points)} waypoints on its flight, Litchi {len(rows)} rows")
team = json.load(open(f"{work}/report.json"))
assert [d["name"] for d in team["drones"]] == ["north", "south"], team
PY

# info: one line per drone and the team report.
"$CINEPATH" info "$work/plan.json" > "$work/info.txt"
grep -q "^cinepath plan, 2 drones, 9 samples at 4 Hz" "$work/info.txt" || fail "info: $(cat "$work/info.txt")"
grep -q "^  south: px4-multirotor, 7 samples (1.50 s)" "$work/info.txt" || fail "info lacks south: $(cat "$work/info.txt")"
grep -q "^team: min separation 5 m; no conflicts" "$work/info.txt" || fail "info lacks the team: $(cat "$work/info.txt")"
"$CINEPATH" info "$work/plan.json" --json | python3 -c "import json, sys; d = json.load(sys.stdin); \
assert [f['name'] for f in d['drones']] == ['north', 'south'] and len(d['edit']) == 2 and d['team']['clear'], d"

# --home cannot be every drone's take-off point.
set +e
"$CINEPATH" export "$work/plan.json" --format qgc-plan --home 46.84,-91.99,200 -o "$work/home" 2> "$work/stderr"
code=$?
set -e
[[ $code -eq 2 ]] || fail "--home with two drones: exit $code, expected 2"
grep -q -- "--home: .* 2 drones" "$work/stderr" || fail "--home message: $(cat "$work/stderr")"
[[ ! -e $work/home ]] || fail "--home with two drones wrote $work/home"
echo "team_export: ok"
