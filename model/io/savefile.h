// Writing files so that a failure (disk full, EFBIG, a crash or kill -9) leaves the old file or
// the new complete one, never a truncated one: QSaveFile with an explicit flush check.
#pragma once

#include <QByteArray>
#include <QString>
#include <functional>

class QIODevice;

namespace kw {

/// Writes `path` atomically: `write` fills a QSaveFile (a temporary file in the same folder)
/// and returns false on failure; the data is flushed and checked explicitly (Qt 6.4's
/// QSaveFile::commit ignores a failed final flush, e.g. EFBIG or ENOSPC, and would replace the
/// old file with a truncated one), then renamed over `path`. On any failure the previous file
/// is untouched, false is returned and *error (if non-null) is "<path>: <reason>".
bool saveFileAtomically(const QString& path, const std::function<bool(QIODevice&)>& write,
                        QString* error);
/// The same for a block of bytes.
bool saveBytesAtomically(const QString& path, const QByteArray& bytes, QString* error);

/// For writers that need a file name of their own (OpenImageIO picks the format from the
/// extension): `write` writes a temporary file in the folder of `path` whose name ends like
/// `path` ("<folder>/.<name>.XXXXXX.<ext>"), which is then renamed over `path` (rename(2) is
/// atomic on one file system). On failure the temporary file is removed, the previous file is
/// untouched, false is returned and *error is "<path>: <reason>" (`write` may set *error
/// itself).
bool saveViaTemporaryName(
    const QString& path,
    const std::function<bool(const QString& temporaryPath, QString* error)>& write, QString* error);

} // namespace kw
