// Atomic file writing: QSaveFile with an explicit flush check, or write-then-rename.
#include "model/io/savefile.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QSaveFile>
#include <QTemporaryFile>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <set>
#include <unistd.h>

namespace kw {

namespace {

// Temporary names of saveViaTemporaryName still in use. A writer library that ends the process
// (libjpeg's default error handler calls exit() on a failed write) would leave its file behind:
// exit() runs atexit handlers, so they are removed there. Leaked on purpose: no destructor
// order to mind at exit.
std::mutex& temporaryMutex() {
    static auto* m = new std::mutex;
    return *m;
}
std::set<QByteArray>& temporaryNames() {
    static auto* names = new std::set<QByteArray>;
    return *names;
}
void removeTemporariesAtExit() {
    std::lock_guard lock(temporaryMutex());
    for (const QByteArray& name : temporaryNames())
        ::unlink(name.constData());
}
struct TemporaryName {
    QByteArray name;
    explicit TemporaryName(const QString& path) : name(QFile::encodeName(path)) {
        static std::once_flag once;
        std::call_once(once, [] { std::atexit(removeTemporariesAtExit); });
        std::lock_guard lock(temporaryMutex());
        temporaryNames().insert(name);
    }
    ~TemporaryName() {
        std::lock_guard lock(temporaryMutex());
        temporaryNames().erase(name);
    }
};

} // namespace

Status saveFileAtomically(const QString& path, const std::function<bool(QIODevice&)>& write) {
    QSaveFile file(path);
    auto failed = [&](const QString& what, const QString& reason) {
        file.cancelWriting();
        return Error(QStringLiteral("%1: %2: %3").arg(path, what, reason), path);
    };
    if (!file.open(QIODevice::WriteOnly))
        return failed(QStringLiteral("cannot open for writing"), file.errorString());
    errno = 0;
    const bool written = write(file);
    // Flush explicitly: Qt 6.4's QSaveFile::commit() ignores a failed final flush.
    if (!written || file.error() != QFileDevice::NoError || !file.flush()) {
        const int err = errno;
        QString reason = file.error() != QFileDevice::NoError ? file.errorString()
                         : err                                ? qt_error_string(err)
                                                              : QStringLiteral("incomplete write");
        return failed(QStringLiteral("cannot write"), reason);
    }
    if (!file.commit())
        return failed(QStringLiteral("cannot save"), file.errorString());
    return ok();
}

Status saveBytesAtomically(const QString& path, const QByteArray& bytes) {
    return saveFileAtomically(path, [&](QIODevice& d) { return d.write(bytes) == bytes.size(); });
}

Status saveViaTemporaryName(const QString& path,
                            const std::function<Status(const QString&)>& write) {
    const QFileInfo info(path);
    const QString suffix = info.suffix();
    QTemporaryFile temporary(info.dir().filePath(
        QStringLiteral(".%1.XXXXXX%2")
            .arg(info.fileName(), suffix.isEmpty() ? QString() : QStringLiteral(".") + suffix)));
    if (!temporary.open())
        return Error(QStringLiteral("%1: cannot write in this folder: %2")
                         .arg(path, temporary.errorString()),
                     path);
    const QString temporaryPath = temporary.fileName();
    temporary.close(); // the writer opens the name itself; QTemporaryFile still removes it
    const TemporaryName registered(temporaryPath);
    if (Status written = write(temporaryPath); !written) {
        if (written.message().isEmpty())
            return Error(QStringLiteral("%1: cannot write").arg(path), path);
        return written;
    }
    // Keep the permissions a new file would get, not QTemporaryFile's 0600.
    QFile::setPermissions(temporaryPath, QFileDevice::ReadOwner | QFileDevice::WriteOwner |
                                             QFileDevice::ReadGroup | QFileDevice::ReadOther);
    if (std::rename(QFile::encodeName(temporaryPath).constData(),
                    QFile::encodeName(path).constData()) != 0)
        return Error(QStringLiteral("%1: cannot replace: %2").arg(path, qt_error_string(errno)),
                     path);
    temporary.setAutoRemove(false); // renamed: nothing left to remove
    return ok();
}

} // namespace kw
