#!/usr/bin/env bash
# The previs page of a plan of several drones in headless Chromium (docs/view.md, "Several drones"): the
# two-drone test plan over the small six-photo Brighton scene loads with no error, draws two flight paths,
# a selector with both drones and the edit, the edit's cuts on the timeline; at t = 1.25 s the camera view
# looks through the drone live in the edit (south), and the lens graphs show the edit's lens; #drone=north
# turns both to north; the feasibility box lists both drones' broken limits. A screenshot is kept in ARTIFACT_DIR. A one-drone plan
# is a team of one, drawn by the same code: one flight path, its camera, no selector, no edit, no team line
# (its pictures: browser_test.sh's golden top view). Exit 77 (skipped) without Chromium.
#   browser_team.sh CINEPATH SOURCE_DIR ARTIFACT_DIR
set -uo pipefail
CINEPATH=$1
SRC=$2
ARTIFACTS=$3
CHROMIUM=$(command -v chromium || command -v chromium-browser || true)
[[ -n $CHROMIUM ]] || { echo "SKIP: no chromium"; exit 77; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$ARTIFACTS"
fail() { echo "FAIL: $*" >&2; exit 1; }
browse() {
  local url=$1
  shift
  timeout 120 "$CHROMIUM" --headless --no-sandbox --no-first-run --disable-extensions --disable-dev-shm-usage \
    --user-data-dir="$work/profile" --use-angle=swiftshader --enable-unsafe-swiftshader --hide-scrollbars \
    --force-device-scale-factor=1 --window-size=1600,900 --virtual-time-budget=15000 "$@" "$url" \
    2>> "$work/chromium.log"
}
attr() { grep -o "$1=\"[^\"]*\"" "$2" | head -1 | sed 's/.*="\(.*\)"/\1/'; }
scene=$SRC/tests/golden/mesh/brighton6_binary/expected/scene.json
# South with a lens of its own (50 mm f/5.6; north keeps 35 mm f/4): its camera view must read it.
sed '/"s_orbit"/,/}}/ s/"focal_length_mm": 35, "f_number": 4/"focal_length_mm": 50, "f_number": 5.6/' \
  "$SRC/tests/export/data/two_drones_shots.json" > "$work/shots.json"
grep -q '"focal_length_mm": 50' "$work/shots.json" || fail "the test's shots did not take south's lens"
"$CINEPATH" plan "$work/shots.json" -o "$work/plan.json" || fail plan
"$CINEPATH" view "$work/plan.json" --scene "$scene" -o "$work/team.html" || fail view
browse "file://$work/team.html#t=1.25" --dump-dom > "$work/dom.html"
state=$(attr data-state "$work/dom.html")
errors=$(attr data-errors "$work/dom.html")
[[ $state == ready && $errors == 0 ]] || fail "state '$state', $errors errors: $(grep -o '<title>[^<]*' "$work/dom.html")"
[[ $(attr data-flights "$work/dom.html") == 2 ]] || fail "data-flights $(attr data-flights "$work/dom.html")"
# The HUD's drone list wraps inside the 3D view, the readout inside the panel, at 1600 and at 1024 px.
[[ $(attr data-text-overflow "$work/dom.html") == 0 ]] || fail "text overflow: $(attr data-text-overflow "$work/dom.html")"
browse "file://$work/team.html#t=1.25" --window-size=1024,700 --dump-dom > "$work/dom_narrow.html"
[[ $(attr data-text-overflow "$work/dom_narrow.html") == 0 ]] ||
  fail "text overflow at 1024 px: $(attr data-text-overflow "$work/dom_narrow.html")"
[[ $(attr data-flight-paths "$work/dom.html") == 2 ]] || fail "flight paths: $(attr data-flight-paths "$work/dom.html")"
# The lens graphs' axes (focal length, dioptres, f-number) start at 0 or above, also for north's constant
# lens, whose focus would otherwise span negative dioptres.
ranges=$(attr data-graph-ranges "$work/dom.html")
[[ -n $ranges && $ranges != *-* ]] || fail "lens graph axes below 0: '$ranges'"
[[ $(attr data-edit-cuts "$work/dom.html") == 2 ]] || fail "edit cuts: $(attr data-edit-cuts "$work/dom.html")"
[[ $(grep -o 'class="edit"' "$work/dom.html" | wc -l) == 2 ]] || fail "the timeline lacks the two cuts"
for d in north south edit; do
  grep -q "data-drone=\"$([[ $d == north ]] && echo 0 || ([[ $d == south ]] && echo 1 || echo edit))\"" \
    "$work/dom.html" || fail "no selector button for $d"
done
grep -q 'id="readout"[^>]*data-drone="south"' "$work/dom.html" ||
  fail "at 1.25 s the camera view is not south's (live): $(grep -o 'id="readout"[^>]*' "$work/dom.html")"
# ... and reads south's lens, not the primary's (north: 35 mm f/4).
grep -q 'id="readout"[^>]*data-focal="50.000"' "$work/dom.html" ||
  fail "the readout's lens is not south's: $(grep -o 'id="readout"[^>]*' "$work/dom.html")"
grep -q 'id="lens-overlay">50.0 mm  f/5.6' "$work/dom.html" ||
  fail "the camera view's lens is not south's: $(grep -o 'id="lens-overlay">[^<]*' "$work/dom.html")"
browse "file://$work/team.html#t=1.25&view=top" --screenshot="$ARTIFACTS/team_top.png" > /dev/null
browse "file://$work/team.html#t=0.5" --screenshot="$ARTIFACTS/team_3d.png" > /dev/null
[[ -s $ARTIFACTS/team_top.png ]] || fail "no screenshot"
# The feasibility box leads with the team line (every pair apart, or the conflicts). (Its tooltip and text span
# lines: the DOM is read as one line.)
box() { tr '\n' '\r' < "$1" | grep -o 'id="violations"[^>]*>[^<]*' | tr '\r' '\n'; }
box "$work/dom.html" | grep -q "team: every pair\|separation" || fail "no team line in the feasibility box"
# ... then every drone's broken limits, not only the primary's (north's): south's orbit starts below its
# minimum altitude too, a minimum written "<".
box "$work/dom.html" | grep -q "✖ south: altitude_min: 1 range, worst -25.50 &lt; 1.00 m" ||
  fail "the feasibility box does not name south's broken limit: $(box "$work/dom.html")"
box "$work/dom.html" | grep -q "✖ north: altitude_min" || fail "the feasibility box lost north's: $(box "$work/dom.html")"
# Every drone's keyframes are drawn, not only the primary's.
keys=$(python3 -c 'import json, sys; print(sum(len(f["keyframes"]) for f in json.load(open(sys.argv[1]))["flights"]))' \
  "$work/plan.json")
[[ $(attr data-keyframes "$work/dom.html") == "$keys" ]] ||
  fail "keyframes drawn: $(attr data-keyframes "$work/dom.html"), the plan's drones have $keys"
# The timeline's shots are the edit's: south's orbit where it is live.
grep -q 'class="shot" title="south: s_orbit (ORBIT)"' "$work/dom.html" || fail "the timeline lacks south's shot in the edit"
# The lens graphs follow the camera view: the edit's lens (south's 50 mm at 1.25 s), then north's when the
# selector picks it (#drone=north).
graph() { grep -o '<canvas id="graphs"[^>]*' "$1"; }
graph "$work/dom.html" | grep -q 'data-drone="edit" data-focal="50.000"' ||
  fail "the lens graphs do not show the edit's lens: $(graph "$work/dom.html")"
browse "file://$work/team.html#t=1.25&drone=north" --dump-dom > "$work/dom_north.html"
grep -q 'id="readout"[^>]*data-drone="north"' "$work/dom_north.html" || fail "#drone=north did not select north"
graph "$work/dom_north.html" | grep -q 'data-drone="north" data-focal="35.000"' ||
  fail "the lens graphs do not show north's lens: $(graph "$work/dom_north.html")"
grep -q 'id="lens-title">Lens · north<' "$work/dom_north.html" || fail "the lens heading does not name north"
# A team of one: the same code draws its flight, with no selector, no edit and no team line.
"$CINEPATH" plan "$SRC/examples/orbit_shots.json" -o "$work/one.json" || fail "plan one drone"
"$CINEPATH" view "$work/one.json" -o "$work/one.html" || fail "view one drone"
browse "file://$work/one.html#t=2" --dump-dom > "$work/one_dom.html"
[[ $(attr data-state "$work/one_dom.html") == ready && $(attr data-errors "$work/one_dom.html") == 0 ]] ||
  fail "one drone: state $(attr data-state "$work/one_dom.html")"
[[ $(attr data-flights "$work/one_dom.html") == 1 ]] || fail "one drone: data-flights $(attr data-flights "$work/one_dom.html")"
[[ $(attr data-flight-paths "$work/one_dom.html") == 1 ]] || fail "one drone: no flight path"
grep -q 'id="drones"' "$work/one_dom.html" && fail "one drone: a drone selector"
box "$work/one_dom.html" | grep -q '✔ feasibility\|✖' || fail "one drone: no feasibility line"
box "$work/one_dom.html" | grep -q 'team: every pair' && fail "one drone: a team line"
echo "browser_team: ok (screenshots in $ARTIFACTS)"
