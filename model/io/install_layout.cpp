// Finds Knotwork's files relative to the running executable (model/io/install_layout.h).
#include "model/io/install_layout.h"

#include <QByteArray>
#include <QDir>
#include <QFileInfo>
#include <unistd.h>

// Relative to the prefix; set by CMake from GNUInstallDirs (the defaults keep a plain compile
// of this file meaningful).
#ifndef KW_INSTALL_BINDIR
#define KW_INSTALL_BINDIR "bin"
#endif
#ifndef KW_INSTALL_PKGLIBDIR
#define KW_INSTALL_PKGLIBDIR "lib/knotwork"
#endif
#ifndef KW_INSTALL_PKGDATADIR
#define KW_INSTALL_PKGDATADIR "share/knotwork"
#endif

namespace kw {

namespace {

/// The prefix the folder `dir` belongs to: dir less its trailing bin/ or lib/knotwork/; the
/// parent of dir when it is neither (a build tree's build/bin has the form of a prefix's bin).
QString prefixOf(const QString& dir) {
    for (const char* relative : {KW_INSTALL_PKGLIBDIR, KW_INSTALL_BINDIR}) {
        const QString tail = QLatin1Char('/') + QString::fromLatin1(relative);
        if (dir.endsWith(tail))
            return dir.left(dir.size() - tail.size());
    }
    return QDir::cleanPath(dir + QStringLiteral("/.."));
}

QString inPrefixOrBeside(const QString& fileName, const char* relativeDir) {
    const QString self = executableDir();
    const QString beside = QDir(self).filePath(fileName);
    if (self.isEmpty() || QFileInfo::exists(beside))
        return beside;
    const QString prefix = prefixOf(self);
    const QString installed =
        QDir(prefix + QLatin1Char('/') + QString::fromLatin1(relativeDir)).filePath(fileName);
    if (QFileInfo::exists(installed))
        return installed;
    // A test executable in a build tree's sub-folder: the build keeps everything in bin/.
    const QString built = QDir(prefix + QStringLiteral("/bin")).filePath(fileName);
    if (QFileInfo::exists(built))
        return built;
    // Nowhere: name the place where this kind of tree keeps it (an installed prefix always
    // has its data folder; a lone copy of an executable has nothing).
    if (QFileInfo(prefix + QLatin1Char('/') + QLatin1String(KW_INSTALL_PKGDATADIR)).isDir())
        return installed;
    return beside;
}

} // namespace

QString executableDir() {
    // Not QCoreApplication::applicationDirPath(): the launcher has no application object.
    static const QString dir = [] {
        QByteArray self(4096, '\0');
        const ssize_t n = ::readlink("/proc/self/exe", self.data(), size_t(self.size()));
        if (n <= 0 || n >= self.size())
            return QString();
        self.truncate(n);
        return QString::fromLocal8Bit(self.left(self.lastIndexOf('/')));
    }();
    return dir;
}

QString programPath(const char* name) {
    const QString file = QString::fromLocal8Bit(name);
    return inPrefixOrBeside(file, file == QLatin1String("knotwork") ? KW_INSTALL_BINDIR
                                                                    : KW_INSTALL_PKGLIBDIR);
}

QString modulePath(const QString& fileName) {
    return inPrefixOrBeside(fileName, KW_INSTALL_PKGLIBDIR);
}

QString dataDir() {
    const QString self = executableDir();
    if (self.isEmpty())
        return {};
    const QString dir = prefixOf(self) + QLatin1Char('/') + QLatin1String(KW_INSTALL_PKGDATADIR);
    return QFileInfo(dir).isDir() ? dir : QString();
}

} // namespace kw
