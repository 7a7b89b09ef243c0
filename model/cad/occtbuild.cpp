// One Knotwork surface to one OpenCASCADE face: exact geometry, p-curve trims, built 3D edges.
#include "model/cad/occtbuild.h"

#include "model/nurbs/nurbs.h"
#include "model/nurbs/trim.h"

#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepLib.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Precision.hxx>
#include <ShapeFix_Face.hxx>
#include <Standard_ErrorHandler.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array1OfPnt2d.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Vertex.hxx>
#include <TopoDS_Wire.hxx>
#include <cmath>
#include <vector>

namespace kw::occt {
namespace {

// A full knot sequence as OCCT's distinct knots and multiplicities (exact comparison: equal
// doubles are one knot, so every value goes through unchanged).
void splitKnots(const std::vector<double>& sequence, std::vector<double>& knots,
                std::vector<int>& mults) {
    for (double k : sequence) {
        if (!knots.empty() && knots.back() == k) {
            ++mults.back();
        } else {
            knots.push_back(k);
            mults.push_back(1);
        }
    }
}

TColStd_Array1OfReal realArray(const std::vector<double>& v) {
    TColStd_Array1OfReal a(1, int(v.size()));
    for (size_t k = 0; k < v.size(); ++k)
        a(int(k) + 1) = v[k];
    return a;
}

TColStd_Array1OfInteger intArray(const std::vector<int>& v) {
    TColStd_Array1OfInteger a(1, int(v.size()));
    for (size_t k = 0; k < v.size(); ++k)
        a(int(k) + 1) = v[k];
    return a;
}

bool allEqual(const std::vector<double>& w) {
    for (double x : w)
        if (x != w.front())
            return false;
    return true;
}

QString failure(const Standard_Failure& e) {
    return QStringLiteral("%1 (%2)").arg(QString::fromUtf8(e.GetMessageString()),
                                         QString::fromLatin1(e.DynamicType()->Name()));
}

gp_Pnt surfacePoint(const Handle(Geom_BSplineSurface) & s, const gp_Pnt2d& uv) {
    return s->Value(uv.X(), uv.Y());
}

// Signed area of a closed polygon (positive: counter-clockwise).
double signedArea(const TrimPolygon& poly) {
    double a = 0.0;
    for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++)
        a += poly[j].x * poly[i].y - poly[i].x * poly[j].y;
    return 0.5 * a;
}

// The loop run the other way: curves in reverse order, each reversed.
TrimLoop reversedLoop(const TrimLoop& loop) {
    TrimLoop r;
    r.id = loop.id;
    for (auto it = loop.curves.rbegin(); it != loop.curves.rend(); ++it)
        r.curves.push_back(trimCurveReversed(*it));
    return r;
}

} // namespace

std::vector<int> loopDirections(const Surface& surface) {
    const double tol = trimTolerance(surface.geometry);
    std::vector<TrimPolygon> polys;
    for (const TrimLoop& l : surface.trims)
        polys.push_back(tessellateTrimLoop(l, tol));
    std::vector<int> out(surface.trims.size(), 0);
    for (size_t k = 0; k < surface.trims.size(); ++k) {
        if (polys[k].size() < 3)
            continue;
        int depth = 0;
        for (size_t m = 0; m < surface.trims.size(); ++m) {
            if (m == k || polys[m].size() < 3)
                continue;
            const TrimRegion other = makeTrimRegion({surface.trims[m]}, tol);
            // A vertex of loop k strictly away from loop m decides (loops may touch).
            for (const glm::dvec2& p : polys[k]) {
                if (trimRegionDistance(other, p) > 10.0 * tol) {
                    depth += trimRegionContains(other, p) ? 1 : 0;
                    break;
                }
            }
        }
        const bool ccw = signedArea(polys[k]) > 0.0;
        const bool wantCcw = depth % 2 == 0;
        out[k] = ccw == wantCcw ? 1 : -1;
    }
    return out;
}

