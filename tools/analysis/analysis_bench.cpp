// kw_analysis_bench [--size N] [--rounds R] [--drag points|trims] FILE.knot...: frame time of
// every analysis mode against plain Phong (docs/PERFORMANCE.md ## Analysis). One off-screen
// renderer; per file, R rounds each drawing every mode once (interleaved, so machine load hits
// all modes alike), glFinish per frame; prints median wall ms and median process CPU ms (all
// threads: llvmpipe rasterises on the CPU) per mode and their ratios to phong, as Markdown.
// Each mode's first frame (shader compile, environment upload) is drawn before timing.
// --drag: every frame first moves a control point of the first surface (points) or a trim
// control point of the first trimmed surface (trims) a little back and forth, as an editor
// drag does (colour range held), and the table adds the frame's uploads from its FrameReport.
// A trim curve end moves with the curve ends at the same (u, v) (kw::trimPointWithCoincidentEnds)
// and a move the document refuses stops the benchmark: a frame must time a real edit.
// Needs OpenGL 4.5 (Xvfb).
#include "model/document/document.h"
#include "model/io/knotfile.h"
#include "model/nurbs/nurbs.h"
#include "model/nurbs/trim.h"
#include "render/offscreen_renderer.h"

#include <QElapsedTimer>
#include <QFileInfo>
#include <QGuiApplication>
#include <algorithm>
#include <cstdio>
#include <ctime>
#include <vector>

namespace {
double cpuMs() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}
double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}
struct Variant {
    QString name;
    kw::AnalysisOptions options;
};

enum class Drag { None, Points, Trims };

/// Moves one point of `doc` by a step that alternates in sign with `frame` (a drag's small
/// back-and-forth), so every frame has an edit to upload. False when there is nothing to drag.
class Dragger {
public:
    Dragger(kw::Document& doc, Drag drag) : m_doc(doc), m_drag(drag) {
        const kw::Scene& scene = doc.scene();
        if (drag == Drag::Points && !scene.surfaces.empty()) {
            const kw::Surface& s = scene.surfaces.front();
            m_surface = s.id;
            m_index = s.geometry.index(s.geometry.countU / 2, s.geometry.countV / 2);
            m_home = s.geometry.points[size_t(m_index)];
            glm::dvec3 lo, hi;
            kw::surfaceControlBounds(s.geometry, lo, hi);
            m_step = 1e-3 * glm::length(hi - lo);
            m_ok = true;
        }
        if (drag == Drag::Trims)
            for (const kw::Surface& s : scene.surfaces)
                if (!s.trims.empty() && !s.trims.front().curves.empty()) {
                    const kw::NurbsCurve2& c = s.trims.front().curves.front();
                    // A curve end moves with the curve ends at the same (u, v), as the UV
                    // editor moves it: alone it would open the loop, which Document refuses.
                    m_trims = kw::trimPointWithCoincidentEnds(
                        s, {s.id, s.trims.front().id, 0, c.points.size() > 2 ? 1 : 0});
                    m_trimHome = c.points[size_t(m_trims.front().index)];
                    const kw::Interval du = kw::surfaceDomainU(s.geometry);
                    m_step = 1e-3 * (du.last - du.first);
                    m_ok = true;
                    break;
                }
    }
    ~Dragger() { (void)move(0.0); } // home again; a refusal leaves nothing to undo
    bool ok() const { return m_ok; }
    /// The document's reason when it refused the move: the frame would time an edit that did
    /// not happen.
    kw::Status step(int frame) { return move(frame % 2 ? -m_step : m_step); }

private:
    kw::Status move(double d) {
        if (!m_ok)
            return kw::Error(QStringLiteral("nothing to drag"));
        if (m_drag == Drag::Points)
            return m_doc.setControlPoints(m_surface, {m_index},
                                          {m_home + glm::dvec3(d, 0.5 * d, 0.25 * d)});
        const glm::dvec2 to = m_trimHome + glm::dvec2(d, 0.5 * d);
        return m_doc.setTrimPoints(m_trims, std::vector<glm::dvec2>(m_trims.size(), to));
    }
    kw::Document& m_doc;
    Drag m_drag;
    bool m_ok = false;
    kw::SurfaceId m_surface;
    int m_index = 0;
    glm::dvec3 m_home{0.0};
    std::vector<kw::TrimPointRef> m_trims; ///< the dragged trim point and its coincident ends
    glm::dvec2 m_trimHome{0.0};
    double m_step = 0.0;
};
} // namespace

