// Starting the executables that sit next to `knotwork`: exec(3), so the command keeps this
// process's id, stdio and exit code, and the launcher's own libraries are unmapped.
#include "app/launch.h"

#include "model/io/install_layout.h"

#include <QByteArray>
#include <cerrno>
#include <cstring>
#include <unistd.h>

namespace kw::app {

QString siblingPath(const char* program) {
    // Without /proc the bare name makes execvp search PATH.
    return executableDir().isEmpty() ? QString::fromLocal8Bit(program) : programPath(program);
}

QString execSibling(const char* program, char** argv) {
    const QByteArray path = siblingPath(program).toLocal8Bit();
    ::execvp(path.constData(), argv);
    const int err = errno;
    return QStringLiteral(
               "knotwork: cannot run %1: %2 (it is built next to knotwork and installed in "
               "lib/knotwork)")
        .arg(QString::fromLocal8Bit(path), QString::fromLocal8Bit(std::strerror(err)));
}

} // namespace kw::app
