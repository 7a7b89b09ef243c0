// GpuScene's buffers beside the records: the surface table and the vertex arrays over the
// pools, and the per-record tessellated meshes and control nets.
#include "render/exact_contract.h"
#include "render/gpu_scene.h"
#include "render/tessellated_pass.h"

namespace kw {

void GpuScene::bindSurfaceData() const {
    for (int k = 0; k < kSurfaceDataViews; ++k)
        m_gl->glBindTextureUnit(GLuint(kSurfaceTableUnit + k), m_views[k]);
    m_analytic.bind(m_gl);
    m_gl->glBindVertexArray(m_triangleVao);
}

void GpuScene::syncTable(const std::vector<SurfaceRecord*>& records) {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    Table& t = m_table;
    if (t.used == 0) {
        // No surface left: no table, no pool memory (the empty scene's bytes).
        for (GLuint* b : {&t.buffer, &t.instances})
            if (*b)
                gl->glDeleteBuffers(1, b), *b = 0;
        t.capacity = 0;
        t.rows.clear();
        t.freeSlots.clear();
        m_analytic.release(gl);
    } else {
        int lo = int(t.rows.size()), hi = -1;
        for (const SurfaceRecord* r : records) {
            if (!r->exact || r->slot < 0)
                continue;
            const SurfaceGpu& g = *r->exact;
            const Material& m = r->surface->material;
            SurfaceTableEntry e;
            e.domain = g.domain;
            e.origin = glm::vec4(glm::vec3(g.origin), 0.0f);
            e.colour = glm::vec4(glm::vec3(m.color), 1.0f);
            e.material = glm::vec4(float(m.ka), float(m.kd), float(m.ks),
                                   float(std::max(m.shininess, 1e-3)));
            int trimBlock = 0;
            if (r->mask.usable()) {
                e.trimRect = glm::vec4(r->mask.rect);
                e.trimSize = glm::vec4(float(r->mask.width), float(r->mask.height),
                                       float(r->mask.layer), 0.0f);
                trimBlock = int(r->mask.grid.offset);
            }
            e.data = glm::ivec4(int(g.controlOffset), g.countU, int(g.spanOffset),
                                int(g.spanOffset + g.spanTexelsU));
            // Which side of the face is a closed solid's outside: the section caps' test.
            const int solidSide =
                r->surface->solid < 0 ? 0 : (r->surface->outsideAlongNormal ? 1 : -1);
            e.ids = glm::ivec4(int(r->id.value), trimBlock, solidSide, 0);
            SurfaceTableEntry& row = t.rows[size_t(r->slot)];
            if (!(row == e)) {
                row = e;
                lo = std::min(lo, r->slot), hi = std::max(hi, r->slot);
            }
        }
        if (int(t.rows.size()) > t.capacity) {
            // Grown: new buffers, every row written.
            t.capacity = std::max(64, t.capacity);
            while (t.capacity < int(t.rows.size()))
                t.capacity *= 2;
            for (GLuint* b : {&t.buffer, &t.instances})
                if (*b)
                    gl->glDeleteBuffers(1, b), *b = 0;
            gl->glCreateBuffers(1, &t.buffer);
            gl->glCreateBuffers(1, &t.instances);
            gl->glNamedBufferData(t.buffer, GLsizeiptr(t.capacity) * sizeof(SurfaceTableEntry),
                                  nullptr, GL_DYNAMIC_DRAW);
            std::vector<int> ids(size_t(t.capacity));
            for (int k = 0; k < t.capacity; ++k)
                ids[size_t(k)] = k;
            gl->glNamedBufferData(t.instances, GLsizeiptr(ids.size() * sizeof(int)), ids.data(),
                                  GL_STATIC_DRAW);
            lo = 0, hi = int(t.rows.size()) - 1;
        }
        if (hi >= lo)
            gl->glNamedBufferSubData(t.buffer, GLintptr(lo) * sizeof(SurfaceTableEntry),
                                     GLsizeiptr(hi - lo + 1) * sizeof(SurfaceTableEntry),
                                     t.rows.data() + lo);
        m_analytic.sync(gl, records, int(t.rows.size()));
    }
    // BaseVertex's attributes from binding 0, at `base` bytes into each vertex; the surface
    // index, one int per instance from binding 1 (a draw's base instance picks its row).
    const auto baseAttributes = [&](GLuint vao, GLuint base, bool instanced) {
        for (const int a : {kAttrPosition, kAttrUv, kAttrSpan, kAttrSpanScale}) {
            gl->glEnableVertexArrayAttrib(vao, GLuint(a));
            gl->glVertexArrayAttribBinding(vao, GLuint(a), 0);
        }
        gl->glVertexArrayAttribFormat(vao, kAttrPosition, 3, GL_FLOAT, GL_FALSE,
                                      base + offsetof(BaseVertex, position));
        gl->glVertexArrayAttribFormat(vao, kAttrUv, 2, GL_FLOAT, GL_FALSE,
                                      base + offsetof(BaseVertex, uv));
        gl->glVertexArrayAttribIFormat(vao, kAttrSpan, 2, GL_INT,
                                       base + offsetof(BaseVertex, span));
        gl->glVertexArrayAttribFormat(vao, kAttrSpanScale, 1, GL_FLOAT, GL_FALSE,
                                      base + offsetof(BaseVertex, spanScale));
        if (instanced) {
            gl->glEnableVertexArrayAttrib(vao, kAttrSurface);
            gl->glVertexArrayAttribIFormat(vao, kAttrSurface, 1, GL_INT, 0);
            gl->glVertexArrayAttribBinding(vao, kAttrSurface, 1);
            gl->glVertexArrayBindingDivisor(vao, 1, 1);
        }
    };
    if (!m_triangleVao) {
        gl->glCreateVertexArrays(1, &m_triangleVao);
        gl->glCreateVertexArrays(1, &m_outlineVao);
        baseAttributes(m_triangleVao, 0, true);
        baseAttributes(m_outlineVao, 0, false);
    }
    for (GLuint* vao : {&m_skirtVao, &m_finVao})
        if (!*vao) {
            // SkirtVertex: its BaseVertex, then the outward (u, v) direction.
            gl->glCreateVertexArrays(1, vao);
            baseAttributes(*vao, offsetof(SkirtVertex, base), true);
            gl->glEnableVertexArrayAttrib(*vao, kAttrOutward);
            gl->glVertexArrayAttribBinding(*vao, kAttrOutward, 0);
            gl->glVertexArrayAttribFormat(*vao, kAttrOutward, 2, GL_FLOAT, GL_FALSE,
                                          offsetof(SkirtVertex, outward));
        }
    const GLuint buffers[4] = {t.buffer, t.buffer, m_pools.control.buffer(),
                               m_pools.spans.buffer()};
    const GLenum formats[4] = {GL_RGBA32F, GL_RGBA32I, GL_RGBA32F, GL_RGBA32F};
    for (int k = 0; k < 4; ++k) {
        if (!m_views[k])
            gl->glCreateTextures(GL_TEXTURE_BUFFER, 1, &m_views[k]);
        // Every frame: a freed buffer's name can come back for a new one, so comparing
        // names could keep a view on the old storage.
        gl->glTextureBuffer(m_views[k], formats[k], buffers[k]);
    }
    // Cheap, and the pools' buffers are renamed when they grow.
    for (GLuint vao : {m_triangleVao, m_outlineVao})
        gl->glVertexArrayVertexBuffer(vao, 0, m_pools.vertices.buffer(), 0, sizeof(BaseVertex));
    gl->glVertexArrayVertexBuffer(m_triangleVao, 1, t.instances, 0, sizeof(int));
    gl->glVertexArrayVertexBuffer(m_skirtVao, 0, m_pools.skirtVertices.buffer(), 0,
                                  sizeof(SkirtVertex));
    gl->glVertexArrayVertexBuffer(m_skirtVao, 1, t.instances, 0, sizeof(int));
    gl->glVertexArrayVertexBuffer(m_finVao, 1, t.instances, 0, sizeof(int));
    gl->glVertexArrayElementBuffer(m_skirtVao, m_pools.skirtIndices.buffer());
    gl->glVertexArrayElementBuffer(m_triangleVao, m_pools.triangles.buffer());
    gl->glVertexArrayElementBuffer(m_outlineVao, m_pools.outlines.buffer());
}

void GpuScene::compactPools() {
    struct Owned {
        GpuPool* pool;
        std::int64_t SurfaceGpu::*offset;
        std::int64_t (*count)(const SurfaceGpu&);
    };
    const Owned owned[] = {
        {&m_pools.vertices, &SurfaceGpu::vertexOffset,
         [](const SurfaceGpu& g) {
             return g.vertexCount;
         }},
        {&m_pools.triangles, &SurfaceGpu::triangleOffset,
         [](const SurfaceGpu& g) {
             return std::int64_t(g.triangleIndexCount);
         }},
        {&m_pools.outlines, &SurfaceGpu::outlineOffset,
         [](const SurfaceGpu& g) {
             return std::int64_t(g.outlineIndexCount);
         }},
        {&m_pools.skirtVertices, &SurfaceGpu::skirtVertexOffset,
         [](const SurfaceGpu& g) {
             return g.skirtVertexCount;
         }},
        {&m_pools.skirtIndices, &SurfaceGpu::skirtIndexOffset,
         [](const SurfaceGpu& g) {
             return std::int64_t(g.skirtIndexCount);
         }},
    };
    bool moved = false;
    for (const Owned& o : owned) {
        if (!GpuPool::shouldCompact(o.pool->residentBytes() / o.pool->elementBytes(),
                                    o.pool->usedElements()))
            continue;
        std::vector<GpuPool::Range> ranges;
        for (auto& [id, e] : m_entries)
            if (SurfaceGpu* g = e.record.exact.get(); g && g->*o.offset >= 0 && o.count(*g) > 0)
                ranges.push_back({&(g->*o.offset), o.count(*g)});
        moved = o.pool->compact(std::move(ranges)) || moved;
    }
    // The same contents at new places: the draw commands (which hold the offsets) are made
    // again. Nothing else keeps them: the polygons, splits, fins and footprints keyed by
    // SurfaceGpu::polygonSerial hold no place in a pool, and a pick from the last frame reads
    // its (u, v) and surface, not the cell's vertex.
    if (moved)
        ++m_layoutStamp;
}

void GpuScene::syncMesh(SurfaceRecord& r, const Revisions& rev, int nu, int nv, UploadStats& up) {
    MeshGpu& m = r.mesh;
    if (m.vao && m.revisions.points == rev.points && m.revisions.knots == rev.knots && m.nu == nu &&
        m.nv == nv)
        return;
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    const TessellatedMesh t = tessellate(r.surface->geometry, nu, nv);
    if (!m.vao) {
        gl->glCreateVertexArrays(1, &m.vao);
        GLuint* bufs[] = {&m.positions, &m.normals, &m.uvs, &m.indices};
        for (GLuint* b : bufs)
            gl->glCreateBuffers(1, b);
        setMeshAttributes(gl, m.vao, {m.positions, m.normals, m.uvs});
        gl->glVertexArrayElementBuffer(m.vao, m.indices);
    }
    gl->glNamedBufferData(m.positions, GLsizeiptr(t.positions.size() * sizeof(glm::vec3)),
                          t.positions.data(), GL_DYNAMIC_DRAW);
    gl->glNamedBufferData(m.normals, GLsizeiptr(t.normals.size() * sizeof(glm::vec3)),
                          t.normals.data(), GL_DYNAMIC_DRAW);
    gl->glNamedBufferData(m.uvs, GLsizeiptr(t.uvs.size() * sizeof(glm::vec2)), t.uvs.data(),
                          GL_DYNAMIC_DRAW);
    gl->glNamedBufferData(m.indices, GLsizeiptr(t.indices.size() * sizeof(unsigned)),
                          t.indices.data(), GL_DYNAMIC_DRAW);
    m.indexCount = int(t.indices.size());
    m_meshBytes -= m.bytes;
    m.bytes =
        std::int64_t(t.positions.size() * sizeof(glm::vec3) + t.normals.size() * sizeof(glm::vec3) +
                     t.uvs.size() * sizeof(glm::vec2) + t.indices.size() * sizeof(unsigned));
    m_meshBytes += m.bytes;
    m.revisions = rev;
    m.nu = nu;
    m.nv = nv;
    up.meshBuilds += 1;
    up.bytes += m.bytes;
}

void GpuScene::syncNet(SurfaceRecord& r, const Revisions& rev, UploadStats& up) {
    NetGpu& n = r.net;
    if (n.vao && n.revisions.points == rev.points && n.revisions.knots == rev.knots)
        return;
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    const NurbsSurface& s = r.surface->geometry;
    if (!n.vao) {
        gl->glCreateVertexArrays(1, &n.vao);
        gl->glCreateBuffers(1, &n.points);
        gl->glCreateBuffers(1, &n.lines);
        gl->glVertexArrayVertexBuffer(n.vao, 0, n.points, 0, sizeof(glm::vec3));
        gl->glEnableVertexArrayAttrib(n.vao, kAttrPosition);
        gl->glVertexArrayAttribFormat(n.vao, kAttrPosition, 3, GL_FLOAT, GL_FALSE, 0);
        gl->glVertexArrayAttribBinding(n.vao, kAttrPosition, 0);
        gl->glVertexArrayElementBuffer(n.vao, n.lines);
    }
    std::vector<glm::vec3> pts(s.points.begin(), s.points.end());
    std::vector<unsigned> idx;
    for (int j = 0; j < s.countV; ++j)
        for (int i = 0; i < s.countU; ++i) {
            if (i + 1 < s.countU)
                idx.insert(idx.end(), {unsigned(s.index(i, j)), unsigned(s.index(i + 1, j))});
            if (j + 1 < s.countV)
                idx.insert(idx.end(), {unsigned(s.index(i, j)), unsigned(s.index(i, j + 1))});
        }
    gl->glNamedBufferData(n.points, GLsizeiptr(pts.size() * sizeof(glm::vec3)), pts.data(),
                          GL_DYNAMIC_DRAW);
    gl->glNamedBufferData(n.lines, GLsizeiptr(idx.size() * sizeof(unsigned)), idx.data(),
                          GL_DYNAMIC_DRAW);
    n.pointCount = int(pts.size());
    n.lineIndexCount = int(idx.size());
    m_netBytes -= n.bytes;
    n.bytes = std::int64_t(pts.size() * sizeof(glm::vec3) + idx.size() * sizeof(unsigned));
    m_netBytes += n.bytes;
    n.revisions = rev;
    up.netBuilds += 1;
    up.bytes += n.bytes;
}

} // namespace kw
