// Writing files so that a failure (disk full, EFBIG, a crash or kill -9) leaves the old file or
// the new complete one, never a truncated one: QSaveFile with an explicit flush check.
#pragma once

#include "model/error.h"

#include <QByteArray>
#include <QString>
#include <functional>

class QIODevice;

namespace kw {

/// Writes `path` atomically: `write` fills a QSaveFile (a temporary file in the same folder)
/// and returns false on failure; the data is flushed and checked explicitly (Qt 6.4's
/// QSaveFile::commit ignores a failed final flush, e.g. EFBIG or ENOSPC, and would replace the
/// old file with a truncated one), then renamed over `path`. On any failure the previous file
/// is untouched and the error is "<path>: <reason>" (Error::file = path).
Status saveFileAtomically(const QString& path, const std::function<bool(QIODevice&)>& write);
/// The same for a block of bytes.
Status saveBytesAtomically(const QString& path, const QByteArray& bytes);

/// For writers that need a file name of their own (OpenImageIO picks the format from the
/// extension): `write` writes a temporary file in the folder of `path` whose name ends like
/// `path` ("<folder>/.<name>.XXXXXX.<ext>"), which is then renamed over `path` (rename(2) is
/// atomic on one file system). On failure the temporary file is removed, the previous file is
/// untouched and the error is "<path>: <reason>": `write`'s own error when it has a message,
/// else "<path>: cannot write".
Status saveViaTemporaryName(const QString& path,
                            const std::function<Status(const QString& temporaryPath)>& write);

} // namespace kw
