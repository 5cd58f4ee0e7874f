#!/usr/bin/env bash
# `cinepath mesh --images` textures the mesh the same way whatever the thread count: the bundled sample
# meshed and textured on one core (taskset: TBB and Embree see one CPU) and on two, and scene.glb and
# scene.json compared byte for byte. Fails too when the texture is missing (so that a run that silently
# skipped texturing cannot pass).
#   texture_determinism.sh CINEPATH SOURCE_DIR
set -euo pipefail
CINEPATH=$1
SRC=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
sample=$SRC/data/brighton_beach
run() {  # run OUT CPUS
  taskset -c "$2" "$CINEPATH" mesh --colmap "$sample/colmap/sparse_default" --refs "$sample/refs_gps.txt" \
    --images "$sample/images" --quality draft --draco --no-timestamp -o "$1" 2> /dev/null
}
run "$work/one" 0
run "$work/two" 0,1
python3 - "$work/one/scene.json" <<'PY'
import json, sys
t = json.load(open(sys.argv[1]))["texture"]
assert t["faces_textured"] > 0.5 * t["faces"], t
assert t["photos_used"] >= 10, t
PY
grep -q baseColorTexture "$work/one/scene.glb" || { echo "scene.glb has no baseColorTexture"; exit 1; }
status=0
for f in scene.glb scene.json; do
  if cmp -s "$work/one/$f" "$work/two/$f"; then
    echo "$f: identical on 1 and 2 threads"
  else
    echo "$f: DIFFERS between 1 and 2 threads"
    status=1
  fi
done
exit $status
