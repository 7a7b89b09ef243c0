#!/bin/bash
# The bench phases of tools/gpu/device_run.sh, also runnable on this machine (under xvfb-run) to
# check them with small sizes before a device run:
#   editloop  `knotwork bench FILE --edit-loop` per model: teapot, hammer, screw and Motor-c at
#             the equal-quality deflections tools/peer_search.py found (docs/PERFORMANCE.md,
#             "The OpenCASCADE mesh peer"), fuselage and tube_surf searched by the bench
#   scale     `knotwork bench --tables scale`: hammer.iges tiled to KW_SCALE_FACES faces at
#             KW_SCALE_SIZE, adaptive partitions, with the drag step; then tube_surf.igs
#             (degree 10 x 5) tiled to KW_SCALE_HIGH_FACES (10000) at uniform 30 x 30
# Environment: KW (prefix holding bin/knotwork; default /opt/kw), KW_DATA (Motor-c.brep,
# fuselage.stp, tube_surf.igs; default $KW/data), OUT (results: $OUT/res/results.txt gets the
# markdown rows; JSON and markdown go to KW_LOGS, default /tmp/kwlogs), KW_EDIT_STEPS (50),
# KW_EDIT_SIZE (1024), KW_SCALE_FACES (10000,100000), KW_SCALE_SIZE (1920x1080).
# Local check, about two minutes:
#   KW=build KW_DATA=../shared/data OUT=/tmp/ph KW_LOGS=/tmp/ph/logs KW_EDIT_STEPS=2 \
#     KW_EDIT_SIZE=64 KW_SCALE_FACES=1,90 KW_SCALE_HIGH_FACES=20 KW_SCALE_SIZE=192x108 \
#     xvfb-run -a -s "-screen 0 1280x1024x24" tools/gpu/phases.sh editloop scale
set -u
K=${KW:-/opt/kw}
DATA=${KW_DATA:-$K/data}
: "${OUT:?OUT must name the folder for the results}"
LOGS=${KW_LOGS:-/tmp/kwlogs}
mkdir -p "$OUT/res" "$LOGS"
# Fine peer meshes of a large part take longer than the CAD child's default limit on a loaded
# machine; the search stops where it is reached either way.
export KNOTWORK_CAD_TIME_LIMIT=${KNOTWORK_CAD_TIME_LIMIT:-120}
rc=0

note() { echo "[$1] $2" | tee -a "$OUT/res/results.txt"; }

editloop() {
    # name, file, deflections (LIN,ANG in model units and degrees) or "search"
    while read -r name file defl; do
        [ -f "$file" ] || { note editloop "$name: no $file, skipped"; continue; }
        args=("$file" --edit-loop --edit-steps "${KW_EDIT_STEPS:-50}" --edit-size
              "${KW_EDIT_SIZE:-1024}" --json "$LOGS/editloop_$name.json"
              --markdown "$LOGS/editloop_$name.md")
        [ "$defl" = search ] || args+=(--peer-deflections "$defl")
        start=$(date +%s)
        if "$K/bin/knotwork" bench "${args[@]}" > /dev/null 2> "$LOGS/editloop_$name.err"; then
            note editloop "$(grep '^| [A-Za-z_-]*\.' "$LOGS/editloop_$name.md") $(($(date +%s) - start)) s"
        else
            rc=1
            note editloop "$name failed: $(tail -1 "$LOGS/editloop_$name.err")"
        fi
    done <<LIST
teapot tests/data/teapot.igs 0.000408,2.5
hammer tests/data/hammer.iges 4.86,2.5
screw tests/data/screw.step 0.0665,5
Motor-c $DATA/Motor-c.brep 0.105,5
fuselage $DATA/fuselage.stp search
tube_surf $DATA/tube_surf.igs search
LIST
}

scale() {
    local start
    start=$(date +%s)
    if "$K/bin/knotwork" bench --tables scale --samples resources/samples \
        --scale-model tests/data/hammer.iges \
        --scale-faces "${KW_SCALE_FACES:-10000,100000}" --scale-size "${KW_SCALE_SIZE:-1920x1080}" \
        --scale-partition-mode adaptive --scale-partitions 1 --json "$LOGS/scale.json" \
        --markdown "$LOGS/scale.md" > /dev/null 2> "$LOGS/scale.err"; then
        grep -E '^### Scale|^\| [0-9]' "$LOGS/scale.md" | while read -r line; do
            note scale "$line"
        done
        note scale "$(grep -m1 'Targets' "$LOGS/scale.md") ($(($(date +%s) - start)) s)"
    else
        rc=1
        note scale "failed: $(tail -1 "$LOGS/scale.err")"
    fi
    # High degree in the paper's uniform mode: tube_surf (degree 10 x 5) tiled to 10,000 faces
    # at 30 x 30, the case that once refused the frame for the buffer limit.
    [ -f "$DATA/tube_surf.igs" ] || { note scale "no $DATA/tube_surf.igs, high degree skipped"; return; }
    start=$(date +%s)
    if "$K/bin/knotwork" bench --tables scale --samples resources/samples \
        --scale-model "$DATA/tube_surf.igs" --scale-faces "${KW_SCALE_HIGH_FACES:-10000}" \
        --scale-size "${KW_SCALE_SIZE:-1920x1080}" --scale-partitions 30 \
        --json "$LOGS/scale_degree10.json" --markdown "$LOGS/scale_degree10.md" \
        > /dev/null 2> "$LOGS/scale_degree10.err"; then
        grep -E '^### Scale|^\| [0-9]' "$LOGS/scale_degree10.md" | while read -r line; do
            note scale "$line"
        done
        note scale "degree 10 x 5 at 30 x 30: $(($(date +%s) - start)) s"
    else
        rc=1
        note scale "degree 10 x 5 failed: $(tail -1 "$LOGS/scale_degree10.err")"
    fi
}

for ph in "$@"; do
    case $ph in
    editloop | scale) $ph ;;
    *) echo "unknown phase $ph (editloop, scale)"; rc=2 ;;
    esac
done
exit $rc
