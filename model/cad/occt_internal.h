// Internal to knotwork_cad: conversion of one OpenCASCADE face into a Knotwork surface.
#pragma once

#include "model/cad/cadimport.h"
#include "model/document/scene.h"
#include "model/document/units.h"
#include "model/io/meshobj.h"

#include <BRepTopAdaptor_FClass2d.hxx>
#include <QString>
#include <QStringList>
#include <Standard_Handle.hxx>
#include <Standard_Transient.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>
#include <XSControl_Reader.hxx>
#include <functional>
#include <gp_Pnt2d.hxx>
#include <memory>
#include <optional>
#include <vector>

namespace kw::occt {

/// What differs between the formats OCCT's data exchange reads (IGES, STEP): kept out of
/// occtimport.cpp so that each format's module (docs/IMPORT.md) links only its own toolkits
/// (TKIGES or TKSTEP and TKSTEPBase); dlopen's symbol relocations are most of a small file's
/// read (docs/PERFORMANCE.md, First image of a CAD file).
struct ExchangeFormat {
    std::unique_ptr<XSControl_Reader> (*makeReader)();
    /// The name the file gives `entity` (empty when none); *igesType gets its IGES entity type
    /// number (0 for other formats' entities).
    QString (*entityName)(const Handle(Standard_Transient) & entity, int* igesType);
    /// The length unit the loaded file states (STEP's length unit, IGES's global unit flag or
    /// name); nullopt when it states none Knotwork knows.
    std::optional<LengthUnit> (*fileUnit)(XSControl_Reader& reader);
    /// The name of the product `entity` defines (a STEP PRODUCT_DEFINITION: its PRODUCT's
    /// name, else its id), empty for any other entity and for a product named by OCCT's
    /// writer default; null for formats without products (IGES).
    QString (*productName)(const Handle(Standard_Transient) & entity);
};
const ExchangeFormat& igesFormat(); // occt_iges.cpp
const ExchangeFormat& stepFormat(); // occt_step.cpp
/// The reader for `format` in this binary, nullptr when it was linked without it. Defined by
/// occt_formats.cpp, compiled into each module with the formats it reads (KW_OCCT_IGES,
/// KW_OCCT_STEP).
const ExchangeFormat* exchangeFormat(CadFormat format);

/// A step after every face is converted (`knotwork mesh`: triangulating the shape), given the
/// transferred shape and the face map result.sourceFaces indexes; it catches OCCT's exceptions
/// itself. Its Error's message reads "<path>: <reason>".
using AfterImport = std::function<Status(
    const TopoDS_Shape& shape, const TopTools_IndexedMapOfShape& faces, ImportResult& result)>;
/// importOcctFile (occtimport.h), with `after` run before the final progress step when set.
/// An Error's message reads "<path>: <reason>" and its file is `path`.
Expected<ImportResult> importShape(const QString& path, CadFormat format,
                                   const ImportProgress& progress, const AfterImport& after);

/// The B-rep edge one trim curve was made from: the edge of the file's face (not of a converted
/// copy), whether the curve runs against the edge's direction (the wire uses it REVERSED), and
/// the larger of its tolerance and that of the converted copy the curve was taken from.
struct CurveEdge {
    TopoDS_Edge edge;
    bool reversed = false;
    double tolerance = 0.0;
};
/// Per trim loop of a converted face, per curve of the loop.
using FaceEdges = std::vector<std::vector<CurveEdge>>;

/// Converts a face: its surface to a kw::NurbsSurface in OCCT's own (u, v) parameterisation
/// (B-spline surfaces as they are, made non-periodic; Bezier and analytic surfaces converted
/// exactly by GeomConvert / BRepBuilderAPI_NurbsConvert) and its wires (outer first) to trim
/// loops of 2D B-spline p-curves, edges reversed as the wire uses them. When
/// `dropNaturalBoundary` (the file gave the surface no boundary of its own) and the face's only
/// wire runs along its surface's natural boundary, the face gets no loop; otherwise every wire
/// is kept as the file states it. Loop ids are taken from `nextId`. `edges`, when given, gets
/// the edge of each trim curve, parallel to out.trims.
/// Returns the reason when the face cannot be represented (degree above kMaxDegree, no
/// p-curve, conversion failure); OCCT exceptions are the caller's to catch.
Status convertFace(const TopoDS_Face& face, Surface& out, std::uint32_t& nextId,
                   bool dropNaturalBoundary, QStringList& warnings, FaceEdges* edges = nullptr);

/// The closed form of `face`'s surface (plane, cylinder, cone, sphere or torus, also behind a
/// rectangular trim; the face's location applied), with the maps from the parameters of
/// `geometry`, the NURBS convertFace made of it: fitted from the surface's points at its knots,
/// then kept only where analyticDeviation(form, geometry) <= max(1e-9 x the control net's
/// diagonal, the face's tolerance), and at most analyticMatchLimit (what a .knot file may hold);
/// Kind::None otherwise and for every other surface.
/// `deviation`, when given, gets the measured deviation (-1 when none was measured). OCCT
/// exceptions are the caller's to catch.
AnalyticForm analyticFormOf(const TopoDS_Face& face, const NurbsSurface& geometry,
                            double* deviation = nullptr);

/// Records in scene.topology what the imported faces share (model/document/topology.h): every edge
/// of `shape` of which exactly two trim curves were made (`faceEdges[k]` is convertFace's `edges`
/// for scene.surfaces[k]), with its number in TopExp::MapShapes(shape, TopAbs_EDGE) as id and
/// the largest tolerance of the edge and its converted copies; and every shell of `shape` with
/// an imported face (id: its number in TopExp::MapShapes(shape, TopAbs_SHELL)), closed when
/// BRepCheck finds it closed, all its faces were imported and each of its edges is recorded,
/// with the solid number markClosedSolids gave its faces (so it runs after that). A face in two
/// shells is kept in the first; an edge of more than two curves (non-manifold) is not recorded
/// and a line in `warnings` counts such edges. OCCT exceptions are the caller's to catch.
void recordTopology(const TopoDS_Shape& shape, const TopTools_IndexedMapOfShape& faces,
                    const std::vector<int>& sourceFaces, const std::vector<FaceEdges>& faceEdges,
                    Scene& scene, QStringList& warnings);

/// Up to `count` parameter points (u, v) inside `face`'s wires (`inside` is the face's
/// BRepTopAdaptor_FClass2d): an odd stride over a 5 x 5 grid of its (u, v) bounds, which spreads
/// the first few over the face, then a 13 x 13 grid when that finds none (a thin face). Empty
/// when neither grid has a point inside.
std::vector<gp_Pnt2d> parametersInside(const TopoDS_Face& face,
                                       const BRepTopAdaptor_FClass2d& inside, int count);

/// Pairs of imported faces that lie on one another (the same surface twice, or a face on part
/// of another): at least half of up to 9 points inside one face's wires lie on the other,
/// within both faces' tolerances (and 1e-6 of the model's size), inside its wires. Such faces
/// have equal depth wherever both are drawn, so either may show, pixel by pixel. Pairs within
/// one solid (or outside solids) get a line each, "face K (LABEL) and face K' (LABEL')
/// coincide: ...", K the file's face numbers (`sourceFaces`, parallel to `labels`), at most
/// `maxReported` and then a count of the rest; pairs of two solids of `shape` (parts of an
/// assembly in contact) one line with their count and the first pair. OCCT exceptions are the
/// caller's to catch.
QStringList coincidentFaces(const TopoDS_Shape& shape, const TopTools_IndexedMapOfShape& faces,
                            const std::vector<int>& sourceFaces, const QStringList& labels,
                            int maxReported);

/// Marks the surfaces of every closed solid of `shape` whose faces were all imported
/// (Surface::solid, numbered from 0 in the order of the solids; Surface::outsideAlongNormal from
/// each face's orientation in the solid and the sign of its volume). Left unmarked: solids with
/// a shell that BRepCheck finds open or inconsistently oriented, no volume, a face skipped,
/// shared with another solid or used twice, or whose first face's outward normal a point
/// classification does not confirm. `faces` and `sourceFaces` as for coincidentFaces. OCCT
/// exceptions are the caller's to catch.
void markClosedSolids(const TopoDS_Shape& shape, const TopTools_IndexedMapOfShape& faces,
                      const std::vector<int>& sourceFaces, Scene& scene);

/// OCCT viewers' default linear deflection for `shape` (AIS_Shape: 0.004 times the largest side
/// of its bounding box); 0 for an empty shape.
double defaultLinearDeflection(const TopoDS_Shape& shape);

/// Triangulates `shape` with BRepMesh_IncrementalMesh(shape, linear, absolute, angular,
/// sequential) and fills `out` with the triangles of each imported face (`faces` is the map
/// imported.sourceFaces indexes; one TaggedMesh per surface of imported.scene, tagged with its
/// id), positions and normals (OCCT viewers' nodal normals, occtmesh.cpp) moved by the face's
/// location. A face left without triangles is a warning. The reason when the deflections are
/// not positive, BRepMesh fails or no face got triangles; OCCT exceptions are the caller's to
/// catch.
Status meshFaces(const TopoDS_Shape& shape, const TopTools_IndexedMapOfShape& faces,
                 const ImportResult& imported, double linear, double angularDegrees,
                 TaggedMeshSet& out, QStringList& warnings);

/// Each surface of `scene` built alone as a face (buildFace at `tolerance`) and triangulated
/// alone by BRepMesh_IncrementalMesh(face, linear, absolute, angular, sequential): what a
/// viewer pays to show a face again after an edit. One TaggedMesh per surface, in order, with
/// its id. The reason, naming the surface, when a face cannot be built or gets no triangle;
/// OCCT exceptions are the caller's to catch.
Status meshBuiltFaces(const Scene& scene, double tolerance, double linear, double angularDegrees,
                      TaggedMeshSet& out);

} // namespace kw::occt
