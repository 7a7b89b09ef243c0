// The OpenCASCADE mesh peer: the faces of a CAD file triangulated the way
// OCCT-based viewers (FreeCAD, Mayo, f3d, AIS_Shape) display them.
#include "model/cad/occt_internal.h"
#include "model/cad/occtbuild.h"
#include "model/cad/occtimport.h"

#include <BRepBndLib.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GeomLib.hxx>
#include <Poly_Connect.hxx>
#include <Poly_Triangulation.hxx>
#include <Precision.hxx>
#include <Standard_ErrorHandler.hxx>
#include <Standard_Failure.hxx>
#include <TopLoc_Location.hxx>
#include <TopoDS.hxx>
#include <cmath>

namespace kw::occt {
namespace {

// Per-node normals as OCCT's viewer computes them (StdPrs_ToolTriangulatedShape::
// ComputeNormals, OCCT 7.6.3, TKV3d): the surface's normal at the node's (u, v) by
// GeomLib::NormEstim; where that fails (status > 1: a singular point such as a cone's apex or
// a pole), the average of the unit normals of the triangles around the node. Written out here
// so that the reader module does not load TKV3d and its image and font libraries.
std::vector<gp_Dir> nodeNormals(const TopoDS_Face& face, const Handle(Poly_Triangulation) & tris) {
    std::vector<gp_Dir> normals(size_t(tris->NbNodes()), gp::DZ());
    const TopoDS_Face zeroFace = TopoDS::Face(face.Located(TopLoc_Location()));
    const Handle(Geom_Surface) surface = BRep_Tool::Surface(zeroFace);
    const double tol = Precision::Confusion();
    Poly_Connect connect;
    bool connected = false;
    for (int node = 1; node <= tris->NbNodes(); ++node) {
        gp_Dir n;
        if (!surface.IsNull() && tris->HasUVNodes() &&
            GeomLib::NormEstim(surface, tris->UVNode(node), tol, n) <= 1) {
            normals[size_t(node - 1)] = n;
            continue;
        }
        if (!connected) {
            connect.Load(tris);
            connected = true;
        }
        gp_XYZ sum(0.0, 0.0, 0.0);
        int t[3];
        for (connect.Initialize(node); connect.More(); connect.Next()) {
            tris->Triangle(connect.Value()).Get(t[0], t[1], t[2]);
            const gp_XYZ a = tris->Node(t[1]).XYZ() - tris->Node(t[0]).XYZ();
            const gp_XYZ b = tris->Node(t[2]).XYZ() - tris->Node(t[1]).XYZ();
            const gp_XYZ c = a ^ b;
            if (c.Modulus() >= tol)
                sum += c / c.Modulus();
        }
        normals[size_t(node - 1)] = sum.Modulus() > tol ? gp_Dir(sum) : gp::DZ();
    }
    return normals;
}

// One face's triangulation as a TaggedMesh (id and source face left for the caller), moved by
// the face's location, with OCCT viewers' nodal normals.
TaggedMesh taggedMesh(const TopoDS_Face& face, const Handle(Poly_Triangulation) & tris,
                      const TopLoc_Location& loc) {
    const gp_Trsf trsf = loc.Transformation();
    const std::vector<gp_Dir> normals = nodeNormals(face, tris);
    TaggedMesh m;
    m.positions.reserve(size_t(tris->NbNodes()));
    for (int i = 1; i <= tris->NbNodes(); ++i) {
        const gp_Pnt p = tris->Node(i).Transformed(trsf);
        m.positions.emplace_back(p.X(), p.Y(), p.Z());
        // The surface's own orientation, as the .knot surface and the CPU reference have
        // it: AIS reverses the normals (and the winding) of a REVERSED face, which two-sided
        // lighting does not show, but the edge report compares normals with their sign.
        const gp_Dir n = normals[size_t(i - 1)].Transformed(trsf);
        m.normals.emplace_back(n.X(), n.Y(), n.Z());
        const gp_Pnt2d uv = tris->HasUVNodes() ? tris->UVNode(i) : gp_Pnt2d(0.0, 0.0);
        m.uvs.emplace_back(uv.X(), uv.Y());
    }
    m.indices.reserve(size_t(tris->NbTriangles()) * 3);
    for (int t = 1; t <= tris->NbTriangles(); ++t) {
        int a, b, c;
        tris->Triangle(t).Get(a, b, c);
        m.indices.insert(m.indices.end(), {unsigned(a - 1), unsigned(b - 1), unsigned(c - 1)});
    }
    return m;
}

} // namespace

double defaultLinearDeflection(const TopoDS_Shape& shape) {
    // AIS_Shape's default: Prs3d_Drawer's deviation coefficient 0.001 times the largest side of
    // the bounding box, times 4 (StdPrs_ToolTriangulatedShape::GetDeflection).
    Bnd_Box box;
    BRepBndLib::Add(shape, box, Standard_False);
    if (box.IsVoid())
        return 0.0;
    double x0, y0, z0, x1, y1, z1;
    box.Get(x0, y0, z0, x1, y1, z1);
    return 0.004 * std::max({x1 - x0, y1 - y0, z1 - z0});
}

Status meshFaces(const TopoDS_Shape& shape, const TopTools_IndexedMapOfShape& faces,
                 const ImportResult& imported, double linear, double angularDegrees,
                 TaggedMeshSet& out, QStringList& warnings) {
    if (!(linear > 0.0) || !(angularDegrees > 0.0))
        return Error(QStringLiteral("the deflections must be positive (linear %1, angular %2 deg)")
                         .arg(linear)
                         .arg(angularDegrees));
    // As the viewers call it: absolute linear deflection, angular in radians, not in parallel
    // (one thread, as on the machine the table is measured on).
    BRepMesh_IncrementalMesh mesher(shape, linear, Standard_False, angularDegrees * M_PI / 180.0,
                                    Standard_False);
    if (!mesher.IsDone())
        return Error(QStringLiteral("BRepMesh_IncrementalMesh failed (status %1)")
                         .arg(mesher.GetStatusFlags()));
    out = TaggedMeshSet{};
    out.linearDeflection = linear;
    out.angularDeflectionDegrees = angularDegrees;
    for (size_t k = 0; k < imported.scene.surfaces.size(); ++k) {
        const int index = imported.sourceFaces[k];
        const TopoDS_Face& face = TopoDS::Face(faces(index));
        TopLoc_Location loc;
        const Handle(Poly_Triangulation) tris = BRep_Tool::Triangulation(face, loc);
        if (tris.IsNull() || tris->NbTriangles() == 0) {
            warnings << QStringLiteral("face %1: BRepMesh made no triangles").arg(index);
            continue;
        }
        TaggedMesh m = taggedMesh(face, tris, loc);
        m.id = imported.scene.surfaces[k].id;
        m.sourceFace = index;
        out.faces.push_back(std::move(m));
    }
    if (out.faces.empty())
        return Error(QStringLiteral("BRepMesh made no triangles on any face"));
    return ok();
}

Status meshBuiltFaces(const Scene& scene, double tolerance, double linear, double angularDegrees,
                      TaggedMeshSet& out) {
    out = TaggedMeshSet{};
    out.linearDeflection = linear;
    out.angularDeflectionDegrees = angularDegrees;
    for (size_t k = 0; k < scene.surfaces.size(); ++k) {
        const Surface& surface = scene.surfaces[k];
        const Expected<TopoDS_Face> built = buildFace(surface, tolerance);
        if (!built)
            return Error(QStringLiteral("surface %1 (\"%2\"): %3")
                             .arg(surface.id.value)
                             .arg(surface.name, built.message()));
        const TopoDS_Face& face = *built;
        // One face alone, as a viewer re-meshes the face an edit changed: absolute linear
        // deflection, angular in radians, not in parallel.
        BRepMesh_IncrementalMesh mesher(face, linear, Standard_False, angularDegrees * M_PI / 180.0,
                                        Standard_False);
        TopLoc_Location loc;
        const Handle(Poly_Triangulation) tris = BRep_Tool::Triangulation(face, loc);
        if (!mesher.IsDone() || tris.IsNull() || tris->NbTriangles() == 0)
            return Error(QStringLiteral("surface %1 (\"%2\"): BRepMesh made no triangles")
                             .arg(surface.id.value)
                             .arg(surface.name));
        TaggedMesh m = taggedMesh(face, tris, loc);
        m.id = surface.id;
        m.sourceFace = int(k) + 1;
        out.faces.push_back(std::move(m));
    }
    return ok();
}

} // namespace kw::occt

