// Which cells of a base polygon a section plane crosses, for the exact pass's split of a cut
// frame (kw::splitCells): cells wholly kept draw as an uncut frame's, crossed ones with exact
// depth and the section test, removed ones not at all. No GL: testable alone.
#pragma once

#include "model/document/scene.h"
#include "render/gpu_layout.h"
#include "render/surface_bound.h"

#include <cstdint>
#include <vector>

namespace kw {

/// How far the section curve's line reaches on screen from a plane (section.glsl's
/// kwSectionLine: 1.5 px, fading out by 2). The deferred pass, whose screen derivatives
/// jump between surfaces, does not draw it: cells within this of a plane count as crossed.
constexpr double kSectionLinePixels = 2.0;

/// A cell's class for the section planes, as ExactPlanner::SectionSide orders them.
enum class CellSection : std::uint8_t { Kept = 0, Crossed = 1, Removed = 2 };

/// World-space bounds of one base-polygon cell, in double.
struct CellBox {
    glm::dvec3 lo{0.0}, hi{0.0};
};

/// The bounds of every cell of `polygon` of `surface` (row by row, v outer, as its
/// triangles): the box of the cell's four corner points (exact surface points) grown by its
/// deviation bound (kw::cellDeviationBound with the largest second-derivative bounds of the
/// span sub-rectangles of `spans`, kw::surfaceSpanBounds, that the cell overlaps: the surface
/// lies within it of the cell's bilinear interpolant, which lies in the corners' hull), cut
/// to the union of those sub-rectangles' Bezier control bounds (convex hull property). They
/// hold the exact surface over the cell and the cell's two triangles. Empty when a cell's
/// knot span is not among `spans` (then no cell can be classified).
std::vector<CellBox> polygonCellBoxes(const NurbsSurface& surface, const BasePolygon& polygon,
                                      const std::vector<SpanBound>& spans);

/// Where the box [lo, hi] lies for `planes`, in double: Removed when it lies more than `margin`
/// (model units) beyond one plane, Kept when more than `margin` inside every plane, else
/// Crossed. Planes with a zero normal are ignored (refused before drawing).
CellSection boxSection(const glm::dvec3& lo, const glm::dvec3& hi,
                       const std::vector<SectionPlane>& planes, double margin);

/// Each cell's class, conservative: a cell is judged by the union of its own box and its
/// eight neighbours' (the point under a pixel of the cell's triangles, found by the Newton
/// step, may lie in a neighbour's (u, v) rectangle), grown by `marginPixels` pixels' worth of
/// model distance at the union's farthest depth under `scale` (the pixel tolerance of that
/// point, and the reach of the section curve's line, which the deferred pass does not draw)
/// and by the float resolution of the shader's test. Empty when `boxes` does not match the
/// polygon.
std::vector<CellSection> sectionCellClasses(const BasePolygon& polygon,
                                            const std::vector<CellBox>& boxes,
                                            const std::vector<SectionPlane>& planes,
                                            const ScreenScale& scale, double marginPixels);

} // namespace kw
