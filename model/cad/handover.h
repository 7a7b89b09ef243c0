// The CAD child process's result as the parent reads it back (cadprocess.h): the imported scene,
// its report and face indices in one binary block, instead of a .knot JSON file and a report
// (for hammer.iges, 1.4 MB of JSON took ~10 ms to write in the child and ~10 ms to read on the
// parent's critical path; docs/PERFORMANCE.md, First image of a CAD file).
//
// Both ends are the same build on the same machine (the parent runs its own `knotwork`), so
// numbers are stored in the machine's byte order and doubles bit for bit; a block from another
// build is refused by its version. The reader trusts nothing: every count is checked against
// the bytes left before anything is allocated, enums and flags against their values, the
// block must end exactly after its end mark, and the scene must then pass kw::checkScene, the
// rule of every reader (docs/FILE_FORMAT.md). A bad block gives an error, never a crash.
#pragma once

#include "model/cad/cadimport.h"

#include <QByteArray>
#include <QString>
#include <optional>

namespace kw {

/// Encodes a finished import (finishImport) for the parent.
QByteArray encodeImportHandover(const ImportResult& result);

/// Decodes encodeImportHandover's block. An Error ("<what> at byte N: <reason>", location
/// "byte N") when it is truncated, corrupt, from another build, or its scene is not valid.
Expected<ImportResult> decodeImportHandover(const QByteArray& block);

} // namespace kw
