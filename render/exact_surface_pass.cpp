// Exact pass: depth pre-pass of the base polygons, then per-fragment evaluation with GL_EQUAL
// (or one pass writing gl_FragDepth when options.shading is ExactDepth).
#include "render/exact_surface_pass.h"

#include "render/depth_convention.h"
#include "render/exact_contract.h"
#include "render/partial_cells.h"
#include "render/partial_frame.h"
#include "render/shading_uniforms.h"
#include "render/thread_clock.h"

#include <QOpenGLShaderProgram>
#include <algorithm>
#include <glm/gtc/type_ptr.hpp>
#include <map>

namespace kw {

namespace {
// The deferred pass's pre-pass writes its texture (kPrepassUnit) at this colour attachment of
// the frame's framebuffer, the last of the 8 every GL 4.5 context has.
constexpr int kPrepassAttachment = 7;
} // namespace

void ExactSurfacePass::initialize(QOpenGLFunctions_4_5_Core* gl, ShaderLibrary* shaders) {
    m_gl = gl;
    m_shaders = shaders;
    m_environment.initialize(gl);
}

ExactVariant ExactSurfacePass::variant(int p, int q, int lightCount, const RenderOptions& options,
                                       bool trimmed, bool gatherAllowed, TrimAa trimAa, bool skirt,
                                       bool affine, bool analytic) {
    ExactVariant v{p, q, lightCount, options.analysis.mode,
                   analysisFeatures(options.analysis, options.writeCurvatureAov)};
    ExactFeatures& f = v.features;
    // Per-cell gather when the cell's control texels and span rows fit the 32 varying
    // vectors next to vUv, vSpan and vSpanScale (bicubic: 16 + 3 + 3).
    f.setFlag(ExactFeature::CellGather,
              !skirt && gatherAllowed &&
                  (p + 1) * (q + 1) + spanTableTexels(p) + spanTableTexels(q) <= 28);
    f.setFlag(ExactFeature::Aov, options.writeAov);
    f.setFlag(ExactFeature::Skirt, skirt);
    f.setFlag(ExactFeature::ExactDepth,
              !skirt && options.shading == RenderOptions::Shading::ExactDepth);
    // Adaptive partitions guarantee the polygon's (u, v) starts Newton's method within the
    // pixel tolerance of the point under the pixel; uniform mode stays the paper's. An affine
    // surface's polygon puts the point under the pixel there already.
    f.setFlag(ExactFeature::RayNewton,
              options.partitioning == RenderOptions::Partitioning::Adaptive && !skirt && !affine);
    f.setFlag(ExactFeature::Trim, trimmed);
    f.setFlag(ExactFeature::TrimExact,
              trimmed && options.trimMode == RenderOptions::TrimMode::Exact);
    f.setFlag(ExactFeature::TrimAa, trimmed && trimAa != TrimAa::Off);
    f.setFlag(ExactFeature::TrimEdge, trimmed && trimAa == TrimAa::Edge);
    f.setFlag(ExactFeature::Section, !options.sections.empty());
    // The closed form replaces the Newton step: only where that step is taken.
    f.setFlag(ExactFeature::Analytic, analytic && f.testFlag(ExactFeature::RayNewton));
    if (f.testFlag(ExactFeature::Analytic))
        f.setFlag(ExactFeature::CellGather, false);
    return v;
}

void ExactSurfacePass::uploadCommands(bool rebuilt,
                                      const std::vector<ExactPlanner::CommandWrite>& writes) {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    if (!rebuilt) {
        for (const ExactPlanner::CommandWrite& w : writes)
            gl->glNamedBufferSubData(m_commands,
                                     GLintptr(w.at * std::int64_t(sizeof(IndirectCommand))),
                                     GLsizeiptr(sizeof(IndirectCommand)), &w.command);
        if (m_commands)
            gl->glBindBuffer(GL_DRAW_INDIRECT_BUFFER, m_commands);
        return;
    }
    const std::vector<IndirectCommand>& all = m_plan.commands();
    const std::int64_t bytes = std::int64_t(all.size() * sizeof(IndirectCommand));
    if (bytes == 0) {
        releaseCommands(); // no surface: no buffer (the empty scene's bytes)
        return;
    }
    if (bytes > m_commandBytes) {
        releaseCommands();
        m_commandBytes = std::max<std::int64_t>(bytes, 2 * m_commandBytes);
        gl->glCreateBuffers(1, &m_commands);
        gl->glNamedBufferData(m_commands, GLsizeiptr(m_commandBytes), nullptr, GL_DYNAMIC_DRAW);
    }
    gl->glNamedBufferSubData(m_commands, 0, GLsizeiptr(bytes), all.data());
    gl->glBindBuffer(GL_DRAW_INDIRECT_BUFFER, m_commands);
}

void ExactSurfacePass::releaseCommands() {
    if (m_commands && m_gl)
        m_gl->glDeleteBuffers(1, &m_commands);
    m_commands = 0;
    m_commandBytes = 0;
}

void ExactSurfacePass::drawBatch(const ExactBatch& batch, bool otherSide) {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    if (const GLenum cull = cullFaceOf(batch.face); cull != 0) {
        gl->glEnable(GL_CULL_FACE);
        gl->glCullFace(otherSide ? (cull == GL_BACK ? GL_FRONT : GL_BACK) : cull);
    } else {
        gl->glDisable(GL_CULL_FACE);
    }
    if (firstDrawCpuMs < 0.0 && !batch.commands.empty())
        firstDrawCpuMs = threadCpuMs();
    if (m_multiDraw) {
        gl->glMultiDrawElementsIndirect(
            GL_TRIANGLES, GL_UNSIGNED_INT,
            reinterpret_cast<const void*>(batch.first * std::int64_t(sizeof(IndirectCommand))),
            GLsizei(batch.commands.size()), 0);
        ++drawCalls;
        return;
    }
    for (const IndirectCommand& c : batch.commands) {
        gl->glDrawElementsInstancedBaseVertexBaseInstance(
            GL_TRIANGLES, GLsizei(c.count), GL_UNSIGNED_INT,
            reinterpret_cast<const void*>(std::uintptr_t(c.firstIndex) * sizeof(unsigned)), 1,
            c.baseVertex, c.baseInstance);
        ++drawCalls;
    }
}

Status ExactSurfacePass::depthPrepass(const std::map<int, ExactBatch>& plain,
                                      const std::map<int, ExactBatch>& trimmed,
                                      const GpuScene& scene, const FrameCamera& camera,
                                      const std::vector<Light>& lights, bool antialiased,
                                      bool atRay, bool deferred) {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    // The pre-pass's programs test the trims of the frame's mode and, with the deferred pass,
    // write its input.
    ExactFeatures trimFeatures = scene.trimMasks().trimFeatures();
    trimFeatures.setFlag(ExactFeature::TrimAa, antialiased);
    const ExactFeatures output = deferred ? ExactFeatures(ExactFeature::GBuffer) : ExactFeatures();
    if (!deferred)
        gl->glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    gl->glDepthMask(GL_TRUE);
    gl->glDepthFunc(kDepthNearer);
    std::vector<const ExactBatch*> batches;
    for (const auto& [k, b] : plain)
        batches.push_back(&b);
    for (const auto& [k, b] : trimmed)
        batches.push_back(&b);
    Status drawn;
    // Untrimmed surfaces keep the empty fragment shader (early depth); trimmed ones discard.
    for (const ExactBatch* b : batches) {
        if (b->commands.empty())
            continue;
        const bool onRay = b->trimmed && atRay && !b->affine;
        const ExactFeatures trims = b->trimmed ? trimFeatures : ExactFeatures();
        ExactVariant v =
            onRay ? ExactVariant{b->degreeU, b->degreeV, int(lights.size()), AnalysisMode::Phong,
                                 ExactFeature::RayNewton | ExactFeature::DepthOnly | trims | output}
                  : ExactVariant{0, 0, 1, AnalysisMode::Phong, trims | output};
        v.features.setFlag(ExactFeature::Analytic, onRay && b->analytic);
        const Expected<QOpenGLShaderProgram*> built = m_shaders->program(
            QStringLiteral("surface.vert"),
            onRay ? QStringLiteral("exact_surface.frag") : QStringLiteral("depth_only.frag"),
            v.defines());
        if (!built) {
            drawn = built.error();
            break;
        }
        QOpenGLShaderProgram* prog = *built;
        prog->bind();
        if (onRay)
            setFrameUniforms(gl, prog, camera, lights);
        else
            gl->glUniformMatrix4fv(ShaderLibrary::uniforms(prog).viewProjection, 1, GL_FALSE,
                                   glm::value_ptr(drawnViewProjection(camera)));
        if (b->trimmed)
            scene.trimMasks().bindArray(prog, kTrimMaskUnit);
        // A stencil write with a discard in the shader would move llvmpipe's depth test after
        // the shader: the trimmed batches write theirs in a second pass below.
        if (deferred && b->trimmed)
            gl->glDisable(GL_STENCIL_TEST);
        else if (deferred)
            gl->glStencilFunc(GL_ALWAYS, m_plan.stencilOf(*b), 0xff);
        // The forward pass's surfaces (no route) write the same words, which the deferred
        // pass skips (ExactPlanner::kForwardStencil) and a pick reads (pickInLastFrame).
        if (deferred)
            gl->glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        drawBatch(*b);
        if (deferred && b->trimmed)
            gl->glEnable(GL_STENCIL_TEST);
    }
    if (drawn && deferred && !trimmed.empty()) {
        // The trimmed batches' stencil: drawn again without the trim test, on the pixels
        // whose depth they left (GL_EQUAL before the shader: early).
        const Expected<QOpenGLShaderProgram*> built = m_shaders->program(
            QStringLiteral("surface.vert"), QStringLiteral("depth_only.frag"), {});
        if (!built) {
            drawn = built.error();
        } else {
            QOpenGLShaderProgram* prog = *built;
            prog->bind();
            gl->glUniformMatrix4fv(ShaderLibrary::uniforms(prog).viewProjection, 1, GL_FALSE,
                                   glm::value_ptr(drawnViewProjection(camera)));
            gl->glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
            gl->glDepthFunc(GL_EQUAL);
            gl->glDepthMask(GL_FALSE);
            for (const auto& [k, b] : trimmed) {
                if (b.commands.empty())
                    continue;
                gl->glStencilFunc(GL_ALWAYS, m_plan.stencilOf(b), 0xff);
                drawBatch(b);
            }
            gl->glDepthFunc(kDepthNearer);
            gl->glDepthMask(GL_TRUE);
        }
    }
    gl->glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    return drawn;
}

Status ExactSurfacePass::draw(const GpuScene& scene, bool trims, const FrameCamera& camera,
                              const std::vector<Light>& lights, const RenderOptions& options,
                              const ValueRange& range, AntialiasTarget* aa) {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    m_multiDraw = options.multiDraw;
    if (analysisParameters(options.analysis.mode) == AnalysisParameters::Environment)
        if (Status bound = m_environment.bind(options.analysis.environmentMap, kEnvironmentUnit);
            !bound)
            return bound;
    const bool prepass = options.shading == RenderOptions::Shading::DepthPrepass;
    const bool adaptive = options.partitioning == RenderOptions::Partitioning::Adaptive;
    // The deferred exact pass: each pixel shaded once however small the cells (docs/
    // RENDERING.md, "The deferred exact pass"). The pre-pass's batches are then split by route.
    glm::ivec2 targetSize{0};
    const bool deferredWanted = options.deferredPass && prepass && aa == nullptr && adaptive &&
                                (targetSize = deferredTargetSize()) != glm::ivec2(0);
    const ExactPlanScene planScene{&scene,
                                   scene.layoutStamp(),
                                   scene.marksRevision(),
                                   &scene.records(),
                                   &scene.touched(),
                                   [&scene](int solid) {
                                       return scene.solidMembers(solid);
                                   }};
    const ExactPlanKey key =
        ExactPlanner::keyFor(planScene, camera, options, trims, aa != nullptr, deferredWanted);
    std::vector<ExactPlanner::CommandWrite> writes;
    uploadCommands(m_plan.update(planScene, key, camera, writes), writes);
    culled += m_plan.culled();
    solidsBackCulled += int(m_plan.backCulled().size());
    // What the pre-pass tests the trims on, and what the split leaves out (per frame: the
    // batches may have been patched).
    trimTestedCells = prepass ? m_plan.trimTestedCells() : 0;
    trimmedAwayCells = prepass ? m_plan.trimmedAwayCells() : 0;
    affineSurfaces = m_plan.affineSurfaces();
    analyticSurfaces = m_plan.analyticSurfaces();
    coverSurfaces = m_plan.coverSurfaces();
    const std::map<int, ExactBatch>& variants = m_plan.variants();
    if (variants.empty() && m_plan.sections().empty())
        return ok(); // nothing to draw (covers are drawn by the section pass alone)

    scene.bindSurfaceData();
    // Each cell's triangles start at the vertex that carries the cell's span (BasePolygon).
    // Set for the pre-pass too: llvmpipe orders the vertices by it when it sets up a
    // triangle, and GL_EQUAL needs bit-identical depths.
    gl->glProvokingVertex(GL_FIRST_VERTEX_CONVENTION);
    Status drawn;
    // One stencil value per route, 1..254 (0: no surface, 255: the forward pass's surfaces);
    // none when every surface has large
    // cells (a close-up): then the forward way alone, without the deferred pass's set-up.
    const bool defer = deferredWanted && !m_plan.routes().empty() &&
                       m_plan.routes().size() < std::size_t(ExactPlanner::kForwardStencil);
    deferredSurfaces = defer ? m_plan.deferredSurfaces() : 0;
    // A frame that could defer but has nothing to (a close-up of large cells) gives the input
    // texture back: 16 bytes a pixel held for nothing (docs/PERFORMANCE.md ### Close-up). This
    // frame leaves no input to read (Renderer::pickInLastFrame forgets it), and the next
    // deferred frame makes the texture again.
    if (deferredWanted && !defer && m_prepassTexture)
        releaseDeferred();
    std::vector<GLenum> drawBuffers; // the frame's, while the pre-pass writes its texture
    const auto mark = [this](PassTimes::Pass pass) {
        if (clock)
            clock->mark(pass);
    };
    mark(PassTimes::Sync); // the plan and its commands
    if (defer)
        drawBuffers = attachPrepassTexture(targetSize);
    if (prepass) {
        drawn = depthPrepass(m_plan.plain(), m_plan.trimmedPrepass(), scene, camera, lights,
                             aa != nullptr, aa == nullptr && adaptive, defer);
        mark(PassTimes::Prepass);
        gl->glDepthFunc(GL_EQUAL);
        gl->glDepthMask(GL_FALSE);
    } else {
        gl->glDepthFunc(kDepthNearer);
        gl->glDepthMask(GL_TRUE);
    }
    if (defer) {
        detachPrepassTexture(drawBuffers);
        if (drawn)
            drawn = deferredPass(scene, camera, lights, options, range);
        gl->glDisable(GL_STENCIL_TEST);
        scene.bindSurfaceData();
        // The surfaces with large cells (no route) the forward way, on the pre-pass's depth.
        if (drawn)
            drawn = drawBatches(variants, TrimAa::Off, scene, camera, lights, options, range, true);
    } else if (drawn) {
        drawn = drawBatches(variants, aa ? TrimAa::Opaque : TrimAa::Off, scene, camera, lights,
                            options, range);
    }
    sectionCrossedCells = m_plan.sectionCells();
    mark(PassTimes::Exact);
    if (drawn && !m_plan.sections().empty())
        drawn = sectionPass(scene, camera, lights, options, range);
    mark(PassTimes::Sections);
    finTriangles = 0;
    if (drawn && !m_plan.skirts().empty())
        drawn = skirtPass(scene, camera, lights, options, range);
    mark(PassTimes::Fins); // skirtPass marked its skirts
    if (drawn && !m_plan.backFaces().empty())
        drawn = backFacePass(scene, camera, lights, options, range);
    mark(PassTimes::BackFaces);
    if (drawn && aa && !m_plan.edges().empty())
        drawn = edgePass(scene, camera, lights, options, range, *aa);
    mark(PassTimes::TrimEdges);
    gl->glDisable(GL_CULL_FACE);
    gl->glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    gl->glProvokingVertex(GL_LAST_VERTEX_CONVENTION);
    gl->glDepthFunc(kDepthNearer);
    gl->glDepthMask(GL_TRUE);
    return drawn;
}

Expected<QOpenGLShaderProgram*>
ExactSurfacePass::bindExactProgram(const ExactVariant& v, bool trimmed, const GpuScene& scene,
                                   const FrameCamera& camera, const std::vector<Light>& lights,
                                   const RenderOptions& options, const ValueRange& range,
                                   const QString& vertexShader) {
    const Expected<QOpenGLShaderProgram*> built =
        m_shaders->program(vertexShader, QStringLiteral("exact_surface.frag"), v.defines());
    if (!built)
        return built;
    QOpenGLShaderProgram* prog = *built;
    prog->bind();
    setFrameUniforms(m_gl, prog, camera, lights);
    setAnalysisUniforms(m_gl, prog, options.analysis, range, camera, lights, kEnvironmentUnit);
    setSectionUniforms(m_gl, prog, options);
    if (trimmed)
        scene.trimMasks().bindArray(prog, kTrimMaskUnit);
    return prog;
}

Status ExactSurfacePass::drawBatches(const std::map<int, ExactBatch>& batches, TrimAa trimAa,
                                     const GpuScene& scene, const FrameCamera& camera,
                                     const std::vector<Light>& lights, const RenderOptions& options,
                                     const ValueRange& range, bool largeCellsOnly) {
    for (const auto& [key, b] : batches) {
        if ((largeCellsOnly && !((key >> 13) & 1)) || b.commands.empty())
            continue; // empty: a partial frame's surfaces sent none of their cells here
        ExactVariant v = variant(b.degreeU, b.degreeV, int(lights.size()), options, b.trimmed,
                                 b.gather, trimAa, false, b.affine, b.analytic);
        if (!b.section) // cells every plane keeps, no solid to cap (ExactBatch::section)
            v.features.setFlag(ExactFeature::Section, false);
        v.features.setFlag(ExactFeature::Cover,
                           b.cover && v.features.testFlag(ExactFeature::Analytic));
        const Expected<QOpenGLShaderProgram*> built =
            bindExactProgram(v, b.trimmed, scene, camera, lights, options, range);
        if (!built)
            return built.error();
        if (v.features.testFlag(ExactFeature::Cover)) // the skirts' overlap past the edges
            m_gl->glUniform1f(ShaderLibrary::uniforms(*built).skirtReach, kSkirtReachPixels);
        drawBatch(b);
    }
    return ok();
}

Status ExactSurfacePass::sectionPass(const GpuScene& scene, const FrameCamera& camera,
                                     const std::vector<Light>& lights, const RenderOptions& options,
                                     const ValueRange& range) {
    // Their exact point decides both the cut and the depth: a fragment in front of the kept
    // cells' (pre-pass) depth replaces them, one the planes remove leaves what lies behind.
    // Their pixels' stencil goes to 0: the pre-pass data under them is the kept cells' behind
    // (Renderer::pickInLastFrame then draws the pixel). gl_FragDepth already keeps llvmpipe's
    // depth test after the shader, so the stencil write costs no early test.
    m_gl->glDepthFunc(kDepthNearer);
    m_gl->glDepthMask(GL_TRUE);
    m_gl->glEnable(GL_STENCIL_TEST);
    m_gl->glStencilFunc(GL_ALWAYS, 0, 0xff);
    m_gl->glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    RenderOptions exactDepth = options;
    exactDepth.shading = RenderOptions::Shading::ExactDepth;
    const Status drawn =
        drawBatches(m_plan.sections(), TrimAa::Off, scene, camera, lights, exactDepth, range);
    m_gl->glDisable(GL_STENCIL_TEST);
    return drawn;
}

Status ExactSurfacePass::backFacePass(const GpuScene& scene, const FrameCamera& camera,
                                      const std::vector<Light>& lights,
                                      const RenderOptions& options, const ValueRange& range) {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    // Last, tested nearer before the shader (KW_BACK_FILL) and writing no depth: the solid's
    // faces in front (and their skirts) reject nearly every fragment unshaded, so what is
    // shaded is the seams' slivers, where two faces' exact trims miss each other by a
    // fraction of a pixel and nothing else covered the pixel centre. Of two back faces in one
    // sliver the later shows (both are the solid's inside). The forward programs test the
    // trims themselves (no pre-pass covers these triangles); the polygon's depth is tested.
    gl->glDepthFunc(kDepthNearer);
    gl->glDepthMask(GL_FALSE);
    Status drawn;
    for (const auto& [key, b] : m_plan.backFaces()) {
        if (b.commands.empty())
            continue;
        ExactVariant v = variant(b.degreeU, b.degreeV, int(lights.size()), options, b.trimmed,
                                 false, TrimAa::Off, false, b.affine, b.analytic);
        v.features.setFlag(ExactFeature::ExactDepth, false);
        v.features |= ExactFeature::BackFill;
        if (const Expected<QOpenGLShaderProgram*> built =
                bindExactProgram(v, b.trimmed, scene, camera, lights, options, range);
            !built) {
            drawn = built.error();
            break;
        }
        drawBatch(b, true);
    }
    gl->glDepthMask(GL_TRUE);
    return drawn;
}

glm::ivec2 ExactSurfacePass::deferredTargetSize() const {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    GLint framebuffer = 0, attachments = 0;
    gl->glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &framebuffer);
    gl->glGetIntegerv(GL_MAX_COLOR_ATTACHMENTS, &attachments);
    if (framebuffer == 0 || attachments <= kPrepassAttachment)
        return glm::ivec2(0);
    const auto attachment = [&](GLenum point, GLenum what) {
        GLint v = 0;
        gl->glGetNamedFramebufferAttachmentParameteriv(GLuint(framebuffer), point, what, &v);
        return v;
    };
    if (attachment(GL_STENCIL_ATTACHMENT, GL_FRAMEBUFFER_ATTACHMENT_STENCIL_SIZE) < 8 ||
        attachment(GL_DEPTH_ATTACHMENT, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE) != GL_TEXTURE ||
        attachment(GL_COLOR_ATTACHMENT0 + GLenum(kPrepassAttachment),
                   GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE) != GL_NONE)
        return glm::ivec2(0);
    // The pre-pass's texture covers the depth texture: a smaller one would shrink the
    // framebuffer's drawable area to it.
    const GLuint depth =
        GLuint(attachment(GL_DEPTH_ATTACHMENT, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME));
    GLint width = 0, height = 0, samples = 0;
    gl->glGetTextureLevelParameteriv(depth, 0, GL_TEXTURE_WIDTH, &width);
    gl->glGetTextureLevelParameteriv(depth, 0, GL_TEXTURE_HEIGHT, &height);
    gl->glGetTextureLevelParameteriv(depth, 0, GL_TEXTURE_SAMPLES, &samples);
    if (samples > 1 || width <= 0 || height <= 0)
        return glm::ivec2(0);
    return glm::ivec2(width, height);
}

