// Output of colour images and AOV buffers through OpenImageIO, which lives in the module
// libknotwork_oiio.so (render/oiio/) and is loaded on the first write: OpenImageIO maps 260
// shared libraries, which a render that fails early or the editor should not pay for.
#include "render/image_writer.h"

#include "model/io/savefile.h"
#include "render/image_save.h"
#include "render/oiio/image_module.h"
#include "render/oiio_loader.h"

#include <algorithm>
#include <cerrno>
#include <vector>

namespace kw {

namespace {

QString suffixOf(const QString& path) {
    const int dot = path.lastIndexOf(QLatin1Char('.'));
    return dot < 0 ? QString() : path.mid(dot + 1).toLower();
}

/// The module's write entry point (render/oiio_loader.h).
Expected<KwImageWriteFn> imageWriter() {
    const Expected<void*> symbol = oiioModuleSymbol(KW_IMAGE_WRITE_SYMBOL);
    if (!symbol)
        return symbol.error();
    return reinterpret_cast<KwImageWriteFn>(*symbol);
}

Status writePixels(const QString& path, KwImageWrite image) {
    const Expected<KwImageWriteFn> writer = imageWriter();
    if (!writer)
        return Error(
            QStringLiteral("%1: cannot write images: the OpenImageIO module did not load (%2)")
                .arg(path, writer.message()),
            path);
    const KwImageWriteFn write = *writer;
    // OpenImageIO writes straight to the name it is given and picks the format from its
    // extension: it writes a temporary name in the same folder, renamed over `path` when done.
    return saveViaTemporaryName(path, [&](const QString& temporary) -> Status {
        const QByteArray file = temporary.toLocal8Bit();
        image.path = file.constData();
        char message[1024] = {0};
        errno = 0;
        if (!write(&image, message, sizeof message)) {
            // OpenImageIO's messages ("Could not open", "Write error") do not say why; the
            // errno of the failed call does (a full disk: "No space left on device").
            const int err = errno;
            return Error(
                QStringLiteral("%1: %2%3")
                    .arg(path, QString::fromLocal8Bit(message),
                         err ? QStringLiteral(" (%1)").arg(qt_error_string(err)) : QString()),
                path);
        }
        return ok();
    });
}

} // namespace

bool isSupportedImagePath(const QString& path) {
    const QString s = suffixOf(path);
    return s == QLatin1String("png") || s == QLatin1String("jpg") || s == QLatin1String("jpeg") ||
           s == QLatin1String("tif") || s == QLatin1String("tiff") || s == QLatin1String("exr");
}

Status writeColorImage(const QImage& image, const QString& path) {
    if (!isSupportedImagePath(path))
        return Error(
            QStringLiteral("%1: unsupported image type (use .png, .jpg, .tif or .exr)").arg(path),
            path);
    if (image.isNull())
        return Error(QStringLiteral("%1: nothing was rendered").arg(path), path);
    const QImage rgb = image.convertToFormat(QImage::Format_RGB888);
    // PNG needs no OpenImageIO: Qt's own encoder, written atomically (image_save.h).
    if (suffixOf(path) == QLatin1String("png"))
        return saveImageAtomically(rgb, path);
    const int w = rgb.width(), h = rgb.height();
    std::vector<unsigned char> bytes(size_t(w) * size_t(h) * 3);
    for (int y = 0; y < h; ++y)
        std::copy_n(rgb.constScanLine(y), size_t(w) * 3, bytes.data() + size_t(y) * size_t(w) * 3);
    if (suffixOf(path) == QLatin1String("exr")) {
        std::vector<float> f(bytes.size());
        for (size_t k = 0; k < bytes.size(); ++k)
            f[k] = float(bytes[k]) / 255.0f;
        return writePixels(path, KwImageWrite{nullptr, w, h, 3, 1, f.data(), nullptr, 0, nullptr});
    }
    const int quality = suffixOf(path).startsWith(QLatin1String("jp")) ? 95 : 0;
    return writePixels(path,
                       KwImageWrite{nullptr, w, h, 3, 0, bytes.data(), nullptr, quality, nullptr});
}

Status writeAovImage(const AovBuffer& aov, const QString& path) {
    if (suffixOf(path) != QLatin1String("exr"))
        return Error(QStringLiteral("%1: the AOV image must be an .exr file").arg(path), path);
    if (aov.width <= 0 || aov.height <= 0 || aov.data.empty())
        return Error(QStringLiteral("%1: no AOV data was rendered").arg(path), path);
    if (aov.curvature.empty())
        return writePixels(path,
                           KwImageWrite{nullptr, aov.width, aov.height, AovBuffer::kChannels, 1,
                                        aov.data.data(), AovBuffer::kChannelNames, 0, "zip"});
    // With the curvature AOV: the 10 channels, then K, H, k1, k2, interleaved per pixel.
    constexpr int channels = AovBuffer::kChannels + AovBuffer::kCurvatureChannels;
    const char* names[channels];
    std::copy_n(AovBuffer::kChannelNames, AovBuffer::kChannels, names);
    std::copy_n(AovBuffer::kCurvatureNames, AovBuffer::kCurvatureChannels,
                names + AovBuffer::kChannels);
    std::vector<float> all(size_t(aov.width) * size_t(aov.height) * size_t(channels));
    for (size_t p = 0; p < size_t(aov.width) * size_t(aov.height); ++p) {
        std::copy_n(aov.data.data() + p * AovBuffer::kChannels, AovBuffer::kChannels,
                    all.data() + p * size_t(channels));
        std::copy_n(aov.curvature.data() + p * AovBuffer::kCurvatureChannels,
                    AovBuffer::kCurvatureChannels,
                    all.data() + p * size_t(channels) + AovBuffer::kChannels);
    }
    return writePixels(path, KwImageWrite{nullptr, aov.width, aov.height, channels, 1, all.data(),
                                          names, 0, "zip"});
}

} // namespace kw
