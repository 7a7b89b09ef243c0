// knotwork bench --zoom-loop: the close-up. At 8x and 64x on a contour, the mesh the peer made for
// the fitted view no longer meets equal quality, so the peer must re-mesh the faces in view;
// Knotwork draws the same exact pixels at any zoom. Times to the first correct close-up frame,
// and the memory each method holds for that view (docs/PERFORMANCE.md ## Close-up).
#pragma once

#include "bench/loop_runner.h"
#include "render/render_types.h"

#include <QJsonArray>
#include <QString>
#include <QStringList>
#include <functional>
#include <vector>

namespace kw::bench {

struct ZoomLoopConfig {
    QStringList files;
    std::vector<double> zooms{8.0, 64.0}; ///< each > 1: the fitted view's distance over it
    int repeats = 5;                      ///< timed transitions per method and zoom
    int side = 1024;                      ///< square frame side
    int lights = 2;
    double normalP99Floor = 0.1;        ///< the equal-quality bar (as --edit-loop's)
    long long maxTriangles = 8'000'000; ///< the search stops refining past this
    RenderOptions base;                 ///< the development switches, else the defaults
};

/// One model at one zoom. Times are medians over the repeats, milliseconds, from the camera's
/// move to the finished frame (glFinish); the peer's include re-meshing the faces in view in
/// its CAD child (its own time; the hand-over is not counted, as a viewer with OCCT in process
/// has none), re-sending them and drawing.
struct ZoomLoopRow {
    QString model;
    QString target; ///< what the close-up looks at: "contour of A"
    double zoom = 1.0;
    int facesInView = 0; ///< faces covering a pixel of the close-up (the peer re-meshes these)
    double knotworkMs = 0.0, knotworkCpuMs = 0.0;
    /// The same close-up drawn once more with every buffer in place: the frame alone, which
    /// no first frame at that view can beat (the floor of knotworkMs).
    double knotworkAgainMs = 0.0, knotworkAgainCpuMs = 0.0;
    double peerMs = 0.0, peerCpuMs = 0.0, peerMeshMs = 0.0;
    bool peerMatched = true; ///< the search reached equal quality at this zoom
    double peerLinear = 0.0, peerAngular = 0.0;
    long long peerTriangles = 0;          ///< the faces in view at the close-up's deflections
    long long fittedTriangles = 0;        ///< the whole model at the fitted view's equal quality
    double fittedMeshSilhouetteMax = 0.0; ///< the fitted view's mesh seen at this zoom, px
    double fittedMeshNormalP99 = 0.0;     ///< and its normal error p99, degrees
    /// The fitted view's mesh still meets equal quality at this zoom: the peer only draws it.
    bool fittedMeshGood = false;
    double knotworkNormalP99 = 0.0, knotworkSilhouetteMax = 0.0;
    double peerNormalP99 = 0.0, peerSilhouetteMax = 0.0;
    /// Memory each method holds for this view, MiB; neither counts the colour and depth target
    /// both draw into. Knotwork: its GPU buffers and textures (FrameReport::gpuBytes, frame
    /// targets excluded), and on the host the exact geometry and the renderer's CPU copies
    /// (FrameReport::hostCopyBytes). The peer: the triangles on the GPU (as sent), and on the
    /// host the triangles as OpenCASCADE holds them in the B-rep (Poly_Triangulation: double
    /// nodes and uv, float normals, int triangles) and the exact geometry it re-meshes from
    /// (counted as Knotwork's).
    double knotworkGpuMiB = 0.0, knotworkCpuMiB = 0.0;
    double peerGpuMiB = 0.0, peerCpuMiB = 0.0;
};

struct ZoomLoopReport {
    LoopMachine machine;
    ZoomLoopConfig config;
    std::vector<ZoomLoopRow> rows;
};

/// Runs the close-ups of every file. Needs what runEditLoop needs (a GL application and the
/// knotwork executable's `__mesh-faces` child). The first failure ends it and is returned.
Status runZoomLoop(const ZoomLoopConfig& config, ZoomLoopReport& report,
                   const std::function<void(const QString&)>& progress);

QJsonArray zoomLoopJson(const ZoomLoopReport& report);
/// The table as GitHub markdown, with the machine.
QString zoomLoopMarkdown(const ZoomLoopReport& report, const QString& command);

} // namespace kw::bench
