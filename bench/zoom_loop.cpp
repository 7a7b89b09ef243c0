// The close-up loop (zoom_loop.h): the contour it looks at, the peer's search at each zoom over
// the faces in view, the alternated timed transitions, and the report.
#include "bench/zoom_loop.h"

#include "bench/loop_runner.h"
#include "bench/peer_model.h"
#include "render/offscreen_renderer.h"

#include <QElapsedTimer>
#include <QFileInfo>
#include <QJsonObject>
#include <algorithm>
#include <cmath>
#include <set>

namespace kw::bench {

namespace {

constexpr double kMiB = 1024.0 * 1024.0;

/// Where the close-up looks: a point of the fitted view's outline where the surface turns
/// away from the eye (a contour, not a trim's edge), the nearest such point to the middle of
/// the frame. There a mesh's facets show first as the view closes in, while inside a face the
/// normal error a mesh makes does not grow with the zoom.
struct Target {
    glm::dvec3 point{0.0};
    QString what;
    bool found = false;
};

Target chooseTarget(const Scene& scene, const AovBuffer& aov, const Camera& camera) {
    Target best;
    double bestScore = 1e300;
    const auto covered = [&](int x, int y) {
        return x >= 0 && y >= 0 && x < aov.width && y < aov.height && aov.pixel(x, y)[0] >= 0.0f;
    };
    for (int y = 0; y < aov.height; ++y)
        for (int x = 0; x < aov.width; ++x) {
            if (!covered(x, y) ||
                (covered(x - 1, y) && covered(x + 1, y) && covered(x, y - 1) && covered(x, y + 1)))
                continue;
            const float* px = aov.pixel(x, y);
            const glm::dvec3 p(px[3], px[4], px[5]), n(px[6], px[7], px[8]);
            const double facing = std::abs(glm::dot(glm::normalize(camera.eye - p), n));
            if (facing > 0.2)
                continue; // the outline of a face seen from the front: a trim's edge
            const double dx = x - 0.5 * aov.width, dy = y - 0.5 * aov.height;
            const double score = facing * aov.width + std::sqrt(dx * dx + dy * dy);
            if (score < bestScore) {
                bestScore = score;
                best.point = p;
                best.found = true;
                const std::uint32_t id = std::uint32_t(px[0]);
                for (const Surface& s : scene.surfaces)
                    if (s.id.value == id)
                        best.what = QStringLiteral("contour of %1").arg(s.name);
            }
        }
    return best;
}

/// The fitted camera moved along its line to the target, `zoom` times closer: the target looks
/// `zoom` times larger, and a contour point stays on the contour ((E - P) . N = 0 still holds).
Camera closeUp(const Camera& fitted, const glm::dvec3& target, double zoom) {
    Camera c = fitted;
    c.target = target;
    c.eye = target + (fitted.eye - target) / zoom;
    return c;
}

std::set<std::uint32_t> facesInView(const AovBuffer& aov) {
    std::set<std::uint32_t> ids;
    for (int y = 0; y < aov.height; ++y)
        for (int x = 0; x < aov.width; ++x)
            if (const float id = aov.pixel(x, y)[0]; id >= 0.0f)
                ids.insert(std::uint32_t(id));
    return ids;
}

/// The triangles as OpenCASCADE keeps them in the B-rep's Poly_Triangulation: gp_Pnt nodes
/// (3 doubles), gp_Pnt2d uv (2 doubles), float normals, and 3 ints per triangle.
std::int64_t occtTriangulationBytes(const TriangleMesh& m) {
    std::int64_t bytes = 0;
    for (const SurfaceMesh& s : m.surfaces)
        bytes += std::int64_t(s.positions.size()) * (24 + 16 + 12) +
                 std::int64_t(s.indices.size()) / 3 * 12;
    return bytes;
}

/// The exact geometry Knotwork holds: control points and weights in double, knots, and the
/// trim curves' points, weights and knots.
std::int64_t geometryBytes(const Scene& scene) {
    std::int64_t bytes = 0;
    for (const Surface& s : scene.surfaces) {
        const NurbsSurface& g = s.geometry;
        bytes += std::int64_t(g.points.size()) * 24 + std::int64_t(g.weights.size()) * 8 +
                 std::int64_t(g.knotsU.size() + g.knotsV.size()) * 8;
        for (const TrimLoop& l : s.trims)
            for (const NurbsCurve2& c : l.curves)
                bytes += std::int64_t(c.points.size()) * 16 +
                         std::int64_t(c.weights.size() + c.knots.size()) * 8;
    }
    return bytes;
}

class ModelZoom {
public:
    ModelZoom(const ZoomLoopConfig& c, OffscreenRenderer& r, FaceMesher& m,
              const std::function<void(const QString&)>& p)
        : config(c), renderer(r), mesher(m), progress(p),
          peer(r, m, {c.lights, c.normalP99Floor, c.maxTriangles}, p) {}