namespace kw {

// Here rather than in occtimport.cpp so that the import-only modules do not link TKMesh.
Expected<ImportResult> importAndMeshOcctFile(const QString& path, CadFormat format,
                                             const MeshDeflection& deflection, TaggedMeshSet& mesh,
                                             const ImportProgress& progress) {
    const auto triangulate = [&](const TopoDS_Shape& shape, const TopTools_IndexedMapOfShape& faces,
                                 ImportResult& result) -> Status {
        try {
            OCC_CATCH_SIGNALS
            const double linear =
                deflection.linear > 0.0 ? deflection.linear : occt::defaultLinearDeflection(shape);
            if (Status meshed =
                    occt::meshFaces(shape, faces, result, linear, deflection.angularDegrees, mesh,
                                    result.report.warnings);
                !meshed)
                return Error(QStringLiteral("%1: cannot mesh: %2").arg(path, meshed.message()));
        } catch (const Standard_Failure& e) {
            return Error(QStringLiteral("%1: OpenCASCADE failed meshing the shape: %2 (%3)")
                             .arg(path, QString::fromUtf8(e.GetMessageString()),
                                  QString::fromLatin1(e.DynamicType()->Name())));
        }
        return ok();
    };
    return occt::importShape(path, format, progress, triangulate);
}

} // namespace kw
