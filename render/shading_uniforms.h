// Uniforms shared by the shaded passes: camera, lights (phong.glsl) and one surface's material.
#pragma once

#include "model/document/scene.h"
#include "render/render_types.h"

#include <QOpenGLFunctions_4_5_Core>
#include <vector>

class QOpenGLShaderProgram;

namespace kw {

/// Sets uViewProjection, uEye, uForward and the light uniforms of phong.glsl on `program`,
/// which must be bound and built with LIGHT_COUNT == lights.size() (at most kMaxLights).
void setFrameUniforms(QOpenGLFunctions_4_5_Core* gl, QOpenGLShaderProgram* program,
                      const FrameCamera& camera, const std::vector<Light>& lights);
/// Sets section.glsl's planes and caps from options.sections (unit normals of the removed
/// sides, at most kMaxSectionPlanes) on the bound program; nothing where it has none.
void setSectionUniforms(QOpenGLFunctions_4_5_Core* gl, QOpenGLShaderProgram* program,
                        const RenderOptions& options);
/// Sets uColor, uMaterial and uSurfaceId (exact in a float up to 2^24) on the bound program.
void setSurfaceUniforms(QOpenGLFunctions_4_5_Core* gl, QOpenGLShaderProgram* program,
                        const Surface& surface);

} // namespace kw
