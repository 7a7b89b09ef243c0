// The benchmark's measurement loop: timed frames (glFinish each), quality frames with AOVs, and
// the equal-quality searches for the fine mesh and the GLU tessellator.
#include "bench/bench_runner.h"

#include "app/commands.h"
#include "bench/glu_tessellator.h"
#include "bench/peer_model.h"
#include "model/cad/cadimport.h"
#include "model/document/document.h"
#include "model/nurbs/trim.h"

#include <QElapsedTimer>
#include <QFile>
#include <QFileInfo>
#include <QThread>
#include <algorithm>
#include <map>
#include <sys/resource.h>

namespace kw::bench {

namespace {

using Frame = std::function<Status()>;

/// A loaded model: its document (for the renderer) and camera at one aspect.
struct Model {
    QString name;
    Document doc;
    Camera camera;
};

// Read as `knotwork render` reads it (kw::openModelFile): a .knot as saved, IGES, STEP and BREP
// through the CAD reader's child process, OBJ; the import's remarks on stderr.
Status loadModel(const QString& file, double aspect, Model& m) {
    Expected<ImportResult> read = openModelFile(file);
    if (!read)
        return read.error();
    cli::printImportRemarks(file, read->report);
    const std::optional<Scene> scene = std::move(read->scene);
    if (const Status reset = m.doc.resetScene(*scene); !reset)
        return Error(QStringLiteral("%1: %2").arg(file, reset.message()), file);
    if (m.doc.scene().surfaces.empty())
        return Error(QStringLiteral("%1: the scene has no surfaces to measure").arg(file), file);
    m.name = QFileInfo(file).fileName();
    m.camera = scene->camera.authored ? scene->camera : fitCamera(*scene, aspect);
    return ok();
}

/// The GL side of a run: the off-screen renderer, which also draws the two comparison meshes
/// (Renderer::setMesh and renderMesh: the bench uses render's public interface only).
class Session {
public:
    /// The renderer's mesh slots of the comparison rows.
    static constexpr int kGluSlot = 0, kFineSlot = 1;

    Session() = default;
    Session(const Session&) = delete;
    Session& operator=(const Session&) = delete;
    Status setSize(QSize size, bool withAov) { return renderer.setSize(size, withAov); }
    FrameCamera frameCamera(const Model& m) const {
        const QSize size = renderer.size();
        FrameCamera fc =
            kw::frameCamera(m.camera, m.doc.scene(), double(size.width()) / double(size.height()));
        fc.viewport = glm::ivec2(size.width(), size.height());
        return fc;
    }
    /// Exact or baseline frame of the model at `partitions`.
    Status drawRenderer(const Model& m, RenderMode mode, int partitions, int lights) {
        RenderOptions o = base;
        o.shading = shading;
        o.mode = mode;
        o.partitionsU = o.partitionsV = partitions;
        o.lightCount = lights;
        o.trims = trims;
        o.polygonOverTrims = trims; // --no-trims draws whole domains
        o.trimMode = trimMode;
        o.samples = aaSamples;
        o.antialiasing = aaMethod;
        return renderer.render(m.doc, m.camera, o);
    }
    /// The comparison mesh in `slot` drawn by the renderer with the model's camera and lights
    /// (cleared as the renderer clears, the baseline's Gouraud shading).
    Status drawMesh(int slot, const Model& m, int lights) {
        RenderOptions o;
        o.lightCount = lights;
        return renderer.renderMesh(m.doc, slot, m.camera, o);
    }
    /// One GLU frame: tessellate with the current camera, upload, draw.
    Status drawGlu(const Model& m, double tolerance, int lights, long long* vertices) {
        if (Status made = gluTessellate(m.doc.scene(), frameCamera(m), tolerance, m_gluMesh); !made)
            return made;
        if (vertices)
            *vertices = m_gluMesh.vertexCount();
        m_gluTriangles = m_gluMesh.triangleCount();
        if (renderer.setMesh(kGluSlot, m_gluMesh) < 0)
            return Error(QStringLiteral("lost the OpenGL context"));
        return drawMesh(kGluSlot, m, lights);
    }
    long long gluTriangles() const { return m_gluTriangles; }

