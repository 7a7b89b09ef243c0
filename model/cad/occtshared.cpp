// Faces built from the import's record: each recorded shared edge one OpenCASCADE edge with both
// faces' own p-curves, its vertices shared, so nothing has to be sewn and no trim moves.
#include "model/cad/occtbuild.h"
#include "model/nurbs/trim.h"

#include <BRepCheck_Analyzer.hxx>
#include <BRepLib.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <BSplCLib.hxx>
#include <Geom_Curve.hxx>
#include <Standard_ErrorHandler.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Vertex.hxx>
#include <TopoDS_Wire.hxx>
#include <algorithm>
#include <limits>
#include <map>
#include <numeric>
#include <unordered_map>

namespace kw::occt {
namespace {

// Union-find over loop junctions (junction j of a loop: where its curve j starts and curve j - 1
// ends), so that the ends of a shared edge are one vertex on both faces.
struct Junctions {
    std::vector<int> parent;
    int add() {
        parent.push_back(int(parent.size()));
        return parent.back();
    }
    int find(int x) {
        while (parent[size_t(x)] != x)
            x = parent[size_t(x)] = parent[size_t(parent[size_t(x)])];
        return x;
    }
    void join(int a, int b) { parent[size_t(find(a))] = find(b); }
};

// A trim curve by its place: surface index, loop index, curve index.
struct Place {
    int surface = -1, loop = -1, curve = -1;
    auto operator<=>(const Place&) const = default;
};

// One recorded edge to build: its sides' places and directions.
struct Shared {
    Place side[2];
    bool reversed[2] = {false, false};
    double tolerance = 0.0;
    TopoDS_Edge edge;
};

// `c` with its knots mapped linearly onto [a, b] (the image does not change).
void reparameterise(const Handle(Geom2d_BSplineCurve) & c, double a, double b) {
    if (c->FirstParameter() == a && c->LastParameter() == b)
        return;
    TColStd_Array1OfReal knots(1, c->NbKnots());
    c->Knots(knots);
    BSplCLib::Reparametrize(a, b, knots);
    c->SetKnots(knots);
}

// Turns faces of each shell so that every edge two of its faces share is used once forward and
// once reversed, as a closed shell needs: the record of a STEP or BREP import is oriented so
// already, but faces paired by matching (loose IGES trimmed surfaces) face whichever way their
// surfaces run. Breadth first from each shell's first face; only TopoDS orientations change.
void orientShells(std::vector<TopoDS_Face>& faces, const std::vector<std::vector<int>>& shells) {
    for (const std::vector<int>& members : shells) {
        // Each edge's uses: face index, orientation in the face as it stands.
        std::map<const TopoDS_TShape*, std::vector<std::pair<int, TopAbs_Orientation>>> uses;
        for (int k : members) {
            if (faces[size_t(k)].IsNull())
                continue;
            for (TopExp_Explorer e(faces[size_t(k)], TopAbs_EDGE); e.More(); e.Next())
                uses[e.Current().TShape().get()].emplace_back(k, e.Current().Orientation());
        }
        std::map<int, std::vector<std::pair<int, bool>>> next; // face -> (face, same way)
        for (const auto& [edge, list] : uses) {
            if (list.size() != 2 || list[0].first == list[1].first)
                continue;
            const bool same = list[0].second == list[1].second;
            next[list[0].first].emplace_back(list[1].first, same);
            next[list[1].first].emplace_back(list[0].first, same);
        }
        std::map<int, bool> flip;
        for (int start : members) {
            if (faces[size_t(start)].IsNull() || flip.count(start))
                continue;
            flip[start] = false;
            std::vector<int> todo{start};
            while (!todo.empty()) {
                const int f = todo.back();
                todo.pop_back();
                for (const auto& [g, same] : next[f]) {
                    if (flip.count(g))
                        continue;
                    // Used the same way by both: the neighbour turns unless this face turned.
                    flip[g] = flip[f] != same;
                    todo.push_back(g);
                }
            }
        }
        for (const auto& [k, turn] : flip)
            if (turn)
                faces[size_t(k)].Reverse();
    }
}

// A shared edge's 3D curve is approximated within this many times the least tolerance (1e-7 of
// the model's diagonal by default), or the edge's own tolerance when that is smaller.
constexpr double kCurveTolerance = 100.0;

QString failure(const Standard_Failure& e) {
    return QStringLiteral("%1 (%2)").arg(QString::fromUtf8(e.GetMessageString()),
                                         QString::fromLatin1(e.DynamicType()->Name()));
}

class Builder {
public:
    Builder(const Scene& scene, double tolerance) : scene_(scene), tolerance_(tolerance) {}

