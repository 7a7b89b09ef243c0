// Loads libknotwork_oiio.so on demand: OpenImageIO maps 260 shared libraries, which a render
// that fails early or the editor should not pay for.
#include "render/oiio_loader.h"

#include "model/io/install_layout.h"

#include <QFileInfo>
#include <QLibrary>
#include <QMutex>

namespace kw {

Expected<void*> oiioModuleSymbol(const char* symbol) {
    static QMutex mutex;
    static QString file;    // the module found, once
    static QString failure; // why none was found
    static bool searched = false;
    QMutexLocker lock(&mutex);
    if (!searched) {
        searched = true;
        // Next to the program, in the installed lib/knotwork/, or a test's build/bin.
        const QString candidate = modulePath(QStringLiteral("libknotwork_oiio.so"));
        QLibrary lib(candidate);
        if (!QFileInfo::exists(candidate))
            failure = QStringLiteral("%1 does not exist").arg(candidate);
        else if (lib.load()) // stays loaded: QLibrary does not unload on destruction
            file = candidate;
        else
            failure = lib.errorString();
    }
    if (file.isEmpty())
        return Error(failure);
    QLibrary lib(file);
    void* address = reinterpret_cast<void*>(lib.resolve(symbol));
    if (!address)
        return Error(lib.errorString(), file);
    return address;
}

} // namespace kw
