// knotwork bench: the measurements behind the paper's Tables 1 and 2, speed and quality side by
// side in one run. Plain result structs; report.h turns them into JSON, markdown, PNG.
#pragma once

#include "bench/bench_quality.h"
#include "model/error.h"

#include <QSize>
#include <QString>
#include <functional>
#include <optional>
#include <vector>

namespace kw::bench {

struct BenchConfig {
    QStringList table1Files; ///< .knot files of Table 1 (exact mode at each size)
    QStringList table2Files; ///< .knot files of Table 2 (exact vs baselines at each partition)
    std::vector<int> sizes;  ///< Table 1 square sizes, each in 1..16384
    std::vector<int>
        partitions;  ///< Table 2 partition counts, each in kMinPartitions..kMaxPartitions
    int frames = 20; ///< timed frames per measurement, >= 1 (the CLI: >= 20, or 2 with --smoke)
    int warmup = 3;  ///< untimed frames first
    int lights = 2;  ///< 1..kMaxLights
    int table1Partitions = 30; ///< exact mode partitions in Table 1
    QSize table2Size{780, 400};
    /// Reference for silhouette error: exact mode at this many partitions (the finest allowed).
    int referencePartitions = 256;
    /// Fine mesh search: densities doubled from the row's partitions (then bisected) up to this
    /// many vertices in the whole scene (beyond, GPU memory and upload time dominate).
    long long fineMaxVertices = 4'000'000;
    /// Equal quality means max normal error <= max(exact mode's, this floor), in degrees.
    /// Exact mode's own max error is float rounding (~1e-3 degrees), which no mesh reaches;
    /// the default, 1/255 rad = 0.2247 degrees, is where a diffuse shade of a unit light changes
    /// by at most one 8-bit level. 0 asks for the strict match.
    double normalFloorDegrees = 0.2247;
    /// Table 1 mode (exact as in the paper; tessellated for comparison) and exact shading way.
    RenderMode table1Mode = RenderMode::Exact;
    RenderOptions::Shading shading = RenderOptions::Shading::DepthPrepass;
    /// False (--no-trims): every renderer frame draws trimmed surfaces over their whole domains.
    bool trims = true;
    /// --trim-mode: exact trims (default) or the trim mask alone, for comparison.
    RenderOptions::TrimMode trimMode = RenderOptions::TrimMode::Exact;
    /// --aa-samples: anti-aliasing samples per pixel of the renderer's timed frames
    /// (RenderOptions::samples; the quality frames read AOVs and are never anti-aliased).
    int aaSamples = 1;
    /// --aa-method: how those samples are drawn (RenderOptions::antialiasing).
    RenderOptions::Antialiasing aaMethod = RenderOptions::Antialiasing::Accumulate;
    /// --trim-drag: each Table 1 row also times frames that each move one trim control point of
    /// the file's first trimmed surface (its mask is redrawn every frame). Needs trims on.
    bool trimDrag = false;
    /// GLU search: sampling tolerance halved from 50 px (GLU's default) down to this.
    double gluMinTolerance = 0.25;
    /// GLU search also stops when one tessellation produces more vertices than this.
    long long gluMaxVertices = 4'000'000;
    /// What every renderer frame starts from: the development switches
    /// (kw::cli::readDevelopmentSwitches), the defaults otherwise.
    RenderOptions base;
};

/// Median, fastest and slowest frame of a run of timed frames, in milliseconds.
struct Timing {
    double medianMs = 0.0, minMs = 0.0, maxMs = 0.0;
    double cpuMs = 0.0; ///< process CPU time per timed frame (all threads)
    double fps() const { return medianMs > 0.0 ? 1000.0 / medianMs : 0.0; }
    double fpsMin() const { return maxMs > 0.0 ? 1000.0 / maxMs : 0.0; }
    double fpsMax() const { return minMs > 0.0 ? 1000.0 / minMs : 0.0; }
};

struct Quality {
    NormalError normal;
    SilhouetteError silhouette;
};

/// Table 1 with --trim-drag: frames that each move one trim control point (see BenchConfig).
struct TrimDrag {
    double medianMs = 0.0;  ///< median frame, mask redrawn every frame
    double maskCpuMs = 0.0; ///< CPU time per mask redraw (flattening + issuing the draws)
    int maskSide = 0;       ///< larger side of the dragged surface's mask, texels
};

struct Table1Row {
    QString model;
    int surfaces = 0;
    int side = 0;
    double coverage = 0.0; ///< fraction of pixels showing a surface
    Timing timing;
    Quality quality;
    /// Set when config.trimDrag and the file has a trimmed surface; empty otherwise.
    std::optional<TrimDrag> drag;
};

/// One method of Table 2 at one partition count.
struct MethodResult {
    Timing timing;
    Quality quality;
    /// Method parameter: partitions (exact, baseline), fine mesh density n (n x n per surface),
    /// GLU sampling tolerance in pixels.
    double parameter = 0.0;
    bool matched = true;     ///< fine / GLU: max normal error <= exact mode's was reached
    long long triangles = 0; ///< triangles drawn per frame (exact: base polygon triangles)
};

struct Table2Row {
    QString model;
    int surfaces = 0;
    int partitions = 0;
    double targetMaxDegrees = 0.0; ///< max normal error the fine mesh and GLU had to reach
    MethodResult exact, baseline, fine, glu;
};

struct BenchReport {
    QString gl;  ///< GL_RENDERER, GL_VERSION
    QString cpu; ///< /proc/cpuinfo model name
    int threads = 0;
    BenchConfig config;
    std::vector<Table1Row> table1;
    std::vector<Table2Row> table2;
};

/// Runs both tables (a table whose file list is empty is skipped) in the current process:
/// needs a QGuiApplication whose default format is OffscreenRenderer::requiredFormat().
/// `progress` receives one line per measurement. Returns the first failure (no GL 4.5
/// context, unreadable or invalid file, GLU error, shader error).
Status runBench(const BenchConfig& config, BenchReport& report,
                const std::function<void(const QString&)>& progress);

} // namespace kw::bench
