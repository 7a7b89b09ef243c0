// Registered temporary folders, removed from a signal handler with async-signal-safe calls only
// (cadtempdir.h).
#include "model/cad/cadtempdir.h"

#include <QDateTime>
#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <dirent.h>
#include <fcntl.h>
#include <mutex>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

namespace kw {
namespace {

// Fixed slots, so the handler needs no allocation and no lock: a slot is in use while its
// flag is set, and its path is written before the flag.
constexpr int kSlots = 32;
constexpr int kPathMax = 1024;
struct DirSlot {
    std::atomic<bool> used{false};
    char path[kPathMax];
};
DirSlot dirSlots[kSlots];
std::atomic<pid_t> childSlots[kSlots];
std::mutex slotMutex; // writers only; the handler reads the flags

constexpr int kSignals[] = {SIGTERM, SIGINT, SIGHUP};
struct sigaction previous[3];

// Removes a flat folder (the child writes files only) with raw system calls.
void removeFlatFolder(const char* path) {
    const int fd = ::open(path, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd >= 0) {
        alignas(8) char buffer[4096];
        for (;;) {
            const long n = ::syscall(SYS_getdents64, fd, buffer, sizeof buffer);
            if (n <= 0)
                break;
            for (long at = 0; at < n;) {
                struct Entry {
                    ino64_t ino;
                    off64_t off;
                    unsigned short reclen;
                    unsigned char type;
                    char name[1];
                };
                const auto* e = reinterpret_cast<const Entry*>(buffer + at);
                at += e->reclen;
                if (std::strcmp(e->name, ".") != 0 && std::strcmp(e->name, "..") != 0)
                    ::unlinkat(fd, e->name, 0);
            }
        }
        ::close(fd);
    }
    ::rmdir(path);
}

void onSignal(int sig) {
    const int saved = errno;
    for (auto& child : childSlots)
        if (const pid_t pid = child.load(); pid > 0)
            ::kill(pid, SIGKILL);
    for (DirSlot& slot : dirSlots)
        if (slot.used.load())
            removeFlatFolder(slot.path);
    // Then whatever was there before: the default action ends the process with this signal.
    for (int k = 0; k < 3; ++k)
        if (kSignals[k] == sig) {
            ::sigaction(sig, &previous[k], nullptr);
            if (previous[k].sa_handler != SIG_DFL && previous[k].sa_handler != SIG_IGN &&
                !(previous[k].sa_flags & SA_SIGINFO)) {
                previous[k].sa_handler(sig);
                errno = saved;
                return;
            }
        }
    errno = saved;
    ::raise(sig);
}

// exit() from a library (libjpeg's error handler) skips the destructors that remove folders.
void removeAllAtExit() {
    for (auto& child : childSlots)
        if (const pid_t pid = child.load(); pid > 0)
            ::kill(pid, SIGKILL);
    for (DirSlot& slot : dirSlots)
        if (slot.used.load())
            removeFlatFolder(slot.path);
}

void installHandlersOnce() {
    static std::once_flag once;
    std::call_once(once, [] {
        std::atexit(removeAllAtExit);
        for (int k = 0; k < 3; ++k) {
            struct sigaction current {};
            ::sigaction(kSignals[k], nullptr, &current);
            if (current.sa_handler == SIG_IGN)
                continue; // the user asked this process to ignore it (nohup)
            previous[k] = current;
            struct sigaction ours {};
            ours.sa_handler = onSignal;
            sigemptyset(&ours.sa_mask);
            ours.sa_flags = SA_RESETHAND;
            ::sigaction(kSignals[k], &ours, nullptr);
        }
    });
}

} // namespace

void registerCadTempDir(const QString& dir) {
    const QByteArray native = QFile::encodeName(dir);
    if (native.size() >= kPathMax)
        return;
    installHandlersOnce();
    std::lock_guard lock(slotMutex);
    for (DirSlot& slot : dirSlots)
        if (!slot.used.load()) {
            std::memcpy(slot.path, native.constData(), size_t(native.size()) + 1);
            slot.used.store(true);
            return;
        }
}

void removeCadTempDir(const QString& dir) {
    const QByteArray native = QFile::encodeName(dir);
    {
        std::lock_guard lock(slotMutex);
        for (DirSlot& slot : dirSlots)
            if (slot.used.load() && native == slot.path)
                slot.used.store(false);
    }
    QDir(dir).removeRecursively();
}

void registerCadChild(pid_t pid) {
    installHandlersOnce();
    std::lock_guard lock(slotMutex);
    for (auto& child : childSlots)
        if (child.load() == 0) {
            child.store(pid);
            return;
        }
}

void unregisterCadChild(pid_t pid) {
    std::lock_guard lock(slotMutex);
    for (auto& child : childSlots)
        if (child.load() == pid)
            child.store(0);
}

int sweepStaleCadTempDirs(const QString& tempDir, int minAgeSeconds) {
    const QDir dir(tempDir);
    const QDateTime before = QDateTime::currentDateTimeUtc().addSecs(-minAgeSeconds);
    int removed = 0;
    const QFileInfoList entries =
        dir.entryInfoList({QStringLiteral("knotwork-*-*")},
                          QDir::Dirs | QDir::Hidden | QDir::NoDotAndDotDot | QDir::NoSymLinks);
    for (const QFileInfo& e : entries) {
        if (e.lastModified().toUTC() > before || e.ownerId() != ::geteuid())
            continue;
        const QString name = e.fileName();
        if (e.isDir()) {
            // knotwork-<pid>-XXXXXX: only when that process is gone.
            const QStringList parts = name.split(QLatin1Char('-'));
            bool ok = false;
            const long long pid = parts.size() == 3 ? parts[1].toLongLong(&ok) : 0;
            if (!ok || pid <= 0 || parts[2].size() != 6)
                continue;
            if (::kill(pid_t(pid), 0) == 0 || errno != ESRCH)
                continue;
            if (QDir(e.filePath()).removeRecursively())
                ++removed;
        }
    }
    return removed;
}

Expected<QString> makeCadTempDir() {
    const QString temp = QDir::tempPath();
    sweepStaleCadTempDirs(temp);
    QByteArray path =
        QFile::encodeName(temp) + "/knotwork-" + QByteArray::number(::getpid()) + "-XXXXXX";
    if (!::mkdtemp(path.data()))
        return Error(qt_error_string(errno), QFile::decodeName(path));
    const QString dir = QFile::decodeName(path);
    registerCadTempDir(dir);
    return dir;
}

} // namespace kw
