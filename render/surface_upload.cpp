// Uploads of one surface's exact-mode GPU data (DSA calls, so no texture or buffer binding of
// the caller is disturbed).
#include "render/surface_upload.h"

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

void uploadSurface(QOpenGLFunctions_4_5_Core* gl, SurfaceGpu& g, const Surface& s, int nu, int nv,
                   const ParameterBox& box, UploadStats& stats) {
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
    stats.fullUploads += 1;
    stats.texels += std::int64_t(g.control.size());
    stats.bytes += std::int64_t(g.control.size() * sizeof(glm::vec4));

    const std::vector<glm::vec4> su = packSpanTable(geo.knotsU, geo.degreeU, geo.countU);
    const std::vector<glm::vec4> sv = packSpanTable(geo.knotsV, geo.degreeV, geo.countV);
    g.spanTextureU =
        createTexture(gl, spanTableTexels(geo.degreeU), geo.countU - geo.degreeU, su.data());
    g.spanTextureV =
        createTexture(gl, spanTableTexels(geo.degreeV), geo.countV - geo.degreeV, sv.data());
    stats.spanTableUploads += 2;
    stats.bytes += std::int64_t((su.size() + sv.size()) * sizeof(glm::vec4));
    rebuildPolygon(gl, g, s, nu, nv, box, stats);
}

void uploadChangedPoints(QOpenGLFunctions_4_5_Core* gl, SurfaceGpu& g, const Surface& s,
                         UploadStats& stats) {
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
    gl->glPixelStorei(GL_UNPACK_ROW_LENGTH, g.countU);
    gl->glTextureSubImage2D(g.controlTexture, 0, i0, j0, w, h, GL_RGBA, GL_FLOAT,
                            g.control.data() + (j0 * g.countU + i0));
    gl->glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    stats.subImageUploads += 1;
    stats.texels += std::int64_t(w) * h;
    stats.bytes += std::int64_t(w) * h * std::int64_t(sizeof(glm::vec4));

    int first = 0, last = -1;
    if (updateBasePolygon(g.polygon, s.geometry, i0, i1, j0, j1, first, last)) {
        const GLintptr offset = GLintptr(first) * GLintptr(sizeof(BaseVertex));
        const GLsizeiptr size = GLsizeiptr(last - first + 1) * GLsizeiptr(sizeof(BaseVertex));
        gl->glNamedBufferSubData(g.vertexBuffer, offset, size,
                                 g.polygon.vertices.data() + size_t(first));
        stats.vertexUpdates += 1;
        stats.vertexBytes += std::int64_t(size);
        stats.bytes += std::int64_t(size);
    }
}

void rebuildPolygon(QOpenGLFunctions_4_5_Core* gl, SurfaceGpu& g, const Surface& s, int nu, int nv,
                    const ParameterBox& box, UploadStats& stats) {
    g.partitionsU = nu;
    g.partitionsV = nv;
    g.polygonBox = box;
    g.polygon = buildBasePolygon(s.geometry, box, nu, nv);
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
    stats.basePolygonBuilds += 1;
    stats.bytes +=
        std::int64_t(vbytes) + std::int64_t((tri.size() + lines.size()) * sizeof(unsigned));
}

void addResidentBytes(const SurfaceGpu& gpu, GpuBytes& out) {
    constexpr std::int64_t texel = sizeof(glm::vec4);
    const SurfaceGpu* g = &gpu;
    {
        out.controlPoints += std::int64_t(g->countU) * g->countV * texel;
        out.spanTables += (std::int64_t(spanTableTexels(g->degreeU)) * (g->countU - g->degreeU) +
                           std::int64_t(spanTableTexels(g->degreeV)) * (g->countV - g->degreeV)) *
                          texel;
        out.basePolygons += std::int64_t(g->polygon.vertices.size() * sizeof(BaseVertex)) +
                            std::int64_t(g->triangleIndexCount + g->outlineIndexCount) *
                                std::int64_t(sizeof(unsigned));
    }
}

void destroySurfaceGpu(QOpenGLFunctions_4_5_Core* gl, SurfaceGpu& g) {
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

} // namespace kw
