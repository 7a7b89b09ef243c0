// Guaranteed bounds on how far a base polygon (triangles through exact corner points) lies from
// the exact NURBS surface, in model units and in screen pixels, and the partitions they imply.
#pragma once

#include "model/document/scene.h"
#include "model/nurbs/nurbs.h"

#include <vector>

namespace kw {

/// Upper bounds, over one knot span rectangle, of |S_uu|, |S_uv| and |S_vv| of the rational
/// surface S (model units per parameter unit squared).
struct SecondDerivativeBound {
    double uu = 0.0;
    double uv = 0.0;
    double vv = 0.0;
};

/// Bounds over the rectangle [u0, u1] x [v0, v1] inside the knot span (spanU, spanV) (indices
/// as findSpan returns them; the span must be non-empty). The homogeneous patch Pw = (w P, w)
/// over the rectangle is cut out as a Bezier patch by blossoming (de Boor's algorithm with
/// the arguments u0^(p-a) u1^a, Ramshaw 1989, "Blossoming: a connect-the-dots approach to
/// splines"); its derivative nets
/// (eq. 3.17 / A3.7 on Bezier knots) bound the homogeneous derivatives by the convex hull
/// property. With c the centre of the patch's Cartesian control bounds, W its smallest weight
/// (a lower bound of w on the rectangle), A = max |P - c| (a bound of |S - c|) and H*, w* the
/// bounds of the derivatives of (w (P - c), w), the quotient rule gives
///   |S_u|  <= (H_u + w_u A) / W
///   |S_uu| <= (H_uu + 2 w_u |S_u| + w_uu A) / W
///   |S_uv| <= (H_uv + w_u |S_v| + w_v |S_u| + w_uv A) / W
/// For a polynomial surface (equal weights) the w terms vanish. Smaller rectangles give tighter
/// bounds (the weights vary less). Precondition: a valid surface, the rectangle in the span.
SecondDerivativeBound rectSecondDerivativeBound(const NurbsSurface& s, int spanU, int spanV,
                                                double u0, double u1, double v0, double v1);
/// rectSecondDerivativeBound over the whole span.
SecondDerivativeBound spanSecondDerivativeBound(const NurbsSurface& s, int spanU, int spanV);

/// Filip, Magedson & Markot (1986), "Surface algorithms using bounds on derivatives": if a
/// cell of widths du x dv lies inside one span with bounds m, every point of either triangle
/// of the cell (linear interpolation of the exact corner points) lies within
///   (m.uu du^2 + 2 m.uv du dv + m.vv dv^2) / 8
/// of the exact surface point at the same (u, v). (Taylor at the point: the linear terms of the
/// three corners cancel; sum(lambda_i d_i^2) <= du^2/4 as the variance of a distribution on an
/// interval of width du, and the mixed sum by Cauchy-Schwarz.) Also holds for the bilinear
/// interpolant of the four corners.
double cellDeviationBound(const SecondDerivativeBound& m, double du, double dv);

/// True when S is an affine map of (u, v), S(u, v) = A + B u + C v: every weight equal, and
/// every control point within `relTolerance` of the net's extent from A + B xi_i + C eta_j,
/// with xi and eta the Greville abscissae (knot averages; B-splines reproduce linear functions
/// through them, Marsden's identity). Then a triangle through exact corner points lies on S
/// with its (u, v) interpolated exactly: the base polygon is the surface, and the point it
/// puts under a pixel is the point truly there. Planes from CAD files (degree 1 x 1
/// rectangles, or degree-elevated ones) are such surfaces; a bilinear patch whose net is no
/// parallelogram, a rational plane with unequal weights, or a net of one point is not.
/// Precondition: a valid surface.
bool surfaceIsAffine(const NurbsSurface& s, double relTolerance = 1e-9);

/// The screen scale of a perspective camera: how a distance in model units near a point maps
/// to pixels.
struct ScreenScale {
    glm::dvec3 eye{0.0};
    glm::dvec3 forward{0.0, 0.0, -1.0}; ///< unit view direction
    double focalPixels = 1.0;           ///< (viewport height / 2) / tan(fovY / 2)
    double tanHalfDiagonal = 1.0;       ///< tan of the half-angle of the frustum's diagonal
    double nearDepth = 1e-3;            ///< depths below this are treated as this (clipped)
    /// When set, parts of a surface that are never on screen do not count (choosePartitions):
    /// a sub-rectangle whose control bounds, grown by the deviation bound of the cells over
    /// it, lie wholly outside one side plane of `viewProjection`'s frustum. Every polygon
    /// point over it then lies outside too, so the bound still holds for all that is drawn.
    bool cullOutsideView = false;
    glm::dmat4 viewProjection{1.0}; ///< OpenGL clip transform (only with cullOutsideView)
    /// The viewport in pixels (only with cullOutsideView): a margin in pixels around the view.
    glm::dvec2 viewportPixels{1.0};
};

/// The scale of `camera` (as kw::cameraMatrices reads it: target - eye is the view direction,
/// fovYDegrees clamped to [1, 170]) for a viewport of width x height pixels and the given near
/// plane depth (> 0).
ScreenScale screenScale(const Camera& camera, int width, int height, double nearDepth);

/// A bound in pixels of the distance on screen between the projections of two points a, b with
/// |a - b| <= distance, both at eye depth >= minDepth, one of them inside the view frustum:
///   |pi(a) - pi(b)| <= f * distance * sqrt(1 + t^2) / minDepth
/// with f the focal length in pixels and t = tanHalfDiagonal (|b_xy| / b_z <= t for b inside
/// the frustum; Cauchy-Schwarz on (a - b)). minDepth is clamped to nearDepth.
double screenDistanceBound(const ScreenScale& scale, double distance, double minDepth);

/// True when the box [lo, hi] lies wholly outside one of the six planes of the clip
/// transform's frustum (all eight corners beyond the same one). Each plane (-w <= x, y, z <= w)
/// is a half-space in model space at any w, so corners behind the eye are classified right.
/// The renderer's reversed-depth matrices (render/depth_convention.h, depth in 0..w, 1 at the
/// near plane) are right here too: z > w is nearer than the near plane or behind the eye, and
/// z < -w lies beyond the far plane, so only the far test is looser (z < 0 would do).
bool boxOutsideFrustum(const glm::dmat4& viewProjection, const glm::dvec3& lo,
                       const glm::dvec3& hi);

/// Smallest eye depth of the axis-aligned box [lo, hi] (the minimum over its corners).
double boxMinDepth(const ScreenScale& scale, const glm::dvec3& lo, const glm::dvec3& hi);

/// Smallest eye depth of the part of the box [lo, hi] inside `scale`'s frustum (its four side
/// planes, from viewProjection, and the near plane at nearDepth; the far plane left out), or
/// +infinity when none of the box is inside. Exact up to rounding: the least depth over the
/// convex polytope box & frustum, at one of its vertices. At least boxMinDepth and nearDepth.
double boxMinDepthInFrustum(const ScreenScale& scale, const glm::dvec3& lo, const glm::dvec3& hi);

/// One knot span rectangle of a surface cut into grid x grid equal sub-rectangles, each with its
/// derivative bounds and the Cartesian bounds of its Bezier control points (the surface and the
/// base polygon points over it lie inside them).
struct SpanBound {
    struct Sub {
        SecondDerivativeBound m;
        glm::dvec3 lo{0.0}, hi{0.0};
    };
    int spanU = 0; ///< knot index as findSpan returns
    int spanV = 0;
    double u0 = 0.0, u1 = 0.0, v0 = 0.0, v1 = 0.0;
    int grid = 1;
    std::vector<Sub> subs; ///< grid x grid, sub (a, b) at b * grid + a (u index a)
    /// Side i (0..grid) of the sub-rectangles along u (v): where surfaceSpanBounds bounds them
    /// and the partition's breaks are cut (chooseBreaks), so that the spans of one knot
    /// interval give the same values.
    double sideU(int i) const { return i == grid ? u1 : u0 + (u1 - u0) / grid * i; }
    double sideV(int j) const { return j == grid ? v1 : v0 + (v1 - v0) / grid * j; }
};

/// All non-empty spans of a surface (precondition: valid), each cut into grid x grid
/// (1..16) sub-rectangles. Cost O(spans grid^2 (p+1)(q+1)(p^2+q^2)); depends only on the
/// geometry, so callers cache it by the surface's geometry and knot revisions.
std::vector<SpanBound> surfaceSpanBounds(const NurbsSurface& s, int grid = 8);

/// Partitions chosen for a view.
struct PartitionChoice {
    int nu = 1;
    int nv = 1;
    double boundPixels = 0.0; ///< the guaranteed screen deviation bound at (nu, nv)
    bool met = true;          ///< false when kMaxPartitions could not reach the tolerance
    /// chooseBreaks' grid: every cell lies inside one sub-rectangle of the spans (a uniform
    /// cell lies inside one span only).
    bool cellsInOneSub = false;
    /// The cell boundaries (chooseBreaks; empty from choosePartitions): nu + 1 increasing
    /// values along u from the box's first to its last, nv + 1 along v.
    std::vector<double> breaksU, breaksV;
};

/// The uniform partitions (nu, nv) >= (minU, minV), as buildBasePolygon cuts them (nu uniform
/// cells merged with the knots, so each cell is at most 1/nu of the domain and inside one
/// span), for which the base polygon lies within `pixelTolerance` pixels of the exact surface
/// on screen for every span, by cellDeviationBound and screenDistanceBound: a cell touching a
/// sub-rectangle lies within one cell size of it, so it is scored with the largest bounds and
/// smallest depth of the sub-rectangles in that reach. Grows the
/// direction that contributes most to the worst span until met or both reach kMaxPartitions.
PartitionChoice choosePartitions(const std::vector<SpanBound>& spans, const Interval& domainU,
                                 const Interval& domainV, const ScreenScale& scale,
                                 double pixelTolerance, int minU = 1, int minV = 1);

/// Non-uniform partitions of the box [boxU] x [boxV] (inside the domain, e.g. the trims' box):
/// a tensor-product grid whose columns and rows follow the sub-rectangles of `spans` (the
/// spans meeting the box), each column cut into its own number of equal cells, so that every
/// cell lies inside one sub-rectangle and is scored with that sub-rectangle's own bounds and
/// depth (no reach, unlike choosePartitions). A column whose sub-rectangles are all off
/// screen or far away keeps few cells while another is refined, and since whole columns and
/// rows are cut, the grid has no T-junctions: neighbouring cells share their corners. The
/// counts are the fewest, column by column and row by row, for which every cell lies within
/// `pixelTolerance` pixels on screen by cellDeviationBound and screenDistanceBound; cells are
/// at most 1 / minU of the box's width (1 / minV of its height). A column or row holds at most
/// kMaxPartitions cells, and the grid at most kMaxPartitions^2 (the uniform choice's largest),
/// so a close-up can put more cells where it looks than the uniform choice can; `met` is false
/// where that does not reach the tolerance. Returns the breaks and
/// nu, nv as the cell counts along u and v.
PartitionChoice chooseBreaks(const std::vector<SpanBound>& spans, const Interval& boxU,
                             const Interval& boxV, const ScreenScale& scale, double pixelTolerance,
                             int minU = 1, int minV = 1);

/// The screen deviation bound of the base polygon at (nu, nv) (the largest over the spans).
double partitionBoundPixels(const std::vector<SpanBound>& spans, const Interval& domainU,
                            const Interval& domainV, const ScreenScale& scale, int nu, int nv);

} // namespace kw
