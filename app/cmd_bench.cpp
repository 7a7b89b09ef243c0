// knotwork bench [FILES...]: off-screen frame rates per file and image size (paper Table 1).
#include "app/commands.h"
#include "app/render_args.h"
#include "render/offscreen_renderer.h"

#include <QCommandLineParser>
#include <QElapsedTimer>
#include <QFile>
#include <QFileInfo>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QThread>
#include <algorithm>
#include <sys/resource.h>

namespace kw::cli {

namespace {

struct BenchRow {
    QString file;
    int surfaces = 0;
    QSize size;
    double coverage = 0.0; ///< fraction of pixels showing a surface
    double medianMs = 0.0, minMs = 0.0, maxMs = 0.0;
    double cpuMs = 0.0; ///< process CPU time per timed frame (independent of other load)
    /// --trim-drag: median frame time while one trim point moves every frame (-1: not run),
    /// and the CPU time per mask redraw (flattening + issuing the draws).
    double dragMs = -1.0, maskCpuMs = 0.0;
    int maskSide = 0; ///< larger side of the dragged surface's mask
};

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

/// A trim control point of the first trimmed surface to drag (an interior point of its first
/// curve when it has one, so the loop stays closed), or an invalid ref without trims.
TrimPointRef dragTarget(const Scene& scene) {
    for (const Surface& s : scene.surfaces)
        if (!s.trims.empty() && !s.trims.front().curves.empty()) {
            const NurbsCurve2& c = s.trims.front().curves.front();
            return {s.id, s.trims.front().id, 0, c.points.size() > 2 ? 1 : 0};
        }
    return {};
}

double fps(double ms) {
    return ms > 0.0 ? 1000.0 / ms : 0.0;
}

/// CPU time of the whole process (all threads: llvmpipe rasterises on its own threads), ms.
double processCpuMs() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return (double(u.ru_utime.tv_sec) + double(u.ru_stime.tv_sec)) * 1e3 +
           (double(u.ru_utime.tv_usec) + double(u.ru_stime.tv_usec)) * 1e-3;
}

} // namespace

