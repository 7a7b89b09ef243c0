// The B-rep topology kept by an import: validation and the edits Document makes to it.
#include "model/document/topology.h"

#include "model/document/scene.h"

#include <QHash>
#include <QSet>
#include <algorithm>
#include <cmath>

namespace kw {

namespace {

QString at(const char* list, size_t index) {
    return QStringLiteral("%1[%2]").arg(QLatin1String(list)).arg(index);
}

struct LoopInfo {
    SurfaceId surface;
    int curves = 0;
};

bool sideOn(const EdgeUse& side, SurfaceId surface, TrimLoopId loop) {
    return side.surface == surface && side.loop == loop;
}

// Clears `closed` on the shell holding `surface`, noting the value it had (once per shell).
void openShellOf(Topology& topology, SurfaceId surface, TopologyPiece& piece) {
    for (Shell& shell : topology.shells) {
        if (!std::binary_search(shell.faces.begin(), shell.faces.end(), surface))
            continue;
        const bool noted = std::any_of(piece.closedBefore.begin(), piece.closedBefore.end(),
                                       [&](const auto& c) { return c.first == shell.id; });
        if (!noted)
            piece.closedBefore.emplace_back(shell.id, shell.closed);
        shell.closed = false;
    }
}

// The id of list[i] (edges or shells, named `noun`): not 0, and above the one before, so that
// each is listed once, in ascending order.
template <typename List>
std::optional<TopologyProblem> idOrderProblem(const List& list, size_t i, const QString& place,
                                              const char* noun) {
    const auto id = list[i].id;
    if (!id.isValid())
        return TopologyProblem{place + QStringLiteral(".id"),
                               QStringLiteral("%1 id is 0").arg(QLatin1String(noun))};
    if (i > 0 && !(list[i - 1].id < id))
        return TopologyProblem{place + QStringLiteral(".id"),
                               QStringLiteral("%1 id %2 does not follow %3 (%1s are listed once "
                                              "each, in ascending id order)")
                                   .arg(QLatin1String(noun))
                                   .arg(id.value)
                                   .arg(list[i - 1].id.value)};
    return std::nullopt;
}

} // namespace

std::optional<TopologyProblem> topologyProblem(const Scene& scene) {
    const Topology& t = scene.topology;
    if (t.edges.size() > size_t(kMaxSharedEdges))
        return TopologyProblem{QStringLiteral("edges"),
                               QStringLiteral("%1 shared edges, more than the limit %2")
                                   .arg(t.edges.size())
                                   .arg(kMaxSharedEdges)};
    if (t.shells.size() > size_t(kMaxShells))
        return TopologyProblem{QStringLiteral("shells"),
                               QStringLiteral("%1 shells, more than the limit %2")
                                   .arg(t.shells.size())
                                   .arg(kMaxShells)};
    if (t.empty())
        return std::nullopt;
    QHash<SurfaceId, int> surfaces;
    QHash<TrimLoopId, LoopInfo> loops;
    for (const Surface& s : scene.surfaces) {
        surfaces.insert(s.id, 0);
        for (const TrimLoop& l : s.trims)
            loops.insert(l.id, LoopInfo{s.id, int(l.curves.size())});
    }
    // A trim curve is a piece of one edge at most; loop ids are unique in the scene, so the loop
    // and the curve's index name it.
    QSet<quint64> used;
    for (size_t e = 0; e < t.edges.size(); ++e) {
        const SharedEdge& edge = t.edges[e];
        const QString place = at("edges", e);
        if (auto problem = idOrderProblem(t.edges, e, place, "edge"))
            return problem;
        if (!(std::isfinite(edge.tolerance) && edge.tolerance >= 0.0))
            return TopologyProblem{place + QStringLiteral(".tolerance"),
                                   QStringLiteral("edge %1's tolerance %2 is not a finite number "
                                                  ">= 0")
                                       .arg(edge.id.value)
                                       .arg(edge.tolerance)};
        for (size_t k = 0; k < 2; ++k) {
            const EdgeUse& side = edge.sides[k];
            const QString where = place + QStringLiteral(".") + at("sides", k);
            if (!surfaces.contains(side.surface))
                return TopologyProblem{
                    where + QStringLiteral(".surface"),
                    QStringLiteral("edge %1 names surface %2, which the scene does not have")
                        .arg(edge.id.value)
                        .arg(side.surface.value)};
            const auto loop = loops.constFind(side.loop);
            if (loop == loops.cend() || loop->surface != side.surface)
                return TopologyProblem{where + QStringLiteral(".loop"),
                                       QStringLiteral("edge %1 names trim loop %2 of surface %3, "
                                                      "which that surface does not have")
                                           .arg(edge.id.value)
                                           .arg(side.loop.value)
                                           .arg(side.surface.value)};
            if (side.curve < 0 || side.curve >= loop->curves)
                return TopologyProblem{
                    where + QStringLiteral(".curve"),
                    QStringLiteral("edge %1 names curve %2 of trim loop %3, which has %4 curve(s)")
                        .arg(edge.id.value)
                        .arg(side.curve)
                        .arg(side.loop.value)
                        .arg(loop->curves)};
            const quint64 key = (quint64(side.loop.value) << 32) | quint32(side.curve);
            if (used.contains(key))
                return TopologyProblem{where,
                                       QStringLiteral("curve %1 of trim loop %2 is already a side "
                                                      "of another edge (or of this one)")
                                           .arg(side.curve)
                                           .arg(side.loop.value)};
            used.insert(key);
        }
    }
    QSet<SurfaceId> inShell;
    for (size_t s = 0; s < t.shells.size(); ++s) {
        const Shell& shell = t.shells[s];
        const QString place = at("shells", s);
        if (auto problem = idOrderProblem(t.shells, s, place, "shell"))
            return problem;
        if (shell.solid < -1)
            return TopologyProblem{place + QStringLiteral(".solid"),
                                   QStringLiteral("solid %1 is below -1").arg(shell.solid)};
        for (size_t f = 0; f < shell.faces.size(); ++f) {
            const SurfaceId face = shell.faces[f];
            const QString where = place + QStringLiteral(".") + at("faces", f);
            if (!surfaces.contains(face))
                return TopologyProblem{
                    where,
                    QStringLiteral("shell %1 names surface %2, which the scene does not have")
                        .arg(shell.id.value)
                        .arg(face.value)};
            if (f > 0 && !(shell.faces[f - 1] < face))
                return TopologyProblem{where, QStringLiteral("surface %1 does not follow %2 (a "
                                                             "shell lists each face once, in "
                                                             "ascending id order)")
                                                  .arg(face.value)
                                                  .arg(shell.faces[f - 1].value)};
            if (inShell.contains(face))
                return TopologyProblem{
                    where, QStringLiteral("surface %1 is already a face of another shell")
                               .arg(face.value)};
            inShell.insert(face);
        }
    }
    return std::nullopt;
}

Status checkTopology(const Scene& scene) {
    if (const std::optional<TopologyProblem> p = topologyProblem(scene))
        return Error(QStringLiteral("topology: %1: %2").arg(p->place, p->reason));
    return ok();
}

const SharedEdge* findSharedEdge(const Topology& topology, EdgeId id) {
    const auto it = std::lower_bound(topology.edges.begin(), topology.edges.end(), id,
                                     [](const SharedEdge& e, EdgeId v) { return e.id < v; });
    return it != topology.edges.end() && it->id == id ? &*it : nullptr;
}

const Shell* shellOfSurface(const Topology& topology, SurfaceId surface) {
    for (const Shell& shell : topology.shells)
        if (std::binary_search(shell.faces.begin(), shell.faces.end(), surface))
            return &shell;
    return nullptr;
}

bool edgeTouches(const SharedEdge& edge, SurfaceId surface) {
    return edge.sides[0].surface == surface || edge.sides[1].surface == surface;
}

Topology topologyOfFaces(const Topology& topology, const std::vector<SurfaceId>& faces) {
    const auto kept = [&faces](SurfaceId id) {
        return std::binary_search(faces.begin(), faces.end(), id);
    };
    Topology out;
    for (const SharedEdge& e : topology.edges)
        if (kept(e.sides[0].surface) && kept(e.sides[1].surface))
            out.edges.push_back(e);
    for (const Shell& shell : topology.shells) {
        Shell part = shell;
        std::erase_if(part.faces, [&](SurfaceId f) { return !kept(f); });
        if (part.faces.empty())
            continue;
        part.closed = shell.closed && part.faces.size() == shell.faces.size();
        out.shells.push_back(std::move(part));
    }
    return out;
}

TopologyPiece takeSurfaceTopology(Topology& topology, SurfaceId surface) {
    TopologyPiece piece;
    openShellOf(topology, surface, piece);
    for (const SharedEdge& e : topology.edges)
        if (edgeTouches(e, surface)) {
            piece.edges.push_back(e);
            openShellOf(topology, e.sides[0].surface, piece);
            openShellOf(topology, e.sides[1].surface, piece);
        }
    std::erase_if(topology.edges, [&](const SharedEdge& e) { return edgeTouches(e, surface); });
    for (Shell& shell : topology.shells) {
        const auto it = std::lower_bound(shell.faces.begin(), shell.faces.end(), surface);
        if (it != shell.faces.end() && *it == surface) {
            shell.faces.erase(it);
            piece.shell = shell.id;
            piece.surface = surface;
        }
    }
    return piece;
}

TopologyPiece takeLoopTopology(Topology& topology, SurfaceId surface, TrimLoopId loop,
                               int loopCurves) {
    TopologyPiece piece;
    piece.loopCurves = loopCurves;
    const auto onLoop = [&](const SharedEdge& e) {
        return sideOn(e.sides[0], surface, loop) || sideOn(e.sides[1], surface, loop);
    };
    for (const SharedEdge& e : topology.edges)
        if (onLoop(e)) {
            piece.edges.push_back(e);
            openShellOf(topology, e.sides[0].surface, piece);
            openShellOf(topology, e.sides[1].surface, piece);
        }
    std::erase_if(topology.edges, onLoop);
    return piece;
}

int restoreTopology(Scene& scene, const TopologyPiece& piece) {
    Topology& t = scene.topology;
    QHash<SurfaceId, int> surfaces;
    QHash<TrimLoopId, LoopInfo> loops;
    for (const Surface& s : scene.surfaces) {
        surfaces.insert(s.id, 0);
        for (const TrimLoop& l : s.trims)
            loops.insert(l.id, LoopInfo{s.id, int(l.curves.size())});
    }
    int lost = 0;
    if (piece.shell.isValid()) {
        Shell* shell = nullptr;
        for (Shell& s : t.shells)
            shell = s.id == piece.shell ? &s : shell;
        if (shell && surfaces.contains(piece.surface) && !shellOfSurface(t, piece.surface))
            shell->faces.insert(
                std::lower_bound(shell->faces.begin(), shell->faces.end(), piece.surface),
                piece.surface);
        else
            ++lost;
    }
    const auto exists = [&](const EdgeUse& side) {
        const auto loop = loops.constFind(side.loop);
        return loop != loops.cend() && loop->surface == side.surface && side.curve >= 0 &&
               side.curve < loop->curves;
    };
    const auto taken = [&](const EdgeUse& side) {
        return std::any_of(t.edges.begin(), t.edges.end(), [&](const SharedEdge& x) {
            return (sideOn(x.sides[0], side.surface, side.loop) &&
                    x.sides[0].curve == side.curve) ||
                   (sideOn(x.sides[1], side.surface, side.loop) && x.sides[1].curve == side.curve);
        });
    };
    for (const SharedEdge& e : piece.edges) {
        if (!exists(e.sides[0]) || !exists(e.sides[1]) || findSharedEdge(t, e.id) ||
            taken(e.sides[0]) || taken(e.sides[1])) {
            ++lost;
            continue;
        }
        const auto it = std::lower_bound(t.edges.begin(), t.edges.end(), e.id,
                                         [](const SharedEdge& x, EdgeId v) { return x.id < v; });
        t.edges.insert(it, e);
    }
    if (lost == 0)
        for (const auto& [id, closed] : piece.closedBefore)
            for (Shell& shell : t.shells)
                if (shell.id == id)
                    shell.closed = closed;
    return lost;
}

void renumberLoopCurves(Topology& topology, SurfaceId surface, TrimLoopId loop,
                        const std::vector<int>& newIndex) {
    for (SharedEdge& e : topology.edges)
        for (EdgeUse& side : e.sides)
            if (sideOn(side, surface, loop) && side.curve >= 0 &&
                size_t(side.curve) < newIndex.size())
                side.curve = newIndex[size_t(side.curve)];
}

} // namespace kw
