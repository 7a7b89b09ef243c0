// The per-file loops' shared shell (loop_runner.h).
#include "bench/loop_runner.h"

#include "bench/peer_model.h"
#include "render/offscreen_renderer.h"

#include <QThread>

namespace kw::bench {

Status runPerFile(const QStringList& files, LoopMachine& machine,
                  const std::function<Status(OffscreenRenderer&, const QString& file)>& perFile) {
    machine.cpu = cpuModel();
    machine.threads = QThread::idealThreadCount();
    OffscreenRenderer renderer;
    if (Status created = renderer.create(); !created)
        return created;
    machine.gl = renderer.renderer().glDescription();
    for (const QString& file : files)
        if (Status done = perFile(renderer, file); !done)
            return done;
    return ok();
}

QString loopTableHead(const QString& title, const QString& command, const LoopMachine& machine,
                      const QStringList& columns) {
    QString md = QStringLiteral("### %1\n\n`%2`\n\n%3, %4 (%5 threads)\n\n")
                     .arg(title, command, machine.gl, machine.cpu)
                     .arg(machine.threads);
    md += markdownRow(columns);
    md += QStringLiteral("|") + QStringLiteral("---|").repeated(columns.size()) + QLatin1Char('\n');
    return md;
}

QString markdownRow(const QStringList& cells) {
    return QStringLiteral("| ") + cells.join(QStringLiteral(" | ")) + QStringLiteral(" |\n");
}

double ratioOf(double a, double b) {
    return b > 0.0 ? a / b : 0.0;
}

} // namespace kw::bench
