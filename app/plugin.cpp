// Loading Knotwork's modules (build/bin, or lib/knotwork/ when installed) with QLibrary.
#include "app/plugin.h"

#include "model/io/install_layout.h"

namespace kw::app {

Expected<QFunctionPointer> resolveModuleSymbol(const QString& name, const char* symbol) {
    const QString file = modulePath(QStringLiteral("lib%1.so").arg(name));
    // Never unloaded: OCCT registers handlers and singletons that must outlive the call.
    auto* library = new QLibrary(file);
    library->setLoadHints(QLibrary::ResolveAllSymbolsHint);
    const QFunctionPointer f = library->resolve(symbol);
    if (!f)
        return Error(QStringLiteral("cannot load %1: %2").arg(file, library->errorString()), file);
    return f;
}

} // namespace kw::app
