// knotwork render --reference / --edge-report.
#include "app/render_reference.h"

#include "app/commands.h"
#include "render/edge_metrics.h"
#include "render/image_writer.h"
#include "render/reference_render.h"

#include <QSaveFile>
#include <algorithm>
#include <cerrno>
#include <cmath>

namespace kw::cli {

Status writeReferenceRender(const Scene& scene, const Camera& camera, QSize size, int lightCount,
                            const QString& outPath, const QString& aovPath) {
    ReferenceOptions options;
    options.lightCount = lightCount;
    ReferenceStats stats;
    const AovBuffer aov =
        renderReference(scene, camera, size.width(), size.height(), options, &stats);
    if (Status written = writeColorImage(shadeReference(scene, camera, aov, options), outPath);
        !written)
        return written;
    if (!aovPath.isEmpty())
        if (Status written = writeAovImage(aov, aovPath); !written)
            return written;
    printOut(QStringLiteral("reference: %1 triangles, %2 covered pixels, %3 Newton failures, "
                            "%4 spans over the cell limit, %5 ms\n")
                 .arg(stats.triangles)
                 .arg(stats.pixels)
                 .arg(stats.newtonFailures)
                 .arg(stats.unmetSpans)
                 .arg(stats.milliseconds, 0, 'f', 0));
    return ok();
}

Status writeEdgeReport(const Scene& scene, const Camera& camera, const AovBuffer& gpu,
                       const QString& jsonPath) {
    const AovBuffer reference = renderReference(scene, camera, gpu.width, gpu.height);
    glm::dvec3 lo(0.0), hi(0.0);
    sceneBounds(scene, lo, hi);
    EdgeMetrics m;
    const double pixelAngle =
        2.0 * std::tan(glm::radians(std::clamp(camera.fovYDegrees, 1.0, 170.0)) * 0.5) /
        double(gpu.height);
    if (Status compared = compareWithReference(gpu, reference, 1e-4 * glm::length(hi - lo), m,
                                               pixelAngle, &camera.eye);
        !compared)
        return compared;
    const QByteArray json = edgeMetricsJson(m).toUtf8();
    if (jsonPath == QLatin1String("-")) {
        printOut(QString::fromUtf8(json));
    } else {
        QSaveFile file(jsonPath);
        errno = 0;
        // Flush explicitly: Qt 6.4's QSaveFile::commit() ignores a failed final flush.
        if (!file.open(QIODevice::WriteOnly) || file.write(json) != json.size() || !file.flush() ||
            !file.commit()) {
            const QString reason = file.errorString();
            file.cancelWriting();
            return Error(
                QStringLiteral("%1: cannot write the edge report: %2").arg(jsonPath, reason),
                jsonPath);
        }
    }
    printOut(QStringLiteral(
                 "edges: silhouette mean %1 px max %2 px, %3 crack pixels, %4 id and "
                 "%5 depth disagreements outside the edge band (%9 of the id ones at equal depth), "
                 "normal error mean %6 p99 %7 max %8 deg\n")
                 .arg(m.silhouetteMeanPixels, 0, 'f', 2)
                 .arg(m.silhouetteMaxPixels, 0, 'f', 2)
                 .arg(m.crackPixels)
                 .arg(m.idDisagreements)
                 .arg(m.depthDisagreements)
                 .arg(m.normalMeanDegrees, 0, 'g', 3)
                 .arg(m.normalP99Degrees, 0, 'g', 3)
                 .arg(m.normalMaxDegrees, 0, 'g', 3)
                 .arg(m.idCoincident));
    return ok();
}

} // namespace kw::cli
