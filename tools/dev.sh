#!/usr/bin/env bash
# Knotwork's one entry point for a fresh Debian 12 machine: install, build, then run or test.
#   tools/dev.sh run    install dependencies, build, open the editor on the teapot sample
#                       (with no display: render it headless to build/teapot.png)
#   tools/dev.sh test   install dependencies, build, run every test through CTest
#   tools/dev.sh deps | build
# Idempotent: packages already installed and an up-to-date build cost a few seconds.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${KW_BUILD_DIR:-$root/build}
sample=$root/resources/samples/teapot.knot
xvfb=(xvfb-run -a -s "-screen 0 1280x1024x24")

packages=(
  build-essential cmake ninja-build pkg-config git
  qt6-base-dev qt6-base-dev-tools libqt6opengl6-dev libglm-dev
  libopenimageio-dev openimageio-tools
  xvfb xauth mesa-utils libgl1-mesa-dri libegl1-mesa-dev libxkbcommon-dev libglu1-mesa-dev
  fonts-dejavu-core
  libocct-data-exchange-dev libocct-modeling-data-dev libocct-modeling-algorithms-dev
  libocct-foundation-dev libtbb-dev
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

build() {
  if [ ! -f "$build/build.ninja" ]; then
    cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo
  fi
  cmake --build "$build" -j "$(nproc)"
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

case "${1:-}" in
  deps) deps ;;
  build) deps; build ;;
  run) deps; build; run ;;
  test) deps; build; test_all ;;
  *) echo "usage: tools/dev.sh run|test|deps|build" >&2; exit 2 ;;
esac
