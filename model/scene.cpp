// Scene helpers: default lights, bounds and a camera that frames the scene.
#include "model/scene.h"

#include <algorithm>
#include <cmath>

namespace kw {

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

bool sceneBounds(const Scene& scene, glm::dvec3& lo, glm::dvec3& hi) {
    bool any = false;
    for (const Surface& s : scene.surfaces) {
        if (s.geometry.points.empty())
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
    sceneBounds(scene, lo, hi);
    const glm::dvec3 centre = 0.5 * (lo + hi);
    const double radius = std::max(0.5 * glm::length(hi - lo), 1e-9);
    // Distance at which a sphere of this radius fits the narrower field of view.
    const double halfFovY = glm::radians(cam.fovYDegrees) * 0.5;
    const double halfFovX = std::atan(std::tan(halfFovY) * std::max(aspect, 1e-3));
    const double distance = radius / std::sin(std::min(halfFovX, halfFovY)) * 1.05;
    const glm::dvec3 dir = glm::normalize(glm::dvec3(0.55, -1.0, 0.65));
    cam.target = centre;
    cam.eye = centre + dir * distance;
    cam.up = glm::dvec3(0.0, 0.0, 1.0);
    cam.authored = false;
    return cam;
}

} // namespace kw
