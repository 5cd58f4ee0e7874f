#!/usr/bin/env bash
# The code's format: every C++ file as clang-format (.clang-format, Google style at 120 columns) would
# write it, and no line of any C++ or CMake file over 120 characters. Lists what differs; exits 1 then.
#   scripts/check-format.sh            every tracked file
#   scripts/check-format.sh FILE...    just these
set -uo pipefail
cd "$(dirname "$0")/.."
if [[ $# -gt 0 ]]; then
  files=("$@")
else
  mapfile -t files < <(git ls-files '*.cc' '*.h' '*.cpp' 'CMakeLists.txt' '*.cmake' | grep -v '^third_party/')
fi
status=0
for f in "${files[@]}"; do
  case "$f" in
    *.cc | *.h | *.cpp)
      if ! clang-format --dry-run --Werror "$f" > /dev/null 2>&1; then
        echo "$f: not formatted (clang-format -i $f)"
        status=1
      fi
      ;;
  esac
  # Characters, not bytes (UTF-8 text such as "≈" counts once); perl is part of every Debian system.
  long=$(perl -CSD -ne 'chomp; print "$ARGV:$.: ", length($_), " characters\n" if length($_) > 120' "$f")
  if [[ -n "$long" ]]; then
    echo "$long"
    status=1
  fi
done
exit $status
