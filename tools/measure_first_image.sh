#!/usr/bin/env bash
# First image of a CAD file, interleaved: ROUNDS rounds of (`knotwork render FILE` for each build
# folder given, then OCCT's own viewer reading, meshing, displaying and dumping the same file),
# per image size, so that every case sees the same machine (docs/PERFORMANCE.md, First image of
# a CAD file). Prints one markdown row per size and case: median wall s, CPU s (user + system of
# all threads and processes) and peak RSS MB (GNU time's: the larger of parent and child), with
# the min-max, and the load average before and after. Run from the repository root under X:
#   XDG_RUNTIME_DIR=/tmp/xdg xvfb-run -a -s "-screen 0 1280x1024x24" env QT_QPA_PLATFORM=xcb \
#     bash tools/measure_first_image.sh [BIN_DIR...]
# BIN_DIR defaults to build/bin; give a copy of an older build/bin first to compare. FILE is
# tests/data/hammer.iges (FILE=... sets another IGES file), ROUNDS 10 (ROUNDS=...). The OCCT
# rows need `occt-draw` (see tools/measure_startup.sh for the unversioned library names).
set -euo pipefail

file=${FILE:-tests/data/hammer.iges}
rounds=${ROUNDS:-10}
[ $# -gt 0 ] || set -- build/bin
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
occt=0
if command -v occt-draw >/dev/null; then
  occt=1
  mkdir -p "$tmp/occtlibs"
  for f in /usr/lib/x86_64-linux-gnu/libTK*.so.7; do
    b=$(basename "$f")
    ln -sf "$f" "$tmp/occtlibs/${b%.7}"
  done
fi

# run TIMES_FILE CMD...: appends "wall cpu kb" for one run of CMD.
run() {
  local out=$1
  shift
  /usr/bin/time -f "%e %U %S %M" -o "$tmp/t" "$@" >/dev/null 2>"$tmp/err" || {
    echo "measure_first_image: '$*' failed:" >&2
    cat "$tmp/err" >&2
    exit 1
  }
  awk '{ print $1, $2 + $3, $4 / 1024 }' "$tmp/t" | tail -n 1 >>"$out"
}

summary() { # summary FILE LABEL SIZE
  awk -v label="$2" -v size="$3" '
    { w[NR] = $1; c[NR] = $2; m[NR] = $3 }
    function sort_(a, n,    i, j, t) { for (i = 1; i <= n; i++) for (j = i + 1; j <= n; j++) if (a[j] < a[i]) { t = a[i]; a[i] = a[j]; a[j] = t } }
    function med(a, n) { return n % 2 ? a[(n + 1) / 2] : (a[n / 2] + a[n / 2 + 1]) / 2 }
    END {
      n = NR; sort_(w, n); sort_(c, n); sort_(m, n)
      printf "| %s | %s | %.3f (%.2f–%.2f) | %.3f (%.2f–%.2f) | %.0f |\n", size, label, med(w, n), w[1], w[n], med(c, n), c[1], c[n], med(m, n)
    }' "$1"
}

echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "| size | case | wall s, median (min–max) of $rounds | CPU s | peak RSS MB |"
echo "|---|---|---|---|---|"
for size in 64x64 1024x768; do
  w=${size%x*} h=${size#*x}
  cat >"$tmp/occt.tcl" <<TCL
pload MODELING VISUALIZATION DATAEXCHANGE
igesread $file s *
vinit View1 w=$w h=$h
vdisplay -dispMode 1 s
vfit
vdump $tmp/occt.png
exit
TCL
  for ((r = 0; r < rounds; r++)); do
    k=0
    for bin in "$@"; do
      run "$tmp/times.$size.$k" "$bin/knotwork" render "$file" -o "$tmp/a.png" --size "$size"
      k=$((k + 1))
    done
    if [ $occt = 1 ]; then
      run "$tmp/times.$size.occt" env LD_LIBRARY_PATH="$tmp/occtlibs" occt-draw -b -f "$tmp/occt.tcl"
    fi
  done
  k=0
  for bin in "$@"; do
    summary "$tmp/times.$size.$k" "\`$bin/knotwork render $(basename "$file")\`" "$size"
    k=$((k + 1))
  done
  [ $occt = 0 ] || summary "$tmp/times.$size.occt" "OCCT viewer (occt-draw)" "$size"
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
