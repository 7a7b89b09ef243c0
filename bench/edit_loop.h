// knotwork bench --edit-loop: one control point dragged through N steps, Knotwork (edit to the
// aliased and to the still frame) against the OpenCASCADE mesh peer, which must rebuild the
// edited face, re-mesh it at equal quality, re-send and draw it (docs/PERFORMANCE.md ## Editing).
#pragma once

#include "bench/loop_runner.h"
#include "render/render_types.h"

#include <QJsonArray>
#include <QString>
#include <QStringList>
#include <functional>
#include <optional>
#include <vector>

namespace kw::bench {

struct EditLoopConfig {
    QStringList files;
    int steps = 50;  ///< drag steps per method, >= 1
    int side = 1024; ///< square frame side
    int lights = 2;
    int stillSamples = 4; ///< the editor's still frame: its automatic anti-aliasing
    /// --peer-deflections: the peer's linear (model units) and angular (degrees) deflections;
    /// unset: searched as tools/peer_search.py searches them.
    std::optional<std::pair<double, double>> peerDeflections;
    /// Equal quality: normal error p99 no worse than max(Knotwork's, this) degrees and
    /// silhouette max no worse than max(Knotwork's, 1) px (peer_search.py's bar).
    double normalP99Floor = 0.1;
    long long maxTriangles = 4'000'000; ///< the search stops refining past this
    RenderOptions base;                 ///< the development switches, else the defaults
    /// --full-frames: the editor's aliased frames drawn whole (RenderOptions::FrameReuse::Full)
    /// instead of partial; the whole-frame column is then the same way.
    bool fullFrames = false;
    /// --pass-times: the editor's aliased frames profiled pass by pass, each pass ended by
    /// glFinish (Renderer::setPassProfiling): their columns then include the waits.
    bool passTimes = false;
};

/// Medians over the steps, milliseconds, wall and process CPU (the peer's CPU includes its
/// child's build and mesh).
struct EditLoopRow {
    QString model;
    int surfaces = 0;
    QString face;         ///< the dragged face's name and id
    bool freeForm = true; ///< false: an analytic face (rational or planar) turned free-form
    /// The editor's aliased frame: partial (RenderOptions::FrameReuse::Partial) unless
    /// --full-frames; then the same frame drawn whole, alternated with it.
    double knotworkMs = 0.0, knotworkCpuMs = 0.0;
    double knotworkFullMs = 0.0, knotworkFullCpuMs = 0.0;
    /// Of the timed editor's frames, those drawn partial, and the medians of their rectangle's
    /// share of the view and of the surfaces it reached.
    int partialFrames = 0;
    double partialArea = 0.0;
    /// Of which the median share of the view the frames redrew (their damage tiles'
    /// rectangles, FrameReport::partialPixels) and the median number of those rectangles.
    double partialRedrawn = 0.0, partialRegions = 0.0;
    double partialSurfaces = 0.0;
    /// Medians of the partial frames' cells drawn (FrameReport::partialCells) and of the
    /// whole frames' (partitions.cells): the partial frame's geometry share.
    double partialCells = 0.0, fullCells = 0.0;
    double knotworkStillMs = 0.0, knotworkStillCpuMs = 0.0;
    /// --pass-times: the editor's aliased frames' medians per pass (PassTimes), wall and
    /// process CPU ms; empty without.
    std::vector<double> passWallMs, passCpuMs;
    double peerMs = 0.0, peerCpuMs = 0.0, peerMeshMs = 0.0;
    double peerDefaultMs = 0.0, peerDefaultCpuMs = 0.0, peerDefaultMeshMs = 0.0;
    long long peerTriangles = 0, peerDefaultTriangles = 0;
    long long peerFaceTriangles = 0; ///< the edited face's, at equal quality (median step)
    double peerLinear = 0.0, peerAngular = 0.0, defaultLinear = 0.0;
    bool deflectionsGiven = false; ///< --peer-deflections (no search, no quality figures)
    bool matched = true;           ///< the search reached equal quality
    double knotworkNormalP99 = 0.0, knotworkSilhouetteMax = 0.0;
    double peerNormalP99 = 0.0, peerSilhouetteMax = 0.0;
};

struct EditLoopReport {
    LoopMachine machine;
    EditLoopConfig config;
    std::vector<EditLoopRow> rows;
};

/// Runs the loop on every file (read as `render` reads it). Needs a QGuiApplication whose
/// default format is OffscreenRenderer::requiredFormat(), and the knotwork executable's
/// `__mesh-faces` child (model/cad/facemesher.h). The first failure ends it and is returned.
Status runEditLoop(const EditLoopConfig& config, EditLoopReport& report,
                   const std::function<void(const QString&)>& progress);

/// The rows as JSON objects: model, knotworkMs, knotworkStillMs, peerMs, peerDefaultMs,
/// peerTriangles and the rest of EditLoopRow.
QJsonArray editLoopJson(const EditLoopReport& report);
/// The table as GitHub markdown, with the machine and the reading of the ratios.
QString editLoopMarkdown(const EditLoopReport& report, const QString& command);

} // namespace kw::bench
