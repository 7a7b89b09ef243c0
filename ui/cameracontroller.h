// CameraController: orbit, pan, zoom, fit and standard views as plain math on a kw::Camera, and
// ViewProjection, the pixel <-> world mapping the viewport and the pickers share (no GL).
#pragma once

#include "model/document/scene.h"

#include <QPointF>
#include <QSize>
#include <glm/glm.hpp>
#include <optional>

namespace kw {

enum class StandardView { Front, Back, Left, Right, Top, Bottom, Iso };

/// The mapping between world space and widget pixels (origin top-left, y down) for one camera,
/// scene and widget size. Uses the renderer's frameCamera, so what is picked is what is drawn.
class ViewProjection {
public:
    /// `size` must be non-empty (an empty size is treated as 1x1).
    ViewProjection(const Camera& camera, const Scene& scene, QSize size);

    /// Pixel position of a world point; nullopt when the point is behind the eye.
    std::optional<QPointF> project(const glm::dvec3& world) const;
    /// Distance of a world point in front of the eye, along the view direction.
    double depth(const glm::dvec3& world) const;
    /// The ray from the eye through a pixel (direction unit length).
    void ray(QPointF pixel, glm::dvec3& origin, glm::dvec3& direction) const;
    /// Where the ray through `pixel` meets the plane through `anchor` facing the viewer;
    /// `anchor` when the ray is parallel to it.
    glm::dvec3 onViewPlane(QPointF pixel, const glm::dvec3& anchor) const;
    /// The point of the line anchor + t*axis closest to the ray through `pixel`; `anchor` when
    /// the axis points along the ray (no usable constraint).
    glm::dvec3 onAxis(QPointF pixel, const glm::dvec3& anchor, const glm::dvec3& axis) const;

    const glm::dvec3& eye() const { return m_eye; }
    const glm::dvec3& forward() const { return m_forward; }
    QSize size() const { return m_size; }

private:
    glm::dmat4 m_viewProjection{1.0};
    glm::dmat4 m_inverse{1.0};
    glm::dvec3 m_eye{0.0};
    glm::dvec3 m_forward{0.0, 0.0, -1.0};
    QSize m_size;
};

/// Turntable camera about camera.target with camera.up as the vertical. All operations keep the
/// camera valid (eye != target, finite values) whatever the input.
class CameraController {
public:
    static constexpr double kDegreesPerPixel = 0.4;
    static constexpr double kZoomPerStep = 0.85; ///< distance factor per wheel step (120 units)

    const Camera& camera() const { return m_camera; }
    void setCamera(const Camera& camera);

    /// Rotates the eye about the target: dx pixels about the vertical, dy about the right axis.
    /// The elevation stays within +-89 degrees so the view never flips.
    void orbit(double dxPixels, double dyPixels);
    /// Moves eye and target in the view plane so the point under the cursor follows it.
    void pan(double dxPixels, double dyPixels, QSize viewport);
    /// Scales the eye-target distance by kZoomPerStep^steps (positive steps move closer).
    void zoom(double steps);
    /// Keeps the view direction and frames the scene's control bounds at `aspect` (w / h).
    void fit(const Scene& scene, double aspect);
    /// Looks along a principal axis (or the default oblique view) and fits the scene.
    void setStandardView(StandardView view, const Scene& scene, double aspect);

private:
    Camera m_camera;
};

} // namespace kw
