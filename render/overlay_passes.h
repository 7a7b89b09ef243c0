// Overlay passes the editor draws over the surfaces: the base polygon wireframe and the control
// net (points and net lines). Both use shaders/lines.{vert,frag}.
#pragma once

#include "model/document/document.h"
#include "render/gpu_scene.h"
#include "render/render_types.h"
#include "render/shader_library.h"

#include <QOpenGLFunctions_4_5_Core>
#include <QString>

namespace kw {

/// Outlines of the base polygon cells, from the records' base polygon buffers. Both passes are
/// cut by options.sections (each line point by its position, as the surfaces are).
class WireframePass {
public:
    void initialize(QOpenGLFunctions_4_5_Core* gl, ShaderLibrary* shaders);
    Status draw(const GpuScene& scene, const FrameCamera& camera, const RenderOptions& options);
    glm::vec4 color{0.05f, 0.05f, 0.08f, 1.0f};
    int drawCalls = 0; ///< counted by draw; the renderer zeroes it per frame

private:
    QOpenGLFunctions_4_5_Core* m_gl = nullptr;
    ShaderLibrary* m_shaders = nullptr;
};

/// Control points as points and the net as lines along i and j, from the records' NetGpu
/// (GpuScene rebuilds one when its surface's Points or Knots revision changes).
class ControlNetPass {
public:
    void initialize(QOpenGLFunctions_4_5_Core* gl, ShaderLibrary* shaders);
    Status draw(const GpuScene& scene, const FrameCamera& camera, const RenderOptions& options);
    int drawCalls = 0; ///< counted by draw; the renderer zeroes it per frame
    glm::vec4 lineColor{0.85f, 0.75f, 0.20f, 1.0f};
    glm::vec4 pointColor{1.0f, 0.90f, 0.10f, 1.0f};
    float pointSize = 6.0f;

private:
    QOpenGLFunctions_4_5_Core* m_gl = nullptr;
    ShaderLibrary* m_shaders = nullptr;
};

} // namespace kw
