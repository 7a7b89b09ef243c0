// A CAD read started before the program that wants it exists: `knotwork render part.iges` starts
// the reader's child process in the launcher, before the launcher replaces itself (exec) with
// knotwork-gl, so OpenCASCADE reads the file while knotwork-gl loads its libraries and starts
// Qt's GUI (~25 ms of a first image; docs/PERFORMANCE.md, First image of a CAD file). The
// child stays the same process's child across the exec; knotwork-gl takes it over and watches
// it as importInChildProcess watches its own (crash, time limit, memory limit, Cancel).
#pragma once

#include <QString>
#include <optional>
#include <sys/types.h>

namespace kw {

/// A prestarted child: its pid, the read ends of its stdout and stderr, when it started
/// (CLOCK_MONOTONIC, ns: the time limit counts from there), its folder and the file it reads.
struct PrestartedCadRead {
    pid_t pid = 0;
    int out = -1;
    int err = -1;
    qint64 startedNs = 0;
    QString dir;
    QString path;
};

/// CLOCK_MONOTONIC in nanoseconds (the same clock in both programs of an exec).
qint64 monotonicNs();

/// Launcher side, before the exec: when `path` is an existing IGES, STEP or BREP file, starts
/// `reader __read-cad path DIR --max-memory-mb N --die-with-parent` in a new folder under
/// QDir::tempPath(), with the limits importInChildProcess gives, and describes it in the
/// environment variable KNOTWORK_CAD_PRESTARTED for the program exec'd next. Anything that
/// fails leaves nothing started (the read then happens as usual).
void prestartCadRead(const QString& reader, const QString& path);

/// knotwork-gl side, first thing in main (one thread): takes a read prestartCadRead described
/// and removes the variable. One not taken by takePrestartedCadRead is killed, and its folder
/// removed, when the program exits.
void claimPrestartedCadRead();

/// The claimed read of exactly `path`, once; the caller then owns the process, the pipes and
/// the folder. nullopt when there is none for that path.
std::optional<PrestartedCadRead> takePrestartedCadRead(const QString& path);

} // namespace kw
