// knotwork bench --drag-step: what the Edge Continuity overlay adds to one control-point drag
// step. A step with the overlay on: the edit, the dragged face's edges re-measured, their band
// lines re-made, the bands uploaded and the frame drawn to glFinish; off: the edit, the same
// edges re-measured for the status bar's "opens N seams" and the frame. Both alternate step by
// step on one drag path (docs/PERFORMANCE.md ## Editing).
#pragma once

#include "bench/loop_runner.h"
#include "render/render_types.h"

#include <QJsonArray>
#include <QString>
#include <QStringList>
#include <functional>
#include <vector>

namespace kw::bench {

struct DragStepConfig {
    QStringList files;
    /// Per file, the models measured: 0 the file as read, N > 0 the file tiled (the scale
    /// table's grid, its shared-edge record copied with it) up to at least N faces.
    std::vector<int> faces{0};
    int steps = 30;  ///< timed steps per overlay state, >= 1
    int side = 1024; ///< square frame side
    int lights = 2;
    bool overlayOn = true, overlayOff = true; ///< --continuity-overlay on | off | both
    RenderOptions base;                       ///< the development switches, else the defaults
};

/// Medians over the steps of one overlay state, milliseconds.
struct DragStepTiming {
    bool measured = false;
    double ms = 0.0, cpuMs = 0.0; ///< edit to finished frame: wall, process CPU
    double continuityMs = 0.0;    ///< thread CPU: the dragged face's edges re-measured
    double bandsMs = 0.0;         ///< thread CPU: their band lines re-made (on only)
    long long bandVertices = 0;   ///< vertices uploaded per step (on only)
};

struct DragStepRow {
    QString model; ///< file name, with "tiled x N" for a tiled model
    int surfaces = 0;
    int copies = 1;
    QString face;       ///< the dragged face's name and id
    int faceEdges = 0;  ///< shared edges of the dragged face (re-measured per step)
    int edges = 0;      ///< shared edges of the model
    double setupMs = 0; ///< turning the overlay on: every edge measured and its bands made
    /// Overlay off: the edges paired (continuityWatch), which the editor does on a pool thread
    /// after each change of the faces, never in a drag step.
    double pairingMs = 0;
    QString opens; ///< the status bar's text at the drag's farthest point
    DragStepTiming on, off;
};

struct DragStepReport {
    LoopMachine machine;
    DragStepConfig config;
    std::vector<DragStepRow> rows;
};

/// Runs every file at every config.faces (read as `render` reads them). Needs a QGuiApplication
/// whose default format is OffscreenRenderer::requiredFormat(). Returns the first failure
/// (unreadable file, a model without surfaces, a refused edit, a GL error).
Status runDragStep(const DragStepConfig& config, DragStepReport& report,
                   const std::function<void(const QString&)>& progress);

/// The rows as JSON objects: model, surfaces, copies, face, faceEdges, edges, steps, side,
/// setupMs, pairingMs, opens, "overlayOn" and "overlayOff" ({ms, cpuMs, continuityMs, bandsMs,
/// bandVertices}, present when measured) and ratio (on / off wall ms, 0 unless both ran).
QJsonArray dragStepJson(const DragStepReport& report);
/// The table as GitHub markdown, with the command and the machine.
QString dragStepMarkdown(const DragStepReport& report, const QString& command);

} // namespace kw::bench
