// Starting the executables that sit next to `knotwork`: exec(3), so the command keeps this
// process's id, stdio and exit code, and the launcher's own libraries are unmapped.
#include "app/launch.h"

#include <QByteArray>
#include <cerrno>
#include <cstring>
#include <unistd.h>

namespace kw::app {

QString siblingPath(const char* program) {
    // Without QCoreApplication (it is never created on this path), so no applicationDirPath().
    QByteArray self(4096, '\0');
    const ssize_t n = ::readlink("/proc/self/exe", self.data(), size_t(self.size()));
    if (n <= 0 || n >= self.size())
        return QString::fromLocal8Bit(program); // fall back to a search of PATH by execvp
    self.truncate(n);
    return QString::fromLocal8Bit(self.left(self.lastIndexOf('/') + 1) + program);
}

QString execSibling(const char* program, char** argv) {
    const QByteArray path = siblingPath(program).toLocal8Bit();
    ::execvp(path.constData(), argv);
    const int err = errno;
    return QStringLiteral("knotwork: cannot run %1: %2 (it is built next to knotwork)")
        .arg(QString::fromLocal8Bit(path), QString::fromLocal8Bit(std::strerror(err)));
}

} // namespace kw::app
