// Exact pass: depth pre-pass of the base polygons, then per-fragment evaluation with GL_EQUAL
// (or one pass writing gl_FragDepth when options.shading is ExactDepth).
#include "render/exact_surface_pass.h"

#include "render/shading_uniforms.h"

#include <QOpenGLShaderProgram>
#include <algorithm>
#include <cstdlib>
#include <glm/gtc/type_ptr.hpp>
#include <limits>

namespace kw {

namespace {
constexpr int kTrimMaskUnit = 3;    // the mask array (TrimMaskPass::bindArray)
constexpr int kEnvironmentUnit = 4; // analysis.glsl's uEnvironment

const TrimMask* maskOf(const SurfaceRecord& r) {
    return r.mask.active && r.mask.layer >= 0 ? &r.mask : nullptr;
}

double gatherMinCellPixels() {
    if (const char* e = std::getenv("KW_GATHER_MIN_CELL_PX"))
        return std::atof(e);
    return ExactSurfacePass::kGatherMinCellPixels;
}
/// One surface's base polygon triangles, its table row selected by the base instance.
void drawSurface(QOpenGLFunctions_4_5_Core* gl, const SurfaceRecord& r) {
    const SurfaceGpu& g = *r.exact;
    gl->glDrawElementsInstancedBaseVertexBaseInstance(
        GL_TRIANGLES, g.triangleIndexCount, GL_UNSIGNED_INT,
        reinterpret_cast<const void*>(g.triangleOffset * std::int64_t(sizeof(unsigned))), 1,
        GLint(g.vertexOffset), GLuint(r.slot));
}

} // namespace

double ExactSurfacePass::projectedPixelsPerCell(const SurfaceGpu& g, const FrameCamera& camera) {
    const int cells = g.polygon.cellCount();
    if (g.control.empty() || cells <= 0)
        return 0.0;
    // Bounding box of the control points (convex hull property: it holds the surface).
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (const glm::vec4& t : g.control) {
        if (!(t.w > 0.0f))
            continue;
        const glm::vec3 p = glm::vec3(t) / t.w;
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    if (lo.x > hi.x)
        return 0.0;
    const glm::vec3 o(g.origin);
    glm::vec2 smin(std::numeric_limits<float>::max()), smax(-std::numeric_limits<float>::max());
    for (int k = 0; k < 8; ++k) {
        const glm::vec3 c(k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z);
        const glm::vec4 clip = camera.viewProjection * glm::vec4(c + o, 1.0f);
        if (!(clip.w > 0.0f)) // a corner behind the eye: treat the surface as large
            return std::numeric_limits<double>::infinity();
        const glm::vec2 ndc = glm::vec2(clip) / clip.w;
        smin = glm::min(smin, ndc);
        smax = glm::max(smax, ndc);
    }
    smin = glm::clamp(smin, glm::vec2(-1.0f), glm::vec2(1.0f));
    smax = glm::clamp(smax, glm::vec2(-1.0f), glm::vec2(1.0f));
    const glm::vec2 extent =
        glm::max(smax - smin, glm::vec2(0.0f)) * 0.5f * glm::vec2(camera.viewport);
    return double(extent.x) * double(extent.y) / double(cells);
}

void ExactSurfacePass::initialize(QOpenGLFunctions_4_5_Core* gl, ShaderLibrary* shaders) {
    m_gl = gl;
    m_shaders = shaders;
    m_environment.initialize(gl);
}

QStringList ExactSurfacePass::variantDefines(int p, int q, int lightCount,
                                             const RenderOptions& options, bool trimmed,
                                             bool gatherAllowed) {
    QStringList d{QStringLiteral("DEGREE_U %1").arg(p), QStringLiteral("DEGREE_V %1").arg(q),
                  QStringLiteral("LIGHT_COUNT %1").arg(lightCount)};
    // Per-cell gather when the cell's control texels and span rows fit the 32 varying
    // vectors next to vUv, vSpan and vSpanScale (bicubic: 16 + 3 + 3).
    if (gatherAllowed && (p + 1) * (q + 1) + spanTableTexels(p) + spanTableTexels(q) <= 28)
        d << QStringLiteral("KW_CELL_GATHER");
    if (options.writeAov)
        d << QStringLiteral("KW_AOV");
    if (options.shading == RenderOptions::Shading::ExactDepth)
        d << QStringLiteral("KW_EXACT_DEPTH");
    if (trimmed)
        d << QStringLiteral("KW_TRIM");
    d << analysisDefines(options.analysis, options.writeCurvatureAov);
    return d;
}

bool ExactSurfacePass::depthPrepass(const GpuScene& scene, bool trims, const FrameCamera& camera,
                                    QString* error) {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    // Untrimmed surfaces keep the empty fragment shader (early depth); trimmed ones discard.
    QOpenGLShaderProgram* plain =
        m_shaders->program(QStringLiteral("surface.vert"), QStringLiteral("depth_only.frag"));
    if (!plain) {
        *error = m_shaders->lastError();
        return false;
    }
    gl->glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    gl->glDepthMask(GL_TRUE);
    gl->glDepthFunc(GL_LESS);
    QOpenGLShaderProgram* bound = nullptr;
    bool ok = true;
    const TrimMaskPass& masks = scene.trimMasks();
    scene.bindSurfaceData();
    for (const SurfaceRecord* r : scene.records()) {
        const SurfaceGpu* g = r->exact.get();
        if (!g)
            continue;
        const TrimMask* mask = trims ? maskOf(*r) : nullptr;
        QOpenGLShaderProgram* prog = mask ? m_shaders->program(QStringLiteral("surface.vert"),
                                                               QStringLiteral("depth_only.frag"),
                                                               {QStringLiteral("KW_TRIM")})
                                          : plain;
        if (!prog) {
            *error = m_shaders->lastError();
            ok = false;
            break;
        }
        if (prog != bound) {
            prog->bind();
            bound = prog;
            gl->glUniformMatrix4fv(ShaderLibrary::uniforms(prog).viewProjection, 1, GL_FALSE,
                                   glm::value_ptr(camera.viewProjection));
            if (mask)
                masks.bindArray(prog, kTrimMaskUnit);
        }
        drawSurface(gl, *r);
        ++drawCalls;
    }
    gl->glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    return ok;
}

bool ExactSurfacePass::draw(const GpuScene& scene, bool trims, const FrameCamera& camera,
                            const std::vector<Light>& lights, const RenderOptions& options,
                            const ValueRange& range, QString* error) {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    if (options.analysis.mode == AnalysisMode::Environment &&
        !m_environment.bind(options.analysis.environmentMap, kEnvironmentUnit, error))
        return false;
    // Each cell's triangles start at the vertex that carries the cell's span (BasePolygon).
    // Set for the pre-pass too: llvmpipe orders the vertices by it when it sets up a
    // triangle, and GL_EQUAL needs bit-identical depths.
    gl->glProvokingVertex(GL_FIRST_VERTEX_CONVENTION);
    if (options.shading == RenderOptions::Shading::DepthPrepass) {
        if (!depthPrepass(scene, trims, camera, error)) {
            gl->glProvokingVertex(GL_LAST_VERTEX_CONVENTION);
            return false;
        }
        gl->glDepthFunc(GL_EQUAL);
        gl->glDepthMask(GL_FALSE);
    } else {
        gl->glDepthFunc(GL_LESS);
        gl->glDepthMask(GL_TRUE);
    }
    QOpenGLShaderProgram* bound = nullptr;
    bool ok = true;
    const double minCellPixels = gatherMinCellPixels();
    const TrimMaskPass& masks = scene.trimMasks();
    scene.bindSurfaceData();
    for (const SurfaceRecord* r : scene.records()) {
        const SurfaceGpu* g = r->exact.get();
        if (!g)
            continue;
        // With the depth pre-pass, a trimmed fragment left no depth there, so GL_EQUAL
        // rejects it before shading and early-z stays on: no lookup needed here. A discard
        // in this shader costs llvmpipe 5x (docs/PERFORMANCE.md, ## Trims), so only the
        // exact-depth way, which has no pre-pass, looks the mask up.
        const TrimMask* mask =
            trims && options.shading == RenderOptions::Shading::ExactDepth ? maskOf(*r) : nullptr;
        // The gather pays only where a cell covers many fragments: on small cells its flat
        // varyings cost llvmpipe's triangle setup more than the fetches it saves.
        const bool gather = projectedPixelsPerCell(*g, camera) >= minCellPixels;
        QOpenGLShaderProgram* prog =
            m_shaders->program(QStringLiteral("surface.vert"), QStringLiteral("exact_surface.frag"),
                               variantDefines(g->degreeU, g->degreeV, int(lights.size()), options,
                                              mask != nullptr, gather));
        if (!prog) {
            *error = m_shaders->lastError();
            ok = false;
            break;
        }
        if (prog != bound) {
            prog->bind();
            bound = prog;
            setFrameUniforms(gl, prog, camera, lights);
            setAnalysisUniforms(gl, prog, options.analysis, range, camera, lights,
                                kEnvironmentUnit);
            if (mask)
                masks.bindArray(prog, kTrimMaskUnit);
        }
        drawSurface(gl, *r);
        ++drawCalls;
    }
    gl->glProvokingVertex(GL_LAST_VERTEX_CONVENTION);
    gl->glDepthFunc(GL_LESS);
    gl->glDepthMask(GL_TRUE);
    return ok;
}

} // namespace kw
