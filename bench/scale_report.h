// The scale table's outputs: JSON, markdown (docs/PERFORMANCE.md ## Scale) and a PNG plot.
#pragma once

#include "bench/scale_bench.h"

#include <QJsonObject>
#include <QString>
#include <QStringList>

namespace kw::bench {

/// Every number of the table ("scale" in the bench JSON; keys in docs/PERFORMANCE.md).
QJsonObject scaleJson(const ScaleReport& report);

/// The table as markdown, with the targets computed from its rows.
QString scaleMarkdown(const ScaleReport& report);

/// Writes scale.png into `dir` (frame, render-call and drag CPU ms; load, first frame and
/// resident memory, against faces) and appends its path to `written`; the error when it
/// cannot be written.
Status writeScalePlot(const ScaleReport& report, const QString& dir, QStringList& written);

} // namespace kw::bench
