// Saving a QImage (Export Image, --screenshot, bench plots) so that a failure or a kill leaves
// the old file or the new complete one.
#pragma once

#include <QImage>
#include <QString>

namespace kw {

/// Writes `image` to `path` atomically (kw::saveFileAtomically: QSaveFile, flush checked), in
/// the format of the path's extension (png, jpg/jpeg, bmp, tif/tiff; PNG when there is none).
/// False with *error "<path>: <reason>" for a null image, an unknown extension or a failed
/// write; the previous file is then untouched.
bool saveImageAtomically(const QImage& image, const QString& path, QString* error);

} // namespace kw
