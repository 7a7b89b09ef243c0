// Atomic QImage saving through QSaveFile.
#include "render/image_save.h"

#include "model/savefile.h"

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
            why = writer.errorString();
            return false;
        },
        error);
    if (!ok && error && !why.isEmpty())
        *error = QStringLiteral("%1: cannot write the image: %2").arg(path, why);
    return ok;
}

} // namespace kw
