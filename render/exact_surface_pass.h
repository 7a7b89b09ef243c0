// Exact pass (paper 3.4.1): per-fragment NURBS evaluation and Phong shading with
// degree-specialised shaders. Three ways to shade each pixel once (RenderOptions::Shading):
// deferred (G-buffer + one screen-space pass per surface), depth pre-pass + GL_EQUAL, or a
// single pass writing the exact depth.
#pragma once

#include "render/render_types.h"
#include "render/shader_library.h"
#include "render/surface_gpu_cache.h"

#include <QSize>
#include <QString>

namespace kw {

class ExactSurfacePass {
public:
    /// Needs the context current while drawing; `shaders` outlives the pass.
    void initialize(QOpenGLFunctions_4_5_Core* gl, ShaderLibrary* shaders);

    /// Draws every surface of `scene` found in `cache` into `targetFbo` (bound, depth test on,
    /// viewport camera.viewport). Returns false with *error set when a shader variant cannot
    /// be built or the G-buffer cannot be allocated.
    bool draw(const Scene& scene, const SurfaceGpuCache& cache, const FrameCamera& camera,
              const std::vector<Light>& lights, const RenderOptions& options, GLuint targetFbo,
              QString* error);
    /// Frees the G-buffer; the context must be current.
    void release();

    /// The defines of the shader variant for degrees (p, q) and these options.
    static QStringList variantDefines(int p, int q, int lightCount, const RenderOptions& options);

private:
    bool drawBasePolygons(const Scene& scene, const SurfaceGpuCache& cache,
                          const FrameCamera& camera, const QString& fragment, QString* error);
    bool drawForward(const Scene& scene, const SurfaceGpuCache& cache, const FrameCamera& camera,
                     const std::vector<Light>& lights, const RenderOptions& options,
                     QString* error);
    bool drawDeferred(const Scene& scene, const SurfaceGpuCache& cache, const FrameCamera& camera,
                      const std::vector<Light>& lights, const RenderOptions& options,
                      GLuint targetFbo, QString* error);
    bool ensureGBuffer(QSize size, QString* error);
    void destroyGBuffer();
    QOpenGLShaderProgram* exactProgram(const QString& vertex, const QString& fragment,
                                       const SurfaceGpu& g, const FrameCamera& camera,
                                       const std::vector<Light>& lights,
                                       const RenderOptions& options, QString* error);

    QOpenGLFunctions_4_5_Core* m_gl = nullptr;
    ShaderLibrary* m_shaders = nullptr;
    QOpenGLShaderProgram* m_bound = nullptr; ///< within one draw() call
    GLuint m_gFbo = 0, m_gUvSpan = 0, m_gSurface = 0, m_gDepth = 0, m_emptyVao = 0;
    QSize m_gSize;
};

} // namespace kw
