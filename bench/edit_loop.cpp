// The edit loop (edit_loop.h): the dragged face, the peer's equal-quality search, the
// alternated timed steps, and the report.
#include "bench/edit_loop.h"

#include "bench/loop_runner.h"
#include "bench/peer_model.h"
#include "model/cad/facemesher.h"
#include "model/document/document.h"
#include "render/gpu_layout.h"
#include "render/offscreen_renderer.h"

#include <QElapsedTimer>
#include <QFileInfo>
#include <QJsonObject>
#include <algorithm>
#include <cmath>

namespace kw::bench {

namespace {

// Free-form: a polynomial (all weights equal) surface curved in some direction. Rational
// surfaces are the conics and quadrics of imported analytic faces, degree 1 x 1 the planes.
bool isFreeForm(const NurbsSurface& g) {
    const bool polynomial = std::all_of(g.weights.begin(), g.weights.end(),
                                        [&](double w) { return w == g.weights.front(); });
    return polynomial && std::max(g.degreeU, g.degreeV) >= 2;
}

double untrimmedArea(const NurbsSurface& g) {
    const TessellatedMesh t = tessellate(g, 8, 8);
    double area = 0.0;
    for (size_t k = 0; k + 2 < t.indices.size(); k += 3) {
        const glm::dvec3 a(t.positions[t.indices[k]]), b(t.positions[t.indices[k + 1]]),
            c(t.positions[t.indices[k + 2]]);
        area += 0.5 * glm::length(glm::cross(b - a, c - a));
    }
    return area;
}

// Greville abscissa of control point i: where it pulls the surface most.
double greville(const std::vector<double>& knots, int degree, int i) {
    double sum = 0.0;
    for (int k = 1; k <= degree; ++k)
        sum += knots[size_t(i + k)];
    return degree > 0 ? sum / degree : knots[size_t(i)];
}

/// The dragged point: the middle control point of the largest free-form face (or, when there is
/// none, of the largest face), moved along the surface normal there.
struct Drag {
    SurfaceId id;
    int index = 0;
    glm::dvec3 home{0.0}, direction{0.0};
    double amplitude = 0.0;
    bool freeForm = true;
    QString name;
};

Drag chooseDrag(const Scene& scene) {
    Drag d;
    double best = -1.0;
    bool bestFree = false;
    for (const Surface& s : scene.surfaces) {
        const bool free = isFreeForm(s.geometry);
        const double area = untrimmedArea(s.geometry);
        if ((free && !bestFree) || (free == bestFree && area > best)) {
            best = area;
            bestFree = free;
            d.id = s.id;
            d.freeForm = free;
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
    d.amplitude = 0.1 * glm::length(hi - lo); // a visible drag: a tenth of the face's size
    return d;
}

/// Position of drag event `e` of `count`: out along the normal and back (a triangle wave).
glm::dvec3 dragPosition(const Drag& d, int e, int count) {
    const double x = double(e + 1) / double(count);
    return d.home + d.direction * (d.amplitude * (1.0 - std::abs(1.0 - 2.0 * x)));
}

/// One model's loop: everything it needs in one place.
class ModelLoop {
public:
    ModelLoop(const EditLoopConfig& c, OffscreenRenderer& r, FaceMesher& m,
              const std::function<void(const QString&)>& p)
        : config(c), renderer(r), mesher(m), progress(p),
          peer(r, m, {c.lights, c.normalP99Floor, c.maxTriangles}, p) {}

    Status run(const QString& file, EditLoopRow& row);

private:
    RenderOptions
    frameOptions(int samples,
                 RenderOptions::FrameReuse reuse = RenderOptions::FrameReuse::None) const;

    const EditLoopConfig& config;
    OffscreenRenderer& renderer;
    FaceMesher& mesher;
    const std::function<void(const QString&)>& progress;
    PeerModel peer;
    Document& doc = peer.doc;
    Camera& camera = peer.camera;
};

RenderOptions ModelLoop::frameOptions(int samples, RenderOptions::FrameReuse reuse) const {
    RenderOptions o = config.base;
    o.frameReuse = reuse;
    o.mode = RenderMode::Exact;
    o.partitioning = RenderOptions::Partitioning::Adaptive; // the editor's and render's default
    o.lightCount = config.lights;
    o.samples = samples;
    o.antialiasing = RenderOptions::Antialiasing::Accumulate;
    o.progressive = false;
    return o;
}

Status ModelLoop::run(const QString& file, EditLoopRow& row) {
    if (Status loaded = peer.load(file); !loaded)
        return loaded;
    const QString name = QFileInfo(file).fileName();
    row.model = name;
    row.surfaces = int(doc.scene().surfaces.size());
    row.defaultLinear = 0.004 * peer.side;
    if (config.peerDeflections) {
        row.deflectionsGiven = true;
        row.peerLinear = config.peerDeflections->first;
        row.peerAngular = config.peerDeflections->second;
    } else {
        // Knotwork's quality and the peer's search, against the CPU reference frame.
        PeerChoice choice;
        if (Status measured = peer.measureKnotwork(config.side, frameOptions(1)); !measured)
            return measured;
        if (Status searched = peer.searchStatic(choice); !searched)
            return searched;
        row.knotworkNormalP99 = peer.knotwork.normalP99;
        row.knotworkSilhouetteMax = peer.knotwork.silhouetteMax;
        row.matched = choice.matched;
        row.peerLinear = choice.linear;
        row.peerAngular = choice.angular;
        row.peerNormalP99 = choice.quality.normalP99;
        row.peerSilhouetteMax = choice.quality.silhouetteMax;
    }
    if (Status sized = renderer.setSize(QSize(config.side, config.side), false); !sized)
        return sized;

    const Drag drag = chooseDrag(doc.scene());
    row.face = drag.name;
    row.freeForm = drag.freeForm;
    // The rest of the model stays in one slot; the edited face goes to the next, re-sent every
    // step (equal quality: slots 0 and 1; OCCT's defaults: 2 and 3).
    struct Peer {
        double linear = 0.0, angular = 0.0;
        int rest = 0, face = 1;
        long long triangles = 0;
        std::vector<double> ms, cpu, mesh;
        std::vector<long long> faceTriangles;
    };
    Peer peers[2];
    peers[0].linear = row.peerLinear;
    peers[0].angular = row.peerAngular;
    peers[1].linear = row.defaultLinear;
    peers[1].angular = 20.0;
    peers[1].rest = 2;
    peers[1].face = 3;
    for (Peer& p : peers) {
        TaggedMeshSet set;
        if (Status meshed = peer.staticMesh(p.linear, p.angular, set); !meshed)
            return meshed;
        p.triangles = set.triangleCount();
        if (renderer.setMesh(p.rest, toTriangleMesh(set, drag.id, true)) < 0 ||
            renderer.setMesh(p.face, toTriangleMesh(set, drag.id, false)) < 0)
            return Error(QStringLiteral("lost the OpenGL context"));
    }
    row.peerTriangles = peers[0].triangles;
    row.peerDefaultTriangles = peers[1].triangles;

    bool refused = false;
    const auto moveTo = [&](const glm::dvec3& p) {
        refused = !doc.setControlPoints(drag.id, {drag.index}, {p}) || refused;
    };
    RenderOptions meshOptions;
    meshOptions.lightCount = config.lights;
    // One peer step: the edit, the face rebuilt and re-meshed in the child (its own time),
    // the triangles re-sent and the frame drawn. The hand-over to the child and back is not
    // counted: a viewer with OCCT in process has none.
    const auto peerStep = [&](Peer& p, const glm::dvec3& to, bool timed) -> Status {
        QElapsedTimer wall;
        const double cpu0 = processCpuMs();
        wall.start();
        moveTo(to);
        const double handoverCpu0 = processCpuMs();
        QElapsedTimer handover;
        handover.start();
        TaggedMeshSet set;
        FaceMeshCost cost;
        if (Status meshed = mesher.mesh({*doc.surface(drag.id)}, peer.tolerance, p.linear,
                                        p.angular, set, cost);
            !meshed)
            return Error(QStringLiteral("%1: %2").arg(name, meshed.message()), file);
        const double handoverMs = double(handover.nsecsElapsed()) * 1e-6;
        const double handoverCpu = processCpuMs() - handoverCpu0;
        if (renderer.setMesh(p.face, toTriangleMesh(set, drag.id, false)) < 0)
            return Error(QStringLiteral("lost the OpenGL context"));
        if (Status drawn = renderer.renderMeshes(doc, {p.rest, p.face}, camera, meshOptions);
            !drawn)
            return drawn;
        renderer.finish();
        if (timed) {
            p.ms.push_back(double(wall.nsecsElapsed()) * 1e-6 - handoverMs + cost.wallMs);
            p.cpu.push_back(processCpuMs() - cpu0 - handoverCpu + cost.cpuMs);
            p.mesh.push_back(cost.wallMs);
            p.faceTriangles.push_back(set.triangleCount());
        }
        return ok();
    };
    std::vector<double> kwMs, kwCpu, fullMs, fullCpu, stillMs, stillCpu, areas, redrawn, regions,
        reached, cells,
        fullCells;
    std::vector<std::vector<double>> passWall(PassTimes::kCount), passCpu(PassTimes::kCount);
    // The editor's aliased frames are kept in the renderer's own framebuffer and copied
    // (ViewSurface::drawFrame); a drag step redraws what the dragged face covered then and now.
    using Reuse = RenderOptions::FrameReuse;
    const Reuse editorReuse = config.fullFrames ? Reuse::Full : Reuse::Partial;
    const auto knotworkStep = [&](int samples, Reuse reuse, const glm::dvec3& to,
                                  std::vector<double>* ms, std::vector<double>* cpu) -> Status {
        QElapsedTimer wall;
        const double cpu0 = processCpuMs();
        wall.start();
        const bool profiled = config.passTimes && ms == &kwMs;
        renderer.renderer().setPassProfiling(profiled);
        moveTo(to);
        const Status drawn = renderer.render(doc, camera, frameOptions(samples, reuse));
        renderer.renderer().setPassProfiling(false);
        if (!drawn)
            return drawn;
        renderer.finish();
        if (ms) {
            ms->push_back(double(wall.nsecsElapsed()) * 1e-6);
            cpu->push_back(processCpuMs() - cpu0);
        }
        const FrameReport& report = renderer.lastReport();
        if (ms == &kwMs && report.partial) {
            ++row.partialFrames;
            areas.push_back(double(report.partialRect.width()) * report.partialRect.height() /
                            (double(config.side) * config.side));
            redrawn.push_back(double(report.partialPixels) / (double(config.side) * config.side));
            regions.push_back(report.partialRegions);
            reached.push_back(report.partialSurfaces);
            cells.push_back(double(report.partialCells));
        }
        if (const PassTimes& p = report.passes; profiled && p.measured)
            for (int pass = 0; pass < PassTimes::kCount; ++pass) {
                passWall[size_t(pass)].push_back(p.wallMs[pass]);
                passCpu[size_t(pass)].push_back(p.cpuMs[pass]);
            }
        if (ms == &fullMs)
            fullCells.push_back(double(report.partitions.cells));
        return ok();
    };
    // Warm-up, untimed: shaders, first uploads, the child's first face. The exact pass picks
    // its shader variant per surface from its cells' size on screen, and a variant is compiled
    // on first use (seconds on llvmpipe): both frames are drawn at the drag's farthest point
    // too, so that no timed step compiles one.
    const glm::dvec3 warm = drag.home + drag.direction * (1e-3 * drag.amplitude);
    const glm::dvec3 peak = drag.home + drag.direction * drag.amplitude;
    Status warmed = knotworkStep(1, Reuse::Full, peak, nullptr, nullptr);
    if (warmed)
        warmed = knotworkStep(1, editorReuse, drag.home, nullptr, nullptr);
    if (warmed)
        warmed = knotworkStep(config.stillSamples, Reuse::None, peak, nullptr, nullptr);
    if (warmed)
        warmed = knotworkStep(1, Reuse::Full, warm, nullptr, nullptr);
    if (warmed)
        warmed = knotworkStep(1, editorReuse, peak, nullptr, nullptr);
    if (warmed)
        warmed = knotworkStep(config.stillSamples, Reuse::None, drag.home, nullptr, nullptr);
    if (warmed)
        warmed = peerStep(peers[0], warm, false);
    if (warmed)
        warmed = peerStep(peers[1], drag.home, false);
    if (!warmed)
        return warmed;
    // The five methods alternate step by step, each at its own point of one drag path. The
    // editor's frame follows the whole aliased frame, as a drag step follows the last: its
    // partial frame redraws the face's rectangles at both points (the still frame, with its
    // samples, is always whole and keeps nothing).
    const int events = 5 * config.steps;
    for (int k = 0; k < config.steps; ++k) {
        Status done = knotworkStep(config.stillSamples, Reuse::None,
                                   dragPosition(drag, 5 * k, events), &stillMs, &stillCpu);
        if (done)
            done = knotworkStep(1, Reuse::Full, dragPosition(drag, 5 * k + 1, events), &fullMs,
                                &fullCpu);
        if (done)
            done =
                knotworkStep(1, editorReuse, dragPosition(drag, 5 * k + 2, events), &kwMs, &kwCpu);
        if (done)
            done = peerStep(peers[0], dragPosition(drag, 5 * k + 3, events), true);
        if (done)
            done = peerStep(peers[1], dragPosition(drag, 5 * k + 4, events), true);
        if (!done)
            return done;
    }
    moveTo(drag.home);
    if (refused)
        return Error(QStringLiteral("%1: the drag's control point move was refused").arg(name),
                     file);
    row.knotworkMs = median(kwMs);
    row.knotworkCpuMs = median(kwCpu);
    row.knotworkFullMs = median(fullMs);
    row.knotworkFullCpuMs = median(fullCpu);
    row.partialArea = areas.empty() ? 0.0 : median(areas);
    row.partialRedrawn = redrawn.empty() ? 0.0 : median(redrawn);
    row.partialRegions = regions.empty() ? 0.0 : median(regions);
    row.partialSurfaces = reached.empty() ? 0.0 : median(reached);
    row.partialCells = cells.empty() ? 0.0 : median(cells);
    row.fullCells = median(fullCells);
    if (!passCpu.front().empty())
        for (int pass = 0; pass < PassTimes::kCount; ++pass) {
            row.passWallMs.push_back(median(passWall[size_t(pass)]));
            row.passCpuMs.push_back(median(passCpu[size_t(pass)]));
        }
    row.knotworkStillMs = median(stillMs);
    row.knotworkStillCpuMs = median(stillCpu);
    row.peerMs = median(peers[0].ms);
    row.peerCpuMs = median(peers[0].cpu);
    row.peerMeshMs = median(peers[0].mesh);
    row.peerDefaultMs = median(peers[1].ms);
    row.peerDefaultCpuMs = median(peers[1].cpu);
    row.peerDefaultMeshMs = median(peers[1].mesh);
    std::vector<double> faceTris(peers[0].faceTriangles.begin(), peers[0].faceTriangles.end());
    row.peerFaceTriangles = (long long)median(faceTris);
    progress(QStringLiteral("%1: edit loop on %2: Knotwork %3 ms (%9 of %10 frames partial; "
                            "whole %11 ms; still %4 ms), peer %5 ms (mesh %6 ms, %7 triangles), "
                            "peer at OCCT's defaults %8 ms")
                 .arg(name, drag.name)
                 .arg(row.knotworkMs, 0, 'f', 1)
                 .arg(row.knotworkStillMs, 0, 'f', 1)
                 .arg(row.peerMs, 0, 'f', 1)
                 .arg(row.peerMeshMs, 0, 'f', 1)
                 .arg(row.peerTriangles)
                 .arg(row.peerDefaultMs, 0, 'f', 1)
                 .arg(row.partialFrames)
                 .arg(config.steps)
                 .arg(row.knotworkFullMs, 0, 'f', 1));
    if (!row.passCpuMs.empty()) {
        QStringList passes;
        for (size_t pass = 0; pass < row.passCpuMs.size(); ++pass)
            if (row.passWallMs[pass] > 0.0)
                passes << QStringLiteral("%1 %2 (%3)")
                              .arg(QLatin1String(PassTimes::name(int(pass))))
                              .arg(row.passWallMs[pass], 0, 'f', 2)
                              .arg(row.passCpuMs[pass], 0, 'f', 2);
        progress(QStringLiteral("%1: the editor's aliased frame by pass, wall (CPU) ms: %2")
                     .arg(name, passes.join(QStringLiteral(", "))));
    }
    return ok();
}

} // namespace

Status runEditLoop(const EditLoopConfig& config, EditLoopReport& report,
                   const std::function<void(const QString&)>& progress) {
    report = EditLoopReport{};
    report.config = config;
    FaceMesher mesher;
    return runPerFile(config.files, report.machine,
                      [&](OffscreenRenderer& renderer, const QString& file) -> Status {
                          ModelLoop loop(config, renderer, mesher, progress);
                          EditLoopRow row;
                          if (Status done = loop.run(file, row); !done)
                              return done;
                          report.rows.push_back(row);
                          return ok();
                      });
}

QJsonArray editLoopJson(const EditLoopReport& report) {
    QJsonArray rows;
    for (const EditLoopRow& r : report.rows) {
        QJsonObject o{{QStringLiteral("model"), r.model},
                      {QStringLiteral("surfaces"), r.surfaces},
                      {QStringLiteral("face"), r.face},
                      {QStringLiteral("freeForm"), r.freeForm},
                      {QStringLiteral("steps"), report.config.steps},
                      {QStringLiteral("side"), report.config.side},
                      {QStringLiteral("knotworkMs"), r.knotworkMs},
                      {QStringLiteral("knotworkCpuMs"), r.knotworkCpuMs},
                      {QStringLiteral("knotworkFullMs"), r.knotworkFullMs},
                      {QStringLiteral("knotworkFullCpuMs"), r.knotworkFullCpuMs},
                      {QStringLiteral("fullFrames"), report.config.fullFrames},
                      {QStringLiteral("partialFrames"), r.partialFrames},
                      {QStringLiteral("partialArea"), r.partialArea},
                      {QStringLiteral("partialRedrawn"), r.partialRedrawn},
                      {QStringLiteral("partialRegions"), r.partialRegions},
                      {QStringLiteral("partialSurfaces"), r.partialSurfaces},
                      {QStringLiteral("partialCells"), r.partialCells},
                      {QStringLiteral("fullCells"), r.fullCells},
                      {QStringLiteral("knotworkStillMs"), r.knotworkStillMs},
                      {QStringLiteral("knotworkStillCpuMs"), r.knotworkStillCpuMs},
                      {QStringLiteral("peerMs"), r.peerMs},
                      {QStringLiteral("peerCpuMs"), r.peerCpuMs},
                      {QStringLiteral("peerMeshMs"), r.peerMeshMs},
                      {QStringLiteral("peerDefaultMs"), r.peerDefaultMs},
                      {QStringLiteral("peerDefaultCpuMs"), r.peerDefaultCpuMs},
                      {QStringLiteral("peerDefaultMeshMs"), r.peerDefaultMeshMs},
                      {QStringLiteral("peerTriangles"), double(r.peerTriangles)},
                      {QStringLiteral("peerFaceTriangles"), double(r.peerFaceTriangles)},
                      {QStringLiteral("peerDefaultTriangles"), double(r.peerDefaultTriangles)},
                      {QStringLiteral("peerLinearDeflection"), r.peerLinear},
                      {QStringLiteral("peerAngularDeflection"), r.peerAngular},
                      {QStringLiteral("defaultLinearDeflection"), r.defaultLinear},
                      {QStringLiteral("deflectionsGiven"), r.deflectionsGiven},
                      {QStringLiteral("ratio"), ratioOf(r.knotworkMs, r.peerMs)}};
        if (!r.passCpuMs.empty()) {
            QJsonObject passes;
            for (size_t pass = 0; pass < r.passCpuMs.size(); ++pass)
                passes.insert(QLatin1String(PassTimes::name(int(pass))),
                              QJsonObject{{QStringLiteral("wallMs"), r.passWallMs[pass]},
                                          {QStringLiteral("cpuMs"), r.passCpuMs[pass]}});
            o.insert(QStringLiteral("partialPasses"), passes);
        }
        if (!r.deflectionsGiven) {
            o.insert(QStringLiteral("equalQuality"), r.matched);
            o.insert(QStringLiteral("knotworkNormalP99"), r.knotworkNormalP99);
            o.insert(QStringLiteral("knotworkSilhouetteMax"), r.knotworkSilhouetteMax);
            o.insert(QStringLiteral("peerNormalP99"), r.peerNormalP99);
            o.insert(QStringLiteral("peerSilhouetteMax"), r.peerSilhouetteMax);
        }
        rows.append(o);
    }
    return rows;
}

QString editLoopMarkdown(const EditLoopReport& report, const QString& command) {
    QString md = loopTableHead(
        QStringLiteral("Edit loop: %1 drag steps at %2 x %2")
            .arg(report.config.steps)
            .arg(report.config.side),
        command, report.machine,
        {QStringLiteral("model"), QStringLiteral("dragged face"),
         QStringLiteral("Knotwork edit → frame ms (CPU)"),
         QStringLiteral("partial frames (rectangle, redrawn in rectangles, surfaces)"),
         QStringLiteral("whole frame ms (CPU)"), QStringLiteral("edit → still frame ms (CPU)"),
         QStringLiteral("peer deflection linear / angular"),
         QStringLiteral("peer triangles (face)"),
         QStringLiteral("peer edit → frame ms (CPU; re-mesh)"), QStringLiteral("Knotwork / peer"),
         QStringLiteral("peer at OCCT defaults ms (re-mesh; triangles)")});
    for (const EditLoopRow& r : report.rows)
        md += markdownRow(
            {r.model,
             r.face + (r.freeForm ? QString() : QStringLiteral(", analytic, turned free-form")),
             QStringLiteral("%1 (%2)").arg(r.knotworkMs, 0, 'f', 1).arg(r.knotworkCpuMs, 0, 'f', 1),
             QStringLiteral("%1 of %2 (%3 %, %4 % in %5, %6)")
                 .arg(r.partialFrames)
                 .arg(report.config.steps)
                 .arg(100.0 * r.partialArea, 0, 'f', 1)
                 .arg(100.0 * r.partialRedrawn, 0, 'f', 1)
                 .arg(r.partialRegions, 0, 'f', 0)
                 .arg(r.partialSurfaces, 0, 'f', 0),
             QStringLiteral("%1 (%2)")
                 .arg(r.knotworkFullMs, 0, 'f', 1)
                 .arg(r.knotworkFullCpuMs, 0, 'f', 1),
             QStringLiteral("%1 (%2)")
                 .arg(r.knotworkStillMs, 0, 'f', 1)
                 .arg(r.knotworkStillCpuMs, 0, 'f', 1),
             QStringLiteral("%1 / %2°%3")
                 .arg(r.peerLinear, 0, 'g', 3)
                 .arg(r.peerAngular)
                 .arg(r.deflectionsGiven ? QStringLiteral(" (given)")
                      : r.matched        ? QString()
                                         : QStringLiteral(" (equal quality not reached)")),
             QStringLiteral("%1 (%2)").arg(r.peerTriangles).arg(r.peerFaceTriangles),
             QStringLiteral("%1 (%2; %3)")
                 .arg(r.peerMs, 0, 'f', 1)
                 .arg(r.peerCpuMs, 0, 'f', 1)
                 .arg(r.peerMeshMs, 0, 'f', 1),
             QStringLiteral("%1× (CPU %2×; whole frames %3×)")
                 .arg(ratioOf(r.knotworkMs, r.peerMs), 0, 'f', 2)
                 .arg(ratioOf(r.knotworkCpuMs, r.peerCpuMs), 0, 'f', 2)
                 .arg(ratioOf(r.knotworkFullMs, r.peerMs), 0, 'f', 2),
             QStringLiteral("%1 (%2; %3)")
                 .arg(r.peerDefaultMs, 0, 'f', 1)
                 .arg(r.peerDefaultMeshMs, 0, 'f', 1)
                 .arg(r.peerDefaultTriangles)});
    return md + QLatin1Char('\n');
}

} // namespace kw::bench
