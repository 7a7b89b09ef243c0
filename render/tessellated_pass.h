// Baseline pass, the paper's "OpenGL API" column: surfaces tessellated on the CPU with the
// kernel at their partitions (GpuScene builds the meshes), per-vertex normals, Gouraud shading.
#pragma once

#include "render/gpu_scene.h"
#include "render/render_types.h"
#include "render/shader_library.h"

#include <QOpenGLFunctions_4_5_Core>
#include <QString>

namespace kw {

/// Sets up `vao` for tessellated.vert: the positions, normals and (u, v) of `buffers`, in that
/// order, each buffer bound at its attribute's location (kAttrPosition, kAttrMeshNormal,
/// kAttrMeshUv). The index buffer is the caller's.
void setMeshAttributes(QOpenGLFunctions_4_5_Core* gl, GLuint vao, const GLuint (&buffers)[3]);

class TessellatedPass {
public:
    void initialize(QOpenGLFunctions_4_5_Core* gl, ShaderLibrary* shaders);
    /// Draws the meshes of `scene`'s records into the bound framebuffer, cutting the surfaces
    /// that have an active mask when `trims`. Returns the error when the shader
    /// cannot be built.
    Status draw(const GpuScene& scene, bool trims, const FrameCamera& camera,
                const std::vector<Light>& lights, const RenderOptions& options);
    int drawCalls = 0; ///< counted by draw; the renderer zeroes it per frame
    /// As ExactSurfacePass::firstDrawCpuMs.
    double firstDrawCpuMs = -1.0;

private:
    QOpenGLFunctions_4_5_Core* m_gl = nullptr;
    ShaderLibrary* m_shaders = nullptr;
};

} // namespace kw
