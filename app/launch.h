// Starting Knotwork's other executables (knotwork-gl, knotwork-bench): next to `knotwork` in
// build/bin, in lib/knotwork/ of an installed prefix.
#pragma once

#include <QString>

namespace kw::app {

/// The absolute path of `program`: next to the running executable in the build tree, in
/// lib/knotwork/ (bin/ for knotwork) of an installed prefix (kw::programPath).
QString siblingPath(const char* program);

/// Replaces this process with `program` from siblingPath(), passing argv unchanged (argv[0]
/// included, so messages still say "knotwork ..."). Returns only when that fails, with the
/// one-line reason ("knotwork: cannot run PATH: No such file or directory").
QString execSibling(const char* program, char** argv);

} // namespace kw::app
