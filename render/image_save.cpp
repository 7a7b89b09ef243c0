// Atomic QImage saving through QSaveFile.
#include "render/image_save.h"

#include "model/io/savefile.h"

#include <QFileDevice>
#include <QFileInfo>
#include <QImageWriter>

namespace kw {

Status saveImageAtomically(const QImage& image, const QString& path) {
    if (image.isNull())
        return Error(QStringLiteral("%1: there is no image to write").arg(path), path);
    QByteArray format = QFileInfo(path).suffix().toLower().toLatin1();
    if (format.isEmpty())
        format = "png";
    if (!QImageWriter::supportedImageFormats().contains(format))
        return Error(QStringLiteral("%1: unsupported image type '%2'")
                         .arg(path, QString::fromLatin1(format)),
                     path);
    QString why;
    const Status saved = saveFileAtomically(path, [&](QIODevice& device) {
        QImageWriter writer(&device, format);
        if (writer.write(image))
            return true;
        // A failed write of the file itself (a full disk) is named by the file's own error
        // (errno's text); QImageWriter only knows "Unknown error".
        const auto* file = qobject_cast<QFileDevice*>(&device);
        if (!file || file->error() == QFileDevice::NoError)
            why = writer.errorString();
        return false;
    });
    if (!saved && !why.isEmpty())
        return Error(QStringLiteral("%1: cannot write the image: %2").arg(path, why), path);
    return saved;
}

} // namespace kw