std::vector<GLenum> ExactSurfacePass::attachPrepassTexture(glm::ivec2 size) {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    if (m_prepassSize != size) {
        releaseDeferred();
        gl->glCreateTextures(GL_TEXTURE_2D, 1, &m_prepassTexture);
        gl->glTextureStorage2D(m_prepassTexture, 1, GL_RGBA32UI, size.x, size.y);
        // An integer texture is complete only with nearest filtering.
        gl->glTextureParameteri(m_prepassTexture, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        gl->glTextureParameteri(m_prepassTexture, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        m_prepassSize = size;
    }
    ++m_prepassWrites;
    GLint framebuffer = 0, count = 0;
    gl->glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &framebuffer);
    gl->glGetIntegerv(GL_MAX_DRAW_BUFFERS, &count);
    std::vector<GLenum> drawBuffers;
    for (int k = 0; k < count; ++k) {
        GLint b = GL_NONE;
        gl->glGetIntegerv(GL_DRAW_BUFFER0 + GLenum(k), &b);
        drawBuffers.push_back(GLenum(b));
    }
    while (!drawBuffers.empty() && drawBuffers.back() == GL_NONE)
        drawBuffers.pop_back();
    // The pre-pass's output is the framebuffer's only draw buffer.
    GLenum only[kPrepassOutput + 1] = {};
    only[kPrepassOutput] = GL_COLOR_ATTACHMENT0 + GLenum(kPrepassAttachment);
    gl->glNamedFramebufferTexture(GLuint(framebuffer), only[kPrepassOutput], m_prepassTexture, 0);
    gl->glNamedFramebufferDrawBuffers(GLuint(framebuffer), kPrepassOutput + 1, only);
    const GLint zero = 0;
    gl->glStencilMask(0xff);
    gl->glClearBufferiv(GL_STENCIL, 0, &zero);
    gl->glEnable(GL_STENCIL_TEST);
    gl->glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    return drawBuffers;
}

void ExactSurfacePass::detachPrepassTexture(const std::vector<GLenum>& drawBuffers) {
    GLint framebuffer = 0;
    m_gl->glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &framebuffer);
    m_gl->glNamedFramebufferTexture(GLuint(framebuffer),
                                    GL_COLOR_ATTACHMENT0 + GLenum(kPrepassAttachment), 0, 0);
    m_gl->glNamedFramebufferDrawBuffers(GLuint(framebuffer), GLsizei(drawBuffers.size()),
                                        drawBuffers.data());
}

