#!/usr/bin/env bash
# `cinepath view` through the real binary: a plan without an origin views (in local metres, with and
# without a scene), a missing scene mesh / plan / --frames folder exits 2 and writes nothing, --depfile
# names what was read, and two runs give the same bytes; --frames takes a team's render folder (its edit),
# and warns about a folder without frames.
#   view_cli.sh CINEPATH SOURCE_DIR
set -uo pipefail
CINEPATH=$1
SRC=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
plan=$SRC/tests/preview/data/look_down_plan.json  # no origin
scene=$SRC/tests/golden/mesh/brighton6_binary/expected/scene.json
status=0
fail() { echo "FAIL $*"; status=1; }
expect_exit() {  # expect_exit CODE NAME ARGS...
  local code=$1 name=$2
  shift 2
  "$CINEPATH" "$@" > "$work/$name.out" 2> "$work/$name.err"
  local got=$?
  if [[ $got != "$code" ]]; then
    fail "$name: exit $got, expected $code: $(cat "$work/$name.err")"
  else
    echo "ok   $name: exit $got $(head -c 200 "$work/$name.err")"
  fi
}

expect_exit 0 no_origin_with_scene view "$plan" --scene "$scene" -o "$work/a.html" --depfile "$work/a.d"
[[ -s $work/a.html ]] || fail "no_origin_with_scene: no page"
grep -q '"origin":null' "$work/a.html" && fail "no_origin_with_scene: the scene's origin should be shown"
grep -q "a.html: $plan $scene .*scene.glb" "$work/a.d" || fail "depfile: $(cat "$work/a.d")"
expect_exit 0 no_origin_alone view "$plan" -o "$work/b.html"
grep -q '"origin":null' "$work/b.html" || fail "no_origin_alone: expected local metres (origin null)"

expect_exit 0 again view "$plan" --scene "$scene" -o "$work/a2.html"
cmp -s "$work/a.html" "$work/a2.html" || fail "two runs differ"

mkdir -p "$work/nomesh"
printf '{"origin": {"lat_deg": 50.8, "lon_deg": -0.14, "height_m": 40}, "mesh": "scene.glb"}\n' \
  > "$work/nomesh/scene.json"
expect_exit 2 missing_mesh view "$plan" --scene "$work/nomesh/scene.json" -o "$work/c.html"
[[ -e $work/c.html ]] && fail "missing_mesh: a page was written"
grep -q "mesh" "$work/missing_mesh.err" || fail "missing_mesh: the message does not name the mesh"
expect_exit 2 missing_plan view "$work/none.json" -o "$work/d.html"
[[ -e $work/d.html ]] && fail "missing_plan: a page was written"
expect_exit 2 frames_not_a_folder view "$plan" --frames "$work/none" -o "$work/e.html"
[[ -e $work/e.html ]] && fail "frames_not_a_folder: a page was written"
expect_exit 2 no_output view "$plan"

# --frames with the folder `render -o DIR` writes for several drones (DIR/<drone>/, DIR/edit/): the edit's
# frames are shown (before: DIR itself has none, and the page silently had no frames); a folder with no
# frame of the plan is a warning, not an error.
"$CINEPATH" plan "$SRC/tests/export/data/two_drones_shots.json" -o "$work/team.json" 2> /dev/null || fail "team plan"
"$CINEPATH" render "$work/team.json" --scene "$scene" --width-px 48 --every 4 -o "$work/team_frames" > /dev/null 2>&1 ||
  fail "team render"
[[ -d $work/team_frames/edit ]] || fail "render wrote no edit sequence: $(ls "$work/team_frames")"
expect_exit 0 team_frames view "$work/team.json" --scene "$scene" --frames "$work/team_frames" -o "$work/f.html"
edit_frames=$(ls "$work/team_frames/edit" | grep -c '^frame_')
inlined=$(grep -o '"[0-9]*":"data:image/png;base64' "$work/f.html" | wc -l)
[[ $edit_frames -gt 0 && $inlined == "$edit_frames" ]] ||
  fail "team_frames: $inlined frames in the page, $edit_frames in the edit's folder"
grep -q "warning" "$work/team_frames.err" && fail "team_frames: a warning: $(cat "$work/team_frames.err")"
mkdir -p "$work/empty_frames"
expect_exit 0 no_frames view "$plan" --frames "$work/empty_frames" -o "$work/g.html"
grep -q "warning: --frames .*empty_frames: no frame_NNNNNN" "$work/no_frames.err" ||
  fail "no_frames: no warning: $(cat "$work/no_frames.err")"
ls "$work"/*.tmp* > /dev/null 2>&1 && fail "temporary files left behind"
exit $status
