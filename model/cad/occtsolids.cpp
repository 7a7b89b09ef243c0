// Closed solids among the imported faces (kw::occt::markClosedSolids): which side of each face
// is the solid's outside, so that the renderer may skip the back faces of their polygons.
#include "model/cad/occt_internal.h"

#include <BRepAdaptor_Surface.hxx>
#include <BRepCheck_Shell.hxx>
#include <BRepClass3d_SolidClassifier.hxx>
#include <BRep_Tool.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_MapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Solid.hxx>
#include <algorithm>
#include <cmath>
#include <vector>

namespace kw::occt {

namespace {

/// Which side of `face` the inside of `solid` lies on: a point just off the face along OCCT's
/// face normal (Su x Sv, reversed on a REVERSED face) and one just off the other way, at the
/// first point inside its wires (parametersInside) where the normal is defined, classified
/// against the solid. 1: the normal points out; -1: in (an inside-out solid); 0: no such point,
/// or the two classifications do not say one inside and one outside.
int normalSide(const TopoDS_Solid& solid, const TopoDS_Face& face, double tolerance) {
    const BRepTopAdaptor_FClass2d inside(face, 1e-9);
    BRepAdaptor_Surface surface(face);
    for (const gp_Pnt2d& uv : parametersInside(face, inside, 9)) {
        gp_Pnt p;
        gp_Vec du, dv;
        surface.D1(uv.X(), uv.Y(), p, du, dv);
        gp_Vec normal = du.Crossed(dv);
        if (!(normal.Magnitude() > 1e-12))
            continue;
        normal.Normalize();
        if (face.Orientation() == TopAbs_REVERSED)
            normal.Reverse();
        // Far enough past the tolerances to classify, near enough to stay by the face.
        const gp_Vec step = normal * (20.0 * tolerance);
        BRepClass3d_SolidClassifier ahead(solid, p.Translated(step), tolerance);
        BRepClass3d_SolidClassifier behind(solid, p.Translated(-step), tolerance);
        if (ahead.State() == TopAbs_OUT && behind.State() == TopAbs_IN)
            return 1;
        if (ahead.State() == TopAbs_IN && behind.State() == TopAbs_OUT)
            return -1;
        return 0;
    }
    return 0;
}

} // namespace

void markClosedSolids(const TopoDS_Shape& shape, const TopTools_IndexedMapOfShape& faces,
                      const std::vector<int>& sourceFaces, Scene& scene) {
    // The surface each of the file's faces became (-1: skipped).
    std::vector<int> surfaceOf(size_t(faces.Extent()) + 1, -1);
    for (size_t i = 0; i < sourceFaces.size(); ++i)
        surfaceOf[size_t(sourceFaces[i])] = int(i);
    TopTools_IndexedDataMapOfShapeListOfShape solidsOf;
    TopExp::MapShapesAndUniqueAncestors(shape, TopAbs_FACE, TopAbs_SOLID, solidsOf);
    int number = 0;
    TopTools_MapOfShape seen;
    for (TopExp_Explorer x(shape, TopAbs_SOLID); x.More(); x.Next()) {
        const TopoDS_Solid solid = TopoDS::Solid(x.Current());
        if (!seen.Add(solid))
            continue; // the same solid listed twice (same shape and placement)
        // Every shell closed and consistently oriented (BRepCheck).
        bool closed = true;
        for (TopExp_Explorer sh(solid, TopAbs_SHELL); closed && sh.More(); sh.Next()) {
            BRepCheck_Shell check(TopoDS::Shell(sh.Current()));
            closed =
                check.Closed() == BRepCheck_NoError && check.Orientation() == BRepCheck_NoError;
        }
        if (!closed)
            continue;
        // Every face imported, held by this solid alone, and used once in it.
        struct Face {
            int surface;
            bool forward; ///< FORWARD in the solid: the face's normal is Su x Sv
        };
        std::vector<Face> members;
        TopTools_MapOfShape once;
        TopoDS_Face probe;
        double tolerance = 0.0;
        bool whole = true;
        for (TopExp_Explorer f(solid, TopAbs_FACE); whole && f.More(); f.Next()) {
            const TopoDS_Face face = TopoDS::Face(f.Current());
            const int k = faces.FindIndex(face);
            const int s = k > 0 ? surfaceOf[size_t(k)] : -1;
            whole = s >= 0 && once.Add(face) && solidsOf.FindFromKey(face).Extent() == 1;
            if (!whole)
                break;
            members.push_back({s, face.Orientation() == TopAbs_FORWARD});
            if (probe.IsNull()) {
                probe = face;
                tolerance = BRep_Tool::Tolerance(face);
            }
        }
        if (!whole || members.empty())
            continue;
        // In a consistently oriented closed shell every face's normal (Su x Sv, reversed on a
        // REVERSED face) points the same way, out or in: one face's classification says which.
        const int side = normalSide(solid, probe, std::max(tolerance, 1e-7));
        if (side == 0)
            continue;
        for (const Face& m : members) {
            Surface& s = scene.surfaces[size_t(m.surface)];
            s.solid = number;
            s.outsideAlongNormal = m.forward == (side > 0);
        }
        ++number;
    }
}

} // namespace kw::occt