void ExactSurfacePass::releaseDeferred() {
    if (m_gl) {
        if (m_prepassTexture)
            m_gl->glDeleteTextures(1, &m_prepassTexture);
        if (m_emptyVao)
            m_gl->glDeleteVertexArrays(1, &m_emptyVao);
        if (m_vertexPoolView)
            m_gl->glDeleteTextures(1, &m_vertexPoolView);
    }
    m_prepassTexture = m_emptyVao = m_vertexPoolView = 0;
    m_prepassSize = glm::ivec2(0);
}

ExactVariant ExactSurfacePass::deferredVariant(int route, int lightCount,
                                               const RenderOptions& options) {
    ExactVariant v = variant(route & 15, (route >> 4) & 15, lightCount, options, false, false,
                             TrimAa::Off, false, (route >> 12) & 1, (route >> 14) & 1);
    v.features |= ExactFeature::Deferred;
    if (!((route >> 15) & 1)) // no section test: ExactBatch::section
        v.features.setFlag(ExactFeature::Section, false);
    return v;
}

Status ExactSurfacePass::deferredPass(const GpuScene& scene, const FrameCamera& camera,
                                      const std::vector<Light>& lights,
                                      const RenderOptions& options, const ValueRange& range) {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    // Each pixel's colour once: no depth test (the pre-pass left the depth), the stencil test
    // before the shader keeps the route's pixels, and llvmpipe skips a block of pixels none of
    // which passes it.
    gl->glDisable(GL_DEPTH_TEST);
    gl->glDisable(GL_CULL_FACE);
    gl->glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    // No stencil write either: llvmpipe moves the stencil test after a shader that may discard
    // (the section test's cut) whenever the stencil's write mask is not 0, and then shaded
    // every pixel of the route's window, background included (4x the cut sphere's exact pass).
    gl->glStencilMask(0);
    if (!m_emptyVao)
        gl->glCreateVertexArrays(1, &m_emptyVao);
    gl->glBindVertexArray(m_emptyVao);
    gl->glBindTextureUnit(kPrepassUnit, m_prepassTexture);
    if (!m_vertexPoolView)
        gl->glCreateTextures(GL_TEXTURE_BUFFER, 1, &m_vertexPoolView);
    // Every frame: the pool's buffer is renamed when it grows (as GpuScene's views).
    gl->glTextureBuffer(m_vertexPoolView, GL_RGBA32UI, scene.pools().vertices.buffer());
    gl->glBindTextureUnit(kVertexPoolUnit, m_vertexPoolView);
    Status drawn;
    const GLboolean scissored = gl->glIsEnabled(GL_SCISSOR_TEST);
    GLint scissor[4] = {0, 0, 0, 0};
    gl->glGetIntegerv(GL_SCISSOR_BOX, scissor);
    gl->glEnable(GL_SCISSOR_TEST);
    GLint view[4] = {0, 0, 0, 0};
    gl->glGetIntegerv(GL_VIEWPORT, view);
    const glm::vec2 origin(view[0], view[1]), size(view[2], view[3]);
    for (const auto& [route, r] : m_plan.routes()) {
        // The route's window in pixels, a pixel more on each side (rounding, and the
        // polygon's pixel centres).
        glm::ivec2 lo(glm::floor(origin + (glm::vec2(r.window) * 0.5f + 0.5f) * size) - 1.0f);
        glm::ivec2 hi(glm::ceil(origin + (glm::vec2(r.window.z, r.window.w) * 0.5f + 0.5f) * size) +
                      1.0f);
        if (scissored) { // within the frame's own scissor (a pick's pixel, a partial frame's)
            lo = glm::max(lo, glm::ivec2(scissor[0], scissor[1]));
            hi = glm::min(hi, glm::ivec2(scissor[0] + scissor[2], scissor[1] + scissor[3]));
        }
        if (hi.x <= lo.x || hi.y <= lo.y)
            continue;
        if (const Expected<QOpenGLShaderProgram*> built = bindExactProgram(
                deferredVariant(route, int(lights.size()), options), false, scene, camera, lights,
                options, range, QStringLiteral("aa_composite.vert"));
            !built) {
            drawn = built.error();
            break;
        }
        gl->glStencilFunc(GL_EQUAL, r.stencil, 0xff);
        // The route's rectangle only: llvmpipe bins nothing outside the scissor.
        gl->glScissor(lo.x, lo.y, hi.x - lo.x, hi.y - lo.y);
        gl->glDrawArrays(GL_TRIANGLES, 0, 3);
        ++drawCalls;
    }
    gl->glScissor(scissor[0], scissor[1], scissor[2], scissor[3]);
    if (!scissored)
        gl->glDisable(GL_SCISSOR_TEST);
    gl->glBindTextureUnit(kVertexPoolUnit, 0);
    gl->glBindTextureUnit(kPrepassUnit, 0);
    gl->glStencilMask(0xff);
    gl->glEnable(GL_DEPTH_TEST);
    return drawn;
}

