// CPU-side layouts of the GPU data of one surface: homogeneous control points, knot span
// tables and the base polygon (paper 3.1, 3.4). No GL here, so the layouts are testable alone.
#pragma once

#include "model/nurbs/nurbs.h"
#include "model/nurbs/visible_bounds.h"

#include <glm/glm.hpp>
#include <vector>

namespace kw {

/// Control point (i, j) as the texel (i, j) of an RGBA32F texture countU x countV:
/// (w (P - origin), w). Points relative to an origin near the surface keep float precision
/// where the model sits far from (0, 0, 0); the shader adds the origin back.
std::vector<glm::vec4> packControlPoints(const NurbsSurface& s, const glm::dvec3& origin);
/// The origin used for packControlPoints: the centre of the control bounds.
glm::dvec3 controlOrigin(const NurbsSurface& s);

/// Number of floats in one span-table row for degree p: p left knots, p right knots and
/// p(p+1)/2 reciprocal knot differences. Must match basis.glsl.
constexpr int spanTableFloats(int p) {
    return 2 * p + p * (p + 1) / 2;
}
/// Texels (RGBA32F) per span-table row.
constexpr int spanTableTexels(int p) {
    return (spanTableFloats(p) + 3) / 4;
}

/// Knot span table of a knot vector of degree p with `count` control points, in the order The
/// NURBS Book A2.2 consumes it, so the shader needs no division and no search: row r is span
/// k = r + p (rows for empty spans are filled but never used) and holds
///   U[k+1-j] for j = 1..p, then U[k+j] for j = 1..p, then for j = 1..p, r = 0..j-1 the
///   reciprocal 1 / (U[k+r+1] - U[k+1-j+r]) (always > 0 for a non-empty span).
/// Rows are padded to whole RGBA texels: width spanTableTexels(p), height count - p.
/// Precondition: a valid knot vector (checkKnotVector passes).
std::vector<glm::vec4> packSpanTable(const std::vector<double>& knots, int p, int count);

/// One base polygon vertex. Must match the attributes of shaders/surface.vert (locations in
/// render/exact_contract.h): position (vec3), (u, v) (vec2), knot spans (ivec2, flat), span scale
/// (float, flat): the diagonal of the bounds of the (p+1)(q+1) control points of the span, the
/// length L of the degenerate-normal rule of kw::surfaceFrame.
struct BaseVertex {
    glm::vec3 position;
    glm::vec2 uv;
    glm::ivec2 span;
    float spanScale;
};
static_assert(sizeof(BaseVertex) == 32); // its word layout: render/gpu_scene.h

/// The base polygon of one surface: the domain cut uniformly into nu x nv cells and further
/// at every distinct interior knot, so each cell lies inside one knot span. Vertices form the
/// shared grid of cell corners, row by row (v outer): vertex (gu, gv) is at
/// (breaksU[gu], breaksV[gv]) with the exact surface point, and carries the span and span
/// scale of the cell whose lower-left corner it is (cell (gu, gv); the last row and column
/// repeat their neighbour's). Both triangles of a cell start at that corner, so with the
/// first-vertex provoking convention the flat attributes are the cell's own.
struct BasePolygon {
    std::vector<double> breaksU; ///< cell boundaries along u, increasing, ends = domain
    std::vector<double> breaksV;
    std::vector<int> spanU; ///< knot span of cell column c (breaksU[c], breaksU[c+1])
    std::vector<int> spanV;
    std::vector<BaseVertex> vertices;

