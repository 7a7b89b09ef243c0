// CameraController and ViewProjection: turntable camera math and pixel <-> world mapping.
#include "ui/cameracontroller.h"

#include "render/render_types.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace kw {

namespace {

bool finite3(const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

glm::dvec3 safeUp(const Camera& c) {
    const double len = glm::length(c.up);
    return len > 0.0 && std::isfinite(len) ? c.up / len : glm::dvec3(0.0, 0.0, 1.0);
}

} // namespace

// ---- ViewProjection

ViewProjection::ViewProjection(const Camera& camera, const Scene& scene, QSize size)
    : m_size(size.isEmpty() ? QSize(1, 1) : size) {
    // The renderer's camera in double precision, so picking and dragging round-trip pixels.
    const double aspect = double(m_size.width()) / double(m_size.height());
    const CameraMatrices m = cameraMatrices(camera, scene, aspect);
    m_eye = m.eye;
    m_forward = m.forward;
    m_viewProjection = m.projection * m.view;
    m_inverse = glm::inverse(m_viewProjection);
}

std::optional<QPointF> ViewProjection::project(const glm::dvec3& world) const {
    const glm::dvec4 clip = m_viewProjection * glm::dvec4(world, 1.0);
    if (clip.w <= 1e-12)
        return std::nullopt;
    const double x = clip.x / clip.w, y = clip.y / clip.w;
    return QPointF((x * 0.5 + 0.5) * m_size.width(), (0.5 - y * 0.5) * m_size.height());
}

double ViewProjection::depth(const glm::dvec3& world) const {
    return glm::dot(world - m_eye, m_forward);
}

void ViewProjection::ray(QPointF pixel, glm::dvec3& origin, glm::dvec3& direction) const {
    const double x = 2.0 * pixel.x() / m_size.width() - 1.0;
    const double y = 1.0 - 2.0 * pixel.y() / m_size.height();
    glm::dvec4 far = m_inverse * glm::dvec4(x, y, 1.0, 1.0);
    far /= far.w;
    origin = m_eye;
    direction = glm::normalize(glm::dvec3(far) - m_eye);
}

glm::dvec3 ViewProjection::onViewPlane(QPointF pixel, const glm::dvec3& anchor) const {
    glm::dvec3 o, d;
    ray(pixel, o, d);
    const double denom = glm::dot(d, m_forward);
    if (std::abs(denom) < 1e-12)
        return anchor;
    const double t = glm::dot(anchor - o, m_forward) / denom;
    const glm::dvec3 p = o + t * d;
    return finite3(p) ? p : anchor;
}

glm::dvec3 ViewProjection::onAxis(QPointF pixel, const glm::dvec3& anchor,
                                  const glm::dvec3& axis) const {
    glm::dvec3 o, d;
    ray(pixel, o, d);
    const glm::dvec3 a = glm::normalize(axis);
    // Closest points of two lines: anchor + s a and o + t d.
    const glm::dvec3 w = anchor - o;
    const double b = glm::dot(a, d);
    const double denom = 1.0 - b * b;
    if (denom < 1e-8)
        return anchor;
    const double s = (b * glm::dot(d, w) - glm::dot(a, w)) / denom;
    const glm::dvec3 p = anchor + s * a;
    return finite3(p) ? p : anchor;
}

// ---- CameraController

void CameraController::setCamera(const Camera& camera) {
    m_camera = camera;
    if (!finite3(m_camera.eye) || !finite3(m_camera.target) ||
        glm::length(m_camera.eye - m_camera.target) < 1e-12)
        m_camera = Camera{};
}

void CameraController::orbit(double dxPixels, double dyPixels) {
    if (!std::isfinite(dxPixels) || !std::isfinite(dyPixels))
        return;
    const glm::dvec3 vertical(0.0, 0.0, 1.0); // turntable axis: world z
    glm::dvec3 offset = m_camera.eye - m_camera.target;
    const double distance = glm::length(offset);
    glm::dvec3 up = safeUp(m_camera);
    // Yaw: offset and up turn about the vertical through the target.
    const glm::dmat4 yaw =
        glm::rotate(glm::dmat4(1.0), glm::radians(-dxPixels * kDegreesPerPixel), vertical);
    offset = glm::dvec3(yaw * glm::dvec4(offset, 0.0));
    up = glm::dvec3(yaw * glm::dvec4(up, 0.0));
    // Pitch about the right axis, keeping the elevation inside +-89 degrees. The right axis
    // comes from the camera's up, so a top or bottom view (offset along z) still has one.
    glm::dvec3 right = glm::cross(-offset, up);
    if (glm::length(right) < 1e-12)
        right = glm::cross(-offset, glm::dvec3(0.0, 1.0, 0.0));
    right = glm::normalize(right);
    const double elevation =
        std::asin(std::clamp(glm::dot(offset / distance, vertical), -1.0, 1.0));
    const double limit = glm::radians(89.0);
    const double wanted =
        std::clamp(elevation + glm::radians(dyPixels * kDegreesPerPixel), -limit, limit);
    offset = glm::dvec3(glm::rotate(glm::dmat4(1.0), -(wanted - elevation), right) *
                        glm::dvec4(offset, 0.0));
    offset = glm::normalize(offset) * distance;
    m_camera.eye = m_camera.target + offset;
    // Inside the elevation limit the world vertical is a valid up; keep the view upright.
    m_camera.up = std::abs(glm::dot(glm::normalize(offset), vertical)) < std::sin(limit) + 1e-9
                      ? vertical
                      : glm::normalize(glm::cross(right, -offset));
}

void CameraController::pan(double dxPixels, double dyPixels, QSize viewport) {
    if (viewport.isEmpty() || !std::isfinite(dxPixels) || !std::isfinite(dyPixels))
        return;
    const glm::dvec3 forward = glm::normalize(m_camera.target - m_camera.eye);
    glm::dvec3 right = glm::cross(forward, safeUp(m_camera));
    if (glm::length(right) < 1e-12)
        return;
    right = glm::normalize(right);
    const glm::dvec3 up = glm::cross(right, forward);
    const double distance = glm::length(m_camera.target - m_camera.eye);
    // World units per pixel on the plane through the target.
    const double perPixel =
        2.0 * distance *
        std::tan(glm::radians(std::clamp(m_camera.fovYDegrees, 1.0, 170.0)) / 2.0) /
        viewport.height();
    const glm::dvec3 shift = (-dxPixels * right + dyPixels * up) * perPixel;
    m_camera.eye += shift;
    m_camera.target += shift;
}

void CameraController::zoom(double steps) {
    if (!std::isfinite(steps))
        return;
    const glm::dvec3 offset = m_camera.eye - m_camera.target;
    const double distance = glm::length(offset);
    const double wanted = std::clamp(distance * std::pow(kZoomPerStep, steps), 1e-6, 1e9);
    m_camera.eye = m_camera.target + offset / distance * wanted;
}

void CameraController::fit(const Scene& scene, double aspect) {
    const Camera fitted = fitCamera(scene, aspect);
    const double distance = glm::length(fitted.eye - fitted.target);
    glm::dvec3 dir = m_camera.eye - m_camera.target;
    dir =
        glm::length(dir) > 1e-12 ? glm::normalize(dir) : glm::normalize(fitted.eye - fitted.target);
    m_camera.target = fitted.target;
    m_camera.eye = fitted.target + dir * distance;
}

void CameraController::setStandardView(StandardView view, const Scene& scene, double aspect) {
    glm::dvec3 dir(0.0), up(0.0, 0.0, 1.0);
    switch (view) {
    case StandardView::Front:
        dir = {0, -1, 0};
        break;
    case StandardView::Back:
        dir = {0, 1, 0};
        break;
    case StandardView::Left:
        dir = {-1, 0, 0};
        break;
    case StandardView::Right:
        dir = {1, 0, 0};
        break;
    case StandardView::Top:
        dir = {0, 0, 1};
        up = {0, 1, 0};
        break;
    case StandardView::Bottom:
        dir = {0, 0, -1};
        up = {0, 1, 0};
        break;
    case StandardView::Iso:
        dir = glm::normalize(glm::dvec3(0.55, -1.0, 0.65));
        break;
    }
    m_camera.up = up;
    m_camera.eye = m_camera.target + dir;
    fit(scene, aspect);
    m_camera.up = up;
}

} // namespace kw
