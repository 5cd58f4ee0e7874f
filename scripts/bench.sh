#!/usr/bin/env bash
# Runs the benchmarks that exist and prints their figures (record them in bench/RESULTS.md).
#   scripts/bench.sh BUILD
set -euo pipefail
BUILD=${1:-build}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
for script in "$ROOT"/bench/*.sh; do
  [[ -e "$script" ]] || continue
  echo "== $(basename "$script")"
  bash "$script" "$BUILD"
done
# Google Benchmark and figure-printing programs; the decimation bench on a 1 M-face terrain (its
# --faces 2500000 run in RESULTS.md takes minutes: CGAL's Garland-Heckbert is the slow peer).
for exe in "$BUILD"/bench/bench_plan "$BUILD"/bench/export_bench "$BUILD"/bench/optimize_bench; do
  [[ -x "$exe" ]] || continue
  echo "== $(basename "$exe")"
  "$exe"
done
if [[ -x "$BUILD/bench/mesh_decimate_bench" ]]; then
  echo "== mesh_decimate_bench --faces 1000000"
  "$BUILD/bench/mesh_decimate_bench" --faces 1000000 --ratio 0.1 --samples 200000 \
    --methods meshoptimizer,meshoptimizer_partitioned,cgal_garland_heckbert_probabilistic
fi
# Rule 2 of optimize as a property on 200 random feasible plans among random buildings (20 in make test).
if [[ -x "$BUILD/tests/optimizer/optimizer_test" ]]; then
  echo "== optimizer_test RandomFeasiblePlansStayFeasibleAtEveryPreset, 200 plans"
  CINEPATH_PROPERTY_PLANS=200 "$BUILD/tests/optimizer/optimizer_test" \
    --gtest_filter='OptimizerRules.RandomFeasiblePlansStayFeasibleAtEveryPreset'
fi
