// IGES, STEP and BREP in a child process: the parent runs `knotwork __read-cad`, watches it
// (progress, time limit, Cancel) and reads back the scene; the child side writes it.
#include "model/cad/cadprocess.h"

#include "model/cad/handover.h"
#include "model/savefile.h"

#include <QCoreApplication>
#include <QDir>
#include <QElapsedTimer>
#include <QFileInfo>
#include <QMutex>
#include <QProcess>
#include <QTemporaryDir>
#include <csignal>
#include <cstring>
#include <unistd.h>

namespace kw {

namespace {

QMutex executableMutex;
QString executableOverride;

constexpr int kPollMs = 50;

constexpr const char* kHandoverFile = "import.kwi"; // handover.h

QString signalText(int sig) {
    const char* name = ::strsignal(sig);
    return QStringLiteral("signal %1: %2").arg(sig).arg(QString::fromLocal8Bit(name ? name : "?"));
}

} // namespace

double cadTimeLimitSeconds(qint64 bytes) {
    bool ok = false;
    const double forced = qEnvironmentVariable("KNOTWORK_CAD_TIME_LIMIT").toDouble(&ok);
    if (ok && forced > 0)
        return forced;
    return 60.0 + 30.0 * double(bytes) / double(1 << 20);
}

long long cadMemoryLimitBytes() {
    bool ok = false;
    const long long mb = qEnvironmentVariable("KNOTWORK_CAD_MEMORY_MB").toLongLong(&ok);
    if (ok && mb > 0)
        return mb << 20;
    const long long physical = (long long)::sysconf(_SC_PHYS_PAGES) * ::sysconf(_SC_PAGESIZE);
    return std::max(physical, 2LL << 30);
}

QString cadReaderExecutable() {
    {
        QMutexLocker lock(&executableMutex);
        if (!executableOverride.isEmpty())
            return executableOverride;
    }
    if (const QString env = qEnvironmentVariable("KNOTWORK_CAD_READER"); !env.isEmpty())
        return env;
    return QDir(QCoreApplication::applicationDirPath()).filePath(QStringLiteral("knotwork"));
}

void setCadReaderExecutable(const QString& path) {
    QMutexLocker lock(&executableMutex);
    executableOverride = path;
}

QByteArray progressLine(int done, int total) {
    return "progress " + QByteArray::number(done) + ' ' + QByteArray::number(total) + '\n';
}

bool writeImportForParent(const ImportResult& result, const QString& dir, QString& error) {
    QString why;
    if (!saveBytesAtomically(QDir(dir).filePath(QString::fromLatin1(kHandoverFile)),
                             encodeImportHandover(result), &why)) {
        error = why;
        return false;
    }
    return true;
}

bool writeMeshForParent(const TaggedMeshSet& mesh, const QString& dir, QString& error) {
    QString why;
    if (!saveBytesAtomically(QDir(dir).filePath(QStringLiteral("mesh.obj")),
                             writeTaggedMeshObj(mesh), &why)) {
        error = why;
        return false;
    }
    return true;
}

std::optional<ImportResult> importInChildProcess(const QString& path, CadFormat format,
                                                 QString& error, const ImportProgress& progress,
                                                 const MeshDeflection* deflection,
                                                 TaggedMeshSet* mesh) {
#ifndef KW_HAVE_OCCT
    Q_UNUSED(progress);
    Q_UNUSED(deflection);
    Q_UNUSED(mesh);
    error = QStringLiteral("%1: cannot read %2: %3")
                .arg(path, cadFormatName(format), occtUnavailableMessage());
    return std::nullopt;
#else
    const QString reader =
        QString::fromLatin1(deflection && mesh ? "the %1 reader and mesher" : "the %1 reader")
            .arg(cadFormatName(format));
    QTemporaryDir dir;
    if (!dir.isValid()) {
        error = QStringLiteral("%1: cannot make a temporary folder for %2: %3")
                    .arg(path, reader, dir.errorString());
        return std::nullopt;
    }
    const double seconds = cadTimeLimitSeconds(QFileInfo(path).size());
    const long long memory = cadMemoryLimitBytes();
    QProcess child;
    child.setProgram(cadReaderExecutable());
    QStringList childArgs{QString::fromLatin1(kReadCadVerb), path, dir.path(),
                          QStringLiteral("--max-memory-mb"), QString::number(memory >> 20)};
    if (deflection && mesh)
        childArgs << QStringLiteral("--mesh") << QString::number(deflection->linear, 'g', 17)
                  << QString::number(deflection->angularDegrees, 'g', 17);
    child.setArguments(childArgs);
    child.start(QIODevice::ReadOnly);
    if (!child.waitForStarted(30000)) {
        error = QStringLiteral("%1: cannot start %2 (%3): %4")
                    .arg(path, reader, child.program(), child.errorString());
        return std::nullopt;
    }
    QElapsedTimer clock;
    clock.start();
    QByteArray out, err;
    // The OCCT import counts 1000 steps (occtimport.cpp): 0 of 1000 until the child reports.
    int done = 0, total = 1000;
    auto stop = [&](const QString& why) {
        child.kill();
        child.waitForFinished(-1);
        error = why;
        return std::nullopt;
    };
    while (child.state() != QProcess::NotRunning) {
        child.waitForFinished(kPollMs);
        out += child.readAllStandardOutput();
        err += child.readAllStandardError();
        for (qsizetype eol; (eol = out.indexOf('\n')) >= 0; out.remove(0, eol + 1)) {
            const QList<QByteArray> t = out.left(eol).split(' ');
            if (t.size() == 3 && t[0] == "progress") {
                done = t[1].toInt();
                total = t[2].toInt();
            }
        }
        // Called every poll, not only on news: the editor's Cancel must not wait for OCCT.
        if (progress && !progress(done, total))
            return stop(QStringLiteral("%1: import cancelled").arg(path));
        if (clock.elapsed() > seconds * 1000.0)
            return stop(QStringLiteral("%1: %2 did not finish within %3 s (the limit for a file "
                                       "of this size; KNOTWORK_CAD_TIME_LIMIT sets another) and "
                                       "was stopped")
                            .arg(path, reader)
                            .arg(seconds, 0, 'f', 0));
    }
    err += child.readAllStandardError();
    if (child.exitStatus() == QProcess::CrashExit || child.error() == QProcess::Crashed) {
        const int sig = child.exitCode(); // Qt reports the signal number as the exit code
        // SIGSEGV is the stack overflow of a cyclic file; an abort can also be memory the
        // limit refused, so that one names the limit.
        error = QStringLiteral("%1 crashed on %2 (%3); nothing was imported%4")
                    .arg(reader, path, signalText(sig),
                         sig == SIGSEGV ? QString()
                                        : QStringLiteral(" (its memory limit was %1 MB; "
                                                         "KNOTWORK_CAD_MEMORY_MB sets another)")
                                              .arg(memory >> 20));
        return std::nullopt;
    }
    if (child.exitCode() != 0) {
        const QList<QByteArray> lines = err.trimmed().split('\n');
        error = lines.isEmpty() || lines.back().trimmed().isEmpty()
                    ? QStringLiteral("%1: %2 failed with exit code %3")
                          .arg(path, reader)
                          .arg(child.exitCode())
                    : QString::fromLocal8Bit(lines.back().trimmed());
        return std::nullopt;
    }
    QString why;
    QFile handover(dir.filePath(QString::fromLatin1(kHandoverFile)));
    std::optional<ImportResult> read;
    if (!handover.open(QIODevice::ReadOnly))
        why = handover.errorString();
    else
        read = decodeImportHandover(handover.readAll(), why);
    if (!read) {
        error = QStringLiteral("%1: %2 gave no readable result: %3").arg(path, reader, why);
        return std::nullopt;
    }
    ImportResult result = std::move(*read);
    if (deflection && mesh &&
        !readTaggedMeshObjFile(dir.filePath(QStringLiteral("mesh.obj")), *mesh, why)) {
        error = QStringLiteral("%1: %2 gave no readable mesh: %3").arg(path, reader, why);
        return std::nullopt;
    }
    return result;
#endif
}

} // namespace kw
