#!/usr/bin/env bash
# Runs check.py in Blender headless; exit 77 (CTest: skipped) with a message when Blender is absent.
#   run_blender.sh gltf|chan OUT_DIR PLAN_JSON [--scene SCENE_JSON]
set -euo pipefail
here=${0%/*}
if ! command -v blender > /dev/null 2>&1; then
  echo "SKIP: blender not found (scripts/install-deps.sh installs Debian's blender)"
  exit 77
fi
exec blender -b --factory-startup --python-exit-code 1 -P "$here/check.py" -- "$@"
