#!/bin/bash
# Runs on the GPU machine, in the repository root, with .gpu/bundle.tar.xz beside it
# (tools/gpu/make_bundle.sh): unpacks the bundle, starts Xvfb, checks that OpenGL runs on the
# NVIDIA GPU (GLX through NVIDIA's vendor library, else EGL through Qt's xcb_egl), then runs
# each PHASE given and leaves everything in $OUT (res/results.txt, res/bench.*, results.tgz).
#   peer1024 peer4k zoom8  Knotwork against the OCCT mesh peer (tools/gpu/kw.py)
#   modes                  adaptive against uniform partitions and 4x anti-aliasing
#   bench                  knotwork bench (paper Tables 1 and 2) on the bundled samples
#   editloop scale         knotwork bench --edit-loop per model and the scale table at 10,000
#                          and 100,000 faces, 1920 x 1080 (tools/gpu/phases.sh)
#   debug                  KW_GL_DEBUG=1 renders of two CAD parts: the driver's messages
# LIMIT (seconds, default 570) bounds the whole run; a phase that would start past it is skipped.
# $OUT keeps at most 6 files (the device returns 8): res/go.log, res/results.txt, res/bench.json,
# res/bench.md as they are written, and at the end results.tgz (those and the other logs) and
# images.tgz (the frames rendered).
T0=$(date +%s)
: "${OUT:?OUT must name the folder for the results}"
mkdir -p "$OUT/res" /tmp/kwwork /tmp/kwlogs
exec > >(tee -a "$OUT/res/go.log") 2>&1
left() { echo $((${LIMIT:-570} - ($(date +%s) - T0))); }

echo "== machine"
nvidia-smi -L
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv
head -2 /etc/os-release; ldd --version | head -1; nproc; grep -m1 "model name" /proc/cpuinfo
K=/opt/kw
export KW=$K
if [ ! -x $K/bin/knotwork ]; then
    mkdir -p $K && tar -C $K -xJf .gpu/bundle.tar.xz || exit 3
    # Debian 12's libexpat needs glibc 2.36; an older system keeps its own.
    ldd --version | head -1 | grep -Eq "2\.(3[6-9]|[4-9][0-9])" || mv $K/lib/libexpat.so.1 $K/lib/libexpat.so.1.off
fi
NVGLX=$(find / -xdev -name 'libGLX_nvidia.so.0' 2>/dev/null | head -1)
NV=$(dirname "$NVGLX")
EGLJSON=$(find / -xdev -name '*nvidia*.json' -path '*egl_vendor*' 2>/dev/null | head -1)
echo "NVIDIA GLX: $NVGLX; EGL vendor file: $EGLJSON"
# Xvfb's GLX loads swrast from its compiled-in path and runs xkbcomp from /usr/bin.
[ -e /usr/bin/xkbcomp ] || cp $K/bin/xkbcomp /usr/bin/
D=/usr/lib/x86_64-linux-gnu/dri
mkdir -p $D && { [ -e $D/swrast_dri.so ] || cp $K/dri/swrast_dri.so $D/; }
LD_LIBRARY_PATH=$K/lib GALLIUM_DRIVER=softpipe DRAW_USE_LLVM=0 setsid $K/bin/Xvfb :5 \
    -screen 0 1280x1024x24 -nolisten tcp -fp built-ins -xkbdir $K/xkb > /tmp/kwlogs/xvfb.log 2>&1 &
sleep 3
export DISPLAY=:5 XDG_RUNTIME_DIR=/tmp/xdg QT_QPA_PLATFORM=xcb QT_PLUGIN_PATH=$K/plugins
mkdir -p -m700 /tmp/xdg
export LD_LIBRARY_PATH=$K/lib:$NV
SYSCXX=$(ldconfig -p | grep "libstdc++.so.6 " | head -1 | awk '{print $NF}')
grep -q GLIBCXX_3.4.30 "$SYSCXX" 2>/dev/null || export LD_LIBRARY_PATH=$LD_LIBRARY_PATH:$K/fallback

probe() {
    rm -f /tmp/p.json
    timeout 60 $K/bin/knotwork bench --smoke --tables 1 --sizes 64 --json /tmp/p.json \
        resources/samples/sphere.knot > /dev/null 2> /tmp/p.err
    python3 -c "import json; print(json.load(open('/tmp/p.json'))['machine']['gl'])" 2>&1
}
echo "== GLX, NVIDIA vendor"
export __GLX_VENDOR_LIBRARY_NAME=nvidia
probe
if ! grep -q "NVIDIA" /tmp/p.json 2>/dev/null; then
    echo "== EGL through xcb_egl"
    unset __GLX_VENDOR_LIBRARY_NAME
    export QT_XCB_GL_INTEGRATION=xcb_egl __EGL_VENDOR_LIBRARY_FILENAMES=$EGLJSON
    probe
fi
if ! grep -q "NVIDIA" /tmp/p.json 2>/dev/null; then
    echo "no OpenGL on the GPU: $(tail -3 /tmp/p.err)"; tail -5 /tmp/kwlogs/xvfb.log
    exit 4
fi

for ph in "$@"; do
    if [ "$(left)" -lt 30 ]; then echo "skip $ph: $(left) s left"; continue; fi
    case $ph in
    bench)
        timeout "$(left)" $K/bin/knotwork bench --frames 20 --samples resources/samples \
            --json "$OUT/res/bench.json" --markdown "$OUT/res/bench.md" --plots /tmp/kwwork \
            > /dev/null 2> /tmp/kwlogs/bench.err
        echo "bench rc $?" ;;
    editloop | scale)
        KW_DATA=$K/data timeout "$(left)" bash tools/gpu/phases.sh "$ph"
        echo "$ph rc $?" ;;
    debug)
        for m in tests/data/hammer.iges tests/data/Pump_Nut.brep; do
            echo "=== $m" >> /tmp/kwlogs/debug.txt
            KW_GL_DEBUG=1 timeout 120 $K/bin/knotwork render $m -o /tmp/kwwork/debug.png \
                --size 1024x1024 2>&1 | sed 's/[0-9][0-9]*/N/g' | sort | uniq -c | sort -rn |
                head -40 >> /tmp/kwlogs/debug.txt
        done ;;
    *)
        KW_MODES=${KW_MODES:-adaptive,uniform,aa4} timeout "$(left)" python3 tools/gpu/kw.py "$ph" ;;
    esac
    echo "after $ph: $(($(date +%s) - T0)) s"
done
cp /tmp/kwlogs/* "$OUT/res/" 2>/dev/null
# Everything goes into results.tgz; res/ keeps only the four files named above.
tar -C "$OUT" -czf /tmp/results.tgz res &&
    find "$OUT/res" -type f ! -name go.log ! -name results.txt ! -name bench.json \
        ! -name bench.md -delete && mv /tmp/results.tgz "$OUT/"
(cd /tmp/kwwork && ls *.png > /dev/null 2>&1 && tar -czf "$OUT/images.tgz" *.png)
