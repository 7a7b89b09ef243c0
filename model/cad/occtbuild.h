// Knotwork surfaces as OpenCASCADE faces: the exact B-spline surface (rational where weighted)
// with its trim loops as 2D p-curves and 3D edges built from them. The writers (occtexport.cpp)
// use it; so can anything else that needs a B-rep of a surface (re-meshing, checks).
#pragma once

#include "model/document/scene.h"

#include <Geom2d_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <QString>
#include <TopoDS_Face.hxx>

namespace kw::occt {

/// `s` as a Geom_BSplineSurface: poles, weights and knots copied bit for bit (the knot sequence
/// split into distinct values and multiplicities by exact comparison), non-periodic, rational
/// when any weight differs from the others. Null with `why` when OCCT refuses it (two distinct
/// knots closer than its Epsilon, a degree above Geom_BSplineSurface::MaxDegree, ...).
/// OCCT exceptions are caught.
Handle(Geom_BSplineSurface) makeGeomSurface(const NurbsSurface& s, QString& why);
/// The same for a trim curve in (u, v).
Handle(Geom2d_BSplineCurve) makeGeomCurve(const NurbsCurve2& c, QString& why);

/// Builds the face of `surface`: its exact surface, and one wire per trim loop whose edges carry
/// the loop's curves as p-curves (unchanged) and 3D curves computed from them
/// (BRepLib::BuildCurves3d, SameParameter). Loops are oriented for OCCT by nesting (Knotwork's
/// even-odd rule): loops inside an even number of others run counter-clockwise in (u, v),
/// the others clockwise. A curve whose 3D image is a point (a sphere's pole) becomes a
/// degenerated edge. Without loops the face is bounded by the surface's natural boundary.
/// `tolerance` (model units, > 0) is the vertices' and edges' least tolerance. When the face
/// BRepCheck finds invalid, ShapeFix_Face repairs its wires (never its surface). Null face with
/// `why` when OCCT rejects the surface or a curve, or the result is still invalid.
TopoDS_Face buildFace(const Surface& surface, double tolerance, QString& why);

} // namespace kw::occt
