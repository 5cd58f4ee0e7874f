#!/usr/bin/env bash
# Installs the Debian 12 packages cinepath builds, tests and runs with (docs/dependencies.md),
# only when some are missing. Idempotent: a machine that has them all is left alone.
#   scripts/install-deps.sh                 install what is missing (build, tests, demo)
#   scripts/install-deps.sh --with fuzz     also clang and its libFuzzer runtime (make fuzz, CI)
#   scripts/install-deps.sh --check [...]   exit 0 when nothing is missing, 1 otherwise (installs nothing)
set -euo pipefail
CHECK=0
EXTRA_GROUPS=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --check) CHECK=1 ;;
    --with) EXTRA_GROUPS+=("$2"); shift ;;
    *) echo "install-deps: unknown argument '$1'" >&2; exit 2 ;;
  esac
  shift
done

PACKAGES=(
  # build
  cmake g++ ninja-build ccache pkg-config clang-format
  # libraries (docs/dependencies.md)
  libcgal-dev libopenmesh-dev libgeographiclib-dev libceres-dev libtinygltf-dev libdraco-dev
  libopenimageio-dev openimageio-tools libembree-dev libeigen3-dev nlohmann-json3-dev libsimdjson-dev libcli11-dev
  libfmt-dev libtbb-dev libgtest-dev libbenchmark-dev libstb-dev libmeshoptimizer-dev zlib1g-dev libdeflate-dev
  libpng-dev libjpeg62-turbo-dev libopenexr-dev libsqlite3-dev
  # data and tools the pipeline runs
  proj-data colmap fonts-dejavu-core ffmpeg
  # independent tools the tests compare against
  geographiclib-tools libxml2-utils parallel
  # the browser the previs page is tested in (tests/viewer/browser_test.sh)
  chromium
  # Blender's own glTF and Nuke .chan importers check `export --format gltf-camera|nuke-chan`
  # (tests/interop/blender; 11 packages, 56 MB download, 202 MB installed, 11 s on the CI machine class).
  # Its glTF importer imports numpy, which Debian's blender package does not depend on.
  blender python3-numpy
)
for g in "${EXTRA_GROUPS[@]+"${EXTRA_GROUPS[@]}"}"; do
  case "$g" in
    fuzz) PACKAGES+=(clang libclang-rt-14-dev) ;;
    *) echo "install-deps: unknown group '$g' (known: fuzz)" >&2; exit 2 ;;
  esac
done
# Node.js runs the interop tests (glTF-Validator, node-mavlink, ajv); use the machine's own if present.
if ! command -v node > /dev/null 2>&1 || ! command -v npm > /dev/null 2>&1; then
  PACKAGES+=(nodejs npm)
fi

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2> /dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [[ ${#missing[@]} -eq 0 ]]; then
  exit 0
fi
if [[ $CHECK -eq 1 ]]; then
  echo "missing Debian packages: ${missing[*]}" >&2
  exit 1
fi

SUDO=""
if [[ $(id -u) -ne 0 ]]; then
  if command -v sudo > /dev/null 2>&1 && sudo -n true 2> /dev/null; then
    SUDO="sudo"
  else
    echo "install-deps: these Debian packages are missing and this user cannot install them:" >&2
    echo "  ${missing[*]}" >&2
    echo "Run as root:  apt-get install --no-install-recommends ${missing[*]}" >&2
    exit 1
  fi
fi

echo "install-deps: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
# --no-install-recommends: the recommends add ~300 MB of GTK/VA/Qt extras nobody needs.
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" > /dev/null
echo "install-deps: done" >&2
