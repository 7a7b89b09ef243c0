// Starting the CAD child in the launcher and taking it over after the exec (cadprestart.h).
#include "model/cad/cadprestart.h"

#include "model/cad/cadimport.h"
#include "model/cad/cadprocess.h"
#include "model/cad/cadtempdir.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QMutex>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace kw {
namespace {

constexpr const char* kVariable = "KNOTWORK_CAD_PRESTARTED";

// The claimed read until someone takes it; killed and cleaned up at exit otherwise.
struct Claimed {
    QMutex mutex;
    std::optional<PrestartedCadRead> read;
    ~Claimed() {
        if (!read)
            return;
        ::kill(read->pid, SIGKILL);
        int status = 0;
        while (::waitpid(read->pid, &status, 0) < 0 && errno == EINTR) {
        }
        ::close(read->out);
        ::close(read->err);
        unregisterCadChild(read->pid);
        removeCadTempDir(read->dir);
    }
};

Claimed& claimed() {
    static Claimed c;
    return c;
}

} // namespace

qint64 monotonicNs() {
    timespec t{};
    ::clock_gettime(CLOCK_MONOTONIC, &t);
    return qint64(t.tv_sec) * 1'000'000'000 + t.tv_nsec;
}

void prestartCadRead(const QString& reader, const QString& path) {
#ifndef KW_HAVE_OCCT
    Q_UNUSED(reader);
    Q_UNUSED(path);
#else
    const CadFormat format = cadFormatFromPath(path);
    if ((format != CadFormat::Iges && format != CadFormat::Step && format != CadFormat::Brep) ||
        !QFileInfo(path).isFile())
        return;
    // Named after this process, which becomes the program that takes the child over: a later
    // run sweeps it should that program be killed (cadtempdir.h).
    QByteArray dir = QFile::encodeName(QDir::tempPath()) + "/knotwork-" +
                     QByteArray::number(::getpid()) + "-XXXXXX";
    if (!::mkdtemp(dir.data()))
        return;
    int out[2] = {-1, -1}, err[2] = {-1, -1};
    if (::pipe2(out, O_CLOEXEC) != 0 || ::pipe2(err, O_CLOEXEC) != 0) {
        for (int fd : {out[0], out[1], err[0], err[1]})
            if (fd >= 0)
                ::close(fd);
        ::rmdir(dir.constData());
        return;
    }
    const QByteArray program = QFile::encodeName(reader);
    const QByteArray file = QFile::encodeName(path);
    const qint64 size = QFileInfo(path).size();
    const QByteArray memory = QByteArray::number(cadMemoryLimitBytes(size) >> 20);
    const QByteArray deadline = QByteArray::number(int(std::ceil(cadTimeLimitSeconds(size))) + 1);
    const char* argv[] = {program.constData(), kReadCadVerb,
                          file.constData(),    dir.constData(),
                          "--max-memory-mb",   memory.constData(),
                          "--deadline-s",      deadline.constData(),
                          "--die-with-parent", nullptr};
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_adddup2(&actions, out[1], 1);
    posix_spawn_file_actions_adddup2(&actions, err[1], 2);
    const qint64 started = monotonicNs();
    pid_t pid = 0;
    const int failed = ::posix_spawn(&pid, program.constData(), &actions, nullptr,
                                     const_cast<char* const*>(argv), environ);
    posix_spawn_file_actions_destroy(&actions);
    ::close(out[1]);
    ::close(err[1]);
    if (failed != 0) {
        ::close(out[0]);
        ::close(err[0]);
        ::rmdir(dir.constData());
        return;
    }
    // The read ends must survive the exec of the program that takes the child over.
    for (int fd : {out[0], err[0]})
        ::fcntl(fd, F_SETFD, 0);
    const QByteArray value = QByteArray::number(pid) + ' ' + QByteArray::number(out[0]) + ' ' +
                             QByteArray::number(err[0]) + ' ' + QByteArray::number(started) + ' ' +
                             dir + '\n' + file;
    ::setenv(kVariable, value.constData(), 1);
#endif
}

void claimPrestartedCadRead() {
    const char* value = ::getenv(kVariable);
    if (!value)
        return;
    const QByteArray text(value);
    ::unsetenv(kVariable);
    const qsizetype eol = text.indexOf('\n');
    const QList<QByteArray> f = text.left(eol).split(' ');
    PrestartedCadRead r;
    bool ok[4] = {};
    if (eol < 0 || f.size() != 5)
        return;
    r.pid = pid_t(f[0].toLongLong(&ok[0]));
    r.out = f[1].toInt(&ok[1]);
    r.err = f[2].toInt(&ok[2]);
    r.startedNs = f[3].toLongLong(&ok[3]);
    r.dir = QFile::decodeName(f[4]);
    r.path = QFile::decodeName(text.mid(eol + 1));
    if (!ok[0] || !ok[1] || !ok[2] || !ok[3] || r.pid <= 0 || r.out < 0 || r.err < 0 ||
        ::fcntl(r.out, F_GETFD) < 0 || ::fcntl(r.err, F_GETFD) < 0)
        return; // not ours (a variable set by hand): nothing to take over
    // Not inherited by this program's own children; read without blocking.
    for (int fd : {r.out, r.err}) {
        ::fcntl(fd, F_SETFD, FD_CLOEXEC);
        ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) | O_NONBLOCK);
    }
    // Removed, and the child killed, should this program be stopped by a signal.
    registerCadTempDir(r.dir);
    registerCadChild(r.pid);
    QMutexLocker lock(&claimed().mutex);
    claimed().read = r;
}

std::optional<PrestartedCadRead> takePrestartedCadRead(const QString& path) {
    QMutexLocker lock(&claimed().mutex);
    if (!claimed().read || claimed().read->path != path)
        return std::nullopt;
    PrestartedCadRead r = *claimed().read;
    claimed().read.reset();
    return r;
}

} // namespace kw
