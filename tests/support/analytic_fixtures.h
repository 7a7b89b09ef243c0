// An imported-looking analytic face for the analytic-form tests: the kernel's exact cylinder
// (quarter arcs in standard form) and the form that describes it.
#pragma once

#include "model/document/scene.h"
#include "model/nurbs/analytic.h"
#include "model/nurbs/nurbs_shapes.h"

#include <QString>
#include <numbers>

namespace kw::test {

/// Radius 2, height 5, base (1, 2, -3), axis +z; id 1, named "Bore".
inline Surface importedCylinder() {
    Surface s;
    s.id = SurfaceId{1};
    s.name = QStringLiteral("Bore");
    const glm::dvec3 base(1.0, 2.0, -3.0);
    s.geometry = makeCylinder(base, 2.0, 5.0);
    s.analytic.kind = AnalyticForm::Kind::Cylinder;
    s.analytic.origin = base;
    s.analytic.radius = 2.0;
    s.analytic.u = {AnalyticParamMap::Kind::HalfAngle, 0.0, 2 * std::numbers::pi};
    s.analytic.v = {AnalyticParamMap::Kind::Linear, 0.0, 5.0};
    return s;
}

} // namespace kw::test
