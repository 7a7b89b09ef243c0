#!/bin/bash
# Packs a built Knotwork, with every shared library it, Qt's xcb plugins, Xvfb and Mesa's
# swrast driver need (glibc and the C++ runtime aside), into .gpu/bundle.tar.xz for a machine
# that has an NVIDIA GPU but none of Debian's packages (docs/PERFORMANCE.md "On a GPU").
# tools/gpu/device_run.sh unpacks and runs it there. Needs a Release/RelWithDebInfo build in
# BUILD (default build/), and Xvfb, xkbcomp and Mesa installed here (the README's test set-up).
#
# Xvfb needs a GLX provider to advertise GLX at all, and Mesa's swrast_dri.so links LLVM
# (117 MB): a stand-in libLLVM-15.so.1 with every symbol the driver imports keeps the bundle
# under the device's 64 MiB. Xvfb runs it as softpipe (GALLIUM_DRIVER=softpipe,
# DRAW_USE_LLVM=0), which never calls LLVM; the client renders on the GPU through NVIDIA's GLX.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=${BUILD:-$ROOT/build}
OUT=$ROOT/.gpu
B=$(mktemp -d)
trap 'rm -rf "$B"' EXIT
mkdir -p "$OUT" "$B"/{bin,lib,fallback,dri,xkb,data,plugins/platforms,plugins/xcbglintegrations}
grep -qx "/.gpu/" "$ROOT/.git/info/exclude" 2>/dev/null || echo "/.gpu/" >> "$ROOT/.git/info/exclude"

for f in knotwork knotwork-gl knotwork-bench libknotwork_occt.so libknotwork_occt_brep.so \
         libknotwork_occt_iges.so libknotwork_occt_step.so; do
    cp "$BUILD/bin/$f" "$B/bin/" && strip "$B/bin/$f"
done
Q=/usr/lib/x86_64-linux-gnu/qt6/plugins
cp $Q/platforms/libqxcb.so "$B/plugins/platforms/"
cp $Q/xcbglintegrations/*.so "$B/plugins/xcbglintegrations/"
cp /usr/bin/Xvfb /usr/bin/xkbcomp "$B/bin/"
cp /usr/lib/x86_64-linux-gnu/dri/swrast_dri.so "$B/dri/"
cp -r /usr/share/X11/xkb/. "$B/xkb/"
# Motor-c (2.6 MB), fuselage and tube_surf (the edit loop's free-form parts) are not in
# tests/data; the others are.
for f in Motor-c.brep fuselage.stp tube_surf.igs; do
    [ -f "${SHARED_DATA:-$ROOT/../shared/data}/$f" ] && cp "${SHARED_DATA:-$ROOT/../shared/data}/$f" "$B/data/"
done

skip='^(linux-vdso|libc\.so|libm\.so|libdl\.so|libpthread\.so|librt\.so|ld-linux|libstdc\+\+|libgcc_s|libLLVM|libz3)'
for e in "$B"/bin/* "$B"/plugins/*/*.so "$B"/dri/*.so; do
    ldd "$e" 2>/dev/null | awk '$3 ~ /^\// {print $1, $3}'
done | sort -u | while read -r n p; do
    echo "$n" | grep -Eq "$skip" || cp -L "$p" "$B/lib/$n"
done
# libglvnd: the NVIDIA vendor libraries come from the device.
for n in libGLX.so.0 libGLdispatch.so.0 libOpenGL.so.0 libEGL.so.1 libGL.so.1; do
    cp -L /usr/lib/x86_64-linux-gnu/$n "$B/lib/"
done
# Only where the device's C++ runtime is older than GCC 12's (device_run.sh checks).
cp -L /lib/x86_64-linux-gnu/libstdc++.so.6 /lib/x86_64-linux-gnu/libgcc_s.so.1 "$B/fallback/"

# The LLVM stand-in: each function the driver imports returns 0, each object is zeroed.
objdump -T "$B/dri/swrast_dri.so" | awk '/\(LLVM_15\)/ {print $2, $NF}' | sort -u |
    awk '$1 == "DF" {print "void *" $2 "(void) { return 0; }"}
         $1 == "DO" {print "char " $2 "[512] __attribute__((aligned(16)));"}' > "$B/llvm_stub.c"
echo 'LLVM_15 { global: *; };' > "$B/llvm_stub.map"
gcc -shared -fPIC -O1 -o "$B/lib/libLLVM-15.so.1" -Wl,-soname,libLLVM-15.so.1 \
    -Wl,--version-script="$B/llvm_stub.map" "$B/llvm_stub.c"
rm "$B/llvm_stub.c" "$B/llvm_stub.map"

tar -C "$B" -cf - . | xz -T2 -6 > "$OUT/bundle.tar.xz"
ls -la "$OUT/bundle.tar.xz"
