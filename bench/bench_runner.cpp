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

/// A step's Status in the bench's QString* reporting: false with *error set on failure.
bool kept(const Status& step, QString* error) {
    if (!step && error)
        *error = step.message();
    return bool(step);
}

using Frame = std::function<bool(QString*)>;

/// A loaded model: its document (for the renderer) and camera at one aspect.
struct Model {
    QString name;
    Document doc;
    Camera camera;
};

// Read as `knotwork render` reads it (kw::openModelFile): a .knot as saved, IGES, STEP and BREP
// through the CAD reader's child process, OBJ; the import's remarks on stderr.
bool loadModel(const QString& file, double aspect, Model& m, QString* error) {
    std::optional<ImportResult> read = openModelFile(file, *error);
    if (!read)
        return false;
    cli::printImportRemarks(file, read->report);
    const std::optional<Scene> scene = std::move(read->scene);
    if (const Status reset = m.doc.resetScene(*scene); !reset) {
        *error = QStringLiteral("%1: %2").arg(file, reset.message());
        return false;
    }
    if (m.doc.scene().surfaces.empty()) {
        *error = QStringLiteral("%1: the scene has no surfaces to measure").arg(file);
        return false;
    }
    m.name = QFileInfo(file).fileName();
    m.camera = scene->camera.authored ? scene->camera : fitCamera(*scene, aspect);
    return true;
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
    bool create(QString* error) { return kept(renderer.create(), error); }
    bool setSize(QSize size, bool withAov, QString* error) {
        return kept(renderer.setSize(size, withAov), error);
    }
    FrameCamera frameCamera(const Model& m) const {
        const QSize size = renderer.size();
        FrameCamera fc =
            kw::frameCamera(m.camera, m.doc.scene(), double(size.width()) / double(size.height()));
        fc.viewport = glm::ivec2(size.width(), size.height());
        return fc;
    }
    /// Exact or baseline frame of the model at `partitions`.
    bool drawRenderer(const Model& m, RenderMode mode, int partitions, int lights, QString* error) {
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
        return kept(renderer.render(m.doc, m.camera, o), error);
    }
    /// The comparison mesh in `slot` drawn by the renderer with the model's camera and lights
    /// (cleared as the renderer clears, the baseline's Gouraud shading).
    bool drawMesh(int slot, const Model& m, int lights, QString* error) {
        RenderOptions o;
        o.lightCount = lights;
        return kept(renderer.renderMesh(m.doc, slot, m.camera, o), error);
    }
    /// One GLU frame: tessellate with the current camera, upload, draw.
    bool drawGlu(const Model& m, double tolerance, int lights, long long* vertices,
                 QString* error) {
        if (!gluTessellate(m.doc.scene(), frameCamera(m), tolerance, m_gluMesh, error))
            return false;
        if (vertices)
            *vertices = m_gluMesh.vertexCount();
        m_gluTriangles = m_gluMesh.triangleCount();
        if (renderer.setMesh(kGluSlot, m_gluMesh) < 0) {
            *error = QStringLiteral("lost the OpenGL context");
            return false;
        }
        return drawMesh(kGluSlot, m, lights, error);
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
bool timeFrames(Session& s, const BenchConfig& config, const Frame& frame, Timing& t,
                QString* error, const std::function<void(int)>& before = {}) {
    std::vector<double> ms;
    double cpuStart = 0.0;
    for (int f = 0; f < config.warmup + config.frames; ++f) {
        if (f == config.warmup)
            cpuStart = processCpuMs();
        if (before)
            before(f);
        QElapsedTimer timer;
        timer.start();
        if (!frame(error))
            return false;
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
    return true;
}

/// Draws one frame with AOVs and measures it against the reference frame.
bool measureQuality(Session& s, const Model& m, const AovBuffer& reference, const Frame& frame,
                    Quality& q, AovBuffer* keep, QString* error) {
    const QSize size = s.renderer.size();
    if (!s.setSize(size, true, error) || !frame(error))
        return false;
    AovBuffer aov = s.renderer.aov();
    q.normal = normalError(m.doc.scene(), aov);
    if (reference.width > 0 && !silhouetteError(aov, reference, q.silhouette, error))
        return false;
    if (keep)
        *keep = std::move(aov);
    return true;
}

/// Quality and timing of one method: an AOV frame, then the timed frames without AOVs.
bool measure(Session& s, const BenchConfig& config, const Model& m, const AovBuffer& reference,
             const Frame& frame, MethodResult& r, QString* error) {
    const QSize size = s.renderer.size();
    return measureQuality(s, m, reference, frame, r.quality, nullptr, error) &&
           s.setSize(size, false, error) && timeFrames(s, config, frame, r.timing, error);
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
bool measureDrag(Session& s, const BenchConfig& config, Model& m, const Frame& frame,
                 const TrimPointRef& target, TrimDrag& drag, QString* error) {
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
    const bool ok = timeFrames(s, config, frame, t, error, move);
    masks += s.renderer.lastReport().masks;
    moveTo(home);
    if (!ok)
        return false;
    if (refused) {
        *error = QStringLiteral("%1: the trim drag's point move was refused").arg(m.name);
        return false;
    }
    drag.medianMs = t.medianMs;
    drag.maskCpuMs =
        masks.redraws ? double(masks.cpuNanoseconds) * 1e-6 / double(masks.redraws) : 0.0;
    drag.maskSide = masks.largestSide;
    return true;
}

bool runTable1(Session& s, const BenchConfig& config, BenchReport& report,
               const std::function<void(const QString&)>& progress, QString* error) {
    for (const QString& file : config.table1Files) {
        Model m;
        if (!loadModel(file, 1.0, m, error))
            return false;
        for (int side : config.sizes) {
            Table1Row row;
            row.model = m.name;
            row.surfaces = int(m.doc.scene().surfaces.size());
            row.side = side;
            AovBuffer reference;
            if (!s.setSize(QSize(side, side), true, error) ||
                !s.drawRenderer(m, RenderMode::Exact, config.referencePartitions, config.lights,
                                error))
                return false;
            reference = s.renderer.aov();
            MethodResult r;
            AovBuffer aov;
            const Frame exact = [&](QString* e) {
                return s.drawRenderer(m, config.table1Mode, config.table1Partitions, config.lights,
                                      e);
            };
            if (!measureQuality(s, m, reference, exact, r.quality, &aov, error) ||
                !s.setSize(QSize(side, side), false, error) ||
                !timeFrames(s, config, exact, r.timing, error))
                return false;
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
                if (!measureDrag(s, config, m, exact, target, drag, error))
                    return false;
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
    return true;
}

/// One density or tolerance tried by an equal-quality search.
struct SearchPoint {
    Quality quality;
    long long vertices = 0;
    long long triangles = 0;
};

bool runTable2Model(Session& s, const BenchConfig& config, const QString& file, BenchReport& report,
                    const std::function<void(const QString&)>& progress, QString* error) {
    const QSize size = config.table2Size;
    Model m;
    if (!loadModel(file, double(size.width()) / double(size.height()), m, error))
        return false;
    const Scene& scene = m.doc.scene();
    const long long surfaces = (long long)scene.surfaces.size();
    if (!s.setSize(size, true, error) ||
        !s.drawRenderer(m, RenderMode::Exact, config.referencePartitions, config.lights, error))
        return false;
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
    const Frame fineFrame = [&](QString* e) {
        return s.drawMesh(Session::kFineSlot, m, config.lights, e);
    };
    auto fineQuality = [&](int n, SearchPoint& sp) {
        if (auto it = fineSeen.find(n); it != fineSeen.end()) {
            sp = it->second;
            return true;
        }
        uploadFine(n);
        sp.vertices = (long long)(n + 1) * (n + 1) * surfaces;
        sp.triangles = 2LL * n * n * surfaces;
        if (!measureQuality(s, m, reference, fineFrame, sp.quality, nullptr, error))
            return false;
        fineSeen[n] = sp;
        return true;
    };
    auto gluQuality = [&](double t, SearchPoint& sp) {
        if (auto it = gluSeen.find(t); it != gluSeen.end()) {
            sp = it->second;
            return true;
        }
        const Frame frame = [&](QString* e) {
            return s.drawGlu(m, t, config.lights, &sp.vertices, e);
        };
        if (!measureQuality(s, m, reference, frame, sp.quality, nullptr, error))
            return false;
        sp.triangles = s.gluTriangles();
        gluSeen[t] = sp;
        return true;
    };

    for (int p : config.partitions) {
        Table2Row row;
        row.model = m.name;
        row.surfaces = int(surfaces);
        row.partitions = p;
        for (auto [mode, result] : {std::pair{RenderMode::Exact, &row.exact},
                                    std::pair{RenderMode::Tessellated, &row.baseline}}) {
            const Frame frame = [&, mode = mode](QString* e) {
                return s.drawRenderer(m, mode, p, config.lights, e);
            };
            result->parameter = p;
            result->triangles = 2LL * p * p * surfaces;
            if (!s.setSize(size, false, error) ||
                !measure(s, config, m, reference, frame, *result, error))
                return false;
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
            if (!fineQuality(n, sp))
                return false;
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
            if (!fineQuality(mid, midPoint))
                return false;
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
        if (!s.setSize(size, false, error) ||
            !timeFrames(s, config, fineFrame, row.fine.timing, error))
            return false;
        progress(describe(m,
                          QStringLiteral("fine mesh %1x%1%2")
                              .arg(n)
                              .arg(row.fine.matched ? QString() : QStringLiteral(" (not matched)")),
                          row.fine));

        // (c) GLU: sampling tolerance halved from GLU's default 50 px.
        double t = 50.0;
        for (;;) {
            if (!gluQuality(t, sp))
                return false;
            row.glu.matched = sp.quality.normal.maxDegrees <= target;
            if (row.glu.matched || t * 0.5 < config.gluMinTolerance ||
                sp.vertices * 4 > config.gluMaxVertices)
                break;
            t *= 0.5;
        }
        row.glu.parameter = t;
        row.glu.triangles = sp.triangles;
        row.glu.quality = sp.quality;
        const Frame gluFrame = [&](QString* e) {
            return s.drawGlu(m, t, config.lights, nullptr, e);
        };
        if (!s.setSize(size, false, error) ||
            !timeFrames(s, config, gluFrame, row.glu.timing, error))
            return false;
        progress(describe(m,
                          QStringLiteral("GLU tolerance %1 px%2")
                              .arg(t)
                              .arg(row.glu.matched ? QString() : QStringLiteral(" (not matched)")),
                          row.glu));
        report.table2.push_back(row);
    }
    return true;
}

} // namespace

bool runBench(const BenchConfig& config, BenchReport& report,
              const std::function<void(const QString&)>& progress, QString* error) {
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
    if (!s.create(error))
        return false;
    report.gl = s.renderer.renderer().glDescription();
    if (!runTable1(s, config, report, progress, error))
        return false;
    for (const QString& file : config.table2Files)
        if (!runTable2Model(s, config, file, report, progress, error))
            return false;
    return true;
}

} // namespace kw::bench
