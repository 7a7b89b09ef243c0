// Knotwork surfaces as OpenCASCADE faces: the exact B-spline surface (rational where weighted)
// with its trim loops as 2D p-curves and 3D edges built from them. The writers (occtexport.cpp)
// use it; so can anything else that needs a B-rep of a surface (re-meshing, checks).
#pragma once

#include "model/document/scene.h"
#include "model/error.h"

#include <Geom2d_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <QString>
#include <TopoDS_Face.hxx>
#include <vector>

namespace kw::occt {

/// `s` as a Geom_BSplineSurface: poles, weights and knots copied bit for bit (the knot sequence
/// split into distinct values and multiplicities by exact comparison), non-periodic, rational
/// when any weight differs from the others. The reason when OCCT refuses it (two distinct
/// knots closer than its Epsilon, a degree above Geom_BSplineSurface::MaxDegree, ...).
/// OCCT exceptions are caught.
Expected<Handle(Geom_BSplineSurface)> makeGeomSurface(const NurbsSurface& s);
/// The same for a trim curve in (u, v).
Expected<Handle(Geom2d_BSplineCurve)> makeGeomCurve(const NurbsCurve2& c);

/// Builds the face of `surface`: its exact surface, and one wire per trim loop whose edges carry
/// the loop's curves as p-curves (unchanged) and 3D curves computed from them
/// (BRepLib::BuildCurves3d, SameParameter). Loops are oriented for OCCT by nesting (Knotwork's
/// even-odd rule): loops inside an even number of others run counter-clockwise in (u, v),
/// the others clockwise. A curve whose 3D image is a point (a sphere's pole) becomes a
/// degenerated edge. Without loops the face is bounded by the surface's natural boundary.
/// `tolerance` (model units, > 0) is the vertices' and edges' least tolerance. When the face
/// BRepCheck finds invalid, ShapeFix_Face repairs its wires (never its surface). The reason
/// when OCCT rejects the surface or a curve, or the result is still invalid.
Expected<TopoDS_Face> buildFace(const Surface& surface, double tolerance);

/// How each trim loop of `surface` must run for OCCT, which reads a face's wires with the
/// material on the left (Knotwork's loops are even-odd): 1 as stored, -1 reversed, 0 left out
/// (its polygon has fewer than 3 points). Loops inside an even number of others run
/// counter-clockwise in (u, v), the others clockwise.
std::vector<int> loopDirections(const Surface& surface);

/// Faces built with the import's record (scene.topology): every recorded shared edge is one
/// TopoDS_Edge carrying both sides' own p-curves (the second side's reparameterised linearly
/// onto the first's range), its 3D curve built from the first side and SameParameter'd, its
/// end vertices shared by every edge that meets there. No face's trims are replaced, so the
/// trimmed areas stay as they are, and no search for neighbours (sewing) is needed.
struct RecordedFaces {
    /// One per scene surface (same order); null for surfaces the record does not cover (no
    /// recorded edge or shell), which the caller sews.
    std::vector<TopoDS_Face> faces;
    /// Per recorded shell (scene.topology.shells order), its built faces.
    std::vector<std::vector<int>> shells;
    int sharedEdges = 0; ///< recorded edges built as one edge
};

/// Builds the faces of `scene` the record covers. `openEdges`: ids of recorded edges whose two
/// sides no longer meet (kw::seamGaps): each side keeps an edge of its own, so the file shows
/// the seam open. `tolerance` (model units, > 0): the least tolerance of every vertex and edge;
/// a shared edge's tolerance is at least its recorded one. A face is turned REVERSED when its
/// loops had to be reversed for OCCT (the source's face was reversed), so the two uses of a
/// shared edge run opposite ways as in the source's shell. The reason when OCCT refuses a
/// curve or a face is invalid (BRepCheck): the caller then builds every face alone and sews.
Status buildRecordedFaces(const Scene& scene, const std::vector<std::uint32_t>& openEdges,
                          double tolerance, RecordedFaces& out);

} // namespace kw::occt
