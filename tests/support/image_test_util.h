// Image comparisons shared by the GL and GUI tests.
#pragma once

#include <QImage>
#include <QtGlobal>

namespace kwtest {

/// Pixels that differ between two same-sized images.
inline int differingPixels(const QImage& a, const QImage& b) {
    if (a.size() != b.size())
        return a.width() * a.height();
    const QImage x = a.convertToFormat(QImage::Format_RGBA8888);
    const QImage y = b.convertToFormat(QImage::Format_RGBA8888);
    int n = 0;
    for (int r = 0; r < x.height(); ++r) {
        const auto* p = reinterpret_cast<const quint32*>(x.constScanLine(r));
        const auto* q = reinterpret_cast<const quint32*>(y.constScanLine(r));
        for (int c = 0; c < x.width(); ++c)
            n += p[c] != q[c];
    }
    return n;
}

} // namespace kwtest
