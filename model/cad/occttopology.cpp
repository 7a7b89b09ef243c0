// The imported faces' topology (kw::occt::recordTopology): which trim curves are one B-rep edge,
// which faces one shell, so that writers can share the edges again and edits can be checked
// against the seams they may open.
#include "model/cad/occt_internal.h"

#include <BRepCheck_Shell.hxx>
#include <BRep_Tool.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Shell.hxx>
#include <algorithm>
#include <map>
#include <set>

namespace kw::occt {

namespace {

struct Use {
    EdgeUse side;
    double tolerance = 0.0;
};

} // namespace

void recordTopology(const TopoDS_Shape& shape, const TopTools_IndexedMapOfShape& faces,
                    const std::vector<int>& sourceFaces, const std::vector<FaceEdges>& faceEdges,
                    Scene& scene, QStringList& warnings) {
    Topology topology;
    TopTools_IndexedMapOfShape edges;
    TopExp::MapShapes(shape, TopAbs_EDGE, edges);
    // The trim curves made from each edge, by its number (a map: the edges come out in order).
    std::map<int, std::vector<Use>> uses;
    for (size_t k = 0; k < scene.surfaces.size() && k < faceEdges.size(); ++k) {
        const Surface& s = scene.surfaces[k];
        for (size_t l = 0; l < s.trims.size() && l < faceEdges[k].size(); ++l) {
            const std::vector<CurveEdge>& curves = faceEdges[k][l];
            for (size_t c = 0; c < curves.size() && c < s.trims[l].curves.size(); ++c) {
                const CurveEdge& e = curves[c];
                // A collapsed edge (a sphere's pole) is a point: nothing to share.
                if (e.edge.IsNull() || BRep_Tool::Degenerated(e.edge))
                    continue;
                const int number = edges.FindIndex(e.edge);
                if (number > 0)
                    uses[number].push_back(
                        Use{EdgeUse{s.id, s.trims[l].id, int(c), e.reversed}, e.tolerance});
            }
        }
    }
    int nonManifold = 0;
    std::set<int> recorded;
    for (const auto& [number, list] : uses) {
        if (list.size() > 2)
            ++nonManifold;
        if (list.size() != 2)
            continue;
        SharedEdge edge;
        edge.id = EdgeId{std::uint32_t(number)};
        edge.tolerance = std::max({BRep_Tool::Tolerance(TopoDS::Edge(edges(number))),
                                   list[0].tolerance, list[1].tolerance});
        edge.sides = {list[0].side, list[1].side};
        topology.edges.push_back(edge);
        recorded.insert(number);
    }
    if (nonManifold > 0)
        warnings << QStringLiteral("%1 edge(s) are shared by more than two faces (non-manifold); "
                                   "they are not kept as shared edges")
                        .arg(nonManifold);

    // The surface each of the file's faces became (-1: skipped).
    std::vector<int> surfaceOf(size_t(faces.Extent()) + 1, -1);
    for (size_t i = 0; i < sourceFaces.size(); ++i)
        surfaceOf[size_t(sourceFaces[i])] = int(i);
    TopTools_IndexedMapOfShape shells;
    TopExp::MapShapes(shape, TopAbs_SHELL, shells);
    std::set<SurfaceId> inShell;
    for (int i = 1; i <= shells.Extent(); ++i) {
        const TopoDS_Shell shell = TopoDS::Shell(shells(i));
        Shell record;
        record.id = ShellId{std::uint32_t(i)};
        bool whole = true;
        std::set<int> solids;
        for (TopExp_Explorer f(shell, TopAbs_FACE); f.More(); f.Next()) {
            const int k = faces.FindIndex(f.Current());
            const int s = k > 0 ? surfaceOf[size_t(k)] : -1;
            if (s < 0) {
                whole = false; // skipped: the shell has a hole where it was
                continue;
            }
            const Surface& surface = scene.surfaces[size_t(s)];
            if (std::find(record.faces.begin(), record.faces.end(), surface.id) !=
                record.faces.end())
                continue; // used twice in the shell
            if (!inShell.insert(surface.id).second) {
                whole = false; // kept in the shell that listed it first
                continue;
            }
            record.faces.push_back(surface.id);
            solids.insert(surface.solid);
        }
        if (record.faces.empty())
            continue;
        std::sort(record.faces.begin(), record.faces.end());
        bool closed = whole && BRepCheck_Shell(shell).Closed() == BRepCheck_NoError;
        if (closed) {
            TopTools_IndexedMapOfShape own;
            TopExp::MapShapes(shell, TopAbs_EDGE, own);
            for (int e = 1; closed && e <= own.Extent(); ++e) {
                const TopoDS_Edge& edge = TopoDS::Edge(own(e));
                closed = BRep_Tool::Degenerated(edge) || recorded.count(edges.FindIndex(edge)) > 0;
            }
        }
        record.closed = closed;
        record.solid = solids.size() == 1 ? *solids.begin() : -1;
        topology.shells.push_back(std::move(record));
    }
    scene.topology = std::move(topology);
}

} // namespace kw::occt
