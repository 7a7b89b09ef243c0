// kw_analysis_bench [--size N] [--rounds R] FILE.knot...: frame time of every analysis mode
// against plain Phong (docs/PERFORMANCE.md ## Analysis). One off-screen renderer; per file,
// R rounds each drawing every mode once (interleaved, so machine load hits all modes alike),
// glFinish per frame; prints median wall ms and median process CPU ms (all threads: llvmpipe
// rasterises on the CPU) per mode and their ratios to phong, as Markdown. Each mode's first
// frame (shader compile, environment upload) is drawn before timing. Needs OpenGL 4.5 (Xvfb).
#include "model/document.h"
#include "model/knotfile.h"
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
} // namespace

int main(int argc, char** argv) {
    QSurfaceFormat::setDefaultFormat(kw::OffscreenRenderer::requiredFormat());
    QGuiApplication app(argc, argv);
    int side = 1024, rounds = 15;
    QStringList files;
    const QStringList args = app.arguments();
    for (int k = 1; k < args.size(); ++k) {
        if (args[k] == QLatin1String("--size") && k + 1 < args.size())
            side = std::clamp(args[++k].toInt(), 16, 4096);
        else if (args[k] == QLatin1String("--rounds") && k + 1 < args.size())
            rounds = std::clamp(args[++k].toInt(), 1, 1000);
        else
            files << args[k];
    }
    if (files.isEmpty()) {
        std::fprintf(stderr, "usage: kw_analysis_bench [--size N] [--rounds R] FILE.knot...\n");
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
    QString error;
    if (!renderer.create(&error) || !renderer.setSize(QSize(side, side), false, &error)) {
        std::fprintf(stderr, "%s\n", qPrintable(error));
        return 1;
    }
    std::printf("GL: %s; %dx%d, %d rounds\n\n", qPrintable(renderer.renderer().glDescription()),
                side, side, rounds);
    std::printf(
        "| file | mode | wall ms | × phong | CPU ms | × phong |\n|---|---|---|---|---|---|\n");
    for (const QString& file : files) {
        const std::optional<kw::Scene> scene = kw::readKnotFile(file, &error);
        kw::Document doc;
        if (!scene || !doc.resetScene(*scene, &error)) {
            std::fprintf(stderr, "%s: %s\n", qPrintable(file), qPrintable(error));
            return 1;
        }
        const kw::Camera cam = scene->camera.authored ? scene->camera : kw::fitCamera(*scene, 1.0);
        std::vector<std::vector<double>> wall(variants.size()), cpu(variants.size());
        kw::RenderOptions opt;
        for (int r = -1; r < rounds; ++r) // round -1: compile and upload, untimed
            for (size_t v = 0; v < variants.size(); ++v) {
                opt.analysis = variants[v].options;
                QElapsedTimer t;
                t.start();
                const double c0 = cpuMs();
                if (!renderer.render(doc, cam, opt, &error)) {
                    std::fprintf(stderr, "%s: %s\n", qPrintable(file), qPrintable(error));
                    return 1;
                }
                renderer.finish();
                if (r >= 0) {
                    wall[v].push_back(double(t.nsecsElapsed()) * 1e-6);
                    cpu[v].push_back(cpuMs() - c0);
                }
            }
        const double w0 = median(wall[0]), c0 = median(cpu[0]);
        for (size_t v = 0; v < variants.size(); ++v)
            std::printf("| %s | %s | %.1f | %.2f | %.1f | %.2f |\n",
                        qPrintable(QFileInfo(file).fileName()), qPrintable(variants[v].name),
                        median(wall[v]), median(wall[v]) / w0, median(cpu[v]), median(cpu[v]) / c0);
    }
    return 0;
}
