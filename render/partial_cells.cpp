// Which cells a partial frame's rectangle reaches, and their runs in the index ranges
// (partial_cells.h).
#include "render/partial_cells.h"

#include "render/gpu_pool.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace kw {

double skirtPushPixels(double skirtPixels) {
    return 4.0 * skirtPixels;
}

namespace {

bool meets(const glm::ivec4& a, const glm::ivec4& b) {
    return a.z > b.x && a.x < b.z && a.w > b.y && a.y < b.w;
}

/// `p` in window pixels of `viewport` as the renderer takes a polygon's rectangle, or false
/// when it lies behind the eye.
bool windowPoint(const glm::vec3& p, const glm::mat4& viewProjection, const glm::vec2& size,
                 glm::vec2& at) {
    const glm::vec4 clip = viewProjection * glm::vec4(p, 1.0f);
    if (!(clip.w > 0.0f))
        return false;
    at = (glm::clamp(glm::vec2(clip) / clip.w, -2.0f, 2.0f) * 0.5f + 0.5f) * size;
    return true;
}

/// The whole pixels holding `lo`..`hi`.
glm::ivec4 pixels(const glm::vec2& lo, const glm::vec2& hi) {
    return glm::ivec4(int(std::floor(lo.x)), int(std::floor(lo.y)), int(std::ceil(hi.x)),
                      int(std::ceil(hi.y)));
}

} // namespace

std::vector<glm::ivec4> cellRects(const BasePolygon& poly, const glm::mat4& viewProjection,
                                  glm::ivec2 viewport) {
    const int nu = poly.nodesU(), nv = int(poly.breaksV.size());
    if (nu < 2 || nv < 2 || poly.vertices.size() != size_t(nu) * size_t(nv))
        return {};
    // The nodes in window pixels, as the renderer projects a polygon's vertices for its
    // rectangle (Renderer::Impl::surfaceFootprints).
    std::vector<glm::vec2> at(poly.vertices.size());
    const glm::vec2 size(viewport);
    for (size_t k = 0; k < at.size(); ++k)
        if (!windowPoint(poly.vertices[k].position, viewProjection, size, at[k]))
            return {};
    const int cu = nu - 1, cv = nv - 1;
    std::vector<glm::ivec4> rects(size_t(cu) * size_t(cv));
    for (int j = 0; j < cv; ++j)
        for (int i = 0; i < cu; ++i) {
            const size_t ll = size_t(j) * size_t(nu) + size_t(i), ul = ll + size_t(nu);
            const glm::vec2 lo =
                glm::min(glm::min(at[ll], at[ll + 1]), glm::min(at[ul], at[ul + 1]));
            const glm::vec2 hi =
                glm::max(glm::max(at[ll], at[ll + 1]), glm::max(at[ul], at[ul + 1]));
            rects[size_t(j) * size_t(cu) + size_t(i)] = pixels(lo, hi);
        }
    return rects;
}

std::vector<std::uint8_t> cellsReaching(const BasePolygon& poly, const glm::mat4& viewProjection,
                                        glm::ivec2 viewport, const glm::ivec4& reach,
                                        int skirtPush) {
    const std::vector<glm::ivec4> rects = cellRects(poly, viewProjection, viewport);
    const glm::ivec4 wide = reach + glm::ivec4(-skirtPush, -skirtPush, skirtPush, skirtPush);
    std::vector<std::uint8_t> keep(rects.size(), 0);
    for (size_t c = 0; c < rects.size(); ++c)
        keep[c] = std::uint8_t((meets(rects[c], reach) ? kCellTriangles : 0) |
                               (meets(rects[c], wide) ? kCellSkirt : 0));
    return keep;
}

std::vector<glm::ivec4> finRects(const std::vector<SkirtVertex>& vertices,
                                 const std::vector<unsigned>& indices,
                                 const glm::mat4& viewProjection, glm::ivec2 viewport, int push) {
    std::vector<glm::ivec4> out;
    out.reserve(indices.size() / 6);
    const glm::vec2 size(viewport);
    for (size_t f = 0; f + 6 <= indices.size(); f += 6) {
        const unsigned first = indices[f];
        bool everywhere = first + 4 > vertices.size(); // not buildFins' layout
        glm::vec2 lo(std::numeric_limits<float>::max()), hi(-lo);
        for (unsigned k = first; !everywhere && k < first + 4; ++k) {
            glm::vec2 at(0.0f);
            if (!windowPoint(vertices[k].base.position, viewProjection, size, at)) {
                everywhere = true;
                break;
            }
            lo = glm::min(lo, at);
            hi = glm::max(hi, at);
        }
        out.push_back(everywhere ? kEverywhere
                                 : pixels(lo, hi) + glm::ivec4(-push, -push, push, push));
    }
    return out;
}

