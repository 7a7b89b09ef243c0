// IGES, STEP and BREP in a child process: the parent runs `knotwork __read-cad`, watches it
// (progress, time limit, Cancel) and reads back the scene; the child side writes it.
#include "model/cad/cadprocess.h"

#include "model/cad/cadprestart.h"
#include "model/cad/handover.h"
#include "model/install_layout.h"
#include "model/savefile.h"

#include <QDir>
#include <QElapsedTimer>
#include <QFileInfo>
#include <QMutex>
#include <QProcess>
#include <QTemporaryDir>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <poll.h>
#include <sys/syscall.h>
#include <sys/wait.h>
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
    return programPath("knotwork");
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

#ifdef KW_HAVE_OCCT
namespace {

// How a child ended, and what it wrote on stderr (its last line is its error).
struct ChildEnd {
    bool crashed = false;
    int signal = 0;
    int exitCode = 0;
    QByteArray err;
};

// Removes a folder when it goes out of scope (the prestarted child's, not a QTemporaryDir).
struct FolderRemover {
    QString path;
    explicit FolderRemover(QString p) : path(std::move(p)) {}
    ~FolderRemover() { QDir(path).removeRecursively(); }
};

// The child's "progress DONE TOTAL" lines.
struct ProgressLines {
    QByteArray out;
    // The OCCT import counts 1000 steps (occtimport.cpp): 0 of 1000 until the child reports.
    int done = 0, total = 1000;
    void take(const QByteArray& bytes) {
        out += bytes;
        for (qsizetype eol; (eol = out.indexOf('\n')) >= 0; out.remove(0, eol + 1)) {
            const QList<QByteArray> t = out.left(eol).split(' ');
            if (t.size() == 3 && t[0] == "progress") {
                done = t[1].toInt();
                total = t[2].toInt();
            }
        }
    }
};

QString cancelled(const QString& path) {
    return QStringLiteral("%1: import cancelled").arg(path);
}

QString outOfTime(const QString& path, const QString& reader, double seconds) {
    return QStringLiteral("%1: %2 did not finish within %3 s (the limit for a file of this size; "
                          "KNOTWORK_CAD_TIME_LIMIT sets another) and was stopped")
        .arg(path, reader)
        .arg(seconds, 0, 'f', 0);
}

// Runs the child with QProcess and watches it: progress every kPollMs, Cancel, time limit.
// False with `error` when it was stopped.
bool watchQProcess(const QString& path, const QString& reader, const QString& dir, long long memory,
                   const MeshDeflection* deflection, TaggedMeshSet* mesh,
                   const ImportProgress& progress, ChildEnd& end, QString& error) {
    const double seconds = cadTimeLimitSeconds(QFileInfo(path).size());
    QProcess child;
    child.setProgram(cadReaderExecutable());
    QStringList childArgs{QString::fromLatin1(kReadCadVerb), path, dir,
                          QStringLiteral("--max-memory-mb"), QString::number(memory >> 20)};
    if (deflection && mesh)
        childArgs << QStringLiteral("--mesh") << QString::number(deflection->linear, 'g', 17)
                  << QString::number(deflection->angularDegrees, 'g', 17);
    child.setArguments(childArgs);
    child.start(QIODevice::ReadOnly);
    if (!child.waitForStarted(30000)) {
        error = QStringLiteral("%1: cannot start %2 (%3): %4")
                    .arg(path, reader, child.program(), child.errorString());
        return false;
    }
    QElapsedTimer clock;
    clock.start();
    ProgressLines lines;
    auto stop = [&](const QString& why) {
        child.kill();
        child.waitForFinished(-1);
        error = why;
        return false;
    };
    while (child.state() != QProcess::NotRunning) {
        child.waitForFinished(kPollMs);
        lines.take(child.readAllStandardOutput());
        end.err += child.readAllStandardError();
        // Called every poll, not only on news: the editor's Cancel must not wait for OCCT.
        if (progress && !progress(lines.done, lines.total))
            return stop(cancelled(path));
        if (clock.elapsed() > seconds * 1000.0)
            return stop(outOfTime(path, reader, seconds));
    }
    end.err += child.readAllStandardError();
    end.crashed = child.exitStatus() == QProcess::CrashExit || child.error() == QProcess::Crashed;
    end.signal = end.crashed ? child.exitCode() : 0; // Qt reports the signal as the exit code
    end.exitCode = end.crashed ? 0 : child.exitCode();
    return true;
}

// Reads what is there on a non-blocking pipe; false once it is closed (or broken).
bool drain(int fd, QByteArray& into) {
    char buffer[65536];
    for (;;) {
        const ssize_t n = ::read(fd, buffer, sizeof buffer);
        if (n > 0) {
            into.append(buffer, n);
            continue;
        }
        if (n < 0 && errno == EINTR)
            continue;
        return n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK);
    }
}

