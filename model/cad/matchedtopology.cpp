// Shared edges found by matching the boundaries of faces without a record (kw::matchedTopology).
#include "model/cad/matchedtopology.h"

#include "model/analysis/continuity.h"
#include "model/document/seamgaps.h"

#include <QHash>
#include <algorithm>
#include <map>
#include <numeric>

namespace kw {
namespace {

// Sewing at a tolerance joins edges its own coarse measure finds within it: hammer.iges's
// seams, all sewn at 0.41 mm, lie up to 2.46 mm apart on the exact surfaces. Pairs are looked
// for within this many tolerances, each then gets its measured gap as its own tolerance.
constexpr double kMatchFactor = 4.0;
// Lengths below this share of the tolerance are points (a collapsed curve, a closed curve's
// ends).
constexpr double kPointFraction = 1e-4;

// The trim curve a side names; nullptr for a domain edge or a side the surface lacks.
const NurbsCurve2* trimCurve(const Surface& s, const ContinuitySide& side) {
    if (side.domainEdge != DomainEdge::None || side.curve < 0)
        return nullptr;
    for (const TrimLoop& l : s.trims)
        if (l.id == side.loop)
            return size_t(side.curve) < l.curves.size() ? &l.curves[size_t(side.curve)] : nullptr;
    return nullptr;
}

glm::dvec3 curveEnd(const Surface& s, const NurbsCurve2& c, bool last) {
    // Trim curves are clamped: their ends are their first and last control points.
    const glm::dvec2 uv = last ? c.points.back() : c.points.front();
    return surfacePoint(s.geometry, uv.x, uv.y);
}

// The largest distance from either side's samples to the other side (kw::seamGaps' measure).
double pairGap(const Surface& a, const NurbsCurve2& ca, const Surface& b, const NurbsCurve2& cb) {
    const SeamSide sa = makeSeamSide(a.geometry, ca, kMinSeamSamples);
    const SeamSide sb = makeSeamSide(b.geometry, cb, kMinSeamSamples);
    double gap = 0.0;
    for (const glm::dvec3& p : sa.at)
        gap = std::max(gap, nearestOnSeamSide(sb, p).distance);
    for (const glm::dvec3& p : sb.at)
        gap = std::max(gap, nearestOnSeamSide(sa, p).distance);
    return gap;
}

struct Groups {
    std::vector<int> parent;
    explicit Groups(int n) : parent(size_t(n)) { std::iota(parent.begin(), parent.end(), 0); }
    int find(int x) {
        while (parent[size_t(x)] != x)
            x = parent[size_t(x)] = parent[size_t(parent[size_t(x)])];
        return x;
    }
    void join(int a, int b) { parent[size_t(find(a))] = find(b); }
};

} // namespace

MatchedTopology matchedTopology(const Scene& scene, double tolerance, double maxGap) {
    MatchedTopology out;
    const int n = int(scene.surfaces.size());
    QHash<SurfaceId, int> index;
    for (int k = 0; k < n; ++k)
        index.insert(scene.surfaces[size_t(k)].id, k);
    // Faces the record touches keep the record's edges; a face matched to one of them would
    // border a face built without its help.
    std::vector<bool> taken(size_t(n), true);
    for (const SharedEdge& e : scene.topology.edges)
        for (const EdgeUse& u : e.sides)
            if (const auto it = index.constFind(u.surface); it != index.cend())
                taken[size_t(*it)] = false;
    for (const Shell& s : scene.topology.shells)
        for (SurfaceId f : s.faces)
            if (const auto it = index.constFind(f); it != index.cend())
                taken[size_t(*it)] = false;
    std::vector<bool> recorded(static_cast<size_t>(n), false);
    for (int k = 0; k < n; ++k)
        recorded[size_t(k)] = !taken[size_t(k)];

    ContinuityTolerances tol;
    // Curves shorter than the tolerance are edges too (the kernel would call them degenerate at
    // g0 = tolerance): on a scene whose diagonal is large next to its parts (a 10,000-face tiling)
    // the sewing tolerance exceeds a small face's curves.
    const double point = kPointFraction * tolerance;
    tol.g0 = point;
    tol.match = kMatchFactor * tolerance;
    const ContinuityTopology topo = continuityTopology(scene, tol);

    // Every candidate pairing the kernel found, with whether it can be one edge (two whole trim
    // curves whose ends meet) and how far apart its ends lie.
    struct Pair {
        int face[2];
        const NurbsCurve2* curve[2];
        ContinuitySide side[2];
        EdgeUse use[2];
        bool usable = false;
        double endGap = 0.0;
    };
    std::vector<Pair> pairs;
    for (const ContinuityEdge& e : topo.edges) {
        if (e.recorded.isValid())
            continue;
        const auto ia = index.constFind(e.sides[0].surface),
                   ib = index.constFind(e.sides[1].surface);
        if (ia == index.cend() || ib == index.cend())
            continue;
        Pair p;
        p.face[0] = *ia;
        p.face[1] = *ib;
        const Surface& sa = scene.surfaces[size_t(p.face[0])];
        const Surface& sb = scene.surfaces[size_t(p.face[1])];
        p.side[0] = e.sides[0];
        p.side[1] = e.sides[1];
        p.curve[0] = trimCurve(sa, e.sides[0]);
        p.curve[1] = trimCurve(sb, e.sides[1]);
        bool reversed = false;
        p.usable = !recorded[size_t(p.face[0])] && !recorded[size_t(p.face[1])] && p.curve[0] &&
                   p.curve[1] && e.covers[0] && e.covers[1];
        if (p.usable) {
            const glm::dvec3 a0 = curveEnd(sa, *p.curve[0], false),
                             a1 = curveEnd(sa, *p.curve[0], true);
            const glm::dvec3 b0 = curveEnd(sb, *p.curve[1], false),
                             b1 = curveEnd(sb, *p.curve[1], true);
            reversed = glm::distance(b0, a0) > glm::distance(b0, a1);
            const bool closed = glm::distance(a0, a1) <= point;
            p.endGap = reversed ? std::max(glm::distance(b0, a1), glm::distance(b1, a0))
                                : std::max(glm::distance(b0, a0), glm::distance(b1, a1));
            p.usable = !closed && p.endGap <= tolerance;
        }
        p.use[0] = EdgeUse{sa.id, e.sides[0].loop, e.sides[0].curve, false};
        p.use[1] = EdgeUse{sb.id, e.sides[1].loop, e.sides[1].curve, reversed};
        pairs.push_back(p);
    }
    // At a loose tolerance a short curve may lie near two others: each curve keeps the usable
    // pairing whose ends meet best, and a pairing is kept when it is the best of both its
    // curves. One not kept is harmless where both its curves have a kept one; otherwise it is a
    // T-junction, a pairing with an untrimmed face's edge or a closed curve, and its faces (and
    // their groups) are left to sewing.
    std::map<ContinuitySide, size_t> best;
    for (size_t k = 0; k < pairs.size(); ++k) {
        if (!pairs[k].usable)
            continue;
        for (const ContinuitySide& side : pairs[k].side) {
            const auto it = best.find(side);
            if (it == best.end() || pairs[k].endGap < pairs[it->second].endGap)
                best[side] = k;
        }
    }
    const auto isBest = [&](const ContinuitySide& side, size_t k) {
        const auto it = best.find(side);
        return it != best.end() && it->second == k;
    };
    Groups groups(n);
    std::vector<bool> kept(pairs.size(), false);
    for (size_t k = 0; k < pairs.size(); ++k)
        kept[k] = pairs[k].usable && isBest(pairs[k].side[0], k) && isBest(pairs[k].side[1], k);
    for (size_t k = 0; k < pairs.size(); ++k) {
        const Pair& p = pairs[k];
        const bool covered = best.count(p.side[0]) && best.count(p.side[1]) &&
                             kept[best.at(p.side[0])] && kept[best.at(p.side[1])];
        if (kept[k]) {
            groups.join(p.face[0], p.face[1]);
        } else if (!covered) {
            groups.join(p.face[0], p.face[1]);
            taken[size_t(p.face[0])] = taken[size_t(p.face[1])] = false;
        }
    }
    // Untrimmed faces are bounded by their domain, which the recorded path does not build.
    for (int k = 0; k < n; ++k)
        if (scene.surfaces[size_t(k)].trims.empty())
            taken[size_t(k)] = false;
    // A group is taken whole or not at all.
    std::vector<bool> groupTaken(size_t(n), true);
    for (int k = 0; k < n; ++k)
        if (!taken[size_t(k)])
            groupTaken[size_t(groups.find(k))] = false;
    for (int k = 0; k < n; ++k)
        taken[size_t(k)] = groupTaken[size_t(groups.find(k))];

    std::uint32_t nextEdge = 1, nextShell = 1;
    for (const SharedEdge& e : scene.topology.edges)
        nextEdge = std::max(nextEdge, e.id.value + 1);
    for (const Shell& s : scene.topology.shells)
        nextShell = std::max(nextShell, s.id.value + 1);
    std::vector<const Pair*> chosen;
    for (size_t k = 0; k < pairs.size(); ++k)
        if (kept[k] && taken[size_t(pairs[k].face[0])])
            chosen.push_back(&pairs[k]);
    out.edges.resize(chosen.size());
    const auto measure = [&](size_t from, size_t to) {
        for (size_t k = from; k < to; ++k) {
            const Pair& p = *chosen[k];
            SharedEdge& e = out.edges[k];
            e.sides = {p.use[0], p.use[1]};
            e.tolerance = pairGap(scene.surfaces[size_t(p.face[0])], *p.curve[0],
                                  scene.surfaces[size_t(p.face[1])], *p.curve[1]);
        }
    };
    forEachRange(chosen.size(), 64, measure);
    // Pairs too far apart to be one edge stay two free curves; shells are the groups the
    // remaining edges join.
    std::vector<const Pair*> withinGap;
    std::vector<SharedEdge> edges;
    for (size_t k = 0; k < chosen.size(); ++k) {
        if (out.edges[k].tolerance > maxGap) {
            const Pair& p = *chosen[k];
            out.tooFar.push_back(
                {{scene.surfaces[size_t(p.face[0])].id, scene.surfaces[size_t(p.face[1])].id},
                 out.edges[k].tolerance});
            continue;
        }
        withinGap.push_back(chosen[k]);
        edges.push_back(out.edges[k]);
    }
    chosen = std::move(withinGap);
    out.edges = std::move(edges);
    for (SharedEdge& e : out.edges)
        e.id = EdgeId{nextEdge++};
    if (!out.tooFar.empty()) {
        Groups joined(n);
        for (const Pair* p : chosen)
            joined.join(p->face[0], p->face[1]);
        groups = joined;
    }

    // One shell per group; closed when each of its curves is a side of an edge or collapses to
    // a point.
    std::map<int, std::vector<int>> members;
    for (int k = 0; k < n; ++k)
        if (taken[size_t(k)])
            members[groups.find(k)].push_back(k);
    std::map<int, int> sidesUsed;
    for (const Pair* p : chosen)
        sidesUsed[groups.find(p->face[0])] += 2;
    std::map<int, int> degenerate;
    for (const ContinuitySide& side : topo.degenerateSides)
        if (const auto it = index.constFind(side.surface); it != index.cend() && taken[size_t(*it)])
            ++degenerate[groups.find(*it)];
    for (const auto& [root, faces] : members) {
        Shell shell;
        shell.id = ShellId{nextShell++};
        int curves = 0;
        for (int k : faces) {
            shell.faces.push_back(scene.surfaces[size_t(k)].id);
            for (const TrimLoop& l : scene.surfaces[size_t(k)].trims)
                curves += int(l.curves.size());
        }
        std::sort(shell.faces.begin(), shell.faces.end());
        shell.closed = sidesUsed[root] + degenerate[root] == curves;
        out.faces += int(faces.size());
        out.shells.push_back(std::move(shell));
    }
    for (int k = 0; k < n; ++k)
        if (!taken[size_t(k)] && !recorded[size_t(k)])
            ++out.leftToSewing;
    return out;
}

} // namespace kw
