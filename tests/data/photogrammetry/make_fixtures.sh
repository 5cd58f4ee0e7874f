#!/bin/sh
# Regenerates the brighton6_colmap and brighton9_photos fixtures from the bundled sample (data/brighton_beach). See PROVENANCE.md.
# Needs python3, oiiotool (OpenImageIO) and colmap. Run from the repository root.
set -eu
out=tests/data/photogrammetry
images="DJI_0020.JPG DJI_0021.JPG DJI_0022.JPG DJI_0025.JPG DJI_0026.JPG DJI_0027.JPG"
rm -rf "$out/brighton6_colmap" "$out/brighton9_photos"
mkdir -p "$out/brighton6_colmap/sparse_txt" "$out/brighton9_photos"
python3 "$out/subset_colmap.py" data/brighton_beach/colmap/sparse_default "$out/brighton6_colmap/sparse" 3 $images
colmap model_converter --input_path "$out/brighton6_colmap/sparse" --output_path "$out/brighton6_colmap/sparse_txt" \
  --output_type TXT
for i in $images; do
  grep "^$i " data/brighton_beach/refs_gps.txt >> "$out/brighton6_colmap/refs_gps.txt"
done
for i in $images DJI_0031.JPG DJI_0032.JPG DJI_0033.JPG; do
  oiiotool "data/brighton_beach/images/$i" --resize 800x450 --compression jpeg:80 -o "$out/brighton9_photos/$i"
done