float ExactSurfacePass::skirtDepthScale(const FrameCamera& camera) {
    // A pixel spans distance * 2 / (P[1][1] * height) of world at that distance; pushing the
    // distance by k of those scales near / distance by 1 / (1 + 2 k / (P[1][1] * height)).
    const float focal = camera.projection[1][1] * 0.5f * float(std::max(camera.viewport.y, 1));
    return focal > 0.0f ? 1.0f / (1.0f + kSkirtDepthPixels / focal) : 1.0f;
}

Status ExactSurfacePass::skirtPass(const GpuScene& scene, const FrameCamera& camera,
                                   const std::vector<Light>& lights, const RenderOptions& options,
                                   const ValueRange& range) {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    // Nearer than what is there, and written: of two skirts over one gap the nearer wins. The
    // strip's depth is its polygon's, pushed back a little (surface.vert), so a face's own
    // pixels and those of faces in front reject it before shading; the shader writes no
    // gl_FragDepth, so the test stays early (a discarded fragment writes nothing).
    gl->glDepthFunc(kDepthNearer);
    gl->glDepthMask(GL_TRUE);
    gl->glBindVertexArray(scene.skirtVao());
    Status drawn;
    for (const auto& [key, b] : m_plan.skirts())
        if (!b.commands.empty() &&
            !(drawn = drawSkirtBatch(b, scene, camera, lights, options, range, skirtTriangles)))
            break;
    if (clock)
        clock->mark(PassTimes::Skirts);
    if (drawn && options.silhouetteFins)
        drawn = finPass(scene, camera, lights, options, range);
    scene.bindSurfaceData(); // the triangles' vertex array again
    return drawn;
}

