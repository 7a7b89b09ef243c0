// Image quality of one rendered frame, measured from its AOV buffer: normal-angle error against
// the CPU kernel and silhouette error against a reference frame.
#pragma once

#include "model/document/scene.h"
#include "model/error.h"
#include "render/offscreen_renderer.h"

namespace kw::bench {

/// Angle between the normal a frame shows at a pixel and the kernel's normal
/// (kw::surfaceFrame) at the (u, v) that pixel shows, over every covered pixel.
struct NormalError {
    double meanDegrees = 0.0;
    double maxDegrees = 0.0;
    long long pixels = 0; ///< covered pixels measured
};

/// `aov` must come from a frame of `scene` (surface ids in channel 0). Pixels whose id names no
/// surface of `scene`, or whose normal is not finite and non-zero, are counted as 180 degrees
/// (a broken pixel must not look good). An empty frame gives pixels == 0 and zero errors.
NormalError normalError(const Scene& scene, const AovBuffer& aov);

/// Coverage masks compared pixel by pixel with a reference frame of the same size. The
/// reference silhouette is the set of covered reference pixels with an uncovered 4-neighbour
/// (or on the image border). Each mismatching pixel (covered in one frame only) is scored by the
/// Euclidean distance, in pixels, from its centre to the nearest reference silhouette pixel
/// centre: 0 on the reference silhouette, 1 right beside it.
struct SilhouetteError {
    long long mismatched = 0;       ///< pixels covered in exactly one of the two frames
    long long silhouettePixels = 0; ///< length of the reference silhouette in pixels
    double meanPixels = 0.0;        ///< mean distance of the mismatching pixels (0 when none)
    double maxPixels = 0.0;         ///< largest distance (0 when none)
    /// mismatched / silhouettePixels: the average thickness of the error band along the
    /// silhouette, in pixels (0 when the reference has no silhouette and nothing mismatches).
    double perSilhouettePixel = 0.0;
};

/// Both buffers must have the same non-zero size; the error says so otherwise.
Status silhouetteError(const AovBuffer& frame, const AovBuffer& reference, SilhouetteError& out);

} // namespace kw::bench
