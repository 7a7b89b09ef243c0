// Which analytic surface a face is, by a test on its sampled exact curvature.
#include "model/analysis/surface_type.h"

#include "model/nurbs/nurbs_curvature.h"
#include "model/nurbs/trim.h"
#include "model/nurbs/visible_bounds.h"
#include "model/nurbs/trim_arcs.h"

#include <cmath>
#include <limits>

namespace kw {
namespace {

/// The points of a (grid + 1)^2 grid over the trims' parameter box that the trims keep; all of
/// them when the trims keep fewer than `least` (a sliver of a face: the surface's type is that of
/// the surface around it).
std::vector<glm::dvec2> keptSamples(const Surface& surface, int grid, size_t least) {
    const TrimArcs arcs = makeTrimArcs(surface.trims, trimTolerance(surface.geometry));
    const ParameterBox box = trimParameterBox(surface);
    std::vector<glm::dvec2> all, kept;
    for (int j = 0; j <= grid; ++j)
        for (int i = 0; i <= grid; ++i) {
            const glm::dvec2 uv(box.u.first + (box.u.last - box.u.first) * i / grid,
                                box.v.first + (box.v.last - box.v.first) * j / grid);
            all.push_back(uv);
            if (arcs.empty() || trimArcsContain(arcs, uv))
                kept.push_back(uv);
        }
    return kept.size() >= least ? kept : all;
}

} // namespace

QString surfaceTypeName(SurfaceType type) {
    switch (type) {
    case SurfaceType::Plane:
        return QStringLiteral("plane");
    case SurfaceType::Cylinder:
        return QStringLiteral("cylinder");
    case SurfaceType::Cone:
        return QStringLiteral("cone");
    case SurfaceType::Sphere:
        return QStringLiteral("sphere");
    case SurfaceType::Torus:
        return QStringLiteral("torus");
    case SurfaceType::FreeForm:
        break;
    }
    return QStringLiteral("free-form");
}

SurfaceType surfaceType(const Surface& surface, double relative) {
    // The importer's closed form, while the face is unedited (Document drops it on an edit),
    // is the file's own statement of the type: no sampling tolerance decides it.
    switch (surface.analytic.kind) {
    case AnalyticForm::Kind::None:
        break;
    case AnalyticForm::Kind::Plane:
        return SurfaceType::Plane;
    case AnalyticForm::Kind::Cylinder:
        return SurfaceType::Cylinder;
    case AnalyticForm::Kind::Cone:
        return SurfaceType::Cone;
    case AnalyticForm::Kind::Sphere:
        return SurfaceType::Sphere;
    case AnalyticForm::Kind::Torus:
        return SurfaceType::Torus;
    }
    const NurbsSurface& g = surface.geometry;
    if (!checkNurbsSurface(g))
        return SurfaceType::FreeForm;
    std::vector<SurfaceCurvature> c;
    for (const glm::dvec2& uv : keptSamples(surface, 8, 12)) {
        const SurfaceCurvature k = surfaceCurvature(g, uv.x, uv.y);
        if (k.regular)
            c.push_back(k);
    }
    if (c.size() < 6)
        return SurfaceType::FreeForm;
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
    for (const SurfaceCurvature& k : c)
        lo = glm::min(lo, k.point), hi = glm::max(hi, k.point);
    const double size = glm::length(hi - lo);
    if (!(size > 0.0))
        return SurfaceType::FreeForm;
    const double tol = relative * size;
    const auto zero = [&](double k) {
        return std::abs(k) * size < relative;
    };
    const auto same = [&](double a, double b) {
        return std::abs(a - b) * size < relative;
    };

    bool plane = true;
    for (const SurfaceCurvature& k : c)
        plane = plane && std::abs(glm::dot(k.point - c[0].point, c[0].normal)) < tol &&
                glm::length(glm::cross(k.normal, c[0].normal)) < relative;
    if (plane)
        return SurfaceType::Plane;

    // Centres of curvature: P - N / k for the chosen principal curvature of each sample.
    const auto centres = [&](auto pick) {
        std::vector<glm::dvec3> out;
        for (const SurfaceCurvature& k : c)
            out.push_back(k.point - k.normal / pick(k));
        return out;
    };
    // The line through the two centres farthest apart, if every centre lies on it.
    const auto onLine = [&](const std::vector<glm::dvec3>& pts, glm::dvec3& at, glm::dvec3& dir) {
        size_t far = 0;
        for (size_t k = 1; k < pts.size(); ++k)
            if (glm::length(pts[k] - pts[0]) > glm::length(pts[far] - pts[0]))
                far = k;
        if (glm::length(pts[far] - pts[0]) < tol)
            return false;
        at = pts[0], dir = glm::normalize(pts[far] - pts[0]);
        for (const glm::dvec3& p : pts)
            if (glm::length(glm::cross(p - at, dir)) > tol)
                return false;
        return true;
    };

    bool sphere = true;
    for (const SurfaceCurvature& k : c)
        sphere = sphere && !zero(k.k1) && same(k.k1, k.k2);
    if (sphere) {
        const std::vector<glm::dvec3> pts = centres([](const SurfaceCurvature& k) { return k.k1; });
        for (const glm::dvec3& p : pts)
            sphere = sphere && glm::length(p - pts[0]) < tol;
        return sphere ? SurfaceType::Sphere : SurfaceType::FreeForm;
    }

    // Developable: one principal curvature zero at every sample, the other not.
    bool ruled = true;
    for (const SurfaceCurvature& k : c)
        ruled = ruled && (zero(k.k1) != zero(k.k2));
    if (ruled) {
        const std::vector<glm::dvec3> pts =
            centres([&](const SurfaceCurvature& k) { return zero(k.k1) ? k.k2 : k.k1; });
        glm::dvec3 at, dir;
        bool cylinder = true, cone = true;
        // A cylinder's centres are one point per axial station, so test its axis along the
        // rulings; a cone's centres spread along its axis.
        const glm::dvec3 ruling = zero(c[0].k1) ? c[0].dir1 : c[0].dir2;
        for (size_t k = 0; k < c.size(); ++k)
            cylinder = cylinder && glm::length(glm::cross(pts[k] - pts[0], ruling)) < tol &&
                       std::abs(glm::dot(c[k].normal, ruling)) < relative;
        if (cylinder)
            return SurfaceType::Cylinder;
        if (onLine(pts, at, dir)) {
            const double cosine = glm::dot(c[0].normal, dir);
            for (const SurfaceCurvature& k : c)
                cone = cone &&
                       std::abs(std::abs(glm::dot(k.normal, dir)) - std::abs(cosine)) < relative;
            if (cone)
                return SurfaceType::Cone;
        }
        return SurfaceType::FreeForm;
    }

    // Torus: one principal curvature constant (1 / tube radius), its centres on one circle.
    for (int which = 0; which < 2; ++which) {
        const auto pick = [which](const SurfaceCurvature& k) {
            return which == 0 ? k.k1 : k.k2;
        };
        bool constant = true;
        for (const SurfaceCurvature& k : c)
            constant = constant && !zero(pick(k)) && same(pick(k), pick(c[0]));
        if (!constant)
            continue;
        const std::vector<glm::dvec3> pts = centres(pick);
        // The circle through three centres far apart, then every centre on it.
        size_t b = 0, d = 0;
        for (size_t k = 1; k < pts.size(); ++k)
            if (glm::length(pts[k] - pts[0]) > glm::length(pts[b] - pts[0]))
                b = k;
        double area = 0.0;
        for (size_t k = 1; k < pts.size(); ++k) {
            const double a = glm::length(glm::cross(pts[b] - pts[0], pts[k] - pts[0]));
            if (a > area)
                area = a, d = k;
        }
        if (area < tol * size)
            continue;
        const glm::dvec3 ab = pts[b] - pts[0], ad = pts[d] - pts[0];
        const glm::dvec3 n = glm::cross(ab, ad);
        const glm::dvec3 centre =
            pts[0] + (glm::dot(ab, ab) * glm::cross(ad, n) + glm::dot(ad, ad) * glm::cross(n, ab)) /
                         (2.0 * glm::dot(n, n));
        const glm::dvec3 axis = glm::normalize(n);
        const double radius = glm::length(pts[0] - centre);
        bool torus = true;
        for (const glm::dvec3& p : pts)
            torus = torus && std::abs(glm::dot(p - centre, axis)) < tol &&
                    std::abs(glm::length(p - centre) - radius) < tol;
        if (torus)
            return SurfaceType::Torus;
    }
    return SurfaceType::FreeForm;
}

} // namespace kw
