// Parameter ranges of a face's edges checked before OCCT's algorithms (NURBS conversion,
// projection, meshing) see them: a range outside the curve it runs along, empty, reversed or
// not finite sends them into approximations that run for a minute on a 160 KB file.
#pragma once

#include "model/error.h"

#include <QString>
#include <TopoDS_Face.hxx>

namespace kw::occt {

/// ok() when every edge of `face` has a finite range [first, last] with first < last that
/// lies within the domain of its 3D curve and of its p-curve on `face` (periodic curves have
/// no bounds; degenerated edges have no 3D curve). Otherwise an Error with the first fault, e.g.
/// "edge 3: its range [3.14159, 4.71239] leaves its p-curve's domain [0, 3.14159]". OCCT exceptions
/// are the caller's to catch.
Status checkEdgeRanges(const TopoDS_Face& face);

} // namespace kw::occt
