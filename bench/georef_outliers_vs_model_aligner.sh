#!/usr/bin/env bash
# Robustness of georeferencing to wrong GPS references: cinepath mesh vs COLMAP 3.8 model_aligner on the
# same inputs (Brighton Beach), with K of the 18 references moved by 50 m (default K = 6, a third).
#   bench/georef_outliers_vs_model_aligner.sh [BUILD_DIR] [DATA_DIR] [K]
# Both tools get the corrupted references; both are scored against the clean ones: the error of every
# camera centre after alignment (ENU metres about one fixed origin), mean / median / max, over all 18
# cameras and over the corrupted ones only. model_aligner runs with RANSAC (--robust_alignment 1) and
# the 3 m inlier threshold cinepath's bench uses; cinepath runs with its defaults.
# Needs: colmap, GeographicLib's CartConvert (geographiclib-tools), Debian's python3.
set -euo pipefail
BUILD=${1:-build}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
DATA=${2:-$ROOT/data/brighton_beach}
K=${3:-6}
CINEPATH=$BUILD/cli/cinepath
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
MODEL=$DATA/colmap/sparse_default

# 1. Corrupt K references deterministically: K images spread evenly through the list, moved 50 m east,
#    north, up, west, south, down in turn (metres → degrees on a sphere of the equatorial radius).
/usr/bin/python3 - "$DATA/refs_gps.txt" "$WORK/refs_bad.txt" "$K" > "$WORK/corrupted.txt" <<'PY'
import math, sys
rows = [l.split() for l in open(sys.argv[1]) if l.strip() and not l.startswith("#")]
k = int(sys.argv[3])
moves = [(50, 0, 0), (0, 50, 0), (0, 0, 50), (-50, 0, 0), (0, -50, 0), (0, 0, -50)]
picked = sorted({(i * len(rows)) // k for i in range(k)}) if k else []
with open(sys.argv[2], "w") as out:
    for i, (name, lat, lon, alt) in enumerate(rows):
        lat, lon, alt = float(lat), float(lon), float(alt)
        if i in picked:
            de, dn, du = moves[picked.index(i) % len(moves)]
            lat += math.degrees(dn / 6378137.0)
            lon += math.degrees(de / (6378137.0 * math.cos(math.radians(lat))))
            alt += du
            print(name)
        out.write("%s %.9f %.9f %.3f\n" % (name, lat, lon, alt))
PY
echo "corrupted ($K of $(grep -c . "$DATA/refs_gps.txt")): $(tr '\n' ' ' < "$WORK/corrupted.txt")"

# The fixed ENU origin: the mean of the clean references (what cinepath picks from clean data).
ORIGIN=$(/usr/bin/python3 -c '
import sys
r=[l.split() for l in open(sys.argv[1]) if l.strip() and not l.startswith("#")]
n=len(r); print("%.9f,%.9f,%.3f" % tuple(sum(float(x[i]) for x in r)/n for i in (1,2,3)))' "$DATA/refs_gps.txt")

# ENU of the clean references about ORIGIN.
enu_of_geodetic() { CartConvert -p 6 -l ${ORIGIN//,/ }; }
awk '!/^#/ && NF {print $2, $3, $4}' "$DATA/refs_gps.txt" | enu_of_geodetic > "$WORK/clean_enu.txt"
awk '!/^#/ && NF {print $1}' "$DATA/refs_gps.txt" > "$WORK/names.txt"
paste -d' ' "$WORK/names.txt" "$WORK/clean_enu.txt" > "$WORK/clean.txt"

# Camera centres C = -R^T t from a COLMAP images.txt: 'NAME cx cy cz' per image.
cat > "$WORK/centres.py" <<'PY'
import sys
lines = [l for l in open(sys.argv[1]) if not l.startswith("#")]
for header in lines[0::2]:
    f = header.split()
    qw, qx, qy, qz, tx, ty, tz = map(float, f[1:8])
    # R from the unit quaternion (world -> camera); centre C = -R^T t.
    R = [[1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qz * qw), 2 * (qx * qz + qy * qw)],
         [2 * (qx * qy + qz * qw), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qx * qw)],
         [2 * (qx * qz - qy * qw), 2 * (qy * qz + qx * qw), 1 - 2 * (qx * qx + qy * qy)]]
    t = (tx, ty, tz)
    c = [-sum(R[r][i] * t[r] for r in range(3)) for i in range(3)]
    print(f[9], "%.6f %.6f %.6f" % tuple(c))
PY

now() { date +%s.%N; }
score() {  # score LABEL FILE_OF(name e n u) TIME_S
  /usr/bin/python3 - "$WORK/clean.txt" "$2" "$WORK/corrupted.txt" "$1" "$3" <<'PY'
import math, statistics, sys
clean = {l.split()[0]: list(map(float, l.split()[1:4])) for l in open(sys.argv[1])}
got = {l.split()[0]: list(map(float, l.split()[1:4])) for l in open(sys.argv[2])}
bad = set(l.strip() for l in open(sys.argv[3]) if l.strip())
err = {n: math.dist(clean[n], got[n]) for n in clean if n in got}
def s(v): return "mean %.3f / median %.3f / max %.3f m" % (statistics.mean(v), statistics.median(v), max(v))
good = [e for n, e in err.items() if n not in bad]
print("%-34s all %d cameras: %s; uncorrupted only: %s; %s s" % (sys.argv[4], len(err), s(list(err.values())), s(good), sys.argv[5]))
PY
}

# 2. COLMAP model_aligner (robust, ECEF), camera centres read back from the aligned model.
mkdir -p "$WORK/aligned" "$WORK/aligned_txt"
t0=$(now)
colmap model_aligner --input_path "$MODEL" --output_path "$WORK/aligned" --ref_images_path "$WORK/refs_bad.txt" \
  --ref_is_gps 1 --alignment_type ecef --robust_alignment 1 --robust_alignment_max_error 3 \
  > "$WORK/aligner.log" 2>&1 || { echo "model_aligner failed:"; tail -5 "$WORK/aligner.log"; }
t1=$(now)
if [[ -f "$WORK/aligned/images.bin" ]]; then
  colmap model_converter --input_path "$WORK/aligned" --output_path "$WORK/aligned_txt" --output_type TXT > /dev/null 2>&1
  /usr/bin/python3 "$WORK/centres.py" "$WORK/aligned_txt/images.txt" > "$WORK/ma_ecef.txt"
  cut -d' ' -f2- "$WORK/ma_ecef.txt" | CartConvert -r -p 9 | enu_of_geodetic > "$WORK/ma_enu.txt"
  paste -d' ' <(cut -d' ' -f1 "$WORK/ma_ecef.txt") "$WORK/ma_enu.txt" > "$WORK/ma.txt"
  score "model_aligner (robust, 3 m)" "$WORK/ma.txt" "$(echo "$t1 - $t0" | bc)"
fi

# 3. cinepath. With the bundle adjustment, camera centre = reference + residual (final_fit's
#    residual_enu_m is fitted - reference, after the adjustment); similarity only, the COLMAP camera
#    centres mapped by scene.json's enu_from_colmap.
mkdir -p "$WORK/model_txt"
colmap model_converter --input_path "$MODEL" --output_path "$WORK/model_txt" --output_type TXT > /dev/null 2>&1
/usr/bin/python3 "$WORK/centres.py" "$WORK/model_txt/images.txt" > "$WORK/colmap_centres.txt"
for mode in "" "--no-bundle-adjust"; do
  out="$WORK/cinepath$mode"
  t0=$(now)
  status=0
  "$CINEPATH" mesh --colmap "$MODEL" --refs "$WORK/refs_bad.txt" --images "$DATA/images" --origin "$ORIGIN" \
    $mode --no-timestamp -o "$out" 2> "$out.stderr" || status=$?
  t1=$(now)
  if [[ $status -ne 0 ]]; then echo "cinepath $mode: exit $status: $(head -c 300 "$out.stderr")"; continue; fi
  /usr/bin/python3 - "$out/scene.json" "$WORK/colmap_centres.txt" > "$out.txt" <<'PY'
import json, sys
scene = json.load(open(sys.argv[1]))
g = scene["georeferencing"]
fit = g.get("final_fit")
if fit:
    refs = {r["image"]: r["enu_m"] for r in g["references"]}
    for r in fit["residuals"]:
        print(r["image"], "%.6f %.6f %.6f" % tuple(a + b for a, b in zip(refs[r["image"]], r["residual_enu_m"])))
else:
    t = scene["enu_from_colmap"]
    w, x, y, z = t["rotation"]
    R = [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
         [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
         [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]
    for line in open(sys.argv[2]):
        name, *c = line.split()
        c = list(map(float, c))
        e = [t["scale"] * sum(R[i][j] * c[j] for j in range(3)) + t["translation_m"][i] for i in range(3)]
        print(name, "%.6f %.6f %.6f" % tuple(e))
PY
  score "cinepath ${mode:-(default, with BA)} [inliers $(/usr/bin/python3 -c 'import json,sys; g=json.load(open(sys.argv[1]))["georeferencing"]; print("%d/%d" % (g["inliers"], len(g["references"])))' "$out/scene.json")]" "$out.txt" "$(echo "$t1 - $t0" | bc)"
done