int main(int argc, char** argv) {
    QSurfaceFormat::setDefaultFormat(kw::OffscreenRenderer::requiredFormat());
    QGuiApplication app(argc, argv);
    int side = 1024, rounds = 15;
    Drag drag = Drag::None;
    QStringList files;
    const QStringList args = app.arguments();
    for (int k = 1; k < args.size(); ++k) {
        if (args[k] == QLatin1String("--size") && k + 1 < args.size())
            side = std::clamp(args[++k].toInt(), 16, 4096);
        else if (args[k] == QLatin1String("--rounds") && k + 1 < args.size())
            rounds = std::clamp(args[++k].toInt(), 1, 1000);
        else if (args[k] == QLatin1String("--drag") && k + 1 < args.size()) {
            const QString what = args[++k];
            drag = what == QLatin1String("points")  ? Drag::Points
                   : what == QLatin1String("trims") ? Drag::Trims
                                                    : Drag::None;
            if (drag == Drag::None) {
                std::fprintf(stderr, "--drag takes points or trims\n");
                return 2;
            }
        } else
            files << args[k];
    }
    if (files.isEmpty()) {
        std::fprintf(stderr, "usage: kw_analysis_bench [--size N] [--rounds R] [--drag "
                             "points|trims] FILE.knot...\n");
        return 2;
    }
    std::vector<Variant> variants;
    for (kw::AnalysisMode m : kw::analysisModes()) {
        kw::AnalysisOptions o;
        o.mode = m;
        variants.push_back({kw::analysisModeName(m), o});
    }
    kw::AnalysisOptions iso;
    iso.isocurves = true;
    variants.push_back({QStringLiteral("isocurves"), iso});
    kw::AnalysisOptions meanIso;
    meanIso.mode = kw::AnalysisMode::Mean;
    meanIso.isocurves = true;
    variants.push_back({QStringLiteral("mean+isocurves"), meanIso});

    kw::OffscreenRenderer renderer;
    kw::Status ready = renderer.create();
    if (ready)
        ready = renderer.setSize(QSize(side, side), false);
    if (!ready) {
        std::fprintf(stderr, "%s\n", qPrintable(ready.message()));
        return 1;
    }
    std::printf("GL: %s; %dx%d, %d rounds\n\n", qPrintable(renderer.renderer().glDescription()),
                side, side, rounds);
    if (drag == Drag::None)
        std::printf(
            "| file | mode | wall ms | × phong | CPU ms | × phong |\n|---|---|---|---|---|---|\n");
    else
        std::printf(
            "| file | mode | drag wall ms | × phong | CPU ms | × phong | upload bytes | "
            "texels | vertex updates | polygon builds | mask redraws |\n|---|---|---|---|---|---|"
            "---|---|---|---|---|\n");
    for (const QString& file : files) {
        const kw::Expected<kw::Scene> scene = kw::readKnotFile(file);
        kw::Document doc;
        const kw::Status reset = scene ? doc.resetScene(*scene) : kw::Status(scene.error());
        if (!reset) {
            std::fprintf(stderr, "%s: %s\n", qPrintable(file), qPrintable(reset.message()));
            return 1;
        }
        const kw::Camera cam = scene->camera.authored ? scene->camera : kw::fitCamera(*scene, 1.0);
        std::vector<std::vector<double>> wall(variants.size()), cpu(variants.size());
        std::vector<kw::UploadStats> uploads(variants.size());
        std::vector<std::int64_t> redraws(variants.size(), 0);
        kw::RenderOptions opt;
        Dragger dragger(doc, drag);
        if (drag != Drag::None && !dragger.ok()) {
            std::printf("| %s | (nothing to drag) |\n", qPrintable(QFileInfo(file).fileName()));
            continue;
        }
        int frame = 0;
        for (int r = -1; r < rounds; ++r) // round -1: compile and upload, untimed
            for (size_t v = 0; v < variants.size(); ++v) {
                opt.analysis = variants[v].options;
                opt.analysis.holdRange = drag != Drag::None; // as the editor during a drag
                QElapsedTimer t;
                t.start();
                const double c0 = cpuMs();
                if (drag != Drag::None)
                    if (const kw::Status moved = dragger.step(frame++); !moved) {
                        std::fprintf(stderr, "%s: the drag's edit was refused (frame %d): %s\n",
                                     qPrintable(file), frame - 1, qPrintable(moved.message()));
                        return 1;
                    }
                if (const kw::Status drawn = renderer.render(doc, cam, opt); !drawn) {
                    std::fprintf(stderr, "%s: %s\n", qPrintable(file), qPrintable(drawn.message()));
                    return 1;
                }
                renderer.finish();
                if (r >= 0) {
                    wall[v].push_back(double(t.nsecsElapsed()) * 1e-6);
                    cpu[v].push_back(cpuMs() - c0);
                    uploads[v] += renderer.lastReport().uploads;
                    redraws[v] += renderer.lastReport().masks.redraws;
                }
            }
        const double w0 = median(wall[0]), c0 = median(cpu[0]);
        for (size_t v = 0; v < variants.size(); ++v) {
            std::printf("| %s | %s | %.1f | %.2f | %.1f | %.2f |",
                        qPrintable(QFileInfo(file).fileName()), qPrintable(variants[v].name),
                        median(wall[v]), median(wall[v]) / w0, median(cpu[v]), median(cpu[v]) / c0);
            if (drag != Drag::None) // per frame, over the timed frames
                std::printf(
                    " %.0f | %.1f | %.1f | %.2f | %.2f |", double(uploads[v].bytes) / rounds,
                    double(uploads[v].texels) / rounds, double(uploads[v].vertexUpdates) / rounds,
                    double(uploads[v].basePolygonBuilds) / rounds, double(redraws[v]) / rounds);
            std::printf("\n");
        }
    }
    return 0;
}
