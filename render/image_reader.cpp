// Image input through the OpenImageIO module (render/oiio/image_module.h).
#include "render/image_reader.h"

#include "render/oiio/image_module.h"
#include "render/oiio_loader.h"

#include <QFileInfo>

namespace kw {

namespace {

/// KwImageAllocFn: the caller's vector, refusing absurd sizes.
float* allocateInto(void* context, size_t count) {
    if (count == 0 || count > kMaxImageFloats)
        return nullptr;
    auto* pixels = static_cast<std::vector<float>*>(context);
    pixels->assign(count, 0.0f);
    return pixels->data();
}

} // namespace

Expected<FloatImage> readImageFile(const QString& path) {
    if (!QFileInfo(path).isFile())
        return Error(QStringLiteral("%1: no such file").arg(path), path);
    const Expected<void*> symbol = oiioModuleSymbol(KW_IMAGE_READ_SYMBOL);
    if (!symbol)
        return Error(
            QStringLiteral("%1: cannot read images: the OpenImageIO module did not load (%2)")
                .arg(path, symbol.message()),
            path);
    const auto read = reinterpret_cast<KwImageReadFn>(*symbol);
    const QByteArray file = path.toLocal8Bit();
    FloatImage img;
    const KwImageRead request{file.constData(), allocateInto, &img.pixels,
                              &img.width,       &img.height,  &img.channels};
    char message[1024] = {0};
    if (!read(&request, message, sizeof message))
        return Error(QStringLiteral("%1: %2").arg(path, QString::fromLocal8Bit(message)), path);
    if (img.width <= 0 || img.height <= 0 || img.channels < 1 || img.channels > 4 ||
        img.pixels.size() != size_t(img.width) * size_t(img.height) * size_t(img.channels))
        return Error(QStringLiteral("%1: the image reader returned an inconsistent size").arg(path),
                     path);
    return img;
}

} // namespace kw
