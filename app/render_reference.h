// knotwork render --reference / --edge-report: the CPU reference frame and the edge metrics.
#pragma once

#include "model/document/scene.h"
#include "model/error.h"
#include "render/aov_buffer.h"

#include <QSize>
#include <QString>

namespace kw::cli {

/// Renders the CPU reference (render/reference_render.h) of `scene` seen by `camera` and writes
/// its Phong image to outPath and, when aovPath is not empty, its AOVs. Prints a one-line
/// summary with the reference's statistics on stdout. The error of a failed write.
Status writeReferenceRender(const Scene& scene, const Camera& camera, QSize size, int lightCount,
                            const QString& outPath, const QString& aovPath);

/// Compares the GPU frame's AOVs with the CPU reference of the same view (edge_metrics.h), writes
/// the metrics as JSON to jsonPath (atomically; "-" prints them on stdout) and a one-line summary
/// on stdout. Depth tolerance: 1e-4 of the scene's control bounds diagonal. The error of a
/// failed comparison or write.
Status writeEdgeReport(const Scene& scene, const Camera& camera, const AovBuffer& gpu,
                       const QString& jsonPath);

} // namespace kw::cli
