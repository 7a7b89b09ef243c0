// The one test hook into a Renderer: what render's GL tests inspect beyond its public interface.
#pragma once

#include "render/analysis_gl.h"
#include "render/gpu_scene.h"
#include "render/renderer.h"

#include <QOpenGLFunctions_4_5_Core>

namespace kw {

/// For render's tests only; application code uses Renderer's public calls. Each needs the
/// renderer initialised, and its context current for any GL call made through it.
struct RendererTestHook {
    /// The GPU mirror of the document: upload statistics, trim masks and their warnings.
    static GpuScene& scene(Renderer& renderer);
    /// The renderer's GL functions, to query limits or raise an error on purpose.
    static QOpenGLFunctions_4_5_Core* gl(Renderer& renderer);
    /// The exact pass's environment map (how often its image was loaded).
    static const EnvironmentMap& environment(const Renderer& renderer);
};

} // namespace kw
