// The bench's PNG line plots, drawn with QPainter into a QImage (no Python needed).
#pragma once

#include <QColor>
#include <QImage>
#include <QString>
#include <vector>

namespace kw::bench {

struct Series {
    QString name;
    QColor color;
    std::vector<double> y; ///< one value per x; NaN leaves a gap
    Qt::PenStyle style = Qt::SolidLine;
};

/// A line plot with categorical x positions (labelled with `x`) and a linear or log10 y axis.
QImage linePlot(const QString& title, const QString& xLabel, const QString& yLabel,
                const std::vector<double>& x, const std::vector<Series>& series, bool logY);

} // namespace kw::bench