namespace {

// Each loop oriented as OCCT reads a face's wires (loopDirections), degenerate loops left out.
std::vector<TrimLoop> orientedLoops(const Surface& surface) {
    const std::vector<int> dirs = loopDirections(surface);
    std::vector<TrimLoop> out;
    for (size_t k = 0; k < surface.trims.size(); ++k) {
        if (dirs[k] != 0)
            out.push_back(dirs[k] > 0 ? surface.trims[k] : reversedLoop(surface.trims[k]));
    }
    return out;
}

// A wire of edges carrying the loop's curves as p-curves on `geom`, consecutive edges sharing
// a vertex. The reason when a curve is refused.
Status buildWire(const TrimLoop& loop, const Handle(Geom_BSplineSurface) & geom, double tolerance,
                 TopoDS_Wire& wire) {
    BRep_Builder b;
    const size_t n = loop.curves.size();
    std::vector<Handle(Geom2d_BSplineCurve)> curves;
    for (const NurbsCurve2& c : loop.curves) {
        Expected<Handle(Geom2d_BSplineCurve)> g = makeGeomCurve(c);
        if (!g)
            return g.error();
        curves.push_back(*g);
    }
    // Vertex k: where curve k starts and curve k - 1 ends; its tolerance covers both ends.
    std::vector<TopoDS_Vertex> vertices(n);
    for (size_t k = 0; k < n; ++k) {
        const Handle(Geom2d_BSplineCurve)& prev = curves[(k + n - 1) % n];
        const gp_Pnt a = surfacePoint(geom, curves[k]->Value(curves[k]->FirstParameter()));
        const gp_Pnt z = surfacePoint(geom, prev->Value(prev->LastParameter()));
        const gp_Pnt mid((a.XYZ() + z.XYZ()) * 0.5);
        b.MakeVertex(vertices[k], mid, std::max(tolerance, 0.5 * a.Distance(z) * 1.001));
    }
    b.MakeWire(wire);
    for (size_t k = 0; k < n; ++k) {
        const Handle(Geom2d_BSplineCurve)& c = curves[k];
        const double t0 = c->FirstParameter(), t1 = c->LastParameter();
        // A curve whose image is one point (a pole, an apex) is a degenerated edge.
        double extent = 0.0;
        const gp_Pnt p0 = surfacePoint(geom, c->Value(t0));
        for (int s = 1; s <= 16; ++s)
            extent = std::max(extent,
                              p0.Distance(surfacePoint(geom, c->Value(t0 + (t1 - t0) * s / 16))));
        TopoDS_Edge edge;
        b.MakeEdge(edge);
        b.UpdateEdge(edge, c, geom, TopLoc_Location(), tolerance);
        b.Range(edge, t0, t1);
        TopoDS_Vertex v0 = vertices[k], v1 = vertices[(k + 1) % n];
        b.Add(edge, v0.Oriented(TopAbs_FORWARD));
        b.Add(edge, v1.Oriented(TopAbs_REVERSED));
        if (extent <= tolerance)
            b.Degenerated(edge, Standard_True);
        b.Add(wire, edge);
    }
    wire.Closed(Standard_True);
    return ok();
}

} // namespace

Expected<Handle(Geom_BSplineSurface)> makeGeomSurface(const NurbsSurface& s) {
    if (const Status valid = checkNurbsSurface(s); !valid)
        return valid.error();
    std::vector<double> ku, kv;
    std::vector<int> mu, mv;
    splitKnots(s.knotsU, ku, mu);
    splitKnots(s.knotsV, kv, mv);
    TColgp_Array2OfPnt poles(1, s.countU, 1, s.countV);
    TColStd_Array2OfReal weights(1, s.countU, 1, s.countV);
    for (int j = 0; j < s.countV; ++j)
        for (int i = 0; i < s.countU; ++i) {
            const glm::dvec3& p = s.points[s.index(i, j)];
            poles(i + 1, j + 1) = gp_Pnt(p.x, p.y, p.z);
            weights(i + 1, j + 1) = s.weights[s.index(i, j)];
        }
    try {
        OCC_CATCH_SIGNALS
        if (allEqual(s.weights) && s.weights.front() == 1.0)
            return Handle(Geom_BSplineSurface)(
                new Geom_BSplineSurface(poles, realArray(ku), realArray(kv), intArray(mu),
                                        intArray(mv), s.degreeU, s.degreeV));
        return Handle(Geom_BSplineSurface)(
            new Geom_BSplineSurface(poles, weights, realArray(ku), realArray(kv), intArray(mu),
                                    intArray(mv), s.degreeU, s.degreeV));
    } catch (const Standard_Failure& e) {
        return Error(QStringLiteral("OpenCASCADE refuses the surface: %1").arg(failure(e)));
    }
}

