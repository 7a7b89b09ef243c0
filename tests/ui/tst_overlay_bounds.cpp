// OverlayBounds (ui/overlay_bounds.h): what QPainter paints on it, text, pens, transforms and a
// pixel ratio included, lies within its bounds: each case is painted on a QImage too and every
// pixel it touched must be inside, while the bounds stay near the painted area.
#include "ui/overlay_bounds.h"

#include <QImage>
#include <QPainter>
#include <QPainterPath>
#include <QTest>
#include <functional>

using namespace kw;

namespace {

/// The pixels `paint` touches on a transparent image of `size` at `dpr` (device pixels).
QRect touched(QSize size, qreal dpr, const std::function<void(QPainter&)>& paint) {
    QImage image(size * dpr, QImage::Format_ARGB32_Premultiplied);
    image.setDevicePixelRatio(dpr);
    image.fill(Qt::transparent);
    {
        QPainter p(&image);
        paint(p);
    }
    QRect r;
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x)
            if (qAlpha(image.pixel(x, y)) != 0)
                r |= QRect(x, y, 1, 1);
    return r;
}

/// OverlayBounds' rectangle (device pixels).
QRect bounded(QSize size, qreal dpr, const std::function<void(QPainter&)>& paint) {
    QImage like(size * dpr, QImage::Format_ARGB32_Premultiplied);
    like.setDevicePixelRatio(dpr);
    OverlayBounds bounds(like);
    {
        QPainter p(&bounds);
        paint(p);
    }
    return bounds.bounds();
}

} // namespace

class TestOverlayBounds : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void coversWhatIsPainted_data() {
        QTest::addColumn<int>("kind");
        QTest::addColumn<qreal>("dpr");
        const char* names[] = {"text",    "thick line",   "rectangle outline",
                               "ellipse", "rotated text", "polyline",
                               "fill",    "point"};
        for (qreal dpr : {1.0, 2.0})
            for (int k = 0; k < 8; ++k)
                QTest::addRow("%s @%g", names[k], dpr) << k << dpr;
    }
    void coversWhatIsPainted() {
        QFETCH(int, kind);
        QFETCH(qreal, dpr);
        const auto paint = [kind](QPainter& p) {
            p.setRenderHint(QPainter::Antialiasing);
            p.setPen(QPen(QColor(255, 80, 40), 2.5));
            switch (kind) {
            case 0:
                p.drawText(QPointF(60, 80), QStringLiteral("Wgjy 12.5 mm"));
                break;
            case 1:
                p.setPen(QPen(Qt::white, 7.0, Qt::SolidLine, Qt::SquareCap, Qt::MiterJoin));
                p.drawLine(QPointF(30, 40), QPointF(170, 120));
                break;
            case 2:
                p.drawRect(QRectF(40.5, 50.5, 60, 30));
                break;
            case 3:
                p.drawEllipse(QPointF(100, 90), 30, 20);
                break;
            case 4:
                p.translate(100, 100);
                p.rotate(35);
                p.drawText(QPointF(0, 0), QStringLiteral("X axis"));
                break;
            case 5: {
                const QPointF points[] = {{20, 20}, {80, 150}, {150, 40}, {170, 160}};
                p.drawPolyline(points, 4);
                break;
            }
            case 6:
                p.fillRect(QRect(110, 20, 76, 98), QColor(0, 0, 0, 140));
                break;
            case 7:
                p.setPen(QPen(Qt::white, 0));
                p.drawPoint(QPointF(123.4, 56.7));
                break;
            }
        };
        const QSize size(200, 200);
        const QRect painted = touched(size, dpr, paint);
        QVERIFY(!painted.isNull());
        const QRect bounds = bounded(size, dpr, paint);
        QVERIFY2(bounds.contains(painted),
                 qPrintable(QStringLiteral("painted %1,%2 %3x%4 outside bounds %5,%6 %7x%8")
                                .arg(painted.x())
                                .arg(painted.y())
                                .arg(painted.width())
                                .arg(painted.height())
                                .arg(bounds.x())
                                .arg(bounds.y())
                                .arg(bounds.width())
                                .arg(bounds.height())));
        // Near it: a margin of a few pixels and, for text, a character's width either side.
        const int slack = int(std::ceil(24 * dpr));
        QVERIFY2(bounds.width() <= painted.width() + 2 * slack &&
                     bounds.height() <= painted.height() + 2 * slack,
                 qPrintable(QStringLiteral("%1x%2 for %3x%4")
                                .arg(bounds.width())
                                .arg(bounds.height())
                                .arg(painted.width())
                                .arg(painted.height())));
    }

    void nothingPaintedIsNoBounds() {
        QImage like(64, 64, QImage::Format_ARGB32_Premultiplied);
        OverlayBounds bounds(like);
        {
            QPainter p(&bounds);
            p.setRenderHint(QPainter::Antialiasing);
        }
        QVERIFY(bounds.bounds().isNull());
    }
};

QTEST_MAIN(TestOverlayBounds)
#include "tst_overlay_bounds.moc"
