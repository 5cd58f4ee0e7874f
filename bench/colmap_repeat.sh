#!/usr/bin/env bash
# COLMAP runs that repeat (`cinepath mesh --images`, photogrammetry/io/colmap_runner.h), measured:
#   bench/colmap_repeat.sh [BUILD_DIR] [PHOTOS_DIR] [RUNS]
# 1. colmap feature_extractor with all threads and with one (wall, user CPU, the ids it gave the images);
# 2. on copies of the one-thread database, in the same run: cinepath's matcher (feature_matcher_bench,
#    2 threads then 1) and colmap exhaustive_matcher (all threads), then matches_importer on cinepath's
#    raw matches: time, raw and verified match counts;
# 3. RUNS whole `cinepath mesh --images` runs: time and md5 of the sparse model and scene.glb.
set -euo pipefail
BUILD=${1:-build}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
PHOTOS=${2:-$ROOT/tests/data/photogrammetry/brighton9_photos}
RUNS=${3:-3}
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
# timed COMMAND...: runs it (its output to $LOG), prints "W s wall, U s user".
timed() {
  /usr/bin/time -o "$WORK/time.txt" -f "%e s wall, %U s user" "$@" > "$LOG" 2>&1
  cat "$WORK/time.txt"
}
count() { sqlite3 "$1" "SELECT COALESCE(SUM(rows), 0) FROM $2"; }
# The images' ids in name order: with several threads COLMAP numbers them as they finish.
image_ids() { sqlite3 "$1" "SELECT image_id FROM images ORDER BY name" | tr '\n' ' '; }

echo "== feature_extractor (OPENCV, one camera, CPU)"
for threads in -1 1; do
  db="$WORK/extract$threads.db"
  LOG="$WORK/extract$threads.log"
  t=$(timed colmap feature_extractor --database_path "$db" --image_path "$PHOTOS" \
    --ImageReader.camera_model OPENCV --ImageReader.single_camera 1 --SiftExtraction.use_gpu 0 \
    --SiftExtraction.num_threads $threads --random_seed 0)
  echo "threads $threads: $t; image ids in name order: $(image_ids "$db")"
done

echo "== matching the one-thread database (same run)"
cp "$WORK/extract1.db" "$WORK/ours.db"
cp "$WORK/extract1.db" "$WORK/colmap.db"
"$BUILD/bench/feature_matcher_bench" "$WORK/ours.db" "$WORK/raw_matches.txt" 2 1
LOG="$WORK/exhaustive.log"
t=$(timed colmap exhaustive_matcher --database_path "$WORK/colmap.db" --SiftMatching.use_gpu 0 --random_seed 0)
echo "colmap exhaustive_matcher: $t; raw $(count "$WORK/colmap.db" matches), verified $(count "$WORK/colmap.db" two_view_geometries)"
LOG="$WORK/importer.log"
t=$(timed colmap matches_importer --database_path "$WORK/ours.db" --match_list_path "$WORK/raw_matches.txt" \
  --match_type raw --SiftMatching.use_gpu 0 --random_seed 0)
echo "colmap matches_importer (cinepath's matches): $t; raw $(count "$WORK/ours.db" matches), verified $(count "$WORK/ours.db" two_view_geometries)"

echo "== $RUNS runs of cinepath mesh --images"
for run in $(seq 1 "$RUNS"); do
  out="$WORK/run$run"
  LOG="$out.log"
  t=$(timed "$BUILD/cli/cinepath" mesh --images "$PHOTOS" -o "$out" --no-timestamp)
  model=$(ls -d "$out"/colmap/sparse/*/ | head -1)
  sums=$(cd "$model" && md5sum cameras.bin images.bin points3D.bin | cut -c1-8 | tr '\n' ' ')
  echo "run $run: $t; cameras/images/points3D.bin $sums; scene.glb $(md5sum < "$out/scene.glb" | cut -c1-8)"
done
