// OpenImageIO output of colour images and AOV buffers.
#include "render/image_writer.h"

#include <OpenImageIO/imageio.h>
#include <algorithm>
#include <vector>

namespace kw {

namespace {

QString suffixOf(const QString& path) {
    const int dot = path.lastIndexOf(QLatin1Char('.'));
    return dot < 0 ? QString() : path.mid(dot + 1).toLower();
}

bool writePixels(const QString& path, const OIIO::ImageSpec& spec, const void* pixels,
                 QString* error) {
    const std::string file = path.toStdString();
    auto out = OIIO::ImageOutput::create(file);
    if (!out) {
        *error = QStringLiteral("%1: no image writer for this format (%2)")
                     .arg(path, QString::fromStdString(OIIO::geterror()));
        return false;
    }
    if (!out->open(file, spec) || !out->write_image(spec.format, pixels) || !out->close()) {
        *error = QStringLiteral("%1: could not write image: %2")
                     .arg(path, QString::fromStdString(out->geterror()));
        return false;
    }
    return true;
}

} // namespace

bool isSupportedImagePath(const QString& path) {
    const QString s = suffixOf(path);
    return s == QLatin1String("png") || s == QLatin1String("jpg") || s == QLatin1String("jpeg") ||
           s == QLatin1String("tif") || s == QLatin1String("tiff") || s == QLatin1String("exr");
}

bool writeColorImage(const QImage& image, const QString& path, QString* error) {
    if (!isSupportedImagePath(path)) {
        *error =
            QStringLiteral("%1: unsupported image type (use .png, .jpg, .tif or .exr)").arg(path);
        return false;
    }
    if (image.isNull()) {
        *error = QStringLiteral("%1: nothing was rendered").arg(path);
        return false;
    }
    const QImage rgb = image.convertToFormat(QImage::Format_RGB888);
    const int w = rgb.width(), h = rgb.height();
    std::vector<unsigned char> bytes(size_t(w) * size_t(h) * 3);
    for (int y = 0; y < h; ++y)
        std::copy_n(rgb.constScanLine(y), size_t(w) * 3, bytes.data() + size_t(y) * size_t(w) * 3);
    if (suffixOf(path) == QLatin1String("exr")) {
        std::vector<float> f(bytes.size());
        for (size_t k = 0; k < bytes.size(); ++k)
            f[k] = float(bytes[k]) / 255.0f;
        OIIO::ImageSpec spec(w, h, 3, OIIO::TypeDesc::FLOAT);
        return writePixels(path, spec, f.data(), error);
    }
    OIIO::ImageSpec spec(w, h, 3, OIIO::TypeDesc::UINT8);
    if (suffixOf(path).startsWith(QLatin1String("jp")))
        spec.attribute("CompressionQuality", 95);
    return writePixels(path, spec, bytes.data(), error);
}

bool writeAovImage(const AovBuffer& aov, const QString& path, QString* error) {
    if (suffixOf(path) != QLatin1String("exr")) {
        *error = QStringLiteral("%1: the AOV image must be an .exr file").arg(path);
        return false;
    }
    if (aov.width <= 0 || aov.height <= 0 || aov.data.empty()) {
        *error = QStringLiteral("%1: no AOV data was rendered").arg(path);
        return false;
    }
    const bool curvature = !aov.curvature.empty();
    const int channels = AovBuffer::kChannels + (curvature ? AovBuffer::kCurvatureChannels : 0);
    OIIO::ImageSpec spec(aov.width, aov.height, channels, OIIO::TypeDesc::FLOAT);
    spec.channelnames.clear();
    for (const char* name : AovBuffer::kChannelNames)
        spec.channelnames.emplace_back(name);
    if (!curvature) {
        spec.attribute("compression", "zip");
        return writePixels(path, spec, aov.data.data(), error);
    }
    for (const char* name : AovBuffer::kCurvatureNames)
        spec.channelnames.emplace_back(name);
    spec.attribute("compression", "zip");
    std::vector<float> all(size_t(aov.width) * size_t(aov.height) * size_t(channels));
    for (size_t p = 0; p < size_t(aov.width) * size_t(aov.height); ++p) {
        std::copy_n(aov.data.data() + p * AovBuffer::kChannels, AovBuffer::kChannels,
                    all.data() + p * size_t(channels));
        std::copy_n(aov.curvature.data() + p * AovBuffer::kCurvatureChannels,
                    AovBuffer::kCurvatureChannels,
                    all.data() + p * size_t(channels) + AovBuffer::kChannels);
    }
    return writePixels(path, spec, all.data(), error);
}

} // namespace kw
