// Loading libknotwork_oiio.so (render/oiio/), the module that holds OpenImageIO, on first use.
#pragma once

#include <QString>

namespace kw {

/// The address of `symbol` in libknotwork_oiio.so, loaded once per process: from the
/// executable's folder (build/bin), else from the build tree's bin folder (test executables
/// live elsewhere). Null with *why set when neither has a loadable module or the symbol is
/// missing.
void* oiioModuleSymbol(const char* symbol, QString* why);

} // namespace kw
