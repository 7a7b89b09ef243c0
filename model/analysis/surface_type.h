// The analytic type of a face (plane, cylinder, cone, sphere, torus or free-form), found by a
// test on its exact surface.
#pragma once

#include "model/document/scene.h"

#include <QString>

namespace kw {

/// What a face's geometry is, found by a test on the sampled exact surface (surfaceType).
enum class SurfaceType { Plane, Cylinder, Cone, Sphere, Torus, FreeForm };

/// "plane", "cylinder", "cone", "sphere", "torus" or "free-form".
QString surfaceTypeName(SurfaceType type);

/// The kind of the importer's closed form when the surface has one (Surface::analytic); else
/// the type of the part of `surface` its trims keep (the whole domain without trims): the
/// surface is sampled on a 9 x 9 grid of the trims' parameter box (kw::trimParameterBox) and
/// each sample the trims keep (every sample, when they keep fewer than 12: a sliver) has its
/// curvature (surfaceCurvature) tested, with `relative` times the samples'
/// bounding-box diagonal as the length tolerance:
/// - plane: every sample on the plane of the first, with its normal;
/// - sphere: k1 = k2 != 0 and every centre of curvature (P - N / k1) at one point;
/// - cylinder / cone: one principal curvature 0 and the centres of the other on one line (the
///   axis), the normal at a constant angle to it (a right angle for a cylinder);
/// - torus: one principal curvature constant (the tube) with its centres on one circle;
/// - anything else free-form. Singular samples (a sphere's pole) are left out.
SurfaceType surfaceType(const Surface& surface, double relative = 1e-6);

} // namespace kw