    Status run(const QString& file, std::vector<ZoomLoopRow>& rows);

private:
    RenderOptions frameOptions() const {
        RenderOptions o = config.base;
        o.mode = RenderMode::Exact;
        o.partitioning = RenderOptions::Partitioning::Adaptive; // the editor's default
        o.lightCount = config.lights;
        o.samples = 1;
        o.progressive = false;
        return o;
    }
    Status meshFaces(const std::set<std::uint32_t>& ids, double linear, double angular,
                     TriangleMesh& out, long long& triangles, double* meshMs);

    const ZoomLoopConfig& config;
    OffscreenRenderer& renderer;
    FaceMesher& mesher;
    const std::function<void(const QString&)>& progress;
    PeerModel peer;
};

Status ModelZoom::meshFaces(const std::set<std::uint32_t>& ids, double linear, double angular,
                            TriangleMesh& out, long long& triangles, double* meshMs) {
    std::vector<Surface> faces;
    for (const Surface& s : peer.doc.scene().surfaces)
        if (ids.count(s.id.value))
            faces.push_back(s);
    TaggedMeshSet set;
    FaceMeshCost cost;
    // A close-up's equal-quality mesh of the faces in view can take BRepMesh minutes on a
    // loaded machine; the search's candidates are timed too, so they get the time they need.
    if (Status meshed = mesher.mesh(faces, peer.tolerance, linear, angular, set, cost, 600.0);
        !meshed)
        return Error(QStringLiteral("%1: %2").arg(peer.path, meshed.message()), peer.path);
    triangles = set.triangleCount();
    out = toTriangleMesh(set, SurfaceId{}, true);
    if (meshMs)
        *meshMs = cost.wallMs;
    return ok();
}

Status ModelZoom::run(const QString& file, std::vector<ZoomLoopRow>& rows) {
    if (Status loaded = peer.load(file); !loaded)
        return loaded;
    const QString name = QFileInfo(file).fileName();
    const Camera fitted = peer.camera;
    const RenderOptions options = frameOptions();

    // The fitted view: Knotwork's bar and the peer's equal-quality mesh of the whole model,
    // which a viewer has already made and sent when the user starts to zoom.
    PeerChoice fittedChoice;
    if (Status measured = peer.measureKnotwork(config.side, options); !measured)
        return measured;
    // The contour in Knotwork's exact frame, before the peer's search draws its candidates
    // into the same AOV (the target then followed where that search stopped).
    const Target target = chooseTarget(peer.doc.scene(), renderer.aov(), fitted);
    if (!target.found)
        return Error(
            QStringLiteral("%1: no contour in the fitted view to look at closely").arg(name), file);
    if (Status searched = peer.searchStatic(fittedChoice); !searched)
        return searched;
    TaggedMeshSet fittedSet;
    if (Status meshed = peer.staticMesh(fittedChoice.linear, fittedChoice.angular, fittedSet);
        !meshed)
        return meshed;
    const TriangleMesh fittedMesh = toTriangleMesh(fittedSet, SurfaceId{}, true);
    const std::int64_t kwGeometry = geometryBytes(peer.doc.scene());

    for (const double zoom : config.zooms) {
        ZoomLoopRow row;
        row.model = name;
        row.target = target.what;
        row.zoom = zoom;
        row.fittedTriangles = fittedSet.triangleCount();
        const Camera near = closeUp(fitted, target.point, zoom);
        peer.camera = near;
        if (Status measured = peer.measureKnotwork(config.side, options); !measured)
            return measured;
        row.knotworkNormalP99 = peer.knotwork.normalP99;
        row.knotworkSilhouetteMax = peer.knotwork.silhouetteMax;
        const std::set<std::uint32_t> inView = facesInView(renderer.aov());
        row.facesInView = int(inView.size());
        row.knotworkGpuMiB = double(renderer.lastReport().gpuBytes.total() -
                                    renderer.lastReport().gpuBytes.frameTargets -
                                    renderer.lastReport().gpuBytes.floatDepthTarget) /
                             kMiB;
        // Host memory: the exact geometry, and the renderer's CPU copies of what it uploaded.
        row.knotworkCpuMiB = double(kwGeometry + renderer.lastReport().hostCopyBytes) / kMiB;
        const GpuBytes& b = renderer.lastReport().gpuBytes;
        progress(QStringLiteral("%1 at %2x: Knotwork's GPU bytes: control points %3, span tables "
                                "%4, base polygons %5, trim masks %6, per surface %7; host "
                                "copies %8 (MiB); %9 cells drawn, %10 surfaces past the "
                                "tolerance")
                     .arg(name)
                     .arg(zoom)
                     .arg(double(b.controlPoints) / kMiB, 0, 'f', 2)
                     .arg(double(b.spanTables) / kMiB, 0, 'f', 2)
                     .arg(double(b.basePolygons) / kMiB, 0, 'f', 2)
                     .arg(double(b.trimMasks) / kMiB, 0, 'f', 2)
                     .arg(double(b.perSurface) / kMiB, 0, 'f', 2)
                     .arg(double(renderer.lastReport().hostCopyBytes) / kMiB, 0, 'f', 2)
                     .arg(renderer.lastReport().partitions.cells)
                     .arg(renderer.lastReport().partitions.unmet));

        // The fitted view's mesh seen this close: what the peer shows before it re-meshes.
        {
            RenderOptions o;
            o.lightCount = config.lights;
            ScreenQuality q;
            if (renderer.setMesh(0, fittedMesh) < 0)
                return Error(QStringLiteral("lost the OpenGL context"));
            if (Status drawn = renderer.renderMesh(peer.doc, 0, near, o); !drawn)
                return drawn;
            if (Status compared = peer.compare(q); !compared)
                return compared;
            row.fittedMeshNormalP99 = q.normalP99;
            row.fittedMeshSilhouetteMax = q.silhouetteMax;
            row.fittedMeshGood = peer.good(q);
        }
        // The faces out of view keep their fitted mesh (slot 1); those in view are re-meshed,
        // the search starting where the fitted view's choice, scaled by the zoom, lands.
        TriangleMesh rest;
        for (const TaggedMesh& f : fittedSet.faces)
            if (!inView.count(f.id.value)) {
                TaggedMeshSet one;
                one.faces.push_back(f);
                for (SurfaceMesh& m : toTriangleMesh(one, SurfaceId{}, true).surfaces)
                    rest.surfaces.push_back(std::move(m));
            }
        const std::int64_t restGpu = renderer.setMesh(1, rest);
        if (restGpu < 0)
            return Error(QStringLiteral("lost the OpenGL context"));
        PeerChoice choice = fittedChoice;
        const int zoomSteps = int(std::lround(std::log2(zoom)));
        if (!row.fittedMeshGood)
            if (Status searched = peer.search(
                    [&](double linear, double angular, TriangleMesh& mesh,
                        long long& triangles) -> Status {
                        if (Status meshed =
                                meshFaces(inView, linear, angular, mesh, triangles, nullptr);
                            !meshed)
                            return meshed;
                        for (const SurfaceMesh& m : rest.surfaces)
                            mesh.surfaces.push_back(m);
                        return ok();
                    },
                    fittedChoice.linearIndex + zoomSteps, fittedChoice.angularIndex, choice);
                !searched)
                return searched;
        row.peerMatched = choice.matched;
        row.peerLinear = choice.linear;
        row.peerAngular = choice.angular;
        row.peerNormalP99 = choice.quality.normalP99;
        row.peerSilhouetteMax = choice.quality.silhouetteMax;
        if (Status sized = renderer.setSize(QSize(config.side, config.side), false); !sized)
            return sized;

        // Timed transitions, alternated: from the fitted view (drawn, untimed) to the close-up.
        RenderOptions meshOptions;
        meshOptions.lightCount = config.lights;
        std::vector<double> kwMs, kwCpu, againMs, againCpu, peerMs, peerCpu, peerMesh;
        std::int64_t peerGpu = 0, peerCpuBytes = 0;
        // The fitted view's mesh in slot 0 once (the search drew its candidates there).
        const std::int64_t fittedGpu = renderer.setMesh(0, fittedMesh);
        if (fittedGpu < 0)
            return Error(QStringLiteral("lost the OpenGL context"));
        for (int k = 0; k <= config.repeats; ++k) {
            const bool timed = k > 0; // the first round warms shaders and the child up
            if (Status drawn = renderer.render(peer.doc, fitted, options); !drawn)
                return drawn;
            renderer.finish();
            QElapsedTimer wall;
            double cpu0 = processCpuMs();
            wall.start();
            if (Status drawn = renderer.render(peer.doc, near, options); !drawn)
                return drawn;
            renderer.finish();
            if (timed) {
                kwMs.push_back(double(wall.nsecsElapsed()) * 1e-6);
                kwCpu.push_back(processCpuMs() - cpu0);
                // Again, nothing to rebuild or send: what is left of the first frame's time
                // when every cost of the move is gone.
                cpu0 = processCpuMs();
                wall.restart();
                if (Status drawn = renderer.render(peer.doc, near, options); !drawn)
                    return drawn;
                renderer.finish();
                againMs.push_back(double(wall.nsecsElapsed()) * 1e-6);
                againCpu.push_back(processCpuMs() - cpu0);
            }

            if (Status drawn = renderer.renderMesh(peer.doc, 0, fitted, meshOptions); !drawn)
                return drawn;
            renderer.finish();
            cpu0 = processCpuMs();
            wall.restart();
            if (row.fittedMeshGood) {
                // The fitted view's mesh still meets the bar: the peer only draws it.
                if (Status drawn = renderer.renderMesh(peer.doc, 0, near, meshOptions); !drawn)
                    return drawn;
                renderer.finish();
                if (timed) {
                    peerMs.push_back(double(wall.nsecsElapsed()) * 1e-6);
                    peerCpu.push_back(processCpuMs() - cpu0);
                    peerMesh.push_back(0.0);
                }
                peerGpu = fittedGpu;
                peerCpuBytes = occtTriangulationBytes(fittedMesh);
                continue;
            }
            TriangleMesh faces;
            long long triangles = 0;
            double meshMs = 0.0;
            const double handoverCpu0 = processCpuMs();
            QElapsedTimer handover;
            handover.start();
            if (Status meshed =
                    meshFaces(inView, choice.linear, choice.angular, faces, triangles, &meshMs);
                !meshed)
                return meshed;
            const double handoverMs = double(handover.nsecsElapsed()) * 1e-6;
            const double handoverCpu = processCpuMs() - handoverCpu0;
            const std::int64_t sent = renderer.setMesh(2, faces);
            if (sent < 0)
                return Error(QStringLiteral("lost the OpenGL context"));
            if (Status drawn = renderer.renderMeshes(peer.doc, {1, 2}, near, meshOptions); !drawn)
                return drawn;
            renderer.finish();
            if (timed) {
                peerMs.push_back(double(wall.nsecsElapsed()) * 1e-6 - handoverMs + meshMs);
                peerCpu.push_back(processCpuMs() - cpu0 - handoverCpu + meshMs);
                peerMesh.push_back(meshMs);
            }
            row.peerTriangles = triangles;
            peerGpu = restGpu + sent;
            TriangleMesh all = rest;
            for (SurfaceMesh& m : faces.surfaces)
                all.surfaces.push_back(std::move(m));
            peerCpuBytes = occtTriangulationBytes(all);
        }
        row.knotworkMs = median(kwMs);
        row.knotworkCpuMs = median(kwCpu);
        row.knotworkAgainMs = median(againMs);
        row.knotworkAgainCpuMs = median(againCpu);
        row.peerMs = median(peerMs);
        row.peerCpuMs = median(peerCpu);
        row.peerMeshMs = median(peerMesh);
        row.peerGpuMiB = double(peerGpu) / kMiB;
        // The peer keeps the exact model too: it re-meshes from it at every close-up.
        row.peerCpuMiB = double(peerCpuBytes + kwGeometry) / kMiB;
        progress(QStringLiteral("%1 at %2x on the %3: Knotwork %4 ms, peer %5 ms (re-mesh %6 ms, "
                                "%7 triangles in view); memory %8 MiB against %9 MiB")
                     .arg(name)
                     .arg(zoom)
                     .arg(target.what)
                     .arg(row.knotworkMs, 0, 'f', 1)
                     .arg(row.peerMs, 0, 'f', 1)
                     .arg(row.peerMeshMs, 0, 'f', 1)
                     .arg(row.peerTriangles)
                     .arg(row.knotworkGpuMiB + row.knotworkCpuMiB, 0, 'f', 1)
                     .arg(row.peerGpuMiB + row.peerCpuMiB, 0, 'f', 1));
        rows.push_back(row);
    }
    return ok();
}

} // namespace

Status runZoomLoop(const ZoomLoopConfig& config, ZoomLoopReport& report,
                   const std::function<void(const QString&)>& progress) {
    report = ZoomLoopReport{};
    report.config = config;
    FaceMesher mesher;
    return runPerFile(config.files, report.machine,
                      [&](OffscreenRenderer& renderer, const QString& file) {
                          ModelZoom loop(config, renderer, mesher, progress);
                          return loop.run(file, report.rows);
                      });
}

QJsonArray zoomLoopJson(const ZoomLoopReport& report) {
    QJsonArray rows;
    for (const ZoomLoopRow& r : report.rows) {
        const double kwMem = r.knotworkGpuMiB + r.knotworkCpuMiB;
        const double peerMem = r.peerGpuMiB + r.peerCpuMiB;
        rows.append(
            QJsonObject{{QStringLiteral("model"), r.model},
                        {QStringLiteral("target"), r.target},
                        {QStringLiteral("zoom"), r.zoom},
                        {QStringLiteral("side"), report.config.side},
                        {QStringLiteral("repeats"), report.config.repeats},
                        {QStringLiteral("facesInView"), r.facesInView},
                        {QStringLiteral("knotworkMs"), r.knotworkMs},
                        {QStringLiteral("knotworkCpuMs"), r.knotworkCpuMs},
                        {QStringLiteral("knotworkAgainMs"), r.knotworkAgainMs},
                        {QStringLiteral("knotworkAgainCpuMs"), r.knotworkAgainCpuMs},
                        {QStringLiteral("peerMs"), r.peerMs},
                        {QStringLiteral("peerCpuMs"), r.peerCpuMs},
                        {QStringLiteral("peerMeshMs"), r.peerMeshMs},
                        {QStringLiteral("peerMatched"), r.peerMatched},
                        {QStringLiteral("peerLinearDeflection"), r.peerLinear},
                        {QStringLiteral("peerAngularDeflection"), r.peerAngular},
                        {QStringLiteral("peerTriangles"), double(r.peerTriangles)},
                        {QStringLiteral("fittedTriangles"), double(r.fittedTriangles)},
                        {QStringLiteral("fittedMeshSilhouetteMax"), r.fittedMeshSilhouetteMax},
                        {QStringLiteral("fittedMeshNormalP99"), r.fittedMeshNormalP99},
                        {QStringLiteral("fittedMeshGood"), r.fittedMeshGood},
                        {QStringLiteral("knotworkNormalP99"), r.knotworkNormalP99},
                        {QStringLiteral("knotworkSilhouetteMax"), r.knotworkSilhouetteMax},
                        {QStringLiteral("peerNormalP99"), r.peerNormalP99},
                        {QStringLiteral("peerSilhouetteMax"), r.peerSilhouetteMax},
                        {QStringLiteral("knotworkGpuMiB"), r.knotworkGpuMiB},
                        {QStringLiteral("knotworkCpuMiB"), r.knotworkCpuMiB},
                        {QStringLiteral("peerGpuMiB"), r.peerGpuMiB},
                        {QStringLiteral("peerCpuMiB"), r.peerCpuMiB},
                        {QStringLiteral("ratio"), ratioOf(r.knotworkMs, r.peerMs)},
                        {QStringLiteral("memoryRatio"), ratioOf(kwMem, peerMem)}});
    }
    return rows;
}

QString zoomLoopMarkdown(const ZoomLoopReport& report, const QString& command) {
    QString md = loopTableHead(
        QStringLiteral("Close-up: fitted view to zoom, %1 transitions at %2 x %2")
            .arg(report.config.repeats)
            .arg(report.config.side),
        command, report.machine,
        {QStringLiteral("model"), QStringLiteral("zoom"), QStringLiteral("faces in view"),
         QStringLiteral("fitted mesh at this zoom: silhouette px / normal p99 °"),
         QStringLiteral("Knotwork ms (CPU)"), QStringLiteral("drawn again ms (CPU)"),
         QStringLiteral("peer ms (CPU; re-mesh)"), QStringLiteral("peer triangles in view"),
         QStringLiteral("Knotwork / peer"), QStringLiteral("drawn again / peer"),
         QStringLiteral("memory MiB Knotwork (GPU + host: geometry, copies)"),
         QStringLiteral("peer (GPU + B-rep: triangles, geometry)"),
         QStringLiteral("memory ratio")});
    for (const ZoomLoopRow& r : report.rows) {
        const double kwMem = r.knotworkGpuMiB + r.knotworkCpuMiB;
        const double peerMem = r.peerGpuMiB + r.peerCpuMiB;
        md += markdownRow(
            {r.model, QStringLiteral("%1×").arg(r.zoom), QString::number(r.facesInView),
             QStringLiteral("%1 / %2")
                 .arg(r.fittedMeshSilhouetteMax, 0, 'f', 1)
                 .arg(r.fittedMeshNormalP99, 0, 'f', 2),
             QStringLiteral("%1 (%2)").arg(r.knotworkMs, 0, 'f', 1).arg(r.knotworkCpuMs, 0, 'f', 1),
             QStringLiteral("%1 (%2)")
                 .arg(r.knotworkAgainMs, 0, 'f', 1)
                 .arg(r.knotworkAgainCpuMs, 0, 'f', 1),
             QStringLiteral("%1 (%2; %3)%4")
                 .arg(r.peerMs, 0, 'f', 1)
                 .arg(r.peerCpuMs, 0, 'f', 1)
                 .arg(r.peerMeshMs, 0, 'f', 1)
                 .arg(r.fittedMeshGood ? QStringLiteral(" (the fitted mesh still holds)")
                      : r.peerMatched  ? QString()
                                       : QStringLiteral(" (equal quality not reached)")),
             QString::number(r.peerTriangles),
             QStringLiteral("%1×").arg(ratioOf(r.knotworkMs, r.peerMs), 0, 'f', 2),
             QStringLiteral("%1×").arg(ratioOf(r.knotworkAgainMs, r.peerMs), 0, 'f', 2),
             QStringLiteral("%1 (%2 + %3)")
                 .arg(kwMem, 0, 'f', 1)
                 .arg(r.knotworkGpuMiB, 0, 'f', 1)
                 .arg(r.knotworkCpuMiB, 0, 'f', 1),
             QStringLiteral("%1 (%2 + %3)")
                 .arg(peerMem, 0, 'f', 1)
                 .arg(r.peerGpuMiB, 0, 'f', 1)
                 .arg(r.peerCpuMiB, 0, 'f', 1),
             QStringLiteral("%1×").arg(ratioOf(kwMem, peerMem), 0, 'f', 2)});
    }
    return md + QLatin1Char('\n');
}

} // namespace kw::bench
