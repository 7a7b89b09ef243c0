// IGES, STEP and BREP in a child process: the parent runs `knotwork __read-cad`, watches it
// (progress, time limit, Cancel) and reads back the scene; the child side writes it.
#include "model/cad/cadprocess.h"

#include "model/cad/cadexport.h"
#include "model/cad/cadprecheck.h"
#include "model/cad/cadprestart.h"
#include "model/cad/cadtempdir.h"
#include "model/cad/handover.h"
#include "model/io/inputcheck.h"
#include "model/io/install_layout.h"
#include "model/io/safetext.h"
#include "model/io/savefile.h"

#include <QDir>
#include <QElapsedTimer>
#include <QFileInfo>
#include <QMutex>
#include <QProcess>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <memory>
#include <poll.h>
#include <sys/prctl.h>
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

double cadTimeLimitSeconds(qint64 bytes, bool mesh) {
    bool ok = false;
    const double forced = qEnvironmentVariable("KNOTWORK_CAD_TIME_LIMIT").toDouble(&ok);
    if (ok && forced > 0)
        return forced;
    // The readers' work grows with the file: hammer.iges (1 MB) takes well under a second, so
    // ten seconds per megabyte leave room for a loaded machine and none for a runaway.
    // Meshing (knotwork mesh) took 0.72 s against the read's 0.35 s for Axis_of_bearing.brep.
    return (mesh ? 2.0 : 1.0) * (10.0 + 10.0 * double(bytes) / double(1 << 20));
}

