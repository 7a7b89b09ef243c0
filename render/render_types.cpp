// Camera matrices and light lists for a frame; upload statistics arithmetic.
#include "render/render_types.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace kw {

TrimMaskStats& TrimMaskStats::operator+=(const TrimMaskStats& o) {
    redraws += o.redraws;
    loops += o.loops;
    triangles += o.triangles;
    texels += o.texels;
    arrayAllocations += o.arrayAllocations;
    cpuNanoseconds += o.cpuNanoseconds;
    largestSide = std::max(largestSide, o.largestSide);
    return *this;
}

UploadStats& UploadStats::operator+=(const UploadStats& o) {
    fullUploads += o.fullUploads;
    subImageUploads += o.subImageUploads;
    texels += o.texels;
    bytes += o.bytes;
    spanTableUploads += o.spanTableUploads;
    basePolygonBuilds += o.basePolygonBuilds;
    vertexUpdates += o.vertexUpdates;
    vertexBytes += o.vertexBytes;
    meshBuilds += o.meshBuilds;
    netBuilds += o.netBuilds;
    return *this;
}

CameraMatrices cameraMatrices(const Camera& camera, const Scene& scene, double aspect) {
    glm::dvec3 box[2];
    return cameraMatrices(camera, sceneBounds(scene, box[0], box[1]) ? &box : nullptr, aspect);
}

FrameCamera frameCamera(const Camera& camera, const Scene& scene, double aspect) {
    glm::dvec3 box[2];
    return frameCamera(camera, sceneBounds(scene, box[0], box[1]) ? &box : nullptr, aspect);
}

CameraMatrices cameraMatrices(const Camera& camera, const glm::dvec3 (*bounds)[2], double aspect) {
    CameraMatrices m;
    m.eye = camera.eye;
    glm::dvec3 forward = camera.target - camera.eye;
    if (glm::length(forward) < 1e-300)
        forward = glm::dvec3(0.0, 1.0, 0.0);
    m.forward = glm::normalize(forward);
    glm::dvec3 up = camera.up;
    if (glm::length(glm::cross(m.forward, up)) < 1e-9 * glm::length(up) || glm::length(up) == 0.0)
        up = std::abs(m.forward.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(0, 1, 0);

    m.nearPlane = 0.01;
    m.farPlane = 100.0;
    if (bounds) {
        const glm::dvec3 lo = (*bounds)[0], hi = (*bounds)[1];
        const glm::dvec3 centre = 0.5 * (lo + hi);
        const double radius = std::max(0.5 * glm::length(hi - lo), 1e-6);
        const double d = glm::dot(centre - m.eye, m.forward);
        m.farPlane = std::max(d + radius * 1.1, radius * 1e-3);
        m.nearPlane = std::max(d - radius * 1.1, m.farPlane * 1e-5);
    }
    const double fovY = glm::radians(std::clamp(camera.fovYDegrees, 1.0, 170.0));
    m.view = glm::lookAt(m.eye, m.eye + m.forward, up);
    m.projection = glm::perspective(fovY, std::max(aspect, 1e-6), m.nearPlane, m.farPlane);
    return m;
}

glm::mat4 drawnViewProjection(const FrameCamera& camera) {
    if (camera.jitter == glm::vec2(0.0f))
        return camera.viewProjection;
    // x_ndc' = x_ndc + 2 jitter.x / width: in clip space x' = x + (2 jitter.x / width) w.
    glm::mat4 shift(1.0f);
    shift[3][0] = 2.0f * camera.jitter.x / float(std::max(camera.viewport.x, 1));
    shift[3][1] = 2.0f * camera.jitter.y / float(std::max(camera.viewport.y, 1));
    return shift * camera.viewProjection;
}

FrameCamera frameCamera(const Camera& camera, const glm::dvec3 (*bounds)[2], double aspect) {
    const CameraMatrices m = cameraMatrices(camera, bounds, aspect);
    // Reversed depth for the GPU (glClipControl's zero-to-one range): depth = near / distance,
    // 1 at the near plane and 0 at infinity, so a float depth buffer resolves about 1e-7 of the
    // distance at every distance, where GL's -1..1 mapping leaves 1e-3 when near is 1e-5 of far
    // (the eye inside the scene's bounds: close-ups). Row z becomes (row w - row z) / 2, in
    // double before rounding: exactly n / (f - n) z + f n / (f - n).
    glm::dmat4 projection = m.projection;
    for (int c = 0; c < 4; ++c)
        projection[c][2] = 0.5 * (m.projection[c][3] - m.projection[c][2]);
    FrameCamera fc;
    fc.view = glm::mat4(m.view);
    fc.projection = glm::mat4(projection);
    fc.viewProjection = glm::mat4(projection * m.view);
    fc.eye = glm::vec3(m.eye);
    fc.forward = glm::vec3(m.forward);
    fc.nearPlane = float(m.nearPlane);
    fc.farPlane = float(m.farPlane);
    return fc;
}

std::vector<Light> lightsFor(const Scene& scene, const Camera& camera, int count, bool headlight) {
    const std::vector<Light> base = scene.lights.empty() ? defaultLights() : scene.lights;
    count = std::clamp(count, 1, kMaxLights);
    std::vector<Light> out;
    glm::dvec3 axis =
        glm::length(camera.up) > 0.0 ? glm::normalize(camera.up) : glm::dvec3(0, 0, 1);
    for (int i = 0; i < count; ++i) {
        const int round = i / int(base.size());
        Light l = base[size_t(i) % base.size()];
        if (round > 0) {
            // Rotate by a golden-angle multiple so added lights spread around the scene.
            const double angle = round * 2.39996322972865332;
            const glm::dmat4 r = glm::rotate(glm::dmat4(1.0), angle, axis);
            l.vector =
                glm::dvec3(r * glm::dvec4(l.vector, l.kind == Light::Kind::Point ? 1.0 : 0.0));
            l.ambient = glm::dvec3(0.0); // ambient is counted once per original light
        }
        out.push_back(l);
    }
    if (headlight) {
        // The camera frame: right, forward (eye to target) and up. In the front view they are
        // x, y and z, so there the lights are exactly as authored.
        const glm::dvec3 f = glm::normalize(camera.target - camera.eye);
        const glm::dvec3 r = glm::normalize(glm::cross(f, axis));
        const glm::dvec3 u = glm::cross(r, f);
        if (std::isfinite(r.x) && std::isfinite(u.x))
            for (Light& l : out) {
                const glm::dvec3 v =
                    l.kind == Light::Kind::Point ? l.vector - camera.target : l.vector;
                const glm::dvec3 turned = v.x * r + v.y * f + v.z * u;
                l.vector = l.kind == Light::Kind::Point ? camera.target + turned : turned;
            }
    }
    return out;
}

} // namespace kw