Expected<Handle(Geom2d_BSplineCurve)> makeGeomCurve(const NurbsCurve2& c) {
    if (const Status valid = checkNurbsCurve(c); !valid)
        return Error(QStringLiteral("trim curve: %1").arg(valid.message()));
    std::vector<double> k;
    std::vector<int> m;
    splitKnots(c.knots, k, m);
    TColgp_Array1OfPnt2d poles(1, int(c.points.size()));
    for (size_t i = 0; i < c.points.size(); ++i)
        poles(int(i) + 1) = gp_Pnt2d(c.points[i].x, c.points[i].y);
    try {
        OCC_CATCH_SIGNALS
        if (allEqual(c.weights) && c.weights.front() == 1.0)
            return Handle(Geom2d_BSplineCurve)(
                new Geom2d_BSplineCurve(poles, realArray(k), intArray(m), c.degree));
        return Handle(Geom2d_BSplineCurve)(new Geom2d_BSplineCurve(
            poles, realArray(c.weights), realArray(k), intArray(m), c.degree));
    } catch (const Standard_Failure& e) {
        return Error(QStringLiteral("OpenCASCADE refuses a trim curve: %1").arg(failure(e)));
    }
}

Expected<TopoDS_Face> buildFace(const Surface& surface, double tolerance) {
    const Expected<Handle(Geom_BSplineSurface)> made = makeGeomSurface(surface.geometry);
    if (!made)
        return made.error();
    const Handle(Geom_BSplineSurface)& geom = *made;
    TopoDS_Face face;
    try {
        OCC_CATCH_SIGNALS
        const std::vector<TrimLoop> loops = orientedLoops(surface);
        if (loops.empty()) {
            BRepBuilderAPI_MakeFace make(geom, tolerance);
            if (!make.IsDone())
                return Error(QStringLiteral("OpenCASCADE cannot bound the surface by its natural "
                                            "edges (BRepBuilderAPI_MakeFace error %1)")
                                 .arg(int(make.Error())));
            face = make.Face();
        } else {
            BRep_Builder b;
            b.MakeFace(face, geom, TopLoc_Location(), tolerance);
            for (const TrimLoop& loop : loops) {
                TopoDS_Wire wire;
                if (Status built = buildWire(loop, geom, tolerance, wire); !built)
                    return built.error();
                b.Add(face, wire);
            }
            BRepLib::BuildCurves3d(face, std::max(tolerance, Precision::Confusion()));
            BRepLib::SameParameter(face, tolerance, Standard_True);
            BRepLib::UpdateTolerances(face);
        }
        if (!BRepCheck_Analyzer(face).IsValid()) {
            // Wires only: ShapeFix never replaces the face's surface.
            ShapeFix_Face fix(face);
            fix.FixOrientationMode() = 0; // the nesting rule above decided the orientation
            fix.Perform();
            face = fix.Face();
            if (!BRepCheck_Analyzer(face).IsValid())
                return Error(QStringLiteral("OpenCASCADE finds the face invalid even after repair "
                                            "(BRepCheck_Analyzer)"));
        }
    } catch (const Standard_Failure& e) {
        return Error(QStringLiteral("OpenCASCADE failed building the face: %1").arg(failure(e)));
    }
    return face;
}

} // namespace kw::occt
