#!/usr/bin/env bash
# examples/Makefile as a crew runs it, in a temporary copy: `make -j2` builds every stage, a second
# `make` does nothing, and touching the shot list reruns plan and what follows but not the mesh.
#   examples_makefile.sh CINEPATH SOURCE_DIR
set -euo pipefail
CINEPATH=$1
SRC=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
cp "$SRC/examples/Makefile" "$work/Makefile"
cp "$SRC/data/brighton_beach/shots.json" "$work/shots.json"
run() { make -C "$work" --no-print-directory ROOT="$SRC" CINEPATH="$CINEPATH" SHOTS="$work/shots.json" TEAM_SHOTS="$SRC/examples/brighton_beach_team.json" OUT=out "$@"; }

run -j2 > "$work/first.log" 2>&1 || { cat "$work/first.log"; fail "make -j2"; }
for f in scene/scene.json scene/scene.glb plan.json optimized.json contact_sheet.png missions/mission.plan \
  previs.html scene.d plan.d optimize.d render.d export.d view.d; do
  [[ -s $work/out/$f ]] || fail "no out/$f"
done
grep -q "data/brighton_beach/images/DJI_0018.JPG" "$work/out/scene.d" || fail "scene.d lacks the photos"

# Nothing to do the second time.
run -q || fail "a second make would run something: $(run -n)"

# Touching the shot list reruns plan, optimize, render and export, and not mesh.
sleep 1.1
touch "$work/shots.json"
commands=$(run -n)
for stage in plan optimize render view export; do
  grep -q "cinepath $stage " <<< "$commands" || fail "touching shots.json does not rerun $stage"
done
grep -q "cinepath mesh " <<< "$commands" && fail "touching shots.json reruns mesh"
before=$(stat -c %Y "$work/out/scene/scene.json")
run > "$work/second.log" 2>&1 || { cat "$work/second.log"; fail "make after touch"; }
[[ $(stat -c %Y "$work/out/scene/scene.json") == "$before" ]] || fail "the mesh was rebuilt"
[[ "$work/out/plan.json" -nt "$work/shots.json" ]] || fail "plan.json not rebuilt"
run -q || fail "not up to date after the rerun"
# The two-drone target: plan, optimize, a mission per drone, every drone's frames and the edit, the page.
run team > "$work/team.log" 2>&1 || { cat "$work/team.log"; fail "make team"; }
for f in team/plan.json team/plan.svg team/optimized.json team/missions/rocks/mission.plan \
  team/missions/shore/mission.plan team/frames/rocks/frame_000000.png team/frames/shore/frame_000000.png \
  team/frames/edit/frame_000000.png team/frames/edit/contact_sheet.png team/previs.html; do
  [[ -s $work/out/$f ]] || fail "make team: no out/$f"
done
# The team's page shows the edit's rendered frames (view --frames takes render's folder of several drones).
grep -q '"0":"data:image/png;base64' "$work/out/team/previs.html" || fail "the team's page has no rendered frames"
run -q team || fail "a second make team would run something: $(run -n team)"
echo "examples_makefile: ok"
