#!/usr/bin/env bash
# The textured mesh as a viewer sees it (bench/RESULTS.md, "Mesh texture"): the Brighton sample meshed
# with the photo texture and with vertex colours only, each rendered from every registered camera's own
# pose and compared with that photo (bench/texture_fidelity.cc: PSNR, NCC over the pixels the mesh
# covers); then leave-one-out: the same mesh textured (in the bench, with the library) from every photo
# but k, rendered from camera k. Also times the textured mesh command (wall clock, and scene.json's time
# of each step).
#
#   bench/texture_fidelity.sh [CINEPATH] [TEXTURE_FIDELITY] [OUTDIR] [QUALITY]
# e.g. bench/texture_fidelity.sh build/cli/cinepath build/bench/texture_fidelity /tmp/texture-fidelity draft
set -euo pipefail
BIN=${1:-build/cli/cinepath}
FID=${2:-build/bench/texture_fidelity}
OUT=${3:-/tmp/texture-fidelity}
QUALITY=${4:-draft}
DATA=data/brighton_beach
IMAGES=$DATA/images
COMMON=(--colmap "$DATA/colmap/sparse_default" --refs "$DATA/refs_gps.txt" --images "$IMAGES" --quality "$QUALITY"
        --draco)
mkdir -p "$OUT"

echo "# timing: textured mesh command, $QUALITY, wall clock (2 runs), load before: $(cut -d' ' -f1-3 /proc/loadavg)"
for i in 1 2; do
  /usr/bin/time -f "%e s wall, %M kB max RSS" "$BIN" mesh "${COMMON[@]}" -o "$OUT/timed" 2>&1 | grep "wall" || true
done
python3 - "$OUT/timed/scene.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
print("# steps (s):", ", ".join(f"{st['step']} {st.get('time_s', '?')}" for st in s["surface"]["steps"]))
print("# bundle adjustment (s):", s["georeferencing"].get("bundle_adjustment", {}).get("time_s", "?"))
t = s["texture"]
print("# texture (s):", json.dumps(t.get("time_s")))
print("# texture:", t["photos_used"], "photos,", t["faces_textured"], "faces textured,", t["faces_vertex_color"],
      "in vertex colour, atlas", t["atlas"]["width_px"], "charts", t["atlas"]["charts"], "texels/pixel",
      t["atlas"]["texels_per_photo_pixel"], "bytes", t["atlas"]["bytes"])
PY

"$BIN" mesh "${COMMON[@]}" --no-timestamp -o "$OUT/textured"
"$BIN" mesh "${COMMON[@]}" --no-timestamp --no-texture -o "$OUT/vertex"
"$FID" "$OUT/textured" "$IMAGES" > "$OUT/textured.tsv"
"$FID" "$OUT/vertex" "$IMAGES" > "$OUT/vertex.tsv"
PX=$(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["texture"]["atlas"]["width_px"])' \
     "$OUT/textured/scene.json")
"$FID" "$OUT/vertex" "$IMAGES" --leave-one-out "$PX" > "$OUT/held_out.tsv"
python3 - "$OUT" <<'PY'
import sys, statistics
out = sys.argv[1]
def read(name):
    rows = {}
    for line in open(f"{out}/{name}.tsv"):
        image, covered, psnr, ncc = line.split("\t")
        rows[image] = (int(covered), float(psnr), float(ncc))
    return rows
v, t, h = read("vertex"), read("textured"), read("held_out")
print("| photo | pixels covered | vertex colours PSNR / NCC | textured PSNR / NCC | textured without it PSNR / NCC |")
print("|---|---|---|---|---|")
for image in t:
    print(f"| {image} | {t[image][0]} | {v[image][1]:.2f} / {v[image][2]:.3f} | {t[image][1]:.2f} / {t[image][2]:.3f} |"
          f" {h[image][1]:.2f} / {h[image][2]:.3f} |")
for label, col in (("mean", statistics.mean), ("median", statistics.median), ("min", min)):
    print(f"| **{label}** | | {col([x[1] for x in v.values()]):.2f} / {col([x[2] for x in v.values()]):.3f} |"
          f" {col([x[1] for x in t.values()]):.2f} / {col([x[2] for x in t.values()]):.3f} |"
          f" {col([x[1] for x in h.values()]):.2f} / {col([x[2] for x in h.values()]):.3f} |")
PY
