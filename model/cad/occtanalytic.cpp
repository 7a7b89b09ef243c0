// The closed form of an imported face's surface, kept beside its exact NURBS (Surface::analytic).
#include "model/cad/occt_internal.h"
#include "model/nurbs/analytic_eval.h"

#include <BRepAdaptor_Surface.hxx>
#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <algorithm>
#include <cmath>
#include <gp_Ax3.hxx>
#include <gp_Cone.hxx>
#include <gp_Cylinder.hxx>
#include <gp_Pln.hxx>
#include <gp_Sphere.hxx>
#include <gp_Torus.hxx>
#include <limits>
#include <numbers>

namespace kw::occt {
namespace {

using Kind = AnalyticForm::Kind;
using MapKind = AnalyticParamMap::Kind;
constexpr double kTwoPi = 2.0 * std::numbers::pi;

glm::dvec3 vec(const gp_XYZ& p) {
    return {p.X(), p.Y(), p.Z()};
}

void setFrame(AnalyticForm& f, const gp_Ax3& ax) {
    f.origin = vec(ax.Location().XYZ());
    f.xAxis = vec(ax.XDirection().XYZ());
    f.yAxis = vec(ax.YDirection().XYZ());
    f.zAxis = vec(ax.Direction().XYZ());
}

// The form of the face's surface in OCCT's parametrisation, the frame moved by the face's
// location (BRepAdaptor_Surface applies it); the maps are left to fitMaps. Kind::None for any
// other surface (B-spline, Bezier, revolution, extrusion, offset).
AnalyticForm surfaceForm(const TopoDS_Face& face) {
    AnalyticForm f;
    const BRepAdaptor_Surface s(face, Standard_False);
    switch (s.GetType()) {
    case GeomAbs_Plane:
        f.kind = Kind::Plane;
        setFrame(f, s.Plane().Position());
        break;
    case GeomAbs_Cylinder:
        f.kind = Kind::Cylinder;
        setFrame(f, s.Cylinder().Position());
        f.radius = s.Cylinder().Radius();
        break;
    case GeomAbs_Cone:
        f.kind = Kind::Cone;
        setFrame(f, s.Cone().Position());
        f.radius = s.Cone().RefRadius();
        f.semiAngle = s.Cone().SemiAngle();
        break;
    case GeomAbs_Sphere:
        f.kind = Kind::Sphere;
        setFrame(f, s.Sphere().Position());
        f.radius = s.Sphere().Radius();
        break;
    case GeomAbs_Torus:
        f.kind = Kind::Torus;
        setFrame(f, s.Torus().Position());
        f.radius = s.Torus().MajorRadius();
        f.minorRadius = s.Torus().MinorRadius();
        break;
    default:
        break;
    }
    return f;
}

// Which analytic parameter is an angle written as rational quadratic arcs (HalfAngle): the
// circle directions (Convert_*ToBSplineSurface: u of cylinder, cone, sphere and torus; v of
// sphere and torus).
MapKind mapKindOf(Kind kind, bool first) {
    switch (kind) {
    case Kind::Cylinder:
    case Kind::Cone:
        return first ? MapKind::HalfAngle : MapKind::Linear;
    case Kind::Sphere:
    case Kind::Torus:
        return MapKind::HalfAngle;
    default:
        return MapKind::Linear;
    }
}

// The affine map phi(s) = offset + scale s of one NURBS direction to analytic parameter
// `which` (0: a, 1: b), read off the surface: the closed-form inverse (analyticProject) of
// S at the direction's distinct knots along its middle iso-line, angles unwrapped from knot
// to knot (each arc turns by less than pi). The turn of an angle is the one nearest the face's
// own parameter range `lo` in the file (so a, b are the file's values where the file gave
// them). The check that the map is right is analyticDeviation's, afterwards.
AnalyticParamMap fitMap(const AnalyticForm& f, const NurbsSurface& g, bool alongU, int which,
                        double lo) {
    AnalyticParamMap m;
    m.kind = mapKindOf(f.kind, which == 0);
    const std::vector<double> k =
        alongU ? distinctKnots(g.knotsU, g.degreeU) : distinctKnots(g.knotsV, g.degreeV);
    const Interval other = alongU ? surfaceDomainV(g) : surfaceDomainU(g);
    const double mid = 0.5 * (other.first + other.last);
    std::vector<double> x;
    for (double s : k) {
        const glm::dvec3 p = alongU ? surfacePoint(g, s, mid) : surfacePoint(g, mid, s);
        const glm::dvec2 ab = analyticProject(f, p);
        double v = which == 0 ? ab.x : ab.y;
        if (m.kind == MapKind::HalfAngle && !x.empty())
            v = x.back() + std::remainder(v - x.back(), kTwoPi);
        x.push_back(v);
    }
    m.scale = (x.back() - x.front()) / (k.back() - k.front());
    double first = x.front();
    if (m.kind == MapKind::HalfAngle) {
        const double low = std::min(x.front(), x.back());
        first += kTwoPi * std::round((lo - low) / kTwoPi);
    }
    m.offset = first - m.scale * k.front();
    return m;
}

} // namespace

AnalyticForm analyticFormOf(const TopoDS_Face& face, const NurbsSurface& geometry,
                            double* deviation) {
    AnalyticForm form = surfaceForm(face);
    if (deviation)
        *deviation = -1.0;
    if (form.kind == Kind::None || !checkNurbsSurface(geometry))
        return {};
    double u0 = 0.0, u1 = 0.0, v0 = 0.0, v1 = 0.0;
    BRepTools::UVBounds(face, u0, u1, v0, v1);
    glm::dvec3 lo, hi;
    surfaceControlBounds(geometry, lo, hi);
    // The face's tolerance, but never beyond what a .knot file may hold (analyticMatchLimit).
    const double tolerance =
        std::min(std::max(1e-9 * glm::length(hi - lo), BRep_Tool::Tolerance(face)),
                 analyticMatchLimit(geometry));
    // NurbsConvert keeps the directions (u with u); the swapped pairing is tried second.
    double best = std::numeric_limits<double>::infinity();
    AnalyticForm kept;
    for (bool swapped : {false, true}) {
        AnalyticForm f = form;
        f.swapped = swapped;
        f.u = fitMap(f, geometry, true, swapped ? 1 : 0, swapped ? v0 : u0);
        f.v = fitMap(f, geometry, false, swapped ? 0 : 1, swapped ? u0 : v0);
        if (!checkAnalyticForm(f, geometry))
            continue;
        const double d = analyticDeviation(f, geometry);
        if (d < best) {
            best = d;
            kept = f;
        }
        if (d <= tolerance)
            break;
    }
    if (deviation)
        *deviation = std::isfinite(best) ? best : -1.0;
    return best <= tolerance ? kept : AnalyticForm{};
}

} // namespace kw::occt
