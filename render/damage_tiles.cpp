// A partial frame's damage tiles and their covering rectangles (damage_tiles.h).
#include "render/damage_tiles.h"

#include "render/partial_cells.h"

#include <algorithm>
#include <functional>
#include <queue>
#include <tuple>

namespace kw {

TileGrid::TileGrid(glm::ivec2 viewport, int tile)
    : m_tile(std::max(tile, 1)), m_viewport(glm::max(viewport, glm::ivec2(0))) {
    m_columns = (m_viewport.x + m_tile - 1) / m_tile;
    m_rows = (m_viewport.y + m_tile - 1) / m_tile;
    m_marked.assign(size_t(m_columns) * size_t(m_rows), 0);
}

void TileGrid::addRect(const glm::ivec4& rect) {
    const int x0 = std::max(rect.x, 0), y0 = std::max(rect.y, 0);
    const int x1 = std::min(rect.z, m_viewport.x), y1 = std::min(rect.w, m_viewport.y);
    if (x1 <= x0 || y1 <= y0)
        return;
    // The last pixel (x1 - 1) is the last tile's: exclusive ends.
    for (int ty = y0 / m_tile; ty <= (y1 - 1) / m_tile; ++ty)
        for (int tx = x0 / m_tile; tx <= (x1 - 1) / m_tile; ++tx)
            m_marked[size_t(ty) * size_t(m_columns) + size_t(tx)] = 1;
}

void TileGrid::addTiles(const std::vector<std::int32_t>& indices) {
    for (const std::int32_t k : indices)
        if (k >= 0 && size_t(k) < m_marked.size())
            m_marked[size_t(k)] = 1;
}

bool TileGrid::has(int tx, int ty) const {
    return tx >= 0 && ty >= 0 && tx < m_columns && ty < m_rows &&
           m_marked[size_t(ty) * size_t(m_columns) + size_t(tx)] != 0;
}

int TileGrid::count() const {
    return int(std::count(m_marked.begin(), m_marked.end(), std::uint8_t(1)));
}

std::vector<std::int32_t> TileGrid::tiles() const {
    std::vector<std::int32_t> out;
    for (size_t k = 0; k < m_marked.size(); ++k)
        if (m_marked[k])
            out.push_back(std::int32_t(k));
    return out;
}

std::int64_t rectPixels(const glm::ivec4& r) {
    if (r.z <= r.x || r.w <= r.y)
        return 0;
    return std::int64_t(r.z - r.x) * std::int64_t(r.w - r.y);
}

namespace {

glm::ivec4 united(const glm::ivec4& a, const glm::ivec4& b) {
    return glm::ivec4(std::min(a.x, b.x), std::min(a.y, b.y), std::max(a.z, b.z),
                      std::max(a.w, b.w));
}

} // namespace

std::vector<glm::ivec4> TileGrid::rects(int maxRects, std::int64_t mergePixels) const {
    // 1. Each row's runs, in tiles (x0, y0, x1, y1 exclusive); a run with the same columns
    // as one ending in the row below extends it.
    std::vector<glm::ivec4> out;
    std::vector<size_t> open; // out's rectangles ending at the current row
    for (int ty = 0; ty < m_rows; ++ty) {
        std::vector<size_t> next;
        for (int tx = 0; tx < m_columns;) {
            if (!has(tx, ty)) {
                ++tx;
                continue;
            }
            int end = tx;
            while (end < m_columns && has(end, ty))
                ++end;
            const auto below = std::find_if(open.begin(), open.end(), [&](size_t k) {
                return out[k].x == tx && out[k].z == end;
            });
            if (below != open.end()) {
                out[*below].w = ty + 1;
                next.push_back(*below);
            } else {
                out.push_back(glm::ivec4(tx, ty, end, ty + 1));
                next.push_back(out.size() - 1);
            }
            tx = end;
        }
        open = std::move(next);
    }
    // 2. In pixels, clamped to the viewport.
    for (glm::ivec4& r : out)
        r = glm::ivec4(r.x * m_tile, r.y * m_tile, std::min(r.z * m_tile, m_viewport.x),
                       std::min(r.w * m_tile, m_viewport.y));
    // 3. The cheapest unions, while cheap enough or too many: pair costs in a queue, cheapest
    // first, of two equal the one whose first and then second rectangle comes first in `out`
    // (as a scan of the pairs in order finds it). A merged pair's first takes the union, keeps
    // its place and is re-dated; entries naming a removed or re-dated rectangle are skipped.
    // Rectangles keep their order, so their indices order them as their places do.
    const int limit = std::max(maxRects, 1);
    struct Pair {
        std::int64_t added;
        std::uint32_t i, j, ageI, ageJ;
        bool operator>(const Pair& o) const {
            return std::tie(added, i, j) > std::tie(o.added, o.i, o.j);
        }
    };
    std::vector<std::uint32_t> age(out.size(), 0);
    std::vector<bool> alive(out.size(), true);
    const auto pair = [&](std::uint32_t i, std::uint32_t j) {
        const std::int64_t added =
            rectPixels(united(out[i], out[j])) - rectPixels(out[i]) - rectPixels(out[j]);
        return Pair{added, i, j, age[i], age[j]};
    };
    std::vector<Pair> initial;
    for (std::uint32_t i = 0; i < out.size(); ++i)
        for (std::uint32_t j = i + 1; j < out.size(); ++j)
            initial.push_back(pair(i, j));
    std::priority_queue<Pair, std::vector<Pair>, std::greater<>> queue(std::greater<>(),
                                                                       std::move(initial));
    size_t left = out.size();
    while (left > 1) {
        while (!alive[queue.top().j] || !alive[queue.top().i] ||
               queue.top().ageI != age[queue.top().i] || queue.top().ageJ != age[queue.top().j])
            queue.pop(); // every live pair is queued at its age: the queue holds one
        const Pair best = queue.top();
        if (best.added > mergePixels && int(left) <= limit)
            break;
        queue.pop();
        out[best.i] = united(out[best.i], out[best.j]);
        alive[best.j] = false;
        ++age[best.i];
        --left;
        for (std::uint32_t k = 0; k < out.size(); ++k)
            if (alive[k] && k != best.i)
                queue.push(k < best.i ? pair(k, best.i) : pair(best.i, k));
    }
    std::vector<glm::ivec4> kept;
    for (size_t k = 0; k < out.size(); ++k)
        if (alive[k])
            kept.push_back(out[k]);
    out = std::move(kept);
    return out;
}

std::optional<std::vector<std::int32_t>>
cellTiles(const BasePolygon& poly, const glm::mat4& viewProjection, const TileGrid& grid, int pad) {
    const std::vector<glm::ivec4> cells = cellRects(poly, viewProjection, grid.viewport());
    if (cells.empty())
        return std::nullopt;
    TileGrid touched(grid.viewport(), grid.tile());
    for (const glm::ivec4& c : cells)
        touched.addRect(c + glm::ivec4(-pad, -pad, pad, pad));
    return touched.tiles();
}

} // namespace kw
