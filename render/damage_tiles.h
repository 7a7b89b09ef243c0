// A partial frame's damage as tiles (docs/RENDERING.md, "The partial frame"): the square
// tiles a surface's cells touch, and the few rectangles that cover the tiles of the surfaces
// that changed. A dragged face's bounding rectangle holds much the face does not cover (a
// claw, a slanted strip); its tiles hold only what it can draw. No GL: the renderer
// (render/renderer.cpp) draws one scissored pass sequence per rectangle.
#pragma once

#include "render/gpu_layout.h"

#include <cstdint>
#include <glm/glm.hpp>
#include <optional>
#include <vector>

namespace kw {

/// Tiles of a viewport, row by row from the bottom-left (GL rows): tile (tx, ty) covers pixels
/// [tx * tile, (tx + 1) * tile) x [ty * tile, (ty + 1) * tile), clamped to the viewport; its
/// index is ty * columns + tx.
class TileGrid {
public:
    TileGrid(glm::ivec2 viewport, int tile);
    int columns() const { return m_columns; }
    int rows() const { return m_rows; }
    int tile() const { return m_tile; }
    glm::ivec2 viewport() const { return m_viewport; }

    /// Marks the tiles `rect` (x0, y0, x1, y1 exclusive, GL rows; clamped to the viewport)
    /// touches; an empty one marks none.
    void addRect(const glm::ivec4& rect);
    /// Marks the tiles of sorted or unsorted `indices` (out of the grid: ignored).
    void addTiles(const std::vector<std::int32_t>& indices);
    bool has(int tx, int ty) const;
    /// The marked tiles.
    int count() const;
    /// The marked tiles' indices, ascending.
    std::vector<std::int32_t> tiles() const;

    /// Rectangles (window pixels, clamped to the viewport) that together cover every marked
    /// tile: each row's runs of marked tiles, runs of the same columns in adjacent rows as one,
    /// then the two whose union adds the fewest pixels merged while that adds at most
    /// `mergePixels` or while there are more than `maxRects`. They may overlap after merging.
    std::vector<glm::ivec4> rects(int maxRects, std::int64_t mergePixels) const;

private:
    int m_tile = 1, m_columns = 0, m_rows = 0;
    glm::ivec2 m_viewport{0};
    std::vector<std::uint8_t> m_marked;
};

/// The tiles of `grid` that the cells of `poly` touch where its nodes project under
/// `viewProjection` into `viewport` (as cellsReaching takes a cell: its four corners' window
/// rectangle, normalised device coordinates clamped to +-2, whole pixels), each rectangle grown
/// by `pad` pixels; ascending. nullopt when a node lies behind the eye or the polygon has no
/// vertices on the CPU: then take its rectangle's.
std::optional<std::vector<std::int32_t>>
cellTiles(const BasePolygon& poly, const glm::mat4& viewProjection, const TileGrid& grid, int pad);

/// Pixels in `r` (x0, y0, x1, y1 exclusive); 0 when empty.
std::int64_t rectPixels(const glm::ivec4& r);

} // namespace kw