Status ExactSurfacePass::drawSkirtBatch(const ExactBatch& b, const GpuScene& scene,
                                        const FrameCamera& camera, const std::vector<Light>& lights,
                                        const RenderOptions& options, const ValueRange& range,
                                        std::int64_t& triangles) {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    const Expected<QOpenGLShaderProgram*> built =
        bindExactProgram(variant(b.degreeU, b.degreeV, int(lights.size()), options, b.trimmed,
                                 false, TrimAa::Off, true),
                         b.trimmed, scene, camera, lights, options, range);
    if (!built)
        return built.error();
    QOpenGLShaderProgram* prog = *built;
    gl->glUniform1f(ShaderLibrary::uniforms(prog).skirtPixels,
                    float(options.pixelTolerance) + kSkirtMarginPixels);
    gl->glUniform1f(ShaderLibrary::uniforms(prog).skirtReach, kSkirtReachPixels);
    gl->glUniform1f(ShaderLibrary::uniforms(prog).skirtDepthScale, skirtDepthScale(camera));
    drawBatch(b);
    for (const IndirectCommand& c : b.commands)
        triangles += c.count / 3;
    return ok();
}

void ExactSurfacePass::releaseFins() {
    if (m_gl)
        for (GLuint* b : {&m_finVertexBuffer, &m_finIndexBuffer, &m_finCommandBuffer})
            if (*b)
                m_gl->glDeleteBuffers(1, b), *b = 0;
    m_finBytes = 0;
    m_fins.clear();
    m_finBatches.clear();
    m_finLayout.clear();
}

