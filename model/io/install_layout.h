// Where Knotwork's programs, modules and data are: in the build tree (everything next to
// `knotwork` in build/bin, data in build/share/knotwork) or in an installed prefix (bin/,
// lib/knotwork/, share/knotwork/), found from the running executable, so a prefix can move.
#pragma once

#include <QString>

namespace kw {

/// The folder of the running executable (/proc/self/exe); usable before any Q*Application.
/// Empty only when /proc is not mounted.
QString executableDir();

/// The absolute path of one of Knotwork's programs ("knotwork", "knotwork-gl",
/// "knotwork-bench"): next to the running executable when it is there (the build tree keeps
/// all of them in build/bin), else where an installed prefix keeps it (knotwork in bin/, the
/// others in lib/knotwork/). The path is returned even when no file is there, so that a
/// message can name where it was looked for.
QString programPath(const char* name);

/// The absolute path of the module `fileName` (e.g. "libknotwork_oiio.so"), by the same rule
/// as programPath: next to the running executable, else in the prefix's lib/knotwork/, else
/// in bin/ of the build tree a test executable (build/tests/...) runs from.
QString modulePath(const QString& fileName);

/// The folder of the shared data (samples/, environment/): share/knotwork in the prefix of
/// the running executable (build/share/knotwork in the build tree). Empty when there is none,
/// as for a test executable outside build/bin.
QString dataDir();

} // namespace kw
