// The benchmark's outputs: JSON (every number), markdown tables and PNG plots drawn with QPainter.
#pragma once

#include "bench/bench_runner.h"

#include <QJsonObject>
#include <QString>
#include <QStringList>

namespace kw::bench {

/// Every measured number. Keys are listed in docs/PERFORMANCE.md and checked by tst_bench.
QJsonObject reportJson(const BenchReport& report, const QString& command);

/// The tables as GitHub markdown: machine, Table 1, Table 2 speed, Table 2 quality, and image
/// links to `plotFiles` (paths relative to the markdown file, may be empty).
QString reportMarkdown(const BenchReport& report, const QString& command,
                       const QStringList& plotFiles);

/// Writes the plots into `dir` (created if missing): table1-fps.png (FPS against resolution, one
/// line per model) and, per Table 2 model, table2-<model>-fps.png and table2-<model>-error.png
/// (FPS and normal / silhouette error against partitions, one line per method). Returns the
/// written paths in `written`, or the error when a file cannot be written.
Status writePlots(const BenchReport& report, const QString& dir, QStringList& written);

} // namespace kw::bench
