// Loading Knotwork's modules from the executable's folder with QLibrary.
#include "app/plugin.h"

#include <QCoreApplication>
#include <QDir>

namespace kw::app {

QFunctionPointer resolveModuleSymbol(const QString& name, const char* symbol, QString* error) {
    const QString file =
        QDir(QCoreApplication::applicationDirPath()).filePath(QStringLiteral("lib%1.so").arg(name));
    // Never unloaded: OCCT registers handlers and singletons that must outlive the call.
    auto* library = new QLibrary(file);
    library->setLoadHints(QLibrary::ResolveAllSymbolsHint);
    const QFunctionPointer f = library->resolve(symbol);
    if (!f && error)
        *error = QStringLiteral("cannot load %1: %2").arg(file, library->errorString());
    return f;
}

} // namespace kw::app
