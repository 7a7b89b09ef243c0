// Trim loops on the CPU for the UV panel: polylines of the trim curves and a parity
// classification image of the domain, drawn with model/nurbs/trim.h (the 3D view uses the GPU
// mask).
#pragma once

#include "model/document/scene.h"

#include <QImage>
#include <QSize>
#include <vector>

namespace kw {

/// One closed polygon per usable trim loop, in (u, v), the last point not repeated
/// (makeTrimRegion: gaps bridged, degenerate loops left out). Degree-1 curves are exact; higher
/// degrees are flattened adaptively, finer for larger `samplesPerSpan` (24: a thousandth of
/// the domain diagonal).
std::vector<std::vector<glm::dvec2>> trimPolylines(const Surface& surface, int samplesPerSpan = 24);

/// Classification of the surface's parameter domain into kept (inside an odd number of loops)
/// and removed pixels by model/nurbs/trim.h's parity rule (trimRegionSpans per column). Pixel (x,
/// y) samples the centre of its cell; row 0 is the top of the domain (v = last), column 0 its left
/// (u = first). A surface without trims is kept everywhere. Returns a Format_Grayscale8 image: 255
/// kept, 0 removed; a null image for an empty size.
QImage trimMaskImage(const Surface& surface, QSize size);

/// Fraction of kept pixels of a mask from trimMaskImage (0 for a null image).
double keptFraction(const QImage& mask);

} // namespace kw
