// The CAD child's working folders in $TMPDIR: named after the process that owns them, removed on
// every exit path (SIGTERM, SIGINT and SIGHUP included), and swept by a later run when a kill -9
// left them behind.
#pragma once

#include "model/error.h"

#include <QString>
#include <sys/types.h>

namespace kw {

/// Makes a new folder QDir::tempPath()/knotwork-<pid>-XXXXXX (mode 0700) and registers it for
/// removal should this process be stopped by SIGTERM, SIGINT or SIGHUP; first sweeps stale
/// folders (sweepStaleCadTempDirs). An Error (the system's reason) when it cannot.
Expected<QString> makeCadTempDir();

/// Registers an existing folder (one the launcher made for a prestarted child) the same way.
void registerCadTempDir(const QString& dir);

/// Removes `dir` and everything in it, and unregisters it.
void removeCadTempDir(const QString& dir);

/// Registers a child that the signals above kill (SIGKILL) before the folders are removed;
/// unregister it once it has been reaped.
void registerCadChild(pid_t pid);
void unregisterCadChild(pid_t pid);

/// Removes the folders knotwork-<pid>-XXXXXX in `tempDir` that belong to this user, are older
/// than `minAgeSeconds` and whose owner <pid> no longer runs. Returns how many it removed.
int sweepStaleCadTempDirs(const QString& tempDir, int minAgeSeconds = 60);

} // namespace kw
