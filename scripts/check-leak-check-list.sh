#!/usr/bin/env bash
# `make sanitize` runs the unit tests with LeakSanitizer, except those in the Makefile's NO_LEAK_CHECK:
# LeakSanitizer's own tracer dies ("Tracer caught signal 11") in a process that loaded a plugin with
# dlopen, depending on how many TLS modules the test binary already has, so a plugin test that passes
# today can fail CI after an unrelated change. This finds the test sources that load a plugin (they call
# a loader: core/plugin.h's, the ground's or a subcommand's, or read a photo or its EXIF through one) and
# exits 1, naming each, when one of their GoogleTest suites is not in NO_LEAK_CHECK; exits 0 otherwise.
# Run from anywhere inside the checkout.
set -euo pipefail
cd "$(git -C "$(dirname "$0")" rev-parse --show-toplevel)"
list=$(sed -n 's/^NO_LEAK_CHECK = //p' Makefile)
if [[ -z $list ]]; then
  echo "Makefile: no NO_LEAK_CHECK line"
  exit 1
fi
status=0
while IFS= read -r file; do
  while IFS= read -r suite; do
    case "|$list|" in
      *"|$suite\\.|"*) ;;
      *)
        echo "$file: suite $suite loads a plugin but is not in the Makefile's NO_LEAK_CHECK"
        status=1
        ;;
    esac
  done < <(grep -oE '^TEST(_F|_P)?\([A-Za-z0-9_]+' "$file" | sed -E 's/^TEST(_F|_P)?\(//' | sort -u)
done < <(git grep -lE 'LoadPluginSymbol|LoadGround|LoadCommandPlugin|CINEPATH_TEST_PLUGIN_DIR|ReadExif|ReadPhotoRgb8' -- 'tests/*.cc')
exit $status
