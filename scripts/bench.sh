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
for exe in "$BUILD"/bench/bench_*; do
  [[ -x "$exe" ]] || continue
  echo "== $(basename "$exe")"
  "$exe"
done
