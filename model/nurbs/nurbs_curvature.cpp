// Surface curvature from the exact derivatives: fundamental forms, K, H, principal curvatures
// and directions, with the collapsed-edge rule of surfaceFrame.
#include "model/nurbs/nurbs_curvature.h"

#include "model/nurbs/nurbs_internal.h"

#include <algorithm>

namespace kw {
namespace {

/// Any unit vector perpendicular to the unit vector n (Frisvad-style branch on the largest
/// component so the cross product is never degenerate).
glm::dvec3 anyPerpendicular(const glm::dvec3& n) {
    const glm::dvec3 a = std::abs(n.x) < 0.6
                             ? glm::dvec3(1, 0, 0)
                             : (std::abs(n.y) < 0.6 ? glm::dvec3(0, 1, 0) : glm::dvec3(0, 0, 1));
    return glm::normalize(glm::cross(n, a));
}

bool finite(const SurfaceCurvature& c) {
    const double all[] = {c.E,  c.F,  c.G,      c.L,      c.M,      c.N,      c.gaussian, c.mean,
                          c.k1, c.k2, c.dir1.x, c.dir1.y, c.dir1.z, c.dir2.x, c.dir2.y,   c.dir2.z};
    return std::all_of(std::begin(all), std::end(all), [](double x) { return std::isfinite(x); });
}

/// Fills the forms, curvatures and directions of `c` from derivatives d at a regular point
/// (Su x Sv != 0) with unit normal n = +-(Su x Sv) / |Su x Sv|.
void fromDerivatives(const SurfaceDerivatives& d, const glm::dvec3& n, SurfaceCurvature& c) {
    c.E = glm::dot(d.su, d.su);
    c.F = glm::dot(d.su, d.sv);
    c.G = glm::dot(d.sv, d.sv);
    c.L = glm::dot(d.suu, n);
    c.M = glm::dot(d.suv, n);
    c.N = glm::dot(d.svv, n);
    // The shape operator as a symmetric 2x2 matrix [[a, b], [b, cc]] in the orthonormal tangent
    // basis e1 = Su / |Su|, e2 = n x e1. With Sv = alpha e1 + beta e2, the tangent x e1 + y e2
    // is (x - alpha y / beta) / |Su| Su + y / beta Sv, i.e. (u, v) coordinates J (x, y) with
    // J = [[1/|Su|, -alpha/(|Su| beta)], [0, 1/beta]]; the shape operator is -J^T II J (positive
    // curvature where the surface bends away from n). Its eigenvalues (a + cc)/2 +- hypot((a -
    // cc)/2, b) have no cancellation at umbilics, unlike H +- sqrt(H^2 - K).
    const double su = std::sqrt(c.E);
    const glm::dvec3 e1 = d.su / su;
    const glm::dvec3 e2 = glm::cross(n, e1);
    const double alpha = glm::dot(d.sv, e1);
    const double beta = glm::dot(d.sv, e2); // +-|Su x Sv| / |Su|, never 0 at a regular point
    const double j11 = 1.0 / su, j12 = -alpha / (su * beta), j22 = 1.0 / beta;
    const double a = -(c.L * j11 * j11);
    const double b = -(c.L * j11 * j12 + c.M * j11 * j22);
    const double cc = -(c.L * j12 * j12 + 2.0 * c.M * j12 * j22 + c.N * j22 * j22);
    const double half = 0.5 * (a - cc);
    const double r = std::hypot(half, b);
    c.mean = 0.5 * (a + cc);
    c.k1 = c.mean + r;
    c.k2 = c.mean - r;
    c.gaussian = a * cc - b * b;
    // Eigenvector of k1: angle theta = atan2(b, half) / 2 from e1 (any angle at an umbilic,
    // where atan2(0, 0) = 0 gives e1).
    const double theta = 0.5 * std::atan2(b, half);
    c.dir1 = std::cos(theta) * e1 + std::sin(theta) * e2;
    c.dir2 = glm::cross(n, c.dir1);
}

} // namespace

SurfaceCurvature surfaceCurvature(const NurbsSurface& s, double u, double v) {
    SurfaceCurvature c;
    if (!detail::shapeOk(s))
        return c;
    const Interval du = surfaceDomainU(s);
    const Interval dv = surfaceDomainV(s);
    u = detail::clampTo(u, du);
    v = detail::clampTo(v, dv);
    // One evaluation serves the frame (point, reported normal) and the curvature.
    detail::LocalEval e = detail::evaluateLocal(s, u, v);
    const SurfaceFrame frame = detail::frameAt(s, u, v, e);
    c.point = frame.point;
    c.normal = frame.normal;
    const double wu = du.last - du.first;
    const double wv = dv.last - dv.first;
    c.regular = detail::regularPoint(e, wu, wv);
    if (!c.regular) {
        // The curvature at surfaceFrame's step-3 point: on a geometrically smooth surface this
        // is the limit at the collapsed edge, within O(kInteriorStep) of it.
        e = detail::evaluateLocal(s, detail::towardsInterior(u, du),
                                  detail::towardsInterior(v, dv));
        if (!detail::regularPoint(e, wu, wv)) {
            c.dir1 = anyPerpendicular(c.normal);
            c.dir2 = glm::cross(c.normal, c.dir1);
            return c;
        }
    }
    glm::dvec3 n = glm::normalize(glm::cross(e.d.su, e.d.sv));
    // Signs follow the reported normal (the limit normal at a collapsed edge has the sign of
    // the interior approach, so this flip is a guard, not the rule).
    if (glm::dot(n, c.normal) < 0.0)
        n = -n;
    SurfaceCurvature r = c;
    fromDerivatives(e.d, n, r);
    if (!c.regular) {
        // Directions tangent to the reported (limit) normal, which differs from n by O(step).
        r.dir1 = glm::normalize(r.dir1 - glm::dot(r.dir1, c.normal) * c.normal);
        r.dir2 = glm::cross(c.normal, r.dir1);
    }
    if (!finite(r)) {
        c.dir1 = anyPerpendicular(c.normal);
        c.dir2 = glm::cross(c.normal, c.dir1);
        return c;
    }
    return r;
}

} // namespace kw
