// Scene helpers: default lights, bounds and a camera that frames the scene.
#include "model/document/scene.h"

#include "model/nurbs/visible_bounds.h"

#include <algorithm>
#include <cmath>

namespace kw {

Status checkSectionPlane(const SectionPlane& plane) {
    const auto finite = [](const glm::dvec3& v) {
        return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
    };
    if (!finite(plane.position))
        return Error(QStringLiteral("the section plane's position is not a finite point"));
    if (!finite(plane.normal))
        return Error(QStringLiteral("the section plane's normal is not a finite vector"));
    // A normal too short to normalise in double gives no plane either.
    if (!(glm::length(plane.normal) > 1e-300))
        return Error(QStringLiteral("the section plane's normal has zero length"));
    return ok();
}

std::vector<Light> defaultLights() {
    Light key;
    key.kind = Light::Kind::Directional;
    key.vector = glm::normalize(glm::dvec3(-0.4, -0.6, 0.7));
    key.ambient = glm::dvec3(0.20);
    key.diffuse = glm::dvec3(0.80);
    key.specular = glm::dvec3(0.60);

    Light fill;
    fill.kind = Light::Kind::Directional;
    fill.vector = glm::normalize(glm::dvec3(0.7, -0.3, 0.2));
    fill.ambient = glm::dvec3(0.0);
    fill.diffuse = glm::dvec3(0.35);
    fill.specular = glm::dvec3(0.15);
    return {key, fill};
}

bool sceneBounds(const Scene& scene, glm::dvec3& lo, glm::dvec3& hi, bool shownOnly) {
    bool any = false;
    for (const Surface& s : scene.surfaces) {
        if (s.geometry.points.empty() || (shownOnly && s.hidden))
            continue;
        glm::dvec3 a, b;
        surfaceControlBounds(s.geometry, a, b);
        lo = any ? glm::min(lo, a) : a;
        hi = any ? glm::max(hi, b) : b;
        any = true;
    }
    return any;
}

Camera fitCamera(const Scene& scene, double aspect) {
    Camera cam;
    glm::dvec3 lo(-1.0), hi(1.0);
    // Frame what is drawn (the trimmed exact geometry of the surfaces shown), not the control
    // nets, which can be several times larger (imported faces on large B-spline domains).
    bool framed = false;
    for (const bool shownOnly : {true, false})
        if (!framed)
            framed = sceneVisibleBounds(scene, lo, hi, shownOnly) ||
                     sceneBounds(scene, lo, hi, shownOnly);
    const glm::dvec3 centre = 0.5 * (lo + hi);
    const double radius = std::max(0.5 * glm::length(hi - lo), 1e-9);
    const double tanY = std::tan(glm::radians(cam.fovYDegrees) * 0.5);
    const double tanX = tanY * std::max(aspect, 1e-3);
    const glm::dvec3 dir = glm::normalize(glm::dvec3(0.55, -1.0, 0.65));
    // The nearest distance from the centre at which all eight corners of the bounds lie in
    // the frustum (a corner at view offsets (x, y) and depth offset z needs d + z >= |x| / tanX
    // and |y| / tanY), with a 5% margin; never inside the bounding sphere. Tighter than fitting
    // the bounding sphere, which left flat and elongated parts small in the frame.
    const glm::dvec3 forward = -dir;
    const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(0.0, 0.0, 1.0)));
    const glm::dvec3 up = glm::cross(right, forward);
    double distance = radius * 1.05;
    for (int k = 0; k < 8; ++k) {
        const glm::dvec3 c((k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z);
        const glm::dvec3 o = c - centre;
        const double need =
            std::max(std::abs(glm::dot(o, right)) / tanX, std::abs(glm::dot(o, up)) / tanY) -
            glm::dot(o, forward);
        distance = std::max(distance, need * 1.05);
    }
    cam.target = centre;
    cam.eye = centre + dir * distance;
    cam.up = glm::dvec3(0.0, 0.0, 1.0);
    cam.authored = false;
    return cam;
}

Camera zoomedCamera(const Camera& camera, double factor, glm::dvec2 at, double aspect) {
    Camera cam = camera;
    const glm::dvec3 toTarget = camera.target - camera.eye;
    const double distance = glm::length(toTarget);
    if (!(distance > 0.0) || !(factor >= 1.0))
        return cam;
    const glm::dvec3 forward = toTarget / distance;
    glm::dvec3 right = glm::cross(forward, camera.up);
    if (!(glm::length(right) > 0.0)) // up along the view: any side will do
        right = glm::cross(forward, std::abs(forward.z) < 0.9 ? glm::dvec3(0.0, 0.0, 1.0)
                                                              : glm::dvec3(0.0, 1.0, 0.0));
    right = glm::normalize(right);
    const glm::dvec3 up = glm::cross(right, forward);
    const double halfY = distance * std::tan(glm::radians(camera.fovYDegrees) * 0.5);
    const double halfX = halfY * std::max(aspect, 1e-3);
    cam.target =
        camera.target + right * ((2.0 * at.x - 1.0) * halfX) + up * ((1.0 - 2.0 * at.y) * halfY);
    cam.fovYDegrees =
        glm::degrees(2.0 * std::atan(std::tan(glm::radians(camera.fovYDegrees) * 0.5) / factor));
    return cam;
}

} // namespace kw
