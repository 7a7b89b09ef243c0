// The drag step with the Edge Continuity overlay on against off (drag_step.h): the model (as
// read, or tiled with its shared-edge record), the dragged face, the alternated timed steps.
#include "bench/drag_step.h"

#include "app/commands.h"
#include "bench/loop_runner.h"
#include "bench/peer_model.h"
#include "bench/scale_scene.h"
#include "model/analysis/continuity.h"
#include "model/cad/cadimport.h"
#include "model/document/document.h"
#include "model/nurbs/nurbs.h"
#include "render/edge_bands.h"
#include "render/offscreen_renderer.h"
#include "render/thread_clock.h"

#include <QElapsedTimer>
#include <QFile>
#include <QFileInfo>
#include <QHash>
#include <QJsonObject>
#include <algorithm>
#include <cmath>
#include <ctime>

namespace kw::bench {

namespace {

/// tileScene(unit, copies) with unit's shared edges copied into every copy: a tiled part is
/// then what an imported assembly of that many faces is, edges from its record (tileScene
/// numbers each copy's surfaces and their loops in unit's order, so the k-th copy of unit's
/// i-th surface is out.surfaces[k * n + i], its loops in the same order).
Scene tileWithRecord(const Scene& unit, int copies) {
    Scene out = tileScene(unit, copies);
    out.unit = unit.unit;
    out.continuity = unit.continuity;
    const size_t n = unit.surfaces.size();
    if (unit.topology.edges.empty() || out.surfaces.size() != n * size_t(copies))
        return out;
    QHash<SurfaceId, size_t> surfaceIndex;
    QHash<TrimLoopId, size_t> loopIndex;
    for (size_t i = 0; i < n; ++i) {
        surfaceIndex.insert(unit.surfaces[i].id, i);
        for (size_t l = 0; l < unit.surfaces[i].trims.size(); ++l)
            loopIndex.insert(unit.surfaces[i].trims[l].id, l);
    }
    std::uint32_t nextEdge = 1;
    for (int k = 0; k < copies; ++k)
        for (const SharedEdge& e : unit.topology.edges) {
            SharedEdge c = e;
            c.id = EdgeId{nextEdge++};
            bool found = true;
            for (EdgeUse& use : c.sides) {
                const auto s = surfaceIndex.find(use.surface);
                const auto l = loopIndex.find(use.loop);
                found = found && s != surfaceIndex.end() && l != loopIndex.end();
                if (!found)
                    break;
                const Surface& copy = out.surfaces[size_t(k) * n + *s];
                use.surface = copy.id;
                use.loop = copy.trims[*l].id;
            }
            if (found)
                out.topology.edges.push_back(c);
        }
    return out;
}

// Greville abscissa of control point i: where it pulls the surface most.
double greville(const std::vector<double>& knots, int degree, int i) {
    double sum = 0.0;
    for (int k = 1; k <= degree; ++k)
        sum += knots[size_t(i + k)];
    return degree > 0 ? sum / degree : knots[size_t(i)];
}

/// The dragged point: the middle control point of the face with the most shared edges among
/// the first copy's faces (the close-up frames that copy), moved along the surface normal
/// there, out and back.
struct Drag {
    SurfaceId id;
    int index = 0;
    int edges = 0;
    glm::dvec3 home{0.0}, direction{0.0};
    double amplitude = 0.0;
    QString name;

