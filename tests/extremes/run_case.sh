#!/usr/bin/env bash
# One row of tests/extremes/cases.txt: run it and check the exit code and the text.
#   run_case.sh CINEPATH CASES_FILE NAME OUT_ROOT
set -uo pipefail
CINEPATH=$1
CASES=$2
NAME=$3
OUT_ROOT=$4
DATA=$(cd "$(dirname "$CASES")/data" && pwd)
line=$(grep -E "^${NAME//./\\.} \|" "$CASES") || { echo "no case $NAME"; exit 1; }
IFS='|' read -r _ expected_exit expected_text args <<< "$line"
expected_exit=$(echo "$expected_exit" | xargs)
expected_text=$(echo "$expected_text" | sed 's/^ *//; s/ *$//')
OUT=$OUT_ROOT/$NAME
rm -rf "$OUT"
mkdir -p "$OUT"
args=${args//@DATA@/$DATA}
args=${args//@OUT@/$OUT}
# shellcheck disable=SC2086  # the arguments are words, none with spaces
"$CINEPATH" $args > "$OUT/output.txt" 2>&1
status=$?
if [[ $status != "$expected_exit" ]]; then
  echo "$NAME: exit $status, expected $expected_exit"
  cat "$OUT/output.txt"
  exit 1
fi
if [[ -n $expected_text ]] && ! grep -qF -- "$expected_text" "$OUT/output.txt"; then
  echo "$NAME: the output lacks '$expected_text'"
  cat "$OUT/output.txt"
  exit 1
fi
echo "$NAME: exit $status as expected"
