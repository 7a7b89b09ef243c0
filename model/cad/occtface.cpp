// One OpenCASCADE face to one Knotwork surface: exact NURBS geometry and p-curve trim loops.
#include "model/cad/occt_internal.h"
#include "model/nurbs/trim.h"

#include <BRepBuilderAPI_NurbsConvert.hxx>
#include <BRepTools.hxx>
#include <BRepTools_WireExplorer.hxx>
#include <BRep_Tool.hxx>
#include <Geom2dConvert.hxx>
#include <Geom2d_BSplineCurve.hxx>
#include <Geom2d_TrimmedCurve.hxx>
#include <GeomConvert.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_BezierSurface.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <Precision.hxx>
#include <Standard_Version.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_DataMapOfShapeShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Wire.hxx>
#include <cmath>
#include <limits>
#include <vector>

namespace kw::occt {
namespace {

QString typeName(const Handle(Standard_Transient) & t) {
    return t.IsNull() ? QStringLiteral("none") : QString::fromLatin1(t->DynamicType()->Name());
}

// The surface as a B-spline if it already is one (possibly behind a rectangular trim, which
// is applied with Segment, keeping parameters) or is a Bezier patch; null otherwise.
Handle(Geom_BSplineSurface) asBSpline(const Handle(Geom_Surface) & surface) {
    Handle(Geom_Surface) s = surface;
    double u1 = 0, u2 = 0, v1 = 0, v2 = 0;
    bool trimmed = false;
    if (auto rt = Handle(Geom_RectangularTrimmedSurface)::DownCast(s)) {
        rt->Bounds(u1, u2, v1, v2);
        s = rt->BasisSurface();
        trimmed = true;
    }
    Handle(Geom_BSplineSurface) bs;
    if (auto b = Handle(Geom_BSplineSurface)::DownCast(s))
        bs = Handle(Geom_BSplineSurface)::DownCast(b->Copy());
    else if (auto z = Handle(Geom_BezierSurface)::DownCast(s))
        bs = GeomConvert::SurfaceToBSplineSurface(z);
    if (!bs.IsNull() && trimmed)
        bs->CheckAndSegment(u1, u2, v1, v2);
    return bs;
}

// Shifts a direction's knots by `delta` (a whole number of periods): the same surface points
// at parameters moved by delta.
void shiftKnots(Handle(Geom_BSplineSurface) & bs, bool u, double delta) {
    TColStd_Array1OfReal k(1, u ? bs->NbUKnots() : bs->NbVKnots());
    if (u)
        bs->UKnots(k);
    else
        bs->VKnots(k);
    for (double& x : k)
        x += delta;
    if (u)
        bs->SetUKnots(k);
    else
        bs->SetVKnots(k);
}

// Puts back knot values that period arithmetic (Segment, shiftKnots) left a few ulps off: each
// knot within 8 ulps of a knot of the periodic surface, or of one moved by whole periods, takes
// that exact value. The file held those values; a round trip then gives them back bit for bit.
void snapKnots(Handle(Geom_BSplineSurface) & bs, bool u, const std::vector<double>& exact,
               double period) {
    TColStd_Array1OfReal k(1, u ? bs->NbUKnots() : bs->NbVKnots());
    if (u)
        bs->UKnots(k);
    else
        bs->VKnots(k);
    bool changed = false;
    for (double& x : k) {
        for (double e : exact) {
            const double shifts = std::round((x - e) / period);
            const double candidate = e + shifts * period;
            const double ulps = 8.0 * std::numeric_limits<double>::epsilon() *
                                std::max({1.0, std::abs(x), std::abs(candidate)});
            if (candidate != x && std::abs(candidate - x) <= ulps) {
                x = candidate;
                changed = true;
                break;
            }
        }
    }
    // Knots must stay strictly increasing; a snap that would break that is not made.
    for (int i = k.Lower() + 1; changed && i <= k.Upper(); ++i)
        if (!(k(i) > k(i - 1)))
            return;
    if (changed) {
        if (u)
            bs->SetUKnots(k);
        else
            bs->SetVKnots(k);
    }
}

std::vector<double> distinctKnots(const Handle(Geom_BSplineSurface) & bs, bool u) {
    TColStd_Array1OfReal k(1, u ? bs->NbUKnots() : bs->NbVKnots());
    if (u)
        bs->UKnots(k);
    else
        bs->VKnots(k);
    return std::vector<double>(k.begin(), k.end());
}

// Periodic B-splines become non-periodic over the face's own (u, v) range, without changing
// any parameter value, so the p-curves keep applying unchanged. (Segment may return the range
// a period away, e.g. [2 pi, 4 pi] for a request of [0, 2 pi]; the knots are moved back.)
void makeNonPeriodic(Handle(Geom_BSplineSurface) & bs, const TopoDS_Face& face) {
    const bool periodicU = bs->IsUPeriodic(), periodicV = bs->IsVPeriodic();
    if (!periodicU && !periodicV)
        return;
    double fu1, fu2, fv1, fv2;
    BRepTools::UVBounds(face, fu1, fu2, fv1, fv2);
    double u1, u2, v1, v2;
    bs->Bounds(u1, u2, v1, v2);
    const double periodU = periodicU ? bs->UPeriod() : 0.0;
    const double periodV = periodicV ? bs->VPeriod() : 0.0;
    const std::vector<double> knotsU = distinctKnots(bs, true), knotsV = distinctKnots(bs, false);
    if (periodicU) {
        u1 = fu1;
        u2 = std::min(fu2, fu1 + periodU);
    }
    if (periodicV) {
        v1 = fv1;
        v2 = std::min(fv2, fv1 + periodV);
    }
    bs->Segment(u1, u2, v1, v2);
    if (bs->IsUPeriodic())
        bs->SetUNotPeriodic();
    if (bs->IsVPeriodic())
        bs->SetVNotPeriodic();
    double a1, a2, b1, b2;
    bs->Bounds(a1, a2, b1, b2);
    if (periodicU && std::abs(a1 - u1) > Precision::PConfusion())
        shiftKnots(bs, true, std::round((u1 - a1) / periodU) * periodU);
    if (periodicV && std::abs(b1 - v1) > Precision::PConfusion())
        shiftKnots(bs, false, std::round((v1 - b1) / periodV) * periodV);
    if (periodicU)
        snapKnots(bs, true, knotsU, periodU);
    if (periodicV)
        snapKnots(bs, false, knotsV, periodV);
}

std::vector<double> knotSequence(const Handle(Geom_BSplineSurface) & bs, bool u) {
    const int n = u ? bs->NbUPoles() + bs->UDegree() + 1 : bs->NbVPoles() + bs->VDegree() + 1;
    TColStd_Array1OfReal seq(1, n);
    if (u)
        bs->UKnotSequence(seq);
    else
        bs->VKnotSequence(seq);
    return std::vector<double>(seq.begin(), seq.end());
}

NurbsSurface toNurbs(const Handle(Geom_BSplineSurface) & bs) {
    NurbsSurface s;
    s.degreeU = bs->UDegree();
    s.degreeV = bs->VDegree();
    s.countU = bs->NbUPoles();
    s.countV = bs->NbVPoles();
    s.knotsU = knotSequence(bs, true);
    s.knotsV = knotSequence(bs, false);
    s.points.resize(static_cast<size_t>(s.countU) * s.countV);
    s.weights.resize(s.points.size());
    for (int j = 0; j < s.countV; ++j) {
        for (int i = 0; i < s.countU; ++i) {
            const gp_Pnt p = bs->Pole(i + 1, j + 1);
            s.points[s.index(i, j)] = {p.X(), p.Y(), p.Z()};
            s.weights[s.index(i, j)] = bs->Weight(i + 1, j + 1);
        }
    }
    return s;
}

NurbsCurve2 toNurbs(const Handle(Geom2d_BSplineCurve) & bc) {
    NurbsCurve2 c;
    c.degree = bc->Degree();
    TColStd_Array1OfReal seq(1, bc->NbPoles() + bc->Degree() + 1);
    bc->KnotSequence(seq);
    c.knots.assign(seq.begin(), seq.end());
    for (int i = 1; i <= bc->NbPoles(); ++i) {
        const gp_Pnt2d p = bc->Pole(i);
        c.points.emplace_back(p.X(), p.Y());
        c.weights.push_back(bc->Weight(i));
    }
    return c;
}

// The edge's p-curve on the face over the edge's range, as a clamped B-spline running in the
// direction the wire uses the edge. Null if the edge has no p-curve on this face.
Handle(Geom2d_BSplineCurve) pcurve(const TopoDS_Edge& edge, const TopoDS_Face& face) {
    double a = 0, b = 0;
    Handle(Geom2d_Curve) c = BRep_Tool::CurveOnSurface(edge, face, a, b);
    if (c.IsNull())
        return nullptr;
    Handle(Geom2d_BSplineCurve) bc;
    auto existing = Handle(Geom2d_BSplineCurve)::DownCast(c);
    if (!existing.IsNull() && !existing->IsPeriodic() &&
        std::abs(existing->FirstParameter() - a) <= Precision::PConfusion() &&
        std::abs(existing->LastParameter() - b) <= Precision::PConfusion())
        bc = Handle(Geom2d_BSplineCurve)::DownCast(existing->Copy()); // as in the file
    else if (!existing.IsNull() && existing->IsPeriodic() &&
             std::abs(existing->FirstParameter() - a) <= Precision::PConfusion() &&
             std::abs(existing->LastParameter() - b) <= Precision::PConfusion()) {
        // A closed curve the reader made periodic, used whole: clamped at its own ends, with
        // its parameters kept. (Trimming a periodic curve over one whole period and converting
        // it gave non-finite poles.)
        bc = Handle(Geom2d_BSplineCurve)::DownCast(existing->Copy());
        bc->SetNotPeriodic();
    } else
        bc = Geom2dConvert::CurveToBSplineCurve(new Geom2d_TrimmedCurve(c, a, b));
    if (bc->IsPeriodic())
        bc->SetNotPeriodic();
    if (edge.Orientation() == TopAbs_REVERSED)
        bc->Reverse();
    return bc;
}

// True when the loop runs along the boundary of the (u, v) domain and encloses all of it.
bool isNaturalBoundary(const TrimLoop& loop, const NurbsSurface& s) {
    const Interval du = surfaceDomainU(s), dv = surfaceDomainV(s);
    const double tol = 1e-7 * std::hypot(du.last - du.first, dv.last - dv.first);
    const TrimPolygon poly = tessellateTrimLoop(loop, tol);
    double area2 = 0.0;
    for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
        const glm::dvec2 p = poly[i];
        const bool onEdge = std::abs(p.x - du.first) <= tol || std::abs(p.x - du.last) <= tol ||
                            std::abs(p.y - dv.first) <= tol || std::abs(p.y - dv.last) <= tol;
        if (!onEdge)
            return false;
        area2 += poly[j].x * p.y - p.x * poly[j].y;
    }
    const double domain = (du.last - du.first) * (dv.last - dv.first);
    return std::abs(0.5 * std::abs(area2) - domain) <= 1e-6 * domain;
}

} // namespace

