// Internal to knotwork_cad: conversion of one OpenCASCADE face into a Knotwork surface.
#pragma once

#include "model/scene.h"

#include <QString>
#include <QStringList>
#include <TopoDS_Face.hxx>

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

} // namespace kw::occt
