#!/usr/bin/env bash
# A clone of the repository stands alone: no tracked file may cite material outside it (the planning
# notes the project started from, an issue tracker's numbers). Prints file:line of each such citation
# and exits 1; exits 0 when there is none. Run from anywhere inside the checkout.
set -euo pipefail
cd "$(git -C "$(dirname "$0")" rev-parse --show-toplevel)"
pattern='(^|[^/a-z_-])(design|style|stack|missions|photogrammetry|optics)\.md|\.\./shared|/work/shared|shared/(specs|data)|[Ii]ssue [0-9]'
hits=$(git grep -nE "$pattern" -- . ':!scripts/check-citations.sh' || true)
if [[ -n $hits ]]; then
  echo "citations of material outside the repository (rewrite them to its own docs/):"
  echo "$hits"
  exit 1
fi
