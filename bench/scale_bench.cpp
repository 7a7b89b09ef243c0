// knotwork bench --tables scale: one part tiled in a grid, from 1 copy to >= 10,000 faces; load,
// memory, frame cost in a fitted view and a close-up, and the cost of one drag step.
#include "bench/scale_bench.h"

#include "app/commands.h"
#include "bench/peer_model.h"
#include "bench/scale_scene.h"
#include "model/cad/cadimport.h"
#include "model/document/document.h"
#include "model/io/knotfile.h"
#include "render/offscreen_renderer.h"
#include "render/thread_clock.h"

#include <QElapsedTimer>
#include <QFile>
#include <QFileInfo>
#include <QTemporaryDir>
#include <algorithm>
#include <ctime>
#include <sys/resource.h>

namespace kw::bench {

namespace {

/// The part as a Scene, read as `knotwork render` reads it (kw::openModelFile: a .knot as saved,
/// IGES, STEP and BREP in the CAD reader's child process, OBJ), its import remarks on stderr.
Expected<Scene> loadUnit(const QString& model) {
    if (!QFileInfo(model).isFile())
        return Error(QStringLiteral("no such file: %1").arg(model), model);
    Expected<ImportResult> read = openModelFile(model);
    if (!read)
        return read.error();
    cli::printImportRemarks(model, read->report);
    return std::move(read->scene);
}

struct Frames {
    OffscreenRenderer& renderer;
    const ScaleConfig& config;
    RenderOptions options;
    /// The first "drawn, but not as asked" message of the row (e.g. more trimmed surfaces than
    /// the GPU has mask layers: the rest are drawn untrimmed); the row is still measured.
    QString warning;

    /// One render call. A frame that was drawn with a warning (FrameReport: ok false, draws
    /// issued) counts as drawn and keeps its message in `warning`.
    Status render(const Document& doc, const Camera& camera) {
        Status drawn = renderer.render(doc, camera, options);
        if (drawn || renderer.lastReport().drawCalls == 0)
            return drawn;
        if (warning.isEmpty())
            warning = drawn.message();
        return ok();
    }

    Status draw(const Document& doc, const Camera& camera, double* callMs) {
        const double t0 = threadCpuMs();
        Status drawn = render(doc, camera);
        if (callMs)
            *callMs = threadCpuMs() - t0;
        return drawn;
    }

    /// Warm-up frames, then config.frames timed frames, each ended by glFinish.
    Status time(const Document& doc, const Camera& camera, ScaleView& view) {
        std::vector<double> wall, call;
        double cpuStart = 0.0;
        for (int f = 0; f < config.warmup + config.frames; ++f) {
            if (f == config.warmup)
                cpuStart = processCpuMs();
            QElapsedTimer timer;
            timer.start();
            double callMs = 0.0;
            if (Status drawn = draw(doc, camera, &callMs); !drawn)
                return drawn;
            renderer.finish();
            if (f >= config.warmup) {
                wall.push_back(double(timer.nsecsElapsed()) * 1e-6);
                call.push_back(callMs);
            }
        }
        view.timing.cpuMs = (processCpuMs() - cpuStart) / std::max(1, config.frames);
        view.timing.medianMs = median(wall);
        view.timing.minMs = *std::min_element(wall.begin(), wall.end());
        view.timing.maxMs = *std::max_element(wall.begin(), wall.end());
        view.renderCallMs = median(call);
        return ok();
    }