    glm::dvec3 at(int e, int count) const {
        const double x = double(e + 1) / double(count);
        return home + direction * (amplitude * (1.0 - std::abs(1.0 - 2.0 * x)));
    }
};

Drag chooseDrag(const Scene& scene, const ContinuityTopology& topology, size_t firstCopyFaces) {
    Drag d;
    for (size_t k = 0; k < std::min(firstCopyFaces, scene.surfaces.size()); ++k) {
        const Surface& s = scene.surfaces[k];
        const int edges = int(edgesOfFace(topology, s.id).size());
        if (!d.id.isValid() || edges > d.edges) {
            d.id = s.id;
            d.edges = edges;
            d.name = QStringLiteral("%1 (id %2)").arg(s.name).arg(s.id.value);
        }
    }
    const NurbsSurface& g =
        std::find_if(scene.surfaces.begin(), scene.surfaces.end(), [&](const Surface& s) {
            return s.id == d.id;
        })->geometry;
    const int i = g.countU / 2, j = g.countV / 2;
    d.index = g.index(i, j);
    d.home = g.points[size_t(d.index)];
    const Interval du = surfaceDomainU(g), dv = surfaceDomainV(g);
    const double u = std::clamp(greville(g.knotsU, g.degreeU, i), du.first, du.last);
    const double v = std::clamp(greville(g.knotsV, g.degreeV, j), dv.first, dv.last);
    d.direction = surfaceFrame(g, u, v).normal;
    glm::dvec3 lo, hi;
    surfaceControlBounds(g, lo, hi);
    d.amplitude = 0.05 * glm::length(hi - lo); // visible, and it opens the face's seams
    return d;
}

/// One model: the document, the overlay's state and the alternated steps.
class ModelSteps {
public:
    ModelSteps(const DragStepConfig& c, OffscreenRenderer& r,
               const std::function<void(const QString&)>& p)
        : config(c), renderer(r), progress(p) {}

    Status run(const Scene& unit, const QString& name, int faces, DragStepRow& row);

private:
    Status step(bool overlay, const glm::dvec3& to, bool timed);

