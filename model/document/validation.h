// The one notion of a valid scene: Document, the .knot reader, every importer and every writer
// check with these functions, so nothing Knotwork accepts or writes fails to reopen
// (docs/FILE_FORMAT.md states the same rules). Each returns ok() when valid, else an Error with
// the reason in plain English.
#pragma once

#include "model/document/scene.h"
#include "model/error.h"

#include <QString>
#include <glm/glm.hpp>
#include <vector>

namespace kw {

/// Limits of a valid scene; larger data is refused as corrupt, not attempted.
constexpr long long kMaxControlPoints = 4'000'000; ///< countU * countV of one surface
constexpr int kMaxCurvePoints = 100'000;           ///< control points of one trim curve
constexpr int kMaxTrimLoops = 10'000;              ///< loops of one surface
constexpr int kMaxLoopCurves = 10'000;             ///< curves of one loop
constexpr int kMaxSurfaces = 100'000;              ///< surfaces of one scene
/// Material and light ranges (docs/FILE_FORMAT.md): colour and coefficients in [0, 1],
/// shininess in [0, kMaxShininess], light intensities in [0, kMaxLightIntensity].
constexpr double kMaxShininess = 1e4;
constexpr double kMaxLightIntensity = 1e3;

/// Both counts in [kMinPartitions, kMaxPartitions].
Status checkPartitions(int nu, int nv);
/// Colour components, ka, kd and ks in [0, 1]; shininess in [0, kMaxShininess].
Status checkMaterial(const Material& material);
/// Known kind; vector finite (non-zero for a directional light); intensities in
/// [0, kMaxLightIntensity].
Status checkLight(const Light& light);
/// 0..kMaxLights lights (none: the scene is unlit), each valid.
Status checkLights(const std::vector<Light>& lights);
/// Finite eye, target and up; eye != target; up not zero and not parallel to the view
/// direction; fovYDegrees in (0, 180).
Status checkCamera(const Camera& camera);
/// A mode other than "", "adaptive" or "uniform", or a tolerance outside
/// [kMinPixelTolerance, kMaxPixelTolerance].
Status checkDisplay(const DisplaySettings& display);

/// The largest distance at which consecutive curves of a loop still meet: 1e-9 times the
/// largest control point coordinate magnitude of the loop, at least 1e-9.
double trimLoopClosureTolerance(const TrimLoop& loop);
/// Where a loop is open: the index k of the first curve whose start is farther than
/// trimLoopClosureTolerance from the end of curve k - 1 (cyclically; curve 0 is compared with
/// the last curve), with both points; -1 when the loop is closed. Precondition: valid curves.
int trimLoopOpenAt(const TrimLoop& loop, glm::dvec2* start = nullptr, glm::dvec2* end = nullptr);

/// A valid id; 1..kMaxLoopCurves curves, each valid (kw::checkNurbsCurve) with at most
/// kMaxCurvePoints control points; the loop closed (trimLoopOpenAt).
Status checkTrimLoop(const TrimLoop& loop);
/// A valid id, geometry valid (kw::checkNurbsSurface) with at most kMaxControlPoints,
/// partitions in range, material valid, its analytic form valid for its NURBS
/// (kw::checkAnalyticForm; whether the form matches the NURBS is the .knot reader's check), at
/// most kMaxTrimLoops loops, every trim loop valid and loop ids unique within the surface. Ids
/// against other surfaces are the scene's business.
Status checkSurface(const Surface& surface);
/// A whole scene: at most kMaxSurfaces surfaces, each valid; surface and loop ids unique
/// across the scene (one counter) and below nextId; lights valid; the topology's references
/// valid (kw::checkTopology); camera and display settings valid.
Status checkScene(const Scene& scene);

} // namespace kw
