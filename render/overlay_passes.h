// Overlay passes the editor draws over the surfaces: the base polygon wireframe and the control
// net (points and net lines). Both use shaders/lines.{vert,frag}.
#pragma once

#include "model/document.h"
#include "render/render_types.h"
#include "render/shader_library.h"
#include "render/surface_gpu_cache.h"

#include <QOpenGLFunctions_4_5_Core>
#include <QString>
#include <map>

namespace kw {

/// Outlines of the base polygon cells, from the SurfaceGpuCache's buffers (no own copies).
class WireframePass {
public:
    void initialize(QOpenGLFunctions_4_5_Core* gl, ShaderLibrary* shaders);
    bool draw(const Scene& scene, const SurfaceGpuCache& cache, const FrameCamera& camera,
              QString* error);
    glm::vec4 color{0.05f, 0.05f, 0.08f, 1.0f};
    int drawCalls = 0; ///< counted by draw; the renderer zeroes it per frame

private:
    QOpenGLFunctions_4_5_Core* m_gl = nullptr;
    ShaderLibrary* m_shaders = nullptr;
};

/// Control points as points and the net as lines along i and j; re-uploaded when a surface's
/// Points or Knots revision changes.
class ControlNetPass {
public:
    void initialize(QOpenGLFunctions_4_5_Core* gl, ShaderLibrary* shaders);
    bool draw(const Document& doc, const FrameCamera& camera, QString* error);
    void release();
    /// Bytes of every net's buffers.
    std::int64_t residentBytes() const;
    int drawCalls = 0;   ///< counted by draw; the renderer zeroes it per frame
    UploadStats uploads; ///< counted by draw; the renderer zeroes it per frame
    glm::vec4 lineColor{0.85f, 0.75f, 0.20f, 1.0f};
    glm::vec4 pointColor{1.0f, 0.90f, 0.10f, 1.0f};
    float pointSize = 6.0f;

private:
    struct Net {
        Revisions revisions;
        GLuint vao = 0, points = 0, lines = 0;
        int pointCount = 0, lineIndexCount = 0;
        std::int64_t bytes = 0;
    };
    void update(Net& n, const NurbsSurface& s, const Revisions& rev);

    QOpenGLFunctions_4_5_Core* m_gl = nullptr;
    ShaderLibrary* m_shaders = nullptr;
    std::map<SurfaceId, Net> m_nets;
};

} // namespace kw
