// Quality at the edges of a frame measured against a CPU reference frame (reference_render.h):
// silhouette error, crack pixels, visible id / depth disagreement and screen normal error.
#pragma once

#include "model/error.h"
#include "render/aov_buffer.h"

#include <QString>
#include <glm/vec3.hpp>

namespace kw {

struct EdgeMetrics {
    long long pixels = 0;  ///< width x height
    long long covered = 0; ///< frame pixels showing a surface
    long long referenceCovered = 0;

    /// Silhouette error: each pixel covered in exactly one of the two frames, scored by the
    /// Euclidean distance (pixels) from its centre to the nearest reference silhouette pixel
    /// (a covered reference pixel with an uncovered 4-neighbour, or on the border).
    long long silhouetteMismatched = 0;
    double silhouetteMeanPixels = 0.0;
    double silhouetteMaxPixels = 0.0;

    /// Crack pixels: background pixels of the frame in a horizontal or vertical run of at most
    /// 2 background pixels with covered pixels at both ends (the definition, which
    /// needs no reference); crackPixelsCoveredInReference counts those the reference covers
    /// (a true gap of the geometry is not a crack).
    long long crackPixels = 0;
    long long crackPixelsCoveredInReference = 0;

    /// The edge band: pixels within one pixel (8-neighbourhood) of an edge of the reference: a
    /// pixel whose reference id differs (background included), or of the same surface with an
    /// eye depth farther away than a surface within 3 degrees of edge-on would put it (the
    /// surface's silhouette over itself). Outside it:
    long long edgeBandPixels = 0;
    /// Visible surface id differs from the reference. idCoincident counts those of them at the
    /// same depth (within depthTolerance): where two surfaces coincide (touching parts of an
    /// assembly) either is the true surface, and where the frame's depth is exact (adaptive
    /// mode) a wrong face in front is a disagreement not counted there.
    long long idDisagreements = 0;
    long long idCoincident = 0;
    long long depthDisagreements = 0; ///< same id, |Z - Z_ref| > depthTolerance
    double depthTolerance = 0.0;

    /// Screen normal error outside the band where both frames show the same surface: the angle
    /// between the normal shown and the reference's exact normal at the point truly under the
    /// pixel (degrees).
    long long normalPixels = 0;
    double normalMeanDegrees = 0.0;
    double normalP99Degrees = 0.0;
    double normalMaxDegrees = 0.0;

    /// Pixels, edge band included, where both frames show the same surface but the frame's
    /// normal faces the eye from the other side than the reference's: near a fold (a
    /// silhouette) the pixel's ray meets the surface twice, and the frame shows the far,
    /// hidden sheet, which the shading (turned towards the eye) lights as the inside. Counted
    /// where the reference's normal is at least 0.01 (cosine) off edge-on and the frame's point
    /// is not nearer than the reference's (then the reference missed it); needs the eye.
    long long facingDisagreements = 0;
    /// Edge band pixels showing another surface than the reference, farther than it by more
    /// than depthTolerance: a face behind showing through along an edge of the one in front.
    long long bandBehind = 0;
};

/// Ok when `frame` and `reference` have one non-empty size; else the error naming both sizes,
/// opened by `who` ("edge metrics need"): the check before any per-pixel comparison.
Status sameAovSize(const AovBuffer& frame, const AovBuffer& reference, const QString& who);

/// Compares `frame` (e.g. the GPU's AOVs) with `reference` (renderReference of the same scene,
/// camera and size). depthTolerance in model units (>= 0). Returns the error naming the sizes
/// when the two buffers differ in size or are empty.
/// `pixelAngle` is the angle one pixel spans at the image centre (2 tan(fovY / 2) / height), for
/// the band's depth jumps; 0 leaves surfaces' silhouettes over themselves out of the band.
/// `eye` (model space) enables facingDisagreements.
Status compareWithReference(const AovBuffer& frame, const AovBuffer& reference,
                            double depthTolerance, EdgeMetrics& out, double pixelAngle = 0.0,
                            const glm::dvec3* eye = nullptr);

/// Crack pixels of one frame alone (EdgeMetrics::crackPixels).
long long crackPixels(const AovBuffer& frame);

/// The metrics as one JSON object (keys as the member names).
QString edgeMetricsJson(const EdgeMetrics& m);

} // namespace kw
