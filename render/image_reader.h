// Reads image files through OpenImageIO (libknotwork_oiio.so, loaded on the first read):
// EXR, HDR, PNG, JPEG, TIFF and the other formats OpenImageIO reads.
#pragma once

#include "model/error.h"

#include <QString>
#include <vector>

namespace kw {

/// A decoded image: width * height * channels floats, rows top first. 8/16-bit files are
/// scaled to [0, 1]; float files (EXR, HDR) keep their values.
struct FloatImage {
    int width = 0;
    int height = 0;
    int channels = 0; ///< 1..4: the file's first channels
    std::vector<float> pixels;
};

/// The most floats readImageFile accepts (512 MiB), so that a corrupt header cannot ask for
/// an absurd allocation.
inline constexpr size_t kMaxImageFloats = size_t(1) << 27;

/// Reads the first subimage of `path`. Returns the error "<path>: <reason>" when the file is
/// missing, the OpenImageIO module does not load, the format is unknown or the data is corrupt
/// or too large.
Expected<FloatImage> readImageFile(const QString& path);

} // namespace kw
