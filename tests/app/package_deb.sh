#!/usr/bin/env bash
# The Debian package (ctest app_package, labels app and package): builds the .deb from the built
# tree with CPack, installs it with `apt-get install ./knotwork_*.deb`, runs the installed
# knotwork --version, info on a sample and a headless render, opens a .knot project through
# the desktop entry (gtk-launch) and through its file type (gio open, as a file manager does),
# then purges the package and checks that none of its files is left. As root on Debian (CI);
# anywhere else, or when a knotwork package is already installed, it is skipped (exit 77).
#   tests/package_deb.sh BUILD_DIR SOURCE_DIR VERSION
set -euo pipefail
build=$1 source=$2 version=$3
fail() { echo "FAIL: $*" >&2; exit 1; }
skip() { echo "SKIPPED: $*"; exit 77; }

[ "$(id -u)" -eq 0 ] || skip "installs a package: needs root (CI runs as root)"
for tool in apt-get dpkg-shlibdeps cpack gtk-launch gio; do
  command -v "$tool" >/dev/null || skip "$tool is missing (tools/dev.sh deps installs it)"
done
if dpkg-query -W -f='${Status}' knotwork 2>/dev/null | grep -q "ok installed"; then
  skip "a knotwork package is already installed here; it is left alone"
fi
[ -n "${DISPLAY:-}" ] || fail "no X display for render and the editor: run under xvfb-run"

work=$(mktemp -d /tmp/knotwork-package.XXXXXX)
installed=0
cleanup() {
  # Editors this test started on its own file, should one not have quit.
  pkill -f -- "$work/my teapot.knot" 2>/dev/null || true
  if [ $installed -eq 1 ]; then
    apt-get purge -y -qq -o DPkg::Lock::Timeout=300 knotwork >/dev/null 2>&1 || true
  fi
  rm -rf "$work"
}
trap cleanup EXIT

echo "cpack"
(cd "$build" && cpack -G DEB -B "$work/cpack" >"$work/cpack.log" 2>&1) ||
  { cat "$work/cpack.log"; fail "cpack -G DEB"; }
deb=$work/cpack/knotwork_${version}_amd64.deb
[ -f "$deb" ] || fail "no $deb: $(ls "$work/cpack")"
depends=$(dpkg-deb -f "$deb" Depends)
echo "Depends: $depends"
for lib in libqt6widgets6 libqt6opengl6 libopenimageio2.4 libocct-data-exchange-7.6 qt6-qpa-plugins; do
  grep -q "$lib" <<<"$depends" || fail "Depends lacks $lib (dpkg-shlibdeps on every ELF file)"
done

echo "apt-get install"
installed=1
DEBIAN_FRONTEND=noninteractive apt-get install -y -qq -o DPkg::Lock::Timeout=300 "$deb" \
  >"$work/apt.log" 2>&1 || { cat "$work/apt.log"; fail "apt-get install $deb"; }
dpkg -L knotwork | sort >"$work/files"

export HOME=$work/home XDG_CONFIG_HOME=$work/home/.config XDG_DATA_HOME=$work/home/.local/share
export XDG_RUNTIME_DIR=$work/runtime
mkdir -p "$XDG_CONFIG_HOME" "$XDG_DATA_HOME" "$XDG_RUNTIME_DIR" && chmod 700 "$XDG_RUNTIME_DIR"
cd "$work"

echo "--version"
out=$(/usr/bin/knotwork --version) || fail "knotwork --version"
[[ $out == "knotwork $version"* ]] || fail "knotwork --version printed '$out'"
echo "info"
/usr/bin/knotwork info /usr/share/knotwork/samples/teapot.knot >/dev/null || fail "info teapot.knot"
echo "render"
QT_QPA_PLATFORM=xcb /usr/bin/knotwork render /usr/share/knotwork/samples/teapot.knot \
  -o "$work/teapot.png" --size 96x64 || fail "render"
[ -s "$work/teapot.png" ] || fail "render wrote nothing"

# The launcher does not wait for the program: wait for the report the editor writes.
wait_opened() {
  local report=$1 file=$2 k
  for k in $(seq 1 120); do
    [ -s "$report" ] && break
    sleep 1
  done
  [ -s "$report" ] || fail "$3: the editor did not report $file opened within 120 s"
  grep -q "^file	$file$" "$report" || fail "$3: $(cat "$report")"
  grep -q "^surfaces	32$" "$report" || fail "$3: $(cat "$report")"
  # ... and then quits: an editor left running would also keep ctest waiting for its output.
  for k in $(seq 1 30); do
    pgrep -f -- "$file" >/dev/null || return 0
    sleep 1
  done
  fail "$3: the editor did not quit after opening $file"
}
cp /usr/share/knotwork/samples/teapot.knot "$work/my teapot.knot"
echo "desktop entry (gtk-launch)"
KNOTWORK_QUIT_AFTER_OPEN=$work/launched.txt QT_QPA_PLATFORM=xcb \
  gtk-launch org.knotwork.Knotwork "$work/my teapot.knot" || fail "gtk-launch"
wait_opened "$work/launched.txt" "$work/my teapot.knot" gtk-launch
echo "file type (gio open)"
[ "$(gio info -a standard::content-type "$work/my teapot.knot" | awk '/content-type/ {print $2}')" \
  = application/x-knotwork-project ] || fail ".knot is not application/x-knotwork-project"
KNOTWORK_QUIT_AFTER_OPEN=$work/opened.txt QT_QPA_PLATFORM=xcb \
  gio open "$work/my teapot.knot" || fail "gio open"
wait_opened "$work/opened.txt" "$work/my teapot.knot" "gio open"

echo "purge"
apt-get purge -y -qq -o DPkg::Lock::Timeout=300 knotwork >"$work/apt.log" 2>&1 ||
  { cat "$work/apt.log"; fail "apt-get purge knotwork"; }
installed=0
while IFS= read -r f; do
  # Folders the package shared with others (/usr/share/applications, hicolor's size
  # folders, ...) stay: dpkg still lists another owner for them.
  [ -d "$f" ] && dpkg-query -S "$f" >/dev/null 2>&1 && continue
  [ -e "$f" ] && fail "$f is left after the purge"
done <"$work/files"
for f in /usr/share/knotwork /usr/lib/knotwork /usr/share/doc/knotwork \
         /usr/share/mime/application/x-knotwork-project.xml; do
  [ -e "$f" ] && fail "$f is left after the purge"
done
dpkg-query -W knotwork >/dev/null 2>&1 && fail "dpkg still lists knotwork"
echo "PASS"
