#!/usr/bin/env bash
# The previs page of a plan of several drones in headless Chromium (docs/view.md, "Several drones"): the
# two-drone test plan over the small six-photo Brighton scene loads with no error, draws two flight paths,
# a selector with both drones and the edit, the edit's cuts on the timeline; at t = 1.25 s the camera view
# looks through the drone live in the edit (south). A screenshot is kept in ARTIFACT_DIR. The page of a
# one-drone plan is unchanged (its bytes: tests/golden/view). Exit 77 (skipped) without Chromium.
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
"$CINEPATH" plan "$SRC/tests/export/data/two_drones_shots.json" -o "$work/plan.json" || fail plan
"$CINEPATH" view "$work/plan.json" --scene "$scene" -o "$work/team.html" || fail view
browse "file://$work/team.html#t=1.25" --dump-dom > "$work/dom.html"
state=$(attr data-state "$work/dom.html")
errors=$(attr data-errors "$work/dom.html")
[[ $state == ready && $errors == 0 ]] || fail "state '$state', $errors errors: $(grep -o '<title>[^<]*' "$work/dom.html")"
[[ $(attr data-flights "$work/dom.html") == 2 ]] || fail "data-flights $(attr data-flights "$work/dom.html")"
[[ $(attr data-flight-paths "$work/dom.html") == 2 ]] || fail "flight paths: $(attr data-flight-paths "$work/dom.html")"
[[ $(attr data-edit-cuts "$work/dom.html") == 2 ]] || fail "edit cuts: $(attr data-edit-cuts "$work/dom.html")"
[[ $(grep -o 'class="edit"' "$work/dom.html" | wc -l) == 2 ]] || fail "the timeline lacks the two cuts"
for d in north south edit; do
  grep -q "data-drone=\"$([[ $d == north ]] && echo 0 || ([[ $d == south ]] && echo 1 || echo edit))\"" \
    "$work/dom.html" || fail "no selector button for $d"
done
grep -q 'id="readout"[^>]*data-drone="south"' "$work/dom.html" ||
  fail "at 1.25 s the camera view is not south's (live): $(grep -o 'id="readout"[^>]*' "$work/dom.html")"
browse "file://$work/team.html#t=1.25&view=top" --screenshot="$ARTIFACTS/team_top.png" > /dev/null
browse "file://$work/team.html#t=0.5" --screenshot="$ARTIFACTS/team_3d.png" > /dev/null
[[ -s $ARTIFACTS/team_top.png ]] || fail "no screenshot"
# The team code goes only into a page of several drones.
"$CINEPATH" plan "$SRC/examples/orbit_shots.json" -o "$work/one.json" || fail "plan one drone"
"$CINEPATH" view "$work/one.json" -o "$work/one.html" || fail "view one drone"
grep -q 'several drones (docs/view.md' "$work/team.html" || fail "the team page lacks the team code"
grep -q 'several drones (docs/view.md' "$work/one.html" && fail "a one-drone page holds the team code"
echo "browser_team: ok (screenshots in $ARTIFACTS)"
