#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, preset "fuzz") and runs each for SECONDS from its seed corpus in
# tests/fuzz/corpus/<target>/ (copied, so the repository's corpus is not modified), plus the files its
# seeds.txt names (globs relative to the repository, e.g. the golden plans).
#   scripts/fuzz.sh [SECONDS] [TARGET ...]     default: 60 s each, every target
# Exit status: non-zero when a target crashes, leaks or times out (its reproducer is left in
# build-fuzz/fuzz-artifacts/).
set -euo pipefail
cd "$(dirname "$0")/.."
SECONDS_EACH=${1:-60}
shift || true
cmake --preset fuzz > build-fuzz.configure.log 2>&1 || { cat build-fuzz.configure.log; exit 1; }
TARGETS=("$@")
if [[ ${#TARGETS[@]} -eq 0 ]]; then
  mapfile -t TARGETS < <(ls tests/fuzz/corpus | grep '^fuzz_')
fi
cmake --build build-fuzz -j "${JOBS:-2}" --target "${TARGETS[@]}"
mkdir -p build-fuzz/fuzz-artifacts
for t in "${TARGETS[@]}"; do
  work=$(mktemp -d)
  cp -r "tests/fuzz/corpus/$t/." "$work/"
  # seeds.txt: globs of repository files to seed from as well (the golden plans), not an input itself.
  if [[ -f "$work/seeds.txt" ]]; then
    while read -r pattern; do
      [[ -z $pattern || $pattern == \#* ]] && continue
      for f in $pattern; do
        if [[ -f $f ]]; then cp "$f" "$work/seed_${f//\//_}"; fi
      done
    done < "$work/seeds.txt"
    rm "$work/seeds.txt"
  fi
  echo "fuzz: $t for ${SECONDS_EACH} s" >&2
  start=$(date +%s)
  "build-fuzz/tests/fuzz/$t" -max_total_time="$SECONDS_EACH" -timeout=10 -rss_limit_mb=2048 \
    -artifact_prefix="build-fuzz/fuzz-artifacts/$t-" -print_final_stats=1 "$work" 2> "build-fuzz/$t.log" || {
    tail -40 "build-fuzz/$t.log"
    echo "fuzz: $t FAILED (reproducer in build-fuzz/fuzz-artifacts/)" >&2
    rm -rf "$work"
    exit 1
  }
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "build-fuzz/$t.log" | grep -o '[0-9]*$' || echo '?')
  echo "fuzz: $t ok, $runs runs in $(( $(date +%s) - start )) s" >&2
  rm -rf "$work"
done
