// Saving a QImage (Export Image, --screenshot, bench plots) so that a failure or a kill leaves
// the old file or the new complete one.
#pragma once

#include "model/error.h"

#include <QImage>
#include <QString>

namespace kw {

/// Writes `image` to `path` atomically (kw::saveFileAtomically: QSaveFile, flush checked), in
/// the format of the path's extension (png, jpg/jpeg, bmp, tif/tiff; PNG when there is none).
/// The error "<path>: <reason>" for a null image, an unknown extension or a failed write; the
/// previous file is then untouched.
Status saveImageAtomically(const QImage& image, const QString& path);

} // namespace kw
