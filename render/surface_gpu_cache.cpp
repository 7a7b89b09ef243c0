// Uploads of per-surface GPU data, only what the revisions say is stale (DSA calls, so no
// texture or buffer binding of the caller is disturbed).
#include "render/surface_gpu_cache.h"

#include <algorithm>

namespace kw {

namespace {

GLuint createTexture(QOpenGLFunctions_4_5_Core* gl, int w, int h, const glm::vec4* data) {
    GLuint tex = 0;
    gl->glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    gl->glTextureStorage2D(tex, 1, GL_RGBA32F, std::max(w, 1), std::max(h, 1));
    gl->glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl->glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    if (w > 0 && h > 0)
        gl->glTextureSubImage2D(tex, 0, 0, 0, w, h, GL_RGBA, GL_FLOAT, data);
    return tex;
}

} // namespace

bool SurfaceGpuCache::sync(const Document& doc, int partitionsU, int partitionsV, QString* error) {
    const Scene& scene = doc.scene();
    GLint maxSize = 0;
    m_gl->glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    QStringList tooLarge;
    m_frame = {};
    for (auto it = m_surfaces.begin(); it != m_surfaces.end();) {
        if (!doc.surface(it->first)) {
            destroy(*it->second);
            it = m_surfaces.erase(it);
        } else {
            ++it;
        }
    }
    for (const Surface& s : scene.surfaces) {
        const int nu = partitionsU > 0 ? partitionsU : s.partitionsU;
        const int nv = partitionsV > 0 ? partitionsV : s.partitionsV;
        const Revisions rev = doc.revisions(s.id);
        const NurbsSurface& geo = s.geometry;
        if (geo.countU > maxSize || geo.countV > maxSize) {
            // Not drawn: its control net does not fit one texture.
            if (auto it = m_surfaces.find(s.id); it != m_surfaces.end()) {
                destroy(*it->second);
                m_surfaces.erase(it);
            }
            tooLarge << QStringLiteral("surface %1 (\"%2\") has %3 x %4 control points, more "
                                       "than the GPU's texture size limit %5")
                            .arg(s.id.value)
                            .arg(s.name)
                            .arg(geo.countU)
                            .arg(geo.countV)
                            .arg(maxSize);
            continue;
        }
        std::unique_ptr<SurfaceGpu>& slot = m_surfaces[s.id];
        if (!slot || slot->revisions.knots != rev.knots || slot->degreeU != geo.degreeU ||
            slot->degreeV != geo.degreeV || slot->countU != geo.countU ||
            slot->countV != geo.countV) {
            if (!slot) {
                slot = std::make_unique<SurfaceGpu>();
                slot->id = s.id;
            }
            uploadAll(*slot, s, nu, nv);
        } else if (slot->partitionsU != nu || slot->partitionsV != nv) {
            // The polygon is rebuilt from the current points anyway; pick up a point change.
            if (slot->revisions.points != rev.points)
                uploadChangedPoints(*slot, s);
            rebuildPolygon(*slot, s, nu, nv);
        } else if (slot->revisions.points != rev.points) {
            uploadChangedPoints(*slot, s);
        }
        slot->revisions = rev;
        slot->stats += m_delta;
        m_frame += m_delta;
        m_delta = {};
    }
    if (!tooLarge.isEmpty() && error)
        *error = tooLarge.join(QStringLiteral("; "));
    return tooLarge.isEmpty();
}

void SurfaceGpuCache::uploadAll(SurfaceGpu& g, const Surface& s, int nu, int nv) {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    const NurbsSurface& geo = s.geometry;
    for (GLuint* t : {&g.controlTexture, &g.spanTextureU, &g.spanTextureV})
        if (*t)
            gl->glDeleteTextures(1, t), *t = 0;
    g.degreeU = geo.degreeU;
    g.degreeV = geo.degreeV;
    g.countU = geo.countU;
    g.countV = geo.countV;
    const Interval du = surfaceDomainU(geo), dv = surfaceDomainV(geo);
    g.domain = glm::vec4(float(du.first), float(du.last), float(dv.first), float(dv.last));

    g.origin = controlOrigin(geo);
    g.control = packControlPoints(geo, g.origin);
    g.controlTexture = createTexture(gl, geo.countU, geo.countV, g.control.data());
    m_delta.fullUploads += 1;
    m_delta.texels += std::int64_t(g.control.size());
    m_delta.bytes += std::int64_t(g.control.size() * sizeof(glm::vec4));

    const std::vector<glm::vec4> su = packSpanTable(geo.knotsU, geo.degreeU, geo.countU);
    const std::vector<glm::vec4> sv = packSpanTable(geo.knotsV, geo.degreeV, geo.countV);
    g.spanTextureU =
        createTexture(gl, spanTableTexels(geo.degreeU), geo.countU - geo.degreeU, su.data());
    g.spanTextureV =
        createTexture(gl, spanTableTexels(geo.degreeV), geo.countV - geo.degreeV, sv.data());
    m_delta.spanTableUploads += 2;
    m_delta.bytes += std::int64_t((su.size() + sv.size()) * sizeof(glm::vec4));
    rebuildPolygon(g, s, nu, nv);
}

void SurfaceGpuCache::uploadChangedPoints(SurfaceGpu& g, const Surface& s) {
    const std::vector<glm::vec4> now = packControlPoints(s.geometry, g.origin);
    int i0 = g.countU, i1 = -1, j0 = g.countV, j1 = -1;
    for (int j = 0; j < g.countV; ++j)
        for (int i = 0; i < g.countU; ++i) {
            const size_t k = size_t(j * g.countU + i);
            if (now[k] != g.control[k]) {
                i0 = std::min(i0, i), i1 = std::max(i1, i);
                j0 = std::min(j0, j), j1 = std::max(j1, j);
            }
        }
    if (i1 < 0)
        return; // revision moved (e.g. undo then redo) but the texels are identical
    g.control = now;
    const int w = i1 - i0 + 1, h = j1 - j0 + 1;
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    gl->glPixelStorei(GL_UNPACK_ROW_LENGTH, g.countU);
    gl->glTextureSubImage2D(g.controlTexture, 0, i0, j0, w, h, GL_RGBA, GL_FLOAT,
                            g.control.data() + (j0 * g.countU + i0));
    gl->glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    m_delta.subImageUploads += 1;
    m_delta.texels += std::int64_t(w) * h;
    m_delta.bytes += std::int64_t(w) * h * std::int64_t(sizeof(glm::vec4));

    int first = 0, last = -1;
    if (updateBasePolygon(g.polygon, s.geometry, i0, i1, j0, j1, first, last)) {
        const GLintptr offset = GLintptr(first) * GLintptr(sizeof(BaseVertex));
        const GLsizeiptr size = GLsizeiptr(last - first + 1) * GLsizeiptr(sizeof(BaseVertex));
        gl->glNamedBufferSubData(g.vertexBuffer, offset, size,
                                 g.polygon.vertices.data() + size_t(first));
        m_delta.vertexUpdates += 1;
        m_delta.vertexBytes += std::int64_t(size);
        m_delta.bytes += std::int64_t(size);
    }
}

void SurfaceGpuCache::rebuildPolygon(SurfaceGpu& g, const Surface& s, int nu, int nv) {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    g.partitionsU = nu;
    g.partitionsV = nv;
    g.polygon = buildBasePolygon(s.geometry, nu, nv);
    const std::vector<unsigned> tri = basePolygonTriangles(g.polygon);
    const std::vector<unsigned> lines = basePolygonOutlines(g.polygon);
    if (!g.vertexBuffer) {
        gl->glCreateBuffers(1, &g.vertexBuffer);
        gl->glCreateBuffers(1, &g.triangleBuffer);
        gl->glCreateBuffers(1, &g.outlineBuffer);
        gl->glCreateVertexArrays(1, &g.triangleVao);
        gl->glCreateVertexArrays(1, &g.outlineVao);
        for (GLuint vao : {g.triangleVao, g.outlineVao}) {
            gl->glVertexArrayVertexBuffer(vao, 0, g.vertexBuffer, 0, sizeof(BaseVertex));
            gl->glEnableVertexArrayAttrib(vao, 0);
            gl->glEnableVertexArrayAttrib(vao, 1);
            gl->glEnableVertexArrayAttrib(vao, 2);
            gl->glEnableVertexArrayAttrib(vao, 3);
            gl->glVertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE,
                                          offsetof(BaseVertex, position));
            gl->glVertexArrayAttribFormat(vao, 1, 2, GL_FLOAT, GL_FALSE, offsetof(BaseVertex, uv));
            gl->glVertexArrayAttribIFormat(vao, 2, 2, GL_INT, offsetof(BaseVertex, span));
            gl->glVertexArrayAttribFormat(vao, 3, 1, GL_FLOAT, GL_FALSE,
                                          offsetof(BaseVertex, spanScale));
            for (GLuint a = 0; a < 4; ++a)
                gl->glVertexArrayAttribBinding(vao, a, 0);
        }
        gl->glVertexArrayElementBuffer(g.triangleVao, g.triangleBuffer);
        gl->glVertexArrayElementBuffer(g.outlineVao, g.outlineBuffer);
    }
    const GLsizeiptr vbytes = GLsizeiptr(g.polygon.vertices.size() * sizeof(BaseVertex));
    gl->glNamedBufferData(g.vertexBuffer, vbytes, g.polygon.vertices.data(), GL_DYNAMIC_DRAW);
    gl->glNamedBufferData(g.triangleBuffer, GLsizeiptr(tri.size() * sizeof(unsigned)), tri.data(),
                          GL_STATIC_DRAW);
    gl->glNamedBufferData(g.outlineBuffer, GLsizeiptr(lines.size() * sizeof(unsigned)),
                          lines.data(), GL_STATIC_DRAW);
    g.triangleIndexCount = int(tri.size());
    g.outlineIndexCount = int(lines.size());
    m_delta.basePolygonBuilds += 1;
    m_delta.bytes +=
        std::int64_t(vbytes) + std::int64_t((tri.size() + lines.size()) * sizeof(unsigned));
}

