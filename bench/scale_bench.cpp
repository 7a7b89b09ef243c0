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

/// A step's Status in the bench's QString* reporting: false with *error set on failure.
bool kept(const Status& step, QString* error) {
    if (!step && error)
        *error = step.message();
    return bool(step);
}

/// The part as a Scene, read as `knotwork render` reads it (kw::openModelFile: a .knot as saved,
/// IGES, STEP and BREP in the CAD reader's child process, OBJ), its import remarks on stderr.
std::optional<Scene> loadUnit(const QString& model, QString* error) {
    if (!QFileInfo(model).isFile()) {
        *error = QStringLiteral("no such file: %1").arg(model);
        return std::nullopt;
    }
    std::optional<ImportResult> read = openModelFile(model, *error);
    if (!read)
        return std::nullopt;
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
    bool render(const Document& doc, const Camera& camera, QString* error) {
        if (kept(renderer.render(doc, camera, options), error))
            return true;
        if (renderer.lastReport().drawCalls == 0)
            return false;
        if (warning.isEmpty())
            warning = *error;
        return true;
    }

    bool draw(const Document& doc, const Camera& camera, double* callMs, QString* error) {
        const double t0 = threadCpuMs();
        const bool ok = render(doc, camera, error);
        if (callMs)
            *callMs = threadCpuMs() - t0;
        return ok;
    }

    /// Warm-up frames, then config.frames timed frames, each ended by glFinish.
    bool time(const Document& doc, const Camera& camera, ScaleView& view, QString* error) {
        std::vector<double> wall, call;
        double cpuStart = 0.0;
        for (int f = 0; f < config.warmup + config.frames; ++f) {
            if (f == config.warmup)
                cpuStart = processCpuMs();
            QElapsedTimer timer;
            timer.start();
            double callMs = 0.0;
            if (!draw(doc, camera, &callMs, error))
                return false;
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
        return true;
    }

    /// Moves one control point of the first surface per step, as a drag does, and times the
    /// edit plus the render call that issues the frame (thread CPU; glFinish outside), and the
    /// edit plus the render call's part before its first surface draw call
    /// (FrameTimes::beforeDraws): the "mouse-move to draw call".
    bool drag(Document& doc, const Camera& camera, double& stepMs, double& toDrawMs,
              QString* error) {
        const Surface& s = doc.scene().surfaces.front();
        const int index = s.geometry.index(s.geometry.countU / 2, s.geometry.countV / 2);
        const glm::dvec3 start = s.geometry.points[size_t(index)];
        glm::dvec3 lo, hi;
        sceneBounds(doc.scene(), lo, hi);
        const double step = 1e-4 * glm::length(hi - lo);
        std::vector<double> ms, toDraw;
        for (int k = 0; k <= config.dragSteps; ++k) {
            const double t0 = threadCpuMs();
            if (!doc.setControlPoints(s.id, {index}, {start + glm::dvec3(0.0, 0.0, step * k)})) {
                *error = QStringLiteral("the drag step could not move the control point");
                return false;
            }
            const double edited = threadCpuMs();
            if (!render(doc, camera, error))
                return false;
            const double t1 = threadCpuMs();
            renderer.finish();
            if (k > 0) { // the first step pays for the first partial upload path
                ms.push_back(t1 - t0);
                toDraw.push_back(edited - t0 + renderer.lastReport().cpuMs.beforeDraws);
            }
        }
        doc.setControlPoints(s.id, {index}, {start});
        stepMs = median(ms);
        toDrawMs = median(toDraw);
        return true;
    }
};

} // namespace

bool runScale(const ScaleConfig& config, ScaleReport& report,
              const std::function<void(const QString&)>& progress, QString* error) {
    QTemporaryDir tmp;
    if (!tmp.isValid()) {
        *error = QStringLiteral("cannot create a temporary folder: %1").arg(tmp.errorString());
        return false;
    }
    const std::optional<Scene> unit = loadUnit(config.model, error);
    if (!unit)
        return false;
    if (unit->surfaces.empty()) {
        *error = QStringLiteral("%1: the model has no surfaces to tile").arg(config.model);
        return false;
    }
    report.model = QFileInfo(config.model).fileName();
    report.unitFaces = int(unit->surfaces.size());
    report.unitTrimmed = int(std::count_if(unit->surfaces.begin(), unit->surfaces.end(),
                                           [](const Surface& s) { return !s.trims.empty(); }));
    report.config = config;

    OffscreenRenderer renderer;
    if (!kept(renderer.create(), error) ||
        !kept(renderer.setSize(QSize(config.side, config.frameHeight()), false), error))
        return false;
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
        if (const Status written = writeKnotFile(file, tileScene(*unit, row.copies)); !written) {
            if (error)
                *error = written.message();
            return false;
        }
        Document doc;
        frames.warning.clear();
        {
            QElapsedTimer load;
            load.start();
            Expected<Scene> scene = readKnotFile(file);
            const Status reset = scene ? doc.resetScene(std::move(*scene)) : Status(scene.error());
            if (!reset) {
                if (error)
                    *error = reset.message();
                return false;
            }
            row.loadSeconds = double(load.nsecsElapsed()) * 1e-9;
        }
        QFile::remove(file);
        row.faces = int(doc.scene().surfaces.size());
        const Camera fitted =
            fitCamera(doc.scene(), double(config.side) / double(config.frameHeight()));
        QElapsedTimer first;
        first.start();
        if (!frames.draw(doc, fitted, nullptr, error))
            return false;
        renderer.finish();
        row.firstFrameSeconds = double(first.nsecsElapsed()) * 1e-9;
        row.residentMiB = residentMiB();
        row.gpuBytes = renderer.lastReport().gpuBytes.total();
        if (!frames.time(doc, fitted, row.fitted, error))
            return false;
        row.drawCalls = renderer.lastReport().drawCalls; // a steady fitted frame's
        if (!frames.time(doc, closeUp, row.closeUp, error) ||
            !frames.drag(doc, fitted, row.dragStepMs, row.dragToDrawMs, error))
            return false;
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
    return true;
}

} // namespace kw::bench