    Status run(const std::vector<std::uint32_t>& openEdges, RecordedFaces& out);

private:
    // The junction ids of a loop (one per curve), made on first use.
    int junction(const Place& p, int offset) {
        std::vector<int>& js = junctions_[{p.surface, p.loop, 0}];
        const int n = int(scene_.surfaces[size_t(p.surface)].trims[size_t(p.loop)].curves.size());
        if (js.empty())
            for (int k = 0; k < n; ++k)
                js.push_back(uf_.add());
        return js[size_t(((p.curve + offset) % n + n) % n)];
    }
    const NurbsCurve2& curve(const Place& p) const {
        return scene_.surfaces[size_t(p.surface)].trims[size_t(p.loop)].curves[size_t(p.curve)];
    }
    bool makeVertices();
    Status makeSharedEdge(Shared& s);
    Status makeFace(int index, TopoDS_Face& face);

    const Scene& scene_;
    double tolerance_;
    BRep_Builder b_;
    Junctions uf_;
    std::map<Place, std::vector<int>> junctions_; // keyed by {surface, loop, 0}
    std::map<int, TopoDS_Vertex> vertices_;       // by junction class
    std::vector<Handle(Geom_BSplineSurface)> geoms_;
    std::vector<std::vector<int>> directions_; // loopDirections per covered surface
    std::map<Place, int> sharedOf_;            // a curve's shared edge (index into shared_)
    std::vector<Shared> shared_;
};

bool Builder::makeVertices() {
    // Every end of every curve of a covered face, by junction class: the vertex sits at their
    // mean, with a tolerance reaching all of them.
    std::map<int, std::vector<gp_Pnt>> points;
    for (const auto& [key, js] : junctions_) {
        const Surface& s = scene_.surfaces[size_t(key.surface)];
        const TrimLoop& loop = s.trims[size_t(key.loop)];
        const Handle(Geom_BSplineSurface)& g = geoms_[size_t(key.surface)];
        const int n = int(loop.curves.size());
        for (int k = 0; k < n; ++k) {
            const NurbsCurve2& c = loop.curves[size_t(k)];
            const NurbsCurve2& prev = loop.curves[size_t((k + n - 1) % n)];
            const glm::dvec2 a = c.points.front(), z = prev.points.back();
            auto& list = points[uf_.find(js[size_t(k)])];
            list.push_back(g->Value(a.x, a.y));
            list.push_back(g->Value(z.x, z.y));
        }
    }
    for (const auto& [root, list] : points) {
        gp_XYZ sum(0, 0, 0);
        for (const gp_Pnt& p : list)
            sum += p.XYZ();
        const gp_Pnt mid(sum / double(list.size()));
        double reach = 0.0;
        for (const gp_Pnt& p : list)
            reach = std::max(reach, mid.Distance(p));
        TopoDS_Vertex v;
        b_.MakeVertex(v, mid, std::max(tolerance_, reach * 1.001));
        vertices_[root] = v;
    }
    return true;
}

Status Builder::makeSharedEdge(Shared& s) {
    // The edge runs as the first side's curve does when that side is not reversed.
    Handle(Geom2d_BSplineCurve) c[2];
    for (int k = 0; k < 2; ++k) {
        const NurbsCurve2& stored = curve(s.side[k]);
        Expected<Handle(Geom2d_BSplineCurve)> made =
            makeGeomCurve(s.reversed[k] ? trimCurveReversed(stored) : stored);
        if (!made)
            return made.error();
        c[k] = *made;
    }
    const double t0 = c[0]->FirstParameter(), t1 = c[0]->LastParameter();
    reparameterise(c[1], t0, t1);
    TopoDS_Edge& e = s.edge;
    b_.MakeEdge(e);
    // The source's 3D curve lay within the recorded tolerance of both sides, so the sides lie
    // within twice that of one another; the 3D curve here is built from the first side. Within
    // that SameParameter finds the second p-curve in step with the 3D curve and keeps it as it
    // is; with less, it would approximate it anew and move the face's trim by up to the gap.
    const double tol = std::max(tolerance_, s.tolerance);
    const Place& a = s.side[0];
    const Place& z = s.side[1];
    if (a.surface == z.surface) {
        // A seam: the p-curve of the edge used FORWARD in the face's wire first.
        const Surface& surf = scene_.surfaces[size_t(a.surface)];
        (void)surf;
        const bool forwardA =
            !s.reversed[0] == (directions_[size_t(a.surface)][size_t(a.loop)] > 0);
        const bool forwardZ =
            !s.reversed[1] == (directions_[size_t(z.surface)][size_t(z.loop)] > 0);
        if (forwardA == forwardZ)
            return Error(QStringLiteral("a seam used the same way by both of its sides"));
        b_.UpdateEdge(e, forwardA ? c[0] : c[1], forwardA ? c[1] : c[0], geoms_[size_t(a.surface)],
                      TopLoc_Location(), tol);
    } else {
        b_.UpdateEdge(e, c[0], geoms_[size_t(a.surface)], TopLoc_Location(), tol);
        b_.UpdateEdge(e, c[1], geoms_[size_t(z.surface)], TopLoc_Location(), tol);
    }
    b_.Range(e, t0, t1);
    // Ends: the first side's curve start (its end when reversed) and the other end.
    const int start = uf_.find(junction(a, s.reversed[0] ? 1 : 0));
    const int end = uf_.find(junction(a, s.reversed[0] ? 0 : 1));
    TopoDS_Vertex v0 = vertices_.at(start), v1 = vertices_.at(end);
    b_.Add(e, v0.Oriented(TopAbs_FORWARD));
    b_.Add(e, v1.Oriented(TopAbs_REVERSED));
    // The 3D curve follows the first side closely whatever the gap: approximated at the gap of
    // two loose faces (up to 2.5 mm on hammer.iges), it came out of degree 14 with knots of
    // multiplicity 13, on which OCCT's own STEP reader throws.
    BRepLib::BuildCurve3d(e, std::min(tol, kCurveTolerance * tolerance_));
    b_.SameParameter(e, Standard_False);
    b_.SameRange(e, Standard_False);
    BRepLib::SameParameter(e, tol);
    return ok();
}

Status Builder::makeFace(int index, TopoDS_Face& face) {
    const Surface& surface = scene_.surfaces[size_t(index)];
    const Handle(Geom_BSplineSurface)& geom = geoms_[size_t(index)];
    const std::vector<int>& dirs = directions_[size_t(index)];
    b_.MakeFace(face, geom, TopLoc_Location(), tolerance_);
    bool flippedOuter = false, decided = false;
    for (size_t l = 0; l < surface.trims.size(); ++l) {
        if (dirs[l] == 0)
            continue;
        const bool flip = dirs[l] < 0;
        if (!decided) {
            flippedOuter = flip;
            decided = true;
        }
        const int n = int(surface.trims[l].curves.size());
        TopoDS_Wire wire;
        b_.MakeWire(wire);
        for (int m = 0; m < n; ++m) {
            const int k = flip ? n - 1 - m : m;
            const Place p{index, int(l), k};
            if (const auto it = sharedOf_.find(p); it != sharedOf_.end()) {
                const Shared& s = shared_[size_t(it->second)];
                const int side = s.side[0] == p ? 0 : 1;
                // The curve runs along the edge unless reversed; the wire runs along the curve
                // unless the loop is flipped.
                const bool along = !s.reversed[side] != flip;
                b_.Add(wire, s.edge.Oriented(along ? TopAbs_FORWARD : TopAbs_REVERSED));
                continue;
            }
            const NurbsCurve2& stored = curve(p);
            const Expected<Handle(Geom2d_BSplineCurve)> made =
                makeGeomCurve(flip ? trimCurveReversed(stored) : stored);
            if (!made)
                return made.error();
            const Handle(Geom2d_BSplineCurve)& c = *made;
            const double t0 = c->FirstParameter(), t1 = c->LastParameter();
            TopoDS_Edge e;
            b_.MakeEdge(e);
            b_.UpdateEdge(e, c, geom, TopLoc_Location(), tolerance_);
            b_.Range(e, t0, t1);
            TopoDS_Vertex v0 = vertices_.at(uf_.find(junction(p, flip ? 1 : 0)));
            TopoDS_Vertex v1 = vertices_.at(uf_.find(junction(p, flip ? 0 : 1)));
            b_.Add(e, v0.Oriented(TopAbs_FORWARD));
            b_.Add(e, v1.Oriented(TopAbs_REVERSED));
            // A curve whose image is one point (a pole, an apex) is a degenerated edge.
            const gp_Pnt q0 = geom->Value(c->Value(t0).X(), c->Value(t0).Y());
            double extent = 0.0;
            for (int s = 1; s <= 16; ++s) {
                const gp_Pnt2d uv = c->Value(t0 + (t1 - t0) * s / 16);
                extent = std::max(extent, q0.Distance(geom->Value(uv.X(), uv.Y())));
            }
            if (extent <= tolerance_) {
                b_.Degenerated(e, Standard_True);
            } else {
                BRepLib::BuildCurve3d(e, tolerance_);
                b_.SameParameter(e, Standard_False);
                b_.SameRange(e, Standard_False);
                BRepLib::SameParameter(e, tolerance_);
            }
            b_.Add(wire, e);
        }
        wire.Closed(Standard_True);
        b_.Add(face, wire);
    }
    if (!decided)
        return Error(QStringLiteral("surface '%1' has no trim loop to build its recorded edges on")
                         .arg(surface.name));
    BRepLib::UpdateTolerances(face);
    if (!BRepCheck_Analyzer(face).IsValid())
        return Error(QStringLiteral("face '%1' built with its shared edges is invalid (BRepCheck)")
                         .arg(surface.name));
    // Wires run counter-clockwise around the material on a FORWARD face; where the loops had to
    // be turned for that, the source's face was reversed, and so is this one.
    if (flippedOuter)
        face.Reverse();
    return ok();
}

Status Builder::run(const std::vector<std::uint32_t>& openEdges, RecordedFaces& out) {
    const int n = int(scene_.surfaces.size());
    std::unordered_map<std::uint32_t, int> index;
    for (int k = 0; k < n; ++k)
        index[scene_.surfaces[size_t(k)].id.value] = k;
    std::vector<bool> covered(size_t(n), false);
    for (const SharedEdge& e : scene_.topology.edges)
        for (const EdgeUse& u : e.sides)
            if (const auto it = index.find(u.surface.value); it != index.end())
                covered[size_t(it->second)] = true;
    for (const Shell& s : scene_.topology.shells)
        for (SurfaceId f : s.faces)
            if (const auto it = index.find(f.value); it != index.end())
                covered[size_t(it->second)] = true;
    geoms_.resize(size_t(n));
    directions_.resize(size_t(n));
    for (int k = 0; k < n; ++k) {
        if (!covered[size_t(k)])
            continue;
        const Surface& s = scene_.surfaces[size_t(k)];
        const Expected<Handle(Geom_BSplineSurface)> made = makeGeomSurface(s.geometry);
        if (!made)
            return Error(
                QStringLiteral("surface '%1' cannot be written: %2").arg(s.name, made.message()));
        geoms_[size_t(k)] = *made;
        directions_[size_t(k)] = loopDirections(s);
        for (size_t l = 0; l < s.trims.size(); ++l)
            if (directions_[size_t(k)][l] != 0)
                junction({k, int(l), 0}, 0);
    }
    const auto placeOf = [&](const EdgeUse& u, Place& p) {
        const auto it = index.find(u.surface.value);
        if (it == index.end())
            return false;
        const Surface& s = scene_.surfaces[size_t(it->second)];
        for (size_t l = 0; l < s.trims.size(); ++l) {
            if (s.trims[l].id != u.loop)
                continue;
            if (directions_[size_t(it->second)][l] == 0 || u.curve < 0 ||
                u.curve >= int(s.trims[l].curves.size()))
                return false;
            p = {it->second, int(l), u.curve};
            return true;
        }
        return false;
    };
    for (const SharedEdge& e : scene_.topology.edges) {
        if (std::binary_search(openEdges.begin(), openEdges.end(), e.id.value))
            continue;
        Shared s;
        if (!placeOf(e.sides[0], s.side[0]) || !placeOf(e.sides[1], s.side[1]) ||
            s.side[0] == s.side[1] || sharedOf_.count(s.side[0]) || sharedOf_.count(s.side[1]))
            continue;
        // The first side is one that runs along the edge, so the edge keeps its parameters.
        s.reversed[0] = e.sides[0].reversed;
        s.reversed[1] = e.sides[1].reversed;
        if (s.reversed[0] && !s.reversed[1]) {
            std::swap(s.side[0], s.side[1]);
            std::swap(s.reversed[0], s.reversed[1]);
        }
        s.tolerance = e.tolerance;
        // The ends of both sides are one vertex each.
        for (int end = 0; end < 2; ++end) {
            const int ja = junction(s.side[0], (end == 1) != s.reversed[0] ? 1 : 0);
            const int jb = junction(s.side[1], (end == 1) != s.reversed[1] ? 1 : 0);
            uf_.join(ja, jb);
        }
        sharedOf_[s.side[0]] = int(shared_.size());
        sharedOf_[s.side[1]] = int(shared_.size());
        shared_.push_back(s);
    }
    try {
        OCC_CATCH_SIGNALS
        makeVertices();
        for (Shared& s : shared_)
            if (Status made = makeSharedEdge(s); !made)
                return made;
        out.faces.assign(size_t(n), TopoDS_Face());
        for (int k = 0; k < n; ++k)
            if (covered[size_t(k)])
                if (Status made = makeFace(k, out.faces[size_t(k)]); !made)
                    return made;
    } catch (const Standard_Failure& e) {
        return Error(
            QStringLiteral("OpenCASCADE failed building the shared edges: %1").arg(failure(e)));
    }
    out.sharedEdges = int(shared_.size());
    out.shells.clear();
    for (const Shell& s : scene_.topology.shells) {
        std::vector<int> faces;
        for (SurfaceId f : s.faces)
            if (const auto it = index.find(f.value); it != index.end())
                faces.push_back(it->second);
        out.shells.push_back(std::move(faces));
    }
    orientShells(out.faces, out.shells);
    return ok();
}

} // namespace

Status buildRecordedFaces(const Scene& scene, const std::vector<std::uint32_t>& openEdges,
                          double tolerance, RecordedFaces& out) {
    std::vector<std::uint32_t> open = openEdges;
    std::sort(open.begin(), open.end());
    return Builder(scene, tolerance).run(open, out);
}

} // namespace kw::occt