Status ExactSurfacePass::finPass(const GpuScene& scene, const FrameCamera& camera,
                                 const std::vector<Light>& lights, const RenderOptions& options,
                                 const ValueRange& range) {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    // 1. The fins of every skirted record drawn, rebuilt where the view or its polygon
    // changed (a still view costs one comparison per record).
    ++m_finFrame;
    const float pixels = float(options.pixelTolerance) + kSkirtMarginPixels;
    std::vector<std::tuple<const SurfaceRecord*, int, int>> layout;
    bool rebuilt = false;
    for (const SurfaceRecord* r : scene.records()) {
        const ExactPlace* place = m_plan.place(r);
        if (!place || !place->drawn || place->culled || place->skirtVariant < 0)
            continue;
        const SurfaceGpu& g = *r->exact;
        Fins& f = m_fins[r];
        f.frame = m_finFrame;
        if (f.viewProjection != camera.viewProjection || f.viewport != camera.viewport ||
            f.pixels != pixels || f.polygonSerial != g.polygonSerial ||
            f.points != g.revisions.points) {
            f.vertices.clear();
            f.indices.clear();
            f.rects.clear();
            buildFins(g.polygon, glm::dmat4(camera.viewProjection), glm::dvec3(camera.eye),
                      camera.viewport, pixels, f.vertices, f.indices);
            f.viewProjection = camera.viewProjection;
            f.viewport = camera.viewport;
            f.pixels = pixels;
            f.polygonSerial = g.polygonSerial;
            f.points = g.revisions.points;
            rebuilt = true;
        }
        if (!f.indices.empty())
            layout.emplace_back(r, r->slot, place->skirtVariant);
    }
    // A partial frame draws the records its rectangle reaches: the others' fins stay for the
    // next whole frame.
    if (camera.reach.z <= camera.reach.x)
        for (auto it = m_fins.begin(); it != m_fins.end();)
            it = it->second.frame == m_finFrame ? std::next(it) : m_fins.erase(it);
    // 2. One upload of them all when any changed, grouped by skirt variant; in a partial frame
    // only the fins that reach its rectangle.
    const bool partial = camera.reach.z > camera.reach.x;
    if (rebuilt || layout != m_finLayout || camera.reach != m_finReach) {
        m_finLayout = layout;
        m_finReach = camera.reach;
        std::stable_sort(layout.begin(), layout.end(), [](const auto& a, const auto& b) {
            return std::get<2>(a) < std::get<2>(b);
        });
        std::vector<SkirtVertex> vertices;
        std::vector<unsigned> indices;
        std::vector<IndirectCommand> commands;
        m_finBatches.clear();
        int lastVariant = -1;
        std::vector<unsigned> reaching;
        for (const auto& [r, slot, variant] : layout) {
            Fins& f = m_fins.at(r);
            bool all = !partial;
            if (partial) {
                if (f.rects.empty() && !f.indices.empty()) {
                    f.rects =
                        finRects(f.vertices, f.indices, camera.viewProjection, camera.viewport,
                                 m_plan.key().skirtPush);
                    f.bounds = glm::ivec4(0); // empty: meets nothing
                    for (const glm::ivec4& q : f.rects)
                        PartialFrames::unite(f.bounds, q);
                }
                const glm::ivec4 &b = f.bounds, &reach = camera.reach;
                reaching.clear();
                if (b.x >= reach.x && b.y >= reach.y && b.z <= reach.z && b.w <= reach.w)
                    all = true; // every fin inside
                else if (b.z > reach.x && b.x < reach.z && b.w > reach.y && b.y < reach.w)
                    reaching = finsMeeting(f.rects, f.indices, camera.reach);
            }
            const std::vector<unsigned>& sent = all ? f.indices : reaching;
            if (sent.empty())
                continue;
            if (variant != lastVariant) {
                lastVariant = variant;
                ExactBatch b;
                b.degreeU = variant & 15;
                b.degreeV = (variant >> 4) & 15;
                b.trimmed = (variant >> 8) & 1;
                b.first = std::int64_t(commands.size());
                m_finBatches.push_back(b);
            }
            const IndirectCommand c{std::uint32_t(sent.size()), 1, std::uint32_t(indices.size()),
                                    std::int32_t(vertices.size()), std::uint32_t(slot)};
            commands.push_back(c);
            m_finBatches.back().commands.push_back(c);
            vertices.insert(vertices.end(), f.vertices.begin(), f.vertices.end());
            indices.insert(indices.end(), sent.begin(), sent.end());
        }
        for (GLuint* b : {&m_finVertexBuffer, &m_finIndexBuffer, &m_finCommandBuffer})
            if (!*b)
                gl->glCreateBuffers(1, b);
        const auto upload = [&](GLuint buffer, std::size_t bytes, const void* data) {
            gl->glNamedBufferData(buffer, GLsizeiptr(std::max<std::size_t>(bytes, 4)), data,
                                  GL_DYNAMIC_DRAW);
            return std::int64_t(bytes);
        };
        m_finBytes = upload(m_finVertexBuffer, vertices.size() * sizeof(SkirtVertex),
                            vertices.empty() ? nullptr : vertices.data()) +
                     upload(m_finIndexBuffer, indices.size() * sizeof(unsigned),
                            indices.empty() ? nullptr : indices.data()) +
                     upload(m_finCommandBuffer, commands.size() * sizeof(IndirectCommand),
                            commands.empty() ? nullptr : commands.data());
    }
    if (m_finBatches.empty())
        return ok();
    // 3. Drawn as the skirts are, in skirtPass's depth state (nearer, depth written, pushed
    // back: they fill only pixels nothing nearer covered), from the fins' own buffers.
    const GLuint vao = scene.finVao();
    gl->glVertexArrayVertexBuffer(vao, 0, m_finVertexBuffer, 0, sizeof(SkirtVertex));
    gl->glVertexArrayElementBuffer(vao, m_finIndexBuffer);
    gl->glBindVertexArray(vao);
    gl->glBindBuffer(GL_DRAW_INDIRECT_BUFFER, m_finCommandBuffer);
    Status drawn;
    for (const ExactBatch& b : m_finBatches)
        if (!(drawn = drawSkirtBatch(b, scene, camera, lights, options, range, finTriangles)))
            break;
    skirtTriangles += finTriangles;
    gl->glBindBuffer(GL_DRAW_INDIRECT_BUFFER, m_commands);
    return drawn; // skirtPass binds the triangles' vertex array again
}

Status ExactSurfacePass::edgePass(const GpuScene& scene, const FrameCamera& camera,
                                  const std::vector<Light>& lights, const RenderOptions& options,
                                  const ValueRange& range, AntialiasTarget& aa) {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    // After every opaque fragment: a partly covered one is summed where it is nearer than
    // what was drawn (the strict nearer test: its own surface's wholly covered fragments fail), and
    // writes no depth, so every partly covered layer in front of the opaque one counts.
    aa.drawToAccumulation(true);
    gl->glDepthFunc(kDepthNearer);
    gl->glDepthMask(GL_FALSE);
    gl->glEnable(GL_BLEND);
    gl->glBlendEquation(GL_FUNC_ADD);
    gl->glBlendFunc(GL_ONE, GL_ONE);
    const Status drawn =
        drawBatches(m_plan.edges(), TrimAa::Edge, scene, camera, lights, options, range);
    gl->glDisable(GL_BLEND);
    aa.drawToAccumulation(false);
    return drawn;
}

} // namespace kw
