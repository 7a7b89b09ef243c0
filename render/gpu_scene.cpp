// GpuScene: the one sync per frame (drop removed surfaces, compare revisions once, rebuild the
// stale parts the frame needs) and the per-record bookkeeping.
#include "render/gpu_scene.h"

#include "model/visible_bounds.h"
#include "render/gpu_layout.h"

#include <QElapsedTimer>
#include <algorithm>

namespace kw {

void GpuScene::initialize(QOpenGLFunctions_4_5_Core* gl, ShaderLibrary* shaders) {
    m_gl = gl;
    m_masks.initialize(gl, shaders);
    GLint64 texels = 0;
    gl->glGetInteger64v(GL_MAX_TEXTURE_BUFFER_SIZE, &texels);
    m_glBufferLimit = std::int64_t(texels) * std::int64_t(sizeof(glm::vec4));
    const std::int64_t max = bufferLimit();
    m_pools.control.initialize(gl, sizeof(glm::vec4), max);
    m_pools.spans.initialize(gl, sizeof(glm::vec4), max);
    m_pools.vertices.initialize(gl, sizeof(BaseVertex), max);
    m_pools.triangles.initialize(gl, sizeof(unsigned), max);
    m_pools.outlines.initialize(gl, sizeof(unsigned), max);
}

std::int64_t GpuScene::bufferLimit() const {
    bool ok = false;
    const qint64 env = qEnvironmentVariable("KW_GPU_BUFFER_LIMIT").toLongLong(&ok);
    return ok && env > 0 ? std::min<std::int64_t>(env, m_glBufferLimit) : m_glBufferLimit;
}

void GpuScene::dropExact(SurfaceRecord& r) {
    if (r.exact)
        destroySurfaceGpu(m_pools, *r.exact);
    r.exact.reset();
    if (r.slot >= 0) {
        m_table.rows[size_t(r.slot)] = SurfaceTableEntry{};
        m_table.freeSlots.push_back(r.slot);
        --m_table.used;
        r.slot = -1;
    }
}

bool GpuScene::sync(const Document& doc, const FrameCamera& camera, const RenderOptions& options,
                    FrameReport& report, QString* error) {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    QElapsedTimer timer;
    timer.start();
    // Ids and revisions are per document: another document's data is never reused.
    if (m_document != &doc) {
        release();
        m_document = &doc;
    }
    const Scene& scene = doc.scene();
    const std::int64_t limit = bufferLimit();
    for (GpuPool* p : {&m_pools.control, &m_pools.spans, &m_pools.vertices, &m_pools.triangles,
                       &m_pools.outlines})
        p->initialize(gl,
                      p == &m_pools.control || p == &m_pools.spans ? sizeof(glm::vec4)
                      : p == &m_pools.vertices                     ? sizeof(BaseVertex)
                                                                   : sizeof(unsigned),
                      limit);
    QStringList tooLarge;
    const bool adaptive = options.partitioning == RenderOptions::Partitioning::Adaptive &&
                          options.mode == RenderMode::Exact;
    ScreenScale scale;
    if (adaptive) {
        const ViewKey key{camera.viewProjection, camera.viewport, options.pixelTolerance};
        if (!(key == m_viewKey)) {
            m_viewKey = key;
            ++m_viewStamp;
        }
        scale = frameScreenScale(camera);
    }
    FrameReport::Partitions& parts = report.partitions;
    QStringList unmet;
    m_order.clear();
    m_order.reserve(scene.surfaces.size());
    UploadStats frame;
    ++m_syncs;
    for (int index = 0; index < int(scene.surfaces.size()); ++index) {
        const Surface& s = scene.surfaces[size_t(index)];
        // The draw list: a hidden surface is left out of the frame (every pass and the pick
        // query draw records() only) but keeps its record, so showing it again uploads only
        // what changed meanwhile. Its trim mask layer is given back: the mask pass reassigns
        // layers among the records it sees, so a kept layer could go to another surface.
        if (s.hidden) {
            if (const auto it = m_entries.find(s.id); it != m_entries.end()) {
                it->second.seen = m_syncs; // kept, not dropped
                m_masks.freeLayer(it->second.record.mask);
            }
            continue;
        }
        Entry& e = m_entries[s.id];
        e.seen = m_syncs;
        SurfaceRecord& r = e.record;
        r.id = s.id;
        r.surface = &s;
        // The sliders' partitions (or the override): the paper's uniform grid, the minimum in
        // adaptive mode, and always the tessellated baseline's.
        const int sliderU = options.partitionsU > 0 ? options.partitionsU : s.partitionsU;
        const int sliderV = options.partitionsV > 0 ? options.partitionsV : s.partitionsV;
        // By index: a search by id per surface made each frame quadratic in the surfaces.
        const Revisions rev = doc.revisionsAt(index);
        r.revisions = rev;
        const NurbsSurface& geo = s.geometry;
        UploadStats up;
        std::unique_ptr<SurfaceGpu>& g = r.exact;
        bool fits = true;
        // The polygon spans the trims' (u, v) box (a small face on a large domain gets its
        // partitions) or, with polygonOverTrims off, the domain. The box is recomputed only
        // when the trims or that option changed.
        const auto boxFor = [&] {
            return options.polygonOverTrims
                       ? trimParameterBox(s)
                       : ParameterBox{surfaceDomainU(geo), surfaceDomainV(geo)};
        };
        const bool fresh = !g || g->revisions.knots != rev.knots || g->degreeU != geo.degreeU ||
                           g->degreeV != geo.degreeV || g->countU != geo.countU ||
                           g->countV != geo.countV;
        const bool boxStale = fresh || g->polygonTrimmed != options.polygonOverTrims ||
                              (options.polygonOverTrims && g->revisions.trims != rev.trims);
        const ParameterBox box = boxStale ? boxFor() : g->polygonBox;
        int nu = sliderU, nv = sliderV;
        if (adaptive) {
            bool evaluated = false;
            const PartitionChoice c =
                e.adaptive.choose(s, rev, box, scale, m_viewStamp, options.pixelTolerance, sliderU,
                                  sliderV, &evaluated);
            nu = c.nu;
            nv = c.nv;
            parts.choicesEvaluated += evaluated;
            parts.worstBoundPixels = std::max(parts.worstBoundPixels, c.boundPixels);
            if (!c.met)
                unmet << QString::number(s.id.value);
        }
        if (fresh) {
            if (!g) {
                g = std::make_unique<SurfaceGpu>();
                g->id = s.id;
            }
            fits = uploadSurface(m_pools, *g, s, nu, nv, box, up);
        } else {
            if (g->partitionsU != nu || g->partitionsV != nv || box != g->polygonBox) {
                // The polygon is rebuilt from the current points; pick up a point change.
                if (g->revisions.points != rev.points)
                    uploadChangedPoints(m_pools, *g, s, up);
                fits = rebuildPolygon(m_pools, *g, s, nu, nv, box, up);
            } else if (g->revisions.points != rev.points) {
                uploadChangedPoints(m_pools, *g, s, up);
            }
        }
        g->polygonTrimmed = options.polygonOverTrims;
        if (fits) {
            g->revisions = rev;
            if (r.slot < 0) {
                if (!m_table.freeSlots.empty()) {
                    r.slot = m_table.freeSlots.back();
                    m_table.freeSlots.pop_back();
                } else {
                    r.slot = int(m_table.rows.size());
                    m_table.rows.emplace_back();
                }
                ++m_table.used;
            }
        } else {
            // Not drawn: its data does not fit the shared buffers. Retried (as a full upload)
            // on the next frame, since other surfaces may have been removed meanwhile.
            dropExact(r);
            tooLarge << QStringLiteral("surface %1 (\"%2\") with %3 x %4 control points does not "
                                       "fit the GPU's buffer limit of %5 bytes")
                            .arg(s.id.value)
                            .arg(s.name)
                            .arg(geo.countU)
                            .arg(geo.countV)
                            .arg(limit);
        }
        if (g)
            parts.cells += std::int64_t(g->triangleIndexCount / 6);
        if (options.mode == RenderMode::Tessellated)
            syncMesh(r, rev, sliderU, sliderV, up);
        if (options.controlNet)
            syncNet(r, rev, up);
        e.stats += up;
        frame += up;
        m_order.push_back(&r);
    }
    // The one place removed surfaces are dropped, with every part they hold: those the loop
    // above did not see.
    for (auto it = m_entries.begin(); it != m_entries.end();) {
        if (it->second.seen != m_syncs) {
            drop(it->second);
            it = m_entries.erase(it);
        } else {
            ++it;
        }
    }
    report.uploads += frame;
    report.cpuMs.sync += double(timer.nsecsElapsed()) * 1e-6;
    parts.unmet += int(unmet.size());
    if (unmet.size() > 8) {
        const qsizetype all = unmet.size();
        unmet.resize(8);
        unmet << QStringLiteral("... (%1 in all)").arg(all);
    }
    if (!unmet.isEmpty())
        report.warnings << QStringLiteral("surfaces %1: the base polygon could not be brought "
                                          "within %2 px of the surface at %3 x %3 partitions "
                                          "(too close to the eye); drawn at %3 x %3")
                               .arg(unmet.join(QStringLiteral(", ")))
                               .arg(options.pixelTolerance)
                               .arg(kMaxPartitions);

    bool ok = tooLarge.isEmpty();
    if (!ok) {
        *error = tooLarge.join(QStringLiteral("; "));
        report.warnings << tooLarge;
    }
    if (options.trims) {
        timer.restart();
        QString maskError;
        if (!m_masks.sync(doc, m_order, camera, options, &maskError)) {
            if (ok)
                *error = maskError;
            ok = false;
        }
        report.masks += m_masks.frameStats();
        report.drawCalls += m_masks.drawCalls;
        report.warnings << maskWarnings();
        report.cpuMs.masks += double(timer.nsecsElapsed()) * 1e-6;
    }
    timer.restart();
    syncTable();
    report.cpuMs.sync += double(timer.nsecsElapsed()) * 1e-6;
    return ok;
}

void GpuScene::bindSurfaceData() const {
    for (int k = 0; k < 4; ++k)
        m_gl->glBindTextureUnit(GLuint(5 + k), m_views[k]);
    m_gl->glBindVertexArray(m_triangleVao);
}

void GpuScene::syncTable() {
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
    } else {
        int lo = int(t.rows.size()), hi = -1;
        for (const SurfaceRecord* r : m_order) {
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
            e.ids = glm::ivec4(int(r->id.value), trimBlock, 0, 0);
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
    }
    if (!m_triangleVao) {
        gl->glCreateVertexArrays(1, &m_triangleVao);
        gl->glCreateVertexArrays(1, &m_outlineVao);
        for (GLuint vao : {m_triangleVao, m_outlineVao}) {
            for (GLuint a = 0; a < 4; ++a) {
                gl->glEnableVertexArrayAttrib(vao, a);
                gl->glVertexArrayAttribBinding(vao, a, 0);
            }
            gl->glVertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE,
                                          offsetof(BaseVertex, position));
            gl->glVertexArrayAttribFormat(vao, 1, 2, GL_FLOAT, GL_FALSE, offsetof(BaseVertex, uv));
            gl->glVertexArrayAttribIFormat(vao, 2, 2, GL_INT, offsetof(BaseVertex, span));
            gl->glVertexArrayAttribFormat(vao, 3, 1, GL_FLOAT, GL_FALSE,
                                          offsetof(BaseVertex, spanScale));
        }
        // The surface index: one int per instance; a draw's base instance picks its row.
        gl->glEnableVertexArrayAttrib(m_triangleVao, 4);
        gl->glVertexArrayAttribIFormat(m_triangleVao, 4, 1, GL_INT, 0);
        gl->glVertexArrayAttribBinding(m_triangleVao, 4, 1);
        gl->glVertexArrayBindingDivisor(m_triangleVao, 1, 1);
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
    gl->glVertexArrayElementBuffer(m_triangleVao, m_pools.triangles.buffer());
    gl->glVertexArrayElementBuffer(m_outlineVao, m_pools.outlines.buffer());
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
        const GLuint attrBuf[] = {m.positions, m.normals, m.uvs};
        const int sizes[] = {3, 3, 2};
        for (GLuint a = 0; a < 3; ++a) {
            gl->glVertexArrayVertexBuffer(m.vao, a, attrBuf[a], 0,
                                          GLsizei(sizes[a] * sizeof(float)));
            gl->glEnableVertexArrayAttrib(m.vao, a);
            gl->glVertexArrayAttribFormat(m.vao, a, sizes[a], GL_FLOAT, GL_FALSE, 0);
            gl->glVertexArrayAttribBinding(m.vao, a, a);
        }
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
    m.bytes =
        std::int64_t(t.positions.size() * sizeof(glm::vec3) + t.normals.size() * sizeof(glm::vec3) +
                     t.uvs.size() * sizeof(glm::vec2) + t.indices.size() * sizeof(unsigned));
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
        gl->glEnableVertexArrayAttrib(n.vao, 0);
        gl->glVertexArrayAttribFormat(n.vao, 0, 3, GL_FLOAT, GL_FALSE, 0);
        gl->glVertexArrayAttribBinding(n.vao, 0, 0);
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
    n.bytes = std::int64_t(pts.size() * sizeof(glm::vec3) + idx.size() * sizeof(unsigned));
    n.revisions = rev;
    up.netBuilds += 1;
    up.bytes += n.bytes;
}

void GpuScene::drop(Entry& e) {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    SurfaceRecord& r = e.record;
    dropExact(r);
    MeshGpu& m = r.mesh;
    for (GLuint* b : {&m.positions, &m.normals, &m.uvs, &m.indices})
        if (*b)
            gl->glDeleteBuffers(1, b), *b = 0;
    if (m.vao)
        gl->glDeleteVertexArrays(1, &m.vao), m.vao = 0;
    NetGpu& n = r.net;
    for (GLuint* b : {&n.points, &n.lines})
        if (*b)
            gl->glDeleteBuffers(1, b), *b = 0;
    if (n.vao)
        gl->glDeleteVertexArrays(1, &n.vao), n.vao = 0;
    m_masks.freeLayer(r.mask);
    m_removedStats += e.stats;
    m_removedMaskStats += r.mask.stats;
}

const SurfaceRecord* GpuScene::find(SurfaceId id) const {
    const auto it = m_entries.find(id);
    return it == m_entries.end() ? nullptr : &it->second.record;
}

const SurfaceGpu* GpuScene::surfaceGpu(SurfaceId id) const {
    const SurfaceRecord* r = find(id);
    return r ? r->exact.get() : nullptr;
}

const TrimMask* GpuScene::mask(SurfaceId id) const {
    const SurfaceRecord* r = find(id);
    return r && r->mask.usable() ? &r->mask : nullptr;
}

UploadStats GpuScene::stats(SurfaceId id) const {
    const auto it = m_entries.find(id);
    return it == m_entries.end() ? UploadStats{} : it->second.stats;
}

UploadStats GpuScene::totalStats() const {
    UploadStats total = m_removedStats;
    for (const auto& [id, e] : m_entries)
        total += e.stats;
    return total;
}

TrimMaskStats GpuScene::maskStats(SurfaceId id) const {
    const SurfaceRecord* r = find(id);
    return r ? r->mask.stats : TrimMaskStats{};
}

TrimMaskStats GpuScene::totalMaskStats() const {
    TrimMaskStats total = m_removedMaskStats;
    for (const auto& [id, e] : m_entries)
        total += e.record.mask.stats;
    total.arrayAllocations = m_masks.arrayAllocations();
    return total;
}

void GpuScene::resetStats() {
    m_removedStats = {};
    m_removedMaskStats = {};
    m_masks.resetArrayAllocations();
    for (auto& [id, e] : m_entries) {
        e.stats = {};
        e.record.mask.stats = {};
    }
}

QStringList GpuScene::maskWarnings() const {
    QStringList out;
    if (!m_masks.budgetWarning().isEmpty())
        out << m_masks.budgetWarning();
    for (const SurfaceRecord* r : m_order)
        for (const QString& w : r->mask.warnings)
            out << QStringLiteral("surface %1: %2").arg(r->id.value).arg(w);
    return out;
}

std::vector<unsigned char> GpuScene::readMask(SurfaceId id) const {
    const TrimMask* m = mask(id);
    return m ? m_masks.readMask(*m) : std::vector<unsigned char>{};
}

void GpuScene::residentBytes(GpuBytes& out) const {
    // The pools' whole buffers (what the GPU holds), not only the live ranges.
    out.controlPoints += m_pools.control.residentBytes();
    out.spanTables += m_pools.spans.residentBytes();
    out.basePolygons += m_pools.vertices.residentBytes() + m_pools.triangles.residentBytes() +
                        m_pools.outlines.residentBytes();
    out.perSurface +=
        std::int64_t(m_table.capacity) * std::int64_t(sizeof(SurfaceTableEntry) + sizeof(int));
    for (const auto& [id, e] : m_entries) {
        out.tessellatedMeshes += e.record.mesh.bytes;
        out.controlNets += e.record.net.bytes;
    }
    out.trimMasks += m_masks.residentBytes();
}

void GpuScene::release() {
    if (m_gl)
        for (auto& [id, e] : m_entries)
            drop(e);
    m_entries.clear();
    m_order.clear();
    if (m_gl) {
        m_masks.release();
        for (GLuint* b : {&m_table.buffer, &m_table.instances})
            if (*b)
                m_gl->glDeleteBuffers(1, b), *b = 0;
        m_table = Table{};
        for (GpuPool* p : {&m_pools.control, &m_pools.spans, &m_pools.vertices, &m_pools.triangles,
                           &m_pools.outlines})
            p->release();
        for (GLuint* a : {&m_triangleVao, &m_outlineVao})
            if (*a)
                m_gl->glDeleteVertexArrays(1, a), *a = 0;
        for (int k = 0; k < 4; ++k)
            if (m_views[k])
                m_gl->glDeleteTextures(1, &m_views[k]), m_views[k] = 0;
    }
    m_document = nullptr;
}

} // namespace kw