// The same watch on a child the launcher started (cadprestart.h), by its pid and pipes; the
// time limit counts from its start. Closes the pipes; false with `error` when it was stopped.
bool watchPrestarted(const PrestartedCadRead& child, double seconds, const ImportProgress& progress,
                     const QString& path, const QString& reader, ChildEnd& end, QString& error) {
    ProgressLines lines;
    // A pidfd wakes the poll when the child exits (QProcess waits the same way); without one
    // (kernels before 5.3) the poll falls back to short naps once both pipes are closed.
    const int pidfd = int(::syscall(SYS_pidfd_open, child.pid, 0));
    pollfd fds[3] = {{child.out, POLLIN, 0}, {child.err, POLLIN, 0}, {pidfd, POLLIN, 0}};
    int status = 0;
    bool exited = false;
    const auto finish = [&] {
        ::close(child.out);
        ::close(child.err);
        if (pidfd >= 0)
            ::close(pidfd);
    };
    const auto stop = [&](const QString& why) {
        ::kill(child.pid, SIGKILL);
        while (!exited && ::waitpid(child.pid, &status, 0) < 0 && errno == EINTR) {
        }
        finish();
        error = why;
        return false;
    };
    for (;;) {
        const bool napping = pidfd < 0 && fds[0].fd < 0 && fds[1].fd < 0;
        ::poll(fds, 3, napping ? 2 : kPollMs);
        QByteArray out;
        for (int k = 0; k < 2; ++k)
            if (fds[k].fd >= 0 && !drain(fds[k].fd, k == 0 ? out : end.err))
                fds[k].fd = -1; // closed: poll ignores negative descriptors
        lines.take(out);
        if (!exited) {
            const pid_t w = ::waitpid(child.pid, &status, WNOHANG);
            exited = w == child.pid || (w < 0 && errno == ECHILD);
        }
        // Once the child has exited, what it wrote is in the pipes: one more read and done.
        if (exited) {
            QByteArray rest;
            drain(child.out, rest);
            lines.take(rest);
            drain(child.err, end.err);
            break;
        }
        if (progress && !progress(lines.done, lines.total))
            return stop(cancelled(path));
        if (double(monotonicNs() - child.startedNs) > seconds * 1e9)
            return stop(outOfTime(path, reader, seconds));
    }
    finish();
    if (WIFSIGNALED(status)) {
        end.crashed = true;
        end.signal = WTERMSIG(status);
    } else {
        end.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 1;
    }
    return true;
}

} // namespace
#endif

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
    const long long memory = cadMemoryLimitBytes();
    ChildEnd end;
    QString dirPath;
    std::optional<QTemporaryDir> dir;
    std::optional<FolderRemover> adoptedDir;
    if (std::optional<PrestartedCadRead> pre =
            deflection && mesh ? std::nullopt : takePrestartedCadRead(path)) {
        // Started by the launcher before it became this program (cadprestart.h): the same
        // watch, on its pid and pipes.
        adoptedDir.emplace(pre->dir);
        dirPath = pre->dir;
        const double seconds = cadTimeLimitSeconds(QFileInfo(path).size());
        if (!watchPrestarted(*pre, seconds, progress, path, reader, end, error))
            return std::nullopt;
    } else {
        dir.emplace();
        if (!dir->isValid()) {
            error = QStringLiteral("%1: cannot make a temporary folder for %2: %3")
                        .arg(path, reader, dir->errorString());
            return std::nullopt;
        }
        dirPath = dir->path();
        if (!watchQProcess(path, reader, dirPath, memory, deflection, mesh, progress, end, error))
            return std::nullopt;
    }
    if (end.crashed) {
        const int sig = end.signal;
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
    if (end.exitCode != 0) {
        const QList<QByteArray> lines = end.err.trimmed().split('\n');
        error = lines.isEmpty() || lines.back().trimmed().isEmpty()
                    ? QStringLiteral("%1: %2 failed with exit code %3")
                          .arg(path, reader)
                          .arg(end.exitCode)
                    : QString::fromLocal8Bit(lines.back().trimmed());
        return std::nullopt;
    }
    QString why;
    QFile handover(QDir(dirPath).filePath(QString::fromLatin1(kHandoverFile)));
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
        !readTaggedMeshObjFile(QDir(dirPath).filePath(QStringLiteral("mesh.obj")), *mesh, why)) {
        error = QStringLiteral("%1: %2 gave no readable mesh: %3").arg(path, reader, why);
        return std::nullopt;
    }
    return result;
#endif
}

} // namespace kw
