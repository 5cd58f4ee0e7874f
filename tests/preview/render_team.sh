#!/usr/bin/env bash
# `cinepath render` of a plan of several drones (docs/render.md, "Several drones"), on the small
# six-photo Brighton scene of the mesh goldens at 48 px:
#   - OUT/<drone>/ holds each drone's frames (north 9 samples, south 7 at 4 Hz);
#   - OUT/edit/ holds one frame per sample of the shared clock, each the bytes of the live drone's frame:
#     before the first cut (0.5 s) the first cut's drone, south from 1 s, and south's last sample held
#     after its flight ends at 1.5 s; plus the edit's contact sheet;
#   - with --frames 7-8 (south's last sample not rendered) the held frame is rendered for the edit and is
#     the same bytes as in the full run; no temporary file is left;
#   - two shards (--shard 0/2, 1/2) give the same frames as one run;
#   - --contact-sheet PATH writes every drone's tiles to PATH and the edit's beside it (PATH.edit.png);
#   - --overlay names the drone in each frame;
#   - --video is refused for several drones (exit 2).
#   render_team.sh CINEPATH SOURCE_DIR
set -euo pipefail
CINEPATH=$1
SRC=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
scene=$SRC/tests/golden/mesh/brighton6_binary/expected/scene.json

"$CINEPATH" plan "$SRC/tests/export/data/two_drones_shots.json" -o "$work/plan.json"
render=("$CINEPATH" render "$work/plan.json" --scene "$scene" --width-px 48 --spp 4 --quality draft)
"${render[@]}" -o "$work/out"
count() { ls "$1" | grep -c '^frame_[0-9]\{6\}\.png$' || true; }
[[ $(count "$work/out/north") == 9 ]] || fail "north: $(count "$work/out/north") frames, expected 9"
[[ $(count "$work/out/south") == 7 ]] || fail "south: $(count "$work/out/south") frames, expected 7"
[[ $(count "$work/out/edit") == 9 ]] || fail "edit: $(count "$work/out/edit") frames, expected 9"
[[ -s $work/out/edit/contact_sheet.png ]] || fail "no edit/contact_sheet.png"
[[ -z $(ls -A "$work/out/edit" | grep -v -e '^frame_' -e '^contact_sheet.png$') ]] || fail "stray files in edit/"
# Live drone per frame (t = k / 4 s): north before the first cut and until 1 s, south after, holding sample 6.
expect=(north/0 north/1 north/2 north/3 south/4 south/5 south/6 south/6 south/6)
for k in 0 1 2 3 4 5 6 7 8; do
  src=${expect[$k]}
  cmp -s "$work/out/edit/$(printf 'frame_%06d.png' "$k")" \
    "$work/out/${src%/*}/$(printf 'frame_%06d.png' "${src#*/}")" || fail "edit frame $k is not $src"
done
cmp -s "$work/out/north/frame_000004.png" "$work/out/south/frame_000004.png" && fail "north and south drew the same"

# Two shards on the shared clock give the frames of one run (each shard's contact sheet is of its frames).
"${render[@]}" --shard 0/2 -o "$work/shards"
"${render[@]}" --shard 1/2 -o "$work/shards"
diff -r -x contact_sheet.png "$work/out" "$work/shards" > /dev/null || fail "two shards differ from one run"

# Frames 7-8 only: south's last sample (6) is not in the selection; the edit renders it.
"${render[@]}" --frames 7-8 -o "$work/part"
[[ $(count "$work/part/south") == 0 ]] || fail "south has no sample 7 or 8"
[[ $(count "$work/part/north") == 2 ]] || fail "north: frames 7 and 8"
for k in 7 8; do
  cmp -s "$work/part/edit/$(printf 'frame_%06d.png' "$k")" "$work/out/south/frame_000006.png" ||
    fail "held edit frame $k differs from south's last frame"
done
[[ -z $(ls -A "$work/part/edit" | grep -v -e '^frame_' -e '^contact_sheet.png$') ]] || fail "stray files: $(ls -A "$work/part/edit")"

# --contact-sheet: every drone's tiles there, the edit's beside it.
"${render[@]}" --every 4 --contact-sheet "$work/sheet.png" -o "$work/every"
[[ -s $work/sheet.png && -s $work/sheet.edit.png ]] || fail "no sheet.png / sheet.edit.png"
[[ ! -e $work/every/edit/contact_sheet.png ]] || fail "the edit's sheet went into the folder despite --contact-sheet"
[[ $(count "$work/every/edit") == 3 ]] || fail "--every 4: edit frames 0, 4, 8"

# --overlay names the drone in a team's frames: the same plan with north renamed draws another label
# (and nothing else: the frame without the overlay is the same bytes).
sed 's/"north"/"nord"/g' "$work/plan.json" > "$work/renamed.json"
for p in plan renamed; do
  "$CINEPATH" render "$work/$p.json" --scene "$scene" --width-px 400 --spp 1 --quality draft --frames 0 --overlay \
    -o "$work/overlay_$p"
  "$CINEPATH" render "$work/$p.json" --scene "$scene" --width-px 400 --spp 1 --quality draft --frames 0 \
    -o "$work/bare_$p"
done
cmp -s "$work/bare_plan/north/frame_000000.png" "$work/bare_renamed/nord/frame_000000.png" ||
  fail "renaming a drone changed its frame"
cmp -s "$work/overlay_plan/north/frame_000000.png" "$work/overlay_renamed/nord/frame_000000.png" &&
  fail "--overlay does not name the drone"

set +e
"${render[@]}" --video "$work/v.mp4" -o "$work/video" 2> "$work/stderr"
code=$?
set -e
[[ $code == 2 ]] && grep -q -- "--video" "$work/stderr" || fail "--video: exit $code: $(cat "$work/stderr")"
echo "render_team: ok"
