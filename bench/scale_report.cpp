// JSON, markdown and the plot of the scale table (see bench/scale_report.h).
#include "bench/scale_report.h"

#include "bench/line_plot.h"
#include "render/analysis.h"
#include "render/image_save.h"

#include <QDir>
#include <QJsonArray>
#include <QPainter>
#include <cmath>

namespace kw::bench {

namespace {

/// How the polygons were cut, for the report: "uniform partitions, each surface's own", ...
QString partitioningLabel(const ScaleConfig& c) {
    const bool adaptive = c.partitioning == RenderOptions::Partitioning::Adaptive;
    const QString own = c.partitions > 0 ? QStringLiteral("%1 x %1").arg(c.partitions)
                                         : QStringLiteral("each surface's own");
    return adaptive ? QStringLiteral("adaptive partitions from %1").arg(own)
                    : QStringLiteral("uniform partitions, %1").arg(own);
}

/// The partitioning, then the shading when it is an analysis mode ("..., mean shading").
QString setupLabel(const ScaleConfig& c) {
    const AnalysisMode shading = c.base.analysis.mode;
    return shading == AnalysisMode::Phong
               ? partitioningLabel(c)
               : QStringLiteral("%1, %2 shading")
                     .arg(partitioningLabel(c), analysisModeName(shading));
}

QJsonObject viewJson(const ScaleView& v) {
    return QJsonObject{{QStringLiteral("fps"), v.timing.fps()},
                       {QStringLiteral("msMedian"), v.timing.medianMs},
                       {QStringLiteral("cpuMsPerFrame"), v.timing.cpuMs},
                       {QStringLiteral("renderCallMs"), v.renderCallMs}};
}

QString num(double v, int decimals = 1) {
    return QString::number(v, 'f', decimals);
}

/// The row whose face count is nearest to `faces` (rows non-empty).
const ScaleRow& nearest(const std::vector<ScaleRow>& rows, int faces) {
    const ScaleRow* best = &rows.front();
    for (const ScaleRow& r : rows)
        if (std::abs(r.faces - faces) < std::abs(best->faces - faces))
            best = &r;
    return *best;
}

} // namespace

QJsonObject scaleJson(const ScaleReport& report) {
    QJsonArray rows;
    for (const ScaleRow& r : report.rows)
        rows.append(QJsonObject{{QStringLiteral("copies"), r.copies},
                                {QStringLiteral("faces"), r.faces},
                                {QStringLiteral("loadSeconds"), r.loadSeconds},
                                {QStringLiteral("firstFrameSeconds"), r.firstFrameSeconds},
                                {QStringLiteral("residentMiB"), r.residentMiB},
                                {QStringLiteral("gpuBytes"), double(r.gpuBytes)},
                                {QStringLiteral("drawCalls"), r.drawCalls},
                                {QStringLiteral("fitted"), viewJson(r.fitted)},
                                {QStringLiteral("closeUp"), viewJson(r.closeUp)},
                                {QStringLiteral("dragStepMs"), r.dragStepMs},
                                {QStringLiteral("dragToDrawMs"), r.dragToDrawMs},
                                {QStringLiteral("warning"), r.warning}});
    const ScaleConfig& c = report.config;
    return QJsonObject{{QStringLiteral("model"), report.model},
                       {QStringLiteral("unitFaces"), report.unitFaces},
                       {QStringLiteral("unitTrimmed"), report.unitTrimmed},
                       {QStringLiteral("width"), c.side},
                       {QStringLiteral("height"), c.frameHeight()},
                       {QStringLiteral("frames"), c.frames},
                       {QStringLiteral("warmup"), c.warmup},
                       {QStringLiteral("dragSteps"), c.dragSteps},
                       {QStringLiteral("trims"), c.trims},
                       {QStringLiteral("partitioning"), partitioningLabel(c)},
                       {QStringLiteral("shading"), analysisModeName(c.base.analysis.mode)},
                       {QStringLiteral("rows"), rows}};
}

QString scaleMarkdown(const ScaleReport& report) {
    const ScaleConfig& c = report.config;
    QString md = QStringLiteral(
                     "### Scale: %1 (%2 faces, %3 trimmed) tiled N times, %4 × %6, %5\n\n"
                     "| copies | faces | load (s) | first frame (s) | resident (MiB) | GPU (MiB) | "
                     "draw calls | fitted FPS | fitted CPU ms/frame | fitted render call (ms) | "
                     "close-up FPS | close-up CPU ms/frame | close-up render call (ms) | drag "
                     "step (ms) | drag: edit to draw call (ms) |\n"
                     "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n")
                     .arg(report.model)
                     .arg(report.unitFaces)
                     .arg(report.unitTrimmed)
                     .arg(c.side)
                     .arg(setupLabel(c))
                     .arg(c.frameHeight());
    for (const ScaleRow& r : report.rows)
        md +=
            QStringLiteral("| %1 | %2 | %3 | %4 | %5 | %6 | %7 | %8 | %9 | %10 | %11 | %12 | "
                           "%13 | %14 | %15 |\n")
                .arg(r.copies)
                .arg(r.faces)
                .arg(num(r.loadSeconds, 2), num(r.firstFrameSeconds, 2), num(r.residentMiB, 0),
                     num(double(r.gpuBytes) / (1 << 20), 1), QString::number(r.drawCalls),
                     num(r.fitted.timing.fps()), num(r.fitted.timing.cpuMs),
                     num(r.fitted.renderCallMs, 2))
                .arg(num(r.closeUp.timing.fps()), num(r.closeUp.timing.cpuMs),
                     num(r.closeUp.renderCallMs, 2), num(r.dragStepMs, 2), num(r.dragToDrawMs, 2));
    for (const ScaleRow& r : report.rows)
        if (!r.warning.isEmpty())
            md += QStringLiteral("\n%1 faces: drawn with a warning: %2\n")
                      .arg(r.faces)
                      .arg(r.warning);
    if (report.rows.size() >= 2) {
        // The targets, read off the rows (100 faces: the row nearest to it).
        const ScaleRow& small = nearest(report.rows, 100);
        const ScaleRow& big = report.rows.back();
        const auto ratio = [](double a, double b) {
            return b > 0.0 ? a / b : 0.0;
        };
        md += QStringLiteral(
                  "\nTargets, %1 faces against %2: fitted CPU ms/frame %3× (target ≤ 20×), "
                  "render call %4×; draw calls %5 against %6 (target: equal); drag: edit to "
                  "draw call %7 ms against %8 ms (target ≤ 2 ms, as at 100), whole drag step "
                  "%9 ms; load %10 s (target < 10 s) with %11 MiB resident (target < 2048).\n")
                  .arg(big.faces)
                  .arg(small.faces)
                  .arg(num(ratio(big.fitted.timing.cpuMs, small.fitted.timing.cpuMs), 2),
                       num(ratio(big.fitted.renderCallMs, small.fitted.renderCallMs), 2),
                       QString::number(big.drawCalls), QString::number(small.drawCalls),
                       num(big.dragToDrawMs, 2), num(small.dragToDrawMs, 2), num(big.dragStepMs, 2))
                  .arg(num(big.loadSeconds, 2), num(big.residentMiB, 0));
    }
    md += QStringLiteral("\nCPU ms/frame: process CPU time (all threads: llvmpipe rasterises on "
                         "its own) per timed frame; render call: the calling thread's CPU "
                         "time inside OffscreenRenderer::render (median); drag step: thread "
                         "CPU from Document::setControlPoints to the end of that call; drag: "
                         "edit to draw call: the same steps' thread CPU up to the frame's first "
                         "surface draw call (the edit plus FrameTimes::beforeDraws).\n\n");
    return md;
}

Status writeScalePlot(const ScaleReport& report, const QString& dir, QStringList& written) {
    if (report.rows.empty())
        return ok();
    std::vector<double> faces;
    Series fitted{QStringLiteral("fitted CPU ms/frame"), QColor(31, 119, 180), {}},
        close{QStringLiteral("close-up CPU ms/frame"), QColor(214, 39, 40), {}},
        call{QStringLiteral("fitted render call ms"), QColor(44, 160, 44), {}},
        drag{QStringLiteral("drag step ms"), QColor(255, 127, 14), {}},
        toDraw{QStringLiteral("drag: edit to draw call ms"), QColor(140, 86, 75), {}},
        load{QStringLiteral("load s"), QColor(31, 119, 180), {}},
        first{QStringLiteral("first frame s"), QColor(214, 39, 40), {}},
        rss{QStringLiteral("resident GiB"), QColor(148, 103, 189), {}};
    for (const ScaleRow& r : report.rows) {
        faces.push_back(r.faces);
        fitted.y.push_back(r.fitted.timing.cpuMs);
        close.y.push_back(r.closeUp.timing.cpuMs);
        call.y.push_back(r.fitted.renderCallMs);
        drag.y.push_back(r.dragStepMs);
        toDraw.y.push_back(r.dragToDrawMs);
        load.y.push_back(r.loadSeconds);
        first.y.push_back(r.firstFrameSeconds);
        rss.y.push_back(r.residentMiB / 1024.0);
    }
    const QString title = QStringLiteral("Scale: %1 tiled, %2x%3")
                              .arg(report.model)
                              .arg(report.config.side)
                              .arg(report.config.frameHeight());
    const QImage top = linePlot(title, QStringLiteral("faces"), QStringLiteral("CPU ms"), faces,
                                {fitted, close, call, drag, toDraw}, true);
    const QImage bottom =
        linePlot(QStringLiteral("load, first frame and memory"), QStringLiteral("faces"),
                 QStringLiteral("s / GiB"), faces, {load, first, rss}, true);
    QImage img(std::max(top.width(), bottom.width()), top.height() + bottom.height(),
               QImage::Format_RGB32);
    img.fill(Qt::white);
    {
        QPainter p(&img);
        p.drawImage(0, 0, top);
        p.drawImage(0, top.height(), bottom);
    }
    if (!QDir().mkpath(dir))
        return Error(QStringLiteral("could not create the folder %1").arg(dir), dir);
    const QString path = QDir(dir).filePath(QStringLiteral("scale.png"));
    if (Status saved = saveImageAtomically(img, path); !saved)
        return saved;
    written << path;
    return ok();
}

} // namespace kw::bench
