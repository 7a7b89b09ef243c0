// Atomic QImage saving through QSaveFile.
#include "render/image_save.h"

#include "model/io/savefile.h"

#include <QFileDevice>
#include <QFileInfo>
#include <QImageWriter>

namespace kw {

bool saveImageAtomically(const QImage& image, const QString& path, QString* error) {
    if (image.isNull()) {
        if (error)
            *error = QStringLiteral("%1: there is no image to write").arg(path);
        return false;
    }
    QByteArray format = QFileInfo(path).suffix().toLower().toLatin1();
    if (format.isEmpty())
        format = "png";
    if (!QImageWriter::supportedImageFormats().contains(format)) {
        if (error)
            *error = QStringLiteral("%1: unsupported image type '%2'")
                         .arg(path, QString::fromLatin1(format));
        return false;
    }
    QString why;
    const bool ok = saveFileAtomically(
        path,
        [&](QIODevice& device) {
            QImageWriter writer(&device, format);
            if (writer.write(image))
                return true;
            // A failed write of the file itself (a full disk) is named by the file's own error
            // (errno's text); QImageWriter only knows "Unknown error".
            const auto* file = qobject_cast<QFileDevice*>(&device);
            if (!file || file->error() == QFileDevice::NoError)
                why = writer.errorString();
            return false;
        },
        error);
    if (!ok && error && !why.isEmpty())
        *error = QStringLiteral("%1: cannot write the image: %2").arg(path, why);
    return ok;
}

} // namespace kw
