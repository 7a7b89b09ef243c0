#!/usr/bin/env bash
# Knotwork's one entry point for a fresh Debian 12 machine: install, build, then run or test.
#   tools/dev.sh run    install dependencies, build what the editor needs (knotwork, knotwork-gl,
#                       the modules; not the tests), open it on the teapot sample (with no
#                       display: render it headless to build/teapot.png)
#   tools/dev.sh test   install dependencies, build everything, run every test through CTest,
#                       then fuzz each libFuzzer harness for 60 s (tests/fuzz, a separate clang
#                       build)
#   tools/dev.sh package   build everything and the Debian package build/package/knotwork_*.deb
#                       (docs/INSTALL.md)
#   tools/dev.sh fuzz [SECONDS]   build the libFuzzer harnesses and run each for SECONDS (60)
#   tools/dev.sh deps | build
# Idempotent: packages already installed and an up-to-date build cost a few seconds.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${KW_BUILD_DIR:-$root/build}
fuzz_build_dir=${KW_FUZZ_BUILD_DIR:-$root/build-fuzz}
fuzz_harnesses=(knot obj trim document step iges)
sample=$root/resources/samples/teapot.knot
# -noreset: by default Xvfb resets when its last client leaves, and a test that connects
# during the reset fails to find the display (seen once in a -j2 run).
xvfb=(xvfb-run -a -s "-screen 0 1280x1024x24 -noreset")

packages=(
  build-essential cmake ninja-build pkg-config git
  qt6-base-dev qt6-base-dev-tools libqt6opengl6-dev libglm-dev
  libopenimageio-dev openimageio-tools
  xvfb xauth mesa-utils libgl1-mesa-dri libegl1-mesa-dev libxkbcommon-dev libglu1-mesa-dev
  fonts-dejavu-core
  libocct-data-exchange-dev libocct-modeling-data-dev libocct-modeling-algorithms-dev
  libocct-foundation-dev libtbb-dev
  occt-draw libocct-draw-dev
  clang libclang-rt-14-dev
  dpkg-dev file desktop-file-utils appstream libgtk-3-bin libglib2.0-bin shared-mime-info
)

as_root() {
  if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi
}

deps() {
  local missing=() p
  for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if [ ${#missing[@]} -gt 0 ]; then
    echo "dev.sh: installing ${missing[*]}" >&2
    as_root apt-get update -qq
    as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${missing[@]}" >/dev/null
  fi
}

# build [TARGET...]: every target (the tests included), or only those named.
build() {
  if [ ! -f "$build/build.ninja" ]; then
    cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo
  fi
  if [ $# -gt 0 ]; then
    cmake --build "$build" -j "$(nproc)" --target "$@"
  else
    cmake --build "$build" -j "$(nproc)"
  fi
}

# The .deb from the built tree (CPack installs it into build/_CPack_Packages, strips it, and
# asks dpkg-shlibdeps for the Depends).
package() {
  (cd "$build" && cpack -G DEB)
  ls "$build"/package/knotwork_*.deb
}

runtime_dir() {
  export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-$(mktemp -d /tmp/knotwork-runtime.XXXXXX)}
  chmod 700 "$XDG_RUNTIME_DIR"
}

run() {
  runtime_dir
  if [ -n "${DISPLAY:-}" ] || [ -n "${WAYLAND_DISPLAY:-}" ]; then
    exec "$build/bin/knotwork" "$sample"
  fi
  echo "dev.sh: no display; rendering $sample headless under Xvfb" >&2
  QT_QPA_PLATFORM=xcb "${xvfb[@]}" "$build/bin/knotwork" render "$sample" \
    -o "$build/teapot.png" --size 1024x768 --aov "$build/teapot_aov.exr"
  echo "dev.sh: wrote $build/teapot.png and $build/teapot_aov.exr" >&2
}

test_all() {
  runtime_dir
  "${xvfb[@]}" ctest --test-dir "$build" --output-on-failure -j "$(nproc)" --timeout 900
}

# The harnesses need clang's libFuzzer and sanitizers: a build of their own (tests/fuzz).
fuzz_build() {
  if [ ! -f "$fuzz_build_dir/build.ninja" ]; then
    CC=clang CXX=clang++ cmake -S "$root/tests/fuzz" -B "$fuzz_build_dir" -G Ninja
  fi
  cmake --build "$fuzz_build_dir" -j "$(nproc)"
}

# Runs every harness for $1 seconds on its seed corpus and every reproducer ever found. New
# inputs collect in build-fuzz/corpus/NAME; a failure leaves its input in build-fuzz/artifacts.
# A single input running longer than 25 s counts as a hang.
fuzz_run() {
  local seconds=${1:-60} h status=0
  for h in "${fuzz_harnesses[@]}"; do
    local work=$fuzz_build_dir/corpus/$h dirs=("$root/tests/fuzz/corpus/$h")
    [ -d "$root/tests/fuzz/repro/$h" ] && dirs+=("$root/tests/fuzz/repro/$h")
    mkdir -p "$work" "$fuzz_build_dir/artifacts"
    echo "dev.sh: fuzzing $h for ${seconds} s" >&2
    if ! "$fuzz_build_dir/fuzz_$h" -max_total_time="$seconds" -timeout=25 -rss_limit_mb=2560 \
        -print_final_stats=1 -artifact_prefix="$fuzz_build_dir/artifacts/$h-" \
        "$work" "${dirs[@]}" 2> "$fuzz_build_dir/fuzz_$h.log"; then
      status=1
      tail -n 40 "$fuzz_build_dir/fuzz_$h.log" >&2
      echo "dev.sh: fuzz_$h failed; the input is in $fuzz_build_dir/artifacts" \
        "(keep it in tests/fuzz/repro/$h/ once fixed)" >&2
    else
      grep -E "^(Done|stat::number_of_executed_units)" "$fuzz_build_dir/fuzz_$h.log" >&2 || true
    fi
  done
  return $status
}

case "${1:-}" in
  deps) deps ;;
  build) deps; build ;;
  # knotwork builds what it starts (knotwork-gl, the OpenImageIO and OCCT modules) and no test.
  run) deps; build knotwork; run ;;
  # The 60 s fuzz smoke run gates like the tests: a finding fails CI (its input is kept in
  # build-fuzz/artifacts); fixed reproducers are replayed by ctest above.
  test) deps; build; test_all; fuzz_build; fuzz_run 60 ;;
  fuzz) deps; fuzz_build; fuzz_run "${2:-60}" ;;
  package) deps; build; package ;;
  *) echo "usage: tools/dev.sh run|test|package|fuzz [SECONDS]|deps|build" >&2; exit 2 ;;
esac
