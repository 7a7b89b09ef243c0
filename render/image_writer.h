// Writes rendered images: colour as PNG (Qt's encoder, atomically) or JPG/TIF (8-bit) or EXR
// (float) and the AOV buffer as a multi-channel float EXR through OpenImageIO, which is loaded
// (libknotwork_oiio.so) only when one of those is written.
#pragma once

#include "model/error.h"
#include "render/aov_buffer.h"

#include <QImage>
#include <QString>

namespace kw {

/// True when `path` ends in .png, .jpg, .jpeg, .tif, .tiff or .exr (case-insensitive).
bool isSupportedImagePath(const QString& path);

/// Writes `image` (any QImage format; converted to RGB) to `path`; the format follows the
/// extension (see isSupportedImagePath): 8-bit RGB for PNG/JPG/TIF, 32-bit float RGB for EXR.
/// Returns the error naming the path on an unknown extension or a write failure.
Status writeColorImage(const QImage& image, const QString& path);

/// Writes the AOV buffer as a float EXR with channels AovBuffer::kChannelNames (and
/// kCurvatureNames when the buffer has curvature). `path` must
/// end in .exr. Returns the error on failure.
Status writeAovImage(const AovBuffer& aov, const QString& path);

} // namespace kw
