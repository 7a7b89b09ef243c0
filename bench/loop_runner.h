// The shell the per-file bench loops share (--edit-loop, --zoom-loop, --drag-step): one
// off-screen renderer, the machine it runs on, each file in turn until the first failure, and
// the head and rows of their markdown tables.
#pragma once

#include "model/error.h"

#include <QString>
#include <QStringList>
#include <functional>

namespace kw {
class OffscreenRenderer;
}

namespace kw::bench {

/// What a loop's table names as its machine.
struct LoopMachine {
    QString gl, cpu;
    int threads = 0;
};

/// Makes the off-screen renderer (needs a QGuiApplication whose default format is
/// OffscreenRenderer::requiredFormat()), records the machine, then runs `perFile` on each file
/// in order. The first failure ends the run and is returned.
Status runPerFile(const QStringList& files, LoopMachine& machine,
                  const std::function<Status(OffscreenRenderer&, const QString& file)>& perFile);

/// A loop table's head: "### title", the command, the machine, then the column header and rule.
QString loopTableHead(const QString& title, const QString& command, const LoopMachine& machine,
                      const QStringList& columns);
/// One markdown table row.
QString markdownRow(const QStringList& cells);
/// a / b, or 0 when b is not positive: the Knotwork-to-peer ratios of the rows.
double ratioOf(double a, double b);

} // namespace kw::bench
