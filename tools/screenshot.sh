#!/usr/bin/env bash
# Takes docs/screenshot.png: the real editor window under Xvfb with the --demo scene, made by
# the Create and trim tools (a shaped NURBS patch with a circular hole, a torus), selected, and
# analysed (View > Analysis > mean curvature, with its legend).
# Usage: tools/screenshot.sh [BUILD_DIR] [OUT] [MODE]
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$here/build}"
out="${2:-$here/docs/screenshot.png}"
mode="${3:-mean}"
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-$(mktemp -d)}"
chmod 700 "$XDG_RUNTIME_DIR"
# Fresh settings so a saved window layout does not change the picture.
export XDG_CONFIG_HOME="$(mktemp -d)"
xvfb-run -a -s "-screen 0 1280x1024x24" \
    "$build/bin/knotwork" --size 1440x860 --screenshot "$out" --demo --shading "$mode"
echo "wrote $out"
