// knotwork bench --tables scale: one real trimmed part tiled from 1 copy up to >= 10,000 faces
// (docs/PERFORMANCE.md ## Scale). Plain result structs; bench_report writes them.
#pragma once

#include "bench/bench_runner.h"
#include "model/document/scene.h"
#include "model/error.h"

#include <QString>
#include <functional>
#include <vector>

namespace kw::bench {

struct ScaleConfig {
    /// The part to tile: a .knot file, or IGES/STEP/BREP converted first by `knotwork convert`
    /// (the executable next to knotwork-bench, so OpenCASCADE is never loaded here).
    QString model;
    /// Face counts to reach; row k tiles copiesForFaces(unit faces, faces[k]) copies.
    std::vector<int> faces;
    int side = 1024; ///< image width
    int height = 0;  ///< image height; 0: side (square)
    int frameHeight() const { return height > 0 ? height : side; }
    int frames = 20;    ///< timed frames per view (medians)
    int warmup = 3;     ///< untimed frames first
    int dragSteps = 20; ///< control-point moves timed per row
    bool trims = true;
    /// What every frame starts from: the development switches (BenchConfig::base).
    RenderOptions base;
    /// How the base polygons are partitioned: the paper's uniform grid by default, or the
    /// editor's adaptive mode; `partitions` > 0 overrides every surface's own (the minimum in
    /// adaptive mode).
    RenderOptions::Partitioning partitioning = RenderOptions::Partitioning::Uniform;
    int partitions = 0;
};

/// One view's frames: wall and process CPU (all threads, llvmpipe rasterises on its own), and
/// the CPU the renderer's call itself took on the calling thread (sync and issuing the draws,
/// without waiting for the GPU).
struct ScaleView {
    Timing timing;
    double renderCallMs = 0.0; ///< median thread CPU ms of OffscreenRenderer::render
};

struct ScaleRow {
    int copies = 0;
    int faces = 0;
    double loadSeconds = 0.0;       ///< reading the tiled .knot into a Document
    double firstFrameSeconds = 0.0; ///< first frame (every upload) to glFinish, fitted view
    double residentMiB = 0.0;       ///< process VmRSS after the first frame
    long long gpuBytes = 0;         ///< FrameReport::gpuBytes.total() after the first frame
    int drawCalls = 0;              ///< FrameReport::drawCalls of a fitted frame
    ScaleView fitted, closeUp;
    /// Median thread CPU ms from moving one control point (Document::setControlPoints, what a
    /// drag step does) to the end of the render call that issues the frame's draws.
    double dragStepMs = 0.0;
    /// Median thread CPU ms of the same steps from the edit to the first surface draw call:
    /// the edit (with the document's signals) plus FrameTimes::beforeDraws of its frame (sync,
    /// uploads, partition choices, masks, culling, batching). The drag target.
    double dragToDrawMs = 0.0;
    /// Empty, or why frames were not drawn as asked (e.g. trimmed surfaces beyond the GPU's
    /// mask layers drawn untrimmed); the numbers are those of the frames as drawn.
    QString warning;
};

struct ScaleReport {
    QString model;       ///< file name of the tiled part
    int unitFaces = 0;   ///< surfaces of one copy
    int unitTrimmed = 0; ///< of which trimmed
    ScaleConfig config;
    std::vector<ScaleRow> rows;
};

/// Runs the table (rows in the order of config.faces) in the current process: needs a
/// QGuiApplication whose default format is OffscreenRenderer::requiredFormat(). Tiled models
/// are written to a temporary folder and read back, as a user would open them. Returns the
/// first failure (unreadable model, conversion failure, GL error).
Status runScale(const ScaleConfig& config, ScaleReport& report,
                const std::function<void(const QString&)>& progress);

} // namespace kw::bench
