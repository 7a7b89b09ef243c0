// Keep Seams Closed: the control points of neighbouring untrimmed faces that a control point
// move carries with it, so that shared iso-boundaries stay one curve (and, with tangency,
// collinear rows across them stay collinear).
#pragma once

#include "model/document/scene.h"

#include <glm/glm.hpp>
#include <vector>

namespace kw {

/// A control point moved along with an edit: `surface`'s point `index` to `position`.
struct LinkedMove {
    SurfaceId surface;
    int index = 0;
    glm::dvec3 position{0.0};
};

/// For a move of points `indices` of `surface` from where the scene has them to `positions`:
/// every other control point that moves by the same displacement. Two boundaries of untrimmed
/// faces (or two boundaries of one, a closed surface's seam) are shared when their rows of
/// control points coincide point by point (either way round, within 1e-9 of the faces' size)
/// with equal weights, and their knot vectors along them are the same up to an affine change
/// of parameter (compatible knots): then the boundary curves are one, and moving a point of one
/// row moves the coincident point of the other (closure: a corner carries every face meeting
/// there). With `tangency`, the point next to each moved boundary point across each shared
/// boundary moves too, on both sides, so rows collinear across the boundary (G1) stay so.
/// The displacement rule makes an undo exact: moving the points back moves the linked points
/// back. A move of every point of the surface (a rigid move of the face) links nothing;
/// neither does a trimmed surface. Points listed in `indices` are never in the result.
std::vector<LinkedMove> linkedMoves(const Scene& scene, SurfaceId surface,
                                    const std::vector<int>& indices,
                                    const std::vector<glm::dvec3>& positions, bool tangency);

} // namespace kw
