// Loading Knotwork's own modules (shared libraries built next to the executables in build/bin)
// on demand, so a command maps a library only when it needs it.
#pragma once

#include <QLibrary>
#include <QString>

namespace kw::app {

/// Resolves `symbol` in the module lib<name>.so in the folder of the running executable
/// (QCoreApplication must exist). The library stays loaded for the life of the process.
/// nullptr with *error "cannot load <file>: <reason>" when the module or symbol is missing.
QFunctionPointer resolveModuleSymbol(const QString& name, const char* symbol, QString* error);

} // namespace kw::app
