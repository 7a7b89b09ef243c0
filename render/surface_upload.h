// One surface's exact-mode GPU data (control-point and span-table textures, base polygon
// buffers) and the uploads that bring it up to date; GpuScene decides which one is due.
#pragma once

#include "model/document.h"
#include "render/frame_report.h"
#include "render/gpu_layout.h"
#include "render/render_types.h"

#include <QOpenGLFunctions_4_5_Core>
#include <QString>

namespace kw {

/// GPU objects of one surface. Textures: control points RGBA32F countU x countV (texel (i, j) =
/// (w P, w)), span tables RGBA32F spanTableTexels(p) x (count - p). Two VAOs share the vertex
/// buffer of BaseVertex: one with triangle indices, one with cell outlines.
struct SurfaceGpu {
    SurfaceId id;
    Revisions revisions; ///< what is on the GPU
    int partitionsU = 0, partitionsV = 0;
    int degreeU = 1, degreeV = 1, countU = 0, countV = 0;
    glm::vec4 domain{0.0f, 1.0f, 0.0f, 1.0f};
    glm::dvec3 origin{0.0}; ///< control texels are relative to it (packControlPoints)
    GLuint controlTexture = 0, spanTextureU = 0, spanTextureV = 0;
    GLuint vertexBuffer = 0, triangleBuffer = 0, outlineBuffer = 0;
    GLuint triangleVao = 0, outlineVao = 0;
    int triangleIndexCount = 0, outlineIndexCount = 0;
    std::vector<glm::vec4> control; ///< the texels now on the GPU
    BasePolygon polygon;            ///< the vertices now on the GPU
    ParameterBox polygonBox;        ///< the (u, v) box the polygon spans
    bool polygonTrimmed = false;    ///< polygonBox is trimParameterBox, not the domain
};

/// Full upload of a new surface, or after its knots, degrees or counts changed: textures
/// (re)created and filled, base polygon rebuilt at nu x nv partitions over `box`. Counts into
/// `stats`.
void uploadSurface(QOpenGLFunctions_4_5_Core* gl, SurfaceGpu& g, const Surface& s, int nu, int nv,
                   const ParameterBox& box, UploadStats& stats);
/// After a Points revision change: the bounding rectangle of the texels that differ as one
/// sub-image, and only the base polygon vertices in the support of those points.
void uploadChangedPoints(QOpenGLFunctions_4_5_Core* gl, SurfaceGpu& g, const Surface& s,
                         UploadStats& stats);
/// The base polygon at nu x nv partitions over `box` (a rectangle of the domain: GpuScene
/// passes trimParameterBox unless RenderOptions::polygonOverTrims is off, so a trimmed face's cells
/// go where its trims keep the surface, issue 10 item 1) from the current points; textures
/// untouched.
void rebuildPolygon(QOpenGLFunctions_4_5_Core* gl, SurfaceGpu& g, const Surface& s, int nu, int nv,
                    const ParameterBox& box, UploadStats& stats);
/// Frees the surface's GL objects.
void destroySurfaceGpu(QOpenGLFunctions_4_5_Core* gl, SurfaceGpu& g);
/// Bytes of the surface's textures and buffers, added to `out` by kind.
void addResidentBytes(const SurfaceGpu& g, GpuBytes& out);

} // namespace kw
