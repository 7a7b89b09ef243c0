// PNG line plots of a BenchReport, drawn with QPainter into a QImage (no Python needed).
#include "bench/bench_report.h"
#include "bench/line_plot.h"
#include "render/image_save.h"

#include <QDir>
#include <QImage>
#include <QPainter>
#include <QPainterPath>
#include <algorithm>
#include <cmath>

namespace kw::bench {

namespace {

const QColor kColors[] = {QColor(31, 119, 180),  QColor(214, 39, 40),   QColor(44, 160, 44),
                          QColor(255, 127, 14),  QColor(148, 103, 189), QColor(140, 86, 75),
                          QColor(227, 119, 194), QColor(127, 127, 127)};

} // namespace

QImage linePlot(const QString& title, const QString& xLabel, const QString& yLabel,
                const std::vector<double>& x, const std::vector<Series>& series, bool logY) {
    QImage img(1100, 540, QImage::Format_RGB32);
    img.fill(Qt::white);
    QPainter p(&img);
    p.setRenderHint(QPainter::Antialiasing);
    const QRectF plot(90, 50, 600, 420);
    auto tr = [&](double v) {
        return logY ? std::log10(std::max(v, 1e-12)) : v;
    };
    double lo = 1e300, hi = -1e300;
    for (const Series& s : series)
        for (double v : s.y)
            if (std::isfinite(v) && (!logY || v > 0.0)) {
                lo = std::min(lo, tr(v));
                hi = std::max(hi, tr(v));
            }
    if (lo > hi)
        lo = 0.0, hi = 1.0;
    if (logY) {
        lo = std::floor(lo);
        hi = std::ceil(hi);
    } else {
        lo = std::min(lo, 0.0);
    }
    if (hi - lo < 1e-12)
        hi = lo + 1.0;
    // Linear axis: a 1-2-5 step giving about five ticks, the top rounded up to a step.
    double step = 1.0;
    if (!logY) {
        const double raw = (hi - lo) / 5.0, mag = std::pow(10.0, std::floor(std::log10(raw)));
        step = raw <= mag         ? mag
               : raw <= 2.0 * mag ? 2.0 * mag
               : raw <= 5.0 * mag ? 5.0 * mag
                                  : 10.0 * mag;
        hi = lo + std::ceil((hi - lo) / step - 1e-9) * step;
    }
    auto px = [&](size_t i) {
        return x.size() < 2 ? plot.center().x()
                            : plot.left() + plot.width() * double(i) / double(x.size() - 1);
    };
    auto py = [&](double v) {
        return plot.bottom() - plot.height() * (tr(v) - lo) / (hi - lo);
    };

    QFont font = p.font();
    font.setPixelSize(14);
    p.setFont(font);
    p.setPen(QColor(60, 60, 60));
    p.drawText(QRectF(0, 8, img.width(), 30), Qt::AlignCenter, title);
    p.drawText(QRectF(plot.left(), plot.bottom() + 30, plot.width(), 24), Qt::AlignCenter, xLabel);
    p.save();
    p.translate(18, plot.center().y());
    p.rotate(-90);
    p.drawText(QRectF(-plot.height() / 2, -12, plot.height(), 24), Qt::AlignCenter, yLabel);
    p.restore();
    // Grid and tick labels.
    const int ticks = logY ? int(hi - lo) : int(std::lround((hi - lo) / step));
    for (int k = 0; k <= ticks; ++k) {
        const double t = lo + (hi - lo) * k / ticks;
        const double y = plot.bottom() - plot.height() * k / ticks;
        p.setPen(QColor(225, 225, 225));
        p.drawLine(QPointF(plot.left(), y), QPointF(plot.right(), y));
        p.setPen(QColor(60, 60, 60));
        const QString label =
            logY ? QString::number(std::pow(10.0, t), 'g', 3) : QString::number(t, 'g', 4);
        p.drawText(QRectF(0, y - 10, plot.left() - 6, 20), Qt::AlignRight | Qt::AlignVCenter,
                   label);
    }
    for (size_t i = 0; i < x.size(); ++i)
        p.drawText(QRectF(px(i) - 40, plot.bottom() + 4, 80, 20), Qt::AlignCenter,
                   QString::number(x[i], 'g', 5));
    p.setPen(QPen(QColor(60, 60, 60), 1.0));
    p.drawRect(plot);
    // Lines with point markers, and the legend on the right.
    for (size_t s = 0; s < series.size(); ++s) {
        const Series& se = series[s];
        QPen pen(se.color, 2.0, se.style);
        p.setPen(pen);
        QPainterPath path;
        bool open = false;
        for (size_t i = 0; i < se.y.size() && i < x.size(); ++i) {
            if (!std::isfinite(se.y[i]) || (logY && se.y[i] <= 0.0)) {
                open = false;
                continue;
            }
            const QPointF pt(px(i), py(se.y[i]));
            open ? path.lineTo(pt) : path.moveTo(pt);
            open = true;
            p.setBrush(se.color);
            p.drawEllipse(pt, 3.0, 3.0);
            p.setBrush(Qt::NoBrush);
        }
        p.drawPath(path);
        const double ly = plot.top() + 10 + 24.0 * double(s);
        p.drawLine(QPointF(plot.right() + 15, ly), QPointF(plot.right() + 45, ly));
        p.setPen(QColor(40, 40, 40));
        p.drawText(QRectF(plot.right() + 50, ly - 10, img.width() - plot.right() - 52, 20),
                   Qt::AlignLeft | Qt::AlignVCenter, se.name);
    }
    return img;
}

namespace {

/// Two plots one above the other.
QImage stacked(const QImage& top, const QImage& bottom) {
    QImage img(std::max(top.width(), bottom.width()), top.height() + bottom.height(),
               QImage::Format_RGB32);
    img.fill(Qt::white);
    QPainter p(&img);
    p.drawImage(0, 0, top);
    p.drawImage(0, top.height(), bottom);
    return img;
}

Status save(const QImage& img, const QString& dir, const QString& name, QStringList& written) {
    const QString path = QDir(dir).filePath(name);
    if (Status saved = saveImageAtomically(img, path); !saved)
        return saved;
    written << path;
    return ok();
}

/// A file-name-safe form of a model name (teapot.knot -> teapot).
QString stem(const QString& model) {
    QString s = model.section(QLatin1Char('.'), 0, 0);
    for (QChar& c : s)
        if (!c.isLetterOrNumber() && c != QLatin1Char('-') && c != QLatin1Char('_'))
            c = QLatin1Char('_');
    return s.isEmpty() ? QStringLiteral("model") : s;
}

} // namespace

Status writePlots(const BenchReport& report, const QString& dir, QStringList& written) {
    written.clear();
    if (!QDir().mkpath(dir))
        return Error(QStringLiteral("could not create the folder %1").arg(dir), dir);
    if (!report.table1.empty()) {
        std::vector<double> sizes(report.config.sizes.begin(), report.config.sizes.end());
        std::vector<Series> series;
        for (const Table1Row& r : report.table1) {
            auto it = std::find_if(series.begin(), series.end(),
                                   [&](const Series& s) { return s.name == r.model; });
            if (it == series.end()) {
                series.push_back(Series{r.model, kColors[series.size() % 8],
                                        std::vector<double>(sizes.size(), NAN)});
                it = series.end() - 1;
            }
            const auto k = std::find(sizes.begin(), sizes.end(), double(r.side)) - sizes.begin();
            if (size_t(k) < sizes.size())
                it->y[size_t(k)] = r.timing.fps();
        }
        const QString title = QStringLiteral("Table 1: exact mode, %1x%1 partitions, %2 lights")
                                  .arg(report.config.table1Partitions)
                                  .arg(report.config.lights);
        if (Status saved = save(linePlot(title, QStringLiteral("resolution (pixels per side)"),
                                         QStringLiteral("FPS (median)"), sizes, series, true),
                                dir, QStringLiteral("table1-fps.png"), written);
            !saved)
            return saved;
    }
    QStringList models;
    for (const Table2Row& r : report.table2)
        if (!models.contains(r.model))
            models << r.model;
    for (const QString& model : models) {
        std::vector<double> parts;
        std::vector<const Table2Row*> rows;
        for (const Table2Row& r : report.table2)
            if (r.model == model) {
                parts.push_back(r.partitions);
                rows.push_back(&r);
            }
        const MethodResult Table2Row::*methods[] = {&Table2Row::exact, &Table2Row::baseline,
                                                    &Table2Row::fine, &Table2Row::glu};
        const QString names[] = {QStringLiteral("exact"), QStringLiteral("baseline"),
                                 QStringLiteral("fine mesh"), QStringLiteral("GLU per frame")};
        std::vector<Series> fps, normals, silhouettes;
        for (int m = 0; m < 4; ++m) {
            Series f{names[m], kColors[m], {}}, en{names[m], kColors[m], {}},
                es{names[m], kColors[m], {}};
            for (const Table2Row* r : rows) {
                const MethodResult& mr = r->*methods[m];
                f.y.push_back(mr.timing.fps());
                en.y.push_back(mr.quality.normal.maxDegrees);
                es.y.push_back(mr.quality.silhouette.perSilhouettePixel);
            }
            fps.push_back(f);
            normals.push_back(en);
            silhouettes.push_back(es);
        }
        const QString size = QStringLiteral("%1x%2")
                                 .arg(report.config.table2Size.width())
                                 .arg(report.config.table2Size.height());
        if (Status saved = save(linePlot(QStringLiteral("Table 2: %1 at %2").arg(model, size),
                                         QStringLiteral("partitions (n x n)"),
                                         QStringLiteral("FPS (median)"), parts, fps, true),
                                dir, QStringLiteral("table2-%1-fps.png").arg(stem(model)), written);
            !saved)
            return saved;
        if (Status saved =
                save(stacked(linePlot(QStringLiteral("Table 2 quality: %1 at %2, max normal error")
                                          .arg(model, size),
                                      QStringLiteral("partitions (n x n)"),
                                      QStringLiteral("max normal error (degrees)"), parts, normals,
                                      true),
                             linePlot(QStringLiteral("silhouette error against exact mode at %1x%1 "
                                                     "partitions")
                                          .arg(report.config.referencePartitions),
                                      QStringLiteral("partitions (n x n)"),
                                      QStringLiteral("mismatched px per silhouette px"), parts,
                                      silhouettes, false)),
                     dir, QStringLiteral("table2-%1-error.png").arg(stem(model)), written);
            !saved)
            return saved;
    }
    return ok();
}

} // namespace kw::bench