std::vector<gp_Pnt2d> parametersInside(const TopoDS_Face& face,
                                       const BRepTopAdaptor_FClass2d& inside, int count) {
    double u0 = 0.0, u1 = 0.0, v0 = 0.0, v1 = 0.0;
    BRepTools::UVBounds(face, u0, u1, v0, v1);
    std::vector<gp_Pnt2d> out;
    for (int n : {5, 13}) {
        for (int j = 0; j < n && int(out.size()) < count; ++j)
            for (int i = 0; i < n && int(out.size()) < count; ++i) {
                const int k = (i * 7 + j * n * 3) % (n * n);
                const gp_Pnt2d p(u0 + (u1 - u0) * ((k % n) + 0.5) / n,
                                 v0 + (v1 - v0) * ((k / n) + 0.5) / n);
                if (inside.Perform(p) == TopAbs_IN)
                    out.push_back(p);
            }
        if (!out.empty())
            break;
    }
    return out;
}

Status convertFace(const TopoDS_Face& original, Surface& out, std::uint32_t& nextId,
                   bool dropNaturalBoundary, QStringList& warnings, FaceEdges* edges) {
    TopoDS_Face face = original;
    // The converted copy's edges by the file's: the topology names the file's edges.
    TopTools_DataMapOfShapeShape fileEdge;
    const Handle(Geom_Surface) geom = BRep_Tool::Surface(face);
    if (geom.IsNull()) {
        return Error(QStringLiteral("face has no surface"));
    }
    Handle(Geom_BSplineSurface) bs = asBSpline(geom);
    if (bs.IsNull()) {
        // Analytic, swept or offset surface: exact conversion of the face (surface and
        // p-curves together, so the trims follow the new parameterisation).
        BRepBuilderAPI_NurbsConvert convert(face, Standard_True);
        if (!convert.IsDone() || convert.Shape().ShapeType() != TopAbs_FACE) {
            return Error(QStringLiteral("conversion of a %1 to NURBS failed").arg(typeName(geom)));
        }
        face = TopoDS::Face(convert.Shape());
        for (TopExp_Explorer e(original, TopAbs_EDGE); e.More(); e.Next()) {
            const TopoDS_Shape& copy = convert.ModifiedShape(e.Current());
            if (!copy.IsNull() && !fileEdge.IsBound(copy))
                fileEdge.Bind(copy, e.Current());
        }
        bs = asBSpline(BRep_Tool::Surface(face));
        if (bs.IsNull()) {
            return Error(
                QStringLiteral("a %1 did not convert to a B-spline surface").arg(typeName(geom)));
        }
    }
    makeNonPeriodic(bs, face);
    if (bs->UDegree() > kMaxDegree || bs->VDegree() > kMaxDegree) {
        return Error(QStringLiteral("degree %1 x %2 is above Knotwork's maximum %3")
                         .arg(bs->UDegree())
                         .arg(bs->VDegree())
                         .arg(kMaxDegree));
    }
    out.geometry = toNurbs(bs);
    const Status valid = checkNurbsSurface(out.geometry);
    if (!valid) {
        return Error(QStringLiteral("invalid surface after conversion: %1").arg(valid.message()));
    }
    // The file's closed form, for the renderer's closed-form intersection (Surface::analytic).
    out.analytic = analyticFormOf(original, out.geometry);

    // Wires: the outer one first, then the holes, each in the order the wire runs.
    std::vector<TopoDS_Wire> wires;
    const TopoDS_Wire outer = BRepTools::OuterWire(face);
    if (!outer.IsNull())
        wires.push_back(outer);
    for (TopExp_Explorer w(face, TopAbs_WIRE); w.More(); w.Next())
        if (!w.Current().IsSame(outer))
            wires.push_back(TopoDS::Wire(w.Current()));

    const Interval du = surfaceDomainU(out.geometry), dv = surfaceDomainV(out.geometry);
    const double uvSize = std::hypot(du.last - du.first, dv.last - dv.first);
    std::vector<TrimLoop> loops;
    FaceEdges loopEdges;
    for (const TopoDS_Wire& wire : wires) {
        TrimLoop loop;
        std::vector<CurveEdge> curveEdges;
        int edges = 0;
        for (TopExp_Explorer e(wire, TopAbs_EDGE); e.More(); e.Next())
            ++edges;
        int explored = 0;
        for (BRepTools_WireExplorer we(wire, face); we.More(); we.Next()) {
            ++explored;
            const TopoDS_Edge& edge = we.Current();
            Handle(Geom2d_BSplineCurve) bc = pcurve(edge, face);
            if (bc.IsNull()) {
                return Error(QStringLiteral("an edge has no curve in the face's parameter space"));
            }
            if (bc->Degree() > kMaxDegree) {
                return Error(QStringLiteral("a trim curve of degree %1 is above the maximum %2")
                                 .arg(bc->Degree())
                                 .arg(kMaxDegree));
            }
            loop.curves.push_back(toNurbs(bc));
            const TopoDS_Shape* file = fileEdge.Seek(edge);
            curveEdges.push_back(
                CurveEdge{file ? TopoDS::Edge(*file) : edge, edge.Orientation() == TopAbs_REVERSED,
                          std::max(BRep_Tool::Tolerance(edge),
                                   file ? BRep_Tool::Tolerance(TopoDS::Edge(*file)) : 0.0)});
        }
        if (explored != edges)
            warnings << QStringLiteral("a wire of %1 edges could only be followed over %2")
                            .arg(edges)
                            .arg(explored);
        if (loop.curves.empty())
            continue;
        // Close the small gaps that tolerant modelling leaves between consecutive p-curves.
        double worst = 0.0;
        for (size_t k = 0; k < loop.curves.size(); ++k) {
            NurbsCurve2& next = loop.curves[(k + 1) % loop.curves.size()];
            const glm::dvec2 end = loop.curves[k].points.back();
            const double gap = glm::length(next.points.front() - end);
            worst = std::max(worst, gap);
            if (gap <= 1e-5 * uvSize)
                next.points.front() = end;
        }
        if (worst > 1e-5 * uvSize)
            warnings << QStringLiteral("a trim loop has a gap of %1 in (u, v) (domain size %2)")
                            .arg(worst)
                            .arg(uvSize);
        for (const NurbsCurve2& c : loop.curves) {
            const Status valid = checkNurbsCurve(c);
            if (!valid) {
                return Error(QStringLiteral("invalid trim curve: %1").arg(valid.message()));
            }
        }
        loops.push_back(std::move(loop));
        loopEdges.push_back(std::move(curveEdges));
    }
    if (dropNaturalBoundary && loops.size() == 1 &&
        isNaturalBoundary(loops.front(), out.geometry)) {
        loops.clear(); // the whole domain: an untrimmed surface
        loopEdges.clear();
    }
    // The p-curves must lie in the surface's domain (files overshoot by tolerances, ~1e-5 of
    // it); a loop well outside means the parameterisations disagree: report it.
    const TrimRegion region = makeTrimRegion(loops, 1e-4 * uvSize);
    for (size_t l = 0; l < region.loops.size(); ++l) {
        const double slack = 1e-3 * uvSize;
        if (region.lo[l].x < du.first - slack || region.hi[l].x > du.last + slack ||
            region.lo[l].y < dv.first - slack || region.hi[l].y > dv.last + slack)
            warnings << QStringLiteral("a trim loop reaches outside the surface's (u, v) domain "
                                       "[%1, %2] x [%3, %4]")
                            .arg(du.first)
                            .arg(du.last)
                            .arg(dv.first)
                            .arg(dv.last);
    }
    for (TrimLoop& l : loops)
        l.id = TrimLoopId{nextId++};
    out.trims = std::move(loops);
    if (edges)
        *edges = std::move(loopEdges);
    return ok();
}

} // namespace kw::occt
