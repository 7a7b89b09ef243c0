// CPU reference frame: per pixel, the visible exact trimmed surface found by ray casting through
// the kernel (no GL), as AOVs and a Phong-shaded image, to measure what the GPU shows against.
#pragma once

#include "model/document/scene.h"
#include "render/aov_buffer.h"

#include <QImage>

namespace kw {

struct ReferenceOptions {
    /// Guaranteed screen distance (pixels) between the fine tessellation that finds each
    /// pixel's candidate surface and the exact surface (render/surface_bound.h). Coverage can
    /// differ from the exact surface's only for pixel centres this close to a silhouette.
    double pixelTolerance = 0.1;
    /// Largest cells per knot span and direction (bounds the work on huge close-ups).
    int maxCellsPerSpan = 256;
    bool trims = true; ///< cut surfaces by their trim loops (model/nurbs/trim.h, even-odd)
    int lightCount = 2;
    glm::vec4 background{0.18f, 0.19f, 0.21f, 1.0f};
};

struct ReferenceStats {
    long long triangles = 0;      ///< fine tessellation triangles rasterised
    long long fragments = 0;      ///< pixel centres covered by them (before the depth test)
    long long pixels = 0;         ///< covered pixels in the result
    long long newtonFailures = 0; ///< pixels kept at the tessellation's (u, v) (no convergence)
    long long unmetSpans = 0;     ///< spans whose tolerance needed more than maxCellsPerSpan
    double milliseconds = 0.0;
};

/// The reference frame of `scene` seen by `camera` (as kw::cameraMatrices builds it) at
/// width x height pixels. Each pixel centre's ray is cast against every valid surface: a
/// fine tessellation, dense enough by spanSecondDerivativeBound that it lies within
/// options.pixelTolerance of the surface on screen, is rasterised with a depth test and trim
/// classification per fragment (trimRegionContains at trimTolerance); the nearest fragment's
/// (u, v) then starts Newton's method on the ray equations a.(S(u,v) - E) = b.(S(u,v) - E) = 0
/// (a, b orthonormal to the ray) on the exact surface. Channels as AovBuffer: id, (u, v), P,
/// N = kw::surfaceFrame's unit normal, Z = eye depth. Invalid surfaces are skipped. Triangles
/// are clipped at the camera's near plane, as the GPU clips (close-ups of faces reaching behind
/// the eye). Precondition: width, height >= 1.
AovBuffer renderReference(const Scene& scene, const Camera& camera, int width, int height,
                          const ReferenceOptions& options = {}, ReferenceStats* stats = nullptr);

/// Phong shading (shaders/phong.glsl, two-sided) of a reference AOV buffer with the scene's
/// materials and lightsFor(scene, camera, lightCount); background elsewhere.
QImage shadeReference(const Scene& scene, const Camera& camera, const AovBuffer& aov,
                      const ReferenceOptions& options = {});

} // namespace kw
