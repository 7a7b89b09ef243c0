// Internal to knotwork_cad: conversion of one OpenCASCADE face into a Knotwork surface.
#pragma once

#include "model/cad/cadimport.h"
#include "model/meshobj.h"
#include "model/scene.h"

#include <QString>
#include <QStringList>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>

namespace kw::occt {

/// Converts a face: its surface to a kw::NurbsSurface in OCCT's own (u, v) parameterisation
/// (B-spline surfaces as they are, made non-periodic; Bezier and analytic surfaces converted
/// exactly by GeomConvert / BRepBuilderAPI_NurbsConvert) and its wires (outer first) to trim
/// loops of 2D B-spline p-curves, edges reversed as the wire uses them. When
/// `dropNaturalBoundary` (the file gave the surface no boundary of its own) and the face's only
/// wire runs along its surface's natural boundary, the face gets no loop; otherwise every wire
/// is kept as the file states it. Loop ids are taken from `nextId`.
/// Returns false with `why` set when the face cannot be represented (degree above kMaxDegree,
/// no p-curve, conversion failure); OCCT exceptions are the caller's to catch.
bool convertFace(const TopoDS_Face& face, Surface& out, std::uint32_t& nextId,
                 bool dropNaturalBoundary, QString& why, QStringList& warnings);

/// OCCT viewers' default linear deflection for `shape` (AIS_Shape: 0.004 times the largest side
/// of its bounding box); 0 for an empty shape.
double defaultLinearDeflection(const TopoDS_Shape& shape);

/// Triangulates `shape` with BRepMesh_IncrementalMesh(shape, linear, absolute, angular,
/// sequential) and fills `out` with the triangles of each imported face (`faces` is the map
/// imported.sourceFaces indexes; one TaggedMesh per surface of imported.scene, tagged with its
/// id), positions and normals (OCCT viewers' nodal normals, occtmesh.cpp) moved by the face's
/// location. A face left without triangles is a warning. False with `error` when the
/// deflections are not positive, BRepMesh fails or no face got triangles; OCCT exceptions are
/// the caller's to catch.
bool meshFaces(const TopoDS_Shape& shape, const TopTools_IndexedMapOfShape& faces,
               const ImportResult& imported, double linear, double angularDegrees,
               TaggedMeshSet& out, QStringList& warnings, QString& error);

} // namespace kw::occt
