// Starting the executables that sit next to `knotwork` in build/bin (knotwork-gl, knotwork-bench).
#pragma once

#include <QString>

namespace kw::app {

/// The absolute path of `program` in the folder of the running executable (/proc/self/exe).
QString siblingPath(const char* program);

/// Replaces this process with `program` from siblingPath(), passing argv unchanged (argv[0]
/// included, so messages still say "knotwork ..."). Returns only when that fails, with the
/// one-line reason ("knotwork: cannot run PATH: No such file or directory").
QString execSibling(const char* program, char** argv);

} // namespace kw::app
