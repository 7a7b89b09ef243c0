// Loading libknotwork_oiio.so (render/oiio/), the module that holds OpenImageIO, on first use.
#pragma once

#include "model/error.h"

#include <QString>

namespace kw {

/// The address of `symbol` in libknotwork_oiio.so, loaded once per process: from the
/// executable's folder (build/bin), else from the build tree's bin folder (test executables
/// live elsewhere). The error says why when neither has a loadable module or the symbol is
/// missing; the address is never null on success.
Expected<void*> oiioModuleSymbol(const char* symbol);

} // namespace kw
