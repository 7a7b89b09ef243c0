// Where a surface is drawn: the (u, v) box its trims keep and the bounds of its exact trimmed
// geometry, which fitCamera frames (not the control nets, which can be far larger).
#pragma once

#include "model/document/scene.h"

namespace kw {

/// A rectangle of a surface's parameter domain.
struct ParameterBox {
    Interval u;
    Interval v;
    bool operator==(const ParameterBox&) const = default;
};

/// The (u, v) rectangle that holds every point a surface's trims keep: the bounds of its
/// trim curves' control points (each curve lies in their convex hull), clipped to the domain.
/// The whole domain for a surface without trims or without a valid trim curve.
/// Precondition: a valid surface.
ParameterBox trimParameterBox(const Surface& surface);

/// Bounds of the exact geometry a surface shows: the surface evaluated at the points of a
/// 33 x 33 grid over trimParameterBox that the trims keep (model/nurbs/trim.h, even-odd) and at
/// every point of its flattened trim loops. False (bounds untouched) for an invalid surface
/// or one whose trims keep none of those points.
bool surfaceVisibleBounds(const Surface& surface, glm::dvec3& lo, glm::dvec3& hi);

/// surfaceVisibleBounds over every surface. Results are cached by the content of each
/// surface's points, weights, knots and trims, so a frame or a Fit after an edit recomputes
/// only the surfaces that changed. With `shownOnly`, hidden surfaces (Surface::hidden) are left
/// out. False when no surface gives bounds.
bool sceneVisibleBounds(const Scene& scene, glm::dvec3& lo, glm::dvec3& hi, bool shownOnly = false);

} // namespace kw