    OffscreenRenderer renderer;
    RenderOptions base; ///< BenchConfig::base
    RenderOptions::Shading shading = RenderOptions::Shading::DepthPrepass;
    bool trims = true;
    RenderOptions::TrimMode trimMode = RenderOptions::TrimMode::Exact;
    int aaSamples = 1;
    RenderOptions::Antialiasing aaMethod = RenderOptions::Antialiasing::Accumulate;

private:
    SceneMesh m_gluMesh;
    long long m_gluTriangles = 0;
};

/// Warm-up frames, then `config.frames` timed frames each ended by glFinish. `before(f)`, when
/// given, runs ahead of frame f outside the timer.
Status timeFrames(Session& s, const BenchConfig& config, const Frame& frame, Timing& t,
                  const std::function<void(int)>& before = {}) {
    std::vector<double> ms;
    double cpuStart = 0.0;
    for (int f = 0; f < config.warmup + config.frames; ++f) {
        if (f == config.warmup)
            cpuStart = processCpuMs();
        if (before)
            before(f);
        QElapsedTimer timer;
        timer.start();
        if (Status drawn = frame(); !drawn)
            return drawn;
        s.renderer.finish();
        if (f >= config.warmup)
            ms.push_back(double(timer.nsecsElapsed()) * 1e-6);
    }
    t.cpuMs = (processCpuMs() - cpuStart) / config.frames;
    std::sort(ms.begin(), ms.end());
    t.minMs = ms.front();
    t.maxMs = ms.back();
    const size_t n = ms.size();
    t.medianMs = n % 2 ? ms[n / 2] : 0.5 * (ms[n / 2 - 1] + ms[n / 2]);
    return ok();
}

/// Draws one frame with AOVs and measures it against the reference frame.
Status measureQuality(Session& s, const Model& m, const AovBuffer& reference, const Frame& frame,
                      Quality& q, AovBuffer* keep) {
    const QSize size = s.renderer.size();
    if (Status sized = s.setSize(size, true); !sized)
        return sized;
    if (Status drawn = frame(); !drawn)
        return drawn;
    AovBuffer aov = s.renderer.aov();
    q.normal = normalError(m.doc.scene(), aov);
    if (reference.width > 0)
        if (Status measured = silhouetteError(aov, reference, q.silhouette); !measured)
            return measured;
    if (keep)
        *keep = std::move(aov);
    return ok();
}

/// Quality and timing of one method: an AOV frame, then the timed frames without AOVs.
Status measure(Session& s, const BenchConfig& config, const Model& m, const AovBuffer& reference,
               const Frame& frame, MethodResult& r) {
    const QSize size = s.renderer.size();
    if (Status measured = measureQuality(s, m, reference, frame, r.quality, nullptr); !measured)
        return measured;
    if (Status sized = s.setSize(size, false); !sized)
        return sized;
    return timeFrames(s, config, frame, r.timing);
}

QString describe(const Model& m, const QString& what, const MethodResult& r) {
    return QStringLiteral("%1 %2: %3 FPS, normal error mean %4 max %5 deg, silhouette max %6 px")
        .arg(m.name, what)
        .arg(r.timing.fps(), 0, 'f', 1)
        .arg(r.quality.normal.meanDegrees, 0, 'g', 3)
        .arg(r.quality.normal.maxDegrees, 0, 'g', 3)
        .arg(r.quality.silhouette.maxPixels, 0, 'f', 1);
}

/// A trim control point of the first trimmed surface to drag: an interior point of a curve of
/// its first loop when one has any, so the loop stays closed; an invalid ref without trims.
/// Otherwise the first curve's start, which measureDrag moves together with the coinciding
/// curve ends (trimPointWithCoincidentEnds; Document refuses a move that opens a loop).
TrimPointRef dragTarget(const Scene& scene) {
    for (const Surface& s : scene.surfaces) {
        if (s.trims.empty() || s.trims.front().curves.empty())
            continue;
        const std::vector<NurbsCurve2>& curves = s.trims.front().curves;
        for (size_t c = 0; c < curves.size(); ++c)
            if (curves[c].points.size() > 2)
                return {s.id, s.trims.front().id, int(c), 1};
        return {s.id, s.trims.front().id, 0, 0};
    }
    return {};
}

/// --trim-drag: times frames that each move `target` a little back and forth (as a drag sends
/// them) so its mask is redrawn every frame; the point is put back afterwards.
Status measureDrag(Session& s, const BenchConfig& config, Model& m, const Frame& frame,
                   const TrimPointRef& target, TrimDrag& drag) {
    const Surface* surface = m.doc.surface(target.surface);
    const std::vector<NurbsCurve2>& curves = surface->trims.front().curves;
    const glm::dvec2 home = curves[size_t(target.curve)].points[size_t(target.index)];
    // A curve end moves with the coinciding curve ends, as the UV editor moves it.
    const std::vector<TrimPointRef> refs = trimPointWithCoincidentEnds(*surface, target);
    bool refused = false;
    const auto moveTo = [&](glm::dvec2 p) {
        refused = !m.doc.setTrimPoints(refs, std::vector<glm::dvec2>(refs.size(), p)) || refused;
    };
    const Interval du = surfaceDomainU(surface->geometry);
    TrimMaskStats masks; // of the timed frames, from their FrameReports
    const auto move = [&](int f) {
        if (f > 0)
            masks += s.renderer.lastReport().masks;
        const double step = (f % 2 ? -1.0 : 1.0) * 1e-3 * (du.last - du.first);
        moveTo(home + glm::dvec2(step, 0.5 * step));
    };
    Timing t;
    const Status timed = timeFrames(s, config, frame, t, move);
    masks += s.renderer.lastReport().masks;
    moveTo(home);
    if (!timed)
        return timed;
    if (refused)
        return Error(QStringLiteral("%1: the trim drag's point move was refused").arg(m.name));
    drag.medianMs = t.medianMs;
    drag.maskCpuMs =
        masks.redraws ? double(masks.cpuNanoseconds) * 1e-6 / double(masks.redraws) : 0.0;
    drag.maskSide = masks.largestSide;
    return ok();
}

Status runTable1(Session& s, const BenchConfig& config, BenchReport& report,
                 const std::function<void(const QString&)>& progress) {
    for (const QString& file : config.table1Files) {
        Model m;
        if (Status loaded = loadModel(file, 1.0, m); !loaded)
            return loaded;
        for (int side : config.sizes) {
            Table1Row row;
            row.model = m.name;
            row.surfaces = int(m.doc.scene().surfaces.size());
            row.side = side;
            AovBuffer reference;
            if (Status sized = s.setSize(QSize(side, side), true); !sized)
                return sized;
            if (Status drawn =
                    s.drawRenderer(m, RenderMode::Exact, config.referencePartitions, config.lights);
                !drawn)
                return drawn;
            reference = s.renderer.aov();
            MethodResult r;
            AovBuffer aov;
            const Frame exact = [&] {
                return s.drawRenderer(m, config.table1Mode, config.table1Partitions, config.lights);
            };
            if (Status measured = measureQuality(s, m, reference, exact, r.quality, &aov);
                !measured)
                return measured;
            if (Status sized = s.setSize(QSize(side, side), false); !sized)
                return sized;
            if (Status timed = timeFrames(s, config, exact, r.timing); !timed)
                return timed;
            long long covered = 0;
            for (int k = 0; k < aov.width * aov.height; ++k)
                covered += aov.data[size_t(k) * AovBuffer::kChannels] >= 0.0f ? 1 : 0;
            row.coverage = double(covered) / double(std::max(1, aov.width * aov.height));
            row.timing = r.timing;
            row.quality = r.quality;
            progress(describe(m,
                              QStringLiteral("%1x%1 %3 %2x%2")
                                  .arg(side)
                                  .arg(config.table1Partitions)
                                  .arg(config.table1Mode == RenderMode::Exact
                                           ? QStringLiteral("exact")
                                           : QStringLiteral("tessellated")),
                              r));
            if (const TrimPointRef target = dragTarget(m.doc.scene());
                config.trimDrag && config.trims && target.surface.isValid()) {
                TrimDrag drag;
                if (Status measured = measureDrag(s, config, m, exact, target, drag); !measured)
                    return measured;
                row.drag = drag;
                progress(QStringLiteral("%1 %2x%2 trim drag: %3 ms/frame, mask redraw %4 CPU ms, "
                                        "mask side %5")
                             .arg(m.name)
                             .arg(side)
                             .arg(drag.medianMs, 0, 'f', 2)
                             .arg(drag.maskCpuMs, 0, 'f', 2)
                             .arg(drag.maskSide));
            }
            report.table1.push_back(row);
        }
    }
    return ok();
}

/// One density or tolerance tried by an equal-quality search.
struct SearchPoint {
    Quality quality;
    long long vertices = 0;
    long long triangles = 0;
};

Status runTable2Model(Session& s, const BenchConfig& config, const QString& file,
                      BenchReport& report, const std::function<void(const QString&)>& progress) {
    const QSize size = config.table2Size;
    Model m;
    if (Status loaded = loadModel(file, double(size.width()) / double(size.height()), m); !loaded)
        return loaded;
    const Scene& scene = m.doc.scene();
    const long long surfaces = (long long)scene.surfaces.size();
    if (Status sized = s.setSize(size, true); !sized)
        return sized;
    if (Status drawn =
            s.drawRenderer(m, RenderMode::Exact, config.referencePartitions, config.lights);
        !drawn)
        return drawn;
    const AovBuffer reference = s.renderer.aov();

    // The fine mesh and the GLU tessellation do not depend on the row's partitions: each
    // density or tolerance is measured once per model.
    std::map<int, SearchPoint> fineSeen;
    std::map<double, SearchPoint> gluSeen;
    int fineUploaded = -1;
    auto uploadFine = [&](int n) {
        if (n == fineUploaded)
            return;
        const SceneMesh mesh = uniformSceneMesh(scene, n, n);
        s.renderer.setMesh(Session::kFineSlot, mesh);
        fineUploaded = n;
    };
    const Frame fineFrame = [&] {
        return s.drawMesh(Session::kFineSlot, m, config.lights);
    };
    auto fineQuality = [&](int n, SearchPoint& sp) -> Status {
        if (auto it = fineSeen.find(n); it != fineSeen.end()) {
            sp = it->second;
            return ok();
        }
        uploadFine(n);
        sp.vertices = (long long)(n + 1) * (n + 1) * surfaces;
        sp.triangles = 2LL * n * n * surfaces;
        if (Status measured = measureQuality(s, m, reference, fineFrame, sp.quality, nullptr);
            !measured)
            return measured;
        fineSeen[n] = sp;
        return ok();
    };
    auto gluQuality = [&](double t, SearchPoint& sp) -> Status {
        if (auto it = gluSeen.find(t); it != gluSeen.end()) {
            sp = it->second;
            return ok();
        }
        const Frame frame = [&] {
            return s.drawGlu(m, t, config.lights, &sp.vertices);
        };
        if (Status measured = measureQuality(s, m, reference, frame, sp.quality, nullptr);
            !measured)
            return measured;
        sp.triangles = s.gluTriangles();
        gluSeen[t] = sp;
        return ok();
    };

    for (int p : config.partitions) {
        Table2Row row;
        row.model = m.name;
        row.surfaces = int(surfaces);
        row.partitions = p;
        for (auto [mode, result] : {std::pair{RenderMode::Exact, &row.exact},
                                    std::pair{RenderMode::Tessellated, &row.baseline}}) {
            const Frame frame = [&, mode = mode] {
                return s.drawRenderer(m, mode, p, config.lights);
            };
            result->parameter = p;
            result->triangles = 2LL * p * p * surfaces;
            if (Status sized = s.setSize(size, false); !sized)
                return sized;
            if (Status measured = measure(s, config, m, reference, frame, *result); !measured)
                return measured;
            progress(describe(m,
                              QStringLiteral("%1 %2x%2")
                                  .arg(mode == RenderMode::Exact ? QStringLiteral("exact")
                                                                 : QStringLiteral("baseline"),
                                       QString::number(p)),
                              *result));
        }
        const double target =
            std::max(row.exact.quality.normal.maxDegrees, config.normalFloorDegrees);
        row.targetMaxDegrees = target;

        // (b) Fine mesh: density doubled from the row's partitions until its max normal error
        // is no worse than the target, or the vertex budget is spent; then bisected between the
        // last density that failed and the first that passed, so the mesh is the smallest of
        // equal quality found (the fairest opponent), whatever the row's starting point.
        int n = p, failed = 0;
        SearchPoint sp;
        for (;;) {
            if (Status measured = fineQuality(n, sp); !measured)
                return measured;
            row.fine.matched = sp.quality.normal.maxDegrees <= target;
            if (row.fine.matched ||
                (long long)(2 * n + 1) * (2 * n + 1) * surfaces > config.fineMaxVertices)
                break;
            failed = n;
            n *= 2;
        }
        while (row.fine.matched && failed > 0 && n - failed > std::max(1, n / 16)) {
            const int mid = (failed + n) / 2;
            SearchPoint midPoint;
            if (Status measured = fineQuality(mid, midPoint); !measured)
                return measured;
            if (midPoint.quality.normal.maxDegrees <= target) {
                n = mid;
                sp = midPoint;
            } else {
                failed = mid;
            }
        }
        row.fine.parameter = n;
        row.fine.triangles = sp.triangles;
        row.fine.quality = sp.quality;
        uploadFine(n);
        if (Status sized = s.setSize(size, false); !sized)
            return sized;
        if (Status timed = timeFrames(s, config, fineFrame, row.fine.timing); !timed)
            return timed;
        progress(describe(m,
                          QStringLiteral("fine mesh %1x%1%2")
                              .arg(n)
                              .arg(row.fine.matched ? QString() : QStringLiteral(" (not matched)")),
                          row.fine));

        // (c) GLU: sampling tolerance halved from GLU's default 50 px.
        double t = 50.0;
        for (;;) {
            if (Status measured = gluQuality(t, sp); !measured)
                return measured;
            row.glu.matched = sp.quality.normal.maxDegrees <= target;
            if (row.glu.matched || t * 0.5 < config.gluMinTolerance ||
                sp.vertices * 4 > config.gluMaxVertices)
                break;
            t *= 0.5;
        }
        row.glu.parameter = t;
        row.glu.triangles = sp.triangles;
        row.glu.quality = sp.quality;
        const Frame gluFrame = [&] {
            return s.drawGlu(m, t, config.lights, nullptr);
        };
        if (Status sized = s.setSize(size, false); !sized)
            return sized;
        if (Status timed = timeFrames(s, config, gluFrame, row.glu.timing); !timed)
            return timed;
        progress(describe(m,
                          QStringLiteral("GLU tolerance %1 px%2")
                              .arg(t)
                              .arg(row.glu.matched ? QString() : QStringLiteral(" (not matched)")),
                          row.glu));
        report.table2.push_back(row);
    }
    return ok();
}

} // namespace

Status runBench(const BenchConfig& config, BenchReport& report,
                const std::function<void(const QString&)>& progress) {
    report = BenchReport{};
    report.config = config;
    report.cpu = cpuModel();
    report.threads = QThread::idealThreadCount();
    Session s;
    s.base = config.base;
    s.shading = config.shading;
    s.trims = config.trims;
    s.trimMode = config.trimMode;
    s.aaSamples = config.aaSamples;
    s.aaMethod = config.aaMethod;
    if (Status created = s.renderer.create(); !created)
        return created;
    report.gl = s.renderer.renderer().glDescription();
    if (Status done = runTable1(s, config, report, progress); !done)
        return done;
    for (const QString& file : config.table2Files)
        if (Status done = runTable2Model(s, config, file, report, progress); !done)
            return done;
    return ok();
}

} // namespace kw::bench
