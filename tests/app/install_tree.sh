#!/usr/bin/env bash
# The installed tree (ctest app_install, label app): `cmake --install` into a temporary prefix,
# which is then moved elsewhere (relocatable), and from there the installed knotwork runs
# --version, info (a project and a CAD part, through the installed CAD modules), a headless
# render (PNG through the installed OpenImageIO module, the environment map from share/) and
# the editor on a STEP file (imported, KNOTWORK_QUIT_AFTER_OPEN). Then: every RPATH is
# $ORIGIN-relative, no installed file holds the build or source path, and the desktop entry and
# the AppStream file pass desktop-file-validate and appstreamcli (skipped with a note where
# those tools are missing). Needs an X display for render and the editor (run under xvfb-run).
#   tests/install_tree.sh BUILD_DIR SOURCE_DIR VERSION
set -euo pipefail
build=$1 source=$2 version=$3
fail() { echo "FAIL: $*" >&2; exit 1; }

work=$(mktemp -d /tmp/knotwork-install.XXXXXX)
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/first" >/dev/null
mv "$work/first" "$work/moved"
prefix=$work/moved
kw=$prefix/bin/knotwork
export HOME=$work/home XDG_CONFIG_HOME=$work/home/.config XDG_RUNTIME_DIR=$work/runtime
mkdir -p "$HOME" "$XDG_RUNTIME_DIR" && chmod 700 "$XDG_RUNTIME_DIR"

echo "layout"
for f in bin/knotwork lib/knotwork/knotwork-gl lib/knotwork/knotwork-bench \
         lib/knotwork/libknotwork_oiio.so lib/knotwork/libknotwork_occt_step.so \
         share/knotwork/samples/teapot.knot share/knotwork/samples/hammer.iges \
         share/knotwork/environment/studio.png share/applications/org.knotwork.Knotwork.desktop \
         share/mime/packages/org.knotwork.Knotwork.xml share/metainfo/org.knotwork.Knotwork.metainfo.xml \
         share/icons/hicolor/scalable/apps/org.knotwork.Knotwork.svg \
         share/icons/hicolor/48x48/apps/org.knotwork.Knotwork.png share/man/man1/knotwork.1 \
         share/doc/knotwork/README.md share/doc/knotwork/INSTALL.md \
         share/doc/knotwork/USER_GUIDE.md share/doc/knotwork/CLI.md; do
  [ -e "$prefix/$f" ] || fail "$f is not installed"
done

echo "--version"
out=$("$kw" --version) || fail "knotwork --version exited $?"
[[ $out == "knotwork $version"* ]] || fail "knotwork --version printed '$out', not $version"

echo "info"
out=$("$kw" info "$prefix/share/knotwork/samples/teapot.knot") || fail "info teapot.knot"
grep -q "32 surface(s)" <<<"$out" || fail "info teapot.knot does not list 32 surfaces: $out"
# The CAD reader: knotwork runs itself as the child, which loads lib/knotwork's STEP module.
"$kw" info "$source/tests/data/screw.step" >/dev/null || fail "info screw.step (installed CAD reader)"

[ -n "${DISPLAY:-}" ] || fail "no X display for render and the editor: run under xvfb-run"
echo "render"
QT_QPA_PLATFORM=xcb "$kw" render "$prefix/share/knotwork/samples/teapot.knot" -o "$work/teapot.png" \
  --size 96x64 --shading environment || fail "render exited $?"
[ "$(head -c 4 "$work/teapot.png" | od -An -c | tr -d ' ')" = "211PNG" ] || fail "render wrote no PNG"

echo "editor"
KNOTWORK_QUIT_AFTER_OPEN=$work/opened.txt QT_QPA_PLATFORM=xcb timeout 120 \
  "$kw" "$source/tests/data/screw.step" || fail "the editor on screw.step exited $?"
grep -q "^file	$source/tests/data/screw.step$" "$work/opened.txt" || fail "$(cat "$work/opened.txt")"
grep -q "^surfaces	10$" "$work/opened.txt" || fail "screw.step: $(cat "$work/opened.txt")"

echo "rpath"
while IFS= read -r -d '' f; do
  if head -c 4 "$f" | grep -q "ELF"; then
    readelf -d "$f" | grep -E "R(UN)?PATH" | grep -v '\[\$ORIGIN' &&
      fail "$f has an RPATH not relative to \$ORIGIN" || true
  fi
done < <(find "$prefix" -type f -print0)

echo "no build or source path"
for path in "$source" "$build" "$(realpath "$source")" "$(realpath "$build")" "$work/first"; do
  hits=$(grep -rlF -- "$path" "$prefix" || true)
  [ -z "$hits" ] || fail "installed files contain $path: $hits"
done

echo "desktop entry and AppStream"
if command -v desktop-file-validate >/dev/null; then
  desktop-file-validate "$prefix/share/applications/org.knotwork.Knotwork.desktop" ||
    fail "desktop-file-validate"
else
  echo "SKIPPED desktop-file-validate: not installed (Debian: desktop-file-utils)"
fi
if command -v appstreamcli >/dev/null; then
  appstreamcli validate --no-net "$prefix/share/metainfo/org.knotwork.Knotwork.metainfo.xml" ||
    fail "appstreamcli validate"
else
  echo "SKIPPED appstreamcli validate: not installed (Debian: appstream)"
fi
echo "PASS"