long long cadMemoryLimitBytes(qint64 bytes) {
    bool ok = false;
    const long long mb = qEnvironmentVariable("KNOTWORK_CAD_MEMORY_MB").toLongLong(&ok);
    if (ok && mb > 0)
        return mb << 20;
    // Address space, not resident memory: the OCCT libraries and thread stacks take a few
    // hundred MB of it before anything is read.
    const long long physical = (long long)::sysconf(_SC_PHYS_PAGES) * ::sysconf(_SC_PAGESIZE);
    const long long scaled = (2LL << 30) + (256LL << 20) * std::max<qint64>(0, bytes >> 20);
    return std::min(scaled, std::max(physical, 2LL << 30));
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

ImportProgress progressToParent() {
    struct State {
        QElapsedTimer sinceLine;
        int lastDone = -1;
    };
    auto state = std::make_shared<State>();
    return [state](int done, int total) {
        if (done == state->lastDone ||
            (done < total && state->sinceLine.isValid() && state->sinceLine.elapsed() < 20))
            return true;
        state->lastDone = done;
        state->sinceLine.start();
        const QByteArray line = progressLine(done, total);
        std::fwrite(line.constData(), 1, size_t(line.size()), stdout);
        std::fflush(stdout);
        return true;
    };
}

Status writeImportForParent(const ImportResult& result, const QString& dir) {
    return saveBytesAtomically(QDir(dir).filePath(QString::fromLatin1(kHandoverFile)),
                               encodeImportHandover(result));
}

Status writeMeshForParent(const TaggedMeshSet& mesh, const QString& dir) {
    return saveBytesAtomically(QDir(dir).filePath(QStringLiteral("mesh.obj")),
                               writeTaggedMeshObj(mesh));
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

// What the parent keeps of the child's stderr: its last line is the error, and a child that
// writes without end must not grow the parent's memory.
constexpr qsizetype kMaxStderrBytes = 64 * 1024;
void keepTail(QByteArray& err) {
    if (err.size() > kMaxStderrBytes)
        err.remove(0, err.size() - kMaxStderrBytes);
}

// Removes the child's folder (cadtempdir.h) when it goes out of scope.
struct FolderRemover {
    QString path;
    explicit FolderRemover(QString p) : path(std::move(p)) {}
    ~FolderRemover() { removeCadTempDir(path); }
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
        if (out.size() > 4096) // no progress line is that long
            out.clear();
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
// An Error of `path` when it could not start or was stopped.
Status watchQProcess(const QString& path, const QString& reader, const QStringList& childArgs,
                     double seconds, const ImportProgress& progress, ChildEnd& end,
                     const QString& cancelText) {
    QProcess child;
    child.setProgram(cadReaderExecutable());
    child.setArguments(childArgs);
    // Between fork and exec: the child dies with this process (SIGKILL when it ends, even by
    // kill -9), and if this process already ended before the request, the child does not run.
    const pid_t parent = ::getpid();
    child.setChildProcessModifier([parent] {
        ::prctl(PR_SET_PDEATHSIG, SIGKILL);
        if (::getppid() != parent)
            ::_exit(127);
    });
    child.start(QIODevice::ReadOnly);
    if (!child.waitForStarted(30000))
        return Error(QStringLiteral("%1: cannot start %2 (%3): %4")
                         .arg(path, reader, child.program(), child.errorString()),
                     path);
    QElapsedTimer clock;
    clock.start();
    const pid_t pid = pid_t(child.processId());
    registerCadChild(pid); // killed before its folder is removed on SIGTERM or SIGINT
    struct Unregister {
        pid_t pid;
        ~Unregister() { unregisterCadChild(pid); }
    } unregister{pid};
    ProgressLines lines;
    auto stop = [&](const QString& why) -> Status {
        child.kill();
        child.waitForFinished(-1);
        return Error(why, path);
    };
    while (child.state() != QProcess::NotRunning) {
        child.waitForFinished(kPollMs);
        lines.take(child.readAllStandardOutput());
        end.err += child.readAllStandardError();
        keepTail(end.err);
        // Called every poll, not only on news: the editor's Cancel must not wait for OCCT.
        if (progress && !progress(lines.done, lines.total))
            return stop(cancelText);
        if (clock.elapsed() > seconds * 1000.0)
            return stop(outOfTime(path, reader, seconds));
    }
    end.err += child.readAllStandardError();
    end.crashed = child.exitStatus() == QProcess::CrashExit || child.error() == QProcess::Crashed;
    end.signal = end.crashed ? child.exitCode() : 0; // Qt reports the signal as the exit code
    end.exitCode = end.crashed ? 0 : child.exitCode();
    return ok();
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
// time limit counts from its start. Closes the pipes; an Error of `path` when it was stopped.
Status watchPrestarted(const PrestartedCadRead& child, double seconds,
                       const ImportProgress& progress, const QString& path, const QString& reader,
                       ChildEnd& end) {
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
    const auto stop = [&](const QString& why) -> Status {
        ::kill(child.pid, SIGKILL);
        while (!exited && ::waitpid(child.pid, &status, 0) < 0 && errno == EINTR) {
        }
        finish();
        return Error(why, path);
    };
    for (;;) {
        const bool napping = pidfd < 0 && fds[0].fd < 0 && fds[1].fd < 0;
        ::poll(fds, 3, napping ? 2 : kPollMs);
        QByteArray out;
        for (int k = 0; k < 2; ++k)
            if (fds[k].fd >= 0 && !drain(fds[k].fd, k == 0 ? out : end.err))
                fds[k].fd = -1; // closed: poll ignores negative descriptors
        keepTail(end.err);
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
    return ok();
}

} // namespace
#endif

Expected<ImportResult> importInChildProcess(const QString& path, CadFormat format,
                                            const ImportProgress& progress,
                                            const MeshDeflection* deflection, TaggedMeshSet* mesh) {
    // Every failure is an Error of `path`.
    const auto fail = [&path](QString message) {
        return Error(std::move(message), path);
    };
#ifndef KW_HAVE_OCCT
    Q_UNUSED(progress);
    Q_UNUSED(deflection);
    Q_UNUSED(mesh);
    return fail(QStringLiteral("%1: cannot read %2: %3")
                    .arg(path, cadFormatName(format), occtUnavailableMessage()));
#else
    // A device, FIFO or directory is named at once and never opened, and a file that does not
    // start like its format is refused from its first bytes, before any child is started.
    QString problem = checkRegularFile(path).message();
    if (problem.isEmpty())
        problem = checkCadHead(format, fileHead(path, kSniffBytes)).message();
    if (!problem.isEmpty())
        return fail(QStringLiteral("%1: %2").arg(path, problem));
    const QString reader =
        QString::fromLatin1(deflection && mesh ? "the %1 reader and mesher" : "the %1 reader")
            .arg(cadFormatName(format));
    const long long memory = cadMemoryLimitBytes(QFileInfo(path).size());
    ChildEnd end;
    QString dirPath;
    std::optional<FolderRemover> adoptedDir;
    if (std::optional<PrestartedCadRead> pre =
            deflection && mesh ? std::nullopt : takePrestartedCadRead(path)) {
        // Started by the launcher before it became this program (cadprestart.h): the same
        // watch, on its pid and pipes.
        // (Registered for removal on a signal when it was claimed.)
        adoptedDir.emplace(pre->dir);
        dirPath = pre->dir;
        const double seconds = cadTimeLimitSeconds(QFileInfo(path).size());
        const Status watched = watchPrestarted(*pre, seconds, progress, path, reader, end);
        unregisterCadChild(pre->pid);
        if (!watched)
            return watched.error();
    } else {
        Expected<QString> made = makeCadTempDir();
        if (!made)
            return fail(QStringLiteral("%1: cannot make a temporary folder for %2: %3")
                            .arg(path, reader, made.message()));
        dirPath = *made;
        adoptedDir.emplace(dirPath);
        const double seconds = cadTimeLimitSeconds(QFileInfo(path).size(), deflection && mesh);
        // The child's own deadline (a second after ours) holds should this process stop
        // watching.
        QStringList childArgs{QString::fromLatin1(kReadCadVerb),
                              path,
                              dirPath,
                              QStringLiteral("--max-memory-mb"),
                              QString::number(memory >> 20),
                              QStringLiteral("--parent-pid"),
                              QString::number(::getpid()),
                              QStringLiteral("--deadline-s"),
                              QString::number(int(std::ceil(seconds)) + 1)};
        if (deflection && mesh)
            childArgs << QStringLiteral("--mesh") << QString::number(deflection->linear, 'g', 17)
                      << QString::number(deflection->angularDegrees, 'g', 17);
        if (const Status watched =
                watchQProcess(path, reader, childArgs, seconds, progress, end, cancelled(path));
            !watched)
            return watched.error();
    }
    if (end.crashed) {
        const int sig = end.signal;
        // SIGSEGV is the stack overflow of a cyclic file; an abort can also be memory the
        // limit refused, so that one names the limit.
        return fail(QStringLiteral("%1 crashed on %2 (%3); nothing was imported%4")
                        .arg(reader, path, signalText(sig),
                             sig == SIGSEGV ? QString()
                                            : QStringLiteral(" (its memory limit was %1 MB; "
                                                             "KNOTWORK_CAD_MEMORY_MB sets another)")
                                                  .arg(memory >> 20)));
    }
    if (end.exitCode != 0) {
        const QList<QByteArray> lines = end.err.trimmed().split('\n');
        return fail(
            lines.isEmpty() || lines.back().trimmed().isEmpty()
                ? QStringLiteral("%1: %2 failed with exit code %3")
                      .arg(path, reader)
                      .arg(end.exitCode)
                : elided(safeMessageText(QString::fromLocal8Bit(lines.back().trimmed())), 1000));
    }
    QFile handover(QDir(dirPath).filePath(QString::fromLatin1(kHandoverFile)));
    Expected<ImportResult> read = handover.open(QIODevice::ReadOnly)
                                      ? decodeImportHandover(handover.readAll())
                                      : Expected<ImportResult>(Error(handover.errorString()));
    if (!read)
        return fail(
            QStringLiteral("%1: %2 gave no readable result: %3").arg(path, reader, read.message()));
    ImportResult result = std::move(*read);
    if (deflection && mesh) {
        Expected<TaggedMeshSet> read =
            readTaggedMeshObjFile(QDir(dirPath).filePath(QStringLiteral("mesh.obj")));
        if (!read)
            return fail(QStringLiteral("%1: %2 gave no readable mesh: %3")
                            .arg(path, reader, read.message()));
        *mesh = std::move(read).value();
    }
    return result;
#endif
}

namespace {

// What an export checks before any child runs: the name, the options, that there is something
// to write (`empty`: the scene has no surface), the folder.
// Errors of `path`.
Status exportPrecheck(const QString& path, const ExportOptions& options, bool empty) {
    const CadFormat format = cadFormatFromPath(path);
    if (format != CadFormat::Step && format != CadFormat::Iges)
        return Error(
            QStringLiteral("%1: not a STEP or IGES name (expected .step, .stp, .iges or .igs)")
                .arg(path),
            path);
    if (const QString bad = checkExportOptions(options).message(); !bad.isEmpty())
        return Error(QStringLiteral("%1: %2").arg(path, bad), path);
    if (empty)
        return Error(
            QStringLiteral("%1: nothing to export: the document has no surfaces").arg(path), path);
    const QFileInfo folder(QFileInfo(path).absolutePath());
    if (!folder.isDir() || !folder.isWritable())
        return Error(QStringLiteral("%1: cannot write there: the folder %2")
                         .arg(path, folder.isDir() ? QStringLiteral("is not writable")
                                                   : QStringLiteral("does not exist")),
                     path);
    return ok();
}

#ifdef KW_HAVE_OCCT
// A folder of the registry (cadtempdir.h) for `writer`'s child: removed on every exit path,
// SIGTERM included, or swept by a later run if this one is killed.
// An Error of `path` when none can be made.
Expected<QString> writerFolder(const QString& path, const QString& writer) {
    const Expected<QString> made = makeCadTempDir();
    if (!made)
        return Error(QStringLiteral("%1: cannot make a temporary folder for %2: %3")
                         .arg(path, writer, made.message()),
                     path);
    return *made;
}

// Runs `knotwork __write-cad FIRST OUT DIR ...` (`extra` after the options), reads its report
// and writes `path` from the bytes it left in `dirPath`. Errors of `path`.
Status runWriter(const QString& first, const QString& path, const QString& dirPath,
                 const ExportOptions& options, const QStringList& extra, double seconds,
                 long long memory, const QString& writer, ExportReport& report,
                 const ImportProgress& progress) {
    QStringList args{QString::fromLatin1(kWriteCadVerb),
                     first,
                     path,
                     dirPath,
                     QStringLiteral("--max-memory-mb"),
                     QString::number(memory >> 20),
                     QStringLiteral("--step-schema"),
                     options.stepSchema,
                     QStringLiteral("--tolerance"),
                     QString::number(options.tolerance, 'g', 17)};
    if (options.igesFaces)
        args << QStringLiteral("--iges-faces");
    if (options.requireClosed)
        args << QStringLiteral("--require-closed");
    args << extra;
    ChildEnd end;
    if (Status watched = watchQProcess(path, writer, args, seconds, progress, end,
                                       QStringLiteral("%1: export cancelled").arg(path));
        !watched)
        return watched;
    if (end.crashed)
        return Error(QStringLiteral("%1 crashed on %2 (%3); nothing was written (its memory "
                                    "limit was %4 MB; KNOTWORK_CAD_MEMORY_MB sets another)")
                         .arg(writer, path, signalText(end.signal))
                         .arg(memory >> 20),
                     path);
    const QDir dir(dirPath);
    QFile text(dir.filePath(QStringLiteral("export.txt")));
    const bool reported = text.open(QIODevice::ReadOnly) && report.fromText(text.readAll());
    if (end.exitCode != 0) {
        const QList<QByteArray> lines = end.err.trimmed().split('\n');
        return Error(lines.isEmpty() || lines.back().trimmed().isEmpty()
                         ? QStringLiteral("%1: %2 failed with exit code %3")
                               .arg(path, writer)
                               .arg(end.exitCode)
                         : QString::fromLocal8Bit(lines.back().trimmed()),
                     path);
    }
    if (!reported)
        return Error(QStringLiteral("%1: %2 gave no readable report").arg(path, writer), path);
    // The destination is written here, not by the child: a child killed half-way leaves
    // nothing beside it.
    QFile bytes(dir.filePath(QStringLiteral("export.out")));
    if (!bytes.open(QIODevice::ReadOnly))
        return Error(
            QStringLiteral("%1: %2 gave no file: %3").arg(path, writer, bytes.errorString()), path);
    const Status saved = saveFileAtomically(path, [&](QIODevice& out) {
        QByteArray chunk;
        while (!(chunk = bytes.read(1 << 20)).isEmpty())
            if (out.write(chunk) != chunk.size())
                return false;
        return bytes.error() == QFileDevice::NoError;
    });
    if (!saved)
        return Error(saved.message(), path);
    return ok();
}
#endif

} // namespace

// Every failure is an Error of `path`.
Status exportCadFile(const Scene& scene, const QString& path, const ExportOptions& options,
                     ExportReport& report, const ImportProgress& progress) {
    report = ExportReport{};
    if (Status checked = exportPrecheck(path, options, scene.surfaces.empty()); !checked)
        return checked;
#ifndef KW_HAVE_OCCT
    Q_UNUSED(progress);
    return Error(QStringLiteral("%1: cannot write %2: Knotwork was built without OpenCASCADE")
                     .arg(path, cadFormatName(cadFormatFromPath(path))),
                 path);
#else
    const QString writer =
        QStringLiteral("the %1 writer").arg(cadFormatName(cadFormatFromPath(path)));
    const Expected<QString> folder = writerFolder(path, writer);
    if (!folder)
        return folder.error();
    const QString dirPath = *folder;
    const FolderRemover removeDir(dirPath);
    // The scene goes over bit for bit (handover.h), as imports come back.
    ImportResult handover;
    handover.scene = scene;
    for (int k = 0; k < int(scene.surfaces.size()); ++k)
        handover.sourceFaces.push_back(k + 1);
    const QByteArray block = encodeImportHandover(handover);
    const QString scenePath = QDir(dirPath).filePath(QStringLiteral("scene.kwi"));
    if (const Status saved = saveBytesAtomically(scenePath, block); !saved)
        return Error(QStringLiteral("%1: cannot hand the scene to %2: %3")
                         .arg(path, writer, saved.message()),
                     path);
    // The memory limit grows with the scene as a read's does with its file: OpenCASCADE's
    // writer holds its whole model and text (10,035 faces: 1.75 GB resident ran out of the
    // fixed 2 GiB of address space).
    return runWriter(scenePath, path, dirPath, options, {}, cadTimeLimitSeconds(block.size(), true),
                     cadMemoryLimitBytes(block.size()), writer, report, progress);
#endif
}

// The read's failures are Errors of `in`, the write's of `path`: each stage names its own file.
Status convertCadFile(const QString& in, const QString& path, const ExportOptions& options,
                      ImportReport& imported, ExportReport& report,
                      const ImportProgress& progress) {
    report = ExportReport{};
    imported = ImportReport{};
    const auto readError = [&](const QString& why) {
        return Error(QStringLiteral("%1: %2").arg(in, why), in);
    };
    const CadFormat format = cadFormatFromPath(in);
    if (format != CadFormat::Iges && format != CadFormat::Step && format != CadFormat::Brep)
        return readError(QStringLiteral("not an IGES, STEP or BREP file"));
    // As importInChildProcess: a device, FIFO or folder, or a file that does not start like
    // its format, is refused before any child starts.
    if (const Status regular = checkRegularFile(in); !regular)
        return readError(regular.message());
    if (const Status head = checkCadHead(format, fileHead(in, kSniffBytes)); !head)
        return readError(head.message());
    if (Status checked = exportPrecheck(path, options, false); !checked)
        return checked;
#ifndef KW_HAVE_OCCT
    Q_UNUSED(progress);
    return readError(
        QStringLiteral("cannot read %1: %2").arg(cadFormatName(format), occtUnavailableMessage()));
#else
    const QString writer = QStringLiteral("the %1 reader and %2 writer")
                               .arg(cadFormatName(format), cadFormatName(cadFormatFromPath(path)));
    const Expected<QString> folder = writerFolder(path, writer);
    if (!folder)
        return folder.error();
    const QString dirPath = *folder;
    const FolderRemover removeDir(dirPath);
    // The read's limits and the write's: the scene is about as large in the hand-over as the
    // file it came from.
    const qint64 size = QFileInfo(in).size();
    const Status written = runWriter(in, path, dirPath, options, {QStringLiteral("--read-cad")},
                                     cadTimeLimitSeconds(size) + cadTimeLimitSeconds(size, true),
                                     cadMemoryLimitBytes(size), writer, report, progress);
    // The child leaves the import's hand-over once the read is finished, before the write
    // starts: with it, the failure is the write's; without it, the read's (also a crash, a
    // time-out or a cancel while reading). Its report comes back also when the write is
    // refused (a face the reader skipped may be why).
    QFile handover(QDir(dirPath).filePath(QString::fromLatin1(kHandoverFile)));
    const bool read = handover.open(QIODevice::ReadOnly);
    if (read) {
        if (Expected<ImportResult> result = decodeImportHandover(handover.readAll()))
            imported = std::move(result->report);
    }
    if (!written)
        return Error(written.message(), read ? path : in);
    return ok();
#endif
}

} // namespace kw