std::vector<unsigned> finsMeeting(const std::vector<glm::ivec4>& rects,
                                  const std::vector<unsigned>& indices, const glm::ivec4& reach) {
    std::vector<unsigned> out;
    for (size_t f = 0; f < rects.size() && 6 * f + 6 <= indices.size(); ++f)
        if (meets(rects[f], reach))
            out.insert(out.end(), indices.begin() + std::ptrdiff_t(6 * f),
                       indices.begin() + std::ptrdiff_t(6 * f + 6));
    return out;
}

std::vector<unsigned> finsReaching(const std::vector<SkirtVertex>& vertices,
                                   const std::vector<unsigned>& indices,
                                   const glm::mat4& viewProjection, glm::ivec2 viewport,
                                   const glm::ivec4& reach, int push) {
    return finsMeeting(finRects(vertices, indices, viewProjection, viewport, push), indices, reach);
}

namespace {

/// Appends `length` units at `at` to `runs`, merged into the last run when at most `gap`
/// units lie between them.
void extend(std::vector<CellRun>& runs, int at, int length, int gap) {
    if (!runs.empty() && at - (runs.back().first + runs.back().count) <= gap)
        runs.back().count = at + length - runs.back().first;
    else
        runs.push_back({at, length});
}

} // namespace

std::vector<CellRun> cellRuns(const SurfaceGpu& g, const std::vector<std::uint8_t>& keep,
                              std::uint8_t bit, int gap) {
    std::vector<CellRun> runs;
    const int cells = int(keep.size());
    if (g.cellBuckets.empty()) { // row by row
        for (int c = 0; c < cells; ++c)
            if (keep[size_t(c)] & bit)
                extend(runs, c, 1, gap);
        return runs;
    }
    if (g.cellBuckets.size() != keep.size())
        return {{0, cells}}; // not this polygon's order (cannot happen): every cell
    // Bucket by bucket, each row by row (kw::splitCells).
    const std::uint8_t last = *std::max_element(g.cellBuckets.begin(), g.cellBuckets.end());
    int place = 0;
    for (int b = 0; b <= int(last); ++b)
        for (int c = 0; c < cells; ++c) {
            if (g.cellBuckets[size_t(c)] != b)
                continue;
            if (keep[size_t(c)] & bit)
                extend(runs, place, 1, gap);
            ++place;
        }
    return runs;
}

std::vector<CellRun> skirtRuns(const SurfaceGpu& g, const std::vector<std::uint8_t>& keep, int gap,
                               bool& whole) {
    std::vector<CellRun> runs;
    const int cu = g.polygon.cellsU(), cv = g.polygon.cellsV();
    whole = g.skirtIndexOffset < 0 || size_t(cu) * size_t(cv) != keep.size() ||
            g.skirtIndexCount != 6 * (2 * cu + 2 * cv) + 12;
    if (whole)
        return runs;
    const auto kept = [&](int i, int j) {
        return (keep[size_t(j) * size_t(cu) + size_t(i)] & kCellSkirt) != 0;
    };
    // buildSkirt's segments: bottom (cell (k, 0)), right (cu - 1, k), top (k, cv - 1), left
    // (0, k), each side with increasing u or v.
    int segment = 0;
    const auto side = [&](int count, auto cell) {
        for (int k = 0; k < count; ++k, ++segment)
            if (cell(k))
                extend(runs, 6 * segment, 6, 6 * gap);
    };
    side(cu, [&](int k) { return kept(k, 0); });
    side(cv, [&](int k) { return kept(cu - 1, k); });
    side(cu, [&](int k) { return kept(k, cv - 1); });
    side(cv, [&](int k) { return kept(0, k); });
    // Then the corners' wedges: (0, 0), (last, 0), (last, last), (0, last).
    const int corners[4][2] = {{0, 0}, {cu - 1, 0}, {cu - 1, cv - 1}, {0, cv - 1}};
    for (int c = 0; c < 4; ++c)
        if (kept(corners[c][0], corners[c][1]))
            extend(runs, 6 * segment + 3 * c, 3, 6 * gap);
    return runs;
}

} // namespace kw
