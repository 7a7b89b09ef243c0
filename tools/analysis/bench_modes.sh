#!/usr/bin/env bash
# Frame time of each --shading mode against plain Phong (docs/PERFORMANCE.md ## Analysis).
# Usage (under Xvfb): tools/analysis/bench_modes.sh BUILD_DIR SIZE FRAMES FILE.knot...
# Prints a Markdown table: median frame ms per mode (knotwork render --time-frames) and the
# ratio to phong, measured file by file with the modes interleaved in one run.
set -euo pipefail
build=$1 size=$2 frames=$3
shift 3
modes=(phong gaussian mean max-curvature min-radius zebra isophotes environment draft isocurves)
out=$(mktemp -d)
printf '| file |'
for m in "${modes[@]}"; do printf ' %s |' "$m"; done
printf '\n|---|'
for m in "${modes[@]}"; do printf -- '---|'; done
printf '\n'
for f in "$@"; do
    declare -A ms=()
    for m in "${modes[@]}"; do
        line=$(QT_QPA_PLATFORM=xcb "$build/bin/knotwork" render "$f" -o "$out/x.png" \
            --size "${size}x${size}" --shading "$m" --time-frames "$frames" | grep 'median frame')
        ms[$m]=$(sed -E 's/.*median frame ([0-9.]+) ms.*/\1/' <<<"$line")
    done
    printf '| %s |' "$(basename "$f")"
    for m in "${modes[@]}"; do
        printf ' %s (%.2f×) |' "${ms[$m]}" "$(bc -l <<<"${ms[$m]} / ${ms[phong]}")"
    done
    printf '\n'
done
rm -rf "$out"
