// Keep Seams Closed: shared untrimmed boundaries found by their control rows, and the closure
// of the points a move carries along.
#include "model/document/seamkeeper.h"

#include <QHash>
#include <algorithm>
#include <cmath>
#include <deque>
#include <map>
#include <set>

namespace kw {

namespace {

/// Side k of a surface: 0 u = first, 1 u = last, 2 v = first, 3 v = last.
struct SideRef {
    const Surface* surface = nullptr;
    int side = 0;
};

int rowLength(const NurbsSurface& g, int side) {
    return side < 2 ? g.countV : g.countU;
}

/// The (i, j) of point k along side `side`.
std::pair<int, int> onSide(const NurbsSurface& g, int side, int k) {
    switch (side) {
    case 0:
        return {0, k};
    case 1:
        return {g.countU - 1, k};
    case 2:
        return {k, 0};
    default:
        return {k, g.countV - 1};
    }
}

/// The point next to (i, j) across side `side`, into the surface.
std::pair<int, int> inward(int side, int i, int j) {
    switch (side) {
    case 0:
        return {i + 1, j};
    case 1:
        return {i - 1, j};
    case 2:
        return {i, j + 1};
    default:
        return {i, j - 1};
    }
}

/// The knots along a side, mapped affinely onto [0, 1] (reversed when `reversed`).
std::vector<double> unitKnots(const NurbsSurface& g, int side, bool reversed) {
    std::vector<double> k = side < 2 ? g.knotsV : g.knotsU;
    const double a = k.front(), b = k.back();
    for (double& x : k)
        x = (x - a) / (b - a);
    if (reversed) {
        std::reverse(k.begin(), k.end());
        for (double& x : k)
            x = 1.0 - x;
    }
    return k;
}

double size(const NurbsSurface& g) {
    glm::dvec3 lo, hi;
    surfaceControlBounds(g, lo, hi);
    return glm::length(hi - lo);
}

/// Whether two sides are one boundary, and which way round (the compatibility of Keep Seams
/// Closed: same rows, same weights, same knots along).
bool sameBoundary(const SideRef& a, const SideRef& b, double eps, bool& reversed) {
    const NurbsSurface& ga = a.surface->geometry;
    const NurbsSurface& gb = b.surface->geometry;
    const int n = rowLength(ga, a.side);
    if (n != rowLength(gb, b.side) ||
        (a.side < 2 ? ga.degreeV : ga.degreeU) != (b.side < 2 ? gb.degreeV : gb.degreeU))
        return false;
    for (int way = 0; way < 2; ++way) {
        bool same = true;
        for (int k = 0; k < n && same; ++k) {
            const auto [ia, ja] = onSide(ga, a.side, k);
            const auto [ib, jb] = onSide(gb, b.side, way == 0 ? k : n - 1 - k);
            same = glm::length(ga.points[size_t(ga.index(ia, ja))] -
                               gb.points[size_t(gb.index(ib, jb))]) <= eps &&
                   ga.weights[size_t(ga.index(ia, ja))] == gb.weights[size_t(gb.index(ib, jb))];
        }
        if (!same)
            continue;
        const std::vector<double> ka = unitKnots(ga, a.side, false);
        const std::vector<double> kb = unitKnots(gb, b.side, way == 1);
        bool knots = ka.size() == kb.size();
        for (size_t k = 0; k < ka.size() && knots; ++k)
            knots = std::abs(ka[k] - kb[k]) <= 1e-12;
        if (knots) {
            reversed = way == 1;
            return true;
        }
    }
    return false;
}

struct Partner {
    SideRef other;
    bool reversed = false;
};

/// The shared boundaries of `s`'s four sides among the untrimmed faces of the scene.
std::vector<std::pair<int, Partner>> partnersOf(const Scene& scene, const Surface& s, double eps) {
    std::vector<std::pair<int, Partner>> out;
    glm::dvec3 lo, hi;
    surfaceControlBounds(s.geometry, lo, hi);
    for (const Surface& n : scene.surfaces) {
        if (!n.trims.empty())
            continue;
        glm::dvec3 nlo, nhi;
        surfaceControlBounds(n.geometry, nlo, nhi);
        if (glm::any(glm::greaterThan(nlo, hi + eps)) || glm::any(glm::greaterThan(lo, nhi + eps)))
            continue;
        for (int a = 0; a < 4; ++a)
            for (int b = 0; b < 4; ++b) {
                if (n.id == s.id && a == b)
                    continue;
                bool reversed = false;
                if (sameBoundary({&s, a}, {&n, b}, eps, reversed))
                    out.push_back({a, Partner{{&n, b}, reversed}});
            }
    }
    return out;
}

/// The sides of g that point (i, j) lies on.
std::vector<int> sidesOf(const NurbsSurface& g, int i, int j) {
    std::vector<int> out;
    if (i == 0)
        out.push_back(0);
    if (i == g.countU - 1)
        out.push_back(1);
    if (j == 0)
        out.push_back(2);
    if (j == g.countV - 1)
        out.push_back(3);
    return out;
}

} // namespace

std::vector<LinkedMove> linkedMoves(const Scene& scene, SurfaceId surface,
                                    const std::vector<int>& indices,
                                    const std::vector<glm::dvec3>& positions, bool tangency) {
    const Surface* s = nullptr;
    for (const Surface& x : scene.surfaces)
        s = x.id == surface ? &x : s;
    if (!s || !s->trims.empty() || indices.size() != positions.size() ||
        indices.size() >= s->geometry.points.size())
        return {};
    const double eps = 1e-9 * std::max(size(s->geometry), 1e-300);
    // The partners of each surface reached, found once.
    std::map<SurfaceId, std::vector<std::pair<int, Partner>>> partners;
    const auto partnersFor = [&](const Surface& x) -> const std::vector<std::pair<int, Partner>>& {
        auto it = partners.find(x.id);
        if (it == partners.end())
            it = partners.emplace(x.id, partnersOf(scene, x, eps)).first;
        return it->second;
    };
    struct Item {
        const Surface* surface;
        int i, j;
        glm::dvec3 delta;
    };
    std::set<std::tuple<std::uint32_t, int, int>> seen;
    std::deque<Item> queue;
    const NurbsSurface& g = s->geometry;
    for (size_t k = 0; k < indices.size(); ++k) {
        const int index = indices[k];
        if (index < 0 || size_t(index) >= g.points.size())
            return {};
        seen.insert({surface.value, index % g.countU, index / g.countU});
    }
    for (size_t k = 0; k < indices.size(); ++k) {
        const glm::dvec3 delta = positions[k] - g.points[size_t(indices[k])];
        if (delta != glm::dvec3(0.0))
            queue.push_back({s, indices[k] % g.countU, indices[k] / g.countU, delta});
    }
    std::vector<LinkedMove> out;
    const auto reach = [&](const Surface* x, int i, int j, const glm::dvec3& delta) {
        if (!seen.insert({x->id.value, i, j}).second)
            return;
        const NurbsSurface& xg = x->geometry;
        const int index = xg.index(i, j);
        out.push_back({x->id, index, xg.points[size_t(index)] + delta});
        queue.push_back({x, i, j, delta});
    };
    while (!queue.empty()) {
        const Item item = queue.front();
        queue.pop_front();
        const NurbsSurface& xg = item.surface->geometry;
        const std::vector<int> sides = sidesOf(xg, item.i, item.j);
        if (sides.empty())
            continue;
        for (const auto& [side, partner] : partnersFor(*item.surface)) {
            if (std::find(sides.begin(), sides.end(), side) == sides.end())
                continue;
            // The position along this side, and the same along the partner's.
            const int along = side < 2 ? item.j : item.i;
            const NurbsSurface& pg = partner.other.surface->geometry;
            const int n = rowLength(pg, partner.other.side);
            const auto [pi, pj] =
                onSide(pg, partner.other.side, partner.reversed ? n - 1 - along : along);
            reach(partner.other.surface, pi, pj, item.delta);
            if (tangency) {
                const auto [ii, ij] = inward(side, item.i, item.j);
                if (ii >= 0 && ii < xg.countU && ij >= 0 && ij < xg.countV)
                    reach(item.surface, ii, ij, item.delta);
            }
        }
    }
    return out;
}

} // namespace kw
