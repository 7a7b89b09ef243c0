// The hybrid trim mask's CPU build and exact classification (see render/trim_grid.h).
#include "render/trim_grid.h"

#include <algorithm>
#include <cmath>

namespace kw {
namespace {

// Left (smaller u) and right end of a piece; a vertical piece keeps its own order, any order
// works there as long as both of its ends are used.
void ends(const TrimPiece& p, glm::dvec2& left, glm::dvec2& right) {
    if (p.p1.x < p.p0.x) {
        left = p.p1;
        right = p.p0;
    } else {
        left = p.p0;
        right = p.p1;
    }
}

// h_P(q) of render/trim_grid.h for one entry.
bool pieceTerm(const TrimPiece& p, const TrimArc& arc, std::uint32_t entry, glm::dvec2 q) {
    glm::dvec2 l, r;
    ends(p, l, r);
    if (q.x < l.x)
        return (entry >> 1) & 1u;
    if (q.x >= r.x)
        return entry & 1u;
    return trimArcPoint(arc, trimArcSolve(arc, 0, q.x, p.t0, p.t1)).y > q.y;
}

} // namespace

int TrimGrid::texelOf(glm::dvec2 uv) const {
    const int i =
        std::clamp(int(std::floor((uv.x - rect.x) / (rect.y - rect.x) * width)), 0, width - 1);
    const int j =
        std::clamp(int(std::floor((uv.y - rect.z) / (rect.w - rect.z) * height)), 0, height - 1);
    return j * width + i;
}

glm::dvec4 trimGridRect(const TrimArcs& arcs) {
    if (arcs.empty())
        return {0.0, 1.0, 0.0, 1.0};
    const glm::dvec2 extent = arcs.hi - arcs.lo;
    const double margin = 1e-6 * std::max({extent.x, extent.y, 1e-300}) + 1e-12;
    return {arcs.lo.x - margin, arcs.hi.x + margin, arcs.lo.y - margin, arcs.hi.y + margin};
}

glm::ivec2 trimGridResolution(const TrimArcs& arcs, int cap) {
    cap = std::max(cap, 1);
    const double want = 16.0 * std::sqrt(double(arcs.arcs.size()));
    int n = std::min(kMinTrimGridSize, cap);
    while (n < want && n < cap)
        n *= 2;
    n = std::min(n, cap);
    return {n, n};
}

TrimGrid makeTrimGrid(const TrimArcs& arcs, glm::ivec2 size) {
    TrimGrid g;
    g.rect = trimGridRect(arcs);
    g.width = std::max(size.x, 1);
    g.height = std::max(size.y, 1);
    const double du = (g.rect.y - g.rect.x) / g.width, dv = (g.rect.w - g.rect.z) / g.height;
    const size_t count = size_t(g.width) * size_t(g.height);
    g.base.assign(count, arcs.empty() ? 1 : 0);
    g.first.assign(count + 1, 0);
    if (arcs.empty())
        return g;

    // 1. Cut every arc where it crosses a grid line; each piece lies in one texel (up to the
    //    rounding of the cut), which the piece's middle names.
    std::vector<int> texelOfPiece;
    for (size_t k = 0; k < arcs.arcs.size(); ++k) {
        const TrimArc& a = arcs.arcs[k];
        std::vector<double> ts{0.0, 1.0};
        for (int axis = 0; axis < 2; ++axis) {
            const double lo = std::min(a.start[axis], a.end[axis]);
            const double hi = std::max(a.start[axis], a.end[axis]);
            const double origin = axis == 0 ? g.rect.x : g.rect.z, step = axis == 0 ? du : dv;
            const int n = axis == 0 ? g.width : g.height;
            for (int m = std::max(1, int(std::floor((lo - origin) / step)));
                 m < n && origin + m * step < hi; ++m) {
                const double line = origin + m * step;
                if (line > lo)
                    ts.push_back(trimArcSolve(a, axis, line, 0.0, 1.0));
            }
        }
        std::sort(ts.begin(), ts.end());
        ts.erase(std::unique(ts.begin(), ts.end()), ts.end());
        glm::dvec2 prev = a.start;
        for (size_t s = 0; s + 1 < ts.size(); ++s) {
            const glm::dvec2 next = s + 2 == ts.size() ? a.end : trimArcPoint(a, ts[s + 1]);
            TrimPiece p;
            p.arc = std::uint32_t(k);
            p.t0 = ts[s];
            p.t1 = ts[s + 1];
            p.p0 = prev;
            p.p1 = next;
            g.pieces.push_back(p);
            texelOfPiece.push_back(g.texelOf(trimArcPoint(a, 0.5 * (p.t0 + p.t1))));
            prev = next;
        }
    }

    // 2. Lists per texel (counting sort), with each piece's end bits for its texel. A piece is
    //    also listed in every texel its box comes within kListMargin texel of: a float lookup
    //    may put a point a rounding error across a texel border, and the formula of TrimGrid
    //    holds a little beyond the texel only when the pieces ending on its border are listed
    //    on both sides (their steps on the vertical line through the shared end cancel).
    constexpr double kListMargin = 1e-3;
    std::vector<std::pair<int, std::uint32_t>> listed; // (texel, piece)
    for (size_t p = 0; p < g.pieces.size(); ++p) {
        const TrimPiece& pc = g.pieces[p];
        const glm::dvec2 lo = glm::min(pc.p0, pc.p1), hi = glm::max(pc.p0, pc.p1);
        const int i0 = std::max(0, int(std::floor((lo.x - g.rect.x) / du - kListMargin)));
        const int i1 = std::min(g.width - 1, int(std::floor((hi.x - g.rect.x) / du + kListMargin)));
        const int j0 = std::max(0, int(std::floor((lo.y - g.rect.z) / dv - kListMargin)));
        const int j1 =
            std::min(g.height - 1, int(std::floor((hi.y - g.rect.z) / dv + kListMargin)));
        bool home = false;
        for (int j = j0; j <= j1; ++j)
            for (int i = i0; i <= i1; ++i) {
                listed.push_back({j * g.width + i, std::uint32_t(p)});
                home = home || j * g.width + i == texelOfPiece[p];
            }
        if (!home)
            listed.push_back({texelOfPiece[p], std::uint32_t(p)});
    }
    for (const auto& [t, p] : listed)
        ++g.first[size_t(t) + 1];
    for (size_t k = 0; k < count; ++k)
        g.first[k + 1] += g.first[k];
    g.entries.resize(listed.size());
    std::vector<std::uint32_t> fill(g.first.begin(), g.first.end() - 1);
    for (const auto& [t, p] : listed) {
        const double vT = g.rect.z + (t / g.width + 0.5) * dv;
        glm::dvec2 l, r;
        ends(g.pieces[p], l, r);
        g.entries[fill[size_t(t)]++] =
            std::uint32_t(p) << 2 | std::uint32_t(l.y > vT) << 1 | std::uint32_t(r.y > vT);
    }

    // 3. Base bits, one column at a time: the ray parity f at each texel centre from the pieces
    //    crossing the column's centre line (all of them lie in that column), with the listed
    //    pieces' terms h_P taken out. A listed piece crossing the centre line has g_P = h_P there
    //    (the same computed v on both sides), so it is skipped rather than added and removed.
    std::vector<double> ys;
    std::vector<double> ysOfTexel;
    for (int i = 0; i < g.width; ++i) {
        const double uc = g.rect.x + (i + 0.5) * du;
        ys.clear();
        ysOfTexel.assign(size_t(g.height), 0.0);
        std::vector<std::vector<std::pair<std::uint32_t, double>>> crossing(size_t(g.height));
        for (int j = 0; j < g.height; ++j) {
            const int t = j * g.width + i;
            for (std::uint32_t e = g.first[size_t(t)]; e < g.first[size_t(t) + 1]; ++e) {
                const TrimPiece& p = g.pieces[g.entries[e] >> 2];
                glm::dvec2 l, r;
                ends(p, l, r);
                if (uc < l.x || uc >= r.x)
                    continue;
                const TrimArc& a = arcs.arcs[p.arc];
                const double y = trimArcPoint(a, trimArcSolve(a, 0, uc, p.t0, p.t1)).y;
                if (texelOfPiece[g.entries[e] >> 2] == t)
                    ys.push_back(y); // each piece once, from its home texel
                crossing[size_t(j)].push_back({e, y});
            }
        }
        std::sort(ys.begin(), ys.end());
        for (int j = 0; j < g.height; ++j) {
            const int t = j * g.width + i;
            const double vc = g.rect.z + (j + 0.5) * dv;
            std::size_t above = size_t(ys.end() - std::upper_bound(ys.begin(), ys.end(), vc));
            for (const auto& [e, y] : crossing[size_t(j)])
                above -= y > vc ? 1 : 0;
            bool parity = above & 1u;
            for (std::uint32_t e = g.first[size_t(t)]; e < g.first[size_t(t) + 1]; ++e) {
                const TrimPiece& p = g.pieces[g.entries[e] >> 2];
                glm::dvec2 l, r;
                ends(p, l, r);
                if (uc < l.x)
                    parity ^= bool((g.entries[e] >> 1) & 1u);
                else if (uc >= r.x)
                    parity ^= bool(g.entries[e] & 1u);
            }
            g.base[size_t(t)] = parity ? 1 : 0;
        }
    }
    return g;
}

bool trimGridContains(const TrimGrid& g, const TrimArcs& arcs, glm::dvec2 uv) {
    if (arcs.empty())
        return true;
    if (uv.x < g.rect.x || uv.x > g.rect.y || uv.y < g.rect.z || uv.y > g.rect.w)
        return false;
    const int t = g.texelOf(uv);
    bool inside = g.base[size_t(t)] != 0;
    for (std::uint32_t e = g.first[size_t(t)]; e < g.first[size_t(t) + 1]; ++e) {
        const TrimPiece& p = g.pieces[g.entries[e] >> 2];
        inside ^= pieceTerm(p, arcs.arcs[p.arc], g.entries[e], uv);
    }
    return inside;
}

TrimGridStats trimGridStats(const TrimGrid& g, const TrimArcs& arcs) {
    TrimGridStats s;
    for (int k = 0; k < g.texelCount(); ++k) {
        const int n = int(g.first[size_t(k) + 1] - g.first[size_t(k)]);
        s.edgeTexels += n > 0;
        s.maxEntries = std::max(s.maxEntries, n);
    }
    s.entries = std::int64_t(g.entries.size());
    s.pieces = std::int64_t(g.pieces.size());
    s.arcs = std::int64_t(arcs.arcs.size());
    for (const TrimArc& a : arcs.arcs)
        s.controlPoints += std::int64_t(a.hw.size());
    s.bytes = 4 * std::int64_t(g.texelCount()) + 4 * s.entries + 32 * s.pieces +
              16 * s.controlPoints + 16 * s.arcs;
    return s;
}

} // namespace kw