int runBench(const QStringList& args) {
    QCommandLineParser parser;
    parser.setApplicationDescription(QStringLiteral(
        "Measure frames per second of the off-screen renderer: for each FILE and size, the "
        "median, fastest and slowest of N frames after 3 warm-up frames, each frame ended by "
        "glFinish. Progress on stderr; a markdown table on stdout. Needs OpenGL 4.5 core (see "
        "knotwork render --help)."));
    const QCommandLineOption sizes(QStringLiteral("sizes"),
                                   QStringLiteral("Square sizes (default 256,512,768,1024)."),
                                   QStringLiteral("LIST"), QStringLiteral("256,512,768,1024"));
    const QCommandLineOption frames(QStringLiteral("frames"),
                                    QStringLiteral("Timed frames per size, >= 20 (default 30)."),
                                    QStringLiteral("N"), QStringLiteral("30"));
    const QCommandLineOption json(QStringLiteral("json"),
                                  QStringLiteral("Also write the results as JSON."),
                                  QStringLiteral("OUT"));
    const QCommandLineOption trimDrag(
        QStringLiteral("trim-drag"),
        QStringLiteral("Also time frames that each move one trim control point of the first "
                       "trimmed surface (its mask is redrawn every frame): what a trim drag "
                       "costs per frame."));
    parser.addOptions({sizes, frames, json, trimDrag});
    const RenderCliOptions shared = addRenderOptions(parser, QStringLiteral("30"));
    parser.addPositionalArgument(QStringLiteral("FILES"), QStringLiteral(".knot projects."),
                                 QStringLiteral("FILE..."));
    if (const int code = parseOrExit(parser, args); code >= 0)
        return code;
    const QString cmd = args.value(0);
    const QStringList files = parser.positionalArguments();
    if (files.isEmpty()) {
        printError(QStringLiteral("%1: expected at least one FILE (see --help)").arg(cmd));
        return kExitUsage;
    }
    RenderOptions options;
    int frameCount = 0;
    std::vector<int> sideList;
    for (const QString& s : parser.value(sizes).split(QLatin1Char(','))) {
        int side = 0;
        if (!parseIntIn(s, 1, 16384, side)) {
            printError(QStringLiteral("%1: --sizes '%2' is not a list of sizes in 1..16384")
                           .arg(cmd, parser.value(sizes)));
            return kExitUsage;
        }
        sideList.push_back(side);
    }
    if (!parseIntIn(parser.value(frames), 20, 100000, frameCount)) {
        printError(QStringLiteral("%1: --frames '%2' is not in 20..100000")
                       .arg(cmd, parser.value(frames)));
        return kExitUsage;
    }
    if (!readRenderOptions(parser, shared, cmd, options))
        return kExitUsage;

    QString error;
    OffscreenRenderer renderer;
    if (!renderer.create(&error)) {
        printError(QStringLiteral("%1: %2").arg(cmd, error));
        return kExitBadInput;
    }
    std::vector<BenchRow> rows;
    for (const QString& file : files) {
        Document doc;
        if (!loadDocument(file, doc))
            return kExitBadInput;
        const Scene& scene = doc.scene();
        for (int side : sideList) {
            BenchRow row;
            row.file = QFileInfo(file).fileName();
            row.surfaces = int(scene.surfaces.size());
            row.size = QSize(side, side);
            const Camera cam = scene.camera.authored ? scene.camera : fitCamera(scene, 1.0);
            // Coverage from one AOV frame, then the timed frames without AOV targets.
            if (!renderer.setSize(row.size, true, &error) ||
                !renderer.render(doc, cam, options, &error)) {
                printError(QStringLiteral("%1: %2").arg(file, error));
                return kExitBadInput;
            }
            const AovBuffer aov = renderer.aov();
            long covered = 0;
            for (int k = 0; k < aov.width * aov.height; ++k)
                covered += aov.data[size_t(k) * AovBuffer::kChannels] >= 0.0f ? 1 : 0;
            row.coverage = double(covered) / double(std::max(1, aov.width * aov.height));
            if (!renderer.setSize(row.size, false, &error)) {
                printError(QStringLiteral("%1: %2").arg(cmd, error));
                return kExitBadInput;
            }
            std::vector<double> ms;
            double cpuStart = 0.0;
            for (int f = 0; f < frameCount + 3; ++f) {
                if (f == 3)
                    cpuStart = processCpuMs();
                QElapsedTimer t;
                t.start();
                if (!renderer.render(doc, cam, options, &error)) {
                    printError(QStringLiteral("%1: %2").arg(file, error));
                    return kExitBadInput;
                }
                renderer.finish();
                if (f >= 3)
                    ms.push_back(double(t.nsecsElapsed()) * 1e-6);
            }
            row.cpuMs = (processCpuMs() - cpuStart) / frameCount;
            row.minMs = *std::min_element(ms.begin(), ms.end());
            row.maxMs = *std::max_element(ms.begin(), ms.end());
            row.medianMs = median(ms);
            const TrimPointRef target = dragTarget(scene);
            if (parser.isSet(trimDrag) && options.trims && target.surface.isValid()) {
                const Surface* s = doc.surface(target.surface);
                const glm::dvec2 home =
                    s->trims.front().curves.front().points[size_t(target.index)];
                const Interval du = surfaceDomainU(s->geometry);
                TrimMaskPass& masks = renderer.renderer().trimMasks();
                masks.resetStats();
                std::vector<double> drag;
                for (int f = 0; f < frameCount; ++f) {
                    // Small steps back and forth, as a drag sends them.
                    const double step = (f % 2 ? -1.0 : 1.0) * 1e-3 * (du.last - du.first);
                    doc.setTrimPoint(target, home + glm::dvec2(step, 0.5 * step));
                    QElapsedTimer t;
                    t.start();
                    if (!renderer.render(doc, cam, options, &error)) {
                        printError(QStringLiteral("%1: %2").arg(file, error));
                        return kExitBadInput;
                    }
                    renderer.finish();
                    drag.push_back(double(t.nsecsElapsed()) * 1e-6);
                }
                doc.setTrimPoint(target, home);
                const TrimMaskStats st = masks.stats(target.surface);
                row.dragMs = median(drag);
                row.maskCpuMs = st.redraws ? double(st.cpuNanoseconds) * 1e-6 / st.redraws : 0.0;
                if (const TrimMask* m = masks.find(target.surface))
                    row.maskSide = std::max(m->width, m->height);
            }
            printError(QStringLiteral("%1 %2x%2: %3 FPS (median of %4 frames)")
                           .arg(row.file)
                           .arg(side)
                           .arg(fps(row.medianMs), 0, 'f', 1)
                           .arg(frameCount));
            rows.push_back(row);
        }
    }

    const QString setting =
        QStringLiteral("%1, %2 x %3 partitions, %4 light(s), %5 shading%6")
            .arg(modeName(options.mode))
            .arg(options.partitionsU)
            .arg(options.partitionsV)
            .arg(options.lightCount)
            .arg(options.mode == RenderMode::Exact ? shadingName(options.shading)
                                                   : QStringLiteral("Gouraud"))
            .arg(options.trims ? QString() : QStringLiteral(", trims off"));
    QString table = QStringLiteral("%1 on %2, %3 CPU threads\n\n")
                        .arg(setting, renderer.renderer().glDescription())
                        .arg(QThread::idealThreadCount());
    table += QStringLiteral(
        "| file | surfaces | resolution | covered | FPS (median) | FPS min | "
        "FPS max | ms (median) | CPU ms/frame | trim drag ms/frame | mask redraw CPU ms | mask "
        "side |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    QJsonArray jsonRows;
    for (const BenchRow& r : rows) {
        const bool dragged = r.dragMs >= 0.0;
        table += QStringLiteral("| %1 | %2 | %3x%4 | %5 % | %6 | %7 | %8 | %9 | %10 | %11 | %12 | "
                                "%13 |\n")
                     .arg(r.file)
                     .arg(r.surfaces)
                     .arg(r.size.width())
                     .arg(r.size.height())
                     .arg(100.0 * r.coverage, 0, 'f', 1)
                     .arg(fps(r.medianMs), 0, 'f', 1)
                     .arg(fps(r.maxMs), 0, 'f', 1)
                     .arg(fps(r.minMs), 0, 'f', 1)
                     .arg(r.medianMs, 0, 'f', 2)
                     .arg(r.cpuMs, 0, 'f', 1)
                     .arg(dragged ? QString::number(r.dragMs, 'f', 2) : QStringLiteral("-"))
                     .arg(dragged ? QString::number(r.maskCpuMs, 'f', 2) : QStringLiteral("-"))
                     .arg(dragged ? QString::number(r.maskSide) : QStringLiteral("-"));
        QJsonObject row{{QStringLiteral("file"), r.file},
                        {QStringLiteral("surfaces"), r.surfaces},
                        {QStringLiteral("width"), r.size.width()},
                        {QStringLiteral("height"), r.size.height()},
                        {QStringLiteral("coverage"), r.coverage},
                        {QStringLiteral("fpsMedian"), fps(r.medianMs)},
                        {QStringLiteral("fpsMin"), fps(r.maxMs)},
                        {QStringLiteral("fpsMax"), fps(r.minMs)},
                        {QStringLiteral("msMedian"), r.medianMs},
                        {QStringLiteral("cpuMsPerFrame"), r.cpuMs}};
        if (dragged) {
            row.insert(QStringLiteral("trimDragMsMedian"), r.dragMs);
            row.insert(QStringLiteral("maskRedrawCpuMs"), r.maskCpuMs);
            row.insert(QStringLiteral("maskSide"), r.maskSide);
        }
        jsonRows.append(row);
    }
    printOut(table);
    if (parser.isSet(json)) {
        const QJsonObject root{{QStringLiteral("setting"), setting},
                               {QStringLiteral("gl"), renderer.renderer().glDescription()},
                               {QStringLiteral("threads"), QThread::idealThreadCount()},
                               {QStringLiteral("frames"), frameCount},
                               {QStringLiteral("rows"), jsonRows}};
        QFile f(parser.value(json));
        if (!f.open(QIODevice::WriteOnly | QIODevice::Truncate) ||
            f.write(QJsonDocument(root).toJson()) < 0) {
            printError(
                QStringLiteral("%1: could not write: %2").arg(f.fileName(), f.errorString()));
            return kExitBadInput;
        }
    }
    return kExitOk;
}

} // namespace kw::cli
