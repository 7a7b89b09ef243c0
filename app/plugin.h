// Loading Knotwork's own modules (shared libraries in build/bin, or lib/knotwork/ when installed)
// on demand, so a command maps a library only when it needs it.
#pragma once

#include "model/error.h"

#include <QLibrary>
#include <QString>

namespace kw::app {

/// Resolves `symbol` in the module lib<name>.so found by kw::modulePath (next to the running
/// executable, or in the installed prefix's lib/knotwork/). The library stays loaded for the life
/// of the process. The error "cannot load <file>: <reason>" when the module or symbol is
/// missing; the function is never null on success.
Expected<QFunctionPointer> resolveModuleSymbol(const QString& name, const char* symbol);

} // namespace kw::app
