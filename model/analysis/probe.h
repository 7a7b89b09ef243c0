// The exact point of a surface under a pixel and what it measures: the pick's (u, v) refined in
// double precision onto the pixel's ray, its frame and curvature; distances, angles and radii
// between such points.
#pragma once

#include "model/document/scene.h"

#include <QString>
#include <glm/glm.hpp>
#include <optional>

namespace kw {

/// One probed point of a surface, with its differential geometry (model/nurbs/nurbs_curvature.h).
struct ProbePoint {
    SurfaceId surface;
    QString name;
    glm::dvec2 uv{0.0};
    glm::dvec3 point{0.0};
    glm::dvec3 normal{0.0, 0.0, 1.0}; ///< unit, along Su x Sv
    double gaussian = 0.0;            ///< K
    double mean = 0.0;                ///< H (positive where convex seen along the normal)
    double k1 = 0.0, k2 = 0.0;        ///< principal curvatures, k1 >= k2
    /// Distance from the point to the ray it was refined onto (0 up to rounding when the
    /// refinement converged; the pick's own point when it could not).
    double rayDistance = 0.0;
    int iterations = 0;
};

/// Radius of curvature 1/|k|; +infinity for k = 0 (a straight direction).
double curvatureRadius(double k);

/// Refines `uvGuess` (the pick's (u, v), float precision) to the point of `surface` on the ray
/// origin + t direction (direction unit length): Newton's iteration on the two components of
/// S(u, v) - origin across the ray, (u, v) clamped to the domain, a halved step whenever the
/// distance to the ray grows (a silhouette, where the ray only grazes the surface). Stops when
/// the distance no longer falls by a step; keeps the best point seen. Then K, H, k1, k2 and the
/// normal at it (surfaceCurvature). Returns nullopt for an invalid surface or non-finite input.
/// Cost: a few surface evaluations, microseconds.
std::optional<ProbePoint> probeOnRay(const Surface& surface, glm::dvec2 uvGuess,
                                     const glm::dvec3& origin, const glm::dvec3& direction);

/// The values as lines of "name: value" text, for the probe panel and the clipboard: surface,
/// (u, v), x y z, normal, K, H, k1, k2 and the two radii (“∞” for a straight direction).
/// `unit` (a length unit's key, "mm") follows every length, and 1/unit every curvature.
QString probeText(const ProbePoint& p, const QString& unit = QString());

/// A measurement between probed points, shown as a dimension in the view.
struct Measurement {
    enum class Kind { Distance, Angle, Radius };
    Kind kind = Kind::Distance;
    ProbePoint a;
    ProbePoint b; ///< unused for Radius
    /// Angle only: both points lie on plane faces (kw::surfaceType), so the angle between the
    /// normals is the angle between the faces themselves.
    bool betweenPlanes = false;
};

/// Distance |b - a|; the angle in degrees between the normals at a and b, in [0, 180]; or the
/// smallest radius of curvature at a (1 / max(|k1|, |k2|), +infinity on a plane).
double measurementValue(const Measurement& m);

/// One line: "distance 12.5 (dx 3, dy 4, dz 12)", "angle 90° between normals" (or "between
/// plane faces"),
/// "radius 5 (principal radii 5, ∞)"; numbers to `digits` significant digits, each length
/// followed by `unit` when one is given ("distance 12.5 mm (dx 3 mm, …)").
QString measurementText(const Measurement& m, int digits = 8, const QString& unit = QString());

} // namespace kw