    /// Moves one control point of the first surface per step, as a drag does, and times the
    /// edit plus the render call that issues the frame (thread CPU; glFinish outside), and the
    /// edit plus the render call's part before its first surface draw call
    /// (FrameTimes::beforeDraws): the "mouse-move to draw call".
    Status drag(Document& doc, const Camera& camera, double& stepMs, double& toDrawMs) {
        const Surface& s = doc.scene().surfaces.front();
        const int index = s.geometry.index(s.geometry.countU / 2, s.geometry.countV / 2);
        const glm::dvec3 start = s.geometry.points[size_t(index)];
        glm::dvec3 lo, hi;
        sceneBounds(doc.scene(), lo, hi);
        const double step = 1e-4 * glm::length(hi - lo);
        std::vector<double> ms, toDraw;
        for (int k = 0; k <= config.dragSteps; ++k) {
            const double t0 = threadCpuMs();
            if (const Status moved =
                    doc.setControlPoints(s.id, {index}, {start + glm::dvec3(0.0, 0.0, step * k)});
                !moved)
                return Error(QStringLiteral("the drag step could not move the control point: %1")
                                 .arg(moved.message()));
            const double edited = threadCpuMs();
            if (Status drawn = render(doc, camera); !drawn)
                return drawn;
            const double t1 = threadCpuMs();
            renderer.finish();
            if (k > 0) { // the first step pays for the first partial upload path
                ms.push_back(t1 - t0);
                toDraw.push_back(edited - t0 + renderer.lastReport().cpuMs.beforeDraws);
            }
        }
        if (const Status home = doc.setControlPoints(s.id, {index}, {start}); !home)
            return home;
        stepMs = median(ms);
        toDrawMs = median(toDraw);
        return ok();
    }
};

} // namespace

Status runScale(const ScaleConfig& config, ScaleReport& report,
                const std::function<void(const QString&)>& progress) {
    QTemporaryDir tmp;
    if (!tmp.isValid())
        return Error(QStringLiteral("cannot create a temporary folder: %1").arg(tmp.errorString()));
    const Expected<Scene> unit = loadUnit(config.model);
    if (!unit)
        return unit.error();
    if (unit->surfaces.empty())
        return Error(QStringLiteral("%1: the model has no surfaces to tile").arg(config.model),
                     config.model);
    report.model = QFileInfo(config.model).fileName();
    report.unitFaces = int(unit->surfaces.size());
    report.unitTrimmed = int(std::count_if(unit->surfaces.begin(), unit->surfaces.end(),
                                           [](const Surface& s) { return !s.trims.empty(); }));
    report.config = config;

    OffscreenRenderer renderer;
    if (Status created = renderer.create(); !created)
        return created;
    if (Status sized = renderer.setSize(QSize(config.side, config.frameHeight()), false); !sized)
        return sized;
    Frames frames{renderer, config, config.base, QString()};
    frames.options.trims = config.trims;
    frames.options.polygonOverTrims = config.trims;
    frames.options.partitioning = config.partitioning;
    frames.options.partitionsU = frames.options.partitionsV = config.partitions;
    const Camera closeUp = closeUpCamera(*unit, 1.0);

    for (int faces : config.faces) {
        ScaleRow row;
        row.copies = copiesForFaces(report.unitFaces, faces);
        const QString file = tmp.filePath(QStringLiteral("tiled-%1.knot").arg(row.copies));
        if (const Status written = writeKnotFile(file, tileScene(*unit, row.copies)); !written)
            return written;
        Document doc;
        frames.warning.clear();
        {
            QElapsedTimer load;
            load.start();
            Expected<Scene> scene = readKnotFile(file);
            const Status reset = scene ? doc.resetScene(std::move(*scene)) : Status(scene.error());
            if (!reset)
                return reset;
            row.loadSeconds = double(load.nsecsElapsed()) * 1e-9;
        }
        QFile::remove(file);
        row.faces = int(doc.scene().surfaces.size());
        const Camera fitted =
            fitCamera(doc.scene(), double(config.side) / double(config.frameHeight()));
        QElapsedTimer first;
        first.start();
        if (Status drawn = frames.draw(doc, fitted, nullptr); !drawn)
            return drawn;
        renderer.finish();
        row.firstFrameSeconds = double(first.nsecsElapsed()) * 1e-9;
        row.residentMiB = residentMiB();
        row.gpuBytes = renderer.lastReport().gpuBytes.total();
        if (Status timed = frames.time(doc, fitted, row.fitted); !timed)
            return timed;
        row.drawCalls = renderer.lastReport().drawCalls; // a steady fitted frame's
        if (Status timed = frames.time(doc, closeUp, row.closeUp); !timed)
            return timed;
        if (Status dragged = frames.drag(doc, fitted, row.dragStepMs, row.dragToDrawMs); !dragged)
            return dragged;
        progress(QStringLiteral("scale %1 x %2 = %3 faces: load %4 s, %5 MiB, fitted %6 FPS "
                                "(%7 CPU ms, %8 draw calls), close-up %9 FPS, drag step %10 ms "
                                "(edit to draw call %11 ms)")
                     .arg(row.copies)
                     .arg(report.unitFaces)
                     .arg(row.faces)
                     .arg(row.loadSeconds, 0, 'f', 2)
                     .arg(row.residentMiB, 0, 'f', 0)
                     .arg(row.fitted.timing.fps(), 0, 'f', 1)
                     .arg(row.fitted.timing.cpuMs, 0, 'f', 1)
                     .arg(row.drawCalls)
                     .arg(row.closeUp.timing.fps(), 0, 'f', 1)
                     .arg(row.dragStepMs, 0, 'f', 2)
                     .arg(row.dragToDrawMs, 0, 'f', 2));
        row.warning = frames.warning;
        if (!row.warning.isEmpty())
            progress(QStringLiteral("scale %1 faces: warning: %2").arg(row.faces).arg(row.warning));
        report.rows.push_back(row);
    }
    renderer.makeCurrent();
    return ok();
}

} // namespace kw::bench
