// Renderer facade: keeps the GPU cache and the passes, draws a Document into a framebuffer.
// Shared by the off-screen renderer (CLI, tests, bench) and the editor's QOpenGLWidget.
#pragma once

#include "model/document.h"
#include "render/exact_surface_pass.h"
#include "render/overlay_passes.h"
#include "render/render_types.h"
#include "render/shader_library.h"
#include "render/surface_gpu_cache.h"
#include "render/tessellated_pass.h"
#include "render/trim_mask_pass.h"

#include <QOpenGLFunctions_4_5_Core>
#include <QPointer>
#include <QSize>
#include <QString>

namespace kw {

class Renderer {
public:
    Renderer();
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    /// Needs a current OpenGL 4.5 core context (the one every later call uses). Returns false
    /// with lastError() set when the context is not 4.5 core or the shaders do not build.
    bool initialize();
    bool isInitialized() const { return m_gl != nullptr; }

    /// Draws `doc` as seen by `camera` into `targetFbo` (0 or a QOpenGLWidget's
    /// defaultFramebufferObject()) at `size` pixels, uploading only stale surface data first.
    /// With options.writeAov the target must have colour attachments 0..3 as described in
    /// OffscreenRenderer. Returns false with lastError() set on failure: a shader that does
    /// not build (nothing drawn), or a surface whose control net exceeds the GPU's texture
    /// size (exact mode and the wireframe draw the frame without it).
    /// Trimmed surfaces are cut by their trim masks unless options.trims is false; a mask
    /// problem (too many trimmed surfaces for the GPU) draws those surfaces untrimmed and
    /// returns false with lastError() set after drawing the frame.
    /// Surface ids and revisions are per document: drawing another Document than last time
    /// drops every cached upload first.
    bool render(const Document& doc, const Camera& camera, QSize size, const RenderOptions& options,
                GLuint targetFbo);

    /// Frees all GL objects; the initialising context must be current.
    void release();

    const SurfaceGpuCache& cache() const { return m_cache; }
    SurfaceGpuCache& cache() { return m_cache; }
    /// The trim masks of the last frame (per-surface layers, redraw statistics, warnings).
    const TrimMaskPass& trimMasks() const { return m_trimMasks; }
    TrimMaskPass& trimMasks() { return m_trimMasks; }
    QString lastError() const { return m_error; }
    /// GL_RENDERER and GL_VERSION of the context, for reports.
    QString glDescription() const { return m_glDescription; }
    QOpenGLFunctions_4_5_Core* gl() const { return m_gl; }
    /// The colour range the last frame's colour-map analysis used: the user's, or the automatic
    /// one (kw::autoRange), recomputed only when the geometry or the mode changed and held while
    /// AnalysisOptions::holdRange is set. For the legend.
    ValueRange analysisRange() const { return m_analysisRange; }
    /// Environment map (re)loads so far (switching modes must not reload it).
    int environmentLoads() const { return m_exact.environment().loads(); }

private:
    void dropSurfaceCaches();
    void resolveAnalysisRange(const Document& doc, const AnalysisOptions& analysis);

    struct RangeKey {
        const Document* document = nullptr;
        AnalysisMode mode = AnalysisMode::Phong;
        size_t surfaces = 0;
        std::uint64_t newestRevision = 0;
        bool operator==(const RangeKey&) const = default;
    };
    RangeKey m_rangeKey;
    ValueRange m_analysisRange;

    QOpenGLFunctions_4_5_Core* m_gl = nullptr;
    QPointer<const Document> m_document; ///< whose data the caches hold
    ShaderLibrary m_shaders;
    SurfaceGpuCache m_cache;
    TrimMaskPass m_trimMasks;
    ExactSurfacePass m_exact;
    TessellatedPass m_tessellated;
    WireframePass m_wireframe;
    ControlNetPass m_controlNet;
    QString m_error;
    QString m_glDescription;
};

} // namespace kw
