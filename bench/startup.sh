#!/usr/bin/env bash
# Start-up time of subcommands that write no images (goal < 20 ms), against a process that links
# OpenImageIO (oiiotool, ~250 ms of dynamic linking, docs/dependencies.md) as the peer. Needs hyperfine (Debian package).
#   bench/startup.sh BUILD
set -euo pipefail
BUILD=${1:-build}
command -v hyperfine > /dev/null || { echo "startup.sh: hyperfine not installed (apt-get install hyperfine)"; exit 0; }
hyperfine -N --warmup 20 --runs 200 \
  "$BUILD/cli/cinepath --version" \
  "$BUILD/cli/cinepath lens --focal-mm 50 --f-number 2.8 --focus-m 10 --at-m 5" \
  "oiiotool --version"
