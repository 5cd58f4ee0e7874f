#!/usr/bin/env bash
# A stage killed with SIGKILL at any moment leaves no partial output: every output file is either
# absent or byte-identical to the one an uninterrupted run writes (core/file_io.h writes to a hidden
# temporary file in the target folder and renames it). Kills the run at a series of delays spread over
# its duration, so the kill lands before, during and after writing.
#   killed_run.sh NAME OUTPUTS -- COMMAND...     OUTPUTS: comma-separated paths relative to the run's
#                                                output folder; @OUT@ in COMMAND is that folder
set -euo pipefail
name=$1
IFS=, read -r -a outputs <<< "$2"
shift 2
[[ "$1" == "--" ]] && shift
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

run() {  # run OUTDIR: the command with @OUT@ replaced
  local out=$1
  local args=()
  for a in "${@:2}"; do args+=("${a//@OUT@/$out}"); done
  "${args[@]}"
}

# The reference run, and its duration.
mkdir -p "$work/ref"
start=$(date +%s%N)
run "$work/ref" "$@" > /dev/null 2>&1
duration_ns=$(($(date +%s%N) - start))
for o in "${outputs[@]}"; do
  [[ -f "$work/ref/$o" ]] || { echo "$name: the uninterrupted run wrote no $o"; exit 1; }
done

kills=0
partial=0
for fraction in 5 15 30 45 60 70 80 88 94 98; do
  out="$work/k$fraction"
  mkdir -p "$out"
  args=()
  for a in "$@"; do args+=("${a//@OUT@/$out}"); done
  "${args[@]}" > /dev/null 2>&1 &
  pid=$!
  sleep "$(awk -v d="$duration_ns" -v f="$fraction" 'BEGIN { printf "%.6f", d * f / 100 / 1e9 }')"
  if kill -9 "$pid" 2> /dev/null; then kills=$((kills + 1)); fi
  wait "$pid" 2> /dev/null || true
  for o in "${outputs[@]}"; do
    if [[ -e "$out/$o" ]] && ! cmp -s "$out/$o" "$work/ref/$o"; then
      echo "$name: killed at ${fraction}% of the run: $o is partial ($(stat -c %s "$out/$o") of $(stat -c %s "$work/ref/$o") bytes)"
      partial=1
    fi
  done
  # Multi-file outputs are all or nothing only up to the renames, which follow one another: report
  # a run that left some but not all of them.
  present=0
  for o in "${outputs[@]}"; do [[ -e "$out/$o" ]] && present=$((present + 1)); done
  if [[ $present -ne 0 && $present -ne ${#outputs[@]} ]]; then
    echo "$name: killed at ${fraction}% of the run: $present of ${#outputs[@]} outputs written (between two renames)"
  fi
done
echo "$name: $kills kills over a $((duration_ns / 1000000)) ms run; no partial file"
exit $partial