const SurfaceGpu* SurfaceGpuCache::find(SurfaceId id) const {
    auto it = m_surfaces.find(id);
    return it == m_surfaces.end() ? nullptr : it->second.get();
}

UploadStats SurfaceGpuCache::stats(SurfaceId id) const {
    const SurfaceGpu* g = find(id);
    return g ? g->stats : UploadStats{};
}

UploadStats SurfaceGpuCache::totalStats() const {
    UploadStats total;
    for (const auto& [id, g] : m_surfaces)
        total += g->stats;
    return total;
}

void SurfaceGpuCache::residentBytes(GpuBytes& out) const {
    constexpr std::int64_t texel = sizeof(glm::vec4);
    for (const auto& [id, g] : m_surfaces) {
        out.controlPoints += std::int64_t(g->countU) * g->countV * texel;
        out.spanTables += (std::int64_t(spanTableTexels(g->degreeU)) * (g->countU - g->degreeU) +
                           std::int64_t(spanTableTexels(g->degreeV)) * (g->countV - g->degreeV)) *
                          texel;
        out.basePolygons += std::int64_t(g->polygon.vertices.size() * sizeof(BaseVertex)) +
                            std::int64_t(g->triangleIndexCount + g->outlineIndexCount) *
                                std::int64_t(sizeof(unsigned));
    }
}

void SurfaceGpuCache::resetStats() {
    for (auto& [id, g] : m_surfaces)
        g->stats = {};
}

void SurfaceGpuCache::destroy(SurfaceGpu& g) {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    for (GLuint* t : {&g.controlTexture, &g.spanTextureU, &g.spanTextureV})
        if (*t)
            gl->glDeleteTextures(1, t), *t = 0;
    for (GLuint* b : {&g.vertexBuffer, &g.triangleBuffer, &g.outlineBuffer})
        if (*b)
            gl->glDeleteBuffers(1, b), *b = 0;
    for (GLuint* a : {&g.triangleVao, &g.outlineVao})
        if (*a)
            gl->glDeleteVertexArrays(1, a), *a = 0;
}

void SurfaceGpuCache::release() {
    if (m_gl)
        for (auto& [id, g] : m_surfaces)
            destroy(*g);
    m_surfaces.clear();
}

} // namespace kw
