#!/usr/bin/env bash
# Start-up and first-image cost of knotwork commands next to OpenCASCADE's own viewer
# (docs/PERFORMANCE.md, ## Start-up). Prints one markdown row per case: median wall seconds,
# median CPU seconds (user + system, all threads) and median peak resident memory over RUNS runs
# (/usr/bin/time -v's fields). Run from the repository root, under X for the drawing cases:
#   XDG_RUNTIME_DIR=/tmp/xdg xvfb-run -a -s "-screen 0 1280x1024x24" env QT_QPA_PLATFORM=xcb \
#     bash tools/measure_startup.sh [BIN_DIR] [LABEL]
# BIN_DIR defaults to build/bin; LABEL names the build in the first column (e.g. "before").
# The OCCT viewer row needs `occt-draw` (apt occt-draw); its `pload` looks for unversioned
# libTK*.so names that only the -dev packages install, so the script points it at symlinks.
# vdisplay meshes with the viewer's default deflection, as the viewer does for a user (an
# explicit `incmesh h 0.1` on the hammer, in mm, takes ~36 s CPU and 700 MB).
set -euo pipefail

bin=${1:-build/bin}
label=${2:-$bin}
runs=${RUNS:-5}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
hammer=tests/data/hammer.iges

# measure NAME CMD...: runs CMD $runs times, prints "| label | NAME | wall | cpu | MB |".
measure() {
  local name=$1
  shift
  local i
  : >"$tmp/times"
  for ((i = 0; i < runs; i++)); do
    /usr/bin/time -f "%e %U %S %M" -o "$tmp/t" "$@" >/dev/null 2>"$tmp/err" || {
      echo "measure_startup: '$*' failed:" >&2
      cat "$tmp/err" >&2
      exit 1
    }
    tail -n 1 "$tmp/t" >>"$tmp/times"
  done
  awk -v label="$label" -v name="$name" '
    { wall[NR] = $1; cpu[NR] = $2 + $3; mem[NR] = $4 / 1024 }
    function median(a, n,    i, j, t) {
      for (i = 1; i <= n; i++) for (j = i + 1; j <= n; j++) if (a[j] < a[i]) { t = a[i]; a[i] = a[j]; a[j] = t }
      return n % 2 ? a[(n + 1) / 2] : (a[n / 2] + a[n / 2 + 1]) / 2
    }
    END { printf "| %s | %s | %.3f | %.3f | %.0f |\n", label, name, median(wall, NR), median(cpu, NR), median(mem, NR) }
  ' "$tmp/times"
}

echo "| build | command | wall s (median of $runs) | CPU s | peak RSS MB |"
echo "|---|---|---|---|---|"
measure "--version" "$bin/knotwork" --version
measure "--help" "$bin/knotwork" --help
measure "info bicubic.knot" "$bin/knotwork" info resources/samples/bicubic.knot
measure "info teapot.knot" "$bin/knotwork" info resources/samples/teapot.knot
if [ -z "${DISPLAY:-}" ]; then
  echo "measure_startup: no DISPLAY, skipping the render rows (see the header)" >&2
  exit 0
fi
measure "render bicubic.knot 64x64" "$bin/knotwork" render resources/samples/bicubic.knot \
  -o "$tmp/a.png" --size 64x64
for s in resources/samples/*.knot; do
  measure "render $(basename "$s") 1024x768" "$bin/knotwork" render "$s" -o "$tmp/a.png"
done
# hammer.iges: convert to .knot, then render (the first image a user gets from the IGES file).
convert_and_render() {
  "$bin/knotwork" convert "$hammer" "$tmp/hammer.knot" && \
    "$bin/knotwork" render "$tmp/hammer.knot" -o "$tmp/hammer.png" "$@"
}
measure "hammer.iges convert + render 1024x768" bash -c "$(declare -f convert_and_render); \
  bin=$bin hammer=$hammer tmp=$tmp convert_and_render"
measure "hammer.iges convert + render 64x64" bash -c "$(declare -f convert_and_render); \
  bin=$bin hammer=$hammer tmp=$tmp convert_and_render --size 64x64"
# The same first image in one command: render reads the IGES file itself (its CAD reader's child
# process runs beside the OpenGL start-up). Builds before that refuse it; they get no row.
# Peak RSS is the larger of the two processes' peaks (GNU time's, for waited-for children),
# as for convert + render; both run at once here, so their sum at one moment can be higher.
if [[ "$("$bin/knotwork" render --help 2>/dev/null)" == *IGES* ]]; then
  measure "render hammer.iges 1024x768" "$bin/knotwork" render "$hammer" -o "$tmp/direct.png"
  measure "render hammer.iges 64x64" "$bin/knotwork" render "$hammer" -o "$tmp/direct.png" \
    --size 64x64
fi

if command -v occt-draw >/dev/null; then
  mkdir -p "$tmp/occtlibs"
  for f in /usr/lib/x86_64-linux-gnu/libTK*.so.7; do
    b=$(basename "$f")
    ln -sf "$f" "$tmp/occtlibs/${b%.7}"
  done
  for size in "1024 768" "64 64"; do
    set -- $size
    cat >"$tmp/occt.tcl" <<TCL
pload MODELING VISUALIZATION DATAEXCHANGE
igesread $hammer h *
vinit View1 w=$1 h=$2
vdisplay -dispMode 1 h
vfit
vdump $tmp/occt.png
exit
TCL
    label_saved=$label
    label="OCCT viewer"
    measure "hammer.iges read + display (meshes) + dump ${1}x$2" \
      env LD_LIBRARY_PATH="$tmp/occtlibs" occt-draw -b -f "$tmp/occt.tcl"
    label=$label_saved
  done
fi
