// The cells of a base polygon that a partial frame's rectangle can reach (docs/RENDERING.md,
// "The partial frame"), and the runs of its triangle and skirt index ranges that draw them.
// A face reaching the rectangle at one corner then sends the few cells there, not all of them
// through the pre-pass, the exact pass, the skirts and the back faces. No GL: the exact
// planner (render/exact_planner.cpp) turns the runs into draw commands.
#pragma once

#include "render/gpu_layout.h"

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace kw {

struct SurfaceGpu;

/// `count` consecutive cells (or indices) from `first`, in drawing order.
struct CellRun {
    int first = 0, count = 0;
    bool operator==(const CellRun&) const = default;
};

/// What cellsReaching says of a cell, one bit each.
enum CellReach : std::uint8_t {
    /// Its triangles' window rectangle meets the rectangle: the passes that draw its
    /// triangles send it.
    kCellTriangles = 1,
    /// That rectangle grown by the skirts' push meets it: the skirt segments along its
    /// boundary sides may cover pixels there.
    kCellSkirt = 2,
};

/// How far on screen a skirt's pushed copy of a node may lie from the node, for a skirt of
/// `skirtPixels` (tolerance + ExactSurfacePass::kSkirtMarginPixels): surface.vert pushes it
/// along the image of the outward tangent until it lies skirtPixels square to the edge, which
/// is at most 4 times that along the push (its `square` is at least a quarter of the rate).
/// The skirt shader keeps only pixels where the face's ray meets the face, but that may be
/// another cell's part of it (it meets the face farther on), so a cell's skirt needs the
/// geometric bound.
double skirtPushPixels(double skirtPixels);

/// Per cell of `poly` (row by row, v outer), the window rectangle (x0, y0, x1, y1 exclusive,
/// GL rows) of its four corners projected under `viewProjection` into `viewport`, taken as the
/// renderer takes a polygon's rectangle (normalised device coordinates clamped to +-2, widened
/// to whole pixels): its triangles lie in the corners' convex hull. Empty when a corner lies
/// behind the eye, or the polygon has no vertices on the CPU.
std::vector<glm::ivec4> cellRects(const BasePolygon& poly, const glm::mat4& viewProjection,
                                  glm::ivec2 viewport);

/// Per cell of `poly` (row by row, v outer), the CellReach bits for the window rectangle
/// `reach` (x0, y0, x1, y1 exclusive, GL rows): where its four corners project under
/// `viewProjection` into `viewport`, taken as the renderer takes a polygon's rectangle
/// (normalised device coordinates clamped to +-2, widened to whole pixels: the triangles lie
/// in the corners' convex hull), kCellTriangles when that meets `reach`, kCellSkirt when it
/// grown by `skirtPush` pixels does. Empty when a corner lies behind the eye, or the polygon
/// has no vertices on the CPU: then every cell may reach it.
std::vector<std::uint8_t> cellsReaching(const BasePolygon& poly, const glm::mat4& viewProjection,
                                        glm::ivec2 viewport, const glm::ivec4& reach,
                                        int skirtPush);

/// The cells `keep` has `bit` set for, at their places in g's triangle range (the order of
/// SurfaceGpu::cellBuckets), as runs in cells, runs with at most `gap` cells between them
/// merged into one (fewer draw commands; a merged cell is drawn as a whole frame draws it). `keep`
/// holds one entry per cell of g's polygon.
std::vector<CellRun> cellRuns(const SurfaceGpu& g, const std::vector<std::uint8_t>& keep,
                              std::uint8_t bit, int gap);

/// The indices of g's skirt (kw::buildSkirt: the segments of the bottom, right, top and left
/// sides, 6 indices each, then the four corners' triangles, 3 each) whose cell has kCellSkirt
/// in `keep`, as runs in indices, merged as cellRuns does (`gap` in segments). Sets `whole`
/// (and returns none) when g's skirt is not laid out over its polygon as buildSkirt lays it:
/// the skirt is drawn whole then.
std::vector<CellRun> skirtRuns(const SurfaceGpu& g, const std::vector<std::uint8_t>& keep, int gap,
                               bool& whole);

/// A window rectangle that meets every other (a fin with a vertex behind the eye).
constexpr glm::ivec4 kEverywhere{-(1 << 29), -(1 << 29), 1 << 29, 1 << 29};

/// Of silhouette fins (kw::buildFins: two triangles each, 6 indices starting at its first of
/// 4 vertices), each one's window rectangle under `viewProjection`: its nodes' (taken as
/// cellsReaching takes a cell's) grown by `push` pixels, how far surface.vert may push its outer
/// edge past them (skirtPushPixels); kEverywhere for one with a vertex behind the eye or not
/// laid out so.
std::vector<glm::ivec4> finRects(const std::vector<SkirtVertex>& vertices,
                                 const std::vector<unsigned>& indices,
                                 const glm::mat4& viewProjection, glm::ivec2 viewport, int push);
/// The indices of the fins whose rectangle (`rects`, finRects') meets `reach`.
std::vector<unsigned> finsMeeting(const std::vector<glm::ivec4>& rects,
                                  const std::vector<unsigned>& indices, const glm::ivec4& reach);
/// finsMeeting of finRects: the indices of the fins whose window rectangle (grown by `push`)
/// meets `reach`.
std::vector<unsigned> finsReaching(const std::vector<SkirtVertex>& vertices,
                                   const std::vector<unsigned>& indices,
                                   const glm::mat4& viewProjection, glm::ivec2 viewport,
                                   const glm::ivec4& reach, int push);

/// Runs of cells at most this many cells apart in a triangle range are sent as one: on
/// llvmpipe each command of a multi-draw is a draw of its own (state, vertex set-up), which
/// costs about what some tens of cells' vertices and triangle set-up do, so a face's rows in a
/// rectangle go as one band of rows, not one command per row (with 4, Motor-c's partial frames
/// sent a few hundred commands more than whole faces and measured no faster).
constexpr int kCellRunGap = 32;

} // namespace kw
