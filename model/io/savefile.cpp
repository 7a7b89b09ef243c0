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

bool saveFileAtomically(const QString& path, const std::function<bool(QIODevice&)>& write,
                        QString* error) {
    QSaveFile file(path);
    auto failed = [&](const QString& what, const QString& reason) {
        if (error)
            *error = QStringLiteral("%1: %2: %3").arg(path, what, reason);
        file.cancelWriting();
        return false;
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
    return true;
}

bool saveBytesAtomically(const QString& path, const QByteArray& bytes, QString* error) {
    return saveFileAtomically(
        path, [&](QIODevice& d) { return d.write(bytes) == bytes.size(); }, error);
}

bool saveViaTemporaryName(const QString& path,
                          const std::function<bool(const QString&, QString*)>& write,
                          QString* error) {
    const QFileInfo info(path);
    const QString suffix = info.suffix();
    QTemporaryFile temporary(info.dir().filePath(
        QStringLiteral(".%1.XXXXXX%2")
            .arg(info.fileName(), suffix.isEmpty() ? QString() : QStringLiteral(".") + suffix)));
    if (!temporary.open()) {
        if (error)
            *error = QStringLiteral("%1: cannot write in this folder: %2")
                         .arg(path, temporary.errorString());
        return false;
    }
    const QString temporaryPath = temporary.fileName();
    temporary.close(); // the writer opens the name itself; QTemporaryFile still removes it
    const TemporaryName registered(temporaryPath);
    QString why;
    if (!write(temporaryPath, &why)) {
        if (error)
            *error = why.isEmpty() ? QStringLiteral("%1: cannot write").arg(path) : why;
        return false;
    }
    // Keep the permissions a new file would get, not QTemporaryFile's 0600.
    QFile::setPermissions(temporaryPath, QFileDevice::ReadOwner | QFileDevice::WriteOwner |
                                             QFileDevice::ReadGroup | QFileDevice::ReadOther);
    if (std::rename(QFile::encodeName(temporaryPath).constData(),
                    QFile::encodeName(path).constData()) != 0) {
        if (error)
            *error = QStringLiteral("%1: cannot replace: %2").arg(path, qt_error_string(errno));
        return false;
    }
    temporary.setAutoRemove(false); // renamed: nothing left to remove
    return true;
}

} // namespace kw
