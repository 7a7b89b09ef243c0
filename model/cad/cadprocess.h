// IGES, STEP and BREP read by OpenCASCADE in a child process: `knotwork __read-cad IN DIR`
// writes the scene, its report and face indices as DIR/import.kwi (handover.h). OCCT's readers can
// overflow the stack or run for ever on hostile input, and no signal handler recovers from
// that; a child that crashes, runs out of time or memory, or is cancelled is simply killed.
#pragma once

#include "model/cad/cadimport.h"
#include "model/io/meshobj.h"

#include <QString>
#include <QStringList>

namespace kw {

/// The verb of the knotwork executable that reads a CAD file for a parent (not in --help).
constexpr const char* kReadCadVerb = "__read-cad";
/// The verb that writes a STEP or IGES file for a parent (exportCadFile, cadexport.h):
/// `knotwork __write-cad SCENE.kwi OUT DIR [--step-schema S] [--iges-faces] [--require-closed]
/// [--tolerance T] [--max-memory-mb N]` reads the scene hand-over SCENE.kwi (handover.h) and
/// leaves the file's bytes in DIR/export.out and its report in DIR/export.txt; OUT names the
/// destination (format, messages, STEP header), which the parent writes. With `--read-cad`,
/// SCENE.kwi is instead an IGES, STEP or BREP file that the child reads first (convertCadFile).
constexpr const char* kWriteCadVerb = "__write-cad";

/// The time a file of `bytes` may take: 10 s plus 10 s per MB to read it, twice that when it is
/// also meshed (`mesh`: BRepMesh takes about as long as the read), or the value of the
/// environment variable KNOTWORK_CAD_TIME_LIMIT (seconds) when it is set.
double cadTimeLimitSeconds(qint64 bytes, bool mesh = false);
/// The child's address-space limit (RLIMIT_AS) for a file of `bytes`: 2 GiB plus 256 MiB per
/// MB, at most the machine's physical memory (or 2 GiB when that is less), or
/// KNOTWORK_CAD_MEMORY_MB megabytes when that environment variable is set.
long long cadMemoryLimitBytes(qint64 bytes = 0);

/// The knotwork executable that runs the child: the one set with setCadReaderExecutable, else
/// the environment variable KNOTWORK_CAD_READER (the tests set it), else kw::programPath
/// ("knotwork"): next to the running executable, or bin/knotwork of an installed prefix.
QString cadReaderExecutable();
/// Sets the executable for this process (tests, which are not knotwork themselves).
void setCadReaderExecutable(const QString& path);

/// Parent side: runs the child on `path` and reads back its scene and report, within
/// cadTimeLimitSeconds(file size) and cadMemoryLimitBytes() (the environment variables there
/// set other limits; the tests use them). Errors (file = path), as
/// "<path>: <reason>" except for a crash: "the STEP reader crashed on <path> (signal 11:
/// Segmentation fault)"; a time-out names the limit; a cancel (progress returned false) kills
/// the child at once and gives "<path>: import cancelled".
/// With `deflection` (and `mesh`) set, the child also triangulates the shape with OpenCASCADE
/// (importAndMeshOcctFile, `knotwork mesh`) and `mesh` gets its triangles, tagged with the ids
/// of the returned scene's surfaces.
Expected<ImportResult> importInChildProcess(const QString& path, CadFormat format,
                                            const ImportProgress& progress = {},
                                            const MeshDeflection* deflection = nullptr,
                                            TaggedMeshSet* mesh = nullptr);

/// Child side: writes a finished import (finishImport) for the parent as DIR/import.kwi
/// (encodeImportHandover), atomically. An Error when it cannot.
Status writeImportForParent(const ImportResult& result, const QString& dir);

/// Child side: writes the mesh for the parent as DIR/mesh.obj (writeTaggedMeshObj), atomically.
Status writeMeshForParent(const TaggedMeshSet& mesh, const QString& dir);

/// "progress DONE TOTAL\n", the line the child prints for the parent's progress bar.
QByteArray progressLine(int done, int total);

/// Child side: a progress callback that prints progressLine to stdout for the parent. One
/// line per change of `done`, at most one per 20 ms but always the last: the parent reads
/// them every 50 ms, and OCCT reports hundreds of steps for a small file (391 for
/// hammer.iges, each a write and a wake-up of the parent). It never cancels: the parent
/// cancels by killing the child.
ImportProgress progressToParent();

} // namespace kw
