// Loads libknotwork_oiio.so on demand: OpenImageIO maps 260 shared libraries, which a render
// that fails early or the editor should not pay for.
#include "render/oiio_loader.h"

#include <QCoreApplication>
#include <QFileInfo>
#include <QLibrary>
#include <QMutex>
#include <QStringList>

#ifndef KW_MODULE_DIR
#define KW_MODULE_DIR ""
#endif

namespace kw {

void* oiioModuleSymbol(const char* symbol, QString* why) {
    static QMutex mutex;
    static QString file;    // the module found, once
    static QString failure; // why none was found
    static bool searched = false;
    QMutexLocker lock(&mutex);
    if (!searched) {
        searched = true;
        QStringList dirs;
        if (QCoreApplication::instance())
            dirs << QCoreApplication::applicationDirPath();
        dirs << QStringLiteral(KW_MODULE_DIR);
        for (const QString& dir : dirs) {
            const QString candidate = dir + QStringLiteral("/libknotwork_oiio.so");
            if (dir.isEmpty() || !QFileInfo::exists(candidate))
                continue;
            QLibrary lib(candidate);
            if (lib.load()) { // stays loaded: QLibrary does not unload on destruction
                file = candidate;
                break;
            }
            failure = lib.errorString();
        }
        if (file.isEmpty() && failure.isEmpty())
            failure = QStringLiteral("libknotwork_oiio.so is not in %1")
                          .arg(dirs.join(QStringLiteral(" or ")));
    }
    if (file.isEmpty()) {
        *why = failure;
        return nullptr;
    }
    QLibrary lib(file);
    void* address = reinterpret_cast<void*>(lib.resolve(symbol));
    if (!address)
        *why = lib.errorString();
    return address;
}

} // namespace kw
