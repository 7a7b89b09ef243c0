// Knotwork's version as `knotwork --version` and Help › About show it.
#pragma once

#include <QString>

namespace kw {

/// project(VERSION) of the top CMakeLists.txt and, for a build from a git checkout, the commit
/// it was built from: "0.1.0 (commit 949f04a1b2c3)", "-modified" after the hash when tracked
/// files differed from the commit. Computed at build time (cmake/version.cmake).
QString versionString();

} // namespace kw
