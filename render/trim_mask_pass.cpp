// Trim masks: resolution from the screen, one array layer per trimmed surface, XOR fan fill.
// Exact mode's grids are in trim_mask_pass_exact.cpp.
#include "render/trim_mask_pass.h"

#include "model/nurbs/trim.h"
#include "render/gpu_scene.h"

#include <QElapsedTimer>
#include <QOpenGLShaderProgram>
#include <algorithm>
#include <limits>

namespace kw {

namespace {

constexpr int kInitialLayers = 4;
// Mask texels per screen pixel of control-net length. The bilinear lookup puts the edge within
// about half a texel. Misclassified pixels are those within that band of a curve, so their
// share halves with each doubling; four texels per pixel bring the faces of an imported CAD
// model (many short edges) under 0.1% at 1024^2 (docs/ACCURACY.md, ## Trims). The cap
// bounds it for large surfaces.
constexpr double kTexelsPerPixel = 4.0;
// Loop flattening tolerance in mask texels: chords of convex arcs cut inside the curve, a bias
// the CPU classification (exact curves) would see on every edge pixel.
constexpr double kFlatteningTexels = 0.05;

int powerOfTwoSide(double length, int cap) {
    int n = kMinTrimMaskSize;
    while (n < length && n < cap)
        n *= 2;
    return std::min(n, cap);
}

} // namespace

void TrimMaskPass::initialize(QOpenGLFunctions_4_5_Core* gl, ShaderLibrary* shaders) {
    m_gl = gl;
    m_shaders = shaders;
}

glm::ivec2 TrimMaskPass::maskResolution(const Surface& surface, const FrameCamera& camera,
                                        int cap) {
    cap = std::max(cap, kMinTrimMaskSize);
    const NurbsSurface& g = surface.geometry;
    const glm::dmat4 vp(camera.viewProjection);
    const glm::dvec2 viewport(camera.viewport);
    std::vector<glm::dvec2> px(g.points.size());
    for (size_t k = 0; k < g.points.size(); ++k) {
        const glm::dvec4 clip = vp * glm::dvec4(g.points[k], 1.0);
        if (clip.w <= 1e-9) // part of the net behind the eye: a close-up, use the cap
            return {cap, cap};
        px[k] = (glm::dvec2(clip) / clip.w * 0.5 + 0.5) * viewport;
    }
    // Control polygon length on screen, the longest row along u and column along v: an upper
    // bound of the surface's own iso-curve lengths (convex hull property), so a texel covers at
    // most about half a pixel below the cap.
    double lenU = 0.0, lenV = 0.0;
    for (int j = 0; j < g.countV; ++j) {
        double len = 0.0;
        for (int i = 0; i + 1 < g.countU; ++i)
            len += glm::length(px[g.index(i + 1, j)] - px[g.index(i, j)]);
        lenU = std::max(lenU, len);
    }
    for (int i = 0; i < g.countU; ++i) {
        double len = 0.0;
        for (int j = 0; j + 1 < g.countV; ++j)
            len += glm::length(px[g.index(i, j + 1)] - px[g.index(i, j)]);
        lenV = std::max(lenV, len);
    }
    const glm::dvec4 rect = maskRect(surface);
    const Interval du = surfaceDomainU(g), dv = surfaceDomainV(g);
    const double shareU = (rect.y - rect.x) / (du.last - du.first);
    const double shareV = (rect.w - rect.z) / (dv.last - dv.first);
    return {powerOfTwoSide(kTexelsPerPixel * lenU * shareU, cap),
            powerOfTwoSide(kTexelsPerPixel * lenV * shareV, cap)};
}

glm::dvec4 TrimMaskPass::maskRect(const Surface& surface) {
    const Interval du = surfaceDomainU(surface.geometry), dv = surfaceDomainV(surface.geometry);
    glm::dvec2 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    for (const TrimLoop& loop : surface.trims)
        for (const NurbsCurve2& c : loop.curves)
            for (const glm::dvec2& p : c.points) {
                lo = glm::min(lo, p);
                hi = glm::max(hi, p);
            }
    const glm::dvec4 rect(std::max(lo.x, du.first), std::min(hi.x, du.last),
                          std::max(lo.y, dv.first), std::min(hi.y, dv.last));
    if (!(rect.y > rect.x) || !(rect.w > rect.z))
        return {du.first, du.last, dv.first, dv.last};
    return rect;
}

Status TrimMaskPass::ensureArray(int size, int layers) {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    if (m_texture)
        gl->glDeleteTextures(1, &m_texture), m_texture = 0;
    while (gl->glGetError() != GL_NO_ERROR) {
        // errors of earlier calls are not this allocation's
    }
    gl->glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &m_texture);
    gl->glTextureStorage3D(m_texture, 1, GL_R8, size, size, layers);
    gl->glTextureParameteri(m_texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl->glTextureParameteri(m_texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl->glTextureParameteri(m_texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl->glTextureParameteri(m_texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    if (const GLenum e = gl->glGetError(); e != GL_NO_ERROR) {
        gl->glDeleteTextures(1, &m_texture);
        m_texture = 0;
        m_size = m_layers = 0;
        return Error(
            QStringLiteral("trim mask array %1x%1x%2 could not be allocated (GL error 0x%3)")
                .arg(size)
                .arg(layers)
                .arg(e, 0, 16));
    }
    m_size = size;
    m_layers = layers;
    ++m_arrayAllocations;
    ++m_frame.arrayAllocations;
    if (!m_fbo) {
        gl->glCreateFramebuffers(1, &m_fbo);
        gl->glCreateVertexArrays(1, &m_vao);
        gl->glCreateBuffers(1, &m_buffer);
        gl->glVertexArrayVertexBuffer(m_vao, 0, m_buffer, 0, GLsizei(sizeof(glm::vec2)));
        gl->glEnableVertexArrayAttrib(m_vao, kAttrTrimCorner);
        gl->glVertexArrayAttribFormat(m_vao, kAttrTrimCorner, 2, GL_FLOAT, GL_FALSE, 0);
        gl->glVertexArrayAttribBinding(m_vao, kAttrTrimCorner, 0);
    }
    return ok();
}

Status TrimMaskPass::sync(const Document& /*doc*/, const std::vector<SurfaceRecord*>& records,
                          const FrameCamera& camera, const RenderOptions& options) {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    m_frame = {};
    drawCalls = 0;
    m_exactMode = options.trimMode == RenderOptions::TrimMode::Exact;
    if (m_exactMode)
        return syncExact(records, camera, options);
    // Mask mode: what exact mode held goes (the records' blocks, then the buffer).
    for (SurfaceRecord* r : records)
        if (r->mask.grid.words || r->mask.grid.cap)
            freeLayer(r->mask);
    freeGrids();
    GLint maxSize = 0, maxLayers = 0;
    gl->glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    gl->glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
    const int cap = std::clamp(options.trimMaskCap, kMinTrimMaskSize, int(maxSize));
    // Too many trimmed surfaces is reported, but the masks that fit are still drawn.
    Status status;

    struct Want {
        SurfaceRecord* record;
        glm::ivec2 resolution;
    };
    std::vector<Want> wants;
    for (SurfaceRecord* r : records) {
        if (!r->surface->trims.empty() && r->exact)
            wants.push_back({r, maskResolution(*r->surface, camera, cap)});
        else
            freeLayer(r->mask); // no longer trimmed (or not drawn)
    }
    if (wants.size() > size_t(maxLayers)) {
        status = Error(QStringLiteral("%1 trimmed surfaces exceed the GPU's %2 mask layers; the "
                                      "rest are drawn untrimmed")
                           .arg(wants.size())
                           .arg(maxLayers));
        for (size_t k = size_t(maxLayers); k < wants.size(); ++k)
            freeLayer(wants[k].record->mask);
        wants.resize(size_t(maxLayers));
    }
    if (wants.empty()) {
        // No trimmed surface left: free the array, so an emptied scene holds no mask memory.
        freeArray();
        return status;
    }

    int size = m_size;
    for (const Want& w : wants)
        size = std::max({size, w.resolution.x, w.resolution.y});
    if (size > m_size || int(wants.size()) > m_layers) {
        // Grow (never shrink, so zooming back and forth does not reallocate): every mask is
        // redrawn into the new array.
        int layers = std::max(m_layers, kInitialLayers);
        while (layers < int(wants.size()))
            layers *= 2;
        layers = std::min(layers, int(maxLayers));
        for (const Want& w : wants)
            w.record->mask.layer = -1;
        if (Status allocated = ensureArray(size, layers); !allocated)
            return allocated;
        m_freeLayers.clear();
        for (int l = layers - 1; l >= 0; --l)
            m_freeLayers.push_back(l);
    }

    for (const Want& w : wants) {
        const Surface& s = *w.record->surface;
        const Revisions& rev = w.record->revisions; // GpuScene::sync's, found by index
        TrimMask& m = w.record->mask;
        const bool fresh = m.layer < 0;
        if (fresh) {
            m.layer = m_freeLayers.back();
            m_freeLayers.pop_back();
        }
        if (fresh || m.trimsRevision != rev.trims || m.knotsRevision != rev.knots ||
            m.width != w.resolution.x || m.height != w.resolution.y) {
            redraw(m, s, w.resolution);
            m.trimsRevision = rev.trims;
            m.knotsRevision = rev.knots;
        }
    }
    gl->glBindFramebuffer(GL_FRAMEBUFFER, 0);
    gl->glDisable(GL_COLOR_LOGIC_OP);
    gl->glDisable(GL_SCISSOR_TEST);
    if (const Expected<QOpenGLShaderProgram*> built =
            m_shaders->program(QStringLiteral("trim_mask.vert"), QStringLiteral("trim_mask.frag"));
        !built)
        return built.error();
    return status;
}

void TrimMaskPass::freeArray() {
    if (m_texture) {
        m_gl->glDeleteTextures(1, &m_texture);
        m_texture = 0;
    }
    m_size = m_layers = 0;
    m_freeLayers.clear();
}

void TrimMaskPass::freeLayer(TrimMask& m) {
    if (m.layer < 0 && !m.active && m.warnings.isEmpty() && !m.grid.words && !m.grid.cap)
        return; // nothing held (the common case: an untrimmed surface)
    if (m.layer >= 0 && m.layer < m_layers)
        m_freeLayers.push_back(m.layer);
    m_grids.release(m.grid);
    const TrimMaskStats stats = m.stats;
    m = TrimMask{};
    m.stats = stats;
}

void TrimMaskPass::redraw(TrimMask& m, const Surface& s, glm::ivec2 resolution) {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    QElapsedTimer timer;
    timer.start();
    TrimMaskStats d;
    d.largestSide = std::max(resolution.x, resolution.y);
    // Counted into the mask's and the frame's statistics on every way out.
    const auto account = [&] {
        d.cpuNanoseconds += timer.nsecsElapsed();
        m.stats += d;
        m_frame += d;
    };
    m.rect = maskRect(s);
    m.width = resolution.x;
    m.height = resolution.y;
    const glm::dvec2 extent(m.rect.y - m.rect.x, m.rect.w - m.rect.z);
    // The flattened loops stay well inside the mask's own quantisation.
    const double tolerance = kFlatteningTexels * std::min(extent.x / m.width, extent.y / m.height);
    m.warnings.clear();
    const TrimRegion region = makeTrimRegion(s.trims, tolerance, &m.warnings);
    m.active = !region.empty();
    ++d.redraws;
    const Expected<QOpenGLShaderProgram*> built =
        m_shaders->program(QStringLiteral("trim_mask.vert"), QStringLiteral("trim_mask.frag"));
    QOpenGLShaderProgram* prog = built.value_or(nullptr);
    if (!m.active || !prog) {
        m.active = false;
        account();
        return;
    }
    std::vector<glm::vec2> vertices;
    std::vector<GLint> firsts;
    std::vector<GLsizei> counts;
    const glm::dvec2 origin(m.rect.x, m.rect.z);
    for (const TrimPolygon& poly : region.loops) {
        firsts.push_back(GLint(vertices.size()));
        counts.push_back(GLsizei(poly.size()));
        for (const glm::dvec2& p : poly) // unit square of the rectangle, in double first
            vertices.push_back(glm::vec2((p - origin) / extent));
        d.triangles += std::int64_t(poly.size()) - 2;
    }
    d.loops += std::int64_t(region.loops.size());
    d.texels += std::int64_t(m.width) * m.height;
    gl->glNamedBufferData(m_buffer, GLsizeiptr(vertices.size() * sizeof(glm::vec2)),
                          vertices.data(), GL_STREAM_DRAW);
    // trim_mask.frag's output reaches the layer as the framebuffer's default draw buffer, the
    // only one: attachment 0.
    static_assert(kTrimMaskOutput == 0);
    gl->glNamedFramebufferTextureLayer(m_fbo, GL_COLOR_ATTACHMENT0, m_texture, 0, m.layer);
    gl->glBindFramebuffer(GL_FRAMEBUFFER, m_fbo);
    gl->glViewport(0, 0, m.width, m.height);
    gl->glEnable(GL_SCISSOR_TEST);
    gl->glScissor(0, 0, m.width, m.height);
    gl->glDisable(GL_DEPTH_TEST);
    gl->glDisable(GL_BLEND);
    gl->glDisable(GL_CULL_FACE);
    gl->glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    const GLfloat zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    gl->glClearBufferfv(GL_COLOR, kTrimMaskOutput, zero);
    // Parity fill: each fan triangle toggles the texels whose centres it covers; the shared
    // fan edges are rasterised once (GL's fill rule), so a texel flips once per loop crossing.
    gl->glEnable(GL_COLOR_LOGIC_OP);
    gl->glLogicOp(GL_XOR);
    prog->bind();
    gl->glBindVertexArray(m_vao);
    gl->glMultiDrawArrays(GL_TRIANGLE_FAN, firsts.data(), counts.data(), GLsizei(firsts.size()));
    gl->glDisable(GL_COLOR_LOGIC_OP);
    gl->glDisable(GL_SCISSOR_TEST);
    gl->glEnable(GL_DEPTH_TEST);
    ++drawCalls;
    account();
}

ExactFeatures TrimMaskPass::trimFeatures() const {
    return m_exactMode ? ExactFeature::Trim | ExactFeature::TrimExact
                       : ExactFeatures(ExactFeature::Trim);
}

QStringList TrimMaskPass::trimDefines() const {
    return featureDefines(trimFeatures());
}

void TrimMaskPass::setUniforms(QOpenGLShaderProgram* program, const TrimMask& mask,
                               int unit) const {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    bindArray(program, unit);
    const UniformLocations& u = ShaderLibrary::uniforms(program);
    const glm::vec4 rect(mask.rect);
    gl->glUniform4f(u.trimRect, rect.x, rect.y, rect.z, rect.w);
    gl->glUniform2f(u.trimSize, float(mask.width), float(mask.height));
    if (m_exactMode)
        gl->glUniform1ui(u.trimBlock, mask.grid.offset);
    else
        gl->glUniform1f(u.trimLayer, float(mask.layer));
}

void TrimMaskPass::bindArray(QOpenGLShaderProgram* program, int unit) const {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    if (m_exactMode) {
        gl->glBindTextureUnit(GLuint(kTrimGridUnit), m_gridView);
        gl->glBindTextureUnit(GLuint(kTrimGridQuadUnit), m_gridQuads);
        return;
    }
    gl->glBindTextureUnit(GLuint(unit), m_texture);
    gl->glUniform1i(ShaderLibrary::uniforms(program).trimMask, unit);
    gl->glUniform2f(ShaderLibrary::uniforms(program).trimLayerScale, 1.0f / float(m_size),
                    1.0f / float(m_size));
}

std::vector<unsigned char> TrimMaskPass::readMask(const TrimMask& mask) const {
    const TrimMask* m = &mask;
    if (!m->active || m->layer < 0)
        return {};
    std::vector<unsigned char> texels(size_t(m->width) * size_t(m->height));
    // llvmpipe (Mesa 22) returned a layer's previous contents to glGetTextureSubImage right
    // after a redraw into it; finishing the queued rendering first gives the current ones.
    m_gl->glFinish();
    m_gl->glPixelStorei(GL_PACK_ALIGNMENT, 1);
    m_gl->glGetTextureSubImage(m_texture, 0, 0, 0, m->layer, m->width, m->height, 1, GL_RED,
                               GL_UNSIGNED_BYTE, GLsizei(texels.size()), texels.data());
    return texels;
}

std::int64_t TrimMaskPass::residentBytes() const {
    return std::int64_t(m_size) * m_size * m_layers + m_gridBufferBytes; // GL_R8, R32UI
}

void TrimMaskPass::release() {
    if (m_gl) {
        if (m_texture)
            m_gl->glDeleteTextures(1, &m_texture);
        if (m_fbo)
            m_gl->glDeleteFramebuffers(1, &m_fbo);
        if (m_vao)
            m_gl->glDeleteVertexArrays(1, &m_vao);
        if (m_buffer)
            m_gl->glDeleteBuffers(1, &m_buffer);
    }
    m_texture = m_fbo = m_vao = m_buffer = 0;
    m_size = m_layers = 0;
    m_freeLayers.clear();
    freeGrids();
}

} // namespace kw