    const DragStepConfig& config;
    OffscreenRenderer& renderer;
    const std::function<void(const QString&)>& progress;
    Document doc;
    Camera camera;
    Drag drag;
    ContinuityReport full, watch; ///< the overlay's report (on), the status bar's (off)
    EdgeBandCache lines;
    QString opens;
    std::vector<double> ms[2], cpu[2], continuityMs[2], bandsMs;
    long long bandVertices = 0;
};

// One drag step as the editor takes it: the edit; on the document's change the overlay (on)
// re-measures the face's edges and re-makes their bands, or (off) the status bar's check
// re-measures the same edges; then the frame, with the bands uploaded when on.
Status ModelSteps::step(bool overlay, const glm::dvec3& to, bool timed) {
    QElapsedTimer wall;
    const double cpu0 = processCpuMs();
    wall.start();
    if (const Status moved = doc.setControlPoints(drag.id, {drag.index}, {to}); !moved)
        return Error(
            QStringLiteral("the drag's control point move was refused: %1").arg(moved.message()));
    const double t0 = threadCpuMs();
    ContinuityReport& report = overlay ? full : watch;
    updateContinuity(report, doc.scene(), {drag.id});
    opens = seamOpeningText(seamsOpenAt(report, {drag.id}), lengthUnitKey(doc.scene().unit));
    const double t1 = threadCpuMs();
    RenderOptions o = config.base;
    o.mode = RenderMode::Exact;
    o.partitioning = RenderOptions::Partitioning::Adaptive; // the editor's default
    o.lightCount = config.lights;
    o.samples = 1; // a drag's frame (the still frame's anti-aliasing waits for the release)
    o.progressive = false;
    if (overlay) {
        o.edgeBands = lines.update(doc.scene(), full, {drag.id});
        bandVertices = (long long)o.edgeBands->vertices.size();
    }
    const double t2 = threadCpuMs();
    if (Status drawn = renderer.render(doc, camera, o); !drawn)
        return drawn;
    renderer.finish();
    if (timed) {
        const int k = overlay ? 0 : 1;
        ms[k].push_back(double(wall.nsecsElapsed()) * 1e-6);
        cpu[k].push_back(processCpuMs() - cpu0);
        continuityMs[k].push_back(t1 - t0);
        if (overlay)
            bandsMs.push_back(t2 - t1);
    }
    return ok();
}

Status ModelSteps::run(const Scene& unit, const QString& name, int faces, DragStepRow& row) {
    const int copies = faces > 0 ? copiesForFaces(int(unit.surfaces.size()), faces) : 1;
    Scene scene = faces > 0 ? tileWithRecord(unit, copies) : unit;
    if (faces > 0)
        scene.camera = closeUpCamera(unit, 1.0);
    else if (!scene.camera.authored)
        scene.camera = fitCamera(scene, 1.0);
    camera = scene.camera;
    if (const Status reset = doc.resetScene(std::move(scene)); !reset)
        return Error(QStringLiteral("%1: %2").arg(name, reset.message()));
    row.model = faces > 0 ? QStringLiteral("%1 tiled x %2").arg(name).arg(copies) : name;
    row.surfaces = int(doc.scene().surfaces.size());
    row.copies = copies;
    const ContinuityTolerances& tolerances = continuityTolerances(doc.scene());
    // Turning the overlay on: every edge measured, every band made (the editor's rebuild).
    QElapsedTimer setup;
    setup.start();
    if (config.overlayOn) {
        full = continuityReport(doc.scene(), tolerances);
        lines.update(doc.scene(), full);
    }
    row.setupMs = double(setup.nsecsElapsed()) * 1e-6;
    // The status bar's check finds the pairs on a drag's first step, then measures per step.
    setup.restart();
    watch = continuityWatch(doc.scene(), tolerances);
    row.pairingMs = double(setup.nsecsElapsed()) * 1e-6;
    row.edges = int(watch.topology.edges.size());
    drag = chooseDrag(doc.scene(), watch.topology, unit.surfaces.size());
    row.face = drag.name;
    row.faceEdges = drag.edges;
    progress(QStringLiteral("%1: %2 faces, %3 shared edges (overlay on in %4 ms); dragging %5 "
                            "(%6 edges)")
                 .arg(row.model)
                 .arg(row.surfaces)
                 .arg(row.edges)
                 .arg(row.setupMs, 0, 'f', 0)
                 .arg(row.face)
                 .arg(row.faceEdges));
    // Warm-up, untimed: shaders, first uploads, the exact pass's variants at the drag's ends.
    const glm::dvec3 peak = drag.home + drag.direction * drag.amplitude;
    for (const bool overlay : {true, false})
        if (overlay ? config.overlayOn : config.overlayOff) {
            if (Status warm = step(overlay, peak, false); !warm)
                return warm;
            if (Status warm = step(overlay, drag.home, false); !warm)
                return warm;
        }
    // On and off alternate step by step, each at its own point of one drag path.
    const int states = int(config.overlayOn) + int(config.overlayOff);
    const int events = states * config.steps;
    int e = 0;
    for (int k = 0; k < config.steps; ++k)
        for (const bool overlay : {true, false})
            if (overlay ? config.overlayOn : config.overlayOff)
                if (Status timed = step(overlay, drag.at(e++, events), true); !timed)
                    return timed;
    // The status bar's text at the farthest point, then the face put back.
    if (Status last = step(config.overlayOn, peak, false); !last)
        return last;
    row.opens = opens;
    if (const Status home = doc.setControlPoints(drag.id, {drag.index}, {drag.home}); !home)
        return Error(QStringLiteral("%1: the drag's control point could not be put back: %2")
                         .arg(name, home.message()));
    for (int k = 0; k < 2; ++k) {
        DragStepTiming& t = k == 0 ? row.on : row.off;
        t.measured = !ms[k].empty();
        t.ms = median(ms[k]);
        t.cpuMs = median(cpu[k]);
        t.continuityMs = median(continuityMs[k]);
    }
    row.on.bandsMs = median(bandsMs);
    row.on.bandVertices = config.overlayOn ? bandVertices : 0;
    progress(QStringLiteral("%1: drag step overlay on %2 ms (CPU %3), off %4 ms (CPU %5); %6")
                 .arg(row.model)
                 .arg(row.on.ms, 0, 'f', 1)
                 .arg(row.on.cpuMs, 0, 'f', 1)
                 .arg(row.off.ms, 0, 'f', 1)
                 .arg(row.off.cpuMs, 0, 'f', 1)
                 .arg(row.opens.isEmpty() ? QStringLiteral("opens no seam") : row.opens));
    return ok();
}

double ratio(const DragStepRow& r) {
    return r.on.measured && r.off.measured && r.off.ms > 0.0 ? r.on.ms / r.off.ms : 0.0;
}

QJsonObject timingJson(const DragStepTiming& t) {
    return {{QStringLiteral("ms"), t.ms},
            {QStringLiteral("cpuMs"), t.cpuMs},
            {QStringLiteral("continuityMs"), t.continuityMs},
            {QStringLiteral("bandsMs"), t.bandsMs},
            {QStringLiteral("bandVertices"), double(t.bandVertices)}};
}

} // namespace

Status runDragStep(const DragStepConfig& config, DragStepReport& report,
                   const std::function<void(const QString&)>& progress) {
    report = DragStepReport{};
    report.config = config;
    return runPerFile(
        config.files, report.machine, [&](OffscreenRenderer& renderer, const QString& file) {
            if (Status sized = renderer.setSize(QSize(config.side, config.side), false); !sized)
                return sized;
            Expected<ImportResult> read = openModelFile(file);
            if (!read)
                return Status(read.error());
            cli::printImportRemarks(file, read->report);
            if (read->scene.surfaces.empty())
                return Status(
                    Error(QStringLiteral("%1: the scene has no surfaces to drag").arg(file), file));
            for (const int faces : config.faces) {
                ModelSteps steps(config, renderer, progress);
                DragStepRow row;
                if (Status done = steps.run(read->scene, QFileInfo(file).fileName(), faces, row);
                    !done)
                    return done;
                report.rows.push_back(row);
            }
            return ok();
        });
}

QJsonArray dragStepJson(const DragStepReport& report) {
    QJsonArray rows;
    for (const DragStepRow& r : report.rows) {
        QJsonObject o{{QStringLiteral("model"), r.model},
                      {QStringLiteral("surfaces"), r.surfaces},
                      {QStringLiteral("copies"), r.copies},
                      {QStringLiteral("face"), r.face},
                      {QStringLiteral("faceEdges"), r.faceEdges},
                      {QStringLiteral("edges"), r.edges},
                      {QStringLiteral("steps"), report.config.steps},
                      {QStringLiteral("side"), report.config.side},
                      {QStringLiteral("setupMs"), r.setupMs},
                      {QStringLiteral("pairingMs"), r.pairingMs},
                      {QStringLiteral("opens"), r.opens},
                      {QStringLiteral("ratio"), ratio(r)}};
        if (r.on.measured)
            o.insert(QStringLiteral("overlayOn"), timingJson(r.on));
        if (r.off.measured)
            o.insert(QStringLiteral("overlayOff"), timingJson(r.off));
        rows.append(o);
    }
    return rows;
}

QString dragStepMarkdown(const DragStepReport& report, const QString& command) {
    QString md = loopTableHead(
        QStringLiteral("Drag step, Edge Continuity overlay on / off: %1 steps each at %2 x %2")
            .arg(report.config.steps)
            .arg(report.config.side),
        command, report.machine,
        {QStringLiteral("model"), QStringLiteral("faces"),
         QStringLiteral("shared edges (dragged face's)"),
         QStringLiteral("overlay on: step ms (CPU; edges, bands CPU ms)"),
         QStringLiteral("overlay off: step ms (CPU; edges CPU ms)"), QStringLiteral("on / off"),
         QStringLiteral("turning it on ms"), QStringLiteral("off: pairing (pool thread) ms")});
    const auto cell = [](const DragStepTiming& t, bool bands) {
        if (!t.measured)
            return QStringLiteral("-");
        QString s = QStringLiteral("%1 (%2; %3")
                        .arg(t.ms, 0, 'f', 1)
                        .arg(t.cpuMs, 0, 'f', 1)
                        .arg(t.continuityMs, 0, 'f', 2);
        if (bands)
            s += QStringLiteral(", %1").arg(t.bandsMs, 0, 'f', 2);
        return s + QLatin1Char(')');
    };
    for (const DragStepRow& r : report.rows)
        md += markdownRow(
            {r.model, QString::number(r.surfaces),
             QStringLiteral("%1 (%2)").arg(r.edges).arg(r.faceEdges), cell(r.on, true),
             cell(r.off, false),
             ratio(r) > 0.0 ? QStringLiteral("%1×").arg(ratio(r), 0, 'f', 2) : QStringLiteral("-"),
             r.on.measured ? QString::number(r.setupMs, 'f', 0) : QStringLiteral("-"),
             QString::number(r.pairingMs, 'f', 0)});
    return md + QLatin1Char('\n');
}

} // namespace kw::bench