    int cellsU() const { return int(spanU.size()); }
    int cellsV() const { return int(spanV.size()); }
    int cellCount() const { return cellsU() * cellsV(); }
    int nodesU() const { return int(breaksU.size()); }
};

/// Breakpoints over `range` (inside the domain): n uniform cells of it merged with the
/// distinct knots strictly inside it; the ends are range's. Uniform breaks closer than 1e-9 of
/// the range's length to a knot are dropped.
std::vector<double> cellBreaks(const std::vector<double>& knots, int n, Interval range);

/// Builds the base polygon. Preconditions: valid surface, nu and nv >= 1.
BasePolygon buildBasePolygon(const NurbsSurface& s, int nu, int nv);
/// The base polygon over `box` (a rectangle of the domain, e.g. trimParameterBox: a trimmed
/// face's partitions go where its trims keep the surface).
BasePolygon buildBasePolygon(const NurbsSurface& s, const ParameterBox& box, int nu, int nv);

/// Where a base polygon's cells go: the paper's nu x nv uniform partitions of the box merged
/// with the knots, or, when breaksU and breaksV are set, exactly those (adaptive mode's
/// choice, kw::chooseBreaks or cellBreaks; each cell inside one knot span).
struct PolygonCut {
    int nu = 1, nv = 1;
    std::vector<double> breaksU, breaksV; ///< increasing, ends = the box's
    bool operator==(const PolygonCut&) const = default;
};
/// The base polygon over `box` cut as `cut` says (with breaks, `box` is theirs).
BasePolygon buildBasePolygon(const NurbsSurface& s, const ParameterBox& box, const PolygonCut& cut);

/// Re-evaluates the vertices whose (u, v) lie in the support of control points
/// [i0, i1] x [j0, j1] (the only ones a move of those points can change), and the span scales
/// of the cells there, and returns the range of vertex indices [first, last] that changed,
/// or false when none did.
bool updateBasePolygon(BasePolygon& poly, const NurbsSurface& s, int i0, int i1, int j0, int j1,
                       int& first, int& last);

/// The diagonal of the bounds of the control points acting on knot span (ku, kv): the length L
/// of the degenerate-normal rule of kw::surfaceFrame (BaseVertex::spanScale).
float spanScale(const NurbsSurface& s, int ku, int kv);

/// Indices of two triangles per cell (GL_TRIANGLES), each starting at the cell's lower-left
/// corner: draw with glProvokingVertex(GL_FIRST_VERTEX_CONVENTION).
std::vector<unsigned> basePolygonTriangles(const BasePolygon& poly);
/// Indices of the four outline edges per cell (GL_LINES).
std::vector<unsigned> basePolygonOutlines(const BasePolygon& poly);

/// One vertex of a base polygon's skirt (docs/RENDERING.md "Skirts"): a node
/// of the polygon's outline and the outward (u, v) direction across its edge, (0, 0) on the
/// strip's inner side. BaseVertex's attributes, then shaders/surface.vert's aOutward
/// (KW_SKIRT, kw::kAttrOutward) is `outward`.
struct SkirtVertex {
    BaseVertex base;
    glm::vec2 outward;
};
static_assert(sizeof(SkirtVertex) == 40);

/// The skirt of `poly`: along each side of its outline (bottom, right, top, left) every
/// boundary node twice, as it is (outward (0, 0)) and marked with the side's outward (u, v)
/// direction (surface.vert pushes those across the edge on screen); and for each boundary
/// segment a quad of two triangles, both starting at the inner copy of the segment's first
/// node, whose BaseVertex span is that of the cell the segment borders (first-vertex
/// provoking convention, as basePolygonTriangles); then at each of the four corners a
/// triangle from the corner's inner copy to its two sides' outer copies, covering the wedge
/// between their pushes. Indices are relative to the first vertex.
void buildSkirt(const BasePolygon& poly, std::vector<SkirtVertex>& vertices,
                std::vector<unsigned>& indices);
/// The vertices only, for a polygon whose nodes moved (same count and order as buildSkirt's).
std::vector<SkirtVertex> skirtVertices(const BasePolygon& poly);

/// The silhouette fins of `poly` for one view (docs/RENDERING.md "Silhouette fins"): for each
/// polygon edge whose two triangles face opposite ways as seen from `eye` (the polygon's
/// silhouette; triangles of no area count as neither), a quad on screen around the edge,
/// `pixels` wide on either side and `pixels` past either end, made of SkirtVertex with
/// outward (0, 0): positions are the edge's end points moved on screen (unprojected through
/// `viewProjection` at their own clip depth), (u, v), span and span scale are the end point's
/// own, so the shader's (u, v) runs along the edge and the skirt shader's per-pixel Newton
/// test keeps only pixels whose ray meets the surface. Two triangles per fin, both starting
/// at the first end's copies. Edges with an end behind the eye, or seen end on (< 1e-3 px
/// long), get none. Appends to `vertices` and `indices` (indices count from `vertices`
/// first element).
void buildFins(const BasePolygon& poly, const glm::dmat4& viewProjection, const glm::dvec3& eye,
               glm::ivec2 viewport, double pixels, std::vector<SkirtVertex>& vertices,
               std::vector<unsigned>& indices);

/// Uniform tessellation for the baseline mode: (nu+1) x (nv+1) grid vertices with the
/// kernel's exact point and unit normal (kw::surfaceFrame).
struct TessellatedMesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::vec2> uvs;
    std::vector<unsigned> indices; ///< GL_TRIANGLES
};
TessellatedMesh tessellate(const NurbsSurface& s, int nu, int nv);

} // namespace kw
